//! `flutterscope eigen`: eigenvalues of the linearised aeroelastic system and the verdict.

use crate::analysis::eigen::{analyse, Stability, Verdict};
use crate::analysis::flutter::RUNAWAY;
use crate::analysis::mode::Mode;
use crate::error::Result;
use crate::preset::ValidPreset;

pub fn run(p: &ValidPreset, json: bool) -> Result<()> {
    // The header names the rotor speed and pitch the turbine runs at: its schedule's.
    let scheduled = crate::model::operating::on_schedule(p)?;
    let p = &scheduled;
    let s = analyse(p).map_err(|e| e.at(p.operating_point()))?;
    if json {
        return super::print_json(&s);
    }
    super::print_text(&render(p, &s))
}

/// The text report: a table of the structural modes, the aero-lag roots apart, the verdict.
pub fn render(p: &ValidPreset, s: &Stability) -> String {
    let mut out = format!(
        "{} — aero model {}, U = {} m/s, Ω = {} rpm, V_t = {} m/s, pitch {}°\n\n",
        p.display_name(),
        p.aero.model.name(),
        p.operating.wind_speed,
        p.operating.rotor_speed,
        p.operating.tunnel_speed,
        p.operating.pitch
    );
    out += &table(&s.eigenvalues);
    if !s.aero_lags.is_empty() {
        out += &format!("\naerodynamic lag roots ({}):\n", s.aero_lags.len());
        out += &table(&s.aero_lags);
    }
    out += "\n";
    out += &match (s.verdict, s.critical()) {
        // Neutral roots (σ = 0 within the neutral tolerance: frozen aero states in still air,
        // an undamped structure) are stable but do not decay: say which.
        (Verdict::Stable, Some(m)) if m.re >= 0.0 => format!(
            "STABLE: no root grows; the least damped is neutral ({}, σ = {:.1e} 1/s, within the \
             neutral tolerance)\n",
            m.label, m.re
        ),
        (Verdict::Stable, Some(m)) => format!(
            "STABLE: every root has σ < 0 (least damped: {}, σ = {:.4} 1/s, ζ = {:.4})\n",
            m.label, m.re, m.damping_ratio
        ),
        (Verdict::Stable, None) => "STABLE: no roots\n".to_string(),
        (Verdict::Flutter, Some(m)) => format!(
            "UNSTABLE (flutter): {} grows at σ = {:.4} 1/s, oscillating at {:.4} Hz\n",
            m.described(),
            m.re,
            m.frequency_hz
        ),
        (Verdict::Divergence, Some(m)) => format!(
            "UNSTABLE (static divergence): {} grows at σ = {:.4} 1/s without oscillating\n",
            m.described(),
            m.re
        ),
        (Verdict::Runaway, Some(m)) => format!(
            "UNSTABLE (rotor speed runaway): {} grows at σ = {:.4} 1/s: {RUNAWAY}\n",
            m.label, m.re
        ),
        (_, None) => "UNSTABLE\n".to_string(),
    };
    out
}

/// One row per root: the root, its structural share, and for a structural mode the in-vacuo
/// frequency of the mode it is named after, the shares of its motion, and an overdamped mode's
/// second decay rate.
fn table(modes: &[Mode]) -> String {
    // As wide as the longest name (`collective torsion 2` on a rotor), at least 14.
    let w = modes
        .iter()
        .map(|m| m.label.chars().count())
        .fold(14, usize::max);
    let mut out = format!(
        "{:<w$} {:>13} {:>13} {:>12} {:>10} {:>7} {:>11}  {:>5} {:>5} {:>5}\n",
        "mode",
        "σ (1/s)",
        "ω (rad/s)",
        "f (Hz)",
        "ζ",
        "struct",
        "in vacuo",
        "flap",
        "edge",
        "twist"
    );
    for m in modes {
        out += &format!(
            "{:<w$} {:>13.5} {:>13.5} {:>12.5} {:>10.5} {:>7.3}",
            m.label, m.re, m.im, m.frequency_hz, m.damping_ratio, m.structural_share
        );
        if let Some(f0) = m.in_vacuo_hz {
            out += &format!(
                " {:>11.5}  {:>5.3} {:>5.3} {:>5.3}",
                f0, m.shares.flap, m.shares.edge, m.shares.twist
            );
        }
        match m.second_re {
            // A rigid-body pair (a free rotor's azimuth and speed) is neutral, not overdamped.
            Some(s2) if m.damping_ratio == 0.0 => {
                out += &format!("  rigid body, second root σ = {s2:.5}")
            }
            Some(s2) => out += &format!("  overdamped, second root σ = {s2:.5}"),
            None => {}
        }
        out += "\n";
    }
    out
}
