use crate::cli::{MarkerKind, PresetArgs, ViewKind};
use crate::error::{Error, Result};
pub fn run(_p: &PresetArgs, _size: &str, _view: ViewKind, _marker: MarkerKind) -> Result<()> {
    Err(Error::usage("snapshot: not available yet"))
}
