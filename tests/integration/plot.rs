//! The plot layer (`flutterscope::plot`): SVG output parses as XML and carries exactly one
//! `<polyline>` per line series, PNG output decodes at the expected size with text drawn from
//! the embedded font, and bad extensions, bad paths and malformed figures give clear errors.

use flutterscope::error::Error;
use flutterscope::plot::{self, Figure, Format, Guide, Marker, Panel, Rgb, Series, DEFAULT_SIZE};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A fresh directory for one test's files.
fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flutterscope-plot-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// With `FLUTTERSCOPE_PLOT_KEEP=DIR`, copy a written plot there for a look by eye.
fn keep(path: &Path) {
    if let Some(dir) = std::env::var_os("FLUTTERSCOPE_PLOT_KEEP") {
        let dir = PathBuf::from(dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::copy(path, dir.join(path.file_name().unwrap())).unwrap();
    }
}

/// A decaying oscillation sampled at `n` points, like a tip response.
fn decay(phase: f64, n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let t = i as f64 * 0.05;
            (t, (3.0 * t + phase).sin() * (-0.2 * t).exp())
        })
        .collect()
}

const BLUE: Rgb = Rgb(0, 114, 178);
const RED: Rgb = Rgb(213, 94, 0);
const GREEN: Rgb = Rgb(0, 158, 115);
const PURPLE: Rgb = Rgb(204, 121, 167);
const ORANGE: Rgb = Rgb(230, 159, 0);

fn hex(c: Rgb) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// A Campbell-like figure: two stacked panels with line, line+points and point series, guides,
/// a marker and a note; every series has its own colour.
fn campbell_like() -> Figure {
    let speeds: Vec<f64> = (0..=40).map(|i| i as f64 * 5.0).collect();
    let freq =
        |f0: f64, k: f64| -> Vec<(f64, f64)> { speeds.iter().map(|&w| (w, f0 + k * w)).collect() };
    Figure::new("Campbell diagram — ζ and f vs Ω")
        .with_panel(
            Panel::new("rotor speed (rpm)", "frequency (Hz)")
                .titled("(a) frequency")
                .with_series(Series::line("flap 1", freq(0.6, 0.004)).with_color(BLUE))
                .with_series(Series::line("flap 2", freq(1.7, 0.006)).with_color(RED))
                .with_series(Series::line_points("torsion 1", freq(2.9, 0.0)).with_color(GREEN))
                .with_guide(Guide::segment((0.0, 0.0), (200.0, 200.0 / 60.0), "1P"))
                .with_guide(Guide::segment((0.0, 0.0), (200.0, 600.0 / 60.0), "3P")),
        )
        .with_panel(
            Panel::new("rotor speed (rpm)", "damping ratio ζ (–)")
                .titled("(b) damping")
                .with_series(
                    Series::line(
                        "flap 1",
                        speeds.iter().map(|&w| (w, 0.02 - 1e-4 * w)).collect(),
                    )
                    .with_color(PURPLE),
                )
                .with_series(
                    Series::points(
                        "torsion 1",
                        speeds.iter().map(|&w| (w, 0.01 + 2e-5 * w)).collect(),
                    )
                    .with_color(ORANGE),
                )
                .with_guide(Guide::horizontal(0.0, "ζ = 0"))
                .with_guide(Guide::vertical(100.0, "boundary 100 rpm"))
                .with_marker(Marker::new(100.0, 0.0, "flutter at 100 rpm"))
                .with_note("flutter boundary: 100 rpm, flap 1"),
        )
}

struct SvgSummary {
    /// `<polyline>` count by stroke colour.
    polylines: HashMap<String, usize>,
    /// `<circle>` count by fill colour.
    circles: HashMap<String, usize>,
    texts: Vec<String>,
    width: String,
    height: String,
}

fn summarise(svg: &str) -> SvgSummary {
    let doc = roxmltree::Document::parse(svg).expect("SVG must parse as XML");
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    let mut s = SvgSummary {
        polylines: HashMap::new(),
        circles: HashMap::new(),
        texts: Vec::new(),
        width: root.attribute("width").unwrap_or_default().to_string(),
        height: root.attribute("height").unwrap_or_default().to_string(),
    };
    for node in doc.descendants().filter(|n| n.is_element()) {
        match node.tag_name().name() {
            "polyline" => {
                let stroke = node.attribute("stroke").unwrap_or_default().to_string();
                *s.polylines.entry(stroke).or_default() += 1;
            }
            "circle" => {
                let fill = node.attribute("fill").unwrap_or_default().to_string();
                *s.circles.entry(fill).or_default() += 1;
            }
            "text" => s
                .texts
                .push(node.text().unwrap_or_default().trim().to_string()),
            _ => {}
        }
    }
    s
}

#[test]
fn svg_parses_and_has_one_polyline_per_line_series() {
    let fig = campbell_like();
    let svg = plot::render_svg(&fig).unwrap();
    let s = summarise(&svg);
    assert_eq!(
        (s.width.as_str(), s.height.as_str()),
        ("1200", "800"),
        "default size"
    );
    // Line and line+points series: exactly one polyline each.
    for c in [BLUE, RED, GREEN, PURPLE] {
        assert_eq!(s.polylines.get(&hex(c)), Some(&1), "colour {}", hex(c));
    }
    // A point series draws no polyline; it draws one circle per point plus its legend swatch.
    assert_eq!(s.polylines.get(&hex(ORANGE)), None);
    assert_eq!(s.circles.get(&hex(ORANGE)), Some(&(41 + 1)));
    // Line+points: a dot at each of the 41 points plus nothing else (its swatch is a bar).
    assert_eq!(s.circles.get(&hex(GREEN)), Some(&41));
    // Guides are drawn solid in grey, one polyline each (dashes and dots are a rotor's whirls),
    // none in a series colour.
    assert_eq!(s.polylines.get("#5A5A5A").copied(), Some(4));
    // Title, captions, axis labels with units, legend entries, guide labels, marker, note.
    for want in [
        "Campbell diagram — ζ and f vs Ω",
        "(a) frequency",
        "(b) damping",
        "rotor speed (rpm)",
        "frequency (Hz)",
        "damping ratio ζ (–)",
        "flap 1",
        "flap 2",
        "torsion 1",
        "1P",
        "3P",
        "ζ = 0",
        "boundary 100 rpm",
        "flutter at 100 rpm",
        "flutter boundary: 100 rpm, flap 1",
    ] {
        assert!(
            s.texts.iter().any(|t| t == want),
            "no text '{want}' in {:?}",
            s.texts
        );
    }
}

#[test]
fn gaps_and_out_of_range_points_split_a_line() {
    let mut pts = decay(0.0, 100);
    pts[40].1 = f64::NAN;
    let fig = Figure::new("gap").with_panel(
        Panel::new("time (s)", "tip twist (rad)")
            .with_series(Series::line("with a gap", pts).with_color(BLUE))
            .with_series(
                Series::line("all NaN", vec![(0.0, f64::NAN), (1.0, f64::NAN)]).with_color(RED),
            )
            .with_series(Series::line("one point", vec![(1.0, 0.5)]).with_color(GREEN)),
    );
    let s = summarise(&plot::render_svg(&fig).unwrap());
    assert_eq!(s.polylines.get(&hex(BLUE)), Some(&2));
    assert_eq!(s.polylines.get(&hex(RED)), None);
    assert_eq!(s.polylines.get(&hex(GREEN)), None);
    // Still listed in the legend.
    for name in ["with a gap", "all NaN", "one point"] {
        assert!(s.texts.iter().any(|t| t == name), "{name} missing");
    }

    // A fixed y range clips the peaks: each excursion above 0.5 cuts the line.
    let fig = Figure::new("clipped").with_panel(
        Panel::new("time (s)", "tip twist (rad)")
            .with_y_range(-0.5, 0.5)
            .with_series(Series::line("clipped", decay(0.0, 100)).with_color(BLUE)),
    );
    let svg = plot::render_svg(&fig).unwrap();
    let runs = plot::visible_runs(&decay(0.0, 100), (0.0, 4.95), (-0.5, 0.5));
    assert!(runs.len() > 2);
    assert_eq!(summarise(&svg).polylines.get(&hex(BLUE)), Some(&runs.len()));
}

fn state_colour(i: usize) -> Rgb {
    Rgb(10 + 6 * i as u8, 60, 140)
}

/// `<text>` elements with their x position.
fn texts_at(svg: &str) -> Vec<(f64, String)> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| {
            let x = n
                .attribute("x")
                .and_then(|x| x.parse().ok())
                .unwrap_or(f64::NAN);
            (x, n.text().unwrap_or_default().trim().to_string())
        })
        .collect()
}

#[test]
fn a_few_series_get_a_legend_inside_the_plot() {
    let mut panel = Panel::new("time (s)", "state (–)");
    for i in 0..3 {
        panel = panel.with_series(
            Series::line(format!("state {i}"), decay(i as f64, 50)).with_color(state_colour(i)),
        );
    }
    let svg = plot::render_svg(&Figure::new("few").with_panel(panel)).unwrap();
    let texts = texts_at(&svg);
    for i in 0..3 {
        let (x, _) = texts
            .iter()
            .find(|(_, t)| *t == format!("state {i}"))
            .unwrap_or_else(|| panic!("state {i} not in the legend"));
        // Inside the axes: left of the right margin (the plot ends 24 px before the edge).
        assert!(*x < 1200.0 - 24.0 - 40.0, "state {i} at x = {x}");
    }
}

#[test]
fn many_series_get_a_legend_column_capped_with_a_count_of_the_rest() {
    let n = 40;
    let mut panel = Panel::new("time (s)", "state (–)");
    for i in 0..n {
        panel = panel.with_series(
            Series::line(format!("state {i}"), decay(i as f64, 50)).with_color(state_colour(i)),
        );
    }
    let svg = plot::render_svg(&Figure::new("many").with_panel(panel)).unwrap();
    let texts = texts_at(&svg);
    let listed: Vec<f64> = texts
        .iter()
        .filter(|(_, t)| {
            t.strip_prefix("state ")
                .is_some_and(|r| r.parse::<usize>().is_ok())
        })
        .map(|(x, _)| *x)
        .collect();
    let more: usize = texts
        .iter()
        .find_map(|(_, t)| t.strip_prefix("+ ")?.strip_suffix(" more")?.parse().ok())
        .unwrap_or_else(|| panic!("no '+ N more' entry in {texts:?}"));
    assert_eq!(listed.len() + more, n);
    assert!(listed.len() >= 15, "only {} listed", listed.len());
    // The column lies right of the plot: every entry in the right part of the figure.
    assert!(listed.iter().all(|&x| x > 900.0), "{listed:?}");
    // Every series is drawn even when not listed: one polyline in each series' colour.
    let s = summarise(&svg);
    for i in 0..n {
        assert_eq!(
            s.polylines.get(&hex(state_colour(i))),
            Some(&1),
            "state {i}"
        );
    }
}

fn decode_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().expect("PNG header");
    let mut buf = vec![0; reader.output_buffer_size().expect("buffer size")];
    let info = reader.next_frame(&mut buf).expect("PNG data");
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

#[test]
fn png_decodes_at_the_expected_size_with_text_and_series() {
    let dir = out_dir("png");
    let path = dir.join("campbell.png");
    plot::write(&campbell_like(), &path).unwrap();
    keep(&path);
    let (w, h, px) = decode_png(&path);
    assert_eq!((w, h), DEFAULT_SIZE);
    let at = |x: u32, y: u32| {
        let i = 3 * (y * w + x) as usize;
        (px[i], px[i + 1], px[i + 2])
    };
    // Series colours are on the canvas.
    for c in [BLUE, RED, GREEN, PURPLE, ORANGE] {
        let found = (0..h).any(|y| (0..w).any(|x| at(x, y) == (c.0, c.1, c.2)));
        assert!(found, "colour {} not drawn", hex(c));
    }
    // The title was rasterised from the embedded font: dark pixels in the top band.
    let dark_in_title = (0..50)
        .flat_map(|y| (300..900).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let (r, g, b) = at(x, y);
            r < 80 && g < 80 && b < 80
        })
        .count();
    assert!(
        dark_in_title > 200,
        "title not drawn ({dark_in_title} dark pixels)"
    );

    // Three stacked panels grow the height; a fixed size is honoured.
    let three = Figure::new("three")
        .with_panel(Panel::new("x (m)", "a (–)").with_series(Series::line("a", decay(0.0, 20))))
        .with_panel(Panel::new("x (m)", "b (–)").with_series(Series::line("b", decay(1.0, 20))))
        .with_panel(Panel::new("x (m)", "c (–)").with_series(Series::line("c", decay(2.0, 20))));
    let path = dir.join("three.PNG");
    plot::write(&three, &path).unwrap();
    keep(&path);
    let (w3, h3, _) = decode_png(&path);
    assert_eq!((w3, h3), (1200, 800 + 420));
    let path = dir.join("small.png");
    plot::write(&three.clone().with_size(640, 480), &path).unwrap();
    let (ws, hs, _) = decode_png(&path);
    assert_eq!((ws, hs), (640, 480));
    // Two columns side by side.
    let side = Figure::new("side")
        .with_columns(2)
        .with_panel(Panel::new("t (s)", "φ (rad)").with_series(Series::line("a", decay(0.0, 20))))
        .with_panel(Panel::new("t (s)", "φ (rad)").with_series(Series::line("b", decay(1.0, 20))));
    assert_eq!(side.rows(), 1);
    let svg = plot::render_svg(&side).unwrap();
    assert_eq!(summarise(&svg).width, "1200");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn extension_picks_the_format_case_insensitively() {
    assert_eq!(plot::format_for(Path::new("a/b.svg")).unwrap(), Format::Svg);
    assert_eq!(plot::format_for(Path::new("B.SVG")).unwrap(), Format::Svg);
    assert_eq!(plot::format_for(Path::new("c.Png")).unwrap(), Format::Png);
    let dir = out_dir("svg");
    let path = dir.join("fig.SVG");
    plot::write(&campbell_like(), &path).unwrap();
    keep(&path);
    let text = std::fs::read_to_string(&path).unwrap();
    summarise(&text);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_extension_is_a_usage_error_naming_it() {
    let dir = out_dir("ext");
    for (name, needle) in [
        ("plot.pdf", "'.pdf'"),
        ("plot.svg.txt", "'.txt'"),
        ("plot", "no file extension"),
    ] {
        let path = dir.join(name);
        match plot::write(&campbell_like(), &path) {
            Err(Error::Usage(msg)) => {
                assert!(msg.contains(needle), "{msg}");
                assert!(msg.contains(".svg") && msg.contains(".png"), "{msg}");
                assert!(msg.contains(name), "{msg}");
            }
            other => panic!("{name}: expected a usage error, got {other:?}"),
        }
        assert!(!path.exists(), "{name} was written");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_path_is_an_io_error_naming_it() {
    let dir = out_dir("path");
    let missing = dir.join("no-such-dir").join("plot.svg");
    match plot::write(&campbell_like(), &missing) {
        Err(Error::Io(msg)) => {
            assert!(msg.contains(&missing.display().to_string()), "{msg}");
            assert!(msg.contains("cannot write plot"), "{msg}");
        }
        other => panic!("expected an I/O error, got {other:?}"),
    }
    // A directory in the way of a PNG.
    let taken = dir.join("taken.png");
    std::fs::create_dir_all(&taken).unwrap();
    match plot::write(&campbell_like(), &taken) {
        Err(Error::Io(msg)) => assert!(msg.contains("taken.png"), "{msg}"),
        other => panic!("expected an I/O error, got {other:?}"),
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn malformed_figures_are_usage_errors_not_panics() {
    let empty = Figure::new("nothing");
    assert!(matches!(plot::render_svg(&empty), Err(Error::Usage(m)) if m.contains("no panels")));
    let zero_cols = campbell_like().with_columns(0);
    assert!(matches!(plot::render_png(&zero_cols), Err(Error::Usage(m)) if m.contains("column")));
    let bad_range = Figure::new("r").with_panel(Panel::new("x", "y").with_x_range(1.0, 1.0));
    assert!(matches!(plot::render_svg(&bad_range), Err(Error::Usage(m)) if m.contains("x range")));
    let tiny = campbell_like().with_size(10, 10);
    assert!(matches!(plot::render_svg(&tiny), Err(Error::Usage(m)) if m.contains("size")));
    // Degenerate but valid data draws without panicking.
    let flat = Figure::new("flat")
        .with_panel(
            Panel::new("x", "y").with_series(Series::line("const", vec![(1.0, 2.0), (1.0, 2.0)])),
        )
        .with_panel(Panel::new("x", "y"))
        .with_panel(
            Panel::new("x", "y")
                .with_series(Series::line("huge", vec![(0.0, 1e300), (1.0, -1e300)])),
        )
        .with_panel(
            Panel::new("x", "y")
                .with_series(Series::points("tiny", vec![(0.0, 1e-9), (1e-9, 2e-9)])),
        );
    summarise(&plot::render_svg(&flat).unwrap());
    assert!(plot::render_png(&flat).unwrap().starts_with(b"\x89PNG"));
}

// ---------------------------------------------------------------------------------------------
// Figures built from the engine's result types (`plot::from_results`), on hand-made results.
// ---------------------------------------------------------------------------------------------

mod from_results {
    use flutterscope::analysis::flutter::{Boundary, BoundaryKind, Search};
    use flutterscope::analysis::response::Response;
    use flutterscope::analysis::simulate::RunStatus;
    use flutterscope::analysis::sweep::{RowStatus, SweepRow, TrackedMode, TrackedSweep};
    use flutterscope::plot::from_results;
    use flutterscope::plot::{Dash, GuideKind, PALETTE};

    /// A solved sweep row of one mode at one grid value.
    fn ok_row(v: f64, mode: &str, f: f64, damping_ratio: f64, re: f64) -> SweepRow {
        SweepRow {
            values: vec![v],
            mode: Some(mode.into()),
            frequency_hz: f,
            damping_ratio,
            re,
            second_re: f64::NAN,
            status: RowStatus::Ok,
            error: None,
        }
    }

    fn mode(label: &str, f: Vec<f64>, z: Vec<f64>) -> TrackedMode {
        let re = z.iter().map(|z| -z).collect();
        TrackedMode {
            label: label.into(),
            second_re: vec![f64::NAN; f.len()],
            switches: Vec::new(),
            frequency_hz: f,
            damping_ratio: z,
            re,
        }
    }

    fn rotor_sweep() -> TrackedSweep {
        let values: Vec<f64> = (0..=20).map(|i| i as f64 * 10.0).collect();
        let n = values.len();
        TrackedSweep {
            parameter: "operating.rotor_speed".into(),
            modes: vec![
                mode(
                    "flap 1",
                    values.iter().map(|w| 1.0 + 0.005 * w).collect(),
                    vec![0.01; n],
                ),
                mode(
                    "flap 2",
                    values.iter().map(|w| 3.0 + 0.01 * w).collect(),
                    vec![0.02; n],
                ),
                // Far above the flap modes: left off the frequency panel, kept in damping.
                mode("torsion 1", vec![96.0; n], vec![0.005; n]),
            ],
            values,
            failed: Vec::new(),
        }
    }

    /// Along a schedule the harmonics follow the schedule's rotor speed, piece by piece, each
    /// labelled once, and the frequency axis starts at 0 Hz so a slow rotor's 1P shows.
    #[test]
    fn campbell_along_the_schedule_draws_harmonics_of_the_scheduled_rotor_speed() {
        let mut sweep = rotor_sweep();
        sweep.parameter = "operating.wind_speed".into();
        sweep.values = (0..sweep.values.len()).map(|i| 3.0 + i as f64).collect();
        // Region 2 then rated: 5 rpm rising to 7.5 rpm at the fifth point, then held.
        let rpm: Vec<f64> = (0..sweep.values.len())
            .map(|i| (5.0 + 0.625 * i as f64).min(7.5))
            .collect();
        let fig = from_results::campbell_along_schedule("test", &sweep, &rpm);
        let freq = &fig.panels[0];
        let pieces = sweep.values.len() - 1;
        assert_eq!(freq.guides.len(), 3 * pieces);
        let labels: Vec<&str> = freq
            .guides
            .iter()
            .map(|g| g.label.as_str())
            .filter(|l| !l.is_empty())
            .collect();
        assert_eq!(labels, ["1P", "3P", "6P"]);
        assert_eq!(freq.y_range.map(|r| r.0), Some(0.0));
        assert!(fig.title.contains("operating schedule"));
    }

    /// The legend (on the damping panel) and the colours start from the lowest mode, whatever
    /// order the sweep holds its modes in: a legend cut short leaves out the high modes.
    #[test]
    fn campbell_legend_and_colours_go_lowest_mode_first() {
        let mut sweep = rotor_sweep();
        sweep.modes.reverse();
        let fig = from_results::sweep("test", &sweep);
        let (freq, damp) = (&fig.panels[0], &fig.panels[1]);
        let names: Vec<&str> = damp.series.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(
            names,
            ["flap 1", "flap 2", "torsion 1 (off scale, 96.0 Hz)"]
        );
        let drawn: Vec<&str> = freq.series.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(drawn, ["flap 1", "flap 2"]);
        // One colour per mode, the same in both panels, the palette's first for the lowest.
        assert_eq!(damp.series[0].style.color, Some(PALETTE[0]));
        assert_eq!(freq.series[0].style.color, damp.series[0].style.color);
        assert_eq!(freq.series[1].style.color, damp.series[1].style.color);
        assert_ne!(damp.series[0].style.color, damp.series[1].style.color);
    }

    #[test]
    fn campbell_has_1p_3p_lines_and_leaves_far_modes_off_the_frequency_scale() {
        let fig = from_results::sweep("test", &rotor_sweep());
        assert_eq!(fig.panels.len(), 2);
        assert!(fig.title.starts_with("Campbell diagram"));
        let (freq, damp) = (&fig.panels[0], &fig.panels[1]);
        assert_eq!(freq.x_label, "operating.rotor_speed (rpm)");
        let labels: Vec<&str> = freq.guides.iter().map(|g| g.label.as_str()).collect();
        assert_eq!(labels, ["1P", "3P"]);
        // 3P at 200 rpm is 10 Hz.
        match freq.guides[1].kind {
            GuideKind::Segment { from, to } => {
                assert_eq!(from, (0.0, 0.0));
                assert_eq!(to, (200.0, 10.0));
            }
            ref k => panic!("3P is {k:?}"),
        }
        let names = |p: &flutterscope::plot::Panel| -> Vec<String> {
            p.series.iter().map(|s| s.name.clone()).collect()
        };
        assert_eq!(names(freq), ["flap 1", "flap 2"]);
        // Named in the legend as off scale, with the frequency it sits at.
        assert_eq!(
            names(damp),
            ["flap 1", "flap 2", "torsion 1 (off scale, 96.0 Hz)"]
        );
        assert!(
            freq.notes[0].starts_with("1 more mode(s) off scale"),
            "{:?}",
            freq.notes
        );
        // One colour per mode in both panels.
        assert_eq!(freq.series[1].style.color, damp.series[1].style.color);
        assert_ne!(damp.series[0].style.color, damp.series[1].style.color);
        for s in &damp.series {
            assert_eq!(s.points.len(), 21);
        }
        // A non-rotor key: no excitation lines.
        let mut other = rotor_sweep();
        other.parameter = "operating.wind_speed".into();
        let fig = from_results::sweep("test", &other);
        assert!(fig.panels[0].guides.is_empty());
        assert_eq!(fig.panels[0].x_label, "operating.wind_speed (m/s)");
    }

    #[test]
    fn frequency_panel_draws_the_campbell_selection_and_damping_every_mode() {
        let mut sweep = rotor_sweep();
        let n = sweep.values.len();
        sweep.modes = (1..=10)
            .map(|k| {
                mode(
                    &format!("flap {k}"),
                    vec![0.9 + 0.1 * k as f64; n],
                    vec![0.01; n],
                )
            })
            .collect();
        // A pair split into real roots: 0 Hz throughout, never oscillating.
        sweep.modes.push(mode("split", vec![0.0; n], vec![1.0; n]));
        // The selection the explorer's Campbell view draws: the eight lowest that oscillate.
        assert_eq!(sweep.campbell_modes().shown, (0..8).collect::<Vec<_>>());
        let fig = from_results::sweep("test", &sweep);
        let (freq, damp) = (&fig.panels[0], &fig.panels[1]);
        let names: Vec<&str> = freq.series.iter().map(|s| s.name.as_str()).collect();
        let lowest: Vec<String> = (1..=8).map(|k| format!("flap {k}")).collect();
        assert_eq!(names, lowest);
        assert_eq!(damp.series.len(), 11);
        // The modes left off, lowest first, each named as such: beyond the eight lowest at
        // their frequency, the split pair as not oscillating.
        let left_off: Vec<&str> = damp.series[8..].iter().map(|s| s.name.as_str()).collect();
        assert_eq!(
            left_off,
            [
                "flap 9 (off scale, 1.80 Hz)",
                "flap 10 (off scale, 1.90 Hz)",
                "split (not oscillating)"
            ]
        );
        assert_eq!(
            freq.notes,
            ["3 more mode(s) off scale, named in the legend"]
        );
    }

    #[test]
    fn sweep_rows_regroup_into_tracked_modes() {
        let row = |v: f64, mode: &str, f: f64| ok_row(v, mode, f, 0.1 * f, -f);
        let rows = [
            row(0.0, "flap 1", 1.0),
            row(0.0, "torsion 1", 9.0),
            row(5.0, "flap 1", 1.5),
            row(10.0, "flap 1", 2.0),
            row(10.0, "torsion 1", 9.5),
            // A point that could not be solved: one row, no mode.
            SweepRow::failed(vec![15.0], Some("numerical: no equilibrium".into())),
        ];
        let t = from_results::tracked_from_rows("operating.wind_speed", &rows);
        assert_eq!(t.values, [0.0, 5.0, 10.0, 15.0]);
        assert_eq!(t.modes.len(), 2);
        assert_eq!(t.modes[0].label, "flap 1");
        assert_eq!(t.modes[0].frequency_hz[..3], [1.0, 1.5, 2.0]);
        assert!(t.modes[0].frequency_hz[3].is_nan());
        assert_eq!(t.modes[1].frequency_hz[0], 9.0);
        assert!(t.modes[1].frequency_hz[1].is_nan());
        assert_eq!(t.modes[1].re[2], -9.5);
        assert_eq!(t.failed.len(), 1);
        assert_eq!((t.failed[0].index, t.failed[0].value), (3, 15.0));
        assert_eq!(t.failed[0].error, "numerical: no equilibrium");
        // The figure says so.
        let fig = from_results::sweep("test", &t);
        assert_eq!(
            fig.panels[1].notes,
            ["1 of 4 point(s) could not be solved (the first at operating.wind_speed = 15): gaps"]
        );
    }

    /// A rotor's Campbell diagram: the whirls of one blade mode share its colour, backward
    /// dashed, collective solid, forward dotted; other modes keep colours of their own.
    #[test]
    fn a_rotors_whirls_share_their_blade_modes_colour_and_differ_in_stroke() {
        let row = |v: f64, mode: &str, f: f64| ok_row(v, mode, f, 0.01, -0.1);
        let mut rows = Vec::new();
        for v in [5.0, 10.0] {
            for (mode, f) in [
                ("tower FA 1", 0.25),
                ("BW edge 1", 0.5),
                ("collective edge 1", 0.7),
                ("FW edge 1", 0.9),
                ("BW flap 1", 0.4),
            ] {
                rows.push(row(v, mode, f));
            }
        }
        let t = from_results::tracked_from_rows("operating.wind_speed", &rows);
        let fig = from_results::sweep("test", &t);
        let look = |name: &str| {
            let s = fig.panels[0]
                .series
                .iter()
                .find(|s| s.name == name)
                .unwrap_or_else(|| panic!("no {name}"));
            (s.style.color.unwrap(), s.style.dash)
        };
        let (edge, bw) = look("BW edge 1");
        assert_eq!(bw, Dash::Dashed);
        assert_eq!(look("collective edge 1"), (edge, Dash::Solid));
        assert_eq!(look("FW edge 1"), (edge, Dash::Dotted));
        let (flap, _) = look("BW flap 1");
        let (tower, tower_dash) = look("tower FA 1");
        assert_eq!(tower_dash, Dash::Solid);
        assert!(flap != edge && tower != edge && tower != flap);
        assert!(flutterscope::plot::render_svg(&fig).is_ok());
        assert!(flutterscope::plot::render_png(&fig).is_ok());
    }

    #[test]
    fn flutter_figure_marks_the_boundary() {
        let mut tracked = rotor_sweep();
        tracked.parameter = "operating.wind_speed".into();
        let search = Search {
            boundary: Boundary {
                parameter: "operating.wind_speed".into(),
                critical: Some(33.25),
                frequency_hz: Some(2.5),
                kind: Some(BoundaryKind::Flutter),
                mode: Some("flap 2".into()),
                shares: None,
            },
            message: "flutter at 33.25 m/s".into(),
            max_re: 0.4,
            failed: Vec::new(),
            unstable_at_start: false,
            grid: Vec::new(),
            results: Vec::new(),
        };
        let fig = from_results::flutter("test", &tracked, &search);
        let damp = &fig.panels[0];
        assert_eq!(damp.y_label, "damping ratio ζ (–)");
        assert_eq!(damp.markers.len(), 1);
        assert_eq!((damp.markers[0].x, damp.markers[0].y), (33.25, 0.0));
        assert_eq!(
            damp.markers[0].label,
            "flutter at 33.25 m/s, 2.5000 Hz (flap 2)"
        );
        assert!(damp
            .guides
            .iter()
            .any(|g| g.kind == GuideKind::Vertical(33.25)));
        assert!(damp
            .guides
            .iter()
            .any(|g| g.kind == GuideKind::Horizontal(0.0)));
        assert_eq!(damp.notes, ["flutter at 33.25 m/s"]);
        // No crossing: no marker, the message still shown.
        let none = Search {
            boundary: Boundary {
                parameter: "operating.wind_speed".into(),
                critical: None,
                frequency_hz: None,
                kind: None,
                mode: None,
                shares: None,
            },
            message: "stable throughout".into(),
            max_re: -0.1,
            failed: Vec::new(),
            unstable_at_start: false,
            grid: Vec::new(),
            results: Vec::new(),
        };
        let fig = from_results::flutter("test", &tracked, &none);
        assert!(fig.panels[0].markers.is_empty());
        assert_eq!(fig.panels[0].notes, ["stable throughout"]);
        assert!(flutterscope::plot::render_svg(&fig).is_ok());
    }

    #[test]
    fn tip_response_marks_a_diverging_run() {
        let t: Vec<f64> = (0..100).map(|i| i as f64 * 0.01).collect();
        let r = Response {
            status: RunStatus::Diverging,
            tip_twist: t.iter().map(|t| (5.0 * t).exp() * 1e-3).collect(),
            tip_flap: t.iter().map(|t| 0.1 * t).collect(),
            diverged_at: Some(0.99),
            rotor_blade: None,
            stall_linearised: false,
            t,
        };
        let fig = from_results::tip_response("test", "quasi-steady", &r);
        assert_eq!(fig.panels.len(), 2);
        assert_eq!(fig.panels[0].series[0].points.len(), 100);
        assert_eq!(fig.panels[1].series[0].points[50], (0.5, 0.1 * 0.5));
        assert!(fig.panels[0].notes[0].contains("DIVERGING"));
        assert!(fig
            .panels
            .iter()
            .all(|p| p.guides.iter().any(|g| g.kind == GuideKind::Vertical(0.99))));
        let ok = Response {
            status: RunStatus::Ok,
            diverged_at: None,
            ..r
        };
        let fig = from_results::tip_response("test", "quasi-steady", &ok);
        assert!(fig
            .panels
            .iter()
            .all(|p| p.notes.is_empty() && p.guides.is_empty()));
    }
}

/// `flutter --plot`: an overdamped root (the IEA 15MW's flap 1 reaches ζ ≈ 3 near 12 rpm) does
/// not set the damping axis; the axis is clipped around ζ = 0, says so, and the roots beyond it
/// are marked at its edge and named in the legend.
#[test]
fn the_flutter_damping_axis_is_clipped_around_zero_with_the_roots_beyond_marked() {
    let dir = out_dir("flutter-clip");
    let path = dir.join("flutter.svg");
    crate::flutterscope_ok(&[
        "flutter",
        "--preset",
        "iea15mw",
        "--vary",
        "operating.rotor_speed",
        "--from",
        "0",
        "--to",
        "30",
        "--points",
        "11",
        "--plot",
        path.to_str().unwrap(),
    ]);
    keep(&path);
    let svg = std::fs::read_to_string(&path).unwrap();
    let texts: Vec<String> = texts_at(&svg).into_iter().map(|t| t.1).collect();
    assert!(
        texts.iter().any(|t| t == "damping ratio ζ (–), clipped"),
        "{texts:?}"
    );
    assert!(
        texts.iter().any(|t| t == "ζ beyond -0.25 … 0.5, at edge"),
        "{texts:?}"
    );
    // The legend's swatch and at least one root drawn at the edge.
    let grey = svg.matches("fill=\"#5A5A5A\" stroke=\"none\"").count();
    assert!(grey > 1, "{grey}");
}

/// The box drawn behind a guide's label (a translucent white rectangle): x, y, height in pixels.
type LabelBox = (f64, f64, f64);

/// `<text>` elements with their y position and the box drawn just before them, if any.
fn labels_with_boxes(svg: &str) -> Vec<(String, f64, Option<LabelBox>)> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    let num = |n: roxmltree::Node, a: &str| -> f64 {
        n.attribute(a)
            .and_then(|v| v.parse().ok())
            .unwrap_or(f64::NAN)
    };
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| {
            let rect = n
                .prev_sibling_element()
                .filter(|r| r.has_tag_name("rect"))
                .map(|r| (num(r, "x"), num(r, "y"), num(r, "height")));
            (
                n.text().unwrap_or_default().trim().to_string(),
                num(n, "y"),
                rect,
            )
        })
        .collect()
}

/// A Campbell diagram along rotor speed (the NREL 5MW, 0 … 20 rpm): the 1P and 3P labels sit on
/// their lines, right of the line's end and centred on its height; torsion 1, above the
/// frequency scale, is named in the legend as off scale with its typical frequency.
#[test]
fn campbell_labels_sit_on_their_lines_and_off_scale_modes_are_named_in_the_legend() {
    let dir = out_dir("campbell-labels");
    let path = dir.join("campbell.svg");
    let out = crate::flutterscope_ok(&[
        "sweep",
        "--preset",
        "nrel5mw",
        "--vary",
        "operating.rotor_speed=0:20:5",
        "--plot",
        path.to_str().unwrap(),
    ]);
    keep(&path);
    let svg = std::fs::read_to_string(&path).unwrap();
    let texts = labels_with_boxes(&svg);
    // The frequency panel's y ticks come first: their pixel heights map hertz to pixels.
    let tick = |label: &str| -> f64 {
        texts
            .iter()
            .find(|t| t.0 == label && t.2.is_none())
            .unwrap_or_else(|| panic!("no tick {label}: {texts:?}"))
            .1
    };
    let (y0, y1) = (tick("0"), tick("1"));
    let y_at = |hz: f64| y0 + (y1 - y0) * hz;
    // Where the lines end, at 20 rpm: the frequency panel's last x tick.
    let x_end = texts_at(&svg)
        .into_iter()
        .find(|t| t.1 == "20")
        .map(|t| t.0)
        .unwrap();
    for n in [1.0, 3.0] {
        let name = format!("{n}P");
        let (_, _, rect) = texts
            .iter()
            .find(|t| t.0 == name)
            .unwrap_or_else(|| panic!("no {name} label: {texts:?}"));
        let (x, y, h) = rect.expect("a guide label on its box");
        // The line ends at 20 rpm, n × 20/60 Hz.
        let line_y = y_at(n * 20.0 / 60.0);
        assert!(
            (y + 0.5 * h - line_y).abs() <= 3.0,
            "{name}: box {y} … {} px, its line at {line_y} px",
            y + h
        );
        assert!(
            (0.0..=12.0).contains(&(x - x_end)),
            "{name}: box from x = {x}, the line ends at {x_end}"
        );
    }
    // Torsion 1's typical frequency, the median of its rows, as the legend names it.
    let stdout = String::from_utf8_lossy(&out.stdout);
    let mut torsion: Vec<f64> = stdout
        .lines()
        .filter_map(|l| {
            let cols: Vec<&str> = l.split(',').collect();
            (cols.get(1) == Some(&"torsion 1")).then(|| cols[2].parse::<f64>().unwrap())
        })
        .collect();
    torsion.sort_by(f64::total_cmp);
    let median = torsion[torsion.len() / 2];
    let entry = texts
        .iter()
        .find_map(|t| t.0.strip_prefix("torsion 1 (off scale, "))
        .unwrap_or_else(|| panic!("torsion 1 not named off scale: {texts:?}"));
    let hz: f64 = entry.strip_suffix(" Hz)").unwrap().parse().unwrap();
    assert!((hz - median).abs() <= 0.005, "{entry} against {median}");
    // Off scale indeed: above the frequency panel's top tick (the y ticks are the numbers before
    // the damping panel off the x ticks' row, the row of "20").
    let x_row = tick("20");
    let top = texts
        .iter()
        .take_while(|t| !t.0.starts_with("(b)"))
        .filter(|t| t.2.is_none() && t.1 != x_row && t.0.parse::<f64>().is_ok())
        .map(|t| t.1)
        .fold(f64::INFINITY, f64::min);
    assert!(top < y0, "no y ticks above 0: {texts:?}");
    assert!(y_at(hz) < top, "{hz} Hz on the scale");
    assert!(
        texts
            .iter()
            .any(|t| t.0.ends_with("more mode(s) off scale, named in the legend")),
        "{texts:?}"
    );
}
