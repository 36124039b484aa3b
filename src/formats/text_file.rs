//! A text file that an input names: the readers take any [`TextFile`], so the same reader serves a
//! file on disk and one built into the binary (the built-in presets' blade files).

use crate::error::Result;

pub trait TextFile: Sized {
    /// The name errors give.
    fn display(&self) -> String;
    /// The whole text.
    fn read(&self) -> Result<String>;
    /// The file `name` names from inside this one, resolved against this file's directory (as
    /// BeamDyn resolves its `BldFile`).
    fn sibling(&self, name: &str) -> Self;
}

/// A file on disk, read through the size-capped reader (`formats::text::read_text`).
#[derive(Debug, Clone, PartialEq)]
pub struct DiskFile(pub std::path::PathBuf);

impl TextFile for DiskFile {
    fn display(&self) -> String {
        self.0.display().to_string()
    }
    fn read(&self) -> Result<String> {
        super::text::read_text(&self.0)
    }
    fn sibling(&self, name: &str) -> DiskFile {
        let dir = self.0.parent().unwrap_or_else(|| std::path::Path::new(""));
        DiskFile(dir.join(name))
    }
}
