//! Figures of the engine's results, for the commands' `--plot FILE`: each function lays out one
//! result type. They only arrange numbers the engine computed (the one derived quantity, the
//! n-per-revolution lines `f = nΩ/60` on a Campbell diagram, is a unit conversion).

use super::{Dash, Figure, Guide, Mark, Marker, Panel, Series, PALETTE};
use crate::analysis::campbell::{typical, ROTOR_SPEED_KEY};
use crate::analysis::flutter::{BoundaryKind, Search};
use crate::analysis::response::Response;
use crate::analysis::simulate::RunStatus;
use crate::analysis::sweep::{FailedPoint, SweepRow, TrackedMode, TrackedSweep};
use crate::physics::cross_section::Mesh;
use crate::physics::laminate::LayupSection;
use crate::physics::turbine::ground::Whirl;

/// "key (unit)" for a preset key, or the bare key when it has no unit or is unknown.
pub fn key_label(key: &str) -> String {
    match crate::preset::key_spec(key) {
        Ok(spec) if !spec.unit.is_empty() => format!("{key} ({})", spec.unit),
        _ => key.to_string(),
    }
}

fn finite_extent(values: &[f64]) -> Option<(f64, f64)> {
    let mut it = values.iter().copied().filter(|v| v.is_finite());
    let first = it.next()?;
    Some(it.fold((first, first), |(lo, hi), v| (lo.min(v), hi.max(v))))
}

/// Frequency and damping-ratio panels for tracked modes, one colour per mode in both. Returns
/// (frequency panel, damping panel). The frequency panel draws the sweep's Campbell selection
/// (the modes the explorer's Campbell view draws); the damping panel, which carries the legend,
/// draws every mode: ζ has no scale problem, and a flutter boundary may be in any mode.
fn mode_panels(s: &TrackedSweep, x_label: &str) -> (Panel, Panel) {
    let mut freq = Panel::new(x_label, "frequency (Hz)");
    let mut damp =
        Panel::new(x_label, "damping ratio ζ (–)").with_guide(Guide::horizontal(0.0, "ζ = 0"));
    freq.legend = false;
    let mark = if s.values.len() < 12 {
        Mark::LinePoints
    } else {
        Mark::Line
    };
    let on_scale = s.campbell_modes();
    // Lowest mode first, in the legend and in the palette: the modes on the frequency scale (lowest
    // typical frequency first), then the others, also lowest first. A legend the panel's height
    // cuts short then leaves out high modes, not flap 1, and the modes drawn on the frequency
    // scale never share a colour.
    let mut off_scale: Vec<usize> = (0..s.modes.len())
        .filter(|i| !on_scale.shown.contains(i))
        .collect();
    off_scale.sort_by(|&a, &b| {
        let f = |i: usize| typical(&s.modes[i]).unwrap_or(f64::INFINITY);
        f(a).total_cmp(&f(b))
    });
    let order: Vec<usize> = on_scale.shown.iter().copied().chain(off_scale).collect();
    // A rotor's whirls of one blade mode (`BW edge 1`, `collective edge 1`, `FW edge 1`) share
    // its colour, stroked by whirl: backward dashed, collective solid, forward dotted.
    let mut hues: Vec<&str> = Vec::new();
    for (rank, &i) in order.iter().enumerate() {
        let m = &s.modes[i];
        let (hue, dash) = match Whirl::of_name(&m.label) {
            Some(whirl) => (
                m.label
                    .split_once(' ')
                    .map_or(m.label.as_str(), |(_, mode)| mode),
                match whirl {
                    Whirl::Backward => Dash::Dashed,
                    Whirl::Collective => Dash::Solid,
                    Whirl::Forward => Dash::Dotted,
                },
            ),
            None => (m.label.as_str(), Dash::Solid),
        };
        let hue_rank = hues.iter().position(|h| *h == hue).unwrap_or_else(|| {
            hues.push(hue);
            hues.len() - 1
        });
        let color = PALETTE[hue_rank % PALETTE.len()];
        let name = if rank < on_scale.shown.len() {
            freq.series.push(
                Series::from_xy(&m.label, &s.values, &m.frequency_hz, mark)
                    .with_color(color)
                    .with_dash(dash),
            );
            m.label.clone()
        } else {
            off_scale_name(m)
        };
        damp.series.push(
            Series::from_xy(name, &s.values, &m.damping_ratio, mark)
                .with_color(color)
                .with_dash(dash),
        );
    }
    if on_scale.left_off > 0 {
        freq.notes.push(format!(
            "{} more mode(s) off scale, named in the legend",
            on_scale.left_off
        ));
    }
    (freq, damp)
}

/// A legend name for a mode the frequency panel does not draw, saying where it is: "torsion 1
/// (off scale, 9.83 Hz)" at its typical frequency, or "(not oscillating)" for real roots only.
fn off_scale_name(m: &TrackedMode) -> String {
    match typical(m) {
        Some(f) => format!("{} (off scale, {} Hz)", m.label, three_digits(f)),
        None => format!("{} (not oscillating)", m.label),
    }
}

/// A positive number to three significant digits, without an exponent (9.83, 0.512, 21.4).
fn three_digits(v: f64) -> String {
    let decimals = (2 - v.abs().log10().floor() as i32).clamp(0, 6) as usize;
    format!("{v:.decimals$}")
}

/// Frequency above, damping ratio below, one line per tracked mode; along rotor speed (rpm) a
/// Campbell diagram with the 1P and 3P excitation lines.
pub fn sweep(preset: &str, s: &TrackedSweep) -> Figure {
    let campbell = s.parameter == ROTOR_SPEED_KEY;
    let x_label = key_label(&s.parameter);
    let title = if campbell {
        format!("Campbell diagram — {preset}")
    } else {
        format!("Tracked modes over {} — {preset}", s.parameter)
    };
    let (mut freq, mut damp) = mode_panels(s, &x_label);
    freq.title = "(a) frequency".into();
    damp.title = "(b) damping ratio ζ = −σ/|λ|".into();
    if let Some(first) = s.failed.first() {
        damp.notes.push(format!(
            "{} of {} point(s) could not be solved (the first at {} = {}): gaps",
            s.failed.len(),
            s.values.len(),
            s.parameter,
            first.value
        ));
    }
    if let (true, Some((lo, hi))) = (campbell, finite_extent(&s.values)) {
        for n in [1.0, 3.0] {
            freq.guides.push(Guide::segment(
                (lo, n * lo / 60.0),
                (hi, n * hi / 60.0),
                format!("{n}P"),
            ));
        }
    }
    Figure::new(title).with_panel(freq).with_panel(damp)
}

/// The aeroelastic Campbell diagram along a turbine's operating schedule (docs/model.md §12.6), as
/// HAWCStab2 draws it: frequency and damping ratio of every tracked mode against wind speed, with
/// the 1P, 3P and 6P lines of the schedule's rotor speed (`rotor_speed_rpm`, one per wind speed).
pub fn campbell_along_schedule(preset: &str, s: &TrackedSweep, rotor_speed_rpm: &[f64]) -> Figure {
    let mut fig = sweep(preset, s);
    fig.title = format!("Aeroelastic Campbell diagram along the operating schedule — {preset}");
    let points: Vec<(f64, f64)> = s
        .values
        .iter()
        .zip(rotor_speed_rpm)
        .map(|(&u, &rpm)| (u, rpm))
        .filter(|(u, rpm)| u.is_finite() && rpm.is_finite())
        .collect();
    // From 0 Hz, so the harmonics of a slow rotor (1P near 0.1 Hz on a 15 MW) are on the axes.
    let top = fig.panels[0]
        .series
        .iter()
        .flat_map(|series| series.points.iter().map(|p| p.1))
        .chain(points.iter().map(|p| 6.0 * p.1 / 60.0))
        .filter(|f| f.is_finite())
        .fold(0.0f64, f64::max);
    if top > 0.0 {
        fig.panels[0].y_range = Some((0.0, 1.05 * top));
    }
    for n in [1.0, 3.0, 6.0] {
        for (k, w) in points.windows(2).enumerate() {
            // The label once, on the last piece of the line.
            let label = if k + 2 == points.len() {
                format!("{n}P")
            } else {
                String::new()
            };
            fig.panels[0].guides.push(Guide::segment(
                (w[0].0, n * w[0].1 / 60.0),
                (w[1].0, n * w[1].1 / 60.0),
                label,
            ));
        }
    }
    fig
}

/// Tip twist above, tip flap below, against time; a diverging run is marked where it stopped.
pub fn tip_response(preset: &str, aero: &str, r: &Response) -> Figure {
    let twist: Vec<(f64, f64)> =
        r.t.iter()
            .copied()
            .zip(r.tip_twist.iter().copied())
            .collect();
    let flap: Vec<(f64, f64)> =
        r.t.iter()
            .copied()
            .zip(r.tip_flap.iter().copied())
            .collect();
    let mut twist_panel = Panel::new("time t (s)", "tip twist φ(L,t) (rad)")
        .titled("(a) tip twist, toward feather")
        .with_series(Series::line("φ(L,t)", twist));
    let mut flap_panel = Panel::new("time t (s)", "tip flap u(L,t) (m)")
        .titled("(b) tip flap, downwind")
        .with_series(Series::line("u(L,t)", flap));
    if r.status == RunStatus::Diverging {
        let t_end = r.diverged_at.or_else(|| r.t.last().copied()).unwrap_or(0.0);
        let note = format!("DIVERGING: the response left the bounds at t = {t_end:.4} s");
        for panel in [&mut twist_panel, &mut flap_panel] {
            panel.guides.push(Guide::vertical(t_end, "run stopped"));
        }
        twist_panel.notes.push(note);
    }
    let whose = match r.rotor_blade {
        Some(b) => format!("Blade {b}'s tip response"),
        None => "Tip response".to_string(),
    };
    let linearised = if r.stall_linearised {
        " (stall linearised)"
    } else {
        ""
    };
    Figure::new(format!(
        "{whose} — {preset}, {aero} aerodynamics{linearised}"
    ))
    .with_panel(twist_panel)
    .with_panel(flap_panel)
}

/// The tracked sweep of a one-key `sweep` rebuilt from its output rows (grid order: the key's
/// values in order, every mode at each, or one `failed` row). Modes keep their first-appearance
/// order; a mode missing at a value is NaN there.
pub fn tracked_from_rows(key: &str, rows: &[SweepRow]) -> TrackedSweep {
    let mut values: Vec<f64> = Vec::new();
    let mut modes: Vec<TrackedMode> = Vec::new();
    let mut failed: Vec<FailedPoint> = Vec::new();
    for r in rows {
        let Some(&v) = r.values.last() else { continue };
        if values.last() != Some(&v) {
            values.push(v);
            for m in &mut modes {
                m.frequency_hz.push(f64::NAN);
                m.damping_ratio.push(f64::NAN);
                m.re.push(f64::NAN);
                m.second_re.push(f64::NAN);
            }
        }
        let n = values.len();
        let Some(label) = &r.mode else {
            failed.push(FailedPoint {
                index: n - 1,
                value: v,
                error: r.error.clone().unwrap_or_default(),
            });
            continue;
        };
        let idx = match modes.iter().position(|m| &m.label == label) {
            Some(i) => i,
            None => {
                modes.push(TrackedMode {
                    label: label.clone(),
                    frequency_hz: vec![f64::NAN; n],
                    damping_ratio: vec![f64::NAN; n],
                    re: vec![f64::NAN; n],
                    second_re: vec![f64::NAN; n],
                    // Grid rows do not carry the branch switches.
                    switches: Vec::new(),
                });
                modes.len() - 1
            }
        };
        let m = &mut modes[idx];
        m.frequency_hz[n - 1] = r.frequency_hz;
        m.damping_ratio[n - 1] = r.damping_ratio;
        m.re[n - 1] = r.re;
        m.second_re[n - 1] = r.second_re;
    }
    TrackedSweep {
        parameter: key.to_string(),
        values,
        modes,
        failed,
    }
}

/// A flutter search: damping ratio of every tracked mode along the key (ζ crosses zero where σ
/// does) with the boundary marked, and the frequencies below.
pub fn flutter(preset: &str, tracked: &TrackedSweep, search: &Search) -> Figure {
    let key = &tracked.parameter;
    let x_label = key_label(key);
    let unit = crate::preset::key_spec(key)
        .map(|k| k.unit)
        .unwrap_or_default();
    let (mut freq, mut damp) = mode_panels(tracked, &x_label);
    damp.title = "(a) damping ratio ζ = −σ/|λ| of the tracked modes".into();
    freq.title = "(b) frequency".into();
    let b = &search.boundary;
    if let Some(x) = b.critical {
        let kind = b.kind.map_or("flutter", BoundaryKind::word);
        let mut label = format!("{kind} at {}", with_unit(x, unit));
        if let Some(f) = b.frequency_hz {
            label.push_str(&format!(", {f:.4} Hz"));
        }
        if let Some(mode) = &b.mode {
            label.push_str(&format!(" ({mode})"));
        }
        damp.guides.push(Guide::vertical(x, "boundary"));
        freq.guides.push(Guide::vertical(x, "boundary"));
        damp.markers.push(Marker::new(x, 0.0, label));
        if let Some(f) = b.frequency_hz {
            freq.markers.push(Marker::new(x, f, ""));
        }
    }
    // The result on two lines, where it is said and what was found, to fit beside the legend.
    match search.message.split_once(": ") {
        Some((at, what)) => damp.notes.extend([format!("{at}:"), what.to_string()]),
        None => damp.notes.push(search.message.clone()),
    }
    clip_damping(&mut damp);
    Figure::new(format!("Flutter search along {key} — {preset}"))
        .with_panel(damp)
        .with_panel(freq)
}

/// The damping ratios a flutter figure's axis spans at most: the region around ζ = 0 where a
/// boundary is read. An overdamped root (ζ up to 3 on the IEA 15MW's flap 1) would squash it.
const ZETA_AXIS: (f64, f64) = (-0.25, 0.5);

/// Clip the damping panel's axis to [`ZETA_AXIS`] where its roots reach beyond, and mark each
/// root beyond at the edge it passes (one grey series, named in the legend and the axis label).
fn clip_damping(damp: &mut Panel) {
    let (bottom, top) = ZETA_AXIS;
    let zetas = damp
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .filter(|z| z.is_finite());
    let Some((lo, hi)) = finite_extent(&zetas.collect::<Vec<f64>>()) else {
        return;
    };
    if lo >= bottom && hi <= top {
        return;
    }
    let edges: Vec<(f64, f64)> = damp
        .series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|p| p.1.is_finite() && !(bottom..=top).contains(&p.1))
        .map(|&(x, z)| (x, z.clamp(bottom, top)))
        .collect();
    let (lo, hi) = (lo.max(bottom), hi.min(top));
    let pad = 0.05 * (hi - lo);
    damp.y_range = Some((lo - pad, hi + pad));
    damp.y_label = "damping ratio ζ (–), clipped".into();
    let name = format!("ζ beyond {bottom} … {top}, at edge");
    damp.series.insert(
        0,
        Series::points(name, edges).with_color(super::figure::GUIDE_GREY),
    );
}

fn with_unit(v: f64, unit: &str) -> String {
    let num = format!("{v:.6}");
    let num = num.trim_end_matches('0').trim_end_matches('.');
    if unit.is_empty() {
        num.to_string()
    } else {
        format!("{num} {unit}")
    }
}

/// C22, C23 and C33 of the layup section over a grid of one key (like the paper's Table 1).
pub fn section_grid(preset: &str, key: &str, values: &[f64], sections: &[LayupSection]) -> Figure {
    let x_label = key_label(key);
    let pick = |f: fn(&LayupSection) -> f64| -> Vec<(f64, f64)> {
        values
            .iter()
            .zip(sections)
            .map(|(&v, s)| (v, f(s)))
            .collect()
    };
    let panel = |title: &str, y: &str, name: &str, pts: Vec<(f64, f64)>| {
        Panel::new(&x_label, y)
            .titled(title)
            .with_series(Series::line_points(name, pts))
    };
    Figure::new(format!("Layup section stiffness over {key} — {preset}"))
        .with_panel(panel(
            "(a) torsion",
            "C22 (N·m²)",
            "C22",
            pick(|s| s.props.c22),
        ))
        .with_panel(panel(
            "(b) bending–twist coupling",
            "C23 (N·m²)",
            "C23",
            pick(|s| s.props.c23),
        ))
        .with_panel(panel(
            "(c) flap bending",
            "C33 (N·m²)",
            "C33",
            pick(|s| s.props.c33),
        ))
}

/// Aerodynamic power and thrust over a grid of one key (`operating --vary`, e.g. the power curve
/// along the operating schedule).
pub fn power_curve(
    preset: &str,
    key: &str,
    values: &[f64],
    power: &[f64],
    thrust: &[f64],
) -> Figure {
    let x_label = key_label(key);
    let series = |ys: &[f64], scale: f64| -> Vec<(f64, f64)> {
        values
            .iter()
            .zip(ys)
            .map(|(&x, &y)| (x, y * scale))
            .collect()
    };
    Figure::new(format!("Steady operation over {key} — {preset}"))
        .with_panel(
            Panel::new(&x_label, "power (MW)")
                .titled("(a) aerodynamic power")
                .with_series(Series::line_points("power", series(power, 1e-6))),
        )
        .with_panel(
            Panel::new(&x_label, "thrust (kN)")
                .titled("(b) rotor thrust")
                .with_series(Series::line_points("thrust", series(thrust, 1e-3))),
        )
}

/// A layup section's mesh at span fraction `eta`: every element's outline, coloured by its
/// material (`materials` names them in the mesh's order), drawn in the chord frame (x₂ toward
/// the trailing edge to the right, x₁ toward the suction side up) on equal scales.
pub fn layup_section(preset: &str, eta: f64, mesh: &Mesh, materials: &[&str]) -> Figure {
    let mut panel = Panel::new(
        "x₂, toward the trailing edge (m)",
        "x₁, toward the suction side (m)",
    );
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for (m, name) in materials.iter().enumerate() {
        // One series per material: each element's outline closed, elements apart by a gap
        // (NaN) so that the line does not run from one to the next.
        let mut points = Vec::new();
        for e in mesh.elements.iter().filter(|e| e.ply.material == m) {
            // A collapsed quadrilateral (a layer's end) drawn as its triangle: a line that
            // doubles back on itself draws a spike at the turn.
            let mut nodes = e.nodes.to_vec();
            nodes.dedup();
            if nodes.len() > 1 && nodes.first() == nodes.last() {
                nodes.pop();
            }
            for &n in nodes.iter().chain(nodes.first()) {
                let (x, y) = (mesh.nodes[n][1], mesh.nodes[n][0]);
                lo = [lo[0].min(x), lo[1].min(y)];
                hi = [hi[0].max(x), hi[1].max(y)];
                points.push((x, y));
            }
            points.push((f64::NAN, f64::NAN));
        }
        if !points.is_empty() {
            // Thin: a wide line's joins spike where a thin element's outline turns back.
            panel = panel.with_series(
                Series::line(name.to_string(), points)
                    .with_color(PALETTE[m % PALETTE.len()])
                    .with_width(1),
            );
        }
    }
    // Equal scales: the wider extent sets both ranges, as the figure is drawn 3:2.
    let half = ((hi[0] - lo[0]) / 2.0).max(0.75 * (hi[1] - lo[1])) * 1.05;
    let mid = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
    let panel = panel
        .with_x_range(mid[0] - half, mid[0] + half)
        .with_y_range(mid[1] - half / 1.5, mid[1] + half / 1.5);
    Figure::new(format!(
        "{preset}: the section at {:.1} % span, meshed from its layup",
        100.0 * eta
    ))
    .with_panel(panel)
}
