//! `flutterscope flutter`: the flutter (or divergence) boundary along one key.

use crate::analysis::flutter::flutter_search;
use crate::error::{Error, Result};
use crate::preset::Preset;
use std::path::Path;

pub fn run(
    p: &Preset,
    key: &str,
    from: f64,
    to: f64,
    points: usize,
    json: bool,
    plot: Option<&Path>,
) -> Result<()> {
    if plot.is_some() {
        return Err(Error::usage("flutter --plot: not available yet"));
    }
    let search = flutter_search(p, key, from, to, points)?;
    if json {
        return super::print_json(&search.boundary);
    }
    println!("{}: {}", p.display_name(), search.message);
    Ok(())
}
