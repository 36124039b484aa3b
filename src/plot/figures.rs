//! Figures for the commands' `--plot FILE`: each function lays out one result type. They only
//! arrange numbers the engine computed (the one derived quantity, the n-per-revolution lines
//! `f = nΩ/60` on a Campbell diagram, is a unit conversion).

use super::{Figure, Guide, Panel, Series};
use crate::analysis::simulate::{RunStatus, TipSample};
use crate::analysis::sweep::TrackedSweep;
use crate::physics::laminate::LayupSection;

/// "key (unit)" for a preset key, or the bare key when it has no unit or is unknown.
pub fn key_label(key: &str) -> String {
    match crate::preset::key_spec(key) {
        Ok(spec) if !spec.unit.is_empty() => format!("{key} ({})", spec.unit),
        _ => key.to_string(),
    }
}

/// The rotor-speed key: a sweep along it is drawn as a Campbell diagram.
pub const ROTOR_SPEED_KEY: &str = "operating.rotor_speed";

fn finite_extent(values: &[f64]) -> Option<(f64, f64)> {
    let mut it = values.iter().copied().filter(|v| v.is_finite());
    let first = it.next()?;
    Some(it.fold((first, first), |(lo, hi), v| (lo.min(v), hi.max(v))))
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
    let mut freq = Panel::new(&x_label, "frequency (Hz)").titled("(a) frequency");
    let mut damp = Panel::new(&x_label, "damping ratio ζ (–)")
        .titled("(b) damping ratio ζ = −σ/|λ|")
        .with_guide(Guide::horizontal(0.0, "ζ = 0"));
    for m in &s.modes {
        freq.series.push(Series::from_xy(
            &m.label,
            &s.values,
            &m.frequency_hz,
            super::Mark::Line,
        ));
        damp.series.push(Series::from_xy(
            &m.label,
            &s.values,
            &m.damping_ratio,
            super::Mark::Line,
        ));
    }
    if s.values.len() < 12 {
        for series in freq.series.iter_mut().chain(damp.series.iter_mut()) {
            series.style.mark = super::Mark::LinePoints;
        }
    }
    // Fit the frequency axis to the modes; the excitation lines are clipped to it.
    damp.legend = false;
    if campbell {
        if let Some((lo, hi)) = finite_extent(&s.values) {
            for n in [1.0, 3.0] {
                freq.guides.push(Guide::segment(
                    (lo, n * lo / 60.0),
                    (hi, n * hi / 60.0),
                    format!("{n}P"),
                ));
            }
        }
    }
    Figure::new(title).with_panel(freq).with_panel(damp)
}

/// Tip twist above, tip flap below, against time.
pub fn tip_response(preset: &str, samples: &[TipSample], status: RunStatus) -> Figure {
    let twist: Vec<(f64, f64)> = samples.iter().map(|s| (s.t, s.tip_twist)).collect();
    let flap: Vec<(f64, f64)> = samples.iter().map(|s| (s.t, s.tip_flap)).collect();
    let mut twist_panel = Panel::new("time t (s)", "tip twist φ(L,t) (rad)")
        .titled("(a) tip twist, toward feather")
        .with_series(Series::line("φ(L,t)", twist));
    let flap_panel = Panel::new("time t (s)", "tip flap u(L,t) (m)")
        .titled("(b) tip flap, downwind")
        .with_series(Series::line("u(L,t)", flap));
    if status == RunStatus::Diverging {
        let t_end = samples.last().map(|s| s.t).unwrap_or(0.0);
        twist_panel = twist_panel.with_note(format!(
            "diverging: the response grew past the bound; run stopped at t = {t_end:.4} s"
        ));
    }
    Figure::new(format!("Tip response — {preset}"))
        .with_panel(twist_panel)
        .with_panel(flap_panel)
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
