//! The explorer's state: [`AppState`], everything the screen shows, with the queries the panes
//! ask of it; [`Msg`], the inputs (a key action or a worker result); and [`Effect`], what the
//! state asks the outside world to do. [`update::update`] changes it without I/O, so key
//! sequences are tested without a terminal or a worker.

pub mod jobs;
pub mod params;
pub mod update;

use crate::analysis::campbell::{schedule_wind_range, Campbell};
use crate::analysis::flutter::{Search, SearchRange};
use crate::analysis::mode::Mode;
use crate::analysis::mode_shape::ModeShapes;
use crate::analysis::simulate::{RunStatus, TipSample};
use crate::explorer::display::{ColorMode, MarkerKind};
use crate::explorer::engine::Solved;
use crate::explorer::keys::Action;
use crate::explorer::state::jobs::{
    opening_key, BoundaryJob, CampbellAxis, CampbellJob, CAMPBELL_POINTS, CAMPBELL_WIND_POINTS,
};
use crate::explorer::state::params::{param_index, value_text, Param, ParamKind, PARAMS};
use crate::preset::{Preset, ValidPreset};
use std::sync::Arc;

/// A solve running longer than this (s) is reported in the status line with its time: keys keep
/// working meanwhile and the newest position replaces it.
pub const SOLVE_BUDGET_S: f64 = 0.5;

/// Earlier pole positions kept as the fading trail while parameters move.
pub const TRAIL_LEN: usize = 12;

/// Tip kick when the preset gives none: a 1° twist and a flap of 1 % of the span, small against
/// the operating pitch so the response stays in the linear range.
pub const KICK_TWIST_DEG: f64 = 1.0;

pub const KICK_FLAP_SPAN_FRACTION: f64 = 0.01;

/// A named preset the `[`/`]` keys cycle through.
#[derive(Debug, Clone)]
pub struct PresetEntry {
    pub name: String,
    /// The preset as checked; `None` for a built-in not opened yet (checked when first opened,
    /// so starting the explorer never waits for presets it may not show).
    pub preset: Option<ValidPreset>,
}

/// A check running off the event loop: an edit that reads or analyses the blade again (a
/// WindIO blade's ply angle), or a preset being opened. The newest replaces any older one.
#[derive(Debug, Clone, PartialEq)]
pub struct Pending {
    pub id: u64,
    /// The generation of the parameters when it was asked for: an edit checked on parameters
    /// that have moved since is made again on the current ones.
    pub gen: u64,
    pub check: Check,
}

/// What a [`Effect::Check`] checks.
#[derive(Debug, Clone, PartialEq)]
pub enum Check {
    /// `base` (the parameters being explored) with `key` set to `value`.
    Edit {
        base: Arc<ValidPreset>,
        key: &'static str,
        value: f64,
    },
    /// The built-in preset `name`, preset entry `index`.
    Open { index: usize, name: String },
}

/// Display options from the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Options {
    pub color: ColorMode,
    pub marker: MarkerKind,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            color: ColorMode::Ansi16,
            marker: MarkerKind::Braille,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViewMode {
    Main,
    Campbell,
    /// The main view with the mode-shape pane in place of the tip response.
    Shape,
}

/// The streaming tip response of the current parameters.
#[derive(Debug, Clone, Default)]
pub struct Response {
    /// Generation of the parameters these samples belong to.
    pub gen: u64,
    pub samples: Vec<TipSample>,
    pub diverging: bool,
    pub error: Option<String>,
}

/// Everything the screen shows.
#[derive(Debug, Clone)]
pub struct AppState {
    pub presets: Vec<PresetEntry>,
    pub preset_index: usize,
    /// The parameters being explored.
    pub preset: ValidPreset,
    /// The current entry's preset as it opened: what `r` resets to and what the parameters pane
    /// marks changes against.
    pub opened: ValidPreset,
    /// The check running off the event loop, if any (the last one asked for).
    pub checking: Option<Pending>,
    /// The id of the last check asked for.
    pub check_id: u64,
    pub focus: usize,
    /// Bumped on every parameter change; results of older generations are ignored.
    pub gen: u64,
    /// The generation of `solved` (or of the error that replaced it).
    pub solved_gen: u64,
    pub solved: Option<Solved>,
    pub solve_error: Option<String>,
    /// How long the solve of the current parameters has run (s), as last told by the event loop.
    pub solve_seconds: f64,
    /// Modes before the last change, for the trend arrows.
    pub prev_modes: Vec<Mode>,
    /// Earlier pole positions (σ, ω), newest first.
    pub trails: Vec<Vec<(f64, f64)>>,
    /// A preset was (re)loaded: the next solve starts a new history (no trails, no trends).
    pub fresh: bool,
    pub response: Response,
    pub boundary_key: &'static str,
    pub boundary: Option<BoundaryJob>,
    pub campbell: Option<CampbellJob>,
    /// The Campbell view's axis (wind speed only on a preset with a schedule).
    pub campbell_axis: CampbellAxis,
    /// Wind speeds in the Campbell diagram along the schedule ([`CAMPBELL_WIND_POINTS`]; tests
    /// and snapshots take fewer).
    pub campbell_wind_points: usize,
    pub view: ViewMode,
    /// The mode the mode-shape pane shows, by label; `None`: the least-damped one (the flutter
    /// mode once unstable). Also `None` when the picked label is gone after a solve.
    pub shape_pick: Option<String>,
    /// The part of a rotor's or turbine's mode the pane draws, by name (`blade 2`, `tower`);
    /// `None`, or a name the mode has not: its main part.
    pub shape_part: Option<String>,
    pub help: bool,
    pub paused: bool,
    pub opts: Options,
    /// One-line note for the user (cleared by the next key).
    pub notice: Option<String>,
    /// The worker failed outside a job (e.g. had to be restarted).
    pub worker_error: Option<String>,
    pub quit: bool,
    /// Why the explorer quit on its own (reported after the terminal is restored).
    pub exit_error: Option<String>,
    /// Something visible changed since the last frame.
    pub dirty: bool,
}

/// Inputs to [`update::update`].
#[derive(Debug, Clone)]
pub enum Msg {
    Action(Action),
    /// The terminal changed size: redraw.
    Resize,
    Solved {
        gen: u64,
        result: Result<Solved, String>,
    },
    Samples {
        gen: u64,
        samples: Vec<TipSample>,
        status: RunStatus,
    },
    SimFailed {
        gen: u64,
        error: String,
    },
    Boundary {
        gen: u64,
        key: String,
        result: Result<Vec<Search>, String>,
    },
    Campbell {
        gen: u64,
        result: Result<Campbell, String>,
    },
    /// The solve of generation `gen` has been running for `seconds` (from the event loop's clock).
    SolveTime {
        gen: u64,
        seconds: f64,
    },
    /// The check `id` is done: the preset it gave, or why it failed.
    Checked {
        id: u64,
        result: Result<Box<ValidPreset>, String>,
    },
    /// The worker died and was restarted (or could not be).
    WorkerFailed(String),
    /// Terminal input failed (e.g. stdin closed): the explorer cannot be driven, so it quits.
    InputClosed(String),
}

/// What [`update::update`] asks the outside world to do.
#[derive(Debug, Clone)]
pub enum Effect {
    /// Solve these parameters and restart the tip simulation from them.
    Solve {
        gen: u64,
        preset: Arc<ValidPreset>,
    },
    /// The searches of one margin along `key`, in order.
    Boundary {
        gen: u64,
        key: &'static str,
        preset: Arc<ValidPreset>,
        ranges: Vec<SearchRange>,
    },
    Campbell {
        gen: u64,
        preset: Arc<ValidPreset>,
        key: &'static str,
        grid: Vec<f64>,
    },
    /// Check a preset off the event loop; the answer is [`Msg::Checked`] with this `id`.
    Check {
        id: u64,
        check: Check,
    },
    /// Kick the running simulation of generation `gen`.
    Kick {
        gen: u64,
        twist_rad: f64,
        flap_m: f64,
    },
    Pause(bool),
    Quit,
}

impl AppState {
    /// A state showing `preset` as entry `index` of `presets` (the entry is given `preset`; with
    /// no entries it is the only one); call [`AppState::start`] for the first effects.
    pub fn new(
        mut presets: Vec<PresetEntry>,
        index: usize,
        preset: ValidPreset,
        opts: Options,
    ) -> AppState {
        if presets.is_empty() {
            presets.push(PresetEntry {
                name: preset.display_name().to_string(),
                preset: None,
            });
        }
        let index = index.min(presets.len() - 1);
        presets[index].preset = Some(preset.clone());
        let focus = param_index(&preset, preset.view.select.key());
        let start = opening_key(&preset, focus);
        AppState {
            presets,
            preset_index: index,
            opened: preset.clone(),
            preset,
            checking: None,
            check_id: 0,
            focus,
            gen: 0,
            solved_gen: 0,
            solved: None,
            solve_error: None,
            solve_seconds: 0.0,
            prev_modes: Vec::new(),
            trails: Vec::new(),
            fresh: false,
            response: Response::default(),
            boundary_key: start,
            boundary: None,
            campbell: None,
            campbell_axis: CampbellAxis::RotorSpeed,
            campbell_wind_points: CAMPBELL_WIND_POINTS,
            view: ViewMode::Main,
            shape_pick: None,
            shape_part: None,
            help: false,
            paused: false,
            opts,
            notice: None,
            worker_error: None,
            quit: false,
            exit_error: None,
            dirty: true,
        }
    }

    /// Still waiting for the solve of the current parameters.
    pub fn solving(&self) -> bool {
        self.solved_gen != self.gen
    }

    pub fn focused(&self) -> &'static Param {
        &PARAMS[self.focus]
    }

    /// The value an edit being checked gives `key`, if one is.
    pub fn pending_value(&self, key: &str) -> Option<f64> {
        match self.checking.as_ref()?.check {
            Check::Edit { key: k, value, .. } if k == key => Some(value),
            _ => None,
        }
    }

    /// What the check running off the event loop is doing, for the status line.
    pub fn checking_text(&self) -> Option<String> {
        Some(match &self.checking.as_ref()?.check {
            Check::Edit { key, value, .. } => {
                let label = PARAMS[param_index(&self.preset, key)].label;
                format!(
                    "analysing the blade at {label} {}…",
                    value_text(key, *value)
                )
            }
            Check::Open { name, .. } => format!("opening {name}…"),
        })
    }

    /// The value of a parameter row as text with its unit.
    pub fn param_text(&self, param: &Param) -> String {
        match param.kind {
            ParamKind::Aero => self.preset.aero.model.name().to_string(),
            ParamKind::Number { key, .. } => {
                match (self.pending_value(key), self.scheduled_value(key)) {
                    // The value asked for shows at once, while its check runs.
                    (Some(v), _) => value_text(key, v),
                    // ↻: the schedule sets it at this wind speed.
                    (None, Some(v)) => format!("↻ {}", value_text(key, v)),
                    (None, None) => value_text(key, self.preset.get(key).unwrap_or(f64::NAN)),
                }
            }
        }
    }

    /// The value the schedule gives `key` (rotor speed or pitch) at the last solve, when the
    /// preset runs on a schedule and no edit has overridden it.
    pub fn scheduled_value(&self, key: &str) -> Option<f64> {
        let (rpm, pitch) = self.solved.as_ref()?.setting?;
        let held = self.preset.schedule_overrides;
        match key {
            "operating.rotor_speed" if !held.rotor_speed => Some(rpm),
            "operating.pitch" if !held.pitch => Some(pitch),
            _ => None,
        }
    }

    /// The tip kick: the preset's, or [`KICK_TWIST_DEG`] and [`KICK_FLAP_SPAN_FRACTION`].
    pub fn kick_amounts(&self) -> (f64, f64) {
        let s = &self.preset.simulation;
        if s.kick_twist != 0.0 || s.kick_flap != 0.0 {
            (s.kick_twist.to_radians(), s.kick_flap)
        } else {
            (
                KICK_TWIST_DEG.to_radians(),
                KICK_FLAP_SPAN_FRACTION * self.preset.blade.length,
            )
        }
    }

    fn solve_effect(&self) -> Effect {
        Effect::Solve {
            gen: self.gen,
            preset: Arc::new(self.preset.clone()),
        }
    }

    /// The preset the Campbell diagram is computed on: along wind speed, on the schedule (an
    /// overridden rotor speed or pitch follows it again: the diagram is the turbine's in
    /// operation).
    fn campbell_preset(&self) -> ValidPreset {
        match self.campbell_axis {
            CampbellAxis::RotorSpeed => self.preset.clone(),
            CampbellAxis::WindSpeed => self
                .preset
                .edited(|q| q.follow_schedule())
                .unwrap_or_else(|_| self.preset.clone()),
        }
    }

    /// The preset as the Campbell diagram sees it (its axis's key, and along the schedule the
    /// rotor speed and pitch the schedule sets, do not change it).
    fn campbell_key(&self) -> Preset {
        let mut p = self.campbell_preset().into_preset();
        p.operating.rotor_speed = 0.0;
        p.schedule_overrides.rotor_speed = false;
        if self.campbell_axis == CampbellAxis::WindSpeed {
            p.operating.wind_speed = 0.0;
            p.operating.pitch = 0.0;
        }
        p
    }

    /// The Campbell axis's range and points: 0 to `view.rotor_speed_max`, or the schedule's
    /// cut-in to cut-out.
    pub fn campbell_range(&self) -> (f64, f64, usize) {
        match (self.campbell_axis, schedule_wind_range(&self.preset)) {
            (CampbellAxis::WindSpeed, Some((lo, hi))) => (lo, hi, self.campbell_wind_points),
            _ => (0.0, self.preset.view.rotor_speed_max, CAMPBELL_POINTS),
        }
    }

    /// The Campbell diagram is current for these parameters (or being computed for them).
    pub fn campbell_current(&self) -> bool {
        let (from, to, points) = self.campbell_range();
        self.campbell.as_ref().is_some_and(|c| {
            c.axis == self.campbell_axis
                && (c.from, c.to, c.points) == (from, to, points)
                && c.for_preset == self.campbell_key()
        })
    }

    /// The structural root the mode-shape pane shows: the picked label, else the least damped
    /// (largest σ: the flutter mode once unstable), as an index into the solved eigenvalues.
    pub fn shape_index(&self) -> Option<usize> {
        let modes = &self.solved.as_ref()?.stability.eigenvalues;
        let picked = self
            .shape_pick
            .as_ref()
            .and_then(|label| modes.iter().position(|m| &m.label == label));
        picked.or_else(|| (0..modes.len()).max_by(|&a, &b| modes[a].re.total_cmp(&modes[b].re)))
    }

    /// The part of `shapes` the pane draws: the picked one, else the mode's main part.
    pub fn shape_part_index(&self, shapes: &ModeShapes) -> usize {
        self.shape_part
            .as_ref()
            .and_then(|name| shapes.parts.iter().position(|p| &p.part == name))
            .unwrap_or(shapes.main)
    }
}

/// Indices of `modes` with the oscillatory ones first, by frequency, then the real roots: the
/// order the modes pane lists them in.
pub fn frequency_order(modes: &[Mode]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..modes.len()).collect();
    order.sort_by(|&a, &b| {
        let real = |m: &Mode| m.frequency_hz <= 0.0;
        real(&modes[a])
            .cmp(&real(&modes[b]))
            .then(modes[a].frequency_hz.total_cmp(&modes[b].frequency_hz))
            .then(modes[b].re.total_cmp(&modes[a].re))
    });
    order
}
