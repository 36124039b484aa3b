//! A blade from its BeamDyn files (docs/model.md §11.5): the key points give the span and the
//! initial twist of the section frames, the blade file's 6×6 matrices the section properties.
//!
//! BeamDyn's section frame (OpenFAST's BeamDyn input-file documentation: the IEC blade system,
//! `X_r` toward the suction side, `Y_r` toward the trailing edge, `Z_r` along the blade) has `x1`
//! normal to the chord (our ξ) and `x2` along it toward the trailing edge (our −η): a reflection
//! of ours, so the twist sense reverses too. The 6×6 stiffness about the reference axis, in the
//! order (shear 1, shear 2, extension, bending about x1, bending about x2, torsion), is reduced to
//! the Euler–Bernoulli section by [`classical::reduce`](super::classical::reduce): its couplings
//! K16, K26 place the shear centre, K34, K35 the tension centre. Bending about `x2` curves the
//! blade along `x1`, so the flap stiffness comes from K55 and the edge stiffness from K44 (in the
//! NREL 5MW file K55 equals ElastoDyn's FlpStff and K44 its EdgStff). Mass matrix
//! `[[m I, −m c̃], [m c̃, J]]`: centre of mass `(x1, x2) = (M26, −M16)/m`, second moments
//! `∫ρx2² = M44`, `∫ρx1² = M55`, `∫ρx1x2 = −M45`, then reflected. The initial twist, positive
//! toward feather as AeroDyn's twist, is linear between key points. The span is `kp_zr`; the
//! curve the beam follows is the rotor's prebend (`aero.prebend_file`, §11.9), not `kp_xr`,
//! `kp_yr`.

use super::classical::{reduce, FileFrame};
use super::{BeamSection, BladeTable, SectionMatrices};
use crate::error::{Error, Result};
use crate::formats::beamdyn::{BeamDynBlade, BeamDynPrimary};

/// The blade of `primary` with the properties of `blade`, its root at `hub_radius` (m), mapped
/// into docs/model.md §11.1's frame as §11.5 describes.
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
    let frame = beamdyn_frame();
    let sections = blade
        .stations
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let (stiffness, m) = (&s.stiffness, &s.mass);
            let z = s.eta * length;
            // A station's faults are the blade file's, at the station's line.
            let at_station = |message: String| {
                Error::format(
                    blade.path.clone(),
                    s.line,
                    format!("station {} (eta = {}): {message}", k + 1, s.eta),
                )
            };
            let section = reduce(stiffness, &frame).map_err(at_station)?;
            let mass = m[0][0];
            let cg = if mass > 0.0 {
                frame.position([m[1][5] / mass, -m[0][5] / mass])
            } else {
                [0.0, 0.0]
            };
            let inertia = frame.second_moments([[m[4][4], -m[3][4]], [-m[3][4], m[3][3]]]);
            let section = section.at_station(z, twist_at(z), mass, cg, inertia);
            match section.fault() {
                Some(fault) => Err(at_station(fault)),
                None => Ok(section),
            }
        })
        .collect::<Result<Vec<BeamSection>>>()?;
    // BeamDyn's matrices are about the reference axis (its key-point line).
    let matrices = blade
        .stations
        .iter()
        .map(|s| SectionMatrices {
            stiffness: s.stiffness,
            mass: Some(s.mass),
            frame,
            origin: [0.0, 0.0],
        })
        .collect();
    BladeTable::new(origin, hub_radius, sections)?.with_matrices(matrices)
}

/// BeamDyn's section axes in ours: `ξ = x1`, `η = −x2` (docs/model.md §11.5).
fn beamdyn_frame() -> FileFrame {
    FileFrame::new([[1.0, 0.0], [0.0, -1.0]]).expect("a reflection is orthogonal")
}
