//! A preset's operating point (docs/model.md §12.6): its setting from `operating.schedule`, and
//! a real blade's steady aeroelastic equilibrium there ([`crate::physics::operating::settle`]
//! on the preset's rotor, strips and structure).

use super::aero::{aero_blade_of, aero_stations_of, rotor_of};
use super::structure::for_preset;
use crate::error::{Error, Result};
use crate::physics::aero::blade_element::{
    BladeElement, ElementSection, Hgm, HgmOverrides, StallDynamics, Unsteadiness,
};
use crate::physics::operating::{settle as settle_passes, Built, Operation, SteadyInputs};
use crate::physics::rotor::schedule::Law;
use crate::physics::rotor::steady::SteadyPoint;
use crate::preset::{AeroModel, Schedule, ValidPreset};
use std::f64::consts::PI;
use std::sync::Arc;

/// The preset with `operating.rotor_speed` and `operating.pitch` taken from its schedule at its
/// wind speed, except where an edit set one by hand ([`crate::preset::ScheduleOverrides`]:
/// overspeed at the schedule's pitch, say), and the schedule then set to `none`; the preset
/// itself when it has no schedule. A law's pitch above rated is the one its blade needs in its
/// static aeroelastic equilibrium ([`steady`]).
pub fn on_schedule(p: &ValidPreset) -> Result<ValidPreset> {
    match scheduled(p)? {
        Scheduled::Set(q) => Ok(q),
        Scheduled::Law(q, law) => {
            let pitch = law_point(&q, &law, unsteadiness(p))?.0.operating.pitch;
            held_against(p, &q, pitch)
        }
    }
}

/// The rotor speed (rpm) `p` runs at on its schedule: what [`on_schedule`] sets, without the
/// law's pitch search (the speed does not depend on the pitch).
pub fn scheduled_rotor_speed(p: &ValidPreset) -> Result<f64> {
    Ok(match scheduled(p)? {
        Scheduled::Set(q) => q.operating.rotor_speed,
        Scheduled::Law(_, _) if p.schedule_overrides.rotor_speed => p.operating.rotor_speed,
        Scheduled::Law(q, _) => q.operating.rotor_speed,
    })
}

/// Where a preset's setting comes from once its schedule is read.
enum Scheduled {
    /// Rotor speed and pitch both known: the preset at them, schedule `none`.
    Set(ValidPreset),
    /// The law's pitch still to find, on the preset at the law's rotor speed.
    Law(ValidPreset, Law),
}

/// `p` at its schedule's rotor speed, and its pitch where the schedule gives it without the
/// blade's equilibrium (a table, a pitch held by hand).
fn scheduled(p: &ValidPreset) -> Result<Scheduled> {
    let o = &p.operating;
    let held = p.schedule_overrides;
    let (rotor_speed, pitch) = match o.schedule {
        Schedule::None => return Ok(Scheduled::Set(p.clone())),
        Schedule::Table => {
            let s = p
                .schedule_table()
                .ok_or_else(|| {
                    Error::numerical("operating.schedule = \"table\" without its table")
                })?
                .at(o.wind_speed)
                .map_err(|e| e.at(p.operating_point()))?;
            (s.rotor_speed, Some(s.pitch))
        }
        Schedule::Law => {
            let law = Law {
                rated_power: o.rated_power,
                rotor_speed_min: o.rotor_speed_min * PI / 30.0,
                rotor_speed_max: o.rotor_speed_max * PI / 30.0,
                tip_speed_ratio: o.tip_speed_ratio,
                tip_radius: rotor_of(p, aero_blade_of(p)?).tip_radius,
            };
            let rotor_speed = law.rotor_speed(o.wind_speed);
            if !held.pitch {
                // The law's pitch belongs to its own rotor speed: overspeed runs at the pitch
                // the law sets at this wind.
                return Ok(Scheduled::Law(at_setting(p, Some(rotor_speed), None)?, law));
            }
            (rotor_speed, None)
        }
    };
    let set = |held: bool, x| (!held).then_some(x);
    at_setting(
        p,
        set(held.rotor_speed, rotor_speed),
        pitch.and_then(|x| set(held.pitch, x)),
    )
    .map(Scheduled::Set)
}

/// `p` with its schedule set to `none` at the rotor speed (rad/s) and pitch (rad) given, the
/// preset's own where not.
fn at_setting(
    p: &ValidPreset,
    rotor_speed: Option<f64>,
    pitch: Option<f64>,
) -> Result<ValidPreset> {
    p.edited(|q| {
        if let Some(rotor_speed) = rotor_speed {
            q.operating.rotor_speed = tidy(rotor_speed * 30.0 / PI);
        }
        if let Some(pitch) = pitch {
            q.operating.pitch = tidy(pitch.to_degrees());
        }
        q.operating.schedule = Schedule::None;
        q.operating.schedule_file.clear();
    })
}

/// Back to the preset's units, rounded to 1e-9 (far below any schedule's precision) so that a
/// table's 12.1 rpm reads 12.1 again after its trip through rad/s.
fn tidy(x: f64) -> f64 {
    (x * 1e9).round() / 1e9
}

/// `law_preset` (the law's rotor speed) with the law's `pitch` (deg), at the rotor speed `p`
/// holds by hand if it holds one.
fn held_against(p: &ValidPreset, law_preset: &ValidPreset, pitch: f64) -> Result<ValidPreset> {
    let held = p.schedule_overrides.rotor_speed;
    law_preset.edited(|q| {
        q.operating.pitch = pitch;
        if held {
            q.operating.rotor_speed = p.operating.rotor_speed;
        }
    })
}

/// The steady operating point of `p` as `flutterscope operating` reports it: the BEM on the
/// blade deflected by its static aeroelastic equilibrium, the setting it ran at and the tip's
/// deflection.
pub fn deflected_point(p: &ValidPreset) -> Result<(SteadyPoint, [f64; 3])> {
    let (at, op) = steady(p, unsteadiness(p))?;
    let tip = op.tip();
    Ok((
        SteadyPoint {
            wind_speed: at.operating.wind_speed,
            rotor_speed_rpm: at.operating.rotor_speed,
            pitch_deg: at.operating.pitch,
            state: op.flow,
        },
        tip,
    ))
}

/// The unsteady strip model a preset's `aero.model` selects on a real blade; quasi-steady for
/// `none` (every form has the same steady loads, so the operating point does not depend on it).
pub fn unsteadiness(p: &ValidPreset) -> Unsteadiness {
    let o = &p.aero.onera;
    match p.aero.model {
        AeroModel::None | AeroModel::QuasiSteady => Unsteadiness::QuasiSteady,
        AeroModel::Theodorsen => Unsteadiness::Theodorsen,
        AeroModel::Onera => Unsteadiness::Onera(StallDynamics {
            a: [o.a_l, o.a_m, o.a_d],
            r: [o.r_l, o.r_m, o.r_d],
        }),
        AeroModel::Hgm => {
            let h = &p.aero.hgm;
            Unsteadiness::Hgm(Hgm {
                overrides: HgmOverrides {
                    a1: h.a1,
                    a2: h.a2,
                    b1: h.b1,
                    b2: h.b2,
                    tau_p: h.tau_p,
                    tau_f: h.tau_f,
                },
            })
        }
    }
}

/// The steady aeroelastic operating point of `p` (a tabulated blade with its aerodynamic
/// description) with the strip model `unsteady`, at its schedule's setting: the preset at the
/// setting the point ran at ([`on_schedule`]) and the point.
pub fn steady(p: &ValidPreset, unsteady: Unsteadiness) -> Result<(ValidPreset, Operation)> {
    match scheduled(p)? {
        Scheduled::Set(q) => settle(&q, unsteady, None),
        Scheduled::Law(q, law) => {
            let (at, op) = law_point(&q, &law, unsteady)?;
            if p.schedule_overrides.rotor_speed {
                let at = held_against(p, &q, at.operating.pitch)?;
                settle(&at, unsteady, None)
            } else {
                Ok((at, op))
            }
        }
    }
}

/// The operating point of `p` (at the law's rotor speed) at the pitch its deflected blade needs
/// for the law's rated power.
fn law_point(
    p: &ValidPreset,
    law: &Law,
    unsteady: Unsteadiness,
) -> Result<(ValidPreset, Operation)> {
    settle(p, unsteady, Some(law))
}

/// The static aeroelastic equilibrium of `p` (docs/model.md §12.6) at its rotor speed; at its
/// pitch, or with `law`, at the pitch its deflected blade needs. With the preset at the pitch
/// the structure was last built at.
fn settle(
    p: &ValidPreset,
    unsteady: Unsteadiness,
    law: Option<&Law>,
) -> Result<(ValidPreset, Operation)> {
    let blade = aero_blade_of(p)?;
    let strips = aero_stations_of(p)?;
    let model = BladeElement {
        sections: strips
            .iter()
            .map(|s| ElementSection {
                chord: s.section.chord,
                ac_ahead: s.section.ac_ahead,
                polar: Arc::clone(&s.section.polar),
            })
            .collect(),
        air_density: p.operating.air_density,
        unsteadiness: unsteady,
    };
    if let Unsteadiness::Hgm(hgm) = unsteady {
        for (i, sec) in model.sections.iter().enumerate() {
            hgm.check(&sec.polar).map_err(|e| Error::Invalid {
                origin: p.origin.clone(),
                message: format!(
                    "aero.model = \"hgm\": the constants of station {} of {}: {e}",
                    i + 1,
                    model.sections.len()
                ),
            })?;
        }
    }
    let context = || p.operating_point();
    let inputs = SteadyInputs {
        rotor: rotor_of(p, blade),
        strips: &strips,
        model,
        wind_speed: p.operating.wind_speed,
        rotor_speed: p.omega(),
        air_density: p.operating.air_density,
        pitch: p.pitch_rad(),
        context: &context,
    };
    let build = |pitch: f64| -> Result<Built<ValidPreset>> {
        let at = if law.is_some() {
            at_setting(p, None, Some(pitch))?
        } else {
            p.clone()
        };
        Ok(Built {
            structure: for_preset(&at)?,
            pitch: at.pitch_rad(),
            tag: at,
        })
    };
    let (op, at) = settle_passes(&inputs, law, &build, &|at: &ValidPreset| {
        at.operating_point()
    })?;
    Ok((at, op))
}

/// True when `p`'s system is a real blade in the wind: a tabulated blade with its aerodynamic
/// description and a strip model.
pub fn in_the_wind(p: &ValidPreset) -> bool {
    p.tabulated_blade().is_some() && p.aero_blade().is_some() && p.aero.model != AeroModel::None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::preset::Preset;
    use std::sync::Arc;

    /// What a sweep along the schedule relies on: moving the wind speed, and then to the
    /// schedule's setting, keeps the aerodynamic description as read and the stations as built;
    /// a new station count builds new ones, and the old count's are still there.
    #[test]
    fn operating_points_share_the_blade_and_its_stations() {
        let p = Preset::load("iea15mw", &[]).unwrap();
        let stations = p.aero_stations().unwrap().unwrap();
        let q = on_schedule(&p.with("operating.wind_speed", 14.0).unwrap()).unwrap();
        assert!(Arc::ptr_eq(
            p.aero_blade().unwrap(),
            q.aero_blade().unwrap()
        ));
        assert!(Arc::ptr_eq(&stations, &q.aero_stations().unwrap().unwrap()));
        let fewer = q.with("aero.stations", 12.0).unwrap();
        let twelve = fewer.aero_stations().unwrap().unwrap();
        assert_eq!((stations.len(), twelve.len()), (30, 12));
        assert!(Arc::ptr_eq(&stations, &p.aero_stations().unwrap().unwrap()));
        // Only the last few counts stay: after four more, 30 is built again.
        for count in 8..12 {
            let other = p.with("aero.stations", f64::from(count)).unwrap();
            assert_eq!(
                other.aero_stations().unwrap().unwrap().len(),
                count as usize
            );
        }
        let again = p.aero_stations().unwrap().unwrap();
        assert!(!Arc::ptr_eq(&stations, &again) && again.len() == 30);
        // A blade read again (another aerodynamic file key) gets stations of its own.
        let straight = p.edited(|e| e.aero.prebend_file.clear()).unwrap();
        assert!(!Arc::ptr_eq(
            p.aero_blade().unwrap(),
            straight.aero_blade().unwrap()
        ));
        let own = straight.aero_stations().unwrap().unwrap();
        assert!(!Arc::ptr_eq(&stations, &own));
    }
}
