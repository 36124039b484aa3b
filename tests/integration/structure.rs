//! Galerkin basis and structural-matrix unit checks (docs/model.md §4).

use flutterscope::model::assemble;
use flutterscope::physics::basis::{bending_root, gauss_legendre, Basis};
use flutterscope::physics::structure::mode_labels;
use flutterscope::preset::{Preset, ValidPreset};
use nalgebra::{Complex, DMatrix};

/// ∫₀ᴸ f over a Gauss rule of `points` points.
fn integrate(l: f64, points: usize, f: impl Fn(f64) -> DMatrix<f64>) -> DMatrix<f64> {
    let (t, w) = gauss_legendre(points);
    let h = 0.5 * l;
    t.iter()
        .zip(&w)
        .map(|(t, w)| f(h * (t + 1.0)) * (h * w))
        .reduce(|a, b| a + b)
        .unwrap()
}

fn assert_close(a: &DMatrix<f64>, b: &DMatrix<f64>, tol: f64, what: &str) {
    let err = (a - b).amax();
    assert!(err <= tol, "{what}: max error {err:e} > {tol:e}");
}

#[test]
fn bending_functions_are_orthogonal_with_known_norms() {
    let l = 3.7;
    let n = 20;
    let basis = Basis::new(n, l);
    let pts = Basis::quadrature_points(n);
    let uu = integrate(l, pts, |x| {
        let u = basis.bending(x, 0);
        &u * u.transpose()
    });
    assert_close(
        &uu,
        &(DMatrix::identity(n, n) * l),
        1e-10 * l,
        "∫U_iU_j = L δ_ij",
    );
    let dd = integrate(l, pts, |x| {
        let u = basis.bending(x, 2);
        &u * u.transpose()
    });
    let expect = DMatrix::from_fn(n, n, |i, j| {
        if i == j {
            bending_root(i + 1).powi(4) / l.powi(3)
        } else {
            0.0
        }
    });
    let scale = expect.amax();
    assert_close(&dd, &expect, 1e-10 * scale, "∫U''_iU''_j = (β_iL)⁴/L³ δ_ij");
}

#[test]
fn torsion_functions_are_orthogonal_with_known_norms() {
    let l = 2.5;
    let n = 20;
    let basis = Basis::new(n, l);
    let pts = Basis::quadrature_points(n);
    let pp = integrate(l, pts, |x| {
        let p = basis.torsion(x, 0);
        &p * p.transpose()
    });
    assert_close(
        &pp,
        &(DMatrix::identity(n, n) * (l / 2.0)),
        1e-12,
        "∫Φ_iΦ_j = L/2 δ_ij",
    );
    let dd = integrate(l, pts, |x| {
        let p = basis.torsion(x, 1);
        &p * p.transpose()
    });
    let expect = DMatrix::from_fn(n, n, |i, j| {
        let k = (2 * i + 1) as f64 * std::f64::consts::FRAC_PI_2 / l;
        if i == j {
            k * k * l / 2.0
        } else {
            0.0
        }
    });
    assert_close(&dd, &expect, 1e-10 * expect.amax(), "∫Φ'_iΦ'_j");
}

#[test]
fn quadrature_rule_is_converged_for_every_basis_product() {
    // The assembly's rule against one twice as rich: every product must agree to 1e-10 relative.
    for n in [1, 5, 12, 20, 40] {
        let l = 1.3;
        let basis = Basis::new(n, l);
        let products = |x: f64| {
            let (p1, u1, u2) = (
                basis.torsion(x, 1),
                basis.bending(x, 1),
                basis.bending(x, 2),
            );
            let mut m = DMatrix::zeros(3 * n, n);
            m.view_mut((0, 0), (n, n))
                .copy_from(&(&p1 * u2.transpose()));
            m.view_mut((n, 0), (n, n))
                .copy_from(&(&u2 * u2.transpose()));
            // Centrifugal weight: a quadratic in x times U'U'.
            m.view_mut((2 * n, 0), (n, n))
                .copy_from(&(&u1 * u1.transpose() * (l * l - x * x)));
            m
        };
        let pts = Basis::quadrature_points(n);
        let a = integrate(l, pts, products);
        let b = integrate(l, 2 * pts, products);
        assert_close(&a, &b, 1e-10 * b.amax(), &format!("N = {n}"));
    }
}

#[test]
fn bending_functions_satisfy_cantilever_conditions_for_large_j() {
    let l = 1.0;
    let basis = Basis::new(60, l);
    let u0 = basis.bending(0.0, 0);
    let u0p = basis.bending(0.0, 1);
    let ulpp = basis.bending(l, 2);
    let ulppp = basis.bending(l, 3);
    let tip = basis.bending(l, 0);
    for j in 0..60 {
        let b = bending_root(j + 1);
        assert!(u0[j].abs() < 1e-12, "U_{}(0) = {}", j + 1, u0[j]);
        assert!(u0p[j].abs() < 1e-12 * b, "U'_{}(0)", j + 1);
        assert!(
            ulpp[j].abs() < 1e-10 * b * b,
            "U''_{}(L) = {}",
            j + 1,
            ulpp[j]
        );
        assert!(ulppp[j].abs() < 1e-10 * b.powi(3), "U'''_{}(L)", j + 1);
        // |U_j(L)| = 2 for every cantilever function.
        assert!(
            (tip[j].abs() - 2.0).abs() < 1e-9,
            "U_{}(L) = {}",
            j + 1,
            tip[j]
        );
    }
}

fn paper_blade(extra: &[&str]) -> ValidPreset {
    let mut sets = vec![
        "operating.rotor_speed=0".to_string(),
        "structure.loss_factor=0".to_string(),
    ];
    sets.extend(extra.iter().map(|s| s.to_string()));
    Preset::load("liu2017", &sets).unwrap()
}

#[test]
fn weak_form_matrices_are_symmetric_and_strong_form_is_not() {
    let weak = assemble(&paper_blade(&["operating.rotor_speed=60"])).unwrap();
    for a in [
        &weak.mass,
        &weak.elastic,
        &weak.centrifugal,
        &weak.stiffness(),
    ] {
        assert_close(a, &a.transpose(), 0.0, "symmetry");
    }
    let strong = assemble(&paper_blade(&["structure.form=strong"])).unwrap();
    let asym = (&strong.elastic - strong.elastic.transpose()).amax();
    assert!(
        asym > 1e-3 * strong.elastic.amax().min(1.0),
        "strong form symmetric: {asym}"
    );
    // The strong form differs only in the flap–twist block.
    let n = strong.n;
    let diff = &strong.elastic - &weak.elastic;
    assert_eq!(diff.view((0, 0), (n, 2 * n)).amax(), 0.0);
    assert_eq!(diff.view((n, n), (n, n)).amax(), 0.0);
}

#[test]
fn damping_is_loss_factor_over_omega1_times_elastic() {
    let p = paper_blade(&["structure.loss_factor=0.02", "operating.rotor_speed=60"]);
    let s = assemble(&p).unwrap();
    let modes = s.natural_modes().unwrap();
    let w1 = 2.0 * std::f64::consts::PI * modes[0].frequency_hz;
    assert!((s.omega1 - w1).abs() < 1e-9 * w1);
    assert_close(
        &s.damping,
        &(&s.elastic * (0.02 / w1)),
        1e-12 * s.damping.amax(),
        "C_s",
    );
}

#[test]
fn rotation_stiffens_the_blade() {
    let still = assemble(&paper_blade(&[])).unwrap();
    let spinning = assemble(&paper_blade(&["operating.rotor_speed=60"])).unwrap();
    assert_eq!(still.centrifugal.amax(), 0.0);
    assert!(spinning.omega1 > 1.5 * still.omega1);
}

#[test]
fn tip_rows_pick_the_tip_values() {
    let s = assemble(&paper_blade(&[])).unwrap();
    let twist = s.tip_twist_row();
    let flap = s.tip_flap_row();
    for j in 0..s.n {
        assert!((twist[j] - if j % 2 == 0 { 1.0 } else { -1.0 }).abs() < 1e-12);
        assert!((flap[j].abs() - 2.0).abs() < 1e-9);
    }
}

#[test]
fn torsion_share_is_phase_invariant_and_bounded() {
    let s = assemble(&paper_blade(&[])).unwrap();
    let modes = s.natural_modes().unwrap();
    for m in &modes {
        let rot = Complex::from_polar(1.0, 0.7);
        let q: Vec<Complex<f64>> = m.shape.iter().map(|&v| rot * v).collect();
        let share = s.torsion_share(&q);
        assert!((share - m.torsion_share).abs() < 1e-12);
        assert!((0.0..=1.0).contains(&share));
    }
    // Pure coordinates are pure kinds.
    let mut q = vec![Complex::new(0.0, 0.0); 2 * s.n];
    q[0] = Complex::new(0.0, 1.0);
    assert_eq!(s.torsion_share(&q), 1.0);
    q[0] = Complex::new(0.0, 0.0);
    q[s.n] = Complex::new(1.0, 0.0);
    assert_eq!(s.torsion_share(&q), 0.0);
}

#[test]
fn labels_count_within_their_kind() {
    let labels = mode_labels(&[0.1, 0.0, 0.9, 0.4, 0.51]);
    assert_eq!(
        labels,
        ["flap 1", "flap 2", "torsion 1", "flap 3", "torsion 2"]
    );
}

/// A non-finite section never reaches the structure: the structure takes only a checked preset,
/// and checking names the key.
#[test]
fn non_finite_section_is_refused_before_assembly() {
    let mut p = paper_blade(&["section.source=direct"]).into_preset();
    p.section.c33 = f64::NAN;
    match p.validate() {
        Err(flutterscope::error::Error::Range { key, .. }) => assert_eq!(key, "section.c33"),
        other => panic!("expected a range error, got {other:?}"),
    }
    let mut p = paper_blade(&[]).into_preset();
    p.blade.length = f64::INFINITY;
    assert!(p.validate().is_err());
}

#[test]
fn every_mode_count_from_1_to_20_assembles() {
    for n in 1..=20 {
        for form in ["weak", "strong"] {
            let p = paper_blade(&[
                &format!("structure.modes={n}"),
                &format!("structure.form={form}"),
                "operating.rotor_speed=60",
            ]);
            let s = assemble(&p).unwrap();
            let modes = s.natural_modes().unwrap();
            assert_eq!(modes.len(), 2 * n);
            assert!(modes
                .windows(2)
                .all(|w| w[0].frequency_hz <= w[1].frequency_hz));
        }
    }
}

#[test]
fn assembled_matrices_equal_direct_quadrature_on_the_blade() {
    // Assembly scales unit-span integrals by L and the hub; compare every block with quadrature
    // of the public basis on [0, L] itself, with a hub, rotation and a cg offset all live.
    let (l, hub, n) = (3.3, 0.7, 6);
    let p = Preset::from_toml(
        &format!(
            "[blade]\nlength = {l}\nhub_radius = {hub}\n[operating]\nrotor_speed = 90.0\n\
             [structure]\nmodes = {n}\n[section]\nsource = \"direct\"\nc22 = 2.0\nc23 = -0.4\n\
             c33 = 1.5\nmass_per_length = 0.8\npolar_inertia = 0.003\nka2 = 0.02\nkm1_2 = 0.001\n\
             km2_2 = 0.01\ncg_offset = 0.004\nchord = 0.2\nea_offset = 0.01\n"
        ),
        "test",
        &[],
    )
    .unwrap();
    let s = assemble(&p).unwrap();
    let sec = s.section;
    let omega = p.omega();
    let basis = Basis::new(n, l);
    let pts = 4 * n + 30;
    let fc = |x: f64| 0.5 * sec.m * omega * omega * ((hub + l).powi(2) - (hub + x).powi(2));
    let expect = integrate(l, pts, |x| {
        let (p0, p1) = (basis.torsion(x, 0), basis.torsion(x, 1));
        let (u0, u1, u2) = (
            basis.bending(x, 0),
            basis.bending(x, 1),
            basis.bending(x, 2),
        );
        let mut m = DMatrix::zeros(6 * n, 2 * n);
        // Rows 0..2N: mass; 2N..4N: elastic; 4N..6N: centrifugal.
        m.view_mut((0, 0), (n, n))
            .copy_from(&(&p0 * p0.transpose() * sec.i));
        m.view_mut((0, n), (n, n))
            .copy_from(&(&p0 * u0.transpose() * (sec.m * sec.cg_offset)));
        m.view_mut((n, 0), (n, n))
            .copy_from(&(&u0 * p0.transpose() * (sec.m * sec.cg_offset)));
        m.view_mut((n, n), (n, n))
            .copy_from(&(&u0 * u0.transpose() * sec.m));
        m.view_mut((2 * n, 0), (n, n))
            .copy_from(&(&p1 * p1.transpose() * sec.c22));
        m.view_mut((2 * n, n), (n, n))
            .copy_from(&(&p1 * u2.transpose() * sec.c23));
        m.view_mut((3 * n, 0), (n, n))
            .copy_from(&(&u2 * p1.transpose() * sec.c23));
        m.view_mut((3 * n, n), (n, n))
            .copy_from(&(&u2 * u2.transpose() * sec.c33));
        let prop = sec.m * omega * omega * (sec.km2_2 - sec.km1_2);
        m.view_mut((4 * n, 0), (n, n))
            .copy_from(&(&p1 * p1.transpose() * (fc(x) * sec.ka2) + &p0 * p0.transpose() * prop));
        m.view_mut((5 * n, n), (n, n))
            .copy_from(&(&u1 * u1.transpose() * fc(x)));
        m
    });
    let pick = |row: usize| expect.view((row, 0), (2 * n, 2 * n)).into_owned();
    assert_close(&s.mass, &pick(0), 1e-11 * s.mass.amax(), "M");
    assert_close(&s.elastic, &pick(2 * n), 1e-11 * s.elastic.amax(), "K_e");
    assert_close(
        &s.centrifugal,
        &pick(4 * n),
        1e-11 * s.centrifugal.amax(),
        "K_c",
    );
    assert!(s.centrifugal.amax() > 0.0 && s.mass[(0, n)] != 0.0);
}
