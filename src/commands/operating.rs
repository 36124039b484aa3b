//! `flutterscope operating`: the steady operating point of a preset's rotor (docs/model.md
//! §12): power, thrust, torque, tip speed ratio and the flow at every station (text, JSON, or
//! the stations as CSV); with `--vary KEY=A:B:STEP` (e.g. `operating.wind_speed`, along the
//! preset's schedule) the power and thrust curves (CSV, JSON, `--plot`).

use crate::commands::{parse_vary, print_json, print_text};
use crate::error::{Error, Result};
use crate::model::operating::deflected_point;
use crate::physics::rotor::steady::SteadyPoint;
use crate::preset::ValidPreset;
use rayon::prelude::*;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

/// Totals of one point as the reports name them (SI, angles in degrees).
#[derive(Serialize)]
struct Totals {
    wind_speed: f64,
    rotor_speed_rpm: f64,
    pitch_deg: f64,
    tip_speed_ratio: f64,
    power_w: f64,
    thrust_n: f64,
    torque_nm: f64,
    /// The tip's elastic deflection at the static aeroelastic equilibrium: twist toward feather,
    /// flap downwind, edge toward the leading edge.
    tip_twist_deg: f64,
    tip_flap_m: f64,
    tip_edge_m: f64,
}

impl Totals {
    fn of((s, [twist, flap, edge]): &(SteadyPoint, [f64; 3])) -> Totals {
        Totals {
            wind_speed: s.wind_speed,
            rotor_speed_rpm: s.rotor_speed_rpm,
            pitch_deg: s.pitch_deg,
            tip_speed_ratio: s.state.tip_speed_ratio,
            power_w: s.state.power,
            thrust_n: s.state.thrust,
            torque_nm: s.state.torque,
            tip_twist_deg: twist.to_degrees(),
            tip_flap_m: *flap,
            tip_edge_m: *edge,
        }
    }
}

/// One station's flow as the reports name it.
#[derive(Serialize)]
struct StationRow {
    span_m: f64,
    radius_m: f64,
    inflow_angle_deg: f64,
    angle_of_attack_deg: f64,
    axial_induction: f64,
    tangential_induction: f64,
    loss_factor: f64,
    relative_speed: f64,
    cl: f64,
    cd: f64,
    cm: f64,
    out_of_plane_load_n_per_m: f64,
    in_plane_load_n_per_m: f64,
}

fn station_rows(s: &SteadyPoint) -> Vec<StationRow> {
    s.state
        .stations
        .iter()
        .map(|f| StationRow {
            span_m: f.span,
            radius_m: f.radius,
            inflow_angle_deg: f.inflow_angle.to_degrees(),
            angle_of_attack_deg: f.angle_of_attack.to_degrees(),
            axial_induction: f.axial_induction,
            tangential_induction: f.tangential_induction,
            loss_factor: f.loss_factor,
            relative_speed: f.relative_speed,
            cl: f.cl,
            cd: f.cd,
            cm: f.cm,
            out_of_plane_load_n_per_m: f.out_of_plane_load,
            in_plane_load_n_per_m: f.in_plane_load,
        })
        .collect()
}

#[derive(Serialize)]
struct PointReport<'a> {
    preset: &'a str,
    schedule: &'static str,
    #[serde(flatten)]
    totals: Totals,
    stations: Vec<StationRow>,
}

pub fn run(
    p: &ValidPreset,
    vary: Option<&str>,
    json: bool,
    csv: bool,
    plot: Option<&Path>,
) -> Result<()> {
    if let Some(path) = plot {
        crate::plot::format_for(path)?;
        if vary.is_none() {
            return Err(Error::usage(
                "operating --plot draws the power and thrust curves: add --vary KEY=A:B:STEP, \
                 e.g. operating.wind_speed=3:25:1",
            ));
        }
    }
    match vary {
        None => one_point(p, json, csv),
        Some(spec) => curve(p, spec, json, plot),
    }
}

fn one_point(p: &ValidPreset, json: bool, csv: bool) -> Result<()> {
    let point = deflected_point(p)?;
    if json {
        return print_json(&PointReport {
            preset: p.display_name(),
            schedule: p.operating.schedule.name(),
            totals: Totals::of(&point),
            stations: station_rows(&point.0),
        });
    }
    if csv {
        return print_text(&stations_csv(&point.0));
    }
    print_text(&point_text(p, &point))
}

const STATION_COLUMNS: &str = "span_m,radius_m,inflow_angle_deg,angle_of_attack_deg,\
axial_induction,tangential_induction,loss_factor,relative_speed,cl,cd,cm,\
out_of_plane_load_n_per_m,in_plane_load_n_per_m";

fn stations_csv(s: &SteadyPoint) -> String {
    let mut out = format!("{STATION_COLUMNS}\n");
    for r in station_rows(s) {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{},{},{},{},{}",
            r.span_m,
            r.radius_m,
            r.inflow_angle_deg,
            r.angle_of_attack_deg,
            r.axial_induction,
            r.tangential_induction,
            r.loss_factor,
            r.relative_speed,
            r.cl,
            r.cd,
            r.cm,
            r.out_of_plane_load_n_per_m,
            r.in_plane_load_n_per_m
        );
    }
    out
}

fn point_text(p: &ValidPreset, (s, [twist, flap, edge]): &(SteadyPoint, [f64; 3])) -> String {
    let t = &s.state;
    let mut out = format!(
        "Steady operating point — {} (operating.schedule = {}; deflected blade, static \
         aeroelastic equilibrium)\n\
         wind {:.3} m/s, rotor speed {:.4} rpm, pitch {:.4}°, tip speed ratio {:.4}\n\
         power {:.1} kW, thrust {:.1} kN, torque {:.1} kN·m\n\
         tip deflection: flap {:.3} m downwind, edge {:.3} m, twist {:.3}° toward feather\n\n",
        p.display_name(),
        p.operating.schedule.name(),
        s.wind_speed,
        s.rotor_speed_rpm,
        s.pitch_deg,
        t.tip_speed_ratio,
        t.power / 1e3,
        t.thrust / 1e3,
        t.torque / 1e3,
        flap,
        edge,
        twist.to_degrees()
    );
    out.push_str(
        "  span (m)  r (m)   φ (°)    α (°)     a       a'      F     W (m/s)   Cl      Cd    \
         Fn (N/m)   Ft (N/m)\n",
    );
    for f in &t.stations {
        let _ = writeln!(
            out,
            "{:9.3} {:7.3} {:7.3} {:8.3} {:7.4} {:7.4} {:6.3} {:8.3} {:6.3} {:7.4} {:10.1} {:10.1}",
            f.span,
            f.radius,
            f.inflow_angle.to_degrees(),
            f.angle_of_attack.to_degrees(),
            f.axial_induction,
            f.tangential_induction,
            f.loss_factor,
            f.relative_speed,
            f.cl,
            f.cd,
            f.out_of_plane_load,
            f.in_plane_load
        );
    }
    out
}

/// The operating points over the grid of one key, in parallel, in grid order.
fn curve(p: &ValidPreset, spec: &str, json: bool, plot: Option<&Path>) -> Result<()> {
    let (key, values) = parse_vary(spec)?;
    // Every input error before the first line of output.
    for &v in [values.first(), values.last()].into_iter().flatten() {
        p.with(&key, v)?;
    }
    let points: Vec<(SteadyPoint, [f64; 3])> = values
        .par_iter()
        .map(|&v| p.with(&key, v).and_then(|q| deflected_point(&q)))
        .collect::<Result<_>>()?;
    if json {
        print_json(&serde_json::json!({
            "preset": p.display_name(),
            "schedule": p.operating.schedule.name(),
            "parameter": key,
            "values": values,
            "points": points.iter().map(Totals::of).collect::<Vec<_>>(),
        }))?;
    } else {
        let mut out = format!(
            "{key},wind_speed,rotor_speed_rpm,pitch_deg,tip_speed_ratio,power_w,thrust_n,\
             torque_nm,tip_twist_deg,tip_flap_m,tip_edge_m\n"
        );
        for (v, s) in values.iter().zip(&points) {
            let t = Totals::of(s);
            let _ = writeln!(
                out,
                "{v},{},{},{},{},{},{},{},{},{},{}",
                t.wind_speed,
                t.rotor_speed_rpm,
                t.pitch_deg,
                t.tip_speed_ratio,
                t.power_w,
                t.thrust_n,
                t.torque_nm,
                t.tip_twist_deg,
                t.tip_flap_m,
                t.tip_edge_m
            );
        }
        print_text(&out)?;
    }
    if let Some(path) = plot {
        let power: Vec<f64> = points.iter().map(|(s, _)| s.state.power).collect();
        let thrust: Vec<f64> = points.iter().map(|(s, _)| s.state.thrust).collect();
        let fig = crate::plot::from_results::power_curve(
            p.display_name(),
            &key,
            &values,
            &power,
            &thrust,
        );
        crate::plot::write(&fig, path)?;
        eprintln!("plot written to {}", path.display());
    }
    Ok(())
}
