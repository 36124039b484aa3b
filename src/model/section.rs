//! A preset's blade section as the physics takes it (docs/model.md §2): the section properties
//! from `section.source`, and the layup's laminate and contour.

use crate::error::Result;
use crate::physics::laminate::{layup_section_props, Contour, LayupInput, PlyMaterial};
use crate::physics::section::{checked, table1_stiffness, SectionProps};
use crate::preset::{SectionSource, ValidPreset};

/// Section properties of a preset from its `section.source` (docs/model.md §2): `direct` takes
/// `c22, c23, c33` from the preset, `table` interpolates the paper's Table 1 at
/// `section.ply_angle`, `layup` computes everything from the laminate and contour (§2.1). Mass
/// properties come from the preset for `direct` and `table`.
pub fn section_properties(p: &ValidPreset) -> Result<SectionProps> {
    let props = match p.section.source {
        SectionSource::Direct => {
            let s = &p.section;
            with_preset_mass(p, [s.c22, s.c23, s.c33])
        }
        SectionSource::Table => with_preset_mass(p, table1_stiffness(p.section.paper_ply_angle())),
        SectionSource::Layup => layup_section_props(&layup_input(p))?,
    };
    checked(props)
}

/// Stiffness `[C22, C23, C33]` with the mass, inertia and geometry given in the preset (the
/// direct and table sources).
fn with_preset_mass(p: &ValidPreset, [c22, c23, c33]: [f64; 3]) -> SectionProps {
    let s = &p.section;
    SectionProps {
        m: s.mass_per_length,
        i: s.polar_inertia,
        ka2: s.ka2,
        km1_2: s.km1_2,
        km2_2: s.km2_2,
        chord: s.chord,
        ea_offset: s.ea_offset,
        cg_offset: s.cg_offset,
        c22,
        c23,
        c33,
    }
}

/// The preset's layup section (`section.layup`, `section.contour`, `section.ply_angle`), whatever
/// `section.source` says: `flutterscope section` reports it for any preset.
pub fn layup_input(p: &ValidPreset) -> LayupInput {
    let (s, l) = (&p.section, &p.section.layup);
    LayupInput {
        material: PlyMaterial {
            e11: l.e11,
            e22: l.e22,
            nu12: l.nu12,
            g12: l.g12,
        },
        density: l.density,
        ply_thickness: l.ply_thickness,
        plies: l.plies,
        ply_angle: s.paper_ply_angle(),
        nonstructural_mass: l.nonstructural_mass,
        nonstructural_position: l.nonstructural_position,
        contour: contour(p),
        ea_offset: s.ea_offset,
        cg_offset: s.cg_offset,
        origin: p.origin.clone(),
    }
}

/// The preset's contour (`section.contour`, scaled by `section.chord` where its shape is the
/// paper's).
pub fn contour(p: &ValidPreset) -> Contour {
    let c = &p.section.contour;
    Contour {
        shape: c.shape,
        width: c.width,
        height: c.height,
        a: c.a,
        b: c.b,
        chord: p.section.chord,
    }
}
