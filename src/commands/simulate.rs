use crate::error::{Error, Result};
use crate::preset::Preset;
use std::path::Path;
pub fn run(_p: &Preset, _json: bool, _csv: bool, _plot: Option<&Path>) -> Result<()> { Err(Error::usage("simulate: not available yet")) }
