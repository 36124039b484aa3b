//! A blade's reduced basis over a range of pitch (docs/model.md §11.8): the modes at any pitch
//! and rotor speed in the range from a small dense eigenproblem, with no re-assembly and no
//! banded Lanczos solve when the pitch changes.
//!
//! Why it is exact in the matrices: the pitch turns every section frame, θ = twist + pitch, and
//! the elements' terms are at most quadratic in `cos θ`, `sin θ` (§11.2–§11.3). So each of `M`,
//! `K₀`, `K_Ω` and the stiffness-proportional damping is `A₀ + A₁ᶜ cos p + A₁ˢ sin p + A₂ᶜ cos 2p +
//! A₂ˢ sin 2p` in the pitch p, and five assemblies at pitches 2πk/5 give the five terms (a
//! discrete Fourier transform with no aliasing). Projected once on the basis, the reduced
//! matrices at any pitch cost five b × b sums.
//!
//! The approximation is the basis (a Ritz reduction): the lowest modes at a few pitches across the
//! range and at rest and the top rotor speed, made one basis by a proper orthogonal
//! decomposition that drops the directions the snapshots hardly use. The tests bound what it
//! costs against a full rebuild at each pitch.

use super::fem::{assemble_banded, Beam, BladeGeometry, BladeMatrices, Mesh};
use super::modal::{
    lowest_modes_basis, m_orthonormal, projected, reduced_family_mass, stiffness_damping,
    ModalBlade, Projections, StiffnessFactors,
};
use super::BladeTable;
use crate::error::{Error, Result};
use crate::numeric::banded::SymmetricBand;
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;
use std::f64::consts::TAU;
use std::sync::Arc;

/// Assemblies that fix the five Fourier terms of a matrix in the pitch.
const SAMPLES: usize = 5;

/// Largest pitch step between the snapshots of the basis (rad, 30°): the 12 IEA 15MW and NREL
/// 5MW modes anywhere in 0…90° then agree with a full rebuild to 1.1e-8 relative in frequency
/// (tests/integration/pitch_range.rs, docs/model.md §11.8).
pub const SNAPSHOT_STEP: f64 = std::f64::consts::FRAC_PI_6;

/// Singular values of the snapshots below this fraction of the largest are dropped. Measured on
/// the IEA 15MW (docs/model.md §11.8): 1e-6 keeps 71 of 96 vectors and the frequencies within
/// 1.1e-8 of a full rebuild; 1e-5 keeps 62 but lets them err by 4e-6, because a dropped
/// direction, small in the mass norm, can carry stiff motion.
const POD_TOLERANCE: f64 = 1e-6;

/// A matrix as the five Fourier terms of its pitch dependence.
#[derive(Debug, Clone)]
struct Harmonics([DMatrix<f64>; SAMPLES]);

impl Harmonics {
    /// The terms from the matrix at the pitches `2πk/5` (k = 0…4): mean, then cos p, sin p,
    /// cos 2p, sin 2p.
    fn from_samples(samples: &[DMatrix<f64>]) -> Harmonics {
        let n = SAMPLES as f64;
        let term = |weight: &dyn Fn(f64) -> f64| {
            samples.iter().enumerate().fold(
                DMatrix::zeros(samples[0].nrows(), samples[0].ncols()),
                |acc, (k, a)| acc + a * weight(sample_pitch(k)),
            )
        };
        Harmonics([
            term(&|_| 1.0 / n),
            term(&|p| 2.0 / n * p.cos()),
            term(&|p| 2.0 / n * p.sin()),
            term(&|p| 2.0 / n * (2.0 * p).cos()),
            term(&|p| 2.0 / n * (2.0 * p).sin()),
        ])
    }

    /// The matrix at `pitch` (rad).
    fn at(&self, pitch: f64) -> DMatrix<f64> {
        let w = [
            1.0,
            pitch.cos(),
            pitch.sin(),
            (2.0 * pitch).cos(),
            (2.0 * pitch).sin(),
        ];
        let mut a = self.0[0].clone();
        for (term, wk) in self.0.iter().zip(w).skip(1) {
            a += term * wk;
        }
        a
    }
}

/// The k-th Fourier sample pitch, `2πk/5` (rad).
fn sample_pitch(k: usize) -> f64 {
    TAU * k as f64 / SAMPLES as f64
}

/// The snapshot pitches spanning `[low, high]` (rad) at most [`SNAPSHOT_STEP`] apart, ends
/// included.
pub fn snapshot_pitches(low: f64, high: f64) -> Vec<f64> {
    let steps = ((high - low) / SNAPSHOT_STEP).ceil().max(1.0) as usize;
    (0..=steps)
        .map(|k| low + (high - low) * k as f64 / steps as f64)
        .collect()
}

/// One Fourier sample's matrices on the basis: `M`, `K₀`, `K_Ω` and the mass's three families.
struct SampleProjections {
    matrices: [DMatrix<f64>; 3],
    family: [DMatrix<f64>; 3],
}

/// A blade's structure reduced on one basis for every pitch of a range.
#[derive(Debug, Clone)]
pub struct PitchRangeBlade {
    table: BladeTable,
    mesh: Mesh,
    beam: Beam,
    basis: Arc<DMatrix<f64>>,
    mass: Harmonics,
    k0: Harmonics,
    k_omega: Harmonics,
    damping: Option<Harmonics>,
    family: [Harmonics; 3],
    /// `Φᵀ` of [`BladeMatrices::curve_loads`], the centrifugal load with the curve turned by 0
    /// and by 90° (b × 1 each): the curve turns with the pitch, so its load at pitch `p` is
    /// `cos p · first + sin p · second`, each of those an ordinary matrix term in `p`.
    curve_load: [Harmonics; 2],
    /// `Φᵀ M r` (b × 4) and `rᵢᵀ M rⱼ` (4 × 4) of the rigid motions with the hub: the mass
    /// turns with the pitch, the motions do not.
    rigid: Harmonics,
    rigid_mass: Harmonics,
}

impl PitchRangeBlade {
    /// The basis of the lowest `per_speed` modes at each of `pitches` (rad) and `speeds`
    /// (rad/s), compressed by a proper orthogonal decomposition, and the Fourier terms of the
    /// blade's matrices projected on it; with stiffness-proportional `damping`, its matrix too.
    pub fn new(
        table: &BladeTable,
        mesh: &Mesh,
        pitches: &[f64],
        speeds: &[f64],
        per_speed: usize,
        damping: Option<StiffnessFactors>,
    ) -> Result<PitchRangeBlade> {
        // The snapshots' solves and the Fourier samples' assemblies share the cores.
        let (snapshots, samples) = rayon::join(
            || {
                pitches
                    .par_iter()
                    .map(|&pitch| {
                        let matrices = assemble_banded(table, mesh, pitch)?;
                        lowest_modes_basis(&matrices, speeds, per_speed)
                    })
                    .collect::<Result<Vec<DMatrix<f64>>>>()
            },
            || {
                (0..SAMPLES)
                    .into_par_iter()
                    .map(|k| assemble_banded(table, mesh, sample_pitch(k)))
                    .collect::<Result<Vec<BladeMatrices<SymmetricBand>>>>()
            },
        );
        let (snapshots, samples) = (snapshots?, samples?);
        let basis = compressed(&samples[0].mass, &snapshots, &table.origin)?;
        // Each sample's projections, the samples on all cores: `[M, K₀, K_Ω]` and the mass's
        // three families.
        let reduced: Vec<SampleProjections> = samples
            .par_iter()
            .map(|s| SampleProjections {
                matrices: [
                    projected(&s.mass, &basis),
                    projected(&s.k0, &basis),
                    projected(&s.k_omega, &basis),
                ],
                family: reduced_family_mass(&s.mass, &basis, &s.beam.layout()),
            })
            .collect();
        let harmonics = |of: &dyn Fn(&SampleProjections) -> &DMatrix<f64>| {
            Harmonics::from_samples(&reduced.iter().map(|r| of(r).clone()).collect::<Vec<_>>())
        };
        let damping = damping
            .map(|f| {
                let on_basis = (0..SAMPLES)
                    .into_par_iter()
                    .map(|k| {
                        stiffness_damping(table, mesh, sample_pitch(k), f)
                            .map(|c| projected(&c, &basis))
                    })
                    .collect::<Result<Vec<_>>>()?;
                Ok::<_, Error>(Harmonics::from_samples(&on_basis))
            })
            .transpose()?;
        let family = [0, 1, 2].map(|g| harmonics(&|r| &r.family[g]));
        let curve_load = [0, 1].map(|turn| {
            Harmonics::from_samples(
                &samples
                    .iter()
                    .map(|s| {
                        let load = basis.tr_mul(&s.curve_loads[turn]);
                        DMatrix::from_column_slice(load.len(), 1, load.as_slice())
                    })
                    .collect::<Vec<_>>(),
            )
        });
        let rigid = Harmonics::from_samples(
            &samples
                .iter()
                .map(|s| basis.tr_mul(&s.rigid_loads))
                .collect::<Vec<_>>(),
        );
        let rigid_mass = Harmonics::from_samples(
            &samples
                .iter()
                .map(|s| s.rigid_mass.clone())
                .collect::<Vec<_>>(),
        );
        Ok(PitchRangeBlade {
            curve_load,
            rigid,
            rigid_mass,
            table: table.clone(),
            mesh: mesh.clone(),
            beam: Beam::of(table),
            mass: harmonics(&|r| &r.matrices[0]),
            k0: harmonics(&|r| &r.matrices[1]),
            k_omega: harmonics(&|r| &r.matrices[2]),
            damping,
            family,
            basis: Arc::new(basis),
        })
    }

    /// Size of the basis.
    pub fn basis_size(&self) -> usize {
        self.basis.ncols()
    }

    /// The blade at `pitch` (rad) on this basis: its modes at any rotor speed then follow from
    /// [`ModalBlade::modes`].
    pub fn at(&self, pitch: f64) -> Result<ModalBlade> {
        let projections = Projections {
            mass: self.mass.at(pitch),
            k0: self.k0.at(pitch),
            k_omega: self.k_omega.at(pitch),
            damping: self.damping.as_ref().map(|d| d.at(pitch)),
            family: [0, 1, 2].map(|g| self.family[g].at(pitch)),
            centrifugal_load: self.curve_load[0].at(pitch).column(0) * pitch.cos()
                + self.curve_load[1].at(pitch).column(0) * pitch.sin(),
            rigid: self.rigid.at(pitch),
            rigid_mass: self.rigid_mass.at(pitch),
        };
        let geometry = BladeGeometry {
            table: self.table.clone(),
            mesh: self.mesh.clone(),
            pitch,
            beam: self.beam,
        };
        ModalBlade::from_projections(geometry, Arc::clone(&self.basis), &projections)
    }
}

/// The banded form of a symmetric matrix.
/// One basis for all `snapshots` (each dofs × k): M-orthonormalised together, then only the
/// directions whose singular value in the snapshots exceeds [`POD_TOLERANCE`] of the largest
/// (proper orthogonal decomposition in the M inner product).
fn compressed(
    mass: &SymmetricBand,
    snapshots: &[DMatrix<f64>],
    origin: &str,
) -> Result<DMatrix<f64>> {
    let columns: Vec<DVector<f64>> = snapshots
        .iter()
        .flat_map(|s| s.column_iter().map(|c| c.into_owned()))
        .collect();
    let all = DMatrix::from_columns(&columns);
    let q = m_orthonormal(mass, columns);
    // The snapshots' coordinates in Q (Q M-orthonormal): C = Qᵀ M S.
    let c = q.tr_mul(&mass.mul(&all));
    let svd = c.svd(true, false);
    let u = svd
        .u
        .ok_or_else(|| Error::numerical(format!("{origin}: pitch-range basis SVD failed")))?;
    let largest = svd.singular_values.max();
    let kept: Vec<usize> = (0..svd.singular_values.len())
        .filter(|&i| svd.singular_values[i] > POD_TOLERANCE * largest)
        .collect();
    if kept.is_empty() {
        return Err(Error::numerical(format!(
            "{origin}: blade pitch-range basis is empty"
        )));
    }
    Ok(q * u.select_columns(&kept))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::text_file::DiskFile;
    use crate::physics::blade::axis::CurvedAxis;
    use crate::physics::blade::fem::assemble;
    use crate::physics::blade::source::{read_beamdyn, read_hawc2, read_twist};

    /// The built-in presets' two blades, as their files describe them, and the IEA 15MW on its
    /// prebent axis.
    fn blades() -> [(&'static str, BladeTable); 3] {
        let file = |name: &str| {
            DiskFile(
                std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                    .join("presets/blades")
                    .join(name),
            )
        };
        let nrel5mw = read_beamdyn(&file("nrel5mw/NRELOffshrBsline5MW_BeamDyn.dat")).unwrap();
        let twist = read_twist(&file("iea15mw/IEA-15-240-RWT_AeroDyn15_blade.dat")).unwrap();
        let iea15mw = read_hawc2(
            &file("iea15mw/IEA_15MW_RWT_Blade_st_noFPM.st"),
            &twist,
            1,
            1,
        )
        .unwrap();
        let prebend = crate::physics::rotor::files::read_prebend(&file(
            "iea15mw/IEA-15-240-RWT_AeroDyn15_blade.dat",
        ))
        .unwrap();
        let points: Vec<(f64, [f64; 2])> = prebend.iter().map(|&(s, x)| (s, [x, 0.0])).collect();
        let curved = iea15mw
            .table
            .clone()
            .with_axis(CurvedAxis::new("prebend", &points).unwrap());
        [
            ("nrel5mw", nrel5mw.table),
            ("iea15mw", iea15mw.table),
            ("iea15mw prebent", curved),
        ]
    }

    /// The centrifugal load of the prebent blade at any pitch, from the basis's two curve
    /// terms, is the projection of the load assembled at that pitch (docs/model.md §11.9).
    #[test]
    fn the_curve_load_turns_with_the_pitch() {
        let [.., (_, table)] = blades();
        let mesh = Mesh::following(&table, 30);
        let blade = PitchRangeBlade::new(&table, &mesh, &[0.0, 1.2], &[0.0, 0.8], 8, None).unwrap();
        for pitch in [0.0, 0.37, 1.1, 1.5] {
            let exact = blade
                .basis
                .tr_mul(&assemble(&table, &mesh, pitch).unwrap().centrifugal_load());
            let from_terms = blade.curve_load[0].at(pitch).column(0) * pitch.cos()
                + blade.curve_load[1].at(pitch).column(0) * pitch.sin();
            let error = (&from_terms - &exact).amax() / exact.amax();
            assert!(
                exact.amax() > 0.0 && error < 1e-10,
                "pitch {pitch}: {error:e}"
            );
        }
    }

    /// The five Fourier terms rebuild every assembled matrix at pitches off the samples, to
    /// round-off: the elements are exactly quadratic in cos θ, sin θ (docs/model.md §11.8).
    #[test]
    fn five_fourier_terms_rebuild_the_matrices_at_any_pitch() {
        for (name, table) in blades() {
            let mesh = Mesh::following(&table, 30);
            let samples: Vec<BladeMatrices> = (0..SAMPLES)
                .map(|k| assemble(&table, &mesh, sample_pitch(k)).unwrap())
                .collect();
            // The bands the bases are built from are the dense matrices' bands.
            for (k, dense) in samples.iter().enumerate() {
                let banded = assemble_banded(&table, &mesh, sample_pitch(k)).unwrap();
                for (b, d) in [
                    (&banded.mass, &dense.mass),
                    (&banded.k0, &dense.k0),
                    (&banded.k_omega, &dense.k_omega),
                ] {
                    let scale = d.amax();
                    let n = d.nrows();
                    let worst = (0..n)
                        .flat_map(|i| (0..n).map(move |j| (i, j)))
                        .map(|(i, j)| (b.get(i, j) - d[(i, j)]).abs())
                        .fold(0.0, f64::max);
                    assert!(worst <= 1e-14 * scale, "{name}: {worst:e} of {scale:e}");
                }
            }
            let terms = |f: fn(&BladeMatrices) -> &DMatrix<f64>| {
                Harmonics::from_samples(&samples.iter().map(|s| f(s).clone()).collect::<Vec<_>>())
            };
            let (m, k0, kw) = (terms(|s| &s.mass), terms(|s| &s.k0), terms(|s| &s.k_omega));
            for pitch in [-0.3, 0.1234, 0.9, 1.4, 2.5] {
                let exact = assemble(&table, &mesh, pitch).unwrap();
                for (fourier, assembled) in [
                    (m.at(pitch), &exact.mass),
                    (k0.at(pitch), &exact.k0),
                    (kw.at(pitch), &exact.k_omega),
                ] {
                    let error = (&fourier - assembled).amax() / assembled.amax();
                    assert!(error < 1e-12, "{name} at pitch {pitch} rad: {error:e}");
                }
            }
        }
    }

    #[test]
    fn snapshots_span_the_range_at_most_a_step_apart() {
        let deg = |d: f64| d.to_radians();
        let p = snapshot_pitches(0.0, deg(90.0));
        assert_eq!(p.len(), 4);
        assert!((p[3] - deg(90.0)).abs() < 1e-15 && p[0] == 0.0);
        let wide = snapshot_pitches(deg(-5.0), deg(90.0));
        assert_eq!(wide.len(), 5);
        assert!(wide
            .windows(2)
            .all(|w| w[1] - w[0] <= SNAPSHOT_STEP + 1e-15));
    }
}
