//! The rotor in the blades' own rotating frames (docs/model.md §13.2–§13.3): N identical blades,
//! each in the coordinates of its modes, and the drivetrain's angles. A [`Structure`] the
//! aeroelastic system builds on as it does on one blade: its strips are the blade's, once per
//! blade ([`Structure::station_rows`]), and the rotor's azimuth moves every strip in the edge
//! direction by its radius.
//!
//! Coordinates: blade k's mode j at `k·K + j`, then the drivetrain's `θ_r` (and `θ_g`). The mass
//! couples each mode with `θ_r` by its share of the rigid rotation (`φ_jᵀ M r`); `θ_r` carries
//! the hub's and the N blades' inertia about the shaft. Turning faster pulls a curved or
//! deflected blade outward, and a blade moving radially changes the rotor's angular momentum:
//! the skew pair `±2Ω g` between the modes and `θ_r`, `g = f − K_Ω q*` the radial load per Ω²
//! on the blade at its equilibrium `q*`.

use super::drivetrain::Drivetrain;
use crate::error::{Error, Result};
use crate::physics::blade::fem::Rigid;
use crate::physics::section::SectionProps;
use crate::physics::structure::{kinetic_energy, MotionRows, NaturalMode, Shares, Structure};
use nalgebra::{Complex, DMatrix, DVector};
use std::sync::Arc;

/// Which of the blade's modes a rotor's blades hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Part {
    /// The retained ones, the blade structure's own coordinates.
    Retained,
    /// The ones it leaves out ([`Structure::left_out`]), for the static correction.
    LeftOut,
}

/// N blades and the drivetrain, in the blades' rotating frames.
pub struct Rotor {
    blade: Arc<dyn Structure>,
    part: Part,
    blades: usize,
    /// Modes per blade.
    per_blade: usize,
    drivetrain: Option<Drivetrain>,
    mass: DMatrix<f64>,
    stiffness: DMatrix<f64>,
    damping: DMatrix<f64>,
    static_load: DVector<f64>,
    family_energy: [DMatrix<f64>; 3],
    /// The left-out modes of every blade, where the blade leaves some out.
    left_out: Option<Box<Rotor>>,
}

impl Rotor {
    /// `blades` copies of `blade` (modes at rotor speed `omega`, rad/s, its equilibrium
    /// coordinates `q_eq`) on `drivetrain` (none: the hub turns at a constant speed, the blades
    /// clamped to it).
    pub fn new(
        blade: Arc<dyn Structure>,
        blades: usize,
        drivetrain: Option<Drivetrain>,
        omega: f64,
        q_eq: &DVector<f64>,
    ) -> Result<Rotor> {
        let coupling = blade.rotor_coupling().ok_or_else(|| {
            Error::numerical(
                "a rotor needs a tabulated blade (the paper's blade has no edge motion)",
            )
        })?;
        if blades < 3 {
            return Err(Error::numerical(format!(
                "a rotor of {blades} blades: the multi-blade transform needs at least 3"
            )));
        }
        let k = blade.coordinates();
        if q_eq.len() != k {
            return Err(Error::numerical(format!(
                "rotor: the blade's equilibrium has {} coordinates, the blade {k}",
                q_eq.len()
            )));
        }
        let left_out = blade.left_out().map(|rest| {
            let (stiffness, load) = (rest.stiffness(), rest.static_load());
            Box::new(Rotor::left_out_of(
                Arc::clone(&blade),
                blades,
                stiffness,
                load,
            ))
        });
        let fixed = drivetrain.as_ref().map_or(0, Drivetrain::coordinates);
        let n = blades * k + fixed;
        let mut mass = DMatrix::zeros(n, n);
        let mut stiffness = DMatrix::zeros(n, n);
        let mut damping = DMatrix::zeros(n, n);
        let mut static_load = DVector::zeros(n);
        let blade_stiffness = blade.stiffness();
        let own_load = blade.static_load();
        for b in 0..blades {
            let at = b * k;
            mass.view_mut((at, at), (k, k)).copy_from(blade.mass());
            stiffness
                .view_mut((at, at), (k, k))
                .copy_from(&blade_stiffness);
            damping
                .view_mut((at, at), (k, k))
                .copy_from(blade.damping());
            static_load.rows_mut(at, k).copy_from(&own_load);
        }
        if let Some(d) = &drivetrain {
            let at = blades * k;
            let [m, s, c] = d.matrices();
            mass.view_mut((at, at), (fixed, fixed)).copy_from(&m);
            stiffness.view_mut((at, at), (fixed, fixed)).copy_from(&s);
            damping.view_mut((at, at), (fixed, fixed)).copy_from(&c);
            mass[(at, at)] += blades as f64
                * coupling.rigid_mass[(Rigid::Rotation as usize, Rigid::Rotation as usize)];
            let radial = &coupling.centrifugal_load - &coupling.centrifugal_stiffness * q_eq;
            for b in 0..blades {
                for j in 0..k {
                    let i = b * k + j;
                    mass[(i, at)] = coupling.rigid[(j, Rigid::Rotation as usize)];
                    mass[(at, i)] = coupling.rigid[(j, Rigid::Rotation as usize)];
                    damping[(i, at)] -= 2.0 * omega * radial[j];
                    damping[(at, i)] += 2.0 * omega * radial[j];
                }
            }
        }
        Ok(Rotor {
            blade,
            part: Part::Retained,
            blades,
            per_blade: k,
            drivetrain,
            mass,
            stiffness,
            damping,
            static_load,
            family_energy: coupling.family_energy,
            left_out,
        })
    }

    /// The left-out modes of `blades` copies of `blade` (their `stiffness` and own static
    /// `load`, per blade): stiffness, rows and static load, all the static correction reads.
    fn left_out_of(
        blade: Arc<dyn Structure>,
        blades: usize,
        stiffness: DMatrix<f64>,
        load: DVector<f64>,
    ) -> Rotor {
        let count = load.len();
        let n = blades * count;
        let mut k = DMatrix::zeros(n, n);
        let mut static_load = DVector::zeros(n);
        for b in 0..blades {
            let at = b * count;
            k.view_mut((at, at), (count, count)).copy_from(&stiffness);
            static_load.rows_mut(at, count).copy_from(&load);
        }
        Rotor {
            blade,
            part: Part::LeftOut,
            blades,
            per_blade: count,
            drivetrain: None,
            mass: DMatrix::identity(n, n),
            stiffness: k,
            damping: DMatrix::zeros(n, n),
            static_load,
            family_energy: [(); 3].map(|_| DMatrix::zeros(count, count)),
            left_out: None,
        }
    }

    /// The blade structure whose modes the blades hold.
    fn body(&self) -> &dyn Structure {
        match self.part {
            Part::Retained => self.blade.as_ref(),
            // Built only from a blade that leaves modes out; its own blade otherwise.
            Part::LeftOut => self.blade.left_out().unwrap_or(self.blade.as_ref()),
        }
    }

    pub fn blades(&self) -> usize {
        self.blades
    }

    /// Modes per blade.
    pub fn per_blade(&self) -> usize {
        self.per_blade
    }

    pub fn drivetrain(&self) -> Option<&Drivetrain> {
        self.drivetrain.as_ref()
    }

    /// The blade structure the rotor is made of.
    pub fn blade(&self) -> &Arc<dyn Structure> {
        &self.blade
    }

    /// The kinetic energy of flap, edge and twist between one blade's modes.
    pub fn family_energy(&self) -> &[DMatrix<f64>; 3] {
        &self.family_energy
    }

    /// The first drivetrain coordinate (`θ_r`).
    pub fn drivetrain_at(&self) -> usize {
        self.blades * self.per_blade
    }

    /// Blade `b`'s rows in `rows` (one blade's, at span `x`), with the azimuth's edge motion.
    fn rows_of_blade(&self, b: usize, x: f64, blade: &MotionRows) -> MotionRows {
        let n = self.coordinates();
        let k = self.per_blade;
        let mut rows = MotionRows::zeros(n);
        rows.twist.rows_mut(b * k, k).copy_from(&blade.twist);
        rows.flap.rows_mut(b * k, k).copy_from(&blade.flap);
        rows.edge.rows_mut(b * k, k).copy_from(&blade.edge);
        if self.drivetrain.is_some() {
            rows.edge[self.drivetrain_at()] = self.hub_radius() + x;
        }
        rows
    }

    /// Kinetic energies of flap, edge and twist in rotating-frame coordinates `q`: the blades'
    /// own, and the rotor's rotation as edge motion (it moves every section in the edge
    /// direction).
    fn energies(&self, q: &[Complex<f64>]) -> [f64; 3] {
        let k = self.per_blade;
        let mut e = [0.0; 3];
        for b in 0..self.blades {
            let block = &q[b * k..(b + 1) * k];
            for (acc, m) in e.iter_mut().zip(&self.family_energy) {
                *acc += kinetic_energy(m, block);
            }
        }
        if self.drivetrain.is_some() {
            let at = self.drivetrain_at();
            e[1] += self.mass[(at, at)] * q[at].norm_sqr();
        }
        e
    }
}

impl Structure for Rotor {
    fn coordinates(&self) -> usize {
        self.mass.nrows()
    }
    fn length(&self) -> f64 {
        self.body().length()
    }
    fn hub_radius(&self) -> f64 {
        self.body().hub_radius()
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
    /// Blade 0's.
    fn motion_rows(&self, x: f64) -> MotionRows {
        self.rows_of_blade(0, x, &self.body().motion_rows(x))
    }
    /// `xs` holds one blade's positions once per blade, blade after blade.
    fn station_rows(&self, xs: &[f64]) -> Vec<MotionRows> {
        let per = xs.len() / self.blades;
        let blade = self.body().station_rows(&xs[..per]);
        xs.iter()
            .enumerate()
            .map(|(i, &x)| {
                let b = (i / per.max(1)).min(self.blades - 1);
                self.rows_of_blade(b, x, &blade[i % per.max(1)])
            })
            .collect()
    }
    /// The rotor's modes are named in the ground frame ([`super::ground::GroundRotor`]); in the
    /// blades' rotating frames they are not one structure's modes.
    fn natural_modes(&self) -> Result<Vec<NaturalMode>> {
        Err(Error::numerical(
            "the rotor's modes are named in the ground frame, not in the blades' rotating frames",
        ))
    }
    fn shares(&self, q: &[Complex<f64>]) -> Shares {
        let [f, e, t] = self.energies(q);
        Shares::from_energies(f, e, t)
    }
    /// Blade 0's.
    fn kick_shapes(&self) -> [DVector<f64>; 2] {
        let n = self.coordinates();
        self.body().kick_shapes().map(|s| {
            let mut v = DVector::zeros(n);
            v.rows_mut(0, s.len()).copy_from(&s);
            v
        })
    }
    fn uniform_section(&self) -> Option<&SectionProps> {
        None
    }
    fn span_points(&self) -> Vec<f64> {
        self.body().span_points()
    }
    fn static_load(&self) -> DVector<f64> {
        self.static_load.clone()
    }
    fn left_out(&self) -> Option<&dyn Structure> {
        self.left_out.as_deref().map(|r| r as &dyn Structure)
    }
}
