//! The parameter catalogue: the rows of the parameters pane ([`PARAMS`]), which of them a preset
//! is offered, their slider ranges, fine and coarse steps, and how their values are shown.

use crate::analysis::campbell::ROTOR_SPEED_KEY;
use crate::preset::rules::not_acting;
use crate::preset::{key_spec, ValidPreset};

/// The bend–twist coupling α: a number without unit, shown as `α -0.11`.
pub const COUPLING_KEY: &str = "blade.bend_twist_coupling";

/// How a parameter row is changed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParamKind {
    /// A numeric preset key with fine and coarse steps and display decimals (as [`steps`] and
    /// [`shown_decimals`] apply them).
    Number {
        key: &'static str,
        step: f64,
        coarse: f64,
        decimals: usize,
        /// Whether the background boundary search runs along this key when it is selected.
        boundary: bool,
    },
    /// `aero.model`, cycled.
    Aero,
}

/// One row of the parameters pane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Param {
    pub label: &'static str,
    pub kind: ParamKind,
}

const fn number(
    label: &'static str,
    key: &'static str,
    step: f64,
    coarse: f64,
    decimals: usize,
    boundary: bool,
) -> Param {
    Param {
        label,
        kind: ParamKind::Number {
            key,
            step,
            coarse,
            decimals,
            boundary,
        },
    }
}

/// The row of `PARAMS` that varies `key`, if it is offered for `p` (else the first row that is).
pub fn param_index(p: &ValidPreset, key: &str) -> usize {
    PARAMS
        .iter()
        .position(|r| {
            offered(p, r) && matches!(r.kind, ParamKind::Number { key: k, .. } if k == key)
        })
        .or_else(|| PARAMS.iter().position(|r| offered(p, r)))
        .unwrap_or(0)
}

/// Whether the parameters pane offers `param` for `p`: a knob that can change nothing for the
/// preset's blade is left out, as `--set` and `--vary` refuse it ([`not_acting`]). Knobs that
/// only wait for another setting the explorer can change (wind speed without aerodynamics) stay,
/// dimmed by the pane.
pub fn offered(p: &ValidPreset, param: &Param) -> bool {
    match param.kind {
        ParamKind::Number { key, .. } => not_acting(p, key).is_none(),
        ParamKind::Aero => true,
    }
}

/// The rows of `PARAMS` offered for `p`, in pane order.
pub fn offered_rows(p: &ValidPreset) -> Vec<usize> {
    (0..PARAMS.len())
        .filter(|&i| offered(p, &PARAMS[i]))
        .collect()
}

/// The parameters the explorer varies, in pane order.
pub static PARAMS: &[Param] = &[
    number("ply angle", "section.ply_angle", 1.0, 5.0, 1, true),
    number(
        "bend–twist α",
        "blade.bend_twist_coupling",
        0.01,
        0.05,
        2,
        true,
    ),
    number("wind speed", "operating.wind_speed", 0.5, 5.0, 1, true),
    number("tunnel speed", "operating.tunnel_speed", 1.0, 10.0, 1, true),
    number("rotor speed", "operating.rotor_speed", 1.0, 10.0, 0, true),
    number("pitch", "operating.pitch", 0.5, 5.0, 1, true),
    Param {
        label: "aero model",
        kind: ParamKind::Aero,
    },
    number("modes N", "structure.modes", 1.0, 5.0, 0, false),
    number(
        "loss factor",
        "structure.loss_factor",
        0.005,
        0.05,
        3,
        false,
    ),
];

/// Rotor speeds below this (rpm) are shown to 0.01 rpm: a turbine rotor turns at 5–15 rpm,
/// where a whole rpm is 7–20 % of its rated speed.
pub const FINE_ROTOR_SPEED_BELOW: f64 = 30.0;

/// The fine and coarse steps of `param` on `p`: the row's own, except the rotor speed of a preset
/// with a rated rotor speed, which steps by 1 % and 10 % of it (so a step is a fixed share of
/// rated, as the overspeed margin is quoted). The paper's blades give none and step by the
/// row's 1 and 10 rpm.
pub fn steps(p: &ValidPreset, param: &Param) -> Option<(f64, f64)> {
    let ParamKind::Number {
        key, step, coarse, ..
    } = param.kind
    else {
        return None;
    };
    let rated = p.operating.rated_rotor_speed;
    Some(if key == ROTOR_SPEED_KEY && rated > 0.0 {
        (0.01 * rated, 0.1 * rated)
    } else {
        (step, coarse)
    })
}

/// The decimals a value of `key` is shown with: its row's, except rotor speeds below
/// [`FINE_ROTOR_SPEED_BELOW`], shown to 0.01 rpm.
pub fn shown_decimals(key: &str, v: f64) -> usize {
    if key == ROTOR_SPEED_KEY && v.abs() < FINE_ROTOR_SPEED_BELOW {
        return 2;
    }
    PARAMS
        .iter()
        .find_map(|p| match p.kind {
            ParamKind::Number {
                key: k, decimals, ..
            } if k == key => Some(decimals),
            _ => None,
        })
        .unwrap_or(2)
}

/// `v` as the parameters pane shows a value of `key`: its decimals and unit (`7.56 rpm`).
pub fn value_text(key: &str, v: f64) -> String {
    let (u, d) = (unit(key), shown_decimals(key, v));
    if u.is_empty() {
        format!("{v:.d$}")
    } else {
        format!("{v:.d$} {u}")
    }
}

/// The unit of a numeric key.
pub fn unit(key: &str) -> &'static str {
    key_spec(key).map(|s| s.unit).unwrap_or("")
}
