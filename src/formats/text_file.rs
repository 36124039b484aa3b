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

/// The folder a model's relative paths resolve against (a HAWC2 model's root: the folder it is
/// run from), held as a name inside it, since a [`TextFile`] resolves names against its own
/// directory.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelRoot<F> {
    inside: F,
}

/// The name [`ModelRoot`] holds inside its folder; no file of that name is ever read.
pub const ROOT_ANCHOR: &str = "(model root)";

impl<F: TextFile> ModelRoot<F> {
    /// The folder above the one `file` is in: a HAWC2 model's root for its `htc/` folder.
    pub fn above_folder_of(file: &F) -> ModelRoot<F> {
        ModelRoot {
            inside: file.sibling(&format!("../{ROOT_ANCHOR}")),
        }
    }

    /// The folder of `anchor`, a name [`ROOT_ANCHOR`] inside it.
    pub fn of_anchor(anchor: F) -> ModelRoot<F> {
        ModelRoot { inside: anchor }
    }

    /// The file `name` names, relative to the root.
    pub fn file(&self, name: &str) -> F {
        self.inside.sibling(name)
    }

    /// The folder, as errors name it.
    pub fn display(&self) -> String {
        self.inside.sibling(".").display()
    }
}
