//! A blade from its HAWC2 structural (st) file (docs/model.md §11.6).
//!
//! HAWC2's cross-section frame (`x_c2`, `y_c2`, `z_c2`) sits on the half-chord line (`c2_def`),
//! turned with the chord: `x_c2` along the chord toward the leading edge, `y_c2` normal to it
//! toward the suction side (downwind), `z_c2` along the blade, right-handed, so a positive angle
//! about `z_c2` turns the leading edge downwind (toward stall). Our frame (§11.1) has ξ = `y_c2`,
//! η = `x_c2`: a reflection, under which a twist reverses its sense. The structural `pitch` turns
//! the principal bending axes (`x_e`, `y_e`) from `x_c2` about `z_c2`; `I_x` is about `x_e`, so
//! `E I_x` is the flap stiffness and `E I_y` the edge stiffness; `ri_x`, `ri_y` are the radii of
//! gyration about the elastic centre for rotations about `x_e` and `y_e`; `G I_p` is the torsional
//! stiffness about the shear centre. A fully populated row gives instead the 6×6 stiffness at the
//! elastic centre along the principal axes (forces and moments along `x_e`, `y_e`, `z_c2`),
//! reduced to the Euler–Bernoulli section by [`classical::reduce`](super::classical::reduce),
//! which also finds the shear centre from its couplings.
//!
//! The st file has no twist: the chord's twist lives in the htc file's `c2_def` ([`C2Line`],
//! [`ChordTwist::from_c2_def`]), or comes from another source (the AeroDyn 15 blade file of the
//! same blade, [`ChordTwist::from_aerodyn`]), and the
//! section frames are the chord frames; the structural pitch enters through the stiffness's
//! cross terms. The reference axis is the half-chord line along the pitch axis, curved by the
//! prebend of the rotor's description (§11.9); its in-plane offsets from the pitch bearing's
//! axis, in `c2_def`, are neglected.

use super::classical::{reduce, ClassicalSection, FileFrame};
use super::{BeamSection, BladeTable, SectionMatrices};
use crate::error::{Error, Result};
use crate::formats::aerodyn::AeroDynBlade;
use crate::formats::hawc2_st::{ClassicRow, FpmRow, StFile, StRows};
use crate::formats::htc::C2Section;
use nalgebra::Matrix3;

/// The twist of the chord along the span (toward feather, as docs/model.md §11.1), linear
/// between its points and constant beyond the ends.
#[derive(Debug, Clone, PartialEq)]
pub struct ChordTwist {
    /// `(span from the root (m), twist (rad))`, span increasing.
    points: Vec<(f64, f64)>,
}

impl ChordTwist {
    /// The chord in the rotor plane everywhere: for a blade described without its twist.
    pub fn untwisted() -> ChordTwist {
        ChordTwist {
            points: vec![(0.0, 0.0)],
        }
    }

    /// docs/model.md §11.6: the aerodynamic twist `BlTwist` of an AeroDyn 15 blade file (degrees,
    /// positive toward feather) at its nodes `BlSpn` (span along the pitch axis from the root;
    /// the reader checked that it increases).
    pub fn from_aerodyn(blade: &AeroDynBlade) -> ChordTwist {
        ChordTwist {
            points: blade
                .nodes
                .iter()
                .map(|n| (n.bl_spn, n.bl_twist_deg.to_radians()))
                .collect(),
        }
    }

    /// docs/model.md §11.6: the twist of an htc `c2_def` (degrees about `z_c2`, HAWC2's sense:
    /// negative toward feather, so ours is its negative) at each section's curved length along
    /// the half-chord line, where the st and ae files' `r` count from.
    pub fn from_c2_def(line: &C2Line) -> ChordTwist {
        ChordTwist {
            points: line
                .points
                .iter()
                .map(|(s, sec)| (*s, -sec.twist_deg.to_radians()))
                .collect(),
        }
    }

    /// The twist at span `z` (rad).
    pub fn at(&self, z: f64) -> f64 {
        let p = &self.points;
        let k = p.partition_point(|x| x.0 <= z);
        if k == 0 {
            return p[0].1;
        }
        if k == p.len() {
            return p[p.len() - 1].1;
        }
        let ((za, ta), (zb, tb)) = (p[k - 1], p[k]);
        ta + (tb - ta) * (z - za) / (zb - za)
    }
}

/// The half-chord line of an htc `c2_def`: each section with its curved length from the first
/// (m), as HAWC2 measures a main body's `r`.
#[derive(Debug, Clone, PartialEq)]
pub struct C2Line {
    /// `(curved length, section)`, the length strictly increasing.
    pub points: Vec<(f64, C2Section)>,
}

impl C2Line {
    /// The sections of `c2_def` (written in the file `origin`) joined by straight segments;
    /// two sections at one point are an error naming the second's line (the length along the
    /// line would stand still there, and nothing can be interpolated on it).
    pub fn new(c2_def: &[C2Section], origin: &str) -> Result<C2Line> {
        let mut s = 0.0;
        let mut points = Vec::with_capacity(c2_def.len());
        for (k, sec) in c2_def.iter().enumerate() {
            if let Some(prev) = k.checked_sub(1).map(|j| &c2_def[j]) {
                let step = ((sec.x - prev.x).powi(2)
                    + (sec.y - prev.y).powi(2)
                    + (sec.z - prev.z).powi(2))
                .sqrt();
                if step.is_nan() || step <= 0.0 {
                    return Err(Error::format(
                        origin,
                        sec.line,
                        format!(
                            "c2_def: section {} is where section {k} is; the half-chord line \
                             must advance from section to section",
                            k + 1
                        ),
                    ));
                }
                s += step;
            }
            points.push((s, *sec));
        }
        Ok(C2Line { points })
    }

    /// The out-of-plane offset `y` of the line (m, downwind positive: HAWC2's blade `y` points
    /// downwind, the IEA 15MW tip sits at `y = −4.0`) at each section's curved length: the
    /// blade's prebend.
    pub fn prebend(&self) -> Vec<(f64, f64)> {
        self.points.iter().map(|(s, sec)| (*s, sec.y)).collect()
    }
}

/// docs/model.md §11.6: the blade of subset `$subset` of set `#set` of `st`, its section frames
/// turned by `twist`, its root at `hub_radius` (m). An unphysical row is an error naming the
/// file, its line and the column.
pub fn from_hawc2_st(
    st: &StFile,
    set: usize,
    subset: usize,
    twist: &ChordTwist,
    hub_radius: f64,
) -> Result<BladeTable> {
    let rows = &st.subset(set, subset)?.rows;
    let origin = format!("{} (set #{set}, subset ${subset})", st.path);
    let place = Place {
        path: &st.path,
        set,
        subset,
    };
    let (sections, matrices) = match rows {
        StRows::Classic(rows) => (
            rows.iter()
                .map(|r| classic_section(r, twist, &place))
                .collect::<Result<Vec<_>>>()?,
            Vec::new(),
        ),
        StRows::FullyPopulated(rows) => (
            rows.iter()
                .map(|r| fpm_section(r, twist, &place))
                .collect::<Result<Vec<_>>>()?,
            rows.iter().map(fpm_matrices).collect(),
        ),
    };
    BladeTable::new(&origin, hub_radius, sections)?.with_matrices(matrices)
}

/// Where a row came from, for its errors.
struct Place<'a> {
    path: &'a str,
    set: usize,
    subset: usize,
}

impl Place<'_> {
    fn error(&self, line: usize, message: String) -> Error {
        Error::format(
            self.path,
            line,
            format!("set #{} subset ${}: {message}", self.set, self.subset),
        )
    }

    /// `Err` naming the first of `values` that is not finite and positive.
    fn positive(&self, line: usize, values: &[(&str, &str, f64)]) -> Result<()> {
        match values.iter().find(|(_, _, v)| !(v.is_finite() && *v > 0.0)) {
            Some((column, meaning, v)) => Err(self.error(
                line,
                format!("expected a positive {column} ({meaning}), found {v}"),
            )),
            None => Ok(()),
        }
    }
}

/// `x_c2 → η`, `y_c2 → ξ`: HAWC2's chord frame in ours (docs/model.md §11.6).
fn chord_frame() -> FileFrame {
    FileFrame::new([[0.0, 1.0], [1.0, 0.0]]).expect("a reflection is orthogonal")
}

/// The common mass columns of a row, checked.
struct MassColumns {
    line: usize,
    m: f64,
    cg: [f64; 2],
    ri: [f64; 2],
    elastic: [f64; 2],
    pitch_deg: f64,
}

/// docs/model.md §11.6: mass per length, centre of mass and second moments about the reference
/// axis in our frame. `ri_x`, `ri_y` are about the elastic centre along the principal axes (no
/// product of inertia there, as HAWC2 assumes), moved to the reference axis by the parallel-axis
/// rule with the centre of mass.
fn mass_section(c: &MassColumns, place: &Place) -> Result<([f64; 2], [f64; 3])> {
    place.positive(c.line, &[("m", "mass per length", c.m)])?;
    if let Some((name, v)) = [("ri_x", c.ri[0]), ("ri_y", c.ri[1])]
        .into_iter()
        .find(|(_, v)| !(v.is_finite() && *v >= 0.0))
    {
        return Err(place.error(
            c.line,
            format!("expected a radius of gyration {name} ≥ 0 m, found {v}"),
        ));
    }
    let frame = chord_frame();
    let principal = frame.turned(c.pitch_deg.to_radians());
    let [rx, ry] = c.ri;
    // About x_e the mass spreads along y_e, and the other way round.
    let [j_xi, j_eta, j_cross] =
        principal.second_moments([[c.m * ry * ry, 0.0], [0.0, c.m * rx * rx]]);
    let cg = frame.position(c.cg);
    let e = frame.position(c.elastic);
    let m = c.m;
    let inertia = [
        j_xi + m * (2.0 * e[0] * cg[0] - e[0] * e[0]),
        j_eta + m * (2.0 * e[1] * cg[1] - e[1] * e[1]),
        j_cross + m * (e[0] * cg[1] + cg[0] * e[1] - e[0] * e[1]),
    ];
    Ok((cg, inertia))
}

/// docs/model.md §11.6: a classic (isotropic) row: `E I_x`, `E I_y` along the principal axes at
/// the elastic centre, `G I_p` about the shear centre, the shear stiffnesses `k_x G A`, `k_y G A`
/// along the principal axes at the shear centre, no bend–twist coupling.
fn classic_section(r: &ClassicRow, twist: &ChordTwist, place: &Place) -> Result<BeamSection> {
    place.positive(
        r.line,
        &[
            ("E", "Young's modulus", r.e),
            ("G", "shear modulus", r.g),
            ("I_x", "area moment about the principal x_e axis", r.i_x),
            ("I_y", "area moment about the principal y_e axis", r.i_y),
            ("I_p", "torsional stiffness constant", r.i_p),
            ("k_x", "shear factor along the principal x_e axis", r.k_x),
            ("k_y", "shear factor along the principal y_e axis", r.k_y),
            ("A", "cross-sectional area", r.a),
        ],
    )?;
    let (cg, inertia) = mass_section(
        &MassColumns {
            line: r.line,
            m: r.m,
            cg: [r.x_cg, r.y_cg],
            ri: [r.ri_x, r.ri_y],
            elastic: [r.x_e, r.y_e],
            pitch_deg: r.pitch_deg,
        },
        place,
    )?;
    let frame = chord_frame();
    let principal = frame.turned(r.pitch_deg.to_radians());
    let c = Matrix3::from_diagonal(&nalgebra::Vector3::new(
        r.e * r.i_x,
        r.e * r.i_y,
        r.g * r.i_p,
    ));
    let [ei_flap, ei_edge, ei_cross, gj, flap_twist, edge_twist] = principal.bending_torsion(&c);
    let section = ClassicalSection {
        ei_flap,
        ei_edge,
        ei_cross,
        gj,
        flap_twist,
        edge_twist,
        shear_centre: frame.position([r.x_sh, r.y_sh]),
        tension_centre: frame.position([r.x_e, r.y_e]),
        shear: principal.shear_stiffness([r.k_x * r.g * r.a, r.k_y * r.g * r.a]),
    };
    Ok(section.at_station(r.r, twist.at(r.r), r.m, cg, inertia))
}

/// A fully populated row's 6×6 stiffness as the file gives it: at the elastic centre, along the
/// principal axes (docs/model.md §11.6). Its mass is in the row's mass columns.
fn fpm_matrices(r: &FpmRow) -> SectionMatrices {
    let frame = chord_frame();
    SectionMatrices {
        stiffness: r.stiffness(),
        mass: None,
        frame: frame.turned(r.pitch_deg.to_radians()),
        origin: frame.position([r.x_e, r.y_e]),
    }
}

/// docs/model.md §11.6: a fully populated row: the 6×6 at the elastic centre along the
/// principal axes, reduced; its centres found from the elastic centre.
fn fpm_section(r: &FpmRow, twist: &ChordTwist, place: &Place) -> Result<BeamSection> {
    let (cg, inertia) = mass_section(
        &MassColumns {
            line: r.line,
            m: r.m,
            cg: [r.x_cg, r.y_cg],
            ri: [r.ri_x, r.ri_y],
            elastic: [r.x_e, r.y_e],
            pitch_deg: r.pitch_deg,
        },
        place,
    )?;
    let frame = chord_frame();
    let principal = frame.turned(r.pitch_deg.to_radians());
    let mut section = reduce(&r.stiffness(), &principal)
        .map_err(|m| place.error(r.line, format!("{m}; expected a positive definite K11…K66")))?;
    let e = frame.position([r.x_e, r.y_e]);
    let shift = |p: [f64; 2]| [p[0] + e[0], p[1] + e[1]];
    section.shear_centre = shift(section.shear_centre);
    section.tension_centre = shift(section.tension_centre);
    Ok(section.at_station(r.r, twist.at(r.r), r.m, cg, inertia))
}
