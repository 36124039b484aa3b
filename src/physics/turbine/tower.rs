//! The tower and what sits on it (docs/model.md §13.6): ElastoDyn's assumed-mode tower, two
//! fore–aft and two side–side bending modes on the polynomial shapes its file gives, carrying
//! the yaw bearing, the nacelle and the hub as point masses. Plain inputs; out: the mass,
//! stiffness and damping over its coordinates and how they move the rotor apex, where the
//! rotor ([`super::rotor::Rotor`]) hangs its blades. A HAWC2 tower, a beam with torsion, is
//! [`super::tower_beam`]'s; both end in a [`Tower`].
//!
//! Frame: x downwind along the (untilted) shaft, z up the tower, y = z × x (lateral). The
//! tower top moves by `u_x = Σ φ_FA q`, `u_y = Σ φ_SS q` and turns by `θ_y = Σ φ'_FA(L) q`
//! (its vertical tipping downwind), `θ_x = −Σ φ'_SS(L) q`, and with torsion `θ_z = Σ φ_T q`.
//! An ElastoDyn tower has no torsion: its file gives no torsional stiffness, and none is
//! assumed.

use crate::error::{Error, Result};
use crate::physics::basis::gauss_rule;
use crate::physics::structure::{kinetic_energy, Family, MotionRows};
use nalgebra::{Complex, DMatrix, DVector, Matrix3, Vector3};

/// One station of the tower's distributed properties, the file's factors applied.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TowerSection {
    /// Fraction of the tower's length from its base.
    pub height_fraction: f64,
    /// kg/m.
    pub mass_density: f64,
    /// N·m², bending fore–aft and side–side.
    pub fore_aft_stiffness: f64,
    pub side_side_stiffness: f64,
}

/// The coefficients of `h², …, h⁶` of one assumed mode shape in the height fraction `h`.
pub type ModeShape = [f64; 5];

/// The tower's plain inputs.
#[derive(Debug, Clone, PartialEq)]
pub struct TowerInputs {
    /// Base to top (m).
    pub length: f64,
    pub sections: Vec<TowerSection>,
    /// Fore–aft modes 1, 2 then side–side modes 1, 2: shape, stiffness tuner, damping ratio
    /// (fraction of critical).
    pub shapes: [ModeShape; 4],
    pub tuners: [f64; 4],
    pub damping: [f64; 4],
}

/// The point masses on the tower top and where the rotor sits.
#[derive(Debug, Clone, PartialEq)]
pub struct TowerTop {
    /// kg, at the tower top.
    pub yaw_bearing_mass: f64,
    /// kg, at `nacelle_cm` from the tower top (x, y, z).
    pub nacelle_mass: f64,
    pub nacelle_cm: [f64; 3],
    /// The nacelle's inertia tensor about its centre of mass in the axes x (roll), y (tilt), z
    /// (yaw), kg·m².
    pub nacelle_inertia: [[f64; 3]; 3],
    /// kg, at `hub_cm` downwind of the apex along the shaft.
    pub hub_mass: f64,
    pub hub_cm: f64,
    /// The rotor apex: `overhang` downwind of the yaw axis (negative upwind) and
    /// `shaft_height` above the tower top.
    pub overhang: f64,
    pub shaft_height: f64,
}

/// One of the tower's coordinates: the mode it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TowerMode {
    ForeAft1,
    ForeAft2,
    SideSide1,
    SideSide2,
    Torsion1,
}

/// The direction a tower mode moves its top in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plane {
    ForeAft = 0,
    SideSide = 1,
    Torsion = 2,
}

impl TowerMode {
    pub const ALL: [TowerMode; 5] = [
        TowerMode::ForeAft1,
        TowerMode::ForeAft2,
        TowerMode::SideSide1,
        TowerMode::SideSide2,
        TowerMode::Torsion1,
    ];

    /// The tower mode a root is named after ([`TowerMode::label`]), none for any other name.
    pub fn of_name(label: &str) -> Option<TowerMode> {
        TowerMode::ALL.into_iter().find(|m| m.label() == label)
    }

    /// An ElastoDyn tower's four, in its coordinates' order.
    pub const BENDING: [TowerMode; 4] = [
        TowerMode::ForeAft1,
        TowerMode::ForeAft2,
        TowerMode::SideSide1,
        TowerMode::SideSide2,
    ];

    pub fn plane(self) -> Plane {
        match self {
            TowerMode::ForeAft1 | TowerMode::ForeAft2 => Plane::ForeAft,
            TowerMode::SideSide1 | TowerMode::SideSide2 => Plane::SideSide,
            TowerMode::Torsion1 => Plane::Torsion,
        }
    }

    /// The `number`-th (from 1) mode of `plane`; beyond the last the tower holds, the last.
    pub fn named(plane: Plane, number: usize) -> TowerMode {
        match (plane, number) {
            (Plane::ForeAft, 1) => TowerMode::ForeAft1,
            (Plane::ForeAft, _) => TowerMode::ForeAft2,
            (Plane::SideSide, 1) => TowerMode::SideSide1,
            (Plane::SideSide, _) => TowerMode::SideSide2,
            (Plane::Torsion, _) => TowerMode::Torsion1,
        }
    }

    /// The motion family a tower mode reads as on a blade (fore–aft moves the blades in flap,
    /// side–side in edge; torsion yaws the rotor, read as the tower's twist) and its number.
    pub fn family_and_number(self) -> (Family, usize) {
        match self {
            TowerMode::ForeAft1 => (Family::Flap, 1),
            TowerMode::ForeAft2 => (Family::Flap, 2),
            TowerMode::SideSide1 => (Family::Edge, 1),
            TowerMode::SideSide2 => (Family::Edge, 2),
            TowerMode::Torsion1 => (Family::Torsion, 1),
        }
    }

    /// `tower FA 1`, … as every output names the mode it dominates.
    pub fn label(self) -> &'static str {
        match self {
            TowerMode::ForeAft1 => "tower FA 1",
            TowerMode::ForeAft2 => "tower FA 2",
            TowerMode::SideSide1 => "tower SS 1",
            TowerMode::SideSide2 => "tower SS 2",
            TowerMode::Torsion1 => "tower torsion 1",
        }
    }
}

/// The rotor apex's motion, the rows of [`Tower::apex`]: translation and the turn of the
/// shaft about x (roll, which adds to the rotor's azimuth), about y (tilt) and about z (yaw).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Apex {
    X = 0,
    Y = 1,
    Z = 2,
    Roll = 3,
    Tilt = 4,
    Yaw = 5,
}

/// How many [`Apex`] motions there are.
pub const APEX_MOTIONS: usize = 6;

/// The tower with its top masses.
#[derive(Debug, Clone, PartialEq)]
pub struct Tower {
    /// What each coordinate is, in order.
    pub modes: Vec<TowerMode>,
    /// Over the coordinates: the tower's own with the yaw bearing, the nacelle and the hub as
    /// rigid masses (the blades are the rotor's).
    pub mass: DMatrix<f64>,
    pub stiffness: DMatrix<f64>,
    pub damping: DMatrix<f64>,
    /// The apex's motion per coordinate (rows in [`Apex`] order).
    pub apex: DMatrix<f64>,
    /// `∫ φ'ᵢ φ'ⱼ dz`: the stiffness a newton of weight on the tower top takes away (its
    /// moment as the tower leans, ElastoDyn's gravity term); the rotor adds its blades'.
    pub sag: DMatrix<f64>,
    /// Its own motion along the height, for drawing its part of a mode: at each height (m from
    /// its base) the rows of fore–aft displacement (`flap`, m), side–side displacement (`edge`,
    /// m) and torsion (`twist`, rad) per coordinate.
    pub profile: Vec<(f64, MotionRows)>,
}

/// Heights at which an assumed-mode tower's profile is sampled (its shapes are polynomials).
const PROFILE_POINTS: usize = 41;

/// Standard gravity (m/s²), as OpenFAST's input files give it: ElastoDyn's tower softens
/// under the weight above each section.
pub const GRAVITY: f64 = 9.80665;

/// Gauss points per interval of the section table: exact for the mass integrand (linear
/// density times two sixth-degree shapes).
const GAUSS_POINTS: usize = 7;

impl Tower {
    /// ElastoDyn's assumed-mode tower: fore–aft 1, 2 and side–side 1, 2 on the file's shapes.
    pub fn new(inputs: &TowerInputs, top: &TowerTop) -> Result<Tower> {
        check(inputs, top)?;
        let l = inputs.length;
        let modes = TowerMode::BENDING.to_vec();
        let n = modes.len();
        let mut own_mass = DMatrix::<f64>::zeros(n, n);
        let mut stiffness = DMatrix::<f64>::zeros(n, n);
        let rule = gauss_rule(GAUSS_POINTS);
        let same_plane = |i: usize, j: usize| modes[i].plane() == modes[j].plane();
        for pair in inputs.sections.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let dh = b.height_fraction - a.height_fraction;
            for (s, w) in rule.0.iter().zip(&rule.1) {
                let t = 0.5 * (s + 1.0);
                let h = a.height_fraction + t * dh;
                let weight = 0.5 * w * dh;
                let lerp = |f: fn(&TowerSection) -> f64| f(&a) + t * (f(&b) - f(&a));
                let mu = lerp(|s| s.mass_density);
                let ei = [
                    lerp(|s| s.fore_aft_stiffness),
                    lerp(|s| s.side_side_stiffness),
                ];
                let phi = inputs.shapes.map(|c| value(&c, h));
                let curvature = inputs.shapes.map(|c| curvature(&c, h));
                for i in 0..n {
                    for j in (0..n).filter(|&j| same_plane(i, j)) {
                        own_mass[(i, j)] += weight * l * mu * phi[i] * phi[j];
                        let e = ei[modes[i].plane() as usize];
                        stiffness[(i, j)] += weight * e * curvature[i] * curvature[j] / l.powi(3);
                    }
                }
            }
        }
        for i in 0..n {
            for j in 0..n {
                stiffness[(i, j)] *= (inputs.tuners[i] * inputs.tuners[j]).sqrt();
            }
        }
        // ElastoDyn's damping reads each mode's frequency without gravity or the top masses.
        let mut damping = DMatrix::zeros(n, n);
        for j in 0..n {
            let omega = (stiffness[(j, j)] / own_mass[(j, j)]).sqrt();
            for i in 0..n {
                damping[(i, j)] = 2.0 * inputs.damping[j] * stiffness[(i, j)] / omega;
            }
        }
        let density: Vec<(f64, f64)> = inputs
            .sections
            .iter()
            .map(|s| (s.height_fraction * l, s.mass_density))
            .collect();
        let slopes = |z: f64| {
            let mut d = DMatrix::zeros(2, n);
            for (j, c) in inputs.shapes.iter().enumerate() {
                d[(modes[j].plane() as usize, j)] = slope(c, z / l) / l;
            }
            d
        };
        let (sag, own_weight) = leaning(&density, &[], n, &slopes);
        let profile = (0..PROFILE_POINTS)
            .map(|i| {
                let h = i as f64 / (PROFILE_POINTS - 1) as f64;
                let mut rows = MotionRows::zeros(n);
                for (j, mode) in modes.iter().enumerate() {
                    let along = value(&inputs.shapes[j], h);
                    match mode.plane() {
                        Plane::ForeAft => rows.flap[j] = along,
                        _ => rows.edge[j] = along,
                    }
                }
                (h * l, rows)
            })
            .collect();
        let mut top_motion = DMatrix::zeros(APEX_MOTIONS, n);
        for (j, mode) in modes.iter().enumerate() {
            let c = &inputs.shapes[j];
            let slope = slope(c, 1.0) / l;
            if mode.plane() == Plane::ForeAft {
                top_motion[(Apex::X as usize, j)] = value(c, 1.0);
                top_motion[(Apex::Tilt as usize, j)] = slope;
            } else {
                top_motion[(Apex::Y as usize, j)] = value(c, 1.0);
                top_motion[(Apex::Roll as usize, j)] = -slope;
            }
        }
        Ok(Tower::on_top(
            modes,
            own_mass,
            stiffness,
            damping,
            own_weight,
            sag,
            &top_motion,
            profile,
            top,
        ))
    }

    /// The tower of `modes` with its own `mass`, `stiffness`, `damping`, gravity terms, its
    /// top's motion `top_motion` ([`Apex`] rows) and its `profile` along the height, carrying
    /// `top`'s masses: their inertia added, their weight on the lean, the apex placed.
    #[allow(clippy::too_many_arguments)]
    pub fn on_top(
        modes: Vec<TowerMode>,
        mass: DMatrix<f64>,
        stiffness: DMatrix<f64>,
        damping: DMatrix<f64>,
        own_weight: DMatrix<f64>,
        sag: DMatrix<f64>,
        top_motion: &DMatrix<f64>,
        profile: Vec<(f64, MotionRows)>,
        top: &TowerTop,
    ) -> Tower {
        let top_mass = top.yaw_bearing_mass + top.nacelle_mass + top.hub_mass;
        let stiffness = stiffness - own_weight - GRAVITY * top_mass * &sag;
        let apex = at_offset(top_motion, [top.overhang, 0.0, top.shaft_height]);
        let mass = mass + Tower::top_inertia(top_motion, top);
        Tower {
            modes,
            mass,
            stiffness,
            damping,
            apex,
            sag,
            profile,
        }
    }

    /// The mass matrix of `top`'s rigid bodies over the coordinates whose tower-top motion
    /// `top_motion` gives ([`Apex`] rows).
    pub fn top_inertia(top_motion: &DMatrix<f64>, top: &TowerTop) -> DMatrix<f64> {
        let n = top_motion.ncols();
        let mut mass = DMatrix::zeros(n, n);
        for (m, offset) in [
            (top.yaw_bearing_mass, [0.0; 3]),
            (top.nacelle_mass, top.nacelle_cm),
            (
                top.hub_mass,
                [top.overhang + top.hub_cm, 0.0, top.shaft_height],
            ),
        ] {
            let v = at_offset(top_motion, offset).rows(0, 3).into_owned();
            mass += m * v.transpose() * v;
        }
        let turn = top_motion.rows(Apex::Roll as usize, 3);
        let inertia = Matrix3::from_fn(|i, j| top.nacelle_inertia[i][j]);
        mass += turn.transpose() * inertia * turn;
        mass
    }

    /// How many coordinates it has.
    pub fn coordinates(&self) -> usize {
        self.modes.len()
    }

    /// The kinetic energy in each [`Plane`] of its coordinates `q`, on its rows `mass` of the
    /// whole system's (the blades' coupling left out).
    pub fn plane_energies(&self, mass: &DMatrix<f64>, at: usize, q: &[Complex<f64>]) -> [f64; 3] {
        let mut e = [0.0; 3];
        for plane in [Plane::ForeAft, Plane::SideSide, Plane::Torsion] {
            let picked: Vec<usize> = (0..self.coordinates())
                .filter(|&i| self.modes[i].plane() == plane)
                .collect();
            let block = DMatrix::from_fn(picked.len(), picked.len(), |i, j| {
                mass[(at + picked[i], at + picked[j])]
            });
            let v: Vec<Complex<f64>> = picked.iter().map(|&i| q[at + i]).collect();
            e[plane as usize] = kinetic_energy(&block, &v);
        }
        e
    }
}

/// The gravity terms of a tower whose coordinates' slopes `slopes` gives at height z (m): a
/// 2 × n matrix, the lean downwind and sideways (rad) per unit of each coordinate. Its mass
/// density `density`: (z, kg/m) stations, linear between. Out: `sag = ∫ φ'ᵀ φ' dz` and the
/// softening of its own weight `∫ g N(z) φ'ᵀ φ' dz`, `N` the tower's mass above z, integrated
/// on every interval between the stations and `breaks` (where the slopes change form).
pub fn leaning(
    density: &[(f64, f64)],
    breaks: &[f64],
    n: usize,
    slopes: &dyn Fn(f64) -> DMatrix<f64>,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let mut points: Vec<f64> = density
        .iter()
        .map(|d| d.0)
        .chain(breaks.iter().copied())
        .collect();
    points.sort_by(f64::total_cmp);
    points.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    // The density on the interval [za, zb] (inside one station interval): at its two ends.
    let ends = |za: f64, zb: f64| {
        let mid = 0.5 * (za + zb);
        let i = density
            .windows(2)
            .position(|w| mid <= w[1].0)
            .unwrap_or(density.len() - 2);
        let (a, b) = (density[i], density[i + 1]);
        let at = |z: f64| a.1 + (z - a.0) / (b.0 - a.0) * (b.1 - a.1);
        (at(za), at(zb))
    };
    let mut above = vec![0.0; points.len()];
    for i in (0..points.len() - 1).rev() {
        let (ma, mb) = ends(points[i], points[i + 1]);
        above[i] = above[i + 1] + (points[i + 1] - points[i]) * 0.5 * (ma + mb);
    }
    let rule = gauss_rule(GAUSS_POINTS);
    let mut sag = DMatrix::zeros(n, n);
    let mut own = DMatrix::zeros(n, n);
    for (i, w) in points.windows(2).enumerate() {
        let (za, zb) = (w[0], w[1]);
        let dz = zb - za;
        let (ma, mb) = ends(za, zb);
        for (s, gw) in rule.0.iter().zip(&rule.1) {
            let t = 0.5 * (s + 1.0);
            let z = za + t * dz;
            let mu = ma + t * (mb - ma);
            let mass_above = above[i + 1] + (zb - z) * 0.5 * (mu + mb);
            let d = slopes(z);
            let leaning = 0.5 * gw * dz * d.transpose() * &d;
            own += GRAVITY * mass_above * &leaning;
            sag += leaning;
        }
    }
    (sag, own)
}

/// The motion of a point rigidly `offset` from the tower top: translation `u + θ × d`, the
/// same turn.
fn at_offset(top: &DMatrix<f64>, offset: [f64; 3]) -> DMatrix<f64> {
    let d = Vector3::from(offset);
    let mut m = top.clone();
    for j in 0..top.ncols() {
        let theta = Vector3::new(
            top[(Apex::Roll as usize, j)],
            top[(Apex::Tilt as usize, j)],
            top[(Apex::Yaw as usize, j)],
        );
        let u = theta.cross(&d);
        for axis in 0..3 {
            m[(axis, j)] += u[axis];
        }
    }
    m
}

fn value(c: &ModeShape, h: f64) -> f64 {
    c.iter()
        .enumerate()
        .map(|(i, c)| c * h.powi(i as i32 + 2))
        .sum()
}

/// d/dh.
fn slope(c: &ModeShape, h: f64) -> f64 {
    c.iter()
        .enumerate()
        .map(|(i, c)| c * (i + 2) as f64 * h.powi(i as i32 + 1))
        .sum()
}

/// d²/dh².
fn curvature(c: &ModeShape, h: f64) -> f64 {
    c.iter()
        .enumerate()
        .map(|(i, c)| c * ((i + 2) * (i + 1)) as f64 * h.powi(i as i32))
        .sum()
}

/// Every value finite, lengths and masses physical, the table from base to top.
fn check(inputs: &TowerInputs, top: &TowerTop) -> Result<()> {
    let bad = |what: &str, v: f64, rule: &str| {
        Error::numerical(format!("tower: {what} is {v}; it must be {rule}"))
    };
    if !(inputs.length.is_finite() && inputs.length > 0.0) {
        return Err(bad("length", inputs.length, "finite and positive"));
    }
    let s = &inputs.sections;
    if s.len() < 2 || s[0].height_fraction != 0.0 || s[s.len() - 1].height_fraction != 1.0 {
        return Err(Error::numerical(
            "tower: the sections must run from its base (height fraction 0) to its top (1)",
        ));
    }
    for x in s {
        for (what, v) in [
            ("a section's mass density", x.mass_density),
            ("a section's fore–aft stiffness", x.fore_aft_stiffness),
            ("a section's side–side stiffness", x.side_side_stiffness),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(what, v, "finite and positive"));
            }
        }
    }
    for (t, z) in inputs.tuners.iter().zip(&inputs.damping) {
        if !(t.is_finite() && *t > 0.0) {
            return Err(bad("a stiffness tuner", *t, "finite and positive"));
        }
        if !(z.is_finite() && *z >= 0.0) {
            return Err(bad("a damping ratio", *z, "finite and ≥ 0"));
        }
    }
    check_top(top)
}

/// Every mass and inertia on the tower top finite and not negative, every offset finite.
pub fn check_top(top: &TowerTop) -> Result<()> {
    let bad = |what: &str, v: f64, rule: &str| {
        Error::numerical(format!("tower: {what} is {v}; it must be {rule}"))
    };
    for (what, v) in [
        ("the yaw bearing's mass", top.yaw_bearing_mass),
        ("the nacelle's mass", top.nacelle_mass),
        ("the hub's mass", top.hub_mass),
    ] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(bad(what, v, "finite and ≥ 0"));
        }
    }
    let inertia = Matrix3::from_fn(|i, j| top.nacelle_inertia[i][j]);
    let scale = inertia.norm();
    let symmetric = (inertia - inertia.transpose()).norm() <= 1e-9 * scale;
    let finite = inertia.iter().all(|v| v.is_finite());
    if !(finite
        && symmetric
        && inertia
            .symmetric_eigenvalues()
            .iter()
            .all(|&v| v >= -1e-9 * scale))
    {
        return Err(Error::numerical(format!(
            "tower: the nacelle's inertia tensor {:?} must be finite, symmetric and not negative",
            top.nacelle_inertia
        )));
    }
    for v in top
        .nacelle_cm
        .iter()
        .chain(&[top.hub_cm, top.overhang, top.shaft_height])
    {
        if !v.is_finite() {
            return Err(bad("a tower-top offset", *v, "finite"));
        }
    }
    Ok(())
}

/// The flap and edge motion (rows over the tower's coordinates) of a blade's strip at
/// `radius` from the apex, the blade at `azimuth` (rad, zero up, turning about +x): the apex's
/// translation seen along the blade's flap (downwind) and edge (its direction of rotation)
/// axes, the tilt swinging it downwind by `radius cos ψ` and the yaw by `radius sin ψ`, the
/// roll turning it as the rotor turns.
pub fn strip_rows(apex: &DMatrix<f64>, azimuth: f64, radius: f64) -> [DVector<f64>; 2] {
    let (c, s) = (azimuth.cos(), azimuth.sin());
    let row = |a: Apex| apex.row(a as usize).transpose();
    [
        row(Apex::X) + row(Apex::Tilt) * (radius * c) + row(Apex::Yaw) * (radius * s),
        row(Apex::Y) * (-c) - row(Apex::Z) * s + row(Apex::Roll) * radius,
    ]
}
