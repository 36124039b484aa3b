use crate::error::{Error, Result};
use crate::preset::Preset;
pub fn run(_p: &Preset, _json: bool) -> Result<()> {
    Err(Error::usage("modes: not available yet"))
}
