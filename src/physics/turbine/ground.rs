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
use crate::error::{Error, Result};
use crate::numeric::mbc::{t1, MultiBlade, Rotating};
use crate::numeric::{decompose, hungarian};
use crate::physics::section::SectionProps;
use crate::physics::structure::{
    kinetic_energy, Family, MotionRows, NaturalMode, Shares, Structure,
};
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
}

/// One slot a root can be named after.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slot {
    Blade { mode: usize, whirl: Whirl },
    Drivetrain,
    Rotation,
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
    /// `φᵀ M` of the drivetrain's modes, mass-normalised, over all coordinates: the rigid
    /// rotation and the twist with the generator free, the twist alone with it locked. A
    /// motion's modal amplitude in each is the product with its coordinates.
    drivetrain_modes: Vec<DVector<f64>>,
    slots: Vec<Slot>,
    natural: Vec<NaturalMode>,
}

impl GroundRotor {
    /// The ground-frame view of `rotor` at rotor speed `omega` (rad/s), its slots' frequencies
    /// in vacuo from the transformed undamped rotor.
    pub fn new(rotor: &Rotor, omega: f64) -> Result<GroundRotor> {
        if rotor.blades() != 3 {
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
        let drivetrain_modes = drivetrain_modes(&mass, at);
        let blade_natural = rotor.blade().natural_modes()?;
        let mut slots: Vec<Slot> = (0..k)
            .flat_map(|mode| Whirl::ALL.map(|whirl| Slot::Blade { mode, whirl }))
            .collect();
        match generator {
            None => {}
            Some(Generator::Locked) => slots.push(Slot::Drivetrain),
            Some(Generator::Free) => slots.extend([Slot::Drivetrain, Slot::Rotation]),
        }
        let mut ground = GroundRotor {
            blade: Arc::clone(rotor.blade()),
            per_blade: k,
            generator,
            mass,
            stiffness: congruent(&rotor.stiffness()),
            damping: congruent(rotor.damping()),
            family_energy: rotor.family_energy().clone(),
            drivetrain_modes,
            slots,
            natural: Vec::new(),
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
        let c = rotor.damping();
        let gyroscopic = (c - c.transpose()) * 0.5;
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

    /// The energies of coordinates `q` in each slot.
    fn slot_energies(&self, q: &[Complex<f64>]) -> Vec<f64> {
        let k = self.per_blade;
        let i = Complex::new(0.0, 1.0);
        let mut e: Vec<f64> = Vec::with_capacity(self.slots.len());
        for slot in &self.slots {
            e.push(match *slot {
                Slot::Blade { mode, whirl } => {
                    let (a0, ac, as_) = (q[mode], q[k + mode], q[2 * k + mode]);
                    match whirl {
                        Whirl::Collective => 3.0 * a0.norm_sqr(),
                        Whirl::Forward => 0.75 * (ac + i * as_).norm_sqr(),
                        Whirl::Backward => 0.75 * (ac - i * as_).norm_sqr(),
                    }
                }
                Slot::Drivetrain | Slot::Rotation => {
                    let modes = &self.drivetrain_modes;
                    let weights = match (slot, modes.len()) {
                        (Slot::Rotation, 2) => &modes[0],
                        (_, 2) => &modes[1],
                        _ => &modes[0],
                    };
                    let eta: Complex<f64> = weights.iter().zip(q).map(|(w, q)| q * *w).sum();
                    eta.norm_sqr()
                }
            });
        }
        e
    }

    fn content(&self, q: &[Complex<f64>]) -> Vec<f64> {
        crate::numeric::shares(self.slot_energies(q))
    }

    /// Blade 0's tip rows at zero azimuth over the ground coordinates (twist, flap).
    pub fn tip_rows(&self) -> [DVector<f64>; 2] {
        let r = self.motion_rows(self.length());
        [r.twist, r.flap]
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
    /// Blade 0 at zero azimuth: its rows on the collective and cosine coordinates, and the
    /// rotor's rotation as edge motion.
    fn motion_rows(&self, x: f64) -> MotionRows {
        let k = self.per_blade;
        let n = self.coordinates();
        let b = self.blade.motion_rows(x);
        let mut rows = MotionRows::zeros(n);
        for at in [0, k] {
            rows.twist.rows_mut(at, k).copy_from(&b.twist);
            rows.flap.rows_mut(at, k).copy_from(&b.flap);
            rows.edge.rows_mut(at, k).copy_from(&b.edge);
        }
        if self.generator.is_some() {
            rows.edge[3 * k] = self.hub_radius() + x;
        }
        rows
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
        Shares::from_energies(e[0], e[1], e[2])
    }
    /// Blade 0 kicked alone: a third collective, two thirds cosine.
    fn kick_shapes(&self) -> [DVector<f64>; 2] {
        let k = self.per_blade;
        let n = self.coordinates();
        self.blade.kick_shapes().map(|s| {
            let mut v = DVector::zeros(n);
            v.rows_mut(0, k).copy_from(&(&s / 3.0));
            v.rows_mut(k, k).copy_from(&(&s * (2.0 / 3.0)));
            v
        })
    }
    fn uniform_section(&self) -> Option<&SectionProps> {
        None
    }
    fn span_points(&self) -> Vec<f64> {
        self.blade.span_points()
    }
    fn slot_content(&self, q: &[Complex<f64>]) -> Option<Vec<f64>> {
        Some(self.content(q))
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

/// `φᵀ M` of the drivetrain's modes, `M` the ground coordinates' mass (the drivetrain's from
/// coordinate `at`), over all coordinates. With the generator free (`θ_r, δ`): the rigid
/// rotation `(1, 0)` on the whole mass, its amplitude the rotor's angular momentum about the
/// shaft (a collective edge mode whose hub swings against its blades holds none of it), and
/// the shaft's twist, M-orthogonal to the rigid rotation on the drivetrain's own mass (the
/// blades' collective motion is their own slot's). Locked (`θ_r`): the twist alone.
fn drivetrain_modes(m: &DMatrix<f64>, at: usize) -> Vec<DVector<f64>> {
    let n = m.nrows();
    let fixed = n - at;
    let own = m.view((at, at), (fixed, fixed)).into_owned();
    let on = |mphi: DVector<f64>, norm: f64| {
        let mut v = DVector::zeros(n);
        v.rows_mut(at, fixed).copy_from(&(mphi / norm));
        v
    };
    let twist = |phi: DVector<f64>| {
        let mphi = &own * &phi;
        let norm = phi.dot(&mphi).sqrt();
        on(mphi, norm)
    };
    match fixed {
        0 => Vec::new(),
        1 => vec![twist(DVector::from_element(1, 1.0))],
        _ => {
            let rigid = m.column(at) / m[(at, at)].sqrt();
            let a = -own[(0, 1)] / own[(0, 0)];
            vec![rigid, twist(DVector::from_vec(vec![a, 1.0]))]
        }
    }
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
