use crate::cli::{DisplayArgs, PresetArgs};
use crate::error::{Error, Result};
pub fn run(_p: &PresetArgs, _d: &DisplayArgs, _fps: u32) -> Result<()> {
    Err(Error::usage("tui: not available yet"))
}
