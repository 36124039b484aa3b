//! `flutterscope presets`: the built-in presets with one-line descriptions, or one preset in full
//! (`--show`), defaults included.

use crate::error::Result;
use crate::preset::{Preset, BUILTIN};
use serde::Serialize;

#[derive(Serialize)]
struct Entry {
    name: &'static str,
    description: String,
    aero_model: &'static str,
}

pub fn run(json: bool) -> Result<()> {
    let mut entries = Vec::new();
    for (name, _) in BUILTIN {
        let p = Preset::load(name, &[])?;
        entries.push(Entry {
            name,
            description: p.meta.description.clone(),
            aero_model: p.aero.model.name(),
        });
    }
    if json {
        return super::print_json(&serde_json::json!({ "presets": entries }));
    }
    let width = entries.iter().map(|e| e.name.len()).max().unwrap_or(0);
    let mut out = String::new();
    for e in &entries {
        out += &format!("{:width$}  {}\n", e.name, e.description);
    }
    out += "\nUse one with --preset NAME, or --preset path/to/file.toml for your own.\n";
    super::print_text(&out)
}

/// One preset as TOML with every key, the defaults it leaves out included.
pub fn show(name: &str, overrides: &[String]) -> Result<()> {
    let p = crate::cli::load_preset(name, overrides)?;
    p.overrides_act(overrides)?;
    super::print_text(&format!(
        "# {} (every key, defaults included)\n{}",
        p.origin,
        p.to_toml()
    ))
}
