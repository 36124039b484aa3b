//! Steady BEM (docs/model.md §12.2) against the reference turbines' published operating points,
//! the aerodynamic descriptions read from their files (§12.1), and the solver's convergence at
//! every station.

use flutterscope::formats::hawc2_aero::read_opt;
use flutterscope::physics::rotor::bem::{solve, Conditions, Rotor, Station};
use flutterscope::physics::rotor::files::{read_aerodyn, read_hawc2};
use flutterscope::physics::rotor::AeroBlade;
use flutterscope::preset::BladeFile;
use std::path::{Path, PathBuf};

fn blades() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/blades")
}

fn disk(rel: &str) -> BladeFile {
    BladeFile::Disk(blades().join(rel))
}

pub fn iea15mw() -> AeroBlade {
    read_hawc2(
        &disk("iea15mw/IEA_15MW_RWT_ae.dat"),
        1,
        &disk("iea15mw/IEA_15MW_RWT_pc.dat"),
        &disk("iea15mw/IEA-15-240-RWT_AeroDyn15_blade.dat"),
    )
    .unwrap()
}

pub fn nrel5mw() -> AeroBlade {
    let airfoils = [
        "Cylinder1", "Cylinder2", "DU40_A17", "DU35_A17", "DU30_A17", "DU25_A17", "DU21_A17",
        "NACA64_A17",
    ]
    .map(|n| disk(&format!("nrel5mw/Airfoils/{n}.dat")));
    read_aerodyn(
        &disk("nrel5mw/NRELOffshrBsline5MW_AeroDyn_blade.dat"),
        &airfoils,
        &disk("nrel5mw/NRELOffshrBsline5MW_Blade.dat"),
    )
    .unwrap()
}

fn rotor(blade: &AeroBlade, hub_radius: f64) -> Rotor {
    Rotor {
        blades: 3,
        hub_radius,
        tip_radius: hub_radius + blade.span_range().1,
    }
}

#[test]
fn iea15mw_against_its_operation_table() {
    let blade = iea15mw();
    let rotor = rotor(&blade, 3.97);
    let stations = Station::gauss(&blade, 30).unwrap();
    let opt = read_opt(&blades().join("iea15mw/IEA_15MW_RWT_Onshore.opt")).unwrap();
    let power = opt.aero_power_kw.as_ref().unwrap();
    let thrust = opt.aero_thrust_kn.as_ref().unwrap();
    let mut misses = Vec::new();
    for wind in [5.0, 7.0, 9.0, 10.0, 13.0, 17.0] {
        let i = opt.wind_speed.iter().position(|&w| w == wind).unwrap();
        let at = Conditions {
            wind_speed: wind,
            rotor_speed: opt.rotor_speed_rpm[i] * std::f64::consts::PI / 30.0,
            pitch: opt.pitch_deg[i].to_radians(),
            air_density: 1.225,
        };
        let s = solve(&rotor, &stations, &[], &at).unwrap();
        let dp = s.power / (power[i] * 1e3) - 1.0;
        let dt = s.thrust / (thrust[i] * 1e3) - 1.0;
        eprintln!(
            "IEA 15MW {wind} m/s: power {:.1} kW (opt {:.1}, {:+.2} %), thrust {:.1} kN (opt {:.1}, {:+.2} %)",
            s.power / 1e3,
            power[i],
            100.0 * dp,
            s.thrust / 1e3,
            thrust[i],
            100.0 * dt
        );
        if std::env::var("BEM_DEBUG").is_ok() {
            for f in &s.stations {
                eprintln!(
                    "  r {:7.2} phi {:6.2} aoa {:6.2} a {:.3} a' {:.4} F {:.3} cl {:.3} cd {:.4}",
                    f.radius,
                    f.inflow_angle.to_degrees(),
                    f.angle_of_attack.to_degrees(),
                    f.axial_induction,
                    f.tangential_induction,
                    f.loss_factor,
                    f.cl,
                    f.cd
                );
            }
        }
        if dp.abs() >= 0.05 || dt.abs() >= 0.05 {
            misses.push((wind, dp, dt));
        }
    }
    assert!(misses.is_empty(), "beyond 5 %: {misses:?}");
}

#[test]
fn nrel5mw_rated_power() {
    let blade = nrel5mw();
    let rotor = rotor(&blade, 1.5);
    let stations = Station::gauss(&blade, 30).unwrap();
    let at = Conditions {
        wind_speed: 11.4,
        rotor_speed: 12.1 * std::f64::consts::PI / 30.0,
        pitch: 0.0,
        air_density: 1.225,
    };
    let s = solve(&rotor, &stations, &[], &at).unwrap();
    eprintln!(
        "NREL 5MW 11.4 m/s 12.1 rpm: power {:.1} kW, thrust {:.1} kN",
        s.power / 1e3,
        s.thrust / 1e3
    );
    assert!((s.power / 5.30e6 - 1.0).abs() < 0.05, "{}", s.power);
}
