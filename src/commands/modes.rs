//! `flutterscope modes`: natural modes of the blade structure at the preset's rotor speed, no
//! aerodynamics: the uniform blade's Galerkin model (docs/model.md §3–§4) or a tabulated
//! blade's finite elements (§11). Both report the same fields per mode: label, family and
//! number in the family, frequency, flap/edge/twist shares and damping ratio, and with
//! `--shapes` the mode shapes along the span.
//!
//! Shape scaling (also in the README): each mode is scaled by one factor so that its own
//! family's component peaks at +1 — the flap displacement `u` of a flap mode, the edge
//! displacement `v` of an edge mode (both then in m per m of that peak), the twist `φ` of a
//! torsion mode (rad per rad). The other components keep their proportion: a flap mode's `φ`
//! reads in rad per m of peak flap displacement, a torsion mode's `u` and `v` in m per rad.

use crate::error::Result;
use crate::model::turbine::structure_in_vacuo;
use crate::physics::structure::{damping_ratio, Family, MotionRows, NaturalMode, Structure};
use crate::plot::{Figure, Panel, Series, PALETTE};
use crate::preset::{Form, TurbineModel, ValidPreset};
use nalgebra::DVector;
use serde::Serialize;
use std::path::Path;

/// What `modes` reports about one mode.
#[derive(Debug, Serialize)]
struct ModeRow {
    /// Label, family, number in the family, frequency, shares and the twist share again under
    /// `torsion_share` (the name older scripts read).
    #[serde(flatten)]
    mode: NaturalMode,
    /// Modal damping ratio ζ; `null` for a mode at zero frequency, which has none.
    damping_ratio: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    shape: Option<Shape>,
}

/// A mode shape sampled along the span, scaled as the module documentation says.
#[derive(Debug, Serialize)]
struct Shape {
    /// The component scaled to peak at +1: `flap`, `edge` or `twist`.
    scaled_by: &'static str,
    /// Span position from the root (m) and radius `r = r_hub + z` (m).
    z: Vec<f64>,
    r: Vec<f64>,
    /// Flap displacement u (downwind), edge displacement v (toward the leading edge), twist φ
    /// (toward feather).
    flap: Vec<f64>,
    edge: Vec<f64>,
    twist: Vec<f64>,
}

/// The report: which blade, at which rotor speed, and its modes.
#[derive(Debug, Serialize)]
struct Report {
    preset: String,
    source: &'static str,
    rotor_speed_rpm: f64,
    modes: Vec<ModeRow>,
}

pub fn run(p: &ValidPreset, json: bool, shapes: bool, plot: Option<&Path>) -> Result<()> {
    if let Some(path) = plot {
        crate::plot::format_for(path)?;
    }
    // The structure alone depends on the rotor speed and pitch only, of the operating point:
    // the schedule's at the preset's wind speed when it has one, as every other command runs.
    let scheduled = crate::model::operating::on_schedule(p)?;
    let p = &scheduled;
    let at = || {
        format!(
            "{} at operating.rotor_speed = {} rpm",
            p.display_name(),
            p.operating.rotor_speed
        )
    };
    let structure = structure_in_vacuo(p).map_err(|e| e.at(at()))?;
    let mut report = report(p, mode_rows(p, structure.as_ref()).map_err(|e| e.at(at()))?);
    let heading = heading(p, structure.as_ref());
    if let Some(path) = plot {
        crate::plot::write(&shapes_figure(p, &report), path)?;
    }
    if !shapes {
        for m in &mut report.modes {
            m.shape = None;
        }
    }
    if json {
        super::print_json(&report)?;
    } else {
        super::print_text(&render(&heading, &report))?;
    }
    if let Some(path) = plot {
        eprintln!("plot written to {}", path.display());
    }
    Ok(())
}

/// Every natural mode of the structure with its name, shares, damping and shape (sampled at the
/// structure's own span points, at the reference axis).
fn mode_rows(p: &ValidPreset, structure: &dyn Structure) -> Result<Vec<ModeRow>> {
    let points = structure.span_points();
    let rows: Vec<_> = points.iter().map(|&z| structure.motion_rows(z)).collect();
    Ok(structure
        .natural_modes()?
        .into_iter()
        .map(|m| {
            let along = |pick: fn(&MotionRows) -> &DVector<f64>| -> Vec<f64> {
                rows.iter().map(|r| pick(r).dot(&m.shape)).collect()
            };
            let shape = shape(
                p,
                m.family,
                points.clone(),
                along(|r| &r.flap),
                along(|r| &r.edge),
                along(|r| &r.twist),
            );
            ModeRow {
                damping_ratio: damping_ratio(structure, &m),
                mode: m,
                shape: Some(shape),
            }
        })
        .collect())
}

/// What the modes are of: the uniform blade's Galerkin size and form, or the tabulated blade's
/// files, span and mesh.
fn heading(p: &ValidPreset, structure: &dyn Structure) -> String {
    let name = p.display_name();
    let rpm = p.operating.rotor_speed;
    match p.tabulated_blade() {
        None => {
            let form = match p.structure.form {
                Form::Weak => "weak",
                Form::Strong => "strong",
            };
            format!(
                "{name}: natural modes at {rpm} rpm, N = {} per field, {form} form (uniform blade)",
                p.structure.modes
            )
        }
        Some(_) if p.turbine.model != TurbineModel::Blade => format!(
            "{name}: {} modes of the {} ({} blades on a {} drivetrain, {}) at {rpm} rpm, pitch \
             {} deg, in the ground frame",
            structure.coordinates(),
            p.turbine.model.name(),
            p.operating.blades,
            p.turbine.drivetrain.name(),
            match p.turbine.model {
                TurbineModel::Turbine => "on its tower",
                _ => "support rigid",
            },
            p.operating.pitch
        ),
        Some(blade) => {
            let count = structure.coordinates();
            let beam = crate::model::blade::beam(p).map_or("", |b| b.title());
            format!(
                "{name}: {count} blade mode{} at {rpm} rpm, pitch {} deg; {} blade from {}, {:.3} m \
                 from r = {} m, {} {beam} elements",
                if count == 1 { "" } else { "s" },
                p.operating.pitch,
                blade.format.title(),
                blade.files.join(" + "),
                structure.length(),
                structure.hub_radius(),
                structure.span_points().len() - 1
            )
        }
    }
}

/// The samples scaled by one factor so that the family's own component peaks at +1.
fn shape(
    p: &ValidPreset,
    f: Family,
    z: Vec<f64>,
    u: Vec<f64>,
    v: Vec<f64>,
    phi: Vec<f64>,
) -> Shape {
    let (scaled_by, own) = match f {
        Family::Flap => ("flap", &u),
        Family::Edge => ("edge", &v),
        Family::Torsion => ("twist", &phi),
    };
    let peak = own
        .iter()
        .copied()
        .fold(0.0, |a: f64, x| if x.abs() > a.abs() { x } else { a });
    let k = if peak != 0.0 { 1.0 / peak } else { 1.0 };
    // `+ 0.0` turns the −0 of a zero scaled by a negative factor (the clamped root) into 0.
    let scale = |xs: Vec<f64>| xs.into_iter().map(|x| x * k + 0.0).collect();
    Shape {
        scaled_by,
        r: z.iter().map(|x| p.blade.hub_radius + x).collect(),
        z,
        flap: scale(u),
        edge: scale(v),
        twist: scale(phi),
    }
}

fn report(p: &ValidPreset, modes: Vec<ModeRow>) -> Report {
    Report {
        preset: p.display_name().to_string(),
        source: p.blade.source.name(),
        rotor_speed_rpm: p.operating.rotor_speed,
        modes,
    }
}

/// The human-readable table, and each mode's shape after it when asked for.
fn render(heading: &str, r: &Report) -> String {
    let mut out = format!("{heading}\n\n");
    // As wide as the longest name (`collective torsion 2` on a rotor), at least 12.
    let w = r
        .modes
        .iter()
        .map(|m| m.mode.label.chars().count())
        .fold(12, usize::max);
    out.push_str(&format!(
        "{:>4}  {:<w$} {:>14}  {:>6}  {:>6}  {:>6}  {:>9}\n",
        "#", "mode", "frequency (Hz)", "flap", "edge", "twist", "damping ζ"
    ));
    for (k, m) in r.modes.iter().enumerate() {
        let zeta = m
            .damping_ratio
            .map_or_else(|| "—".to_string(), |z| format!("{z:.5}"));
        out.push_str(&format!(
            "{:>4}  {:<w$} {:>14}  {:>6.3}  {:>6.3}  {:>6.3}  {zeta:>9}\n",
            k + 1,
            m.mode.label,
            format_hz(m.mode.frequency_hz),
            m.mode.shares.flap,
            m.mode.shares.edge,
            m.mode.shares.twist,
        ));
    }
    for m in &r.modes {
        if let Some(s) = &m.shape {
            out.push_str(&render_shape(m, s));
        }
    }
    out
}

fn render_shape(m: &ModeRow, s: &Shape) -> String {
    let units = match s.scaled_by {
        "twist" => "twist φ peaks at +1 rad; u and v in m per rad",
        "edge" => "edge v peaks at +1 m; u in m per m, φ in rad per m",
        _ => "flap u peaks at +1 m; v in m per m, φ in rad per m",
    };
    let mut out = format!(
        "\n{} at {} Hz ({units})\n{:>9}  {:>9}  {:>12}  {:>12}  {:>12}\n",
        m.mode.label,
        format_hz(m.mode.frequency_hz),
        "z (m)",
        "r (m)",
        "flap u",
        "edge v",
        "twist φ"
    );
    for i in 0..s.z.len() {
        out.push_str(&format!(
            "{:>9.4}  {:>9.4}  {:>12.5e}  {:>12.5e}  {:>12.5e}\n",
            s.z[i], s.r[i], s.flap[i], s.edge[i], s.twist[i]
        ));
    }
    out
}

/// Flap, edge and twist of every mode against the radius, one colour per mode in each panel
/// (edge left out for the uniform blade, which has none).
fn shapes_figure(p: &ValidPreset, r: &Report) -> Figure {
    let tabulated = p.blade.source.is_tabulated();
    let mut panels = vec![
        Panel::new("radius r (m)", "flap u (scaled)").titled("(a) flap, downwind"),
        Panel::new("radius r (m)", "edge v (scaled)").titled("(b) edge, toward the leading edge"),
        Panel::new("radius r (m)", "twist φ (scaled)").titled("(c) twist, toward feather"),
    ];
    for (i, m) in r.modes.iter().enumerate() {
        let Some(s) = &m.shape else { continue };
        let color = PALETTE[i % PALETTE.len()];
        let name = format!("{} ({} Hz)", m.mode.label, format_hz(m.mode.frequency_hz));
        for (panel, values) in panels.iter_mut().zip([&s.flap, &s.edge, &s.twist]) {
            panel.series.push(
                Series::from_xy(&name, &s.r, values, crate::plot::Mark::Line).with_color(color),
            );
        }
    }
    for panel in panels.iter_mut().skip(1) {
        panel.legend = false;
    }
    panels[0].notes.push(
        "each mode scaled so that its own family's component peaks at +1 (u, v in m, φ in rad)"
            .into(),
    );
    if !tabulated {
        panels.remove(1);
    }
    panels.into_iter().fold(
        Figure::new(format!(
            "Mode shapes — {}, {} rpm",
            p.display_name(),
            p.operating.rotor_speed
        )),
        Figure::with_panel,
    )
}

/// Frequencies span 1e-2 to 1e4 Hz on the paper's blade: fixed decimals where they read well,
/// scientific notation otherwise, always 5 significant digits.
fn format_hz(f: f64) -> String {
    if f == 0.0 {
        "0".into()
    } else if (1e-3..1e5).contains(&f.abs()) {
        let decimals = (4 - f.abs().log10().floor() as i32).clamp(0, 7) as usize;
        format!("{f:.decimals$}")
    } else {
        format!("{f:.4e}")
    }
}
