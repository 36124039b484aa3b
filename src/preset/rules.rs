//! Rules across keys: values each allowed on their own that together describe nothing physical
//! or nothing the program can hold (or, for the blade keys, a blade other than the one computed). Checked with the key ranges by [`super::Preset::validate`], for
//! every preset whatever its `section.source` (`flutterscope section` evaluates the layup of any
//! preset).

use super::schema::{
    AeroModel, BladeSource, ContourShape, DrivetrainModel, Preset, Schedule, SectionSource,
    TurbineModel, TurbineSource,
};
use crate::error::{Error, Result};
use crate::model::files::ReadFiles;
use crate::physics::blade::coupling::{coupling_ratio, indefinite_station};
use crate::physics::blade::windio::is_span;

/// Most samples one time response may hold (`simulation.duration × simulation.sample_rate`):
/// 2e6 samples is 10⁴ s at 200/s; time, tip twist and flap take 48 MB.
pub const MAX_SAMPLES: f64 = 2e6;

/// `blade.source` and `blade.file` agree: a tabulated blade names its file, the uniform blade
/// names none (a file given without its source would otherwise be ignored), nor a bend–twist
/// coupling α (it scales a tabulated blade's stations). Checked before the file is read.
pub fn check_blade_keys(p: &Preset) -> Result<()> {
    let b = &p.blade;
    let clash = htc_keys_clash(p);
    let span = bad_span(p);
    let message = match (b.source, b.file.trim().is_empty()) {
        _ if clash.is_some() => clash.unwrap_or_default(),
        (BladeSource::Hawc2, true) if b.from_htc() => return Ok(()),
        (BladeSource::Uniform, _) if b.bend_twist_coupling != 0.0 => format!(
            "blade.bend_twist_coupling = {} {}",
            b.bend_twist_coupling,
            not_acting(p, "blade.bend_twist_coupling").unwrap_or_default()
        ),
        (BladeSource::Uniform, false) => format!(
            "blade.file = \"{}\" does not apply to blade.source = \"uniform\" (the paper's \
             uniform blade, from blade.length and section.*); set blade.source = \"beamdyn\" for \
             a BeamDyn primary file or \"hawc2\" for a HAWC2 st file",
            b.file
        ),
        (BladeSource::Windio, true) => "blade.source = \"windio\" needs blade.file: the WindIO \
             ontology file (.yaml) of the turbine, relative to the preset file"
            .to_string(),
        (source, _) if source != BladeSource::Windio && fill_keys_given(p) => format!(
            "section.trailing_edge_fill, section.trailing_edge_fill_length and \
             section.trailing_edge_fill_span fill the trailing edge of a WindIO blade's layup \
             (blade.source = \"windio\"); blade.source = \"{}\" has no layup",
            source.name()
        ),
        (source, _) if source != BladeSource::Windio && turn_keys_given(p) => format!(
            "section.rotate_layers and section.rotate_span turn the layers of a WindIO blade's \
             layup (blade.source = \"windio\"); blade.source = \"{}\" has no layup",
            source.name()
        ),
        (BladeSource::Windio, false) if span.is_some() => span.unwrap_or_default(),
        (BladeSource::Uniform, _) if !(0.0..=90.0).contains(&p.section.paper_ply_angle()) => {
            format!(
                "section.ply_angle = {}: the paper's blade takes a ply angle in [0, 90] deg (its \
             Table 1 and its CAS layup; a negative angle is the mirrored layup)",
                p.section.paper_ply_angle()
            )
        }
        (source @ (BladeSource::Beamdyn | BladeSource::Hawc2), true) => format!(
            "blade.source = \"{}\" needs blade.file: the {}, relative to the preset file",
            source.name(),
            match source {
                BladeSource::Beamdyn => "BeamDyn primary file (it names its blade file)",
                _ =>
                    "HAWC2 st file (blade.st_set and blade.st_subset choose the subset; or \
                      give a HAWC2 model's htc file as blade.htc_file instead)",
            }
        ),
        _ => match (b.source, b.twist_file.trim().is_empty()) {
            (BladeSource::Hawc2, true) => "blade.source = \"hawc2\" needs blade.twist_file: an \
                 AeroDyn 15 blade file whose BlTwist turns the sections (a HAWC2 st file carries \
                 no twist; HAWC2 takes it from the htc's c2_def), relative to the preset file"
                .to_string(),
            (BladeSource::Uniform | BladeSource::Beamdyn | BladeSource::Windio, false) => format!(
                "blade.twist_file = \"{}\" does not apply to blade.source = \"{}\" (only a \
                 HAWC2 st file takes its twist from another file; BeamDyn and WindIO files have \
                 their own)",
                b.twist_file,
                b.source.name()
            ),
            _ => return Ok(()),
        },
    };
    Err(Error::Invalid {
        origin: p.origin.clone(),
        message,
    })
}

/// The first of a WindIO blade's span keys that is no span `[from, to]` within the blade.
fn bad_span(p: &Preset) -> Option<String> {
    let s = &p.section;
    [
        ("section.trailing_edge_fill_span", s.trailing_edge_fill_span),
        ("section.rotate_span", s.rotate_span),
    ]
    .into_iter()
    .find(|(_, span)| !is_span(*span))
    .map(|(key, [from, to])| {
        format!("{key} = [{from}, {to}]: expected span fractions [from, to] with 0 ≤ from ≤ to ≤ 1")
    })
}

/// Whether the preset sets any of the trailing-edge fill's keys.
fn fill_keys_given(p: &Preset) -> bool {
    let d = crate::preset::schema::Section::default();
    !p.section.trailing_edge_fill.trim().is_empty()
        || p.section.trailing_edge_fill_length != d.trailing_edge_fill_length
        || p.section.trailing_edge_fill_span != d.trailing_edge_fill_span
}

/// Whether the preset turns layers other than by the defaults (spar caps, whole span).
fn turn_keys_given(p: &Preset) -> bool {
    !p.section.rotate_layers.is_empty() || p.section.rotate_span != [0.0, 1.0]
}

/// How the htc keys clash with the others: an htc blade takes its st file, set, twist and
/// prebend from the htc, so a preset that names them too describes the blade twice.
fn htc_keys_clash(p: &Preset) -> Option<String> {
    let b = &p.blade;
    if !b.from_htc() {
        return (b.htc_body != "blade1" || !b.htc_root.trim().is_empty()).then(|| {
            format!(
                "blade.htc_body = \"{}\" and blade.htc_root = \"{}\" apply only with \
                 blade.htc_file (a HAWC2 model's htc file)",
                b.htc_body, b.htc_root
            )
        });
    }
    if b.source != BladeSource::Hawc2 {
        return Some(format!(
            "blade.htc_file = \"{}\" is a HAWC2 model: it needs blade.source = \"hawc2\", not \
             \"{}\"",
            b.htc_file,
            b.source.name()
        ));
    }
    let both = |key: &str, what: &str| {
        Some(format!(
            "{key} and blade.htc_file both give the blade's {what}; give one of them"
        ))
    };
    let given = |s: &str| !s.trim().is_empty();
    if given(&b.file) {
        both(
            "blade.file",
            "st file (the htc's timoschenko_input names it)",
        )
    } else if given(&b.twist_file) {
        both("blade.twist_file", "twist (the htc's c2_def holds it)")
    } else if (b.st_set, b.st_subset) != (1, 1) {
        both(
            "blade.st_set/blade.st_subset",
            "st set and subset (the htc's timoschenko_input 'set' chooses them)",
        )
    } else if given(&p.aero.prebend_file) {
        both("aero.prebend_file", "prebend (the htc's c2_def holds it)")
    } else {
        None
    }
}

/// Why numeric `key` can change nothing the model computes for `p`'s blade, and what acts in its
/// place; `None` when it acts. A `--set` or `--vary` of such a key is an error
/// ([`super::Preset::acts`]) and the explorer does not offer it. The `section` command is apart:
/// it evaluates the layup whatever the blade uses.
pub fn not_acting(p: &Preset, key: &str) -> Option<String> {
    let source = p.blade.source;
    // The key that names the blade's sections: its htc model or its file.
    let file = if p.blade.from_htc() {
        format!("blade.htc_file = \"{}\"", p.blade.htc_file)
    } else {
        format!("blade.file = \"{}\"", p.blade.file)
    };
    let tabulated = source.is_tabulated();
    let reason = match key {
        "section.ply_angle" if source == BladeSource::Windio => return None,
        "section.ply_angle" if tabulated => format!(
            "does not apply to blade.source = \"{}\": the sections come from {file}; the \
             coupling added to them is blade.bend_twist_coupling",
            source.name()
        ),
        "section.ply_angle" if p.section.source == SectionSource::Direct => "does not apply to \
             section.source = \"direct\": its stiffnesses are section.c22, section.c23 and \
             section.c33 (the ply angle turns the plies of section.source = \"table\" or \
             \"layup\")"
            .to_string(),
        "structure.loss_factor" if tabulated => format!(
            "does not apply to blade.source = \"{}\": a tabulated blade is damped per mode \
             family, by structure.damping_flap, structure.damping_edge and \
             structure.damping_torsion (unset: the damping blade.file states)",
            source.name()
        ),
        // A real blade's inflow is the BEM's (docs/model.md §12.6): no tunnel.
        "operating.tunnel_speed" if tabulated => format!(
            "does not apply to blade.source = \"{}\": a rotor blade's inflow is the BEM's, from \
             operating.wind_speed, operating.rotor_speed and operating.pitch",
            source.name()
        ),
        "blade.bend_twist_coupling" if !tabulated => "does not apply to blade.source = \
             \"uniform\": it adds to the flap–twist coupling of a tabulated blade's stations \
             (blade.source = \"beamdyn\" or \"hawc2\"); the uniform blade's coupling is \
             section.c23, or section.ply_angle for a table or layup section"
            .to_string(),
        // The uniform blade's own section and strip keys (docs/model.md §2, §5): a tabulated
        // blade's sections come from its file and its strips from its polars.
        _ if tabulated && key.starts_with("section.") => format!(
            "does not apply to blade.source = \"{}\": the sections (stiffness, mass, chord, \
             centres) come from {file}",
            source.name()
        ),
        "operating.twist_root" | "operating.twist_tip" if tabulated => format!(
            "does not apply to blade.source = \"{}\": a tabulated blade's twist comes from its \
             files (the BeamDyn key points, blade.twist_file for a HAWC2 st file, or the \
             c2_def of blade.htc_file), and \
             operating.pitch turns it",
            source.name()
        ),
        "operating.induction" if tabulated => format!(
            "does not apply to blade.source = \"{}\": a rotor blade's induction is the BEM's, \
             at every station, from operating.wind_speed, operating.rotor_speed and \
             operating.pitch",
            source.name()
        ),
        "aero.lift_slope" | "aero.drag_coefficient" if tabulated => format!(
            "does not apply to blade.source = \"{}\": a tabulated blade's strips read lift and \
             drag from each station's polar (aero.airfoils or aero.pc_file)",
            source.name()
        ),
        // The rotor's keys shape the BEM (docs/model.md §12), which only a tabulated blade has.
        "operating.blades" | "operating.precone" | "operating.shaft_tilt" if !tabulated => {
            "does not apply to blade.source = \"uniform\": it shapes the rotor's steady BEM, \
             which runs on a tabulated blade (blade.source = \"beamdyn\" or \"hawc2\"); the \
             uniform blade's inflow is operating.wind_speed with operating.induction"
                .to_string()
        }
        "structure.damping_flap" | "structure.damping_edge" | "structure.damping_torsion"
            if !tabulated =>
        {
            "does not apply to blade.source = \"uniform\": the uniform blade is damped by \
             structure.loss_factor (the per-family damping ratios are a tabulated blade's)"
                .to_string()
        }
        "blade.st_set" | "blade.st_subset" if p.blade.from_htc() => format!(
            "does not apply with blade.htc_file = \"{}\": the htc's timoschenko_input chooses \
             the st set and subset",
            p.blade.htc_file
        ),
        "aero.ae_set" if p.blade.from_htc() && p.aero.ae_file.trim().is_empty() => format!(
            "does not apply without aero.ae_file: the ae set is the one the aero block of \
             blade.htc_file = \"{}\" gives its blade (ae_sets)",
            p.blade.htc_file
        ),
        "blade.st_set" | "blade.st_subset" if source != BladeSource::Hawc2 => format!(
            "does not apply to blade.source = \"{}\": it chooses a subset of a HAWC2 st file \
             (blade.source = \"hawc2\")",
            source.name()
        ),
        "aero.ae_set" if p.aero.ae_file.trim().is_empty() => "does not apply without \
             aero.ae_file: it chooses a set of a HAWC2 ae file"
            .to_string(),
        "operating.rated_power"
        | "operating.rotor_speed_min"
        | "operating.rotor_speed_max"
        | "operating.tip_speed_ratio"
            if p.operating.schedule != Schedule::Law =>
        {
            format!(
                "does not apply to operating.schedule = \"{}\": it is a parameter of the \
                 control law (operating.schedule = \"law\")",
                p.operating.schedule.name()
            )
        }
        "section.c22" | "section.c23" | "section.c33"
            if p.section.source != SectionSource::Direct =>
        {
            format!(
                "does not apply to section.source = \"{}\": the stiffnesses come from {}",
                p.section.source.name(),
                match p.section.source {
                    SectionSource::Table => "the paper's Table 1 at section.ply_angle",
                    _ => "the laminate (section.layup, section.contour, section.ply_angle)",
                }
            )
        }
        "section.mass_per_length"
        | "section.polar_inertia"
        | "section.ka2"
        | "section.km1_2"
        | "section.km2_2"
            if p.section.source == SectionSource::Layup =>
        {
            "does not apply to section.source = \"layup\": the mass and inertia come from the \
             laminate and its materials (section.layup, section.contour)"
                .to_string()
        }
        _ => return None,
    };
    Some(reason)
}

/// The rotor's file keys agree with each other and with the blade (docs/model.md §12.1): one
/// aerodynamic description, complete, on the structure whose reference axis it is placed from
/// (AeroDyn + ElastoDyn `PitchAxis`: the pitch axis of a BeamDyn blade; HAWC2 ae + pc: the
/// half-chord line of a HAWC2 blade, twisted by its `blade.twist_file`), and a table schedule
/// with its file. Checked before the files are read.
pub fn check_rotor_keys(p: &Preset) -> Result<()> {
    let a = &p.aero;
    let given = |s: &str| !s.trim().is_empty();
    let aerodyn = given(&a.blade_file) || !a.airfoils.is_empty() || given(&a.pitch_axis_file);
    let hawc2 = given(&a.ae_file) || given(&a.pc_file);
    let message = if aerodyn && hawc2 {
        "aero.blade_file/aero.airfoils/aero.pitch_axis_file (AeroDyn) and aero.ae_file/\
         aero.pc_file (HAWC2) both describe the blade's aerodynamics; give one set"
            .to_string()
    } else if aerodyn
        && !(given(&a.blade_file) && !a.airfoils.is_empty() && given(&a.pitch_axis_file))
    {
        format!(
            "an AeroDyn aerodynamic description needs all three of aero.blade_file (the AeroDyn 15 \
             blade file, now \"{}\"), aero.airfoils (its polar files in BlAFID order, now {} \
             listed) and aero.pitch_axis_file (an ElastoDyn blade file whose PitchAxis places the \
             pitch axis on the chord, now \"{}\")",
            a.blade_file,
            a.airfoils.len(),
            a.pitch_axis_file
        )
    } else if hawc2 && !(given(&a.ae_file) && given(&a.pc_file)) && !p.blade.from_htc() {
        format!(
            "a HAWC2 aerodynamic description needs both aero.ae_file (now \"{}\") and \
             aero.pc_file (now \"{}\")",
            a.ae_file, a.pc_file
        )
    } else if aerodyn && p.blade.source != BladeSource::Beamdyn {
        format!(
            "aero.blade_file places the aerodynamic centre from the pitch axis, the reference axis \
             of a BeamDyn blade; blade.source = \"{}\" has another (set blade.source = \
             \"beamdyn\", or describe a HAWC2 blade's aerodynamics by aero.ae_file and \
             aero.pc_file)",
            p.blade.source.name()
        )
    } else if hawc2 && p.blade.source != BladeSource::Hawc2 {
        format!(
            "aero.ae_file places the aerodynamic centre from the half-chord line and takes the \
             twist from blade.twist_file, as a HAWC2 blade (blade.source = \"hawc2\") has them; \
             blade.source = \"{}\" has neither",
            p.blade.source.name()
        )
    } else {
        match (p.operating.schedule, given(&p.operating.schedule_file)) {
            (Schedule::Table, false) => "operating.schedule = \"table\" needs \
                 operating.schedule_file: a HAWC2 .opt file of wind speed, pitch and rotor speed, \
                 relative to the preset file"
                .to_string(),
            (s @ (Schedule::None | Schedule::Law), true) => format!(
                "operating.schedule_file = \"{}\" does not apply to operating.schedule = \"{}\" \
                 (set operating.schedule = \"table\" to run along it)",
                p.operating.schedule_file,
                s.name()
            ),
            _ => return Ok(()),
        }
    };
    Err(Error::Invalid {
        origin: p.origin.clone(),
        message,
    })
}

/// `operating.schedule = "law"` needs its parameters and the rotor's aerodynamics (the pitch
/// above rated comes from the BEM).
fn law_is_complete(p: &Preset, files: &ReadFiles) -> std::result::Result<(), String> {
    let o = &p.operating;
    if o.schedule != Schedule::Law {
        return Ok(());
    }
    let missing = [
        ("operating.rated_power", o.rated_power),
        ("operating.tip_speed_ratio", o.tip_speed_ratio),
        ("operating.rotor_speed_max", o.rotor_speed_max),
    ]
    .into_iter()
    .find(|(_, v)| *v <= 0.0);
    if let Some((key, v)) = missing {
        return Err(format!(
            "operating.schedule = \"law\" needs {key} > 0, found {v}"
        ));
    }
    if o.rotor_speed_min > o.rotor_speed_max {
        return Err(format!(
            "operating.rotor_speed_min = {} rpm exceeds operating.rotor_speed_max = {} rpm",
            o.rotor_speed_min, o.rotor_speed_max
        ));
    }
    if files.aero_blade().is_none() {
        return Err(
            "operating.schedule = \"law\" pitches to hold operating.rated_power with \
                    the rotor's aerodynamics: give aero.blade_file (AeroDyn) or aero.ae_file \
                    (HAWC2)"
                .to_string(),
        );
    }
    Ok(())
}

/// Stated cut-in and cut-out wind speeds bound a range (0 leaves either unstated).
fn cut_in_below_cut_out(p: &Preset) -> std::result::Result<(), String> {
    let o = &p.operating;
    if o.cut_in > 0.0 && o.cut_out > 0.0 && o.cut_in >= o.cut_out {
        return Err(format!(
            "operating.cut_in = {} m/s must be below operating.cut_out = {} m/s",
            o.cut_in, o.cut_out
        ));
    }
    Ok(())
}

/// Every rule, in the order a user would fix them, the preset's keys against each other and
/// against what its `files` gave; the first broken one is the error.
pub fn check(p: &Preset, files: &ReadFiles) -> Result<()> {
    let invalid = |message: String| Error::Invalid {
        origin: p.origin.clone(),
        message,
    };
    length_is_the_files(p, files).map_err(invalid)?;
    law_is_complete(p, files).map_err(invalid)?;
    cut_in_below_cut_out(p).map_err(invalid)?;
    coupling_is_definite(p, files).map_err(invalid)?;
    turbine_is_complete(p, files).map_err(invalid)?;
    let described = files.aero_blade().is_some();
    if p.blade.source.is_tabulated() && p.aero.model != AeroModel::None && !described {
        return Err(invalid(format!(
            "aero.model = \"{}\" with blade.source = \"{}\": strip aerodynamics on a tabulated \
             blade needs its aerodynamic description: aero.blade_file, aero.airfoils and \
             aero.pitch_axis_file (AeroDyn 15) or aero.ae_file and aero.pc_file (HAWC2); or set \
             aero.model = \"none\" for the blade's structural modes and damping",
            p.aero.model.name(),
            p.blade.source.name()
        )));
    }
    if p.aero.model.needs_polars() && !p.blade.source.is_tabulated() {
        return Err(invalid(format!(
            "aero.model = \"{}\" with blade.source = \"{}\": the Hansen–Gaunaa–Madsen model \
             reads each station's airfoil polar (its separation point from the polar's lift), \
             and the uniform blade has none; give a tabulated blade with its aerodynamic \
             description (blade.source = \"beamdyn\" or \"hawc2\"), or choose aero.model = \
             \"none\", \"quasi-steady\", \"theodorsen\" or \"onera\"",
            p.aero.model.name(),
            p.blade.source.name()
        )));
    }
    if let (Some(a1), Some(a2)) = (p.aero.hgm.a1, p.aero.hgm.a2) {
        if a1 + a2 > 1.0 {
            return Err(invalid(format!(
                "aero.hgm.a1 + aero.hgm.a2 = {a1} + {a2} = {}; allowed: at most 1 (the direct \
                 part 1 − A1 − A2 of the indicial response is not negative)",
                a1 + a2
            )));
        }
    }
    let o = &p.aero.onera;
    if o.alpha2 <= o.alpha1 {
        return Err(invalid(format!(
            "aero.onera.alpha2 = {} must exceed aero.onera.alpha1 = {}",
            o.alpha2, o.alpha1
        )));
    }
    let sim = &p.simulation;
    let samples = sim.duration * sim.sample_rate;
    if !(1.0..=MAX_SAMPLES).contains(&samples) {
        return Err(invalid(format!(
            "simulation.duration × simulation.sample_rate = {} s × {} 1/s = {samples:.4e} \
             samples; allowed: 1 … {MAX_SAMPLES:e} (the response is kept in memory)",
            sim.duration, sim.sample_rate
        )));
    }
    if p.section.ea_offset.abs() > p.section.chord {
        return Err(invalid(format!(
            "section.ea_offset = {} lies outside the chord (|e_a| must be ≤ section.chord = {})",
            p.section.ea_offset, p.section.chord
        )));
    }
    inertia_exceeds_offset_mass(p).map_err(invalid)?;
    stiffness_is_definite(p).map_err(invalid)?;
    ply_is_physical(p).map_err(invalid)?;
    walls_do_not_overlap(p).map_err(invalid)
}

/// The `[turbine]` keys describe a model the program holds: a rotor of three tabulated blades,
/// its drivetrain's values from the turbine file (none for a rigid one), the file's blade count
/// the preset's; a turbine file names its source.
fn turbine_is_complete(p: &Preset, files: &ReadFiles) -> std::result::Result<(), String> {
    let t = &p.turbine;
    let named = !t.file.trim().is_empty();
    let htc_named = !t.htc_file.trim().is_empty();
    match (t.source, named, htc_named) {
        (TurbineSource::None, true, _) => {
            return Err(format!(
                "turbine.file = \"{}\" without turbine.source: set turbine.source = \
                 \"elastodyn\" for an ElastoDyn main file",
                t.file
            ))
        }
        (TurbineSource::None | TurbineSource::Elastodyn, _, true) => {
            return Err(format!(
                "turbine.htc_file = \"{}\" is a HAWC2 model's: set turbine.source = \"hawc2\"",
                t.htc_file
            ))
        }
        (TurbineSource::Elastodyn, false, _) => {
            return Err(
                "turbine.source = \"elastodyn\" needs turbine.file: the ElastoDyn main \
                        file, relative to the preset file"
                    .to_string(),
            )
        }
        (TurbineSource::Hawc2, _, false) => {
            return Err(
                "turbine.source = \"hawc2\" needs turbine.htc_file: the HAWC2 model's \
                        htc file, relative to the preset file"
                    .to_string(),
            )
        }
        (TurbineSource::Hawc2, true, _) => {
            return Err(format!(
                "turbine.file = \"{}\" is an ElastoDyn main file's key: a HAWC2 turbine is read \
                 from turbine.htc_file alone",
                t.file
            ))
        }
        _ => {}
    }
    if let Some((turbine, name)) = files.turbine() {
        if turbine.blades != p.operating.blades {
            return Err(format!(
                "operating.blades = {} but {name} has NumBl = {}: the rotor is the file's",
                p.operating.blades, turbine.blades
            ));
        }
    }
    if let Some((turbine, name)) = files.hawc2_turbine() {
        if turbine.blades != p.operating.blades {
            return Err(format!(
                "operating.blades = {} but {name} hangs {} hubs on its shaft: the rotor is the \
                 file's",
                p.operating.blades, turbine.blades
            ));
        }
    }
    let has_file = files.turbine().is_some() || files.hawc2_turbine().is_some();
    if t.torque_slope != 0.0 && t.drivetrain != DrivetrainModel::Free {
        return Err(format!(
            "turbine.torque_slope = {} with turbine.drivetrain = \"{}\": only a free generator \
             turns against its torque's slope",
            t.torque_slope,
            t.drivetrain.name()
        ));
    }
    if t.model == TurbineModel::Blade {
        return Ok(());
    }
    if !p.blade.source.is_tabulated() {
        return Err(format!(
            "turbine.model = \"{}\" with blade.source = \"{}\": a rotor is made of a tabulated \
             blade (beamdyn, hawc2 or windio); the paper's uniform blade has no edge motion",
            t.model.name(),
            p.blade.source.name()
        ));
    }
    if p.operating.blades != 3 {
        return Err(format!(
            "turbine.model = \"{}\" with operating.blades = {}: the ground-frame model is a \
             three-bladed rotor's",
            t.model.name(),
            p.operating.blades
        ));
    }
    if t.model == TurbineModel::Turbine && !has_file {
        return Err(
            "turbine.model = \"turbine\" reads the tower, the nacelle, the hub and the \
             drivetrain from a turbine file: set turbine.source = \"elastodyn\" and \
             turbine.file (an ElastoDyn main file) or turbine.source = \"hawc2\" and \
             turbine.htc_file"
                .to_string(),
        );
    }
    if t.drivetrain != DrivetrainModel::Rigid && !has_file {
        return Err(format!(
            "turbine.model = \"{}\" with turbine.drivetrain = \"{}\" reads the hub's and the \
             drivetrain's inertia, stiffness and damping from the turbine file: set \
             turbine.source = \"elastodyn\" and turbine.file (or \"hawc2\" and \
             turbine.htc_file), or turbine.drivetrain = \"rigid\" \
             for a hub turning at exactly the rotor speed",
            t.model.name(),
            t.drivetrain.name()
        ));
    }
    Ok(())
}

/// A tabulated blade is as long as its file says: `blade.length` either left out (it is then
/// filled in from the file) or equal to it, so a preset cannot describe one blade and compute
/// another.
fn length_is_the_files(p: &Preset, files: &ReadFiles) -> std::result::Result<(), String> {
    let Some(t) = files.tabulated() else {
        return Ok(());
    };
    let from_file = t.blade().length();
    if (p.blade.length - from_file).abs() <= 1e-9 * from_file {
        return Ok(());
    }
    Err(format!(
        "blade.length = {} m does not apply to blade.source = \"{}\": the blade is {from_file} m \
         long as blade.file = \"{}\" describes it; leave blade.length out or give the file's",
        p.blade.length,
        t.source().name(),
        t.file()
    ))
}

/// A tabulated blade's stations stay positive definite in bending and torsion with
/// `blade.bend_twist_coupling` added (docs/model.md §11.7), or its strain energy is not.
fn coupling_is_definite(p: &Preset, files: &ReadFiles) -> std::result::Result<(), String> {
    let (Some(t), alpha) = (files.tabulated(), p.blade.bend_twist_coupling) else {
        return Ok(());
    };
    let Some((k, s)) = indefinite_station(&t.blade().table, alpha) else {
        return Ok(());
    };
    Err(format!(
        "blade.bend_twist_coupling = {alpha} couples station {} of blade.file = \"{}\" (z = {} \
         m) more than its stiffnesses can carry: its flap–twist coupling g/√(EI_flap·GJ) = {:.4} \
         from the file plus α must leave the section's bending–torsion stiffness positive \
         definite (|g|/√(EI_flap·GJ) < 1 without edge coupling); choose a smaller |α|",
        k + 1,
        t.file(),
        s.z,
        coupling_ratio(&s)
    ))
}

/// For the sections whose mass properties the preset gives (`direct`, `table`), the polar inertia
/// about the elastic axis `I` must exceed `m d²`: by the parallel-axis theorem `I − m d²` is the
/// inertia about the centre of mass, which must be positive, or the mass matrix is not positive
/// definite (docs/model.md §3–§4). The layup source computes `m`, `I` and `d` from its own walls.
fn inertia_exceeds_offset_mass(p: &Preset) -> std::result::Result<(), String> {
    let s = &p.section;
    if s.source == SectionSource::Layup {
        return Ok(());
    }
    let about_cg = s.polar_inertia - s.mass_per_length * s.cg_offset * s.cg_offset;
    if about_cg > 0.0 {
        return Ok(());
    }
    Err(format!(
        "section.polar_inertia = {} kg·m (the inertia about the elastic axis) must exceed \
         section.mass_per_length × section.cg_offset² = {} kg/m × ({} m)² = {:.4e} kg·m: the \
         inertia about the centre of mass, I − m·d² = {about_cg:.4e} kg·m, must be positive \
         (move the centre of mass closer to the elastic axis or raise the inertia)",
        s.polar_inertia,
        s.mass_per_length,
        s.cg_offset,
        s.mass_per_length * s.cg_offset * s.cg_offset
    ))
}

/// For the `direct` section, the stiffnesses it gives must hold the coupling:
/// `C22·C33 − C23² > 0`, or the strain energy `C22 φ'² + 2 C23 φ' u'' + C33 u''²` is not positive
/// definite (docs/model.md §3–§4). The table and layup sources compute their own.
fn stiffness_is_definite(p: &Preset) -> std::result::Result<(), String> {
    let s = &p.section;
    if s.source != SectionSource::Direct {
        return Ok(());
    }
    let det = s.c22 * s.c33 - s.c23 * s.c23;
    if det > 0.0 {
        return Ok(());
    }
    Err(format!(
        "section.c23 = {} N·m² couples more than section.c22 = {} and section.c33 = {} N·m² \
         can carry: C22·C33 − C23² = {det:.4e} N²·m⁴ must be positive (|C23| < √(C22·C33) = \
         {:.4e} N·m²)",
        s.c23,
        s.c22,
        s.c33,
        (s.c22 * s.c33).sqrt()
    ))
}

/// A ply's compliance must be positive definite: with positive moduli (key ranges) that is
/// `Δ = 1 − ν12²·E22/E11 > 0` (docs/model.md §2.1 item 1).
fn ply_is_physical(p: &Preset) -> std::result::Result<(), String> {
    let l = &p.section.layup;
    let delta = 1.0 - l.nu12 * l.nu12 * l.e22 / l.e11;
    if delta > 0.0 {
        return Ok(());
    }
    Err(format!(
        "section.layup.nu12 = {} gives Δ = 1 − ν12·ν21 = 1 − ν12²·E22/E11 = {delta:.4} with \
         section.layup.e11 = {:e} Pa and section.layup.e22 = {:e} Pa; a physical ply needs \
         Δ > 0, i.e. |ν12| < √(E11/E22) = {:.4}",
        l.nu12,
        l.e11,
        l.e22,
        (l.e11 / l.e22).sqrt()
    ))
}

/// The wall (plies × ply thickness) must be thinner than the section it encloses, or the inner
/// faces overlap and the thin-walled contour integrals mean nothing.
fn walls_do_not_overlap(p: &Preset) -> std::result::Result<(), String> {
    let c = &p.section.contour;
    let t = p.section.layup.plies as f64 * p.section.layup.ply_thickness;
    let (key, inner) = match c.shape {
        ContourShape::Box if c.width < c.height => ("section.contour.width", c.width),
        ContourShape::Box => ("section.contour.height", c.height),
        ContourShape::Ellipse if c.a < c.b => ("section.contour.a", 2.0 * c.a),
        ContourShape::Ellipse => ("section.contour.b", 2.0 * c.b),
        // The Eq. (1) line is nearly a circle of diameter ≈ 1.7e = 0.43 chord.
        ContourShape::Paper => ("section.chord", 1.7 * p.section.chord / 4.0),
    };
    if t < inner {
        return Ok(());
    }
    Err(format!(
        "wall thickness section.layup.plies × section.layup.ply_thickness = {t:e} m is not \
         smaller than the section's inner dimension {inner:e} m (from {key}); the walls would \
         overlap"
    ))
}
