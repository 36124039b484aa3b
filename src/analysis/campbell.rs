//! Campbell diagrams: along rotor speed, or along the operating schedule's wind speeds with the
//! scheduled rotor speed for the harmonics (docs/model.md §6.4, §12.7), and which tracked modes
//! a diagram draws. The latter is a property of the sweep's result, decided here once, so the
//! explorer's Campbell view and `--plot` show the same modes for the same sweep.

use crate::analysis::cancel::Cancel;
use crate::analysis::sweep::{track_cancellable, TrackedMode, TrackedSweep};
use crate::error::Result;
use crate::preset::{Schedule, ValidPreset};

/// The rotor-speed key: a sweep along it is a Campbell diagram.
pub const ROTOR_SPEED_KEY: &str = "operating.rotor_speed";

/// The wind-speed key: along it, on a preset with an operating schedule, the sweep is the
/// aeroelastic Campbell diagram of the turbine in operation (docs/model.md §12.7).
pub const WIND_SPEED_KEY: &str = "operating.wind_speed";

/// A Campbell diagram: the tracked modes and the rotor speed at every point of the axis (the
/// axis itself along rotor speed; the schedule's along wind speed), for the rotor harmonics.
#[derive(Debug, Clone)]
pub struct Campbell {
    pub sweep: TrackedSweep,
    pub rotor_speed_rpm: Vec<f64>,
}

/// The wind speeds a scheduled preset operates over (m/s): `operating.cut_in` to
/// `operating.cut_out`, within the table's rows for a table (a wind outside it is refused);
/// where either is unstated, the table's end, or for a law 0 and `view.wind_speed_max`.
/// `None` without a schedule.
pub fn schedule_wind_range(p: &ValidPreset) -> Option<(f64, f64)> {
    let o = &p.operating;
    let stated = |v: f64| (v > 0.0).then_some(v);
    let (first, last) = match o.schedule {
        Schedule::None => return None,
        Schedule::Table => {
            let w = &p.schedule_table()?.wind_speed;
            (*w.first()?, *w.last()?)
        }
        Schedule::Law => (0.0, p.view.wind_speed_max),
    };
    let lo = stated(o.cut_in).map_or(first, |c| c.max(first));
    let hi = stated(o.cut_out).map_or(last, |c| c.min(last));
    (lo < hi).then_some((lo, hi))
}

/// The rotor speed (rpm) the schedule sets at each wind speed of `winds`.
fn scheduled_rotor_speeds(p: &ValidPreset, winds: &[f64]) -> Result<Vec<f64>> {
    winds
        .iter()
        .map(|&u| crate::model::operating::scheduled_rotor_speed(&p.with(WIND_SPEED_KEY, u)?))
        .collect()
}

/// Along wind speed on a preset with an operating schedule: the scheduled rotor speed (rpm) at
/// every wind of `grid`, for the rotor harmonics; `None` along any other key.
pub fn along_schedule_rotor_speeds(
    p: &ValidPreset,
    key: &str,
    grid: &[f64],
) -> Result<Option<Vec<f64>>> {
    if key != WIND_SPEED_KEY || p.operating.schedule == Schedule::None {
        return Ok(None);
    }
    scheduled_rotor_speeds(p, grid).map(Some)
}

/// The Campbell diagram of `p` along `key` (rotor speed, or wind speed along the schedule) over
/// `grid`, polling `cancel` between solves.
pub fn campbell(p: &ValidPreset, key: &str, grid: &[f64], cancel: &Cancel) -> Result<Campbell> {
    let sweep = track_cancellable(p, key, grid, cancel)?;
    cancel.check()?;
    let rotor_speed_rpm = if let Some(rpm) = along_schedule_rotor_speeds(p, key, grid)? {
        rpm
    } else if key == ROTOR_SPEED_KEY {
        grid.to_vec()
    } else {
        vec![p.operating.rotor_speed; grid.len()]
    };
    Ok(Campbell {
        sweep,
        rotor_speed_rpm,
    })
}

/// At most this many modes are drawn (the lowest); more would be an unreadable tangle.
pub const MAX_CAMPBELL_MODES: usize = 8;

/// Modes typically above this multiple of the lowest mode's top frequency (or above 3P at the top
/// rotor speed, if higher) are left off the frequency scale so the low modes stay readable (on
/// the paper's blade torsion sits ~100× above flap and would flatten it).
const SCALE_FACTOR: f64 = 5.0;

/// Where a tracked mode oscillates: a finite, positive frequency (tracked modes are NaN where
/// they have no partner and 0 Hz where the pair split into real roots).
pub fn oscillates(f_hz: f64) -> bool {
    f_hz.is_finite() && f_hz > 0.0
}

/// A mode's frequencies where it oscillates.
fn oscillating(m: &TrackedMode) -> impl Iterator<Item = f64> + '_ {
    m.frequency_hz.iter().copied().filter(|f| oscillates(*f))
}

/// A mode's typical frequency: the median of its oscillating points (`None` if it never does).
pub fn typical(m: &TrackedMode) -> Option<f64> {
    let mut f: Vec<f64> = oscillating(m).collect();
    if f.is_empty() {
        return None;
    }
    f.sort_by(f64::total_cmp);
    Some(f[f.len() / 2])
}

/// The modes drawn on one frequency scale.
#[derive(Debug, Clone, PartialEq)]
pub struct CampbellSelection {
    /// Indices into the sweep's modes, lowest typical frequency first.
    pub shown: Vec<usize>,
    /// Modes not drawn: far above the lowest, beyond the [`MAX_CAMPBELL_MODES`] lowest, or never
    /// oscillating.
    pub left_off: usize,
}

impl TrackedSweep {
    /// The modes a Campbell diagram (or, along another key, its frequency panel) draws: those
    /// that oscillate somewhere and typically stay within 5 × the lowest mode's top frequency
    /// (along rotor speed, at least up to 3P at the top speed), at most the
    /// [`MAX_CAMPBELL_MODES`] lowest.
    pub fn campbell_modes(&self) -> CampbellSelection {
        let mut order: Vec<(usize, f64)> = self
            .modes
            .iter()
            .enumerate()
            .filter_map(|(i, m)| typical(m).map(|t| (i, t)))
            .collect();
        order.sort_by(|a, b| a.1.total_cmp(&b.1));
        let total = self.modes.len();
        if order.is_empty() {
            return CampbellSelection {
                shown: Vec::new(),
                left_off: total,
            };
        }
        // The scale follows the lowest mode that oscillates at most points: a root that turns
        // real over most of the range (a free rotor's rotation, oscillating only where it
        // meets a lag root) would squeeze every other mode off it.
        let points = self.values.len();
        let lowest = order
            .iter()
            .find(|(i, _)| 2 * oscillating(&self.modes[*i]).count() >= points)
            .map_or(order[0].0, |&(i, _)| i);
        let top = oscillating(&self.modes[lowest]).fold(0.0, f64::max);
        let three_p = if self.parameter == ROTOR_SPEED_KEY {
            3.0 * self.values.iter().copied().fold(0.0, f64::max) / 60.0
        } else {
            0.0
        };
        let limit = (SCALE_FACTOR * top).max(three_p);
        let shown: Vec<usize> = order
            .into_iter()
            .filter(|(_, t)| *t <= limit)
            .take(MAX_CAMPBELL_MODES)
            .map(|(i, _)| i)
            .collect();
        CampbellSelection {
            left_off: total - shown.len(),
            shown,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mode(label: &str, f: Vec<f64>) -> TrackedMode {
        TrackedMode {
            label: label.into(),
            damping_ratio: vec![0.01; f.len()],
            re: vec![-0.1; f.len()],
            second_re: vec![f64::NAN; f.len()],
            switches: Vec::new(),
            frequency_hz: f,
        }
    }

    fn sweep(parameter: &str, modes: Vec<TrackedMode>) -> TrackedSweep {
        TrackedSweep {
            parameter: parameter.into(),
            values: vec![0.0, 60.0, 120.0],
            modes,
            failed: Vec::new(),
        }
    }

    #[test]
    fn far_modes_are_left_off_the_scale() {
        let s = sweep(
            ROTOR_SPEED_KEY,
            vec![
                mode("torsion 1", vec![400.0, 401.0, 402.0]),
                mode("flap 1", vec![0.1, 1.0, 2.0]),
                mode("flap 2", vec![0.6, 2.5, 4.9]),
            ],
        );
        let sel = s.campbell_modes();
        // Lowest first, up to 5 × flap 1's top (2 Hz), above 3P at 120 rpm (6 Hz).
        assert_eq!(sel.shown, [1, 2]);
        assert_eq!(sel.left_off, 1);
    }

    #[test]
    fn along_rotor_speed_the_scale_reaches_3p() {
        let modes = vec![
            mode("flap 1", vec![0.1, 0.2, 0.3]),
            mode("flap 2", vec![5.0, 5.0, 5.0]),
        ];
        // 3P at 120 rpm is 6 Hz, above 5 × 0.3 Hz: flap 2 stays.
        let sel = sweep(ROTOR_SPEED_KEY, modes.clone()).campbell_modes();
        assert_eq!(sel.shown, [0, 1]);
        // Along another key there is no 3P line: up to 5 × 0.3 Hz.
        let sel = sweep("operating.wind_speed", modes).campbell_modes();
        assert_eq!((sel.shown, sel.left_off), (vec![0], 1));
    }

    #[test]
    fn silent_modes_and_modes_beyond_the_lowest_few_are_left_off() {
        let mut modes: Vec<TrackedMode> = (0..10)
            .map(|k| mode(&format!("flap {}", k + 1), vec![1.0 + 0.1 * k as f64; 3]))
            .collect();
        modes.push(mode("split", vec![0.0, f64::NAN, 0.0]));
        let sel = sweep("operating.wind_speed", modes).campbell_modes();
        assert_eq!(sel.shown, (0..MAX_CAMPBELL_MODES).collect::<Vec<_>>());
        assert_eq!(sel.left_off, 11 - MAX_CAMPBELL_MODES);
        let none = sweep(ROTOR_SPEED_KEY, vec![mode("split", vec![0.0; 3])]).campbell_modes();
        assert_eq!((none.shown.len(), none.left_off), (0, 1));
    }
}
