//! A tabulated blade as the aeroelastic system sees it (docs/model.md §6, §11.4): the coordinates
//! are the amplitudes of its first K rotating modes at the operating rotor speed, M-normalised,
//! so `M = I`, `K = diag ω_k²` and `C = diag 2ζ_kω_k` with one modal damping ratio per mode. The
//! motion rows are the mode shapes carried from the shear centre to the reference (pitch) axis,
//! where the aerodynamics attach.

use super::{kinetic_energy, Family, MotionRows, NaturalMode, RotorCoupling, Shares, Structure};
use crate::error::{Error, Result};
use crate::physics::blade::modal::{BladeMode, ModalBlade};
use crate::physics::section::SectionProps;
use nalgebra::{Complex, DMatrix, DVector};
use std::f64::consts::TAU;
use std::sync::Arc;

/// The first K rotating modes of a tabulated blade, as structural coordinates.
pub struct TabulatedStructure {
    blade: Arc<ModalBlade>,
    modes: Vec<BladeMode>,
    natural: Vec<NaturalMode>,
    mass: DMatrix<f64>,
    stiffness: DMatrix<f64>,
    damping: DMatrix<f64>,
    /// [`Structure::static_load`] at the rotor speed the modes are at.
    static_load: DVector<f64>,
    /// `Φᵀ M_b Φ` for the flap, edge and twist blocks `b` of the mass matrix: the kinetic energy
    /// of each family in any combination of the modes.
    family_energy: [DMatrix<f64>; 3],
    /// The reduced basis's modes beyond these, as a structure of their own
    /// ([`Structure::left_out`]).
    left_out: Option<Box<TabulatedStructure>>,
}

/// `modes` each turned so that the tip moves positively in the mode's own family (flap,
/// edge or twist): an eigensolver's sign is arbitrary, and a coordinate whose sign flipped
/// between two rotor speeds or pitches would make the same motion look unlike itself to the
/// tracking's eigenvector correlation (a rotor's whirl modes, mixing several blade modes,
/// lost their match between neighbouring wind speeds) and turn a kick's tip response over.
fn signed(blade: &ModalBlade, mut modes: Vec<BladeMode>) -> Vec<BladeMode> {
    let Ok(tip) = blade
        .geometry
        .reference_axis_at(blade.geometry.table.length())
    else {
        return modes;
    };
    for m in &mut modes {
        let motion = tip.motion(&m.shape);
        let own = match m.family() {
            Family::Flap => motion.flap,
            Family::Edge => motion.edge,
            Family::Torsion => motion.twist,
        };
        if own < 0.0 {
            m.shape.neg_mut();
            m.coordinates.neg_mut();
        }
    }
    modes
}

impl TabulatedStructure {
    /// The blade's `modes` (from [`ModalBlade::modes`] at rotor speed `rotor_speed`, rad/s), each
    /// damped by its own [`BladeMode::damping_ratio`].
    pub fn new(
        blade: Arc<ModalBlade>,
        modes: Vec<BladeMode>,
        rotor_speed: f64,
    ) -> Result<TabulatedStructure> {
        if modes.is_empty() {
            return Err(Error::numerical("tabulated blade: no modes retained"));
        }
        let modes = signed(&blade, modes);
        let ratios: Vec<f64> = modes.iter().map(|m| m.damping_ratio).collect();
        let k = modes.len();
        let omega: Vec<f64> = modes.iter().map(|m| TAU * m.frequency_hz).collect();
        let stiffness =
            DMatrix::from_fn(k, k, |i, j| if i == j { omega[i] * omega[i] } else { 0.0 });
        let damping = DMatrix::from_fn(k, k, |i, j| {
            if i == j {
                2.0 * ratios[i] * omega[i]
            } else {
                0.0
            }
        });
        let family_energy = blade.family_energy(&modes);
        let static_load = blade.centrifugal_load(&modes) * (rotor_speed * rotor_speed);
        let natural = NaturalMode::named(
            modes
                .iter()
                .enumerate()
                .map(|(i, m)| {
                    let [flap, edge, twist] = m.shares;
                    let unit = DVector::from_fn(k, |r, _| if r == i { 1.0 } else { 0.0 });
                    (
                        m.frequency_hz,
                        Shares::from_energies(flap, edge, twist),
                        unit,
                    )
                })
                .collect(),
        );
        Ok(TabulatedStructure {
            blade,
            modes,
            natural,
            mass: DMatrix::identity(k, k),
            stiffness,
            damping,
            static_load,
            family_energy,
            left_out: None,
        })
    }

    /// This structure with `left_out`, the modes of the same blade beyond its own (from
    /// [`ModalBlade::modes`] at the same rotor speed, ascending), whose static response the
    /// system adds to the equilibrium and its state matrix (docs/model.md §12.6); none when
    /// `left_out` is empty.
    pub fn with_left_out(
        mut self,
        left_out: Vec<BladeMode>,
        rotor_speed: f64,
    ) -> Result<TabulatedStructure> {
        self.left_out = if left_out.is_empty() {
            None
        } else {
            let blade = Arc::clone(&self.blade);
            Some(Box::new(TabulatedStructure::new(
                blade,
                left_out,
                rotor_speed,
            )?))
        };
        Ok(self)
    }

    /// The modes the coordinates are amplitudes of.
    pub fn modes(&self) -> &[BladeMode] {
        &self.modes
    }

    /// The coordinate of the lowest mode of `family`, if the basis holds one.
    fn first_of(&self, family: Family) -> Option<usize> {
        self.natural.iter().position(|m| m.family == family)
    }
}

impl Structure for TabulatedStructure {
    fn coordinates(&self) -> usize {
        self.modes.len()
    }
    fn length(&self) -> f64 {
        self.blade.geometry.table.length()
    }
    fn hub_radius(&self) -> f64 {
        self.blade.geometry.table.hub_radius
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
    /// Each mode's twist, flap and edge at the reference axis (docs/model.md §11.2: a point off
    /// the shear centre moves with the twist).
    fn motion_rows(&self, x: f64) -> MotionRows {
        let k = self.modes.len();
        let mut rows = MotionRows::zeros(k);
        let z = x.clamp(0.0, self.length());
        // z is on the blade, so locating it cannot fail.
        if let Ok(map) = self.blade.geometry.reference_axis_at(z) {
            for (i, m) in self.modes.iter().enumerate() {
                let motion = map.motion(&m.shape);
                rows.twist[i] = motion.twist;
                rows.flap[i] = motion.flap;
                rows.edge[i] = motion.edge;
            }
        }
        rows
    }
    fn natural_modes(&self) -> Result<Vec<NaturalMode>> {
        Ok(self.natural.clone())
    }
    fn shares(&self, q: &[Complex<f64>]) -> Shares {
        let energy = |e: &DMatrix<f64>| kinetic_energy(e, q);
        let [f, e, t] = &self.family_energy;
        Shares::from_energies(energy(f), energy(e), energy(t))
    }
    /// The lowest torsion and the lowest flap mode (the first mode where the basis has none).
    fn kick_shapes(&self) -> [DVector<f64>; 2] {
        let k = self.modes.len();
        let unit = |i: usize| DVector::from_fn(k, |r, _| if r == i { 1.0 } else { 0.0 });
        [
            unit(self.first_of(Family::Torsion).unwrap_or(0)),
            unit(self.first_of(Family::Flap).unwrap_or(0)),
        ]
    }
    fn uniform_section(&self) -> Option<&SectionProps> {
        None
    }
    /// The mesh nodes, which follow the input stations.
    fn static_load(&self) -> DVector<f64> {
        self.static_load.clone()
    }
    fn span_points(&self) -> Vec<f64> {
        self.blade.geometry.mesh.nodes.clone()
    }
    fn left_out(&self) -> Option<&dyn Structure> {
        self.left_out.as_deref().map(|s| s as &dyn Structure)
    }
    fn rotor_coupling(&self) -> Option<RotorCoupling> {
        Some(RotorCoupling {
            rigid: self.blade.rigid_participation(&self.modes),
            rigid_mass: self.blade.rigid_mass().clone(),
            centrifugal_load: self.blade.centrifugal_load(&self.modes),
            centrifugal_stiffness: self.blade.centrifugal_stiffness(&self.modes),
            family_energy: self.family_energy.clone(),
        })
    }
}
