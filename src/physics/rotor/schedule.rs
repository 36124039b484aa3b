//! The operating curve (docs/model.md §12.3): the rotor speed and pitch the turbine runs at in a
//! given wind, from a table (a HAWC2 `.opt` file) or from a control law.
//!
//! The law is the textbook variable-speed, pitch-regulated one: below rated the rotor tracks its
//! optimal tip speed ratio, `Ω = λ_opt U / R`, clipped to `[Ω_min, Ω_max]`, at zero pitch; where
//! that would make more than the rated aerodynamic power, the pitch turns toward feather until
//! the power is rated again (found by a bracketed root find on the pitch with the BEM, §12.2).

use crate::error::{Error, Result};
use crate::numeric::root::brent;

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
    /// The setting at `wind`; `power(Ω, θ_p)` is the rotor's aerodynamic power there (the BEM).
    pub fn at(&self, wind: f64, mut power: impl FnMut(f64, f64) -> Result<f64>) -> Result<Setting> {
        let rotor_speed = (self.tip_speed_ratio * wind / self.tip_radius)
            .clamp(self.rotor_speed_min, self.rotor_speed_max);
        let fine = power(rotor_speed, 0.0)?;
        if fine <= self.rated_power {
            return Ok(Setting {
                rotor_speed,
                pitch: 0.0,
            });
        }
        let mut failure = None;
        let mut excess = |pitch: f64| match power(rotor_speed, pitch) {
            Ok(p) => p - self.rated_power,
            Err(e) => {
                failure.get_or_insert(e);
                f64::NAN
            }
        };
        let pitch = brent(&mut excess, 0.0, MAX_PITCH, PITCH_TOLERANCE);
        if let Some(e) = failure {
            return Err(e);
        }
        let pitch = pitch.ok_or_else(|| {
            Error::numerical(format!(
                "operating.schedule = \"law\": at {wind} m/s no pitch between 0° and {}° brings \
                 the aerodynamic power down to operating.rated_power = {} W (at 0°: {fine:.6e} W)",
                MAX_PITCH.to_degrees(),
                self.rated_power
            ))
        })?;
        Ok(Setting { rotor_speed, pitch })
    }
}

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

    #[test]
    fn law_tracks_tsr_then_pitches_to_rated() {
        let law = Law {
            rated_power: 1.0,
            rotor_speed_min: 0.5,
            rotor_speed_max: 1.0,
            tip_speed_ratio: 5.0,
            tip_radius: 10.0,
        };
        // A made-up rotor: power ∝ U³ cos²(pitch)·… , falling with pitch.
        let wind = std::cell::Cell::new(0.0f64);
        let power = |_: f64, pitch: f64| Ok(0.002 * wind.get().powi(3) * (1.0 - pitch));
        wind.set(1.0);
        let low = law.at(1.0, power).unwrap();
        assert_eq!((low.rotor_speed, low.pitch), (0.5, 0.0));
        wind.set(10.0);
        let high = law.at(10.0, power).unwrap();
        assert_eq!(high.rotor_speed, 1.0);
        assert!(
            (0.002 * 1000.0 * (1.0 - high.pitch) - 1.0).abs() < 1e-6,
            "{high:?}"
        );
    }
}
