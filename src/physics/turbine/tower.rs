//! The tower and what sits on it (docs/model.md §13.6): ElastoDyn's assumed-mode tower, two
//! fore–aft and two side–side bending modes on the polynomial shapes its file gives, carrying
//! the yaw bearing, the nacelle and the hub as point masses. Plain inputs; out: the mass,
//! stiffness and damping over its four coordinates and how they move the rotor apex, where the
//! rotor ([`super::rotor::Rotor`]) hangs its blades.
//!
//! Frame: x downwind along the (untilted) shaft, z up the tower, y = z × x (lateral). The
//! tower top moves by `u_x = Σ φ_FA q`, `u_y = Σ φ_SS q` and turns by `θ_y = Σ φ'_FA(L) q`
//! (its vertical tipping downwind), `θ_x = −Σ φ'_SS(L) q`. The tower has no torsion: an
//! ElastoDyn tower file gives no torsional stiffness, and none is assumed.

use crate::error::{Error, Result};
use crate::physics::basis::gauss_rule;
use crate::physics::structure::Family;
use nalgebra::{DMatrix, DVector, Vector3};

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
    /// kg, at `hub_cm` downwind of the apex along the shaft.
    pub hub_mass: f64,
    pub hub_cm: f64,
    /// The rotor apex: `overhang` downwind of the yaw axis (negative upwind) and
    /// `shaft_height` above the tower top.
    pub overhang: f64,
    pub shaft_height: f64,
}

/// How many coordinates the tower has.
pub const TOWER_COORDINATES: usize = 4;

/// The tower's coordinates, in order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TowerMode {
    ForeAft1 = 0,
    ForeAft2 = 1,
    SideSide1 = 2,
    SideSide2 = 3,
}

impl TowerMode {
    pub const ALL: [TowerMode; TOWER_COORDINATES] = [
        TowerMode::ForeAft1,
        TowerMode::ForeAft2,
        TowerMode::SideSide1,
        TowerMode::SideSide2,
    ];

    pub fn fore_aft(self) -> bool {
        matches!(self, TowerMode::ForeAft1 | TowerMode::ForeAft2)
    }

    /// The `number`-th (from 1) fore–aft or side–side mode; beyond the second, the second.
    pub fn named(fore_aft: bool, number: usize) -> TowerMode {
        match (fore_aft, number) {
            (true, 1) => TowerMode::ForeAft1,
            (true, _) => TowerMode::ForeAft2,
            (false, 1) => TowerMode::SideSide1,
            (false, _) => TowerMode::SideSide2,
        }
    }

    /// The motion family a tower mode reads as on a blade (fore–aft moves the blades in flap,
    /// side–side in edge) and its number.
    pub fn family_and_number(self) -> (Family, usize) {
        match self {
            TowerMode::ForeAft1 => (Family::Flap, 1),
            TowerMode::ForeAft2 => (Family::Flap, 2),
            TowerMode::SideSide1 => (Family::Edge, 1),
            TowerMode::SideSide2 => (Family::Edge, 2),
        }
    }

    /// `tower FA 1`, … as every output names the mode it dominates.
    pub fn label(self) -> &'static str {
        match self {
            TowerMode::ForeAft1 => "tower FA 1",
            TowerMode::ForeAft2 => "tower FA 2",
            TowerMode::SideSide1 => "tower SS 1",
            TowerMode::SideSide2 => "tower SS 2",
        }
    }
}

/// The rotor apex's motion, the rows of [`Tower::apex`]: translation and the turn of the
/// shaft about x (roll, which adds to the rotor's azimuth) and about y (tilt).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Apex {
    X = 0,
    Y = 1,
    Z = 2,
    Roll = 3,
    Tilt = 4,
}

/// How many [`Apex`] motions there are.
pub const APEX_MOTIONS: usize = 5;

/// The tower with its top masses.
#[derive(Debug, Clone, PartialEq)]
pub struct Tower {
    /// Over the four coordinates: the tower's own with the yaw bearing, the nacelle and the
    /// hub as point masses (the blades are the rotor's).
    pub mass: DMatrix<f64>,
    pub stiffness: DMatrix<f64>,
    /// ElastoDyn's modal damping: each mode's ratio on its tower-alone frequency (top masses
    /// left out), `C = 2 ζ K / ω` column by column.
    pub damping: DMatrix<f64>,
    /// The apex's motion per coordinate (5 × 4, rows in [`Apex`] order).
    pub apex: DMatrix<f64>,
    /// `∫ φ'ᵢ φ'ⱼ dz`: the stiffness a newton of weight on the tower top takes away (its
    /// moment as the tower leans, ElastoDyn's gravity term); the rotor adds its blades'.
    pub sag: DMatrix<f64>,
}

/// Standard gravity (m/s²), as OpenFAST's input files give it: ElastoDyn's tower softens
/// under the weight above each section.
pub const GRAVITY: f64 = 9.80665;

/// Gauss points per interval of the section table: exact for the mass integrand (linear
/// density times two sixth-degree shapes).
const GAUSS_POINTS: usize = 7;

impl Tower {
    pub fn new(inputs: &TowerInputs, top: &TowerTop) -> Result<Tower> {
        check(inputs, top)?;
        let l = inputs.length;
        let n = TOWER_COORDINATES;
        let mut own_mass = DMatrix::<f64>::zeros(n, n);
        let mut stiffness = DMatrix::<f64>::zeros(n, n);
        let mut sag = DMatrix::<f64>::zeros(n, n);
        let mut own_weight = DMatrix::<f64>::zeros(n, n);
        let rule = gauss_rule(GAUSS_POINTS);
        // The tower's own mass above each station (kg).
        let mut above = vec![0.0; inputs.sections.len()];
        for i in (0..inputs.sections.len() - 1).rev() {
            let (a, b) = (inputs.sections[i], inputs.sections[i + 1]);
            let dh = b.height_fraction - a.height_fraction;
            above[i] = above[i + 1] + l * dh * 0.5 * (a.mass_density + b.mass_density);
        }
        for (pair, &above_b) in inputs.sections.windows(2).zip(&above[1..]) {
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
                let slopes = inputs.shapes.map(|c| slope(&c, h));
                let mass_above =
                    above_b + l * (b.height_fraction - h) * 0.5 * (mu + b.mass_density);
                for i in 0..n {
                    for j in 0..n {
                        let same_plane =
                            TowerMode::ALL[i].fore_aft() == TowerMode::ALL[j].fore_aft();
                        if !same_plane {
                            continue;
                        }
                        own_mass[(i, j)] += weight * l * mu * phi[i] * phi[j];
                        let leaning = weight * slopes[i] * slopes[j] / l;
                        sag[(i, j)] += leaning;
                        own_weight[(i, j)] += GRAVITY * mass_above * leaning;
                        let e = ei[usize::from(!TowerMode::ALL[i].fore_aft())];
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
        let top_mass = top.yaw_bearing_mass + top.nacelle_mass + top.hub_mass;
        let stiffness = stiffness - own_weight - GRAVITY * top_mass * &sag;
        let top_motion = top_motion(inputs);
        let apex = at_offset(&top_motion, [top.overhang, 0.0, top.shaft_height]);
        let mut mass = own_mass;
        for (m, offset) in [
            (top.yaw_bearing_mass, [0.0; 3]),
            (top.nacelle_mass, top.nacelle_cm),
            (
                top.hub_mass,
                [top.overhang + top.hub_cm, 0.0, top.shaft_height],
            ),
        ] {
            let v = at_offset(&top_motion, offset).rows(0, 3).into_owned();
            mass += m * v.transpose() * v;
        }
        Ok(Tower {
            mass,
            stiffness,
            damping,
            apex,
            sag,
        })
    }
}

/// The tower top's translation and turn per coordinate, in [`Apex`] rows (z zero: the tower
/// does not stretch).
fn top_motion(inputs: &TowerInputs) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(APEX_MOTIONS, TOWER_COORDINATES);
    for (j, mode) in TowerMode::ALL.iter().enumerate() {
        let c = &inputs.shapes[j];
        let slope = slope(c, 1.0) / inputs.length;
        if mode.fore_aft() {
            m[(Apex::X as usize, j)] = value(c, 1.0);
            m[(Apex::Tilt as usize, j)] = slope;
        } else {
            m[(Apex::Y as usize, j)] = value(c, 1.0);
            m[(Apex::Roll as usize, j)] = -slope;
        }
    }
    m
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
            0.0,
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
    for (what, v) in [
        ("the yaw bearing's mass", top.yaw_bearing_mass),
        ("the nacelle's mass", top.nacelle_mass),
        ("the hub's mass", top.hub_mass),
    ] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(bad(what, v, "finite and ≥ 0"));
        }
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
/// axes, the tilt swinging it downwind by `radius cos ψ`, the roll turning it as the rotor
/// turns.
pub fn strip_rows(apex: &DMatrix<f64>, azimuth: f64, radius: f64) -> [DVector<f64>; 2] {
    let (c, s) = (azimuth.cos(), azimuth.sin());
    let row = |a: Apex| apex.row(a as usize).transpose();
    [
        row(Apex::X) + row(Apex::Tilt) * (radius * c),
        row(Apex::Y) * (-c) - row(Apex::Z) * s + row(Apex::Roll) * radius,
    ]
}
