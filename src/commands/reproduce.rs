use crate::cli::Reproduction;
use crate::error::{Error, Result};
use std::path::Path;
pub fn run(_what: Reproduction, _json: bool, _plot: Option<&Path>) -> Result<()> {
    Err(Error::usage("reproduce: not available yet"))
}
