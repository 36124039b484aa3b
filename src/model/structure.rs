//! A preset's structure (docs/model.md §3–§4, §11): the paper's uniform blade from its section
//! and blade keys, or the first K modes of a tabulated blade at the rotor speed and pitch, and
//! the structures kept across calls.

use super::blade::{keyed_blade_structure, BuildKey};
use super::kept::Kept;
use super::section::section_properties;
use crate::error::Result;
use crate::physics::section::SectionProps;
use crate::physics::structure::galerkin::{assemble_section, BladeSpec, Form, StructuralModel};
use crate::physics::structure::tabulated::TabulatedStructure;
use crate::physics::structure::Structure;
use crate::preset::ValidPreset;
use std::sync::Arc;

/// The structure a preset describes, at its rotor speed and pitch: the paper's uniform blade
/// (§3–§4), or the first K modes of the tabulated blade its files describe (§11), from a build
/// kept across rotor-speed changes ([`super::blade::blade_structure`]).
///
/// Both are kept for the next call, by value: the uniform blade per section and blade
/// ([`KEPT_UNIFORM`]: the points of a sweep over the wind speed or the pitch share one), a
/// tabulated blade's structure per rotor speed and what its build was made from ([`AT_SPEED`]:
/// the passes of an operating point and the re-solves of a sweep ask for it again and again).
pub fn for_preset(p: &ValidPreset) -> Result<Arc<dyn Structure>> {
    match keyed_blade_structure(p)? {
        None => {
            static KEPT: Kept<UniformKey, StructuralModel> = Kept::new();
            let (section, spec) = uniform_inputs(p)?;
            let structure =
                KEPT.get_or_build(uniform_key(&section, &spec), KEPT_UNIFORM, || {
                    assemble_section(section, &spec)
                })?;
            Ok(structure)
        }
        Some((build, built)) => {
            // The rotor speed first: the cheap half of the key tells most builds apart.
            static KEPT: Kept<(u64, bool, BuildKey), TabulatedStructure> = Kept::new();
            let omega = p.omega();
            let corrected = p.structure.static_correction;
            let key = (omega.to_bits(), corrected, build);
            let structure = KEPT.get_or_build(key, AT_SPEED, || {
                if corrected {
                    let (modes, left_out) = built.retained_and_left_out(omega)?;
                    TabulatedStructure::new(built.modal.clone(), modes, omega)?
                        .with_left_out(left_out, omega)
                } else {
                    TabulatedStructure::new(built.modal.clone(), built.modes(omega)?, omega)
                }
            })?;
            Ok(structure)
        }
    }
}

/// Everything that fixes a uniform blade, bit for bit: `-0.0` and `0.0` are different inputs
/// (a structure built from one prints its zeros with the other's sign).
fn uniform_key(s: &SectionProps, b: &BladeSpec) -> UniformKey {
    let values = [
        s.m,
        s.i,
        s.ka2,
        s.km1_2,
        s.km2_2,
        s.chord,
        s.ea_offset,
        s.cg_offset,
        s.c22,
        s.c23,
        s.c33,
        b.length,
        b.hub_radius,
        b.omega,
        b.loss_factor,
    ];
    (values.map(f64::to_bits), b.n, b.form)
}

/// What [`uniform_key`] gives: the section's and blade's values as bits, N and the form.
type UniformKey = ([u64; 15], usize, Form);

/// Uniform blades kept: one per sweep worker and a few more.
const KEPT_UNIFORM: usize = 8;

/// Structures at one rotor speed kept: one per sweep worker and a few more.
const AT_SPEED: usize = 8;

/// The paper's uniform blade of a preset: section from its source, N from `structure.modes`,
/// form from `structure.form`, rotor speed from `operating.rotor_speed`, damping from
/// `structure.loss_factor` (docs/model.md §3–§4).
pub fn assemble(p: &ValidPreset) -> Result<StructuralModel> {
    let (section, spec) = uniform_inputs(p)?;
    assemble_section(section, &spec)
}

/// What fixes the uniform blade of a preset: its section and the blade around it.
fn uniform_inputs(p: &ValidPreset) -> Result<(SectionProps, BladeSpec)> {
    let section = section_properties(p)?;
    let spec = BladeSpec {
        n: p.structure.modes,
        length: p.blade.length,
        hub_radius: p.blade.hub_radius,
        omega: p.omega(),
        form: p.structure.form,
        loss_factor: p.structure.loss_factor,
    };
    spec.check()?;
    Ok((section, spec))
}
