//! `flutterscope flutter`: the flutter (or divergence) boundary along one key.

use crate::analysis::flutter::flutter_search;
use crate::analysis::sweep::track;
use crate::error::Result;
use crate::preset::ValidPreset;
use std::path::Path;

pub fn run(
    p: &ValidPreset,
    key: &str,
    from: f64,
    to: f64,
    points: usize,
    json: bool,
    plot: Option<&Path>,
) -> Result<()> {
    if let Some(path) = plot {
        crate::plot::format_for(path)?;
    }
    let search = flutter_search(p, key, from, to, points)?;
    if json {
        super::print_json(&search)?;
    } else {
        println!("{}: {}", p.display_name(), search.message);
    }
    if let Some(path) = plot {
        // The tracked modes on the search grid: damping ratio and frequency along the key.
        let grid: Vec<f64> = (0..points)
            .map(|i| from + (to - from) * i as f64 / (points - 1) as f64)
            .collect();
        let tracked = track(p, key, &grid)?;
        let fig = crate::plot::from_results::flutter(p.display_name(), &tracked, &search);
        crate::plot::write(&fig, path)?;
        eprintln!("plot written to {}", path.display());
    }
    Ok(())
}
