//! A preset's tabulated blade at its pitch (docs/model.md §11): the settings its basis is built
//! with, and the builds kept across calls.

use super::kept::Kept;
use crate::error::Result;
use crate::physics::blade::axis::CurvedAxis;
use crate::physics::blade::fem::Beam;
use crate::physics::blade::pitch_range::PitchRangeBlade;
use crate::physics::blade::source::{
    family_ratios, pitch_range_basis, BasisSettings, BladeStructure, TabulatedBlade,
};
use crate::physics::blade::BladeTable;
use crate::preset::ValidPreset;
use std::sync::Arc;

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
    Ok(keyed_blade_structure(p)?.map(|(_, built)| built))
}

/// [`blade_structure`] with the key it was kept under: what the build depends on, for the
/// builds made from it to be kept by.
pub(super) fn keyed_blade_structure(
    p: &ValidPreset,
) -> Result<Option<(BuildKey, Arc<BladeStructure>)>> {
    let Some(blade) = p.tabulated_blade() else {
        return Ok(None);
    };
    static BUILT_CACHE: Kept<BuildKey, BladeStructure> = Kept::new();
    let key = BuildKey::of(p, blade)?;
    let built = BUILT_CACHE.get_or_build(key.clone(), BUILT, || build(p, blade.clone()))?;
    Ok(Some((key, built)))
}

/// The beam a preset's tabulated blade is built as (`None` for the uniform blade): shear-deformable
/// where its files give a shear stiffness and `structure.shear` keeps it (docs/model.md §11.3).
pub fn beam(p: &ValidPreset) -> Option<Beam> {
    let blade = p.tabulated_blade()?;
    Some(if p.structure.shear {
        Beam::of(&blade.table)
    } else {
        Beam::EulerBernoulli
    })
}

/// Blades at one pitch kept: the explorer's current blade and a few it was just at (a pitch
/// dragged back), or the points a sweep's worker is between.
const BUILT: usize = 4;

/// Pitch-range bases kept: one per blade in use (a design sweep over the coupling builds one
/// per value).
const RANGES: usize = 2;

/// Everything [`build`] reads from a preset, compared by value.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct BuildKey {
    // The pitch and ratios first: keys that differ mostly differ there, and the range's blade
    // is compared station by station.
    pitch: f64,
    ratios: [Option<f64>; 3],
    range: RangeKey,
}

/// Everything the pitch-range basis depends on.
#[derive(Debug, Clone, PartialEq)]
struct RangeKey {
    blade: Arc<TabulatedBlade>,
    settings: BasisSettings,
}

impl BuildKey {
    fn of(p: &ValidPreset, blade: &Arc<TabulatedBlade>) -> Result<BuildKey> {
        Ok(BuildKey {
            range: RangeKey {
                blade: blade.clone(),
                settings: BasisSettings {
                    coupling: p.blade.bend_twist_coupling,
                    hub_radius: p.blade.hub_radius,
                    min_elements: p.structure.min_elements,
                    shear: p.structure.shear,
                    axis: axis(p)?,
                    count: p.structure.modes,
                    speeds: reference_speeds(p),
                    pitches: pitch_range(p),
                },
            },
            pitch: p.pitch_rad(),
            ratios: ratios(p, blade),
        })
    }
}

/// The reference axis the beam follows (docs/model.md §11.9): the prebend the aerodynamics
/// see (`aero.prebend_file` or the htc's `c2_def`), unless `structure.curved` is off or the
/// preset describes no aerodynamics.
fn axis(p: &ValidPreset) -> Result<CurvedAxis> {
    match p.aero_blade() {
        Some(aero) if p.structure.curved && !aero.prebend.is_empty() => {
            let points: Vec<(f64, [f64; 2])> =
                aero.prebend.iter().map(|&(s, x)| (s, [x, 0.0])).collect();
            CurvedAxis::new(&aero.origin, &points)
        }
        _ => Ok(CurvedAxis::straight()),
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
    let key = BuildKey::of(p, &blade)?.range;
    static RANGE_CACHE: Kept<RangeKey, (BladeTable, PitchRangeBlade)> = Kept::new();
    let range = RANGE_CACHE.get_or_build(key.clone(), RANGES, || {
        pitch_range_basis(&blade, &key.settings)
    })?;
    let (table, modal) = &*range;
    Ok(BladeStructure {
        ratios: ratios(p, &blade),
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

/// Per family, `structure.damping_*` where the preset sets it, else what the blade's files state.
fn ratios(p: &ValidPreset, blade: &TabulatedBlade) -> [Option<f64>; 3] {
    let s = &p.structure;
    family_ratios(
        [s.damping_flap, s.damping_edge, s.damping_torsion],
        blade.damping,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::preset::Preset;

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
