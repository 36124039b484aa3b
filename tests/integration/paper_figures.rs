//! `reproduce fig2..fig5`: each figure's series have the expected count and lengths
//! and only finite values; the findings name ply angles from the paper's set; the figures draw.

use flutterscope::commands::reproduce::paper_figures::{self, TipQuantity, MODELS, PLY_ANGLES};
use flutterscope::plot::{self, Mark};

fn all_finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

#[test]
fn fig5_has_four_real_parts_per_model_and_angle() {
    let f = paper_figures::fig5().unwrap();
    assert_eq!(f.rows.len(), MODELS.len() * PLY_ANGLES.len());
    for r in &f.rows {
        assert_eq!(r.roots.len(), 4, "{} {}°", r.model, r.ply_angle);
        assert!(r.roots.iter().all(|x| x.re.is_finite() && x.im.is_finite()));
        // Rightmost first.
        assert!(r.roots.windows(2).all(|w| w[0].re >= w[1].re));
    }
    assert_eq!(f.findings.len(), 2);
    for fd in &f.findings {
        assert!(PLY_ANGLES.contains(&fd.most_stable_ply_angle));
        assert!(PLY_ANGLES.contains(&fd.least_stable_ply_angle));
        assert_ne!(fd.most_stable_ply_angle, fd.least_stable_ply_angle);
        let at = |a: f64| fd.largest_re.iter().find(|x| x.0 == a).unwrap().1;
        for &(_, re) in &fd.largest_re {
            assert!(at(fd.most_stable_ply_angle) <= re && re <= at(fd.least_stable_ply_angle));
        }
    }
    let fig = paper_figures::fig5_figure(&f);
    assert_eq!(fig.panels.len(), 2);
    for p in &fig.panels {
        assert_eq!(p.series.len(), 4);
        for s in &p.series {
            assert_eq!(s.style.mark, Mark::LinePoints);
            let xs: Vec<f64> = s.points.iter().map(|p| p.0).collect();
            assert_eq!(xs, PLY_ANGLES);
            assert!(s.points.iter().all(|p| p.1.is_finite()));
        }
    }
    assert!(plot::render_svg(&fig).is_ok());
}

#[test]
fn fig3_and_fig4_have_five_runs_per_model_side_by_side() {
    for q in [TipQuantity::TipTwist, TipQuantity::TipFlap] {
        let f = paper_figures::tip_runs(q).unwrap();
        assert_eq!(f.runs.len(), 10);
        for r in &f.runs {
            assert!(
                r.t.len() > 100,
                "{} {}°: {} samples",
                r.model,
                r.ply_angle,
                r.t.len()
            );
            assert_eq!(r.t.len(), r.values.len());
            assert!(all_finite(&r.t) && all_finite(&r.values));
            assert_eq!(r.t[0], 0.0);
        }
        let fig = paper_figures::tip_figure(&f);
        assert_eq!(fig.columns, 2);
        assert_eq!(fig.panels.len(), 2);
        for (p, &(model, _)) in fig.panels.iter().zip(&MODELS) {
            assert!(p.title.contains(model));
            assert_eq!(p.series.len(), PLY_ANGLES.len());
            let names: Vec<String> = PLY_ANGLES.iter().map(|a| format!("θ = {a}°")).collect();
            assert_eq!(
                p.series.iter().map(|s| s.name.clone()).collect::<Vec<_>>(),
                names
            );
        }
    }
}

#[test]
fn fig2_has_every_state_and_ten_eigenvalues() {
    let f = paper_figures::fig2().unwrap();
    assert_eq!(f.eigenvalues.len(), 10);
    assert!(f.eigenvalues.windows(2).all(|w| w[0].re >= w[1].re));
    let count = |g: &str| f.states.iter().filter(|s| s.group == g).count();
    // N = 5 Galerkin functions per field: 10 coordinates, 10 rates; ONERA adds aero states.
    assert_eq!(count("displacement"), 10);
    assert_eq!(count("velocity"), 10);
    assert!(count("aerodynamic") > 0);
    assert!(f.t.len() > 100);
    for s in &f.states {
        assert_eq!(s.values.len(), f.t.len(), "{}", s.name);
        assert!(all_finite(&s.values), "{}", s.name);
    }
    let fig = paper_figures::fig2_figure(&f);
    assert_eq!(fig.panels.len(), 4);
    let drawn: usize = fig.panels[..3].iter().map(|p| p.series.len()).sum();
    assert_eq!(drawn, f.states.len());
    assert_eq!(fig.panels[3].series[0].points.len(), 10);
    assert!(plot::render_png(&fig).is_ok());
}
