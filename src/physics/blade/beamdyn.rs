//! A blade from its BeamDyn files (docs/model.md §11.5): the key points give the span and the
//! initial twist of the section frames, the blade file's 6×6 matrices the section properties.
//!
//! BeamDyn's section frame: `x1` normal to the chord (our ξ), `x2` along the chord (our η), `x3`
//! along the reference axis; matrices in the order (shear 1, shear 2, extension, bending about x1,
//! bending about x2, torsion). Bending about `x2` curves the blade along `x1`, so the flap
//! stiffness is K55 and the edge stiffness K44 (in the NREL 5MW file K44 is ElastoDyn's EdgStff
//! and K55 its FlpStff). With `κ1 = −w2''`, `κ2 = w1''`, `κ3 = φ'`, BeamDyn's `½κᵀKκ` gives
//! `EI_ξη = −K45`, `g_ξ = −K56` and `g_η = K46` in §11.2's signs. Mass matrix: `m = M11`,
//! centre of mass `ξ_c = M26/m`, `η_c = −M16/m`, mass moments `∫ρη² = M44`, `∫ρξ² = M55`,
//! `∫ρξη = −M45`. The initial twist, positive toward feather as AeroDyn's twist, is linear
//! between key points. The reference axis is taken straight along `kp_zr` (prebend and sweep in
//! `kp_xr`, `kp_yr` are neglected, §11.2).

use super::{BladeTable, Section};
use crate::error::{Error, Result};
use crate::formats::beamdyn::{BeamDynBlade, BeamDynPrimary};

/// The blade of `primary` with the properties of `blade`, its root at `hub_radius` (m).
pub fn from_beamdyn(
    primary: &BeamDynPrimary,
    blade: &BeamDynBlade,
    origin: &str,
    hub_radius: f64,
) -> Result<BladeTable> {
    let points: Vec<(f64, f64)> = primary
        .members
        .iter()
        .flatten()
        .map(|k| (k.kp_zr, k.initial_twist_deg))
        .collect();
    let (first, last) = match (points.first(), points.last()) {
        (Some(f), Some(l)) if l.0 > f.0 => (*f, *l),
        _ => {
            return Err(Error::Invalid {
                origin: origin.to_string(),
                message: "the BeamDyn key points do not span a blade (kp_zr must increase)".into(),
            })
        }
    };
    let length = last.0 - first.0;
    let twist_at = |z: f64| -> f64 {
        let zr = first.0 + z;
        let k = points
            .partition_point(|p| p.0 <= zr)
            .clamp(1, points.len() - 1);
        let ((za, ta), (zb, tb)) = (points[k - 1], points[k]);
        let t = if zb > za {
            ((zr - za) / (zb - za)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (ta + (tb - ta) * t).to_radians()
    };
    let sections = blade
        .stations
        .iter()
        .map(|s| {
            let (k, m) = (&s.stiffness, &s.mass);
            let mass = m[0][0];
            let z = s.eta * length;
            Section {
                z,
                mass,
                cg: if mass > 0.0 {
                    [m[1][5] / mass, -m[0][5] / mass]
                } else {
                    [0.0, 0.0]
                },
                inertia: [m[4][4], m[3][3], -m[3][4]],
                ei_flap: k[4][4],
                ei_edge: k[3][3],
                ei_cross: -k[3][4],
                gj: k[5][5],
                flap_twist: -k[4][5],
                edge_twist: k[3][5],
                twist: twist_at(z),
            }
        })
        .collect();
    BladeTable::new(origin, hub_radius, sections)
}
