use crate::error::{Error, Result};
use crate::preset::Preset;
use std::path::Path;
pub fn run(_p: &Preset, _vary: Option<&str>, _json: bool, _plot: Option<&Path>) -> Result<()> {
    Err(Error::usage("section: not available yet"))
}
