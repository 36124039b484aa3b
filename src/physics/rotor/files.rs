//! The rotor's aerodynamic description from the turbine's own files (docs/model.md §12.1):
//! an AeroDyn 15 blade file with its AirfoilInfo polars and an ElastoDyn blade file's
//! `PitchAxis`, or a HAWC2 ae set with its pc file (and the chord twist HAWC2 keeps in the htc).
//!
//! Where the aerodynamic centre sits (`ac_ahead`: from the structure's reference axis forward
//! along the chord to the aerodynamic centre, docs/model.md §12.1):
//! - AeroDyn + ElastoDyn: the structure's reference axis is the pitch axis (BeamDyn's key-point
//!   line, §11.5), which ElastoDyn's `PitchAxis` places at that fraction of the chord from the
//!   leading edge; the aerodynamic centre is at the quarter chord, where AirfoilInfo's `Cm` is
//!   taken. So `ac_ahead = (PitchAxis − ¼) c`.
//! - HAWC2: the reference axis is the half-chord line `c2_def` (§11.6) and HAWC2 applies the
//!   aerodynamic forces at the quarter chord: `ac_ahead = ¼ c`.
//! - WindIO: the reference axis is the pitch axis, at `pitch_axis` of the chord from the leading
//!   edge, and each airfoil states its aerodynamic centre (the quarter chord where it does not):
//!   `ac_ahead = (pitch_axis − ac) c`.

use super::{AeroBlade, AeroNode};
use crate::error::{Error, Result};
use crate::formats::aerodyn::{self, AeroDynBlade};
use crate::formats::airfoil::{self, AirfoilFile, PolarColumns};
use crate::formats::elastodyn::{self, ElastoDynBlade};
use crate::formats::hawc2_aero::{self, AeFile, PcFile, PcProfile, PcSet};
use crate::formats::text_file::TextFile;
use crate::formats::windio::{self, WindIo};
use crate::physics::aero::polar::{Polar, UnsteadyBlock, UnsteadyConstants};
use crate::physics::blade::hawc2::ChordTwist;
use crate::physics::blade::source::{c2_line, HtcFiles};
use std::sync::Arc;

/// The aerodynamic blade an AeroDyn 15 blade file describes, its airfoil ids (`BlAFID`, 1-based)
/// naming `airfoils` in order, the aerodynamic centre placed by the ElastoDyn blade file
/// `pitch_axis` (its `BlFract` scaled to the AeroDyn blade's span).
pub fn read_aerodyn<F: TextFile>(blade: &F, airfoils: &[F], pitch_axis: &F) -> Result<AeroBlade> {
    let blade_name = blade.display();
    let nodes = aerodyn::parse_blade(&blade.read()?, &blade_name)?;
    let polars = airfoils
        .iter()
        .map(|f| {
            let name = f.display();
            let file = airfoil::parse_airfoil(&f.read()?, &name, PolarColumns::default())?;
            Ok(Arc::new(airfoil_polar(&file, &name)?))
        })
        .collect::<Result<Vec<_>>>()?;
    let axis_name = pitch_axis.display();
    let axis = elastodyn::parse_blade(&pitch_axis.read()?, &axis_name)?;
    from_aerodyn(&nodes, &blade_name, &polars, &axis, &axis_name)
}

/// The prebend of a blade from an AeroDyn 15 blade file (docs/model.md §12.2): its `BlCrvAC`
/// column, the out-of-plane offset of the blade's axis, downwind positive, at `BlSpn`. The
/// reader checks the table (spans strictly increasing) and names the file and line.
pub fn read_prebend(file: &impl TextFile) -> Result<Vec<(f64, f64)>> {
    let nodes = aerodyn::parse_blade(&file.read()?, &file.display())?.nodes;
    Ok(nodes.iter().map(|n| (n.bl_spn, n.bl_crv_ac)).collect())
}

/// The polar of an AirfoilInfo file: its first table (AeroDyn's default `AFTabMod = 1` uses
/// the first table whatever the Reynolds number), in radians. A table without `Cm` is refused:
/// the pitching moment is part of the aerodynamic description.
pub fn airfoil_polar(file: &AirfoilFile, origin: &str) -> Result<Polar> {
    let table = file.tables.first().ok_or_else(|| {
        Error::format(
            origin,
            0,
            "the airfoil file has no polar table (NumTabs = 0)",
        )
    })?;
    let cm = table.cm.clone().ok_or_else(|| {
        Error::format(
            origin,
            0,
            "the polar table has no Cm column (InCol_Cm = 0); the pitching moment about the \
             quarter chord is needed",
        )
    })?;
    let alpha = table.alpha_deg.iter().map(|a| a.to_radians()).collect();
    let polar = Polar::new(
        alpha,
        table.cl.clone(),
        table.cd.clone(),
        cm,
        &format!("{origin}, table 1"),
    )
    .map_err(|e| Error::format(origin, 0, e.to_string()))?;
    Ok(match &table.ua {
        Some(ua) => polar.with_unsteady(UnsteadyBlock {
            constants: unsteady_constants(ua),
            origin: format!("{origin}, table 1"),
        }),
        None => polar,
    })
}

/// AeroDyn's defaults for the constants an AirfoilInfo UA block leaves at `Default` (its
/// AirfoilInfo documentation): `A1 = 0.3`, `A2 = 0.7`, `b1 = 0.14`, `b2 = 0.53`, `T_f0 = 3`,
/// `T_p = 1.7`.
pub const AERODYN_UA_DEFAULTS: UnsteadyConstants = UnsteadyConstants {
    a1: 0.3,
    a2: 0.7,
    b1: 0.14,
    b2: 0.53,
    tau_p: 1.7,
    tau_f: 3.0,
};

/// The Hansen–Gaunaa–Madsen constants of a UA block, AeroDyn's defaults where it says `Default`.
pub fn unsteady_constants(ua: &airfoil::UaBlock) -> UnsteadyConstants {
    let d = AERODYN_UA_DEFAULTS;
    UnsteadyConstants {
        a1: ua.a1.unwrap_or(d.a1),
        a2: ua.a2.unwrap_or(d.a2),
        b1: ua.b1.unwrap_or(d.b1),
        b2: ua.b2.unwrap_or(d.b2),
        tau_p: ua.t_p.unwrap_or(d.tau_p),
        tau_f: ua.t_f0.unwrap_or(d.tau_f),
    }
}

/// [`read_aerodyn`] on parsed files; `blade_origin` and `axis_origin` name them in errors.
pub fn from_aerodyn(
    blade: &AeroDynBlade,
    blade_origin: &str,
    polars: &[Arc<Polar>],
    axis: &ElastoDynBlade,
    axis_origin: &str,
) -> Result<AeroBlade> {
    let span = blade.nodes.last().map_or(0.0, |n| n.bl_spn);
    check_fractions(axis, axis_origin)?;
    let nodes = blade
        .nodes
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let at =
                |what: String| Error::format(blade_origin, 0, format!("node {}: {what}", i + 1));
            let polar = polars.get(n.bl_af_id - 1).ok_or_else(|| {
                at(format!(
                    "BlAFID = {} names airfoil {} but aero.airfoils lists {} file(s)",
                    n.bl_af_id,
                    n.bl_af_id,
                    polars.len()
                ))
            })?;
            if n.bl_chord <= 0.0 {
                return Err(at(format!(
                    "BlChord = {} m; a chord must be positive",
                    n.bl_chord
                )));
            }
            let pitch_axis = pitch_axis_at(axis, n.bl_spn / span);
            Ok(AeroNode {
                span: n.bl_spn,
                chord: n.bl_chord,
                twist: n.bl_twist_deg.to_radians(),
                ac_ahead: (pitch_axis - 0.25) * n.bl_chord,
                polar: Arc::clone(polar),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    if nodes[0].span < 0.0 {
        return Err(Error::format(
            blade_origin,
            0,
            format!(
                "BlSpn starts at {} m; spans are measured from the root, ≥ 0",
                nodes[0].span
            ),
        ));
    }
    Ok(AeroBlade {
        prebend: Vec::new(),
        nodes,
        origin: blade_origin.to_string(),
    })
}

/// The ElastoDyn table must reach from the root (`BlFract` 0) to the tip (1), so that every
/// AeroDyn node has a pitch-axis position read, not extrapolated, and `PitchAxis` must lie on
/// the chord.
fn check_fractions(axis: &ElastoDynBlade, origin: &str) -> Result<()> {
    let first = axis.stations.first().map_or(f64::NAN, |s| s.bl_fract);
    let last = axis.stations.last().map_or(f64::NAN, |s| s.bl_fract);
    if first.abs() > 1e-6 || (last - 1.0).abs() > 1e-6 {
        return Err(Error::format(
            origin,
            0,
            format!(
                "BlFract runs from {first} to {last}; the PitchAxis table must span the blade \
                 from 0 to 1"
            ),
        ));
    }
    if let Some((i, s)) = axis
        .stations
        .iter()
        .enumerate()
        .find(|(_, s)| !(0.0..=1.0).contains(&s.pitch_axis))
    {
        return Err(Error::format(
            origin,
            0,
            format!(
                "station {} (BlFract {}): PitchAxis = {} is off the chord; allowed [0, 1] (a \
                 fraction of the chord from the leading edge)",
                i + 1,
                s.bl_fract,
                s.pitch_axis
            ),
        ));
    }
    Ok(())
}

/// `PitchAxis` at blade fraction `f`, linear between stations.
fn pitch_axis_at(axis: &ElastoDynBlade, f: f64) -> f64 {
    let s = &axis.stations;
    let k = s
        .partition_point(|x| x.bl_fract <= f)
        .clamp(1, s.len().max(2) - 1);
    if s.len() == 1 {
        return s[0].pitch_axis;
    }
    let (a, b) = (&s[k - 1], &s[k]);
    let t = ((f - a.bl_fract) / (b.bl_fract - a.bl_fract)).clamp(0.0, 1.0);
    a.pitch_axis + t * (b.pitch_axis - a.pitch_axis)
}

/// The aerodynamic blade of set `ae_set` (1-based) of a HAWC2 ae file with its pc file, twisted
/// as the AeroDyn 15 blade file `twist` says (HAWC2 keeps the twist in the htc's `c2_def`, which
/// the same twist turns for the structure, docs/model.md §11.6).
pub fn read_hawc2<F: TextFile>(ae: &F, ae_set: usize, pc: &F, twist: &F) -> Result<AeroBlade> {
    let twist_name = twist.display();
    let twist = ChordTwist::from_aerodyn(&aerodyn::parse_blade(&twist.read()?, &twist_name)?);
    read_hawc2_twisted(ae, ae_set, pc, &twist)
}

/// The ae and pc files a preset names in place of an htc's (each `None`: the htc's own), the ae
/// file with its set.
pub struct AePc<F> {
    pub ae: Option<(F, usize)>,
    pub pc: Option<F>,
}

/// The aerodynamic blade of a HAWC2 model's blade (docs/model.md §12.1–§12.2): the ae set and
/// pc file its htc's `aero` block names for it (either replaced by `given`'s), twisted and
/// prebent as its `c2_def` says. `None` when the model has no `aero` block and nothing is given.
pub fn read_htc_aero<F: TextFile>(htc: &HtcFiles<F>, given: AePc<F>) -> Result<Option<AeroBlade>> {
    let model = htc.model()?;
    let line = c2_line(&model)?;
    let twist = ChordTwist::from_c2_def(&line);
    let blade = match (given, &model.aero) {
        (
            AePc {
                ae: Some((ae, set)),
                pc: Some(pc),
            },
            _,
        ) => read_hawc2_twisted(&ae, set, &pc, &twist)?,
        (AePc { ae: None, pc: None }, None) => return Ok(None),
        (_, None) => {
            return Err(Error::Invalid {
                origin: htc.htc.display(),
                message: "the model has no aero block to take the other of its ae and pc files \
                          from: give both aero.ae_file and aero.pc_file"
                    .to_string(),
            })
        }
        (AePc { ae: None, pc: None }, Some(a)) => {
            let (ae, pc) = (htc.named(&a.ae_filename), htc.named(&a.pc_filename));
            read_hawc2_twisted(&ae, a.ae_set, &pc, &twist).map_err(|e| {
                Error::format(
                    &a.ae_filename.file,
                    a.ae_filename.line,
                    format!(
                        "in aero: ae_filename {} (ae set {} of blade {}), pc_filename {}: {e}",
                        a.ae_filename.value, a.ae_set, a.blade, a.pc_filename.value
                    ),
                )
            })?
        }
        // One file the preset's, the other the aero block's: errors name the preset's keys.
        (given, Some(a)) => {
            let (ae, ae_set) = given
                .ae
                .unwrap_or_else(|| (htc.named(&a.ae_filename), a.ae_set));
            let pc = given.pc.unwrap_or_else(|| htc.named(&a.pc_filename));
            read_hawc2_twisted(&ae, ae_set, &pc, &twist)?
        }
    };
    Ok(Some(AeroBlade {
        prebend: line.prebend(),
        ..blade
    }))
}

/// [`from_hawc2`] on set `ae_set` of the ae file `ae` and the pc file `pc`.
fn read_hawc2_twisted<F: TextFile>(
    ae: &F,
    ae_set: usize,
    pc: &F,
    twist: &ChordTwist,
) -> Result<AeroBlade> {
    let ae_name = ae.display();
    let ae_file = hawc2_aero::parse_ae(&ae.read()?, &ae_name)?;
    let pc_name = pc.display();
    let pc_file = hawc2_aero::parse_pc(&pc.read()?, &pc_name)?;
    from_hawc2(&ae_file, &ae_name, ae_set, &pc_file, &pc_name, twist)
}

/// [`read_hawc2`] on parsed files; the origins name them in errors.
pub fn from_hawc2(
    ae: &AeFile,
    ae_origin: &str,
    ae_set: usize,
    pc: &PcFile,
    pc_origin: &str,
    twist: &ChordTwist,
) -> Result<AeroBlade> {
    let set = ae.sets.get(ae_set.wrapping_sub(1)).ok_or_else(|| {
        Error::format(
            ae_origin,
            0,
            format!(
                "aero.ae_set = {ae_set}: the file has {} ae set(s)",
                ae.sets.len()
            ),
        )
    })?;
    // Rows of the same pc set and thickness share one polar (the outboard IEA 15MW rows all
    // have 21.1 %), so the section lookup blends nothing between them.
    let mut made: Vec<(usize, f64, Arc<Polar>)> = Vec::new();
    let mut nodes = Vec::with_capacity(set.rows.len());
    for (i, row) in set.rows.iter().enumerate() {
        let at = |what: String| {
            Error::format(
                ae_origin,
                0,
                format!("ae set {ae_set}, row {} (r = {} m): {what}", i + 1, row.r),
            )
        };
        if row.chord <= 0.0 {
            return Err(at(format!(
                "chord {} m; a chord must be positive",
                row.chord
            )));
        }
        let pc_set = pc.sets.get(row.pc_set - 1).ok_or_else(|| {
            at(format!(
                "pc set {} named, but {pc_origin} has {} set(s)",
                row.pc_set,
                pc.sets.len()
            ))
        })?;
        let found = made
            .iter()
            .find(|(s, t, _)| *s == row.pc_set && *t == row.thickness_pct)
            .map(|(_, _, p)| Arc::clone(p));
        let polar = match found {
            Some(p) => p,
            None => {
                let p = Arc::new(
                    thickness_polar(pc_set, row.thickness_pct, pc_origin, row.pc_set)
                        .map_err(|e| at(e.to_string()))?,
                );
                made.push((row.pc_set, row.thickness_pct, Arc::clone(&p)));
                p
            }
        };
        nodes.push(AeroNode {
            span: row.r,
            chord: row.chord,
            twist: twist.at(row.r),
            ac_ahead: 0.25 * row.chord,
            polar,
        });
    }
    Ok(AeroBlade {
        prebend: Vec::new(),
        nodes,
        origin: ae_origin.to_string(),
    })
}

/// Relative thickness (percent) within which an ae row may lie outside its pc set's range and
/// take the end profile: files written in floating point put 21.1 % as 21.09999999999999.
const THICKNESS_SLACK: f64 = 1e-6;

/// The polar HAWC2 uses at relative thickness `t` (percent): each coefficient linear in
/// thickness between the two profiles of the set that bracket it (as DTU's Wind Energy
/// Toolbox, `wetb/hawc2/pc_file.py`, reads HAWC2's interpolation). A thickness outside the set's
/// profiles is refused rather than extrapolated.
fn thickness_polar(set: &PcSet, t: f64, origin: &str, set_no: usize) -> Result<Polar> {
    let mut profiles: Vec<&PcProfile> = set.profiles.iter().collect();
    profiles.sort_by(|a, b| a.thickness_pct.total_cmp(&b.thickness_pct));
    let thinnest = profiles[0].thickness_pct;
    let thickest = profiles[profiles.len() - 1].thickness_pct;
    if t < thinnest - THICKNESS_SLACK || t > thickest + THICKNESS_SLACK {
        return Err(Error::format(
            origin,
            0,
            format!(
                "relative thickness {t} % is outside pc set {set_no}'s profiles ({thinnest} … \
                 {thickest} %); HAWC2 interpolates between profiles, it does not extrapolate"
            ),
        ));
    }
    let t = t.clamp(thinnest, thickest);
    let k = profiles
        .partition_point(|p| p.thickness_pct <= t)
        .clamp(1, profiles.len().max(2) - 1);
    let name = |p: &PcProfile| format!("{origin}, pc set {set_no} profile {}", p.number);
    if profiles.len() == 1 {
        return profile_polar(profiles[0], &name(profiles[0]));
    }
    let (a, b) = (profiles[k - 1], profiles[k]);
    let w = (t - a.thickness_pct) / (b.thickness_pct - a.thickness_pct);
    if w <= 0.0 {
        return profile_polar(a, &name(a));
    }
    if w >= 1.0 {
        return profile_polar(b, &name(b));
    }
    let (lower, upper) = (profile_polar(a, &name(a))?, profile_polar(b, &name(b))?);
    lower.blend(&upper, w, &format!("{origin}, pc set {set_no} at {t} %"))
}

fn profile_polar(p: &PcProfile, origin: &str) -> Result<Polar> {
    Polar::new(
        p.alpha_deg.iter().map(|a| a.to_radians()).collect(),
        p.cl.clone(),
        p.cd.clone(),
        p.cm.clone(),
        origin,
    )
}

/// The aerodynamic blade of a WindIO file (docs/model.md §12.1): at every point of the chord's
/// grid the chord, the twist and the pitch axis, the polars of the two airfoils that bracket the
/// station's relative thickness blended in it (as its shape is, §11.12), and the prebend from
/// the reference axis's `x` (downwind positive, as `BlCrvAC`).
pub fn windio_aero(w: &WindIo) -> Result<AeroBlade> {
    let shape = &w.blade.outer_shape;
    let axis = &shape.reference_axis;
    let root = axis.z.linear(0.0);
    let polar_of = |a: &windio::Airfoil| -> Result<Polar> {
        let p = &a.polars[0];
        let alpha = p.c_l.grid.clone();
        let on_lift = |d: &windio::Distribution| alpha.iter().map(|&x| d.linear(x)).collect();
        Polar::new(
            alpha.clone(),
            p.c_l.values.clone(),
            on_lift(&p.c_d),
            on_lift(&p.c_m),
            &format!("{}: airfoil {} (line {}), polar 1", w.path, a.name, a.line),
        )
    };
    let mut made: Vec<(String, String, f64, Arc<Polar>)> = Vec::new();
    let mut nodes = Vec::with_capacity(shape.chord.grid.len());
    for &eta in &shape.chord.grid {
        let b = w.thickness_blend(eta);
        let polar = match made
            .iter()
            .find(|(a, c, t, _)| *a == b.thinner.name && *c == b.thicker.name && *t == b.weight)
        {
            Some((_, _, _, p)) => Arc::clone(p),
            None => {
                let thin = polar_of(b.thinner)?;
                let polar = if b.weight > 0.0 {
                    thin.blend(&polar_of(b.thicker)?, b.weight, &w.path)?
                } else {
                    thin
                };
                let polar = Arc::new(polar);
                made.push((
                    b.thinner.name.clone(),
                    b.thicker.name.clone(),
                    b.weight,
                    Arc::clone(&polar),
                ));
                polar
            }
        };
        let centre = |a: &windio::Airfoil| a.aerodynamic_center.unwrap_or(0.25);
        let ac = (1.0 - b.weight) * centre(b.thinner) + b.weight * centre(b.thicker);
        let chord = shape.chord.linear(eta);
        nodes.push(AeroNode {
            span: axis.z.linear(eta) - root,
            chord,
            twist: shape.twist.linear(eta),
            ac_ahead: (shape.pitch_axis.linear(eta) - ac) * chord,
            polar,
        });
    }
    let prebend = shape
        .chord
        .grid
        .iter()
        .map(|&eta| (axis.z.linear(eta) - root, axis.x.linear(eta)))
        .collect();
    Ok(AeroBlade {
        nodes,
        prebend,
        origin: w.path.clone(),
    })
}
