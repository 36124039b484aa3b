//! `reproduce fig2..fig5`: the paper's Figures 2–5 (§4.1–4.2) computed on the paper presets
//! `liu2017` (quasi-steady aerodynamics, classical flutter) and `liu2017-stall` (ONERA, stall
//! flutter), with ply angles 15°–75° in steps of 15°.
//!
//! Everything here goes through the library (preset loading, `analyse`, `simulate`,
//! `Simulator`); this file only selects, orders and lays out the results: terminal braille plots
//! with the numbers in a table, `--json` with every series, `--plot FILE` with the figure.
//! "Rightmost" eigenvalues are all roots (structural and aerodynamic-lag, one per conjugate
//! pair) ordered by real part, largest first — the paper's "1st, 2nd, … eigenvalue" (§4.2).

use crate::analysis::eigen::{analyse, Stability};
use crate::analysis::mode::Mode;
use crate::analysis::response::{sample_count, simulate};
use crate::analysis::simulate::RunStatus;
use crate::analysis::solve::solve;
use crate::error::Result;
use crate::plot::{self, Figure, Guide, Mark, Panel, Series};
use crate::preset::{Preset, ValidPreset};
use rayon::prelude::*;
use serde::Serialize;
use std::io::IsTerminal;
use std::path::Path;

/// (model name, preset) pairs: classical flutter and stall flutter.
pub const MODELS: [(&str, &str); 2] = [
    ("classical (quasi-steady)", "liu2017"),
    ("stall (onera)", "liu2017-stall"),
];

/// The paper's ply angles (deg).
pub const PLY_ANGLES: [f64; 5] = [15.0, 30.0, 45.0, 60.0, 75.0];

/// The paper's statements on which ply angle is most and least stable (§4.2).
pub const PAPER_CLASSICAL: &str =
    "classical: 15° most stable (four eigenvalues minimum), 45° least stable (largest)";
pub const PAPER_STALL: &str = "stall: 45° most stable (four eigenvalues almost minimum); \
     from the responses (Fig. 4), 15° the least stable";

fn paper_preset(name: &str, angle: f64) -> Result<ValidPreset> {
    Preset::load(name, &[format!("section.ply_angle={angle}")])
}

/// `run(model, preset, ply angle)` for every model at every one of the paper's ply angles, on all
/// cores; the results in model order, then angle order.
fn each_case<T: Send>(
    run: impl Fn(&'static str, &'static str, f64) -> Result<T> + Sync,
) -> Result<Vec<T>> {
    let cases: Vec<(usize, f64)> = (0..MODELS.len())
        .flat_map(|m| PLY_ANGLES.iter().map(move |&a| (m, a)))
        .collect();
    cases
        .par_iter()
        .map(|&(m, angle)| {
            let (model, preset) = MODELS[m];
            run(model, preset, angle)
        })
        .collect()
}

/// A panel per model, side by side: "(a) model — preset", "(b) …".
fn model_panel(i: usize, x_label: &str, y_label: &str) -> Panel {
    let (model, preset) = MODELS[i];
    Panel::new(x_label, y_label).titled(format!("({}) {model} — {preset}", ['a', 'b'][i]))
}

/// Largest |value|.
fn peak(values: &[f64]) -> f64 {
    values.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// One eigenvalue λ = σ + iω (one per conjugate pair).
#[derive(Debug, Clone, Serialize)]
pub struct Root {
    /// σ (1/s).
    pub re: f64,
    /// ω (rad/s).
    pub im: f64,
    pub frequency_hz: f64,
    pub label: String,
}

impl From<&Mode> for Root {
    fn from(m: &Mode) -> Self {
        Root {
            re: m.re,
            im: m.im,
            frequency_hz: m.frequency_hz,
            label: m.label.clone(),
        }
    }
}

/// The `n` rightmost roots of a stability result, structural and aerodynamic together.
pub fn rightmost(s: &Stability, n: usize) -> Vec<Root> {
    let mut all: Vec<&Mode> = s.eigenvalues.iter().chain(&s.aero_lags).collect();
    all.sort_by(|a, b| b.re.total_cmp(&a.re));
    all.into_iter().take(n).map(Root::from).collect()
}

// ---------------------------------------------------------------------------------------------
// Figure 5: the four rightmost eigenvalues against ply angle
// ---------------------------------------------------------------------------------------------

#[derive(Debug, Clone, Serialize)]
pub struct EigenRow {
    pub model: String,
    pub preset: String,
    pub ply_angle: f64,
    /// The four rightmost roots, largest real part first.
    pub roots: Vec<Root>,
}

/// Which ply angle is most and least stable for one model, judged by the largest real part.
#[derive(Debug, Clone, Serialize)]
pub struct Finding {
    pub model: String,
    pub most_stable_ply_angle: f64,
    pub least_stable_ply_angle: f64,
    /// (ply angle, largest real part) in angle order.
    pub largest_re: Vec<(f64, f64)>,
    pub paper: String,
}

#[derive(Debug, Clone, Serialize)]
pub struct Fig5 {
    pub figure: &'static str,
    pub rows: Vec<EigenRow>,
    pub findings: Vec<Finding>,
}

pub fn fig5() -> Result<Fig5> {
    let rows: Vec<EigenRow> = each_case(|model, preset, angle| {
        let s = analyse(&paper_preset(preset, angle)?)?;
        Ok(EigenRow {
            model: model.into(),
            preset: preset.into(),
            ply_angle: angle,
            roots: rightmost(&s, 4),
        })
    })?;
    let findings = MODELS
        .iter()
        .zip([PAPER_CLASSICAL, PAPER_STALL])
        .map(|(&(model, _), paper)| {
            let largest_re: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.model == model)
                .map(|r| (r.ply_angle, r.roots.first().map_or(f64::NAN, |x| x.re)))
                .collect();
            let pick = |most: bool| {
                largest_re
                    .iter()
                    .copied()
                    .reduce(|a, b| {
                        let better = if most { b.1 < a.1 } else { b.1 > a.1 };
                        if better {
                            b
                        } else {
                            a
                        }
                    })
                    .map_or(f64::NAN, |x| x.0)
            };
            Finding {
                model: model.into(),
                most_stable_ply_angle: pick(true),
                least_stable_ply_angle: pick(false),
                largest_re,
                paper: paper.into(),
            }
        })
        .collect();
    Ok(Fig5 {
        figure: "fig5",
        rows,
        findings,
    })
}

/// Panel (a) classical, (b) stall: real parts of the 1st…4th eigenvalue against ply angle.
pub fn fig5_figure(f: &Fig5) -> Figure {
    let mut fig = Figure::new(
        "Fig. 5 — four rightmost eigenvalues (real parts) against ply angle, liu2017 presets",
    )
    .with_columns(2);
    for (i, &(model, _)) in MODELS.iter().enumerate() {
        let rows: Vec<&EigenRow> = f.rows.iter().filter(|r| r.model == model).collect();
        let mut panel = model_panel(i, "ply angle θ (deg)", "real part σ (1/s)");
        for k in 0..4 {
            let pts = rows
                .iter()
                .map(|r| (r.ply_angle, r.roots.get(k).map_or(f64::NAN, |x| x.re)))
                .collect();
            panel
                .series
                .push(Series::new(ordinal(k + 1), pts, Mark::LinePoints));
        }
        fig.panels.push(panel);
    }
    fig
}

fn ordinal(k: usize) -> String {
    let suffix = match k {
        1 => "st",
        2 => "nd",
        3 => "rd",
        _ => "th",
    };
    format!("{k}{suffix} eigenvalue")
}

fn fig5_table(f: &Fig5) -> String {
    let mut o = String::from("real parts σ (1/s) of the four rightmost eigenvalues\n");
    o += &format!(
        "{:<26} {:>6} {:>13} {:>13} {:>13} {:>13}  1st root\n",
        "model", "θ (°)", "1st", "2nd", "3rd", "4th"
    );
    for r in &f.rows {
        o += &format!("{:<26} {:>6}", r.model, r.ply_angle);
        for k in 0..4 {
            o += &format!(" {:>13.5e}", r.roots.get(k).map_or(f64::NAN, |x| x.re));
        }
        if let Some(first) = r.roots.first() {
            o += &format!("  {} ({:.4} Hz)", first.label, first.frequency_hz);
        }
        o.push('\n');
    }
    o.push('\n');
    o += &findings_text(&f.findings);
    o
}

fn findings_text(findings: &[Finding]) -> String {
    let mut o = String::from("findings (largest real part per ply angle; smaller = more stable)\n");
    for f in findings {
        o += &format!(
            "  ours  {}: {}° most stable, {}° least stable\n  paper {}\n",
            f.model, f.most_stable_ply_angle, f.least_stable_ply_angle, f.paper
        );
    }
    o
}

// ---------------------------------------------------------------------------------------------
// Figures 3 and 4: tip twist / tip flap responses against ply angle
// ---------------------------------------------------------------------------------------------

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TipQuantity {
    TipTwist,
    TipFlap,
}

#[derive(Debug, Clone, Serialize)]
pub struct TipRun {
    pub model: String,
    pub preset: String,
    pub ply_angle: f64,
    pub status: RunStatus,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub diverged_at: Option<f64>,
    pub t: Vec<f64>,
    /// Tip twist (rad) or tip flap (m).
    pub values: Vec<f64>,
}

impl TipRun {
    fn peak(&self) -> f64 {
        peak(&self.values)
    }
    /// Largest |value − final value| over the second half: what is left of the oscillation.
    fn late_swing(&self) -> f64 {
        let last = self.values.last().copied().unwrap_or(0.0);
        self.values[self.values.len() / 2..]
            .iter()
            .fold(0.0f64, |m, v| m.max((v - last).abs()))
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct TipFigure {
    pub figure: &'static str,
    pub quantity: TipQuantity,
    pub unit: &'static str,
    pub runs: Vec<TipRun>,
    pub paper: &'static str,
}

pub fn tip_runs(quantity: TipQuantity) -> Result<TipFigure> {
    let runs = each_case(|model, preset, angle| {
        let r = simulate(&paper_preset(preset, angle)?)?;
        let values = match quantity {
            TipQuantity::TipTwist => r.tip_twist,
            TipQuantity::TipFlap => r.tip_flap,
        };
        Ok(TipRun {
            model: model.into(),
            preset: preset.into(),
            ply_angle: angle,
            status: r.status,
            diverged_at: r.diverged_at,
            t: r.t,
            values,
        })
    })?;
    let (figure, unit, paper) = match quantity {
        TipQuantity::TipTwist => (
            "fig3",
            "rad",
            "Fig. 3: classical amplitudes higher than stall; 45° least stable, 15° most stable",
        ),
        TipQuantity::TipFlap => (
            "fig4",
            "m",
            "Fig. 4: 45° most stable, stability decreasing on both sides; 15° least stable",
        ),
    };
    Ok(TipFigure {
        figure,
        quantity,
        unit,
        runs,
        paper,
    })
}

pub fn tip_figure(f: &TipFigure) -> Figure {
    let (what, y) = match f.quantity {
        TipQuantity::TipTwist => ("tip twist", "tip twist φ(L,t) (rad)"),
        TipQuantity::TipFlap => ("tip flap", "tip flap u(L,t) (m)"),
    };
    let num = if f.figure == "fig3" { 3 } else { 4 };
    let mut fig = Figure::new(format!(
        "Fig. {num} — {what} responses against ply angle, liu2017 presets"
    ))
    .with_columns(2);
    for (i, &(model, _)) in MODELS.iter().enumerate() {
        let mut panel = model_panel(i, "time t (s)", y);
        for r in f.runs.iter().filter(|r| r.model == model) {
            let pts = r.t.iter().copied().zip(r.values.iter().copied()).collect();
            panel
                .series
                .push(Series::line(format!("θ = {}°", r.ply_angle), pts));
            if let Some(t) = r.diverged_at {
                panel
                    .guides
                    .push(Guide::vertical(t, format!("θ = {}° diverged", r.ply_angle)));
            }
        }
        fig.panels.push(panel);
    }
    fig
}

fn tip_table(f: &TipFigure) -> String {
    let mut o = format!(
        "{:<26} {:>6} {:>13} {:>13} {:>13}  status\n",
        "model",
        "θ (°)",
        format!("peak ({})", f.unit),
        format!("final ({})", f.unit),
        "late swing"
    );
    for r in &f.runs {
        o += &format!(
            "{:<26} {:>6} {:>13.5e} {:>13.5e} {:>13.5e}  {}\n",
            r.model,
            r.ply_angle,
            r.peak(),
            r.values.last().copied().unwrap_or(f64::NAN),
            r.late_swing(),
            match (r.status, r.diverged_at) {
                (RunStatus::Diverging, Some(t)) => format!("diverging at t = {t:.3} s"),
                (RunStatus::Diverging, None) => "diverging".into(),
                (RunStatus::Ok, _) => "ok".into(),
            }
        );
    }
    o += "late swing: largest |value − final value| over the second half of the run\n";
    o += &format!("paper {}\n", f.paper);
    o
}

// ---------------------------------------------------------------------------------------------
// Figure 2: every state of the stall-flutter system, and its ten rightmost eigenvalues
// ---------------------------------------------------------------------------------------------

#[derive(Debug, Clone, Serialize)]
pub struct StateSeries {
    pub name: String,
    /// "displacement", "velocity" or "aerodynamic".
    pub group: &'static str,
    pub values: Vec<f64>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Fig2 {
    pub figure: &'static str,
    pub preset: &'static str,
    pub ply_angle: f64,
    pub status: RunStatus,
    pub t: Vec<f64>,
    pub states: Vec<StateSeries>,
    pub eigenvalues: Vec<Root>,
}

/// Names of the state vector `[q_φ (N), q_u (N), q̇_φ, q̇_u, z (n_aero)]` (rates as `dq…`).
fn state_names(n: usize, n_aero: usize) -> Vec<(String, &'static str)> {
    let mut names = Vec::with_capacity(4 * n + n_aero);
    for (prefix, group) in [("q", "displacement"), ("dq", "velocity")] {
        for field in ["φ", "u"] {
            for k in 1..=n {
                names.push((format!("{prefix}{field}{k}"), group));
            }
        }
    }
    for k in 1..=n_aero {
        names.push((format!("z{k}"), "aerodynamic"));
    }
    names
}

pub fn fig2() -> Result<Fig2> {
    let preset = MODELS[1].1;
    let ply_angle = 45.0;
    let p = paper_preset(preset, ply_angle)?;
    let solution = solve(&p)?;
    let eigenvalues = rightmost(&solution.stability()?, 10);
    let mut sim = solution.simulator(&p)?;
    let linear = sim.linear();
    let (nq, n_aero) = (linear.nq, linear.n_aero);
    let names = state_names(nq / 2, n_aero);
    let mut t = Vec::new();
    let mut columns: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    for _ in 0..sample_count(&p) {
        let x = sim.state();
        let samples = sim.advance(1)?;
        let Some(s) = samples.first() else { break };
        t.push(s.t);
        for (c, v) in columns.iter_mut().zip(x.iter()) {
            c.push(*v);
        }
    }
    let states = names
        .into_iter()
        .zip(columns)
        .map(|((name, group), values)| StateSeries {
            name,
            group,
            values,
        })
        .collect();
    Ok(Fig2 {
        figure: "fig2",
        preset,
        ply_angle,
        status: sim.status(),
        t,
        states,
        eigenvalues,
    })
}

pub fn fig2_figure(f: &Fig2) -> Figure {
    let mut fig = Figure::new(format!(
        "Fig. 2 — stall-flutter system ({}, θ = {}°): every state and the ten rightmost eigenvalues",
        f.preset, f.ply_angle
    ))
    .with_columns(2);
    for (group, title, y) in [
        ("displacement", "(a) structural coordinates q", "q (–)"),
        ("velocity", "(b) structural rates dq/dt", "dq/dt (1/s)"),
        ("aerodynamic", "(c) aerodynamic states z", "z (–)"),
    ] {
        let mut panel = Panel::new("time t (s)", y).titled(title);
        for s in f.states.iter().filter(|s| s.group == group) {
            let pts = f.t.iter().copied().zip(s.values.iter().copied()).collect();
            panel.series.push(Series::line(s.name.clone(), pts));
        }
        fig.panels.push(panel);
    }
    let mut eig = Panel::new("real part σ (1/s)", "imaginary part ω (rad/s)")
        .titled("(d) ten rightmost eigenvalues")
        .with_guide(Guide::vertical(0.0, "σ = 0"));
    eig.legend = false;
    eig.series.push(Series::points(
        "λ = σ + iω",
        f.eigenvalues.iter().map(|r| (r.re, r.im)).collect(),
    ));
    fig.panels.push(eig);
    fig
}

fn fig2_table(f: &Fig2) -> String {
    let mut o = String::from("ten rightmost eigenvalues (one per conjugate pair)\n");
    o += &format!(
        "{:>3} {:>13} {:>13} {:>11}  label\n",
        "#", "σ (1/s)", "ω (rad/s)", "f (Hz)"
    );
    for (i, r) in f.eigenvalues.iter().enumerate() {
        o += &format!(
            "{:>3} {:>13.5e} {:>13.5e} {:>11.4}  {}\n",
            i + 1,
            r.re,
            r.im,
            r.frequency_hz,
            r.label
        );
    }
    o += &format!(
        "\nstates over {} samples to t = {:.3} s (status: {:?})\n",
        f.t.len(),
        f.t.last().copied().unwrap_or(0.0),
        f.status
    );
    o += &format!(
        "{:<8} {:<13} {:>13} {:>13}\n",
        "state", "group", "peak |x|", "final"
    );
    for s in &f.states {
        o += &format!(
            "{:<8} {:<13} {:>13.5e} {:>13.5e}\n",
            s.name,
            s.group,
            peak(&s.values),
            s.values.last().copied().unwrap_or(f64::NAN)
        );
    }
    o += "paper: all states stable; the ten largest eigenvalues far below 0 (§4.1)\n";
    o
}

// ---------------------------------------------------------------------------------------------
// Output
// ---------------------------------------------------------------------------------------------

/// Terminal width for the braille plots: the terminal's, or 100 columns in a pipe.
fn plot_width() -> u16 {
    if std::io::stdout().is_terminal() {
        if let Ok((w, _)) = crossterm::terminal::size() {
            return w.clamp(60, 160);
        }
    }
    100
}

fn text_plots(fig: &Figure) -> String {
    let color = std::io::stdout().is_terminal() && std::env::var_os("NO_COLOR").is_none();
    let width = plot_width();
    let mut o = format!("{}\n\n", fig.title);
    for p in &fig.panels {
        o += &plot::text::render(p, width, 20, color);
        o.push('\n');
    }
    o
}

fn emit<T: Serialize>(
    data: &T,
    fig: Figure,
    table: String,
    json: bool,
    path: Option<&Path>,
) -> Result<()> {
    if json {
        crate::commands::print_json(data)?;
    } else {
        crate::commands::print_text(&format!("{}{table}", text_plots(&fig)))?;
    }
    if let Some(path) = path {
        plot::write(&fig, path)?;
        eprintln!("plot written to {}", path.display());
    }
    Ok(())
}

pub fn run_fig2(json: bool, path: Option<&Path>) -> Result<()> {
    check_path(path)?;
    let f = fig2()?;
    emit(&f, fig2_figure(&f), fig2_table(&f), json, path)
}

pub fn run_tip(quantity: TipQuantity, json: bool, path: Option<&Path>) -> Result<()> {
    check_path(path)?;
    let f = tip_runs(quantity)?;
    emit(&f, tip_figure(&f), tip_table(&f), json, path)
}

pub fn run_fig5(json: bool, path: Option<&Path>) -> Result<()> {
    check_path(path)?;
    let f = fig5()?;
    emit(&f, fig5_figure(&f), fig5_table(&f), json, path)
}

fn check_path(path: Option<&Path>) -> Result<()> {
    path.map_or(Ok(()), |p| plot::format_for(p).map(|_| ()))
}
