//! A preset's HAWC2 model (`blade.htc_file`, docs/model.md §11.6): the htc file, the body and the
//! root folder its paths resolve against, as the physics reads them.

use crate::formats::text_file::{ModelRoot, ROOT_ANCHOR};
use crate::physics::blade::source::HtcFiles;
use crate::preset::files::{BladeFile, FileBase};
use crate::preset::schema::blade::Blade;

/// The htc blade `blade` names, its files resolved from `base` (the preset's directory): the
/// root is `blade.htc_root` when given, else the folder above the htc file's (HAWC2 is run from
/// the model's folder, the one holding `htc/`).
pub fn htc_files(blade: &Blade, base: &FileBase) -> HtcFiles<BladeFile> {
    let htc = base.resolve(&blade.htc_file);
    let root = match blade.htc_root.trim().trim_end_matches(['/', '\\']) {
        "" => ModelRoot::above_folder_of(&htc),
        folder => ModelRoot::of_anchor(base.resolve(&format!("{folder}/{ROOT_ANCHOR}"))),
    };
    HtcFiles {
        htc,
        root,
        body: blade.htc_body.clone(),
    }
}
