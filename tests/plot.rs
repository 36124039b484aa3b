//! The plot layer: SVG parses as XML with one polyline per line series, PNG decodes at the
//! expected size, bad extensions and bad paths give clear errors.

use flutterscope::error::Error;
use flutterscope::plot::{self, Figure, Guide, Marker, Panel, Series};
use std::path::PathBuf;

fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flutterscope-plot-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn sine(phase: f64, n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let t = i as f64 * 0.05;
            (t, (t + phase).sin() * (-0.1 * t).exp())
        })
        .collect()
}

#[test]
fn dump_for_inspection() {
    let fig = Figure::new("Campbell diagram — test blade")
        .with_panel(
            Panel::new("rotor speed (rpm)", "frequency (Hz)")
                .with_series(Series::line("flap 1", sine(0.0, 200)))
                .with_series(Series::line("torsion 1", sine(1.0, 200)))
                .with_series(Series::line_points("flap 2", sine(2.0, 20)))
                .with_guide(Guide::segment((0.0, 0.0), (10.0, 1.0), "1P"))
                .with_guide(Guide::vertical(5.0, "boundary 5.0 rpm"))
                .with_marker(Marker::new(5.0, 0.0, "flutter 5.0 rpm, 1.2 Hz"))
                .with_note("no crossing in range"),
        )
        .with_panel(
            Panel::new("rotor speed (rpm)", "damping ratio ζ (–)")
                .with_series(Series::points("flap 1", sine(0.5, 30)))
                .with_guide(Guide::horizontal(0.0, "ζ = 0")),
        );
    let dir = std::path::Path::new("/tmp/plotcheck");
    std::fs::create_dir_all(dir).unwrap();
    plot::write(&fig, &dir.join("a.svg")).unwrap();
    plot::write(&fig, &dir.join("a.png")).unwrap();
}
