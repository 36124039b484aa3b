//! A tabulated blade from the files a preset names, and its structure (docs/model.md §11): the
//! files are read and mapped to a [`BladeTable`] with the damping they state
//! ([`read_blade`], once, when the preset is checked); [`blade_structure`] then builds the
//! finite elements at the preset's pitch, the modal basis and each mode's damping.
//!
//! Damping (docs/model.md §11.4): `structure.damping_flap`, `…_edge`, `…_torsion` set a modal
//! damping ratio for every mode of that family; a family the preset leaves unset takes what the
//! files state: BeamDyn's stiffness-proportional `mu` projected on each mode, or a ratio per
//! family ([`SourceDamping::PerFamily`]); a file that states none leaves the mode undamped.

use super::beamdyn::from_beamdyn;
use super::coupling::with_bend_twist_coupling;
use super::fem::Mesh;
use super::hawc2::{from_hawc2_st, ChordTwist};
use super::modal::{BladeMode, ModalBlade, StiffnessFactors};
use super::pitch_range::{snapshot_pitches, PitchRangeBlade};
use super::BladeTable;
use crate::error::{Error, Result};
use crate::formats::{aerodyn, beamdyn, elastodyn, hawc2_st};
use crate::preset::{BladeFile, BladeSource, ValidPreset};
use std::sync::Arc;

/// Damping as a blade's files state it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SourceDamping {
    /// The files state none.
    None,
    /// Stiffness-proportional damping (BeamDyn `damp_type = 1`), projected on each mode.
    StiffnessProportional(StiffnessFactors),
    /// A damping ratio per family, in [`Family::ALL`](super::modal::Family::ALL) order (a
    /// source that states its damping per mode family, e.g. tuned HAWC2 log decrements).
    PerFamily([f64; 3]),
}

/// A blade as its files describe it: the sections (root at the hub radius 0: the preset's
/// `blade.hub_radius` places it) and the damping they state.
#[derive(Debug, Clone, PartialEq)]
pub struct TabulatedBlade {
    pub source: BladeSource,
    pub table: BladeTable,
    pub damping: SourceDamping,
    /// The files read, as errors name them (a BeamDyn blade: the primary file, then its blade
    /// file).
    pub files: Vec<String>,
}

impl TabulatedBlade {
    /// Blade length (m): the span of the last station.
    pub fn length(&self) -> f64 {
        self.table.length()
    }
}

/// Read the blade `file` describes as a `source` blade (a HAWC2 st file: subset `st_subset` of
/// set `st_set`). Errors name the file and line; a file of another known kind says which kind
/// it is and what to do instead.
pub fn read_blade(
    source: BladeSource,
    file: &BladeFile,
    twist: Option<&ChordTwist>,
    st_set: usize,
    st_subset: usize,
) -> Result<TabulatedBlade> {
    match (source, twist) {
        (BladeSource::Beamdyn, _) => read_beamdyn(file),
        (BladeSource::Hawc2, Some(twist)) => read_hawc2(file, twist, st_set, st_subset),
        (BladeSource::Hawc2, None) => Err(Error::Invalid {
            origin: file.display(),
            message: "a HAWC2 st file carries no twist: blade.twist_file must name the blade's \
                      AeroDyn 15 blade file"
                .into(),
        }),
        (BladeSource::Uniform, _) => Err(Error::Invalid {
            origin: file.display(),
            message: "blade.source = \"uniform\" describes its blade by blade.length and \
                      section.*, not by a file"
                .into(),
        }),
    }
}

/// The BeamDyn primary file, then the blade file its `BldFile` names (relative to it, as
/// BeamDyn resolves it).
fn read_beamdyn(file: &BladeFile) -> Result<TabulatedBlade> {
    let name = file.display();
    let text = file.read()?;
    let primary = beamdyn::parse_primary(&text, &name)
        .map_err(|e| misread(&text, &name, BladeSource::Beamdyn).unwrap_or(e))?;
    let blade_file = file.sibling(&primary.blade_file);
    let blade_name = blade_file.display();
    let blade_text = blade_file.read()?;
    let blade = beamdyn::parse_blade(&blade_text, &blade_name)?;
    let table = from_beamdyn(&primary, &blade, &name, 0.0)?;
    // BeamDyn's mu follow its strain order (shear 1, shear 2, extension, bending about x1 =
    // edge, bending about x2 = flap, torsion); the beam here has no shear or axial dofs, so
    // mu1–mu3 have nothing to damp.
    let damping = match blade.damp_type {
        1 => SourceDamping::StiffnessProportional(StiffnessFactors {
            flap: blade.mu[4],
            edge: blade.mu[3],
            torsion: blade.mu[5],
        }),
        _ => SourceDamping::None,
    };
    Ok(TabulatedBlade {
        source: BladeSource::Beamdyn,
        table,
        damping,
        files: vec![name, blade_name],
    })
}

/// Subset `st_subset` of set `st_set` of a HAWC2 st file, its sections turned by `twist`
/// (docs/model.md §11.6). The st file states no damping: a HAWC2 blade is damped as the preset
/// sets `structure.damping_*`.
fn read_hawc2(
    file: &BladeFile,
    twist: &ChordTwist,
    st_set: usize,
    st_subset: usize,
) -> Result<TabulatedBlade> {
    let name = file.display();
    let text = file.read()?;
    let st = hawc2_st::parse_st(&text, &name)
        .map_err(|e| misread(&text, &name, BladeSource::Hawc2).unwrap_or(e))?;
    let table = from_hawc2_st(&st, st_set, st_subset, twist, 0.0)?;
    Ok(TabulatedBlade {
        source: BladeSource::Hawc2,
        table,
        damping: SourceDamping::None,
        files: vec![name],
    })
}

/// The chord twist a HAWC2 blade takes from an AeroDyn 15 blade file's `BlTwist`.
pub fn read_twist(file: &BladeFile) -> Result<ChordTwist> {
    let name = file.display();
    let text = file.read()?;
    let blade = aerodyn::parse_blade(&text, &name)?;
    Ok(ChordTwist::from_aerodyn(&blade))
}

/// When a file does not parse as what `expected` needs, whether it is another kind of blade
/// file this program knows, as an error that says so: an ElastoDyn blade file above all, which
/// has no torsional stiffness and so cannot describe a blade for flutter.
fn misread(text: &str, name: &str, expected: BladeSource) -> Option<Error> {
    let is = |message: String| Some(Error::format(name, 0, message));
    if elastodyn::parse_blade(text, name).is_ok() {
        return is(
            "this is an ElastoDyn blade file (NBlInpSt, FlpStff, EdgStff): ElastoDyn blade files \
             carry no torsional stiffness, which flutter needs; use the blade's BeamDyn files \
             (blade.source = \"beamdyn\", blade.file = the primary file) or a HAWC2 st file \
             (blade.source = \"hawc2\"), which do"
                .into(),
        );
    }
    match expected {
        BladeSource::Beamdyn if beamdyn::parse_blade(text, name).is_ok() => is(
            "this is a BeamDyn blade file; blade.file names the BeamDyn primary file, which \
             names this one in its BldFile line"
                .into(),
        ),
        BladeSource::Beamdyn
            if hawc2_st::parse_st(text, name).is_ok_and(|s| !s.sets.is_empty()) =>
        {
            is("this is a HAWC2 st file: set blade.source = \"hawc2\"".into())
        }
        BladeSource::Hawc2 if beamdyn::parse_primary(text, name).is_ok() => {
            is("this is a BeamDyn primary file: set blade.source = \"beamdyn\"".into())
        }
        _ => None,
    }
}

/// A tabulated blade's structure at a preset's pitch: the modal basis the analyses work on, and
/// how its modes are damped.
#[derive(Debug, Clone)]
pub struct BladeStructure {
    pub blade: Arc<TabulatedBlade>,
    /// The blade as the elements see it: the file's sections at the preset's hub radius, with
    /// the preset's `blade.bend_twist_coupling` added (docs/model.md §11.7).
    pub table: BladeTable,
    pub modal: Arc<ModalBlade>,
    /// K, the modes retained (`structure.modes`).
    pub count: usize,
    /// Per family, the damping ratio the preset sets (`structure.damping_*`) or the source
    /// states per family; `None`: the projected ratio of each mode (0 without damping).
    ratios: [Option<f64>; 3],
}

/// The structure of the tabulated blade `p` holds (`None` for the uniform blade): elements at
/// `structure.min_elements`, pitch `operating.pitch`, a basis good from rest to
/// `view.rotor_speed_max` (or the operating speed, if higher) and over the pitch range
/// ([`pitch_range`]).
///
/// Two builds are kept for the next call: the pitch-range basis, once per blade, coupling α,
/// hub radius, mesh, K, damping and speed and pitch ranges ([`RANGES`] of them; docs/model.md
/// §11.8), and the blade at one pitch on it ([`BUILT`] of them). A change of rotor speed, wind
/// or anything aerodynamic then costs the reduced eigenproblem only (§11.4), a change of pitch
/// the reduced matrices at the new pitch, never a re-assembly.
pub fn blade_structure(p: &ValidPreset) -> Result<Option<Arc<BladeStructure>>> {
    let Some(blade) = p.tabulated_blade() else {
        return Ok(None);
    };
    static BUILT_CACHE: Kept<BuildKey, BladeStructure> = Kept::new();
    BUILT_CACHE
        .get_or_build(BuildKey::of(p, blade), BUILT, || build(p, blade.clone()))
        .map(Some)
}

/// Blades at one pitch kept: the explorer's current blade and a few it was just at (a pitch
/// dragged back), or the points a sweep's worker is between.
const BUILT: usize = 4;

/// Pitch-range bases kept: one per blade in use (a design sweep over the coupling builds one
/// per value).
const RANGES: usize = 2;

/// The last few builds, newest last, found by their key.
pub(crate) struct Kept<K, V>(std::sync::Mutex<Vec<(K, Arc<V>)>>);

impl<K: PartialEq, V> Kept<K, V> {
    pub(crate) const fn new() -> Kept<K, V> {
        Kept(std::sync::Mutex::new(Vec::new()))
    }

    /// The build kept under `key`, or a new one from `build`, kept in place of the oldest
    /// when `capacity` are. A poisoned lock only means another thread panicked mid-push: the
    /// list is still whole.
    pub(crate) fn get_or_build(
        &self,
        key: K,
        capacity: usize,
        build: impl FnOnce() -> Result<V>,
    ) -> Result<Arc<V>> {
        let lock = || self.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(hit) = lock().iter().find(|(k, _)| *k == key) {
            return Ok(hit.1.clone());
        }
        let built = Arc::new(build()?);
        let mut kept = lock();
        if kept.len() >= capacity {
            kept.remove(0);
        }
        kept.push((key, built.clone()));
        Ok(built)
    }
}

/// Everything [`build`] reads from a preset.
#[derive(Debug, Clone, PartialEq)]
struct BuildKey {
    range: RangeKey,
    pitch: f64,
    ratios: [Option<f64>; 3],
}

/// Everything the pitch-range basis depends on.
#[derive(Debug, Clone, PartialEq)]
struct RangeKey {
    blade: Arc<TabulatedBlade>,
    /// `blade.bend_twist_coupling`: another α is another blade.
    coupling: f64,
    hub_radius: f64,
    min_elements: usize,
    count: usize,
    speeds: Vec<f64>,
    pitches: (f64, f64),
}

impl BuildKey {
    fn of(p: &ValidPreset, blade: &Arc<TabulatedBlade>) -> BuildKey {
        BuildKey {
            range: RangeKey {
                blade: blade.clone(),
                coupling: p.blade.bend_twist_coupling,
                hub_radius: p.blade.hub_radius,
                min_elements: p.structure.min_elements,
                count: p.structure.modes,
                speeds: reference_speeds(p),
                pitches: pitch_range(p),
            },
            pitch: p.pitch_rad(),
            ratios: family_ratios(p, blade.damping),
        }
    }
}

/// The pitch range every basis spans (rad): from fine pitch 0 to feather at 90°, widened to
/// hold the preset's pitch when it lies outside, so the basis, and every result on it, does not
/// depend on the pitch inside the range.
fn pitch_range(p: &ValidPreset) -> (f64, f64) {
    let pitch = p.pitch_rad();
    (pitch.min(0.0), pitch.max(std::f64::consts::FRAC_PI_2))
}

fn build(p: &ValidPreset, blade: Arc<TabulatedBlade>) -> Result<BladeStructure> {
    let key = BuildKey::of(p, &blade).range;
    static RANGE_CACHE: Kept<RangeKey, (BladeTable, PitchRangeBlade)> = Kept::new();
    let range = RANGE_CACHE.get_or_build(key, RANGES, || {
        let coupled = with_bend_twist_coupling(&blade.table, p.blade.bend_twist_coupling);
        let table = BladeTable::new(&coupled.origin, p.blade.hub_radius, coupled.sections)?;
        let mesh = Mesh::following(&table, p.structure.min_elements);
        let (low, high) = pitch_range(p);
        let damping = match blade.damping {
            SourceDamping::StiffnessProportional(f) => Some(f),
            _ => None,
        };
        let modal = PitchRangeBlade::new(
            &table,
            &mesh,
            &snapshot_pitches(low, high),
            &reference_speeds(p),
            p.structure.modes,
            damping,
        )?;
        Ok((table, modal))
    })?;
    let (table, modal) = &*range;
    Ok(BladeStructure {
        ratios: family_ratios(p, blade.damping),
        blade,
        table: table.clone(),
        modal: Arc::new(modal.at(p.pitch_rad())?),
        count: p.structure.modes,
    })
}

/// Rest and the top of the explorer's range, or the operating speed above it (rad/s): the
/// basis then holds the modes across the range (on the NREL 5MW blade within 1.5e-10 between
/// the references), so the build does not depend on the operating speed inside it.
fn reference_speeds(p: &ValidPreset) -> Vec<f64> {
    let top = p.view.rotor_speed_max * std::f64::consts::PI / 30.0;
    vec![0.0, top.max(p.omega())]
}

/// Per family, the ratio that replaces a mode's projected damping: `structure.damping_*` when
/// the preset sets it, else the source's per-family ratio if it states one.
fn family_ratios(p: &ValidPreset, damping: SourceDamping) -> [Option<f64>; 3] {
    let s = &p.structure;
    let set = [s.damping_flap, s.damping_edge, s.damping_torsion];
    let stated = match damping {
        SourceDamping::PerFamily(r) => r.map(Some),
        _ => [None; 3],
    };
    [0, 1, 2].map(|k| set[k].or(stated[k]))
}

impl BladeStructure {
    /// The first K modes at rotor speed `omega` (rad/s), ascending, each with its damping
    /// ratio: the family's when the preset or the source sets one, else its projection.
    pub fn modes(&self, omega: f64) -> Result<Vec<BladeMode>> {
        let mut modes = self.modal.modes(omega, self.count)?;
        for m in &mut modes {
            if let Some(ratio) = self.ratios[m.family().index()] {
                m.damping_ratio = ratio;
            }
        }
        Ok(modes)
    }

    /// Finite elements along the span.
    pub fn elements(&self) -> usize {
        self.modal.geometry.mesh.elements()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::preset::Preset;

    /// A preset's `structure.damping_*` wins over a source's per-family ratio, family by family;
    /// without either a family keeps each mode's projection (`None`).
    #[test]
    fn family_ratios_take_the_preset_then_the_source() {
        let p = Preset::load("nrel5mw", &["structure.damping_edge=0.05".into()]).unwrap();
        let stated = SourceDamping::PerFamily([0.01, 0.02, 0.03]);
        assert_eq!(
            family_ratios(&p, stated),
            [Some(0.01), Some(0.05), Some(0.03)]
        );
        let mu = SourceDamping::StiffnessProportional(StiffnessFactors {
            flap: 1e-3,
            edge: 1e-3,
            torsion: 1e-3,
        });
        assert_eq!(family_ratios(&p, mu), [None, Some(0.05), None]);
        assert_eq!(
            family_ratios(&p, SourceDamping::None),
            [None, Some(0.05), None]
        );
    }

    #[test]
    fn reference_speeds_are_rest_and_the_top_of_the_range_or_the_operating_speed() {
        let rad = |rpm: f64| rpm * std::f64::consts::PI / 30.0;
        let p = Preset::load("nrel5mw", &[]).unwrap();
        assert_eq!(reference_speeds(&p), [0.0, rad(20.0)]);
        let p = p.with("operating.rotor_speed", 0.0).unwrap();
        assert_eq!(reference_speeds(&p), [0.0, rad(20.0)]);
        let p = p.with("operating.rotor_speed", 30.0).unwrap();
        assert_eq!(reference_speeds(&p), [0.0, rad(30.0)]);
    }

    /// A second call with the same blade, pitch and mesh reuses the first build; another
    /// rotor speed inside the range does too; another pitch builds anew.
    #[test]
    fn builds_are_kept_across_rotor_speeds_and_redone_for_a_new_pitch() {
        let p = Preset::load("nrel5mw", &[]).unwrap();
        let first = blade_structure(&p).unwrap().unwrap();
        let faster = p.with("operating.rotor_speed", 15.0).unwrap();
        let again = blade_structure(&faster).unwrap().unwrap();
        assert!(Arc::ptr_eq(&first, &again));
        let pitched = p.with("operating.pitch", 5.0).unwrap();
        let other = blade_structure(&pitched).unwrap().unwrap();
        assert!(!Arc::ptr_eq(&first, &other));
    }
}
