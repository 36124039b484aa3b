//! The files a preset refers to (`blade.file`, `aero.*` files, `operating.schedule_file`) and
//! where they resolve. A preset file's relative
//! paths resolve against its own directory, as BeamDyn resolves its `BldFile`; a built-in
//! preset's against the blade files built into the binary ([`BUILTIN_FILES`]), so the binary
//! runs from any directory; text given without a location against the working directory.

use crate::error::{Error, Result};
use crate::formats::text_file::DiskFile;
pub use crate::formats::text_file::TextFile;
use std::path::PathBuf;

/// The blade files the built-in presets use, embedded as their presets are, by their path under
/// `presets/`.
pub static BUILTIN_FILES: &[(&str, &str)] = &[
    (
        "blades/nrel5mw-turbine/onshore/ElastoDyn.dat",
        include_str!("../../presets/blades/nrel5mw-turbine/onshore/ElastoDyn.dat"),
    ),
    (
        "blades/nrel5mw-turbine/5MW_Baseline/NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat",
        include_str!("../../presets/blades/nrel5mw-turbine/5MW_Baseline/NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"),
    ),
    (
        "blades/iea15mw-monopile/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn_tower.dat",
        include_str!("../../presets/blades/iea15mw-monopile/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn_tower.dat"),
    ),
    (
        "blades/iea15mw-monopile/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn.dat",
        include_str!(
            "../../presets/blades/iea15mw-monopile/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn.dat"
        ),
    ),
    (
        "blades/iea15mw-windio/IEA-15-240-RWT.yaml",
        include_str!("../../presets/blades/iea15mw-windio/IEA-15-240-RWT.yaml"),
    ),
    (
        "blades/nrel5mw/NRELOffshrBsline5MW_BeamDyn.dat",
        include_str!("../../presets/blades/nrel5mw/NRELOffshrBsline5MW_BeamDyn.dat"),
    ),
    (
        "blades/nrel5mw/NRELOffshrBsline5MW_BeamDyn_Blade.dat",
        include_str!("../../presets/blades/nrel5mw/NRELOffshrBsline5MW_BeamDyn_Blade.dat"),
    ),
    (
        "blades/iea15mw/IEA_15MW_RWT_Blade_st_noFPM.st",
        include_str!("../../presets/blades/iea15mw/IEA_15MW_RWT_Blade_st_noFPM.st"),
    ),
    (
        "blades/iea15mw/IEA_15MW_RWT_BTC8deg_Blade_st.dat",
        include_str!("../../presets/blades/iea15mw/IEA_15MW_RWT_BTC8deg_Blade_st.dat"),
    ),
    (
        "blades/iea15mw/IEA-15-240-RWT_AeroDyn15_blade.dat",
        include_str!("../../presets/blades/iea15mw/IEA-15-240-RWT_AeroDyn15_blade.dat"),
    ),
    (
        "blades/nrel5mw/NRELOffshrBsline5MW_AeroDyn_blade.dat",
        include_str!("../../presets/blades/nrel5mw/NRELOffshrBsline5MW_AeroDyn_blade.dat"),
    ),
    (
        "blades/nrel5mw/NRELOffshrBsline5MW_Blade.dat",
        include_str!("../../presets/blades/nrel5mw/NRELOffshrBsline5MW_Blade.dat"),
    ),
    (
        "blades/nrel5mw/Airfoils/Cylinder1.dat",
        include_str!("../../presets/blades/nrel5mw/Airfoils/Cylinder1.dat"),
    ),
    (
        "blades/nrel5mw/Airfoils/Cylinder2.dat",
        include_str!("../../presets/blades/nrel5mw/Airfoils/Cylinder2.dat"),
    ),
    (
        "blades/nrel5mw/Airfoils/DU40_A17.dat",
        include_str!("../../presets/blades/nrel5mw/Airfoils/DU40_A17.dat"),
    ),
    (
        "blades/nrel5mw/Airfoils/DU35_A17.dat",
        include_str!("../../presets/blades/nrel5mw/Airfoils/DU35_A17.dat"),
    ),
    (
        "blades/nrel5mw/Airfoils/DU30_A17.dat",
        include_str!("../../presets/blades/nrel5mw/Airfoils/DU30_A17.dat"),
    ),
    (
        "blades/nrel5mw/Airfoils/DU25_A17.dat",
        include_str!("../../presets/blades/nrel5mw/Airfoils/DU25_A17.dat"),
    ),
    (
        "blades/nrel5mw/Airfoils/DU21_A17.dat",
        include_str!("../../presets/blades/nrel5mw/Airfoils/DU21_A17.dat"),
    ),
    (
        "blades/nrel5mw/Airfoils/NACA64_A17.dat",
        include_str!("../../presets/blades/nrel5mw/Airfoils/NACA64_A17.dat"),
    ),
    (
        "blades/iea15mw/IEA_15MW_RWT_ae.dat",
        include_str!("../../presets/blades/iea15mw/IEA_15MW_RWT_ae.dat"),
    ),
    (
        "blades/iea15mw/IEA_15MW_RWT_pc.dat",
        include_str!("../../presets/blades/iea15mw/IEA_15MW_RWT_pc.dat"),
    ),
    (
        "blades/iea15mw/IEA_15MW_RWT_Onshore.opt",
        include_str!("../../presets/blades/iea15mw/IEA_15MW_RWT_Onshore.opt"),
    ),
    // The IEA 15MW HAWC2 model in its own folders: the htc files the onshore model reads and
    // the st, ae and pc files they name for the blade, the tower and the shaft.
    (
        "blades/iea15mw-hawc2/IEA-15-240-RWT-Onshore/htc/IEA_15MW_RWT_Onshore.htc",
        include_str!("../../presets/blades/iea15mw-hawc2/IEA-15-240-RWT-Onshore/htc/IEA_15MW_RWT_Onshore.htc"),
    ),
    (
        "blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_WTG_bodies_noFPM.htc",
        include_str!("../../presets/blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_WTG_bodies_noFPM.htc"),
    ),
    (
        "blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_WTG_orientation.htc",
        include_str!("../../presets/blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_WTG_orientation.htc"),
    ),
    (
        "blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_WTG_constraint.htc",
        include_str!("../../presets/blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_WTG_constraint.htc"),
    ),
    (
        "blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_WTG_aero.htc",
        include_str!("../../presets/blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_WTG_aero.htc"),
    ),
    (
        "blades/iea15mw-hawc2/IEA-15-240-RWT-Onshore/data/IEA_15MW_RWT_Tower_st.dat",
        include_str!("../../presets/blades/iea15mw-hawc2/IEA-15-240-RWT-Onshore/data/IEA_15MW_RWT_Tower_st.dat"),
    ),
    (
        "blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_Shaft_st.dat",
        include_str!("../../presets/blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_Shaft_st.dat"),
    ),
    (
        "blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_Blade_st_noFPM.st",
        include_str!("../../presets/blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_Blade_st_noFPM.st"),
    ),
    (
        "blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_ae.dat",
        include_str!("../../presets/blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_ae.dat"),
    ),
    (
        "blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_pc_OpenFASTpolars_3dcorr.dat",
        include_str!("../../presets/blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_pc_OpenFASTpolars_3dcorr.dat"),
    ),
];

/// Where a preset's relative file names resolve.
#[derive(Debug, Clone, Default)]
pub enum FileBase {
    /// Text loaded from nowhere in particular ([`super::Preset::from_toml`]).
    #[default]
    WorkingDir,
    /// A preset file's directory.
    Dir(PathBuf),
    /// A built-in preset: the embedded blade files, then the working directory (for a file a
    /// `--set blade.file=…` names).
    Builtin,
}

/// Where a preset was loaded from says nothing about the blade it describes: two presets with the
/// same keys (and the same blade read from their files) are equal wherever they were loaded from.
impl PartialEq for FileBase {
    fn eq(&self, _: &FileBase) -> bool {
        true
    }
}

impl FileBase {
    /// The file `name` names from here.
    pub fn resolve(&self, name: &str) -> BladeFile {
        match self {
            FileBase::Builtin => match builtin(name) {
                Some(file) => file,
                None => BladeFile::Disk(PathBuf::from(name)),
            },
            FileBase::Dir(dir) => BladeFile::Disk(dir.join(name)),
            FileBase::WorkingDir => BladeFile::Disk(PathBuf::from(name)),
        }
    }
}

/// A blade file: on disk, or built into the binary.
#[derive(Debug, Clone, PartialEq)]
pub enum BladeFile {
    Disk(PathBuf),
    /// Its path under `presets/`; `text` is `None` when no built-in file has that path.
    Builtin {
        name: String,
        text: Option<&'static str>,
    },
}

fn builtin(name: &str) -> Option<BladeFile> {
    let name = normalise(name);
    BUILTIN_FILES
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(n, text)| BladeFile::Builtin {
            name: n.to_string(),
            text: Some(text),
        })
}

/// `a/./b/../c` as `a/c`, with `/` separators: how a built-in file is named.
fn normalise(name: &str) -> String {
    let mut parts: Vec<&str> = Vec::new();
    for part in name.split(['/', '\\']) {
        match part {
            "" | "." => {}
            ".." => {
                parts.pop();
            }
            p => parts.push(p),
        }
    }
    parts.join("/")
}

impl TextFile for BladeFile {
    /// The path on disk, or `presets/…` for a built-in file (where it is in the source tree).
    fn display(&self) -> String {
        match self {
            BladeFile::Disk(path) => DiskFile(path.clone()).display(),
            BladeFile::Builtin { name, .. } => format!("presets/{name}"),
        }
    }

    /// Through the size-capped reader for a file on disk.
    fn read(&self) -> Result<String> {
        match self {
            BladeFile::Disk(path) => DiskFile(path.clone()).read(),
            BladeFile::Builtin {
                text: Some(text), ..
            } => Ok(text.to_string()),
            BladeFile::Builtin { text: None, .. } => Err(Error::format(
                self.display(),
                0,
                format!(
                    "cannot read: not among the blade files built into the binary ({})",
                    BUILTIN_FILES
                        .iter()
                        .map(|(n, _)| format!("presets/{n}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )),
        }
    }

    fn sibling(&self, name: &str) -> BladeFile {
        match self {
            BladeFile::Disk(path) => BladeFile::Disk(DiskFile(path.clone()).sibling(name).0),
            BladeFile::Builtin { name: own, .. } => {
                let dir = own.rsplit_once('/').map_or("", |(d, _)| d);
                let joined = normalise(&format!("{dir}/{name}"));
                builtin(&joined).unwrap_or(BladeFile::Builtin {
                    name: joined,
                    text: None,
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_files_resolve_by_their_path_under_presets() {
        let primary = FileBase::Builtin.resolve("blades/nrel5mw/NRELOffshrBsline5MW_BeamDyn.dat");
        assert!(primary.read().unwrap().contains("BldFile"));
        let blade = primary.sibling("NRELOffshrBsline5MW_BeamDyn_Blade.dat");
        assert!(blade.read().unwrap().contains("station_total"));
        assert_eq!(
            blade.display(),
            "presets/blades/nrel5mw/NRELOffshrBsline5MW_BeamDyn_Blade.dat"
        );
        let missing = primary.sibling("../other.dat");
        let e = missing.read().unwrap_err().to_string();
        assert!(
            e.starts_with("presets/blades/other.dat: cannot read: not among the blade files"),
            "{e}"
        );
    }

    #[test]
    fn a_builtin_preset_reads_other_files_from_the_working_directory() {
        assert_eq!(
            FileBase::Builtin.resolve("my/blade.dat"),
            BladeFile::Disk(PathBuf::from("my/blade.dat"))
        );
        assert_eq!(
            FileBase::Dir(PathBuf::from("/p")).resolve("b/x.st"),
            BladeFile::Disk(PathBuf::from("/p/b/x.st"))
        );
        assert_eq!(
            FileBase::Dir(PathBuf::from("/p")).resolve("/abs/x.st"),
            BladeFile::Disk(PathBuf::from("/abs/x.st"))
        );
    }

    #[test]
    fn names_are_normalised_before_the_builtin_lookup() {
        assert_eq!(
            normalise("./blades/x/../nrel5mw//a.dat"),
            "blades/nrel5mw/a.dat"
        );
    }
}
