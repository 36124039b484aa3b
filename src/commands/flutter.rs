//! `flutterscope flutter`: the flutter (or divergence) boundary along one key.

use crate::analysis::flutter::{flutter_search, key_range};
use crate::analysis::flutter::{BoundaryKind, Search};
use crate::analysis::sweep::named_modes;
use crate::error::Result;
use crate::preset::ValidPreset;
use serde::Serialize;
use std::path::Path;

/// The search as `--json` prints it, with the overspeed margin when it is one.
#[derive(Serialize)]
struct Report<'a> {
    #[serde(flatten)]
    search: &'a Search,
    #[serde(skip_serializing_if = "Option::is_none")]
    rated_rotor_speed_rpm: Option<f64>,
    /// Critical rotor speed / `operating.rated_rotor_speed`.
    #[serde(skip_serializing_if = "Option::is_none")]
    rated_multiple: Option<f64>,
}

/// The critical rotor speed as a multiple of the rated one, when the search is along the rotor
/// speed and the preset states its rated speed (`operating.rated_rotor_speed` > 0).
fn overspeed_margin(p: &ValidPreset, key: &str, critical: Option<f64>) -> Option<f64> {
    let rated = p.operating.rated_rotor_speed;
    (key == "operating.rotor_speed" && rated > 0.0)
        .then_some(critical)
        .flatten()
        .map(|c| c / rated)
}

/// The search range: as given, else from the preset's value of `key` (the schedule's, for a
/// scheduled rotor speed or pitch) to the top of the key's range ([`key_range`]).
fn search_range(
    p: &ValidPreset,
    key: &str,
    from: Option<f64>,
    to: Option<f64>,
) -> Result<(f64, f64)> {
    let from = match from {
        Some(v) => v,
        None => crate::model::operating::on_schedule(p)?.get(key)?,
    };
    let to = match to {
        Some(v) => v,
        // An unknown key is an error, not the endless range `key_range` gives it.
        None => p.get(key).map(|_| key_range(p, key).1)?,
    };
    Ok((from, to))
}

pub fn run(
    p: &ValidPreset,
    key: &str,
    from: Option<f64>,
    to: Option<f64>,
    points: usize,
    json: bool,
    plot: Option<&Path>,
) -> Result<()> {
    if let Some(path) = plot {
        crate::plot::format_for(path)?;
    }
    let given = from.is_some() && to.is_some();
    let (from, to) = search_range(p, key, from, to)?;
    if !given {
        eprintln!("searching {key} from {from} to {to} (--from/--to for another range)");
    }
    let search = flutter_search(p, key, from, to, points)?;
    let overspeed = overspeed_margin(p, key, search.boundary.critical);
    if json {
        super::print_json(&Report {
            search: &search,
            rated_rotor_speed_rpm: overspeed.map(|_| p.operating.rated_rotor_speed),
            rated_multiple: overspeed,
        })?;
    } else {
        let mut out = format!("{}: {}\n", p.display_name(), search.message);
        if let Some(multiple) = overspeed {
            // Only a structural boundary above rated is a margin against overspeed.
            let what = if multiple >= 1.0 && search.boundary.kind != Some(BoundaryKind::Runaway) {
                "overspeed margin: "
            } else {
                "at "
            };
            out += &format!(
                "{what}{multiple:.3}× the rated rotor speed ({} rpm, \
                 operating.rated_rotor_speed)\n",
                p.operating.rated_rotor_speed
            );
        }
        super::print_text(&out)?;
    }
    if let Some(path) = plot {
        // The modes on the search's own grid, named as at each point (the figure draws names,
        // not branch switches, so nothing is re-solved for it).
        let tracked = named_modes(key, &search.grid, &search.results);
        let fig = crate::plot::from_results::flutter(p.display_name(), &tracked, &search);
        crate::plot::write(&fig, path)?;
        eprintln!("plot written to {}", path.display());
    }
    Ok(())
}
