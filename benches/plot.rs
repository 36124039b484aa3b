//! Writing plots: any single plot under 200 ms. Figures of realistic size are drawn
//! and written to a temporary file as SVG and PNG: a Campbell diagram (16 tracked modes over
//! 201 rotor speeds, 1P/3P lines, two panels) and a tip response (20 000 samples, two panels).

use flutterscope::plot::{self, Figure, Guide, Marker, Panel, Series};
use std::path::PathBuf;

fn main() {
    divan::main();
}

fn campbell() -> Figure {
    let speeds: Vec<f64> = (0..=200).map(|i| i as f64).collect();
    let mut freq = Panel::new("operating.rotor_speed (rpm)", "frequency (Hz)");
    let mut damp = Panel::new("operating.rotor_speed (rpm)", "damping ratio ζ (–)")
        .with_guide(Guide::horizontal(0.0, "ζ = 0"))
        .with_guide(Guide::vertical(150.0, "flutter 150 rpm"))
        .with_marker(Marker::new(150.0, 0.0, "flutter at 150 rpm, 3.1 Hz"));
    for k in 0..16 {
        let f0 = 0.5 + k as f64 * 1.3;
        let name = format!("mode {}", k + 1);
        let f: Vec<(f64, f64)> = speeds
            .iter()
            .map(|&w| (w, f0 + 0.002 * k as f64 * w))
            .collect();
        let z: Vec<(f64, f64)> = speeds
            .iter()
            .map(|&w| (w, 0.02 - 1e-4 * w * (k as f64 / 16.0)))
            .collect();
        freq.series.push(Series::line(name.clone(), f));
        damp.series.push(Series::line(name, z));
    }
    for n in [1.0, 3.0] {
        freq.guides.push(Guide::segment(
            (0.0, 0.0),
            (200.0, n * 200.0 / 60.0),
            format!("{n}P"),
        ));
    }
    Figure::new("Campbell diagram — bench")
        .with_panel(freq)
        .with_panel(damp)
}

fn response() -> Figure {
    let n = 20_000;
    let twist: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let t = i as f64 * 1e-3;
            (t, 0.01 * (60.0 * t).sin() * (-0.3 * t).exp())
        })
        .collect();
    let flap: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let t = i as f64 * 1e-3;
            (t, 0.2 * (6.0 * t).sin() * (-0.1 * t).exp())
        })
        .collect();
    Figure::new("Tip response — bench")
        .with_panel(
            Panel::new("time t (s)", "tip twist (rad)").with_series(Series::line("φ", twist)),
        )
        .with_panel(Panel::new("time t (s)", "tip flap (m)").with_series(Series::line("u", flap)))
}

fn target(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("flutterscope-bench-{}-{name}", std::process::id()))
}

#[divan::bench(args = ["svg", "png"])]
fn write_campbell(b: divan::Bencher, ext: &str) {
    let fig = campbell();
    let path = target(&format!("campbell.{ext}"));
    b.bench(|| plot::write(divan::black_box(&fig), &path).unwrap());
    std::fs::remove_file(&path).ok();
}

#[divan::bench(args = ["svg", "png"])]
fn write_response(b: divan::Bencher, ext: &str) {
    let fig = response();
    let path = target(&format!("response.{ext}"));
    b.bench(|| plot::write(divan::black_box(&fig), &path).unwrap());
    std::fs::remove_file(&path).ok();
}

/// The terminal rendering of one panel (reproduce's braille plots).
#[divan::bench]
fn braille_panel(b: divan::Bencher) {
    let fig = campbell();
    b.bench(|| plot::text::render(divan::black_box(&fig.panels[0]), 100, 24, false));
}

/// `reproduce fig5` end to end without printing: 2 models × 5 ply angles analysed, the figure
/// written (target: under 1 s).
#[divan::bench(sample_count = 20)]
fn reproduce_fig5(b: divan::Bencher) {
    use flutterscope::commands::reproduce::paper_figures;
    let path = target("fig5.svg");
    b.bench(|| {
        let f = paper_figures::fig5().unwrap();
        plot::write(&paper_figures::fig5_figure(&f), &path).unwrap();
    });
    std::fs::remove_file(&path).ok();
}

/// The paper figures' plots alone (data computed once): each under 200 ms.
#[divan::bench(args = ["fig2", "fig3", "fig5"], sample_count = 20)]
fn write_paper_figure(b: divan::Bencher, which: &str) {
    use flutterscope::commands::reproduce::paper_figures;
    let fig = match which {
        "fig2" => paper_figures::fig2_figure(&paper_figures::fig2().unwrap()),
        "fig3" => paper_figures::tip_figure(
            &paper_figures::tip_runs(paper_figures::TipQuantity::TipTwist).unwrap(),
        ),
        _ => paper_figures::fig5_figure(&paper_figures::fig5().unwrap()),
    };
    let path = target(&format!("{which}.png"));
    b.bench(|| plot::write(divan::black_box(&fig), &path).unwrap());
    std::fs::remove_file(&path).ok();
}
