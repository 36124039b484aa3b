//! The blade structure as the aeroelastic system sees it (docs/model.md §6): `n_q` structural
//! coordinates `q` with mass, stiffness and damping matrices at the operating rotor speed, and,
//! at any span position, the rows that turn `q` into the motion of the reference (pitch) axis:
//! elastic twist `φ`, flap `u` (out of the rotor plane) and edge `v` (in it).
//!
//! Two structures provide it: the paper's uniform blade in Galerkin coordinates ([`galerkin`],
//! §3–§4; no edge motion, its edge rows are zero) and a tabulated real blade in the coordinates
//! of its rotating modes (§11.4). The system, the eigen-analysis and the time response work on
//! [`Structure`] alone, so they never ask which one they have.

pub mod galerkin;
pub mod tabulated;

pub use galerkin::{ac_frequency_hz, StructuralModel};

use crate::error::Result;
use crate::physics::section::SectionProps;
use nalgebra::{Complex, DMatrix, DVector};

/// A natural mode's modal damping ratio `qᵀCq / (2ω qᵀMq)` in `structure` (none at zero
/// frequency).
pub fn damping_ratio(structure: &dyn Structure, m: &NaturalMode) -> Option<f64> {
    let omega = m.frequency_hz * std::f64::consts::TAU;
    let q = &m.shape;
    let mass = q.dot(&(structure.mass() * q));
    (omega > 0.0 && mass > 0.0).then(|| q.dot(&(structure.damping() * q)) / (2.0 * omega * mass))
}

/// The motion families of a mode (docs/model.md §6.2, §11.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Family {
    Flap,
    Edge,
    Torsion,
}

impl Family {
    /// In the order of every `[flap, edge, twist]` share array.
    pub const ALL: [Family; 3] = [Family::Flap, Family::Edge, Family::Torsion];

    /// Position in [`Family::ALL`] (and in share arrays).
    pub fn index(self) -> usize {
        self as usize
    }

    /// `flap`, `edge`, `torsion`: the first word of a mode's label.
    pub fn name(self) -> &'static str {
        match self {
            Family::Flap => "flap",
            Family::Edge => "edge",
            Family::Torsion => "torsion",
        }
    }

    /// The family holding the largest share of `[flap, edge, twist]` motion; ties go to
    /// bending, flap before edge (a mode with no twist at all is never called torsion).
    pub fn of(shares: [f64; 3]) -> Family {
        let [flap, edge, twist] = shares;
        if twist > flap && twist > edge {
            Family::Torsion
        } else if edge > flap {
            Family::Edge
        } else {
            Family::Flap
        }
    }
}

/// Shares of a motion's kinetic energy in flap, edge and twist (each in [0, 1], summing to 1
/// unless the motion is zero).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Shares {
    pub flap: f64,
    pub edge: f64,
    pub twist: f64,
}

impl Shares {
    /// Normalised from the three (non-negative) kinetic energies.
    pub fn from_energies(flap: f64, edge: f64, twist: f64) -> Shares {
        let (flap, edge, twist) = (flap.max(0.0), edge.max(0.0), twist.max(0.0));
        let total = flap + edge + twist;
        if total > 0.0 {
            Shares {
                flap: flap / total,
                edge: edge / total,
                twist: twist / total,
            }
        } else {
            Shares {
                flap: 0.0,
                edge: 0.0,
                twist: 0.0,
            }
        }
    }

    pub fn array(self) -> [f64; 3] {
        [self.flap, self.edge, self.twist]
    }

    pub fn family(self) -> Family {
        Family::of(self.array())
    }
}

/// One undamped natural mode of the structure at its rotor speed (in vacuo).
#[derive(Debug, Clone, serde::Serialize)]
pub struct NaturalMode {
    /// `flap k`, `edge k` or `torsion k`: [`NaturalMode::family`] and [`NaturalMode::number`].
    pub label: String,
    pub family: Family,
    /// Its number within the family, counting from 1 in frequency order.
    pub number: usize,
    pub frequency_hz: f64,
    /// Kinetic-energy shares of flap, edge and twist motion.
    pub shares: Shares,
    /// The twist share alone (`shares.twist`), kept for scripts that read it.
    pub torsion_share: f64,
    /// Structural coordinates q (`n_q`).
    #[serde(skip)]
    pub shape: DVector<f64>,
}

impl NaturalMode {
    /// Modes from (frequency, shares, shape) in ascending frequency, named and numbered within
    /// their families.
    pub fn named(modes: Vec<(f64, Shares, DVector<f64>)>) -> Vec<NaturalMode> {
        let families: Vec<Family> = modes.iter().map(|(_, s, _)| s.family()).collect();
        let numbers = numbers_within_families(&families);
        modes
            .into_iter()
            .zip(families.into_iter().zip(numbers))
            .map(
                |((frequency_hz, shares, shape), (family, number))| NaturalMode {
                    frequency_hz,
                    label: format!("{} {number}", family.name()),
                    family,
                    number,
                    shares,
                    torsion_share: shares.twist,
                    shape,
                },
            )
            .collect()
    }
}

/// Each family's modes numbered 1, 2, … in the given (frequency) order.
pub fn numbers_within_families(families: &[Family]) -> Vec<usize> {
    let mut seen = [0usize; 3];
    families
        .iter()
        .map(|f| {
            let k = f.index();
            seen[k] += 1;
            seen[k]
        })
        .collect()
}

/// Labels `flap k` / `torsion k` of a flap–torsion blade from its twist shares (share > 0.5 →
/// torsion), k counting within its kind in the given (frequency) order.
pub fn mode_labels(torsion_shares_in_frequency_order: &[f64]) -> Vec<String> {
    let families: Vec<Family> = torsion_shares_in_frequency_order
        .iter()
        .map(|&t| Family::of([1.0 - t, 0.0, t]))
        .collect();
    numbers_within_families(&families)
        .into_iter()
        .zip(families)
        .map(|(k, f)| format!("{} {k}", f.name()))
        .collect()
}

/// `Re(qᴴ M q)` of a (complex) motion `q` on a block `M` of kinetic energy (the leading
/// `M.nrows()` coordinates of `q`).
pub fn kinetic_energy(m: &DMatrix<f64>, q: &[Complex<f64>]) -> f64 {
    let mut sum = 0.0;
    for (j, qj) in q.iter().enumerate().take(m.ncols()) {
        for (i, qi) in q.iter().enumerate().take(m.nrows()) {
            sum += m[(i, j)] * (qi.conj() * qj).re;
        }
    }
    sum
}

/// A rotor's or a turbine's motion by component (docs/model.md §13.4): the kinetic energy's
/// shares in the blades' flap, edge and twist (their motion relative to the hub), the
/// drivetrain's angles and the tower's modes, summing to 1.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Components {
    pub blade_flap: f64,
    pub blade_edge: f64,
    pub blade_twist: f64,
    pub drivetrain: f64,
    pub tower: f64,
}

impl Components {
    /// Normalised from the five (non-negative) kinetic energies, in the fields' order.
    pub fn from_energies(energies: [f64; 5]) -> Components {
        let e = energies.map(|v| v.max(0.0));
        let total: f64 = e.iter().sum();
        let s = e.map(|v| if total > 0.0 { v / total } else { 0.0 });
        Components {
            blade_flap: s[0],
            blade_edge: s[1],
            blade_twist: s[2],
            drivetrain: s[3],
            tower: s[4],
        }
    }
}

/// Rows mapping the structural coordinates `q` to the motion of the reference axis at one span
/// position: `φ = twist·q` (rad), `u = flap·q`, `v = edge·q` (m).
#[derive(Debug, Clone, PartialEq)]
pub struct MotionRows {
    pub twist: DVector<f64>,
    pub flap: DVector<f64>,
    pub edge: DVector<f64>,
}

impl MotionRows {
    /// No motion from any of `n` coordinates.
    pub fn zeros(n: usize) -> MotionRows {
        MotionRows {
            twist: DVector::zeros(n),
            flap: DVector::zeros(n),
            edge: DVector::zeros(n),
        }
    }
}

/// What a part of a structure is, for drawing a mode on it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PartKind {
    Blade,
    /// A tower: its rows' `flap`, `edge` and `twist` are fore–aft, side–side and torsion.
    Tower,
}

/// One part of a structure a mode shape is drawn on (docs/model.md §6.5), in coordinates of
/// its own: `own = map · q` (a blade of a rotor: its modes at its azimuth, the hub's turning,
/// the tower top), few against the structure's.
#[derive(Debug, Clone)]
pub struct ShapePart {
    /// `blade`, `blade 2`, `tower`.
    pub name: String,
    pub kind: PartKind,
    /// Positions along it (m from its root or base).
    pub points: Vec<f64>,
    /// Its own coordinates per coordinate of the structure.
    pub map: DMatrix<f64>,
    /// Flap, edge and twist (a tower's fore–aft, side–side, torsion) at each point per own
    /// coordinate.
    pub rows: [DMatrix<f64>; 3],
}

impl ShapePart {
    /// A part on the structure's coordinates themselves, its rows at each point given.
    pub fn direct(name: &str, kind: PartKind, points: Vec<(f64, MotionRows)>) -> ShapePart {
        let n = points.first().map_or(0, |(_, r)| r.flap.len());
        let stacked = |pick: fn(&MotionRows) -> &DVector<f64>| {
            DMatrix::from_fn(points.len(), n, |i, j| pick(&points[i].1)[j])
        };
        ShapePart {
            name: name.to_string(),
            kind,
            rows: [
                stacked(|r| &r.flap),
                stacked(|r| &r.edge),
                stacked(|r| &r.twist),
            ],
            map: DMatrix::identity(n, n),
            points: points.into_iter().map(|(x, _)| x).collect(),
        }
    }
}

/// A blade structure in some coordinates `q` (docs/model.md §6): what the aeroelastic system
/// needs, and nothing about how the coordinates were made.
pub trait Structure: Send + Sync {
    /// `n_q`, the number of structural coordinates.
    fn coordinates(&self) -> usize;
    /// Span from the clamped root to the tip (m).
    fn length(&self) -> f64;
    /// Root radius (m): span position `x` sits at radius `hub_radius + x`.
    fn hub_radius(&self) -> f64;
    /// M (`n_q × n_q`).
    fn mass(&self) -> &DMatrix<f64>;
    /// K at the rotor speed: elastic plus centrifugal.
    fn stiffness(&self) -> DMatrix<f64>;
    /// Structural damping C.
    fn damping(&self) -> &DMatrix<f64>;
    /// Twist, flap and edge of the reference axis at span position `x` (m from the root).
    fn motion_rows(&self, x: f64) -> MotionRows;
    /// The motion rows at each of the strips' span positions `xs`, in order. One blade's at each
    /// position; a rotor of N blades takes the same positions once per blade, blade after
    /// blade, and gives each its own blade's rows (docs/model.md §13.3).
    fn station_rows(&self, xs: &[f64]) -> Vec<MotionRows> {
        xs.iter().map(|&x| self.motion_rows(x)).collect()
    }
    /// Undamped natural modes at the rotor speed, ascending, named by family.
    fn natural_modes(&self) -> Result<Vec<NaturalMode>>;
    /// Kinetic-energy shares of a (complex) motion's coordinates `q`.
    fn shares(&self, q: &[Complex<f64>]) -> Shares;
    /// Coordinates of the shapes a tip kick excites: the first torsion and the first flap shape.
    fn kick_shapes(&self) -> [DVector<f64>; 2];
    /// The uniform section, when the blade is the paper's uniform beam.
    fn uniform_section(&self) -> Option<&SectionProps>;
    /// Span positions (m from the root) at which to show its mode shapes.
    fn span_points(&self) -> Vec<f64>;
    /// The parts its mode shapes are drawn on: the blade alone at its span points (a rotor's
    /// blades at their azimuths and its tower, [`crate::physics::turbine::GroundRotor`]).
    fn shape_parts(&self) -> Vec<ShapePart> {
        let points = self.span_points();
        let rows = points
            .into_iter()
            .map(|x| (x, self.motion_rows(x)))
            .collect();
        vec![ShapePart::direct("blade", PartKind::Blade, rows)]
    }
    /// The constant load on the coordinates at the rotor speed, with no motion and no air: the
    /// centrifugal pull on a curved blade's axis (docs/model.md §11.9); zero for a straight one.
    fn static_load(&self) -> DVector<f64> {
        DVector::zeros(self.coordinates())
    }
    /// The modes these coordinates leave out, as a structure of their own (diagonal stiffness,
    /// their motion rows and static load), where the coordinates truncate a larger basis: the
    /// system adds their static response to the equilibrium and their quasi-static response to
    /// its state matrix, the truncated basis's correction (docs/model.md §12.6). None for a
    /// complete basis (the paper's blade).
    fn left_out(&self) -> Option<&dyn Structure> {
        None
    }
    /// Exact zero roots of the coordinates that are no mode: the azimuth of a rotor free to
    /// turn, on which nothing depends (docs/model.md §13.2). The analyses leave them out of
    /// the roots they name.
    fn rigid_body_roots(&self) -> usize {
        0
    }
    /// What a rotor needs of one of its blades (docs/model.md §13.2): none for a blade that
    /// cannot sit on one (the paper's, which has no edge motion).
    fn rotor_coupling(&self) -> Option<RotorCoupling> {
        None
    }
    /// The content of a root (eigenvalue `lambda`, motion `q`) in the named slots of
    /// [`Structure::natural_modes`], in their order (shares summing to 1), where the structure
    /// names its roots by a measure of its own (a rotor in multi-blade coordinates, §13.5);
    /// none: the mass-weighted projection on the natural modes' shapes.
    fn slot_content(&self, _q: &[Complex<f64>], _lambda: Complex<f64>) -> Option<Vec<f64>> {
        None
    }
    /// How far a root named `label` is seen shifted in its blades' rotating frame (Hz, added to
    /// its ground-frame frequency): `+1P` for a backward whirl, `−1P` forward, 0 collective;
    /// none where the name is not a blade mode's in the ground frame.
    fn rotating_shift_hz(&self, _label: &str) -> Option<f64> {
        None
    }
    /// Whether a system's state matrix on these coordinates is the same at every instant, so
    /// that it gives the rates of any motion the state implies (docs/model.md §12.6, the
    /// left-out modes' dynamics); not for a rotor whose blades' frames turn against the hub's
    /// coordinates, whose state matrix is one azimuth's (§13).
    fn time_invariant(&self) -> bool {
        true
    }
    /// A motion's shares by component, for a structure made of several (a rotor, a turbine).
    fn components(&self, _q: &[Complex<f64>]) -> Option<Components> {
        None
    }
}

/// One blade's part in a rotor (docs/model.md §13.2), in its modal coordinates.
#[derive(Debug, Clone)]
pub struct RotorCoupling {
    /// `φ_jᵀ M r_k`: each mode's (row) share of the blade's rigid motions (columns, in the
    /// order of [`crate::physics::blade::Rigid`]).
    pub rigid: DMatrix<f64>,
    /// `r_kᵀ M r_l` of the blade's rigid motions; `[Rotation, Rotation]` is its moment of
    /// inertia about the shaft (kg·m²), `[Flap, Flap]` its mass.
    pub rigid_mass: DMatrix<f64>,
    /// The centrifugal load per Ω² on a curved blade (zero for a straight one).
    pub centrifugal_load: DVector<f64>,
    /// `K_Ω`, the stiffness per Ω² between the modes.
    pub centrifugal_stiffness: DMatrix<f64>,
    /// The kinetic energy of flap, edge and twist between the modes ([`Structure::shares`]).
    pub family_energy: [DMatrix<f64>; 3],
}
