use crate::error::{Error, Result};
use crate::preset::Preset;
use std::path::Path;
pub fn run(_p: &Preset, _key: &str, _from: f64, _to: f64, _points: usize, _json: bool, _plot: Option<&Path>) -> Result<()> { Err(Error::usage("flutter: not available yet")) }
