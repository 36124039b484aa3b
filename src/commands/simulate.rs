//! `flutterscope simulate`: tip twist and flap over time.

use crate::analysis::simulate::RunStatus;

use crate::analysis::response::{simulate, Response};
use crate::error::Result;
use crate::preset::ValidPreset;
use std::io::Write;
use std::path::Path;

pub fn run(p: &ValidPreset, json: bool, csv: bool, plot: Option<&Path>) -> Result<()> {
    if let Some(path) = plot {
        crate::plot::format_for(path)?;
    }
    let r = simulate(p).map_err(|e| e.at(p.operating_point()))?;
    if json {
        super::print_json(&r)?;
    } else if csv {
        write_csv(&r)?;
    } else {
        super::print_text(&summary(p, &r))?;
    }
    if let Some(path) = plot {
        let fig =
            crate::plot::from_results::tip_response(p.display_name(), p.aero.model.name(), &r);
        crate::plot::write(&fig, path)?;
        eprintln!("plot written to {}", path.display());
    }
    Ok(())
}

fn write_csv(r: &Response) -> Result<()> {
    let io = super::stdout_error;
    let mut out = std::io::BufWriter::new(super::stdout()?);
    writeln!(out, "t,tip_twist,tip_flap").map_err(io)?;
    for ((t, a), u) in r.t.iter().zip(&r.tip_twist).zip(&r.tip_flap) {
        writeln!(out, "{t},{a},{u}").map_err(io)?;
    }
    out.flush().map_err(io)
}

/// Start, end, extremes and status in a few lines.
pub fn summary(p: &ValidPreset, r: &Response) -> String {
    let extreme = |v: &[f64]| {
        v.iter()
            .fold(0.0f64, |m, x| if x.abs() > m.abs() { *x } else { m })
    };
    let last = |v: &[f64]| v.last().copied().unwrap_or(0.0);
    let mut out = format!(
        "{} — {}{} aerodynamics{}, start {:?}, {} samples over {:.3} s\n",
        p.display_name(),
        match r.rotor_blade {
            Some(b) => format!("blade {b}'s tip on the {}, ", p.turbine.model.name()),
            None => String::new(),
        },
        p.aero.model.name(),
        if r.stall_linearised {
            " (stall linearised about the equilibrium)"
        } else {
            ""
        },
        p.simulation.start,
        r.t.len(),
        r.t.last().copied().unwrap_or(0.0)
    );
    out += &format!(
        "tip twist: final {:.6e} rad ({:.4}°), largest {:.6e} rad\n",
        last(&r.tip_twist),
        last(&r.tip_twist).to_degrees(),
        extreme(&r.tip_twist)
    );
    out += &format!(
        "tip flap:  final {:.6e} m, largest {:.6e} m\n",
        last(&r.tip_flap),
        extreme(&r.tip_flap)
    );
    out += &match (r.status, r.diverged_at) {
        (RunStatus::Diverging, Some(t)) => {
            format!("status: DIVERGING — the response left the bounds at t = {t:.4} s\n")
        }
        _ => "status: ok\n".to_string(),
    };
    out
}
