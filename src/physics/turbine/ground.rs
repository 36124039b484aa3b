//! The rotor in the ground frame (docs/model.md §13.4–§13.5): its coordinates after the
//! multi-blade transform, and what names a root there. Coordinate `b·K + j` is blade mode j's
//! collective (b = 0), cosine (1) and sine (2) amplitude; the drivetrain's angles follow.
//!
//! A root's slots: per blade mode, `collective`, `BW` (backward whirl) and `FW` (forward whirl);
//! `drivetrain 1` (the shaft twisting) and `rotor rotation` (the drivetrain turning as a whole)
//! with the generator free. Its content in each is its share of the rotor's kinetic energy
//! there: with `F = a_c + i a_s`, `B = a_c − i a_s` (for a root of positive frequency), the three
//! blades hold `Σ_k |q_k|² = 3|a_0|² + ¾|F|² + ¾|B|²` at every azimuth, and the drivetrain its
//! free-free modes' energies. Each slot's frequency in vacuo is the ground-frame root of the
//! undamped rotor (gyroscopic terms kept) that holds most of it.

use super::drivetrain::Generator;
use super::rotor::Rotor;
use super::tower::{strip_rows, Plane, Tower, TowerMode};
use crate::error::{Error, Result};
use crate::numeric::mbc::{t1, MultiBlade, Rotating};
use crate::numeric::{decompose, hungarian};
use crate::physics::section::SectionProps;
use crate::physics::structure::{
    kinetic_energy, Components, Family, MotionRows, NaturalMode, PartKind, ShapePart, Shares,
    Structure,
};
use crate::physics::system::{Azimuthal, TurningBlade};
use nalgebra::{Complex, DMatrix, DVector};
use std::f64::consts::TAU;
use std::sync::Arc;

/// How a blade mode's three coordinates move together in a root.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Whirl {
    Collective,
    Backward,
    Forward,
}

impl Whirl {
    pub const ALL: [Whirl; 3] = [Whirl::Collective, Whirl::Backward, Whirl::Forward];

    /// The first word of a name: `collective`, `BW`, `FW`.
    pub fn prefix(self) -> &'static str {
        match self {
            Whirl::Collective => "collective",
            Whirl::Backward => "BW",
            Whirl::Forward => "FW",
        }
    }

    /// The whirl a root's name begins with ([`Whirl::prefix`]), none for a name that is not a
    /// blade mode's in the ground frame (the tower's, the drivetrain's, one blade's).
    pub fn of_name(label: &str) -> Option<Whirl> {
        let first = label.split_whitespace().next()?;
        Whirl::ALL.into_iter().find(|w| w.prefix() == first)
    }
}

/// The blades of a rotor the ground-frame names are made for.
const BLADES: usize = 3;

/// How close to 1P, against its decay rate, a root is taken for a non-oscillating blade
/// root's image (its damping ratio in the blades' frame above 0.995).
const UNDECIDED_WHIRL: f64 = 0.1;

/// One slot a root can be named after.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slot {
    Blade {
        mode: usize,
        whirl: Whirl,
    },
    Drivetrain,
    Rotation,
    /// The tower's mode on the ground-frame rotor's rigid masses, by [`GroundRotor`]'s
    /// `tower_modes` index.
    Tower(usize),
}

/// The rotor's coordinates in the ground frame, as the analyses read them.
pub struct GroundRotor {
    blade: Arc<dyn Structure>,
    per_blade: usize,
    generator: Option<Generator>,
    /// `T1(0)ᵀ (·) T1(0)` of the rotor's matrices: what the ground coordinates carry at zero
    /// azimuth, the transform's rate terms aside.
    mass: DMatrix<f64>,
    stiffness: DMatrix<f64>,
    damping: DMatrix<f64>,
    family_energy: [DMatrix<f64>; 3],
    /// The rotor's angular momentum about the shaft per unit of each coordinate, with the
    /// generator free ([`rotation_weights`]).
    rotation: Option<DVector<f64>>,
    /// `φᵀ M` of the collective modes of the rotor on a rigid support, mass-normalised, over
    /// all coordinates: blade mode j's collective slot's (`j`), then the drivetrain's
    /// ([`collective_modes`]).
    collective: Vec<DVector<f64>>,
    /// The tower's modes with the rotor as rigid masses on its top, mass-normalised: `φᵀ M`
    /// over all coordinates, and each one's name (fore–aft or side–side, counted up in
    /// frequency).
    tower_modes: Vec<(DVector<f64>, TowerMode)>,
    /// The first tower coordinate and the tower, on one.
    tower: Option<(usize, Tower)>,
    slots: Vec<Slot>,
    natural: Vec<NaturalMode>,
    /// Ω (rad/s).
    omega: f64,
}

impl GroundRotor {
    /// The ground-frame view of `rotor` at rotor speed `omega` (rad/s), its slots' frequencies
    /// in vacuo from the transformed undamped rotor.
    pub fn new(rotor: &Rotor, omega: f64) -> Result<GroundRotor> {
        if rotor.blades() != BLADES {
            return Err(Error::numerical(format!(
                "a rotor of {} blades: the ground-frame names are those of a three-bladed rotor",
                rotor.blades()
            )));
        }
        let k = rotor.per_blade();
        let n = rotor.coordinates();
        let t = transform_matrix(rotor);
        let congruent = |a: &DMatrix<f64>| t.transpose() * a * &t;
        let at = rotor.drivetrain_at();
        let generator = rotor.drivetrain().map(|d| d.generator);
        let mass = congruent(rotor.mass());
        let stiffness = congruent(&rotor.stiffness());
        let rotation = rotation_weights(&mass, at, generator);
        let collective =
            collective_modes(&mass, &stiffness, k, at, rotor.drivetrain_coordinates())?;
        let tower = rotor.tower().map(|(at, apex)| (at, apex.clone()));
        let tower_modes = match &tower {
            Some((at, tower)) => tower_modes(&mass, &stiffness, *at, tower)?,
            None => Vec::new(),
        };
        let blade_natural = rotor.blade().natural_modes()?;
        let mut slots: Vec<Slot> = (0..k)
            .flat_map(|mode| Whirl::ALL.map(|whirl| Slot::Blade { mode, whirl }))
            .collect();
        match generator {
            None => {}
            Some(Generator::Locked) => slots.push(Slot::Drivetrain),
            Some(Generator::Free) => slots.extend([Slot::Drivetrain, Slot::Rotation]),
        }
        slots.extend((0..tower_modes.len()).map(Slot::Tower));
        let mut ground = GroundRotor {
            blade: Arc::clone(rotor.blade()),
            per_blade: k,
            generator,
            mass,
            stiffness,
            damping: congruent(&(rotor.damping() - rotor.gyroscopic())),
            family_energy: rotor.family_energy().clone(),
            rotation,
            collective,
            tower_modes,
            tower,
            slots,
            natural: Vec::new(),
            omega,
        };
        let mut frequencies = ground.in_vacuo_frequencies(rotor, omega)?;
        // Ascending in frequency, as a blade's natural modes are.
        let mut order: Vec<usize> = (0..ground.slots.len()).collect();
        order.sort_by(|&a, &b| frequencies[a].0.total_cmp(&frequencies[b].0));
        ground.slots = order.iter().map(|&i| ground.slots[i]).collect();
        frequencies = order.iter().map(|&i| frequencies[i].clone()).collect();
        ground.natural = ground
            .slots
            .iter()
            .zip(frequencies)
            .map(|(slot, (frequency_hz, shape))| {
                let complex: Vec<Complex<f64>> =
                    shape.iter().map(|&v| Complex::new(v, 0.0)).collect();
                let (label, family, number, shares) = match *slot {
                    Slot::Blade { mode, whirl } => {
                        let m = &blade_natural[mode];
                        (
                            format!("{} {}", whirl.prefix(), m.label),
                            m.family,
                            m.number,
                            ground.shares(&complex),
                        )
                    }
                    Slot::Drivetrain => (
                        "drivetrain 1".to_string(),
                        Family::Edge,
                        1,
                        Shares::from_energies(0.0, 1.0, 0.0),
                    ),
                    Slot::Rotation => (
                        "rotor rotation".to_string(),
                        Family::Edge,
                        1,
                        Shares::from_energies(0.0, 1.0, 0.0),
                    ),
                    Slot::Tower(i) => {
                        let mode = ground.tower_modes[i].1;
                        let (family, number) = mode.family_and_number();
                        (
                            mode.label().to_string(),
                            family,
                            number,
                            ground.shares(&complex),
                        )
                    }
                };
                NaturalMode {
                    label,
                    family,
                    number,
                    frequency_hz,
                    shares,
                    torsion_share: shares.twist,
                    shape,
                }
            })
            .collect();
        debug_assert_eq!(ground.mass.nrows(), n);
        Ok(ground)
    }

    /// Each slot's frequency (Hz) and shape in vacuo: the ground-frame roots of the rotor with
    /// its structural damping left out, each oscillating root given one-to-one to the slot it
    /// holds most of; a slot no oscillating root takes (the rotor's rotation) is at zero.
    fn in_vacuo_frequencies(&self, rotor: &Rotor, omega: f64) -> Result<Vec<(f64, DVector<f64>)>> {
        let n = rotor.coordinates();
        let gyroscopic = rotor.gyroscopic();
        let mass_inv = rotor
            .mass()
            .clone()
            .lu()
            .try_inverse()
            .ok_or_else(|| Error::numerical("the rotor's mass matrix is singular"))?;
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        a.view_mut((0, n), (n, n)).fill_with_identity();
        a.view_mut((n, 0), (n, n))
            .copy_from(&(-&mass_inv * rotor.stiffness()));
        a.view_mut((n, n), (n, n))
            .copy_from(&(-&mass_inv * gyroscopic));
        let a = layout(rotor, 2 * n)?.transform(&a, 0.0, omega)?;
        let roots = decompose(&a, false)?;
        let oscillating: Vec<usize> = (0..roots.values.len())
            .filter(|&i| roots.values[i].im > 1e-9 * roots.values[i].norm().max(1.0))
            .collect();
        let content: Vec<Vec<f64>> = oscillating
            .iter()
            .map(|&i| {
                let q: Vec<Complex<f64>> =
                    roots.vectors.column(i).rows(0, n).iter().copied().collect();
                self.content(&q)
            })
            .collect();
        // The rotor's rotation is the zero roots, never an oscillating one.
        let turning: Vec<usize> = (0..self.slots.len())
            .filter(|&s| self.slots[s] != Slot::Rotation)
            .collect();
        let size = oscillating.len().max(turning.len());
        let cost: Vec<Vec<f64>> = (0..size)
            .map(|r| {
                (0..size)
                    .map(|c| match (content.get(r), turning.get(c)) {
                        (Some(content), Some(&s)) => -content[s],
                        _ => 0.0,
                    })
                    .collect()
            })
            .collect();
        let assigned = hungarian(&cost);
        let mut out = vec![(0.0, DVector::zeros(n)); self.slots.len()];
        for (r, &i) in oscillating.iter().enumerate() {
            if let Some(&s) = turning.get(assigned[r]) {
                let shape = roots.vectors.column(i).rows(0, n).map(|c| c.re);
                out[s] = (roots.values[i].im / TAU, shape);
            }
        }
        Ok(out)
    }

    /// The energies of coordinates `q` in each slot: a blade mode's backward and forward whirl
    /// its cyclic amplitudes' (`¾|B|²`, `¾|F|²`); the collective slots and the drivetrain
    /// the modal amplitudes of the rotor's collective modes on a rigid support (the blades'
    /// collective coordinates are mass-coupled with the drivetrain, and with the nacelle's
    /// roll, so a clamped blade's mode is not one of them); the tower's its modes'; the
    /// rotation the angular momentum about the shaft.
    fn slot_energies(&self, q: &[Complex<f64>]) -> Vec<f64> {
        let k = self.per_blade;
        let i = Complex::new(0.0, 1.0);
        let mut e: Vec<f64> = Vec::with_capacity(self.slots.len());
        for slot in &self.slots {
            e.push(match *slot {
                Slot::Blade { mode, whirl } => {
                    let (ac, as_) = (q[k + mode], q[2 * k + mode]);
                    match whirl {
                        Whirl::Collective => projected(&self.collective[mode], q),
                        Whirl::Forward => 0.75 * (ac + i * as_).norm_sqr(),
                        Whirl::Backward => 0.75 * (ac - i * as_).norm_sqr(),
                    }
                }
                Slot::Tower(t) => projected(&self.tower_modes[t].0, q),
                Slot::Drivetrain => projected(&self.collective[k], q),
                Slot::Rotation => self.rotation.as_ref().map_or(0.0, |w| projected(w, q)),
            });
        }
        e
    }

    /// Each slot's share of a motion ([`GroundRotor::slot_energies`]).
    fn content(&self, q: &[Complex<f64>]) -> Vec<f64> {
        crate::numeric::shares(self.slot_energies(q))
    }

    /// [`GroundRotor::content`] of a root with eigenvalue `lambda`. A root at 1P decaying far
    /// faster than it turns away from 1P is the image of a blade root that does not oscillate
    /// in its own frame (an overdamped mode's decay): its ground-frame motion is a forward
    /// whirl at `+1P` and, equally, a backward one at `−1P`, so each blade mode's whirl
    /// energy is split between its two whirl slots, the backward one a thousandth ahead so
    /// that of two such roots the one with the larger claim takes the backward name, every
    /// time.
    fn root_content(&self, q: &[Complex<f64>], lambda: Complex<f64>) -> Vec<f64> {
        let mut e = self.slot_energies(q);
        let away = lambda.im.abs() - self.omega;
        if away.abs() <= UNDECIDED_WHIRL * lambda.re.abs() {
            for mode in 0..self.per_blade {
                let at = |whirl| {
                    self.slots
                        .iter()
                        .position(|s| *s == Slot::Blade { mode, whirl })
                };
                if let (Some(b), Some(f)) = (at(Whirl::Backward), at(Whirl::Forward)) {
                    let half = 0.5 * (e[b] + e[f]);
                    e[b] = half * (1.0 + 1e-3);
                    e[f] = half * (1.0 - 1e-3);
                }
            }
        }
        crate::numeric::shares(e)
    }

    /// Blade 0 as the ground coordinates see it at `azimuth` (rad), turning with the rotor: its
    /// tip rows (twist, flap) and its kick shapes ([`Structure::kick_shapes`], blade 0 kicked
    /// alone), each affine in `cos ψ`, `sin ψ` (docs/model.md §13.8).
    pub fn blade_view(&self) -> TurningBlade {
        TurningBlade {
            rotor_speed: self.omega,
            tip: Azimuthal::sampled(|psi| self.tip_rows_at(psi)),
            kick: Azimuthal::sampled(|psi| self.kick_shapes_at(psi)),
        }
    }

    /// Blade 0's tip rows over the ground coordinates, the blade at `azimuth`
    /// ([`GroundRotor::motion_rows_at`]).
    fn tip_rows_at(&self, azimuth: f64) -> [DVector<f64>; 2] {
        let rows = self.motion_rows_at(self.length(), azimuth);
        [rows.twist, rows.flap]
    }

    /// Blade 0's rows at span `x` over the ground coordinates, the blade at `azimuth`: its own
    /// modes' `a_0 + a_c cos ψ + a_s sin ψ`, the rotor's rotation as edge motion, the tower's
    /// apex seen along its flap and edge axes there.
    fn motion_rows_at(&self, x: f64, azimuth: f64) -> MotionRows {
        let k = self.per_blade;
        let b = self.blade.motion_rows(x);
        let mut rows = MotionRows::zeros(self.coordinates());
        for (at, weight) in [(0, 1.0), (k, azimuth.cos()), (2 * k, azimuth.sin())] {
            rows.twist.rows_mut(at, k).copy_from(&(&b.twist * weight));
            rows.flap.rows_mut(at, k).copy_from(&(&b.flap * weight));
            rows.edge.rows_mut(at, k).copy_from(&(&b.edge * weight));
        }
        let radius = self.hub_radius() + x;
        if self.generator.is_some() {
            rows.edge[3 * k] = radius;
        }
        if let Some((at, tower)) = &self.tower {
            let [flap, edge] = strip_rows(&tower.apex, azimuth, radius);
            rows.flap.rows_mut(*at, flap.len()).copy_from(&flap);
            rows.edge.rows_mut(*at, edge.len()).copy_from(&edge);
        }
        rows
    }

    /// Blade 0 kicked alone at `azimuth`, its rates and the other blades left as they are:
    /// a third of the blade's shape `s` collective, two thirds along the cosine and sine of
    /// its azimuth, and the ground rates that cancel what turning those adds to the blades'
    /// own (`q̇_k` holds `Ω (a_s cos ψ_k − a_c sin ψ_k)`). Over `[q, q̇]`.
    fn kick_shapes_at(&self, azimuth: f64) -> [DVector<f64>; 2] {
        let (k, n) = (self.per_blade, self.coordinates());
        let (c, s) = (azimuth.cos(), azimuth.sin());
        let w = self.omega;
        self.blade.kick_shapes().map(|shape| {
            let mut v = DVector::zeros(2 * n);
            let cyclic = 2.0 / 3.0;
            for (at, weight) in [
                (0, 1.0 / 3.0),
                (k, cyclic * c),
                (2 * k, cyclic * s),
                (n + k, -w * cyclic * s),
                (n + 2 * k, w * cyclic * c),
            ] {
                v.rows_mut(at, k).copy_from(&(&shape * weight));
            }
            v
        })
    }
}

impl Structure for GroundRotor {
    fn coordinates(&self) -> usize {
        self.mass.nrows()
    }
    fn length(&self) -> f64 {
        self.blade.length()
    }
    fn hub_radius(&self) -> f64 {
        self.blade.hub_radius()
    }
    fn mass(&self) -> &DMatrix<f64> {
        &self.mass
    }
    fn stiffness(&self) -> DMatrix<f64> {
        self.stiffness.clone()
    }
    fn damping(&self) -> &DMatrix<f64> {
        &self.damping
    }
    /// Blade 0 at zero azimuth ([`GroundRotor::motion_rows_at`]).
    fn motion_rows(&self, x: f64) -> MotionRows {
        self.motion_rows_at(x, 0.0)
    }
    fn natural_modes(&self) -> Result<Vec<NaturalMode>> {
        Ok(self.natural.clone())
    }
    /// Averaged over the azimuth: `3 E(a_0) + 3/2 (E(a_c) + E(a_s))` per family, the rotor's
    /// rotation as edge motion.
    fn shares(&self, q: &[Complex<f64>]) -> Shares {
        let k = self.per_blade;
        let mut e = [0.0; 3];
        for (acc, m) in e.iter_mut().zip(&self.family_energy) {
            *acc = 3.0 * kinetic_energy(m, &q[..k])
                + 1.5 * (kinetic_energy(m, &q[k..2 * k]) + kinetic_energy(m, &q[2 * k..3 * k]));
        }
        if self.generator.is_some() {
            e[1] += self.mass[(3 * k, 3 * k)] * q[3 * k].norm_sqr();
        }
        if let Some((at, tower)) = &self.tower {
            let [fore_aft, side_side, torsion] = tower.plane_energies(&self.mass, *at, q);
            e[0] += fore_aft;
            e[1] += side_side;
            e[2] += torsion;
        }
        Shares::from_energies(e[0], e[1], e[2])
    }
    /// Blade 0 kicked alone at zero azimuth: a third collective, two thirds cosine (the
    /// coordinates; [`GroundRotor::blade_view`] has the rates that go with them).
    fn kick_shapes(&self) -> [DVector<f64>; 2] {
        let n = self.coordinates();
        self.kick_shapes_at(0.0).map(|v| v.rows(0, n).into_owned())
    }
    fn uniform_section(&self) -> Option<&SectionProps> {
        None
    }
    fn span_points(&self) -> Vec<f64> {
        self.blade.span_points()
    }
    /// Each blade at its azimuth (blade 1 at zero, the next a third of a turn ahead, as the
    /// multi-blade transform numbers them), then the tower along its height. A blade's own
    /// coordinates: its modes `a_0 + a_c cos ψ + a_s sin ψ`, the drivetrain's and the tower's
    /// as they are ([`GroundRotor::motion_rows_at`] with the cyclic weights taken out).
    fn shape_parts(&self) -> Vec<ShapePart> {
        let (k, n) = (self.per_blade, self.coordinates());
        // Everything but the cyclic coordinates: the collective stands for the blade's own.
        let own: Vec<usize> = (0..k).chain(3 * k..n).collect();
        let pick = |v: &DVector<f64>| DVector::from_fn(own.len(), |i, _| v[own[i]]);
        let span = self.span_points();
        let mut parts: Vec<ShapePart> = (0..BLADES)
            .map(|b| {
                let azimuth = TAU * b as f64 / BLADES as f64;
                let mut map = DMatrix::zeros(own.len(), n);
                for (i, &c) in own.iter().enumerate() {
                    map[(i, c)] = 1.0;
                }
                for j in 0..k {
                    map[(j, k + j)] = azimuth.cos();
                    map[(j, 2 * k + j)] = azimuth.sin();
                }
                // Its rows on the collective coordinates are its own modes' at any azimuth.
                let points = span
                    .iter()
                    .map(|&x| {
                        let rows = self.motion_rows_at(x, azimuth);
                        let own_rows = MotionRows {
                            twist: pick(&rows.twist),
                            flap: pick(&rows.flap),
                            edge: pick(&rows.edge),
                        };
                        (x, own_rows)
                    })
                    .collect();
                ShapePart {
                    map,
                    ..ShapePart::direct(&format!("blade {}", b + 1), PartKind::Blade, points)
                }
            })
            .collect();
        if let Some((at, tower)) = &self.tower {
            let t = tower.coordinates();
            let mut map = DMatrix::zeros(t, n);
            for i in 0..t {
                map[(i, at + i)] = 1.0;
            }
            parts.push(ShapePart {
                map,
                ..ShapePart::direct("tower", PartKind::Tower, tower.profile.clone())
            });
        }
        parts
    }
    fn slot_content(&self, q: &[Complex<f64>], lambda: Complex<f64>) -> Option<Vec<f64>> {
        Some(self.root_content(q, lambda))
    }
    /// `BW …` at `f + 1P`, `FW …` at `f − 1P`, `collective …` at `f` (a backward whirl of a
    /// blade mode above 1P; below it the ground-frame root would be `1P − f`).
    fn rotating_shift_hz(&self, label: &str) -> Option<f64> {
        let one_p = self.omega / TAU;
        Some(match Whirl::of_name(label)? {
            Whirl::Backward => one_p,
            Whirl::Forward => -one_p,
            Whirl::Collective => 0.0,
        })
    }
    /// The blades' own motion averaged over the azimuth as in [`GroundRotor::shares`], the
    /// drivetrain's and the tower's coordinates on their own mass.
    fn components(&self, q: &[Complex<f64>]) -> Option<Components> {
        let k = self.per_blade;
        let mut e = [0.0; 5];
        for (acc, m) in e.iter_mut().zip(&self.family_energy) {
            *acc = 3.0 * kinetic_energy(m, &q[..k])
                + 1.5 * (kinetic_energy(m, &q[k..2 * k]) + kinetic_energy(m, &q[2 * k..3 * k]));
        }
        let block = |at: usize, len: usize| {
            let m = self.mass.view((at, at), (len, len)).into_owned();
            kinetic_energy(&m, &q[at..at + len])
        };
        let tower_at = self.tower.as_ref().map_or(self.mass.nrows(), |(at, _)| *at);
        e[3] = block(3 * k, tower_at - 3 * k);
        if let Some((_, tower)) = &self.tower {
            e[4] = block(tower_at, tower.coordinates());
        }
        Some(Components::from_energies(e))
    }
    /// The azimuth of a drivetrain free to turn.
    fn rigid_body_roots(&self) -> usize {
        usize::from(self.generator == Some(Generator::Free))
    }
}

/// The multi-blade layout of a first-order rotor state `[q, q̇, z]` of `dim` states: each blade
/// mode's displacement and rate, each strip state (one blade's `(dim − 2n)/3` after the
/// coordinates, blade after blade).
pub fn layout(rotor: &Rotor, dim: usize) -> Result<MultiBlade> {
    let (n, k, blades) = (rotor.coordinates(), rotor.per_blade(), rotor.blades());
    let per_blade_aero = (dim - 2 * n) / blades;
    let mut groups: Vec<Rotating> = (0..k)
        .map(|j| Rotating {
            states: (0..blades).map(|b| b * k + j).collect(),
            rate_of: None,
        })
        .collect();
    groups.extend((0..k).map(|j| Rotating {
        states: (0..blades).map(|b| n + b * k + j).collect(),
        rate_of: Some(j),
    }));
    groups.extend((0..per_blade_aero).map(|i| {
        Rotating {
            states: (0..blades)
                .map(|b| 2 * n + b * per_blade_aero + i)
                .collect(),
            rate_of: None,
        }
    }));
    MultiBlade::new(dim, groups)
}

/// The rotor's angular momentum about the shaft per unit of `q`, mass-normalised, with the
/// generator free (`θ_r` at coordinate `at` of the ground mass `m`): the rigid rotation
/// `(1, 0)` on the whole mass (a collective edge mode whose hub swings against its blades holds
/// none of it). None with the generator locked or no drivetrain: nothing turns freely.
fn rotation_weights(
    m: &DMatrix<f64>,
    at: usize,
    generator: Option<Generator>,
) -> Option<DVector<f64>> {
    (generator == Some(Generator::Free)).then(|| m.column(at) / m[(at, at)].sqrt())
}

/// `φᵀ M` (mass-normalised, over all `m.nrows()` coordinates) of the collective modes of the
/// rotor on a rigid support: the undamped modes of the collective coordinates of its `k`
/// blade modes and the drivetrain's `fixed` coordinates (from `at`), all else held, ordered as
/// the slots they are named after: blade mode j's collective slot at `j`, the drivetrain's at
/// `k` (with a drivetrain). A mode goes to the slot whose coordinates hold most of its kinetic
/// energy (`3|a_0j|²` for blade mode j, the shaft's twist M-orthogonal to the rigid rotation
/// for the drivetrain), one-to-one; a free drivetrain's rigid rotation, at zero frequency, to
/// none.
fn collective_modes(
    m: &DMatrix<f64>,
    stiffness: &DMatrix<f64>,
    k: usize,
    at: usize,
    fixed: usize,
) -> Result<Vec<DVector<f64>>> {
    let n = m.nrows();
    let coords: Vec<usize> = (0..k).chain(at..at + fixed).collect();
    let nc = coords.len();
    let mc = m.select_rows(&coords).select_columns(&coords);
    let kc = stiffness.select_rows(&coords).select_columns(&coords);
    let (values, phi) = undamped_modes(&mc, &kc)?;
    // The shaft's twist in the drivetrain's own coordinates: `θ_r` locked; `(a, 1)` in
    // `θ_r, δ`, M-orthogonal to the rigid rotation `(1, 0)`, with the generator free.
    let own = mc.view((k, k), (fixed, fixed)).into_owned();
    let twist = match fixed {
        0 => None,
        1 => Some(DVector::from_element(1, 1.0)),
        _ => Some(DVector::from_vec(vec![-own[(0, 1)] / own[(0, 0)], 1.0])),
    }
    .map(|t| {
        let mt = &own * &t;
        mt / t.dot(&(&own * &t)).sqrt()
    });
    let slots = k + usize::from(fixed > 0);
    // A free drivetrain's rigid rotation is the lowest mode, at zero.
    let skip = usize::from(fixed == 2);
    let content: Vec<Vec<f64>> = (skip..nc)
        .map(|i| {
            let y = phi.column(i);
            let mut e: Vec<f64> = (0..k).map(|j| 3.0 * y[j] * y[j]).collect();
            if let Some(t) = &twist {
                e.push(t.dot(&y.rows(k, fixed)).powi(2));
            }
            crate::numeric::shares(e)
        })
        .collect();
    debug_assert!(values.len() == nc && content.len() == slots);
    let cost: Vec<Vec<f64>> = content
        .iter()
        .map(|c| c.iter().map(|v| -v).collect())
        .collect();
    let assigned = hungarian(&cost);
    let mut out = vec![DVector::zeros(n); slots];
    for (r, &slot) in assigned.iter().enumerate() {
        let mphi = &mc * phi.column(skip + r);
        let mut w = DVector::zeros(n);
        for (c, &i) in coords.iter().enumerate() {
            w[i] = mphi[c];
        }
        out[slot] = w;
    }
    Ok(out)
}

/// The undamped modes of mass `m` and stiffness `k` (symmetric parts), ascending: `ω²` and the
/// mass-normalised shapes as columns.
fn undamped_modes(m: &DMatrix<f64>, k: &DMatrix<f64>) -> Result<(DVector<f64>, DMatrix<f64>)> {
    let l_inv = m
        .clone()
        .cholesky()
        .ok_or_else(|| Error::numerical("a mass matrix is not positive definite"))?
        .l()
        .try_inverse()
        .ok_or_else(|| Error::numerical("a mass matrix is singular"))?;
    let a = &l_inv * k * l_inv.transpose();
    let eig = ((&a + a.transpose()) * 0.5).symmetric_eigen();
    let mut order: Vec<usize> = (0..a.nrows()).collect();
    order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
    let values = DVector::from_iterator(order.len(), order.iter().map(|&i| eig.eigenvalues[i]));
    let shapes = l_inv.transpose() * eig.eigenvectors.select_columns(&order);
    Ok((values, shapes))
}

/// `|wᵀ q|²`.
fn projected(w: &DVector<f64>, q: &[Complex<f64>]) -> f64 {
    w.iter()
        .zip(q)
        .map(|(w, q)| q * *w)
        .sum::<Complex<f64>>()
        .norm_sqr()
}

/// The tower's modes (coordinates from `at`) on the ground coordinates' mass `m` and
/// stiffness `k` with everything else held: `φᵀ M` over all coordinates, mass-normalised, and
/// each mode's name: the plane (fore–aft, side–side, torsion) whose coordinates hold most of its
/// kinetic energy, numbered in frequency within its plane.
fn tower_modes(
    m: &DMatrix<f64>,
    k: &DMatrix<f64>,
    at: usize,
    tower: &Tower,
) -> Result<Vec<(DVector<f64>, TowerMode)>> {
    let t = tower.coordinates();
    let mt = m.view((at, at), (t, t)).into_owned();
    let kt = k.view((at, at), (t, t)).into_owned();
    let (_, phi) = undamped_modes(&mt, &kt)?;
    let mut counts = [0usize; 3];
    let n = m.nrows();
    Ok((0..t)
        .map(|i| {
            let phi = phi.column(i);
            let mphi = &mt * phi;
            let mut energy = [0.0; 3];
            for (j, mode) in tower.modes.iter().enumerate() {
                energy[mode.plane() as usize] += phi[j] * mphi[j];
            }
            let plane = [Plane::ForeAft, Plane::SideSide, Plane::Torsion]
                .into_iter()
                .max_by(|a, b| energy[*a as usize].total_cmp(&energy[*b as usize]))
                .unwrap_or(Plane::ForeAft);
            counts[plane as usize] += 1;
            let mode = TowerMode::named(plane, counts[plane as usize]);
            let mut weights = DVector::zeros(n);
            weights.rows_mut(at, t).copy_from(&mphi);
            (weights, mode)
        })
        .collect())
}

/// `T1(0)` on the rotor's coordinates (blade blocks; identity on the drivetrain's).
fn transform_matrix(rotor: &Rotor) -> DMatrix<f64> {
    let (n, k, blades) = (rotor.coordinates(), rotor.per_blade(), rotor.blades());
    let t1 = t1(blades, 0.0);
    let mut t = DMatrix::identity(n, n);
    for j in 0..k {
        for b in 0..blades {
            for c in 0..blades {
                t[(b * k + j, c * k + j)] = t1[(b, c)];
            }
        }
    }
    t
}
