//! The explorer's state and the one function that changes it. [`update`] takes a message (a key
//! action or a worker result), changes [`AppState`] and returns the [`Effect`]s to carry out; it
//! does no I/O, so key sequences are tested without a terminal or a worker.

use crate::analysis::campbell::{schedule_wind_range, Campbell, ROTOR_SPEED_KEY, WIND_SPEED_KEY};
use crate::analysis::flutter::{Search, SearchRange};
use crate::analysis::mode::Mode;
use crate::analysis::simulate::{RunStatus, TipSample};
use crate::explorer::display::{ColorMode, MarkerKind};
use crate::explorer::engine::Solved;
use crate::explorer::keys::Action;
use crate::preset::rules::not_acting;
use crate::preset::{key_spec, Preset, ValidPreset};
use std::sync::Arc;

/// Grid points the background boundary search brackets on (as `flutterscope flutter`).
pub const BOUNDARY_POINTS: usize = 41;
/// Rotor speeds in the Campbell diagram, 0 to `view.rotor_speed_max`.
pub const CAMPBELL_POINTS: usize = 41;
/// Wind speeds in the Campbell diagram along the schedule: 1 m/s steps from cut-in 3 to
/// cut-out 25 m/s on the real-blade presets, as HAWCStab2's operating-point files have them.
pub const CAMPBELL_WIND_POINTS: usize = 23;
/// The bend–twist coupling α: a number without unit, shown as `α -0.11`.
pub const COUPLING_KEY: &str = "blade.bend_twist_coupling";
/// A solve running longer than this (s) is reported in the status line with its time: keys keep
/// working meanwhile and the newest position replaces it.
pub const SOLVE_BUDGET_S: f64 = 0.5;
/// Earlier pole positions kept as the fading trail while parameters move.
pub const TRAIL_LEN: usize = 12;
/// Tip kick when the preset gives none: a 1° twist and a flap of 1 % of the span, small against
/// the operating pitch so the response stays in the linear range.
pub const KICK_TWIST_DEG: f64 = 1.0;
pub const KICK_FLAP_SPAN_FRACTION: f64 = 0.01;

/// How a parameter row is changed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParamKind {
    /// A numeric preset key with fine and coarse steps and display decimals (as [`steps`] and
    /// [`shown_decimals`] apply them).
    Number {
        key: &'static str,
        step: f64,
        coarse: f64,
        decimals: usize,
        /// Whether the background boundary search runs along this key when it is selected.
        boundary: bool,
    },
    /// `aero.model`, cycled.
    Aero,
}

/// One row of the parameters pane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Param {
    pub label: &'static str,
    pub kind: ParamKind,
}

const fn number(
    label: &'static str,
    key: &'static str,
    step: f64,
    coarse: f64,
    decimals: usize,
    boundary: bool,
) -> Param {
    Param {
        label,
        kind: ParamKind::Number {
            key,
            step,
            coarse,
            decimals,
            boundary,
        },
    }
}

/// The row of `PARAMS` that varies `key`, if it is offered for `p` (else the first row that is).
pub fn param_index(p: &ValidPreset, key: &str) -> usize {
    PARAMS
        .iter()
        .position(|r| {
            offered(p, r) && matches!(r.kind, ParamKind::Number { key: k, .. } if k == key)
        })
        .or_else(|| PARAMS.iter().position(|r| offered(p, r)))
        .unwrap_or(0)
}

/// Whether the parameters pane offers `param` for `p`: a knob that can change nothing for the
/// preset's blade is left out, as `--set` and `--vary` refuse it ([`not_acting`]). Knobs that
/// only wait for another setting the explorer can change (wind speed without aerodynamics) stay,
/// dimmed by the pane.
pub fn offered(p: &ValidPreset, param: &Param) -> bool {
    match param.kind {
        ParamKind::Number { key, .. } => not_acting(p, key).is_none(),
        ParamKind::Aero => true,
    }
}

/// The rows of `PARAMS` offered for `p`, in pane order.
pub fn offered_rows(p: &ValidPreset) -> Vec<usize> {
    (0..PARAMS.len())
        .filter(|&i| offered(p, &PARAMS[i]))
        .collect()
}

/// The parameters the explorer varies, in pane order.
pub static PARAMS: &[Param] = &[
    number("ply angle", "section.ply_angle", 1.0, 5.0, 1, true),
    number(
        "bend–twist α",
        "blade.bend_twist_coupling",
        0.01,
        0.05,
        2,
        true,
    ),
    number("wind speed", "operating.wind_speed", 0.5, 5.0, 1, true),
    number("tunnel speed", "operating.tunnel_speed", 1.0, 10.0, 1, true),
    number("rotor speed", "operating.rotor_speed", 1.0, 10.0, 0, true),
    number("pitch", "operating.pitch", 0.5, 5.0, 1, true),
    Param {
        label: "aero model",
        kind: ParamKind::Aero,
    },
    number("modes N", "structure.modes", 1.0, 5.0, 0, false),
    number(
        "loss factor",
        "structure.loss_factor",
        0.005,
        0.05,
        3,
        false,
    ),
];

/// The slider range of a numeric key: the key table's range, with wind and rotor speed capped by
/// the preset's `view` maxima (but never below the current value).
pub fn param_bounds(p: &ValidPreset, key: &str) -> (f64, f64) {
    let Ok(spec) = key_spec(key) else {
        return (f64::NEG_INFINITY, f64::INFINITY);
    };
    let (lo, mut hi) = (spec.min, spec.max);
    let cur = (spec.get)(p);
    // Along a schedule the wind runs where the turbine operates, cut-in to cut-out.
    if key == WIND_SPEED_KEY {
        if let Some((a, b)) = schedule_wind_range(p) {
            return (a.min(cur), b.max(cur));
        }
    }
    match key {
        "operating.rotor_speed" => hi = p.view.rotor_speed_max.max(cur),
        "operating.wind_speed" => hi = p.view.wind_speed_max.max(cur),
        "operating.tunnel_speed" => hi = p.view.tunnel_speed_max.max(cur),
        _ => {}
    }
    (lo, hi)
}

/// Rotor speeds below this (rpm) are shown to 0.01 rpm: a turbine rotor turns at 5–15 rpm,
/// where a whole rpm is 7–20 % of its rated speed.
pub const FINE_ROTOR_SPEED_BELOW: f64 = 30.0;

/// The fine and coarse steps of `param` on `p`: the row's own, except the rotor speed of a preset
/// with a rated rotor speed, which steps by 1 % and 10 % of it (so a step is a fixed share of
/// rated, as the overspeed margin is quoted). The paper's blades give none and step by the
/// row's 1 and 10 rpm.
pub fn steps(p: &ValidPreset, param: &Param) -> Option<(f64, f64)> {
    let ParamKind::Number {
        key, step, coarse, ..
    } = param.kind
    else {
        return None;
    };
    let rated = p.operating.rated_rotor_speed;
    Some(if key == ROTOR_SPEED_KEY && rated > 0.0 {
        (0.01 * rated, 0.1 * rated)
    } else {
        (step, coarse)
    })
}

/// The decimals a value of `key` is shown with: its row's, except rotor speeds below
/// [`FINE_ROTOR_SPEED_BELOW`], shown to 0.01 rpm.
pub fn shown_decimals(key: &str, v: f64) -> usize {
    if key == ROTOR_SPEED_KEY && v.abs() < FINE_ROTOR_SPEED_BELOW {
        return 2;
    }
    PARAMS
        .iter()
        .find_map(|p| match p.kind {
            ParamKind::Number {
                key: k, decimals, ..
            } if k == key => Some(decimals),
            _ => None,
        })
        .unwrap_or(2)
}

/// `v` as the parameters pane shows a value of `key`: its decimals and unit (`7.56 rpm`).
pub fn value_text(key: &str, v: f64) -> String {
    let (u, d) = (unit(key), shown_decimals(key, v));
    if u.is_empty() {
        format!("{v:.d$}")
    } else {
        format!("{v:.d$} {u}")
    }
}

/// The unit of a numeric key.
pub fn unit(key: &str) -> &'static str {
    key_spec(key).map(|s| s.unit).unwrap_or("")
}

/// A named preset the `[`/`]` keys cycle through.
#[derive(Debug, Clone)]
pub struct PresetEntry {
    pub name: String,
    pub preset: ValidPreset,
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

/// The Campbell view's axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CampbellAxis {
    /// 0 to `view.rotor_speed_max`, everything else as set.
    RotorSpeed,
    /// Cut-in to cut-out along the operating schedule (rotor speed and pitch the schedule's).
    WindSpeed,
}

impl CampbellAxis {
    pub fn key(self) -> &'static str {
        match self {
            CampbellAxis::RotorSpeed => ROTOR_SPEED_KEY,
            CampbellAxis::WindSpeed => WIND_SPEED_KEY,
        }
    }
}

/// Which way from the current value one search of a margin runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Down to the slider's low end.
    Below,
    /// Up to the slider's high end.
    Above,
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

/// The background boundary search along one key: from the current value both ways to the
/// slider's ends. From a stable point each side's search finds the nearest boundary on that side;
/// from an unstable one, where the blade is stable again, so the two bound the unstable stretch
/// the current value lies in.
#[derive(Debug, Clone)]
pub struct BoundaryJob {
    pub gen: u64,
    pub key: &'static str,
    /// The slider's range and the value the searches start from.
    pub from: f64,
    pub to: f64,
    pub current: f64,
    /// Whether the operating point was unstable.
    pub unstable: bool,
    /// The sides searched, in the order of the results (a side with nothing between the current
    /// value and the slider's end is not searched).
    pub sides: Vec<Side>,
    /// One search per side; `None` while running (or when no side has a range).
    pub result: Option<Result<Vec<Search>, String>>,
}

/// The Campbell diagram, valid for every preset equal to `for_preset` up to the axis's key.
#[derive(Debug, Clone)]
pub struct CampbellJob {
    pub gen: u64,
    pub axis: CampbellAxis,
    /// The axis's range.
    pub from: f64,
    pub to: f64,
    pub points: usize,
    pub for_preset: Preset,
    pub result: Option<Result<Campbell, String>>,
}

/// Everything the screen shows.
#[derive(Debug, Clone)]
pub struct AppState {
    pub presets: Vec<PresetEntry>,
    pub preset_index: usize,
    /// The parameters being explored.
    pub preset: ValidPreset,
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

/// Inputs to [`update`].
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
    /// The worker died and was restarted (or could not be).
    WorkerFailed(String),
    /// Terminal input failed (e.g. stdin closed): the explorer cannot be driven, so it quits.
    InputClosed(String),
}

/// What [`update`] asks the outside world to do.
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
    /// A state showing `presets[index]`; call [`AppState::start`] for the first effects.
    pub fn new(presets: Vec<PresetEntry>, index: usize, opts: Options) -> AppState {
        assert!(
            !presets.is_empty(),
            "the explorer needs at least one preset"
        );
        let index = index.min(presets.len() - 1);
        let preset = presets[index].preset.clone();
        let focus = param_index(&preset, preset.view.select.key());
        let start = opening_key(&preset, focus);
        AppState {
            presets,
            preset_index: index,
            preset,
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

    /// The first request: solve the starting parameters.
    pub fn start(&mut self) -> Vec<Effect> {
        self.gen += 1;
        vec![self.solve_effect()]
    }

    /// Still waiting for the solve of the current parameters.
    pub fn solving(&self) -> bool {
        self.solved_gen != self.gen
    }

    pub fn focused(&self) -> &'static Param {
        &PARAMS[self.focus]
    }

    /// The value of a parameter row as text with its unit.
    pub fn param_text(&self, param: &Param) -> String {
        match param.kind {
            ParamKind::Aero => self.preset.aero.model.name().to_string(),
            ParamKind::Number { key, .. } => match self.scheduled_value(key) {
                // ↻: the schedule sets it at this wind speed.
                Some(v) => format!("↻ {}", value_text(key, v)),
                None => value_text(key, self.preset.get(key).unwrap_or(f64::NAN)),
            },
        }
    }

    /// Rotor speed and pitch follow the preset's schedule again (`o`).
    fn follow_schedule(&mut self) -> Vec<Effect> {
        let p = &self.preset;
        if p.operating.schedule == crate::preset::Schedule::None {
            self.notice =
                Some("this preset has no operating schedule (operating.schedule = none)".into());
            return Vec::new();
        }
        if p.schedule_overrides == crate::preset::ScheduleOverrides::default() {
            self.notice = Some("rotor speed and pitch already follow the schedule".into());
            return Vec::new();
        }
        // Back to the starting preset's own values too, so nothing reads as changed by hand.
        let start = &self.presets[self.preset_index].preset.operating;
        let (rpm, pitch) = (start.rotor_speed, start.pitch);
        let edited = p.edited(|q| {
            q.follow_schedule();
            q.operating.rotor_speed = rpm;
            q.operating.pitch = pitch;
        });
        self.apply(edited)
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

    /// The parameters changed: new generation, re-solve.
    fn changed(&mut self) -> Vec<Effect> {
        self.gen += 1;
        self.solve_seconds = 0.0;
        vec![self.solve_effect()]
    }

    /// Load preset entry `index` (or the current one again for reset).
    fn load_entry(&mut self, index: usize) -> Vec<Effect> {
        self.preset_index = index;
        self.preset = self.presets[index].preset.clone();
        // Each preset opens on the parameter it selects (`view.select`).
        self.focus = param_index(&self.preset, self.preset.view.select.key());
        self.boundary_key = opening_key(&self.preset, self.focus);
        if schedule_wind_range(&self.preset).is_none() {
            self.campbell_axis = CampbellAxis::RotorSpeed;
        }
        self.shape_pick = None;
        self.trails.clear();
        self.prev_modes.clear();
        self.fresh = true;
        self.changed()
    }

    /// A boundary search along the current boundary key, once the verdict is known.
    fn boundary_effect(&mut self) -> Option<Effect> {
        let solved = self.solved.as_ref()?;
        if self.solved_gen != self.gen {
            return None;
        }
        let key = self.boundary_key;
        let (lo, hi) = param_bounds(&self.preset, key);
        // The value the parameters pane shows: a scheduled rotor speed or pitch is the
        // schedule's, not the preset's own.
        let current = self
            .scheduled_value(key)
            .or_else(|| self.preset.get(key).ok())?
            .clamp(lo, hi);
        let unstable = !solved.stability.stable;
        // Each side on its share of the points: the spacing of one search over the slider.
        let span = hi - lo;
        let (sides, ranges): (Vec<Side>, Vec<SearchRange>) = [(Side::Below, lo), (Side::Above, hi)]
            .into_iter()
            .filter(|&(_, end)| end != current)
            .map(|(side, end)| {
                let share = ((current - end).abs() / span * (BOUNDARY_POINTS - 1) as f64).ceil();
                let range = SearchRange {
                    key: key.to_string(),
                    from: current,
                    to: end,
                    points: (share as usize + 1).max(2),
                    regain: true,
                };
                (side, range)
            })
            .unzip();
        self.boundary = Some(BoundaryJob {
            gen: self.gen,
            key,
            from: lo,
            to: hi,
            current,
            unstable,
            sides,
            result: None,
        });
        if ranges.is_empty() {
            return None;
        }
        Some(Effect::Boundary {
            gen: self.gen,
            key,
            preset: Arc::new(self.preset.clone()),
            ranges,
        })
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

    fn campbell_effect(&mut self) -> Option<Effect> {
        if self.view != ViewMode::Campbell || self.campbell_current() {
            return None;
        }
        let (from, to, points) = self.campbell_range();
        let grid = crate::precision::grid(from, to, points);
        self.campbell = Some(CampbellJob {
            gen: self.gen,
            axis: self.campbell_axis,
            from,
            to,
            points,
            for_preset: self.campbell_key(),
            result: None,
        });
        Some(Effect::Campbell {
            gen: self.gen,
            preset: Arc::new(self.campbell_preset()),
            key: self.campbell_axis.key(),
            grid,
        })
    }

    /// `w`: the Campbell axis rotor speed ↔ wind speed along the schedule (opening the view).
    fn toggle_campbell_axis(&mut self) -> Vec<Effect> {
        if schedule_wind_range(&self.preset).is_none() {
            self.campbell_axis = CampbellAxis::RotorSpeed;
            self.notice = Some(
                "this preset has no operating schedule: its Campbell diagram is against rotor \
                 speed only"
                    .into(),
            );
        } else if self.view == ViewMode::Campbell {
            self.campbell_axis = match self.campbell_axis {
                CampbellAxis::RotorSpeed => CampbellAxis::WindSpeed,
                CampbellAxis::WindSpeed => CampbellAxis::RotorSpeed,
            };
        } else {
            self.campbell_axis = CampbellAxis::WindSpeed;
        }
        self.view = ViewMode::Campbell;
        self.campbell_effect().into_iter().collect()
    }

    /// Take an edited preset and re-solve, or keep the current one and say why the edit failed.
    fn apply(&mut self, edited: crate::error::Result<ValidPreset>) -> Vec<Effect> {
        match edited {
            Ok(p) => {
                self.preset = p;
                self.changed()
            }
            Err(e) => {
                self.notice = Some(e.to_string());
                Vec::new()
            }
        }
    }

    /// The next (or previous) aerodynamic model.
    fn cycle_aero(&mut self, forward: bool) -> Vec<Effect> {
        let model = self.preset.aero.model.cycle(forward);
        let edited = self.preset.edited(|p| p.aero.model = model);
        self.apply(edited)
    }

    /// Step the focused parameter by `steps` fine or coarse steps.
    fn adjust(&mut self, up: bool, coarse: bool) -> Vec<Effect> {
        match self.focused().kind {
            ParamKind::Aero => self.cycle_aero(up),
            ParamKind::Number { key, .. } => {
                let Some((fine, coarse_step)) = steps(&self.preset, self.focused()) else {
                    return Vec::new();
                };
                let step = if coarse { coarse_step } else { fine };
                // A scheduled value steps from where the schedule has it.
                let Some(v) = self
                    .scheduled_value(key)
                    .or_else(|| self.preset.get(key).ok())
                else {
                    return Vec::new();
                };
                let (lo, hi) = param_bounds(&self.preset, key);
                // Snap to the step grid, then clamp; round away float drift. A value within a
                // thousandth of a step of a grid point counts as on it (a schedule's 7.559987 rpm,
                // shown as 7.56, steps to 7.56 + a step, not to 7.56).
                let k = v / step;
                let next = if up {
                    ((k + 1e-3).floor() + 1.0) * step
                } else {
                    ((k - 1e-3).ceil() - 1.0) * step
                };
                let next = (next.clamp(lo, hi) * 1e9).round() / 1e9;
                if next == v {
                    self.notice = Some(format!(
                        "{} is at its {} ({})",
                        self.focused().label,
                        if up { "maximum" } else { "minimum" },
                        self.param_text(self.focused())
                    ));
                    return Vec::new();
                }
                let edited = self.preset.with(key, next);
                self.apply(edited)
            }
        }
    }

    fn on_action(&mut self, action: Action) -> Vec<Effect> {
        self.notice = None;
        match action {
            Action::FocusPrev | Action::FocusNext => {
                // Step through the rows offered for this preset only.
                let rows = offered_rows(&self.preset);
                let n = rows.len().max(1);
                let at = rows.iter().position(|&r| r == self.focus).unwrap_or(0);
                let next = if action == Action::FocusNext {
                    (at + 1) % n
                } else {
                    (at + n - 1) % n
                };
                self.focus = rows.get(next).copied().unwrap_or(self.focus);
                self.trails.clear();
                if let ParamKind::Number {
                    key,
                    boundary: true,
                    ..
                } = self.focused().kind
                {
                    if key != self.boundary_key {
                        self.boundary_key = key;
                        return self.boundary_effect().into_iter().collect();
                    }
                }
                Vec::new()
            }
            Action::Decrease => self.adjust(false, false),
            Action::Increase => self.adjust(true, false),
            Action::DecreaseCoarse => self.adjust(false, true),
            Action::IncreaseCoarse => self.adjust(true, true),
            Action::PrevPreset | Action::NextPreset => {
                let n = self.presets.len();
                if n < 2 {
                    self.notice = Some("no other presets to cycle through".into());
                    return Vec::new();
                }
                let i = if action == Action::NextPreset {
                    (self.preset_index + 1) % n
                } else {
                    (self.preset_index + n - 1) % n
                };
                self.load_entry(i)
            }
            Action::CycleAero => self.cycle_aero(true),
            Action::TogglePause => {
                self.paused = !self.paused;
                vec![Effect::Pause(self.paused)]
            }
            Action::Reset => self.load_entry(self.preset_index),
            Action::FollowSchedule => self.follow_schedule(),
            Action::Kick => {
                if self.response.diverging {
                    self.notice = Some("the response diverged; press r to restart it".into());
                    return Vec::new();
                }
                let (twist_rad, flap_m) = self.kick_amounts();
                let mut out = Vec::new();
                if self.paused {
                    self.paused = false;
                    out.push(Effect::Pause(false));
                }
                out.push(Effect::Kick {
                    gen: self.gen,
                    twist_rad,
                    flap_m,
                });
                out
            }
            Action::Boundary => {
                if self.solved.is_none() || self.solving() {
                    self.notice = Some("the boundary search starts once the solve is done".into());
                    return Vec::new();
                }
                self.boundary_effect().into_iter().collect()
            }
            Action::ToggleCampbell => {
                self.view = match self.view {
                    ViewMode::Main | ViewMode::Shape => ViewMode::Campbell,
                    ViewMode::Campbell => ViewMode::Main,
                };
                self.campbell_effect().into_iter().collect()
            }
            Action::ToggleCampbellAxis => self.toggle_campbell_axis(),
            Action::ToggleShape => {
                self.view = match self.view {
                    ViewMode::Main | ViewMode::Campbell => ViewMode::Shape,
                    ViewMode::Shape => ViewMode::Main,
                };
                // The pane opens on the least-damped mode.
                self.shape_pick = None;
                Vec::new()
            }
            Action::PrevMode | Action::NextMode => {
                self.step_shape(action == Action::NextMode);
                Vec::new()
            }
            Action::CycleMarker => {
                self.opts.marker = self.opts.marker.next();
                Vec::new()
            }
            Action::ToggleHelp => {
                self.help = !self.help;
                Vec::new()
            }
            Action::Back => {
                if self.help {
                    self.help = false;
                } else {
                    self.view = ViewMode::Main;
                }
                Vec::new()
            }
            Action::Quit => {
                self.quit = true;
                vec![Effect::Quit]
            }
        }
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

    /// Pick the next (or previous) mode for the mode-shape pane, in the modes pane's order:
    /// oscillatory roots by frequency, then the real ones.
    fn step_shape(&mut self, forward: bool) {
        let Some(current) = self.shape_index() else {
            self.notice = Some("no modes solved yet".into());
            return;
        };
        let Some(solved) = self.solved.as_ref() else {
            return;
        };
        let modes = &solved.stability.eigenvalues;
        let order = frequency_order(modes);
        let n = order.len();
        let at = order.iter().position(|&i| i == current).unwrap_or(0);
        let next = order[if forward {
            (at + 1) % n
        } else {
            (at + n - 1) % n
        }];
        self.shape_pick = Some(modes[next].label.clone());
        if self.view != ViewMode::Shape {
            self.view = ViewMode::Shape;
        }
    }

    fn on_solved(&mut self, gen: u64, result: Result<Solved, String>) -> Vec<Effect> {
        self.solved_gen = gen;
        match result {
            Ok(solved) => {
                let old = self.solved.take().filter(|_| !self.fresh);
                self.fresh = false;
                if let Some(old) = old {
                    let poles: Vec<(f64, f64)> = old
                        .stability
                        .eigenvalues
                        .iter()
                        .map(|m| (m.re, m.im))
                        .collect();
                    self.trails.insert(0, poles);
                    self.trails.truncate(TRAIL_LEN);
                    self.prev_modes = old.stability.eigenvalues;
                }
                self.solved = Some(solved);
                self.solve_error = None;
                let mut out: Vec<Effect> = self.boundary_effect().into_iter().collect();
                out.extend(self.campbell_effect());
                out
            }
            Err(e) => {
                if let Some(old) = self.solved.take().filter(|_| !self.fresh) {
                    self.prev_modes = old.stability.eigenvalues;
                }
                self.solve_error = Some(e);
                self.boundary = None;
                Vec::new()
            }
        }
    }
}

/// The parameter a preset's first boundary search runs along: the focused row's key when it
/// searches one, else rotor speed.
fn opening_key(p: &ValidPreset, focus: usize) -> &'static str {
    match PARAMS[focus].kind {
        ParamKind::Number {
            key,
            boundary: true,
            ..
        } if offered(p, &PARAMS[focus]) => key,
        _ => "operating.rotor_speed",
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

/// Apply one message. Returns the effects to carry out, in order.
pub fn update(s: &mut AppState, msg: Msg) -> Vec<Effect> {
    let visible = match &msg {
        Msg::Action(_) | Msg::Resize | Msg::WorkerFailed(_) | Msg::InputClosed(_) => true,
        Msg::Solved { gen, .. } | Msg::Samples { gen, .. } | Msg::SimFailed { gen, .. } => {
            *gen == s.gen
        }
        // Only a slow solve of the current parameters is worth a redraw.
        Msg::SolveTime { gen, seconds } => {
            *gen == s.gen && s.solving() && *seconds >= SOLVE_BUDGET_S
        }
        Msg::Boundary { gen, key, .. } => {
            s.boundary
                .as_ref()
                .is_some_and(|b| b.gen == *gen && b.key == key.as_str())
                && *gen == s.gen
        }
        Msg::Campbell { gen, .. } => s.campbell.as_ref().is_some_and(|c| c.gen == *gen),
    };
    if !visible {
        // A stale result: the parameters moved on since it was asked for.
        return Vec::new();
    }
    s.dirty = true;
    match msg {
        Msg::Action(a) => s.on_action(a),
        Msg::Resize => Vec::new(),
        Msg::Solved { gen, result } => s.on_solved(gen, result),
        Msg::Samples {
            gen,
            samples,
            status,
        } => {
            let r = &mut s.response;
            if r.gen != gen {
                *r = Response {
                    gen,
                    ..Response::default()
                };
            }
            r.samples.extend(samples);
            r.diverging = status == RunStatus::Diverging;
            // Keep one simulation duration of history.
            if let Some(last) = r.samples.last().map(|x| x.t) {
                let window = s.preset.simulation.duration;
                let first_kept = r.samples.partition_point(|x| x.t < last - window);
                if first_kept > 0 {
                    r.samples.drain(..first_kept);
                }
            }
            Vec::new()
        }
        Msg::SimFailed { gen, error } => {
            if s.response.gen != gen {
                s.response = Response {
                    gen,
                    ..Response::default()
                };
            }
            s.response.error = Some(error);
            Vec::new()
        }
        Msg::Boundary { result, .. } => {
            if let Some(b) = s.boundary.as_mut() {
                b.result = Some(result);
            }
            Vec::new()
        }
        Msg::Campbell { result, .. } => {
            if let Some(c) = s.campbell.as_mut() {
                c.result = Some(result);
            }
            Vec::new()
        }
        Msg::SolveTime { seconds, .. } => {
            s.solve_seconds = seconds;
            Vec::new()
        }
        Msg::WorkerFailed(e) => {
            s.worker_error = Some(e);
            Vec::new()
        }
        Msg::InputClosed(e) => {
            s.quit = true;
            s.exit_error = Some(e);
            vec![Effect::Quit]
        }
    }
}
