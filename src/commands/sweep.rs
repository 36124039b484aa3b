use crate::error::{Error, Result};
use crate::preset::Preset;
use std::path::Path;
pub fn run(_p: &Preset, _vary: &[String], _json: bool, _shard: Option<&str>, _plot: Option<&Path>) -> Result<()> { Err(Error::usage("sweep: not available yet")) }
