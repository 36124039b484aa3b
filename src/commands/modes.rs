//! `flutterscope modes`: coupled natural frequencies of the blade structure (docs/model.md §3–§4), no
//! aerodynamics, at the preset's rotor speed.

use crate::error::Result;
use crate::physics::structure::{assemble, NaturalMode};
use crate::preset::{Form, ValidPreset};

pub fn run(p: &ValidPreset, json: bool) -> Result<()> {
    // The structure alone depends on the rotor speed only, of the operating point.
    let at = || {
        format!(
            "{} at operating.rotor_speed = {} rpm",
            p.display_name(),
            p.operating.rotor_speed
        )
    };
    let modes = assemble(p)
        .and_then(|model| model.natural_modes())
        .map_err(|e| e.at(at()))?;
    if json {
        return super::print_json(&serde_json::json!({ "modes": modes }));
    }
    super::print_text(&render(p, &modes))
}

/// The human-readable table.
fn render(p: &ValidPreset, modes: &[NaturalMode]) -> String {
    let form = match p.structure.form {
        Form::Weak => "weak",
        Form::Strong => "strong",
    };
    let mut out = format!(
        "{}: natural modes at {} rpm, N = {} per field, {} form\n\n",
        p.display_name(),
        p.operating.rotor_speed,
        p.structure.modes,
        form
    );
    out.push_str(&format!(
        "{:>4}  {:<12} {:>14}  {:>13}\n",
        "#", "mode", "frequency (Hz)", "torsion share"
    ));
    for (k, m) in modes.iter().enumerate() {
        out.push_str(&format!(
            "{:>4}  {:<12} {:>14}  {:>13.4}\n",
            k + 1,
            m.label,
            format_hz(m.frequency_hz),
            m.torsion_share
        ));
    }
    out
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
