//! The one function that changes the explorer's state: [`update`] takes a message, changes
//! [`AppState`] and returns the [`Effect`]s to carry out, with the state transitions behind it
//! (keys, edits, preset changes, solve results and the jobs they start). It does no I/O.

use crate::analysis::campbell::schedule_wind_range;
use crate::analysis::flutter::key_range;
use crate::analysis::flutter::SearchRange;
use crate::analysis::simulate::RunStatus;
use crate::explorer::engine::Solved;
use crate::explorer::keys::Action;
use crate::explorer::state::jobs::{
    opening_key, BoundaryJob, CampbellAxis, CampbellJob, Side, BOUNDARY_POINTS,
};
use crate::explorer::state::params::{offered_rows, param_index, steps, ParamKind};
use crate::explorer::state::{
    frequency_order, AppState, Check, Effect, Msg, Pending, Response, ViewMode, SOLVE_BUDGET_S,
    TRAIL_LEN,
};
use crate::preset::ValidPreset;
use std::sync::Arc;

impl AppState {
    /// The first request: solve the starting parameters.
    pub fn start(&mut self) -> Vec<Effect> {
        self.gen += 1;
        vec![self.solve_effect()]
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
        let start = &self.opened.operating;
        let (rpm, pitch) = (start.rotor_speed, start.pitch);
        let edited = p.edited(|q| {
            q.follow_schedule();
            q.operating.rotor_speed = rpm;
            q.operating.pitch = pitch;
        });
        self.apply(edited)
    }

    /// The parameters changed: new generation, re-solve.
    fn changed(&mut self) -> Vec<Effect> {
        self.gen += 1;
        self.solve_seconds = 0.0;
        vec![self.solve_effect()]
    }

    /// Open preset entry `index` (or the current one again for reset): at once when it has been
    /// checked, else once its check comes back.
    fn load_entry(&mut self, index: usize) -> Vec<Effect> {
        let Some(entry) = self.presets.get(index) else {
            return Vec::new();
        };
        match entry.preset.clone() {
            Some(p) => self.open(index, p),
            None => {
                let name = entry.name.clone();
                self.check(Check::Open { index, name })
            }
        }
    }

    /// Show `preset` as entry `index`, from a fresh start: an edit still being checked was made
    /// on what is left behind, and is dropped with it.
    fn open(&mut self, index: usize, preset: ValidPreset) -> Vec<Effect> {
        if matches!(
            self.checking,
            Some(Pending {
                check: Check::Edit { .. },
                ..
            })
        ) {
            self.checking = None;
        }
        self.preset_index = index;
        self.opened = preset.clone();
        self.preset = preset;
        // Each preset opens on the parameter it selects (`view.select`).
        self.focus = param_index(&self.preset, self.preset.view.select.key());
        self.boundary_key = opening_key(&self.preset, self.focus);
        if schedule_wind_range(&self.preset).is_none() {
            self.campbell_axis = CampbellAxis::RotorSpeed;
        }
        self.shape_pick = None;
        self.shape_part = None;
        self.trails.clear();
        self.prev_modes.clear();
        self.fresh = true;
        self.changed()
    }

    /// Ask for `check` off the event loop; it replaces any check still running.
    fn check(&mut self, check: Check) -> Vec<Effect> {
        self.check_id += 1;
        let id = self.check_id;
        self.checking = Some(Pending {
            id,
            gen: self.gen,
            check: check.clone(),
        });
        vec![Effect::Check { id, check }]
    }

    /// A check came back: apply the edit, or open the preset.
    fn on_checked(&mut self, result: Result<Box<ValidPreset>, String>) -> Vec<Effect> {
        let Some(pending) = self.checking.take() else {
            return Vec::new();
        };
        match (pending.check, result) {
            // The parameters moved on meanwhile (another key): the edit is made on them now,
            // its blade kept from the check.
            (Check::Edit { key, value, .. }, Ok(_)) if pending.gen != self.gen => {
                let edited = self.preset.with(key, value);
                self.apply(edited)
            }
            (Check::Edit { .. }, Ok(p)) => self.apply(Ok(*p)),
            (Check::Open { index, .. }, Ok(p)) => {
                if let Some(entry) = self.presets.get_mut(index) {
                    entry.preset = Some((*p).clone());
                }
                self.open(index, *p)
            }
            (_, Err(e)) => {
                self.notice = Some(e);
                Vec::new()
            }
        }
    }

    /// A boundary search along the current boundary key, once the verdict is known.
    fn boundary_effect(&mut self) -> Option<Effect> {
        let solved = self.solved.as_ref()?;
        if self.solved_gen != self.gen {
            return None;
        }
        let key = self.boundary_key;
        let (lo, hi) = key_range(&self.preset, key);
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
        let polars = self.preset.blade.source.is_tabulated();
        let model = self.preset.aero.model.cycle_for(forward, polars);
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
                    .pending_value(key)
                    .or_else(|| self.scheduled_value(key))
                    .or_else(|| self.preset.get(key).ok())
                else {
                    return Vec::new();
                };
                let (lo, hi) = key_range(&self.preset, key);
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
                // A blade analysed again (a WindIO blade's ply angle) is checked off the event
                // loop; the row shows the new value meanwhile.
                if self.preset.with_reads_blade(key, next) {
                    return self.check(Check::Edit {
                        base: Arc::new(self.preset.clone()),
                        key,
                        value: next,
                    });
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
            Action::Reset => self.open(self.preset_index, self.opened.clone()),
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
            Action::CyclePart => {
                self.cycle_shape_part();
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

    /// Draw the next part of the shown mode (blade 1, 2, 3, tower) in the mode-shape pane.
    fn cycle_shape_part(&mut self) {
        let shapes = self
            .shape_index()
            .and_then(|i| self.solved.as_ref()?.shapes.get(i));
        let Some(shapes) = shapes else {
            self.notice = Some("no mode shapes solved yet".into());
            return;
        };
        if shapes.parts.len() < 2 {
            self.notice = Some(
                "one blade has one part: the rotor and turbine models (turbine.model) draw each \
                 blade and the tower"
                    .into(),
            );
            return;
        }
        let next = (self.shape_part_index(shapes) + 1) % shapes.parts.len();
        self.shape_part = Some(shapes.parts[next].part.clone());
        self.view = ViewMode::Shape;
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
        Msg::Checked { id, .. } => s.checking.as_ref().is_some_and(|c| c.id == *id),
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
        Msg::Checked { result, .. } => s.on_checked(result),
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
