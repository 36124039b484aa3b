//! The operating curve (docs/model.md §12.3): the rotor speed and pitch the turbine runs at in a
//! given wind, from a table (a HAWC2 `.opt` file) or from a control law.
//!
//! The law is the textbook variable-speed, pitch-regulated one: below rated the rotor tracks its
//! optimal tip speed ratio, `Ω = λ_opt U / R`, clipped to `[Ω_min, Ω_max]`, at zero pitch; where
//! that would make more than the rated aerodynamic power, the pitch turns toward feather until
//! the power is rated again (found by a bracketed root find on the pitch with the BEM, §12.2).

use crate::error::{Error, Result};
use crate::numeric::root::brent_with_values;

/// Rotor speed and pitch at one wind speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setting {
    /// Ω (rad/s).
    pub rotor_speed: f64,
    /// θ_p (rad), toward feather.
    pub pitch: f64,
}

/// A tabulated operating curve: pitch and rotor speed against wind speed, linear in between.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Wind speed (m/s), strictly increasing.
    pub wind_speed: Vec<f64>,
    /// Pitch (rad).
    pub pitch: Vec<f64>,
    /// Rotor speed (rad/s).
    pub rotor_speed: Vec<f64>,
    /// Where the table came from, for messages.
    pub origin: String,
}

/// The control law's parameters (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Law {
    /// Rated aerodynamic power (W).
    pub rated_power: f64,
    /// Ω_min, Ω_max (rad/s).
    pub rotor_speed_min: f64,
    pub rotor_speed_max: f64,
    /// λ_opt, region 2.
    pub tip_speed_ratio: f64,
    /// R (m).
    pub tip_radius: f64,
}

/// Pitch searched at most above rated (rad): beyond 60° toward feather a blade makes no power
/// in any wind a turbine runs in.
const MAX_PITCH: f64 = std::f64::consts::FRAC_PI_3;
/// Tolerance of the pitch that holds rated power (rad): 1e-7 rad changes the power by about
/// 1e-6 of rated.
const PITCH_TOLERANCE: f64 = 1e-7;

impl Table {
    /// The setting at `wind`, linear between rows; a wind outside the table is refused, not
    /// extrapolated.
    pub fn at(&self, wind: f64) -> Result<Setting> {
        let w = &self.wind_speed;
        let (first, last) = (w[0], w[w.len() - 1]);
        if !(first..=last).contains(&wind) {
            return Err(Error::numerical(format!(
                "operating.wind_speed = {wind} m/s is outside the operating table {} ({first} … \
                 {last} m/s)",
                self.origin
            )));
        }
        let k = w
            .partition_point(|&x| x <= wind)
            .clamp(1, w.len().max(2) - 1);
        if w.len() == 1 {
            return Ok(Setting {
                rotor_speed: self.rotor_speed[0],
                pitch: self.pitch[0],
            });
        }
        let t = (wind - w[k - 1]) / (w[k] - w[k - 1]);
        let lerp = |v: &[f64]| v[k - 1] + t * (v[k] - v[k - 1]);
        Ok(Setting {
            rotor_speed: lerp(&self.rotor_speed),
            pitch: lerp(&self.pitch),
        })
    }
}

impl Law {
    /// Ω at `wind` (rad/s): the optimal tip speed ratio within the rotor-speed limits.
    pub fn rotor_speed(&self, wind: f64) -> f64 {
        (self.tip_speed_ratio * wind / self.tip_radius)
            .clamp(self.rotor_speed_min, self.rotor_speed_max)
    }

    /// The pitch that holds rated power on the blade as it stands, or zero where the fine pitch
    /// makes no more than rated; `power(θ_p)` is the rotor's aerodynamic power at a pitch (the
    /// BEM on that blade) and `search` carries the last pass's pitch and slope. The returned
    /// pitch is one `power` was evaluated at.
    pub fn pitch(
        &self,
        wind: f64,
        search: &mut PitchSearch,
        mut power: impl FnMut(f64) -> Result<f64>,
    ) -> Result<f64> {
        let mut failure = None;
        let mut tried: Vec<(f64, f64)> = Vec::new();
        let mut excess = |pitch: f64| {
            let e = match power(pitch) {
                Ok(p) => p - self.rated_power,
                Err(e) => {
                    failure.get_or_insert(e);
                    f64::NAN
                }
            };
            tried.push((pitch, e));
            e
        };
        let found = search
            .last
            .and_then(|(pitch, slope)| secant(&mut excess, pitch, slope))
            .or_else(|| bracketed(&mut excess));
        if let Some(e) = failure {
            return Err(e);
        }
        let pitch = found.ok_or_else(|| {
            let fine = tried
                .iter()
                .find(|(pitch, _)| *pitch == 0.0)
                .map_or(f64::NAN, |(_, e)| e + self.rated_power);
            Error::numerical(format!(
                "operating.schedule = \"law\": at {wind} m/s no pitch between 0° and {}° brings \
                 the aerodynamic power down to operating.rated_power = {} W (at 0°: {fine:.6e} W)",
                MAX_PITCH.to_degrees(),
                self.rated_power
            ))
        })?;
        search.settle(pitch, &tried);
        Ok(pitch)
    }
}

/// What one pass of the law's pitch search leaves the next: the pitch it found and the power's
/// slope there. The passes of the static aeroelastic equilibrium (docs/model.md §12.6) each
/// need the pitch of a blade deflected a little differently from the last, so a secant step or
/// two from the last pitch along the last slope finds it where a bracketed search would take
/// ten BEM solves.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PitchSearch {
    /// Pitch (rad) and `dP/dθ_p` (W/rad), negative above rated.
    last: Option<(f64, f64)>,
}

impl PitchSearch {
    /// Keep `pitch` and the slope through the two evaluations nearest it (the last slope when
    /// there is only one: the fine pitch below rated).
    fn settle(&mut self, pitch: f64, tried: &[(f64, f64)]) {
        let mut near: Vec<&(f64, f64)> = tried.iter().filter(|(_, e)| e.is_finite()).collect();
        near.sort_by(|a, b| (a.0 - pitch).abs().total_cmp(&(b.0 - pitch).abs()));
        // Evaluations closer than this are as much the BEM's convergence noise as the slope.
        let apart = |a: &(f64, f64), b: &(f64, f64)| (a.0 - b.0).abs() > SLOPE_BASE;
        let slope = match near.as_slice() {
            [a, rest @ ..] => rest
                .iter()
                .find(|b| apart(a, b))
                .map(|b| (a.1 - b.1) / (a.0 - b.0)),
            [] => None,
        };
        let slope = slope.unwrap_or_else(|| self.last.map_or(f64::NAN, |(_, s)| s));
        self.last = Some((pitch, slope));
    }
}

/// Secant steps from `pitch` along `slope` on the excess power `f` (W over rated), held at or
/// above zero pitch, until the next step would be below [`PITCH_TOLERANCE`]: the last pitch
/// evaluated. `None` where the slope is not a falling one or the steps do not settle (the
/// caller then brackets the root).
fn secant(f: &mut impl FnMut(f64) -> f64, pitch: f64, slope: f64) -> Option<f64> {
    let (mut x, mut fx, mut slope) = (pitch, f(pitch), slope);
    for _ in 0..SECANT_STEPS {
        if !(fx.is_finite() && slope < 0.0) {
            return None;
        }
        let next = (x - fx / slope).clamp(0.0, MAX_PITCH);
        if (next - x).abs() <= PITCH_TOLERANCE {
            return Some(x);
        }
        let f_next = f(next);
        if next == 0.0 && f_next <= 0.0 {
            return Some(0.0);
        }
        slope = (f_next - fx) / (next - x);
        (x, fx) = (next, f_next);
    }
    None
}

/// Zero pitch where the fine pitch makes no more than rated, else Brent's method between 0° and
/// [`MAX_PITCH`] (the power falls toward feather).
fn bracketed(f: &mut impl FnMut(f64) -> f64) -> Option<f64> {
    let fine = f(0.0);
    if fine <= 0.0 {
        return Some(0.0);
    }
    let feathered = f(MAX_PITCH);
    brent_with_values(f, 0.0, fine, MAX_PITCH, feathered, PITCH_TOLERANCE)
}

/// Shortest pitch interval (rad) a slope is taken over: 1e-5 rad changes the power by about
/// 1e-4 of rated, far above the BEM's convergence noise.
const SLOPE_BASE: f64 = 1e-5;

/// Secant steps a pass may take before its search falls back to the bracket.
const SECANT_STEPS: usize = 8;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_interpolates_and_refuses_outside() {
        let t = Table {
            wind_speed: vec![4.0, 6.0],
            pitch: vec![0.0, 0.1],
            rotor_speed: vec![0.5, 0.7],
            origin: "t".into(),
        };
        let s = t.at(5.0).unwrap();
        assert!((s.pitch - 0.05).abs() < 1e-15 && (s.rotor_speed - 0.6).abs() < 1e-15);
        assert!(t.at(3.9).is_err() && t.at(6.1).is_err());
    }

    /// A made-up rotor whose power falls linearly with the pitch: below rated the law stays at
    /// fine pitch, above it the bracket finds the pitch for rated power, and a search started
    /// from that pitch and slope on a slightly different blade lands on its pitch in a secant
    /// step or two.
    #[test]
    fn law_tracks_tsr_then_pitches_to_rated() {
        let law = Law {
            rated_power: 1.0,
            rotor_speed_min: 0.5,
            rotor_speed_max: 1.0,
            tip_speed_ratio: 5.0,
            tip_radius: 10.0,
        };
        assert_eq!(law.rotor_speed(1.0), 0.5);
        assert_eq!(law.rotor_speed(1.5), 0.75);
        assert_eq!(law.rotor_speed(10.0), 1.0);
        let rotor = |wind: f64, gain: f64| {
            move |pitch: f64| Ok(gain * 0.002 * wind.powi(3) * (1.0 - pitch))
        };
        let mut search = PitchSearch::default();
        assert_eq!(law.pitch(1.0, &mut search, rotor(1.0, 1.0)).unwrap(), 0.0);
        let mut search = PitchSearch::default();
        let high = law.pitch(10.0, &mut search, rotor(10.0, 1.0)).unwrap();
        assert!((2.0 * (1.0 - high) - 1.0).abs() < 1e-6, "{high}");
        let mut calls = 0;
        let stiffer = law
            .pitch(10.0, &mut search, |pitch| {
                calls += 1;
                rotor(10.0, 1.01)(pitch)
            })
            .unwrap();
        assert!((2.02 * (1.0 - stiffer) - 1.0).abs() < 1e-6, "{stiffer}");
        assert!(calls <= 3, "{calls} evaluations");
        // Below rated again: back to fine pitch.
        assert_eq!(law.pitch(1.0, &mut search, rotor(1.0, 1.0)).unwrap(), 0.0);
        // No pitch up to 60° brings the power down: an error naming the wind and the rating.
        let e = law
            .pitch(10.0, &mut PitchSearch::default(), |_| Ok(5.0))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("at 10 m/s") && e.contains("rated_power = 1 W"),
            "{e}"
        );
    }
}
