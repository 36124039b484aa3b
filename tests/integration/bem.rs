//! Steady BEM (docs/model.md §12.2) against the reference turbines' published operating points,
//! the aerodynamic descriptions read from their files (§12.1), and the solver's convergence at
//! every station.

use flutterscope::formats::aerodyn::read_blade as read_aerodyn_blade;
use flutterscope::formats::hawc2_aero::{read_opt, read_pc};
use flutterscope::model::aero::rotor_of;
use flutterscope::model::operating::steady;
use flutterscope::physics::aero::blade_element::Unsteadiness;
use flutterscope::physics::rotor::bem::{solve, AeroStation, Conditions, Deflection, Rotor};
use flutterscope::physics::rotor::files::{read_aerodyn, read_hawc2};
use flutterscope::physics::rotor::induction::HighThrust;
use flutterscope::physics::rotor::AeroBlade;
use flutterscope::preset::BladeFile;
use flutterscope::preset::Preset;
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
        "Cylinder1",
        "Cylinder2",
        "DU40_A17",
        "DU35_A17",
        "DU30_A17",
        "DU25_A17",
        "DU21_A17",
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
        precone: 0.0,
        shaft_tilt: 0.0,
        high_thrust: HighThrust::Buhl,
    }
}

/// The three-bladed rotor of `blade` on a hub of `hub_radius` with `count` Gauss stations.
fn rig(blade: &AeroBlade, hub_radius: f64, count: usize) -> (Rotor, Vec<AeroStation>) {
    (
        rotor(blade, hub_radius),
        AeroStation::gauss(blade, count).unwrap(),
    )
}

/// Wind (m/s), rotor speed (rpm) and pitch (deg) at sea-level air density.
fn at(wind: f64, rpm: f64, pitch_deg: f64) -> Conditions {
    Conditions {
        wind_speed: wind,
        rotor_speed: rpm * std::f64::consts::PI / 30.0,
        pitch: pitch_deg.to_radians(),
        air_density: 1.225,
    }
}

/// One row of the IEA 15MW operation table: wind, setting, aerodynamic power (W), thrust (N).
struct OptRow {
    wind: f64,
    at: Conditions,
    power: f64,
    thrust: f64,
}

fn iea15mw_table(winds: &[f64]) -> Vec<OptRow> {
    let opt = read_opt(&blades().join("iea15mw/IEA_15MW_RWT_Onshore.opt")).unwrap();
    let power = opt.aero_power_kw.as_ref().unwrap();
    let thrust = opt.aero_thrust_kn.as_ref().unwrap();
    winds
        .iter()
        .map(|&wind| {
            let i = opt.wind_speed.iter().position(|&w| w == wind).unwrap();
            OptRow {
                wind,
                at: at(wind, opt.rotor_speed_rpm[i], opt.pitch_deg[i]),
                power: power[i] * 1e3,
                thrust: thrust[i] * 1e3,
            }
        })
        .collect()
}

const IEA_WINDS: [f64; 6] = [5.0, 7.0, 9.0, 10.0, 13.0, 17.0];

/// The rigid BEM against HAWCStab2's steady states of the flexible blade (docs/model.md §12.4).
/// The table's blade bends and twists toward feather under load; ours is rigid, so it carries
/// more thrust at every wind speed, and above rated it needs more pitch than the table for the
/// same power: the elastic twist of the table's blade. The rigid rotor's numbers and the effect
/// of a twist toward feather (linear from the root to the tip) are printed for the record.
#[test]
fn iea15mw_rigid_against_the_flexible_operation_table() {
    let blade = iea15mw();
    let (rotor, stations) = rig(&blade, 3.97, 30);
    let length = blade.span_range().1;
    for row in iea15mw_table(&IEA_WINDS) {
        let s = solve(&rotor, &stations, &[], &row.at).unwrap();
        eprintln!(
            "IEA 15MW {} m/s rigid: power {:.1} kW (table {:.1}, {:+.2} %), thrust {:.1} kN (table {:.1}, {:+.2} %)",
            row.wind,
            s.power / 1e3,
            row.power / 1e3,
            100.0 * (s.power / row.power - 1.0),
            s.thrust / 1e3,
            row.thrust / 1e3,
            100.0 * (s.thrust / row.thrust - 1.0)
        );
        for tip in [1.0, 2.0, 3.0] {
            let twist: Vec<Deflection> = stations
                .iter()
                .map(|st| Deflection {
                    twist: f64::to_radians(tip) * st.span / length,
                    flap: 0.0,
                })
                .collect();
            let t = solve(&rotor, &stations, &twist, &row.at).unwrap();
            eprintln!(
                "    tip twist {tip}° toward feather: power {:+.2} %, thrust {:+.2} %",
                100.0 * (t.power / row.power - 1.0),
                100.0 * (t.thrust / row.thrust - 1.0)
            );
        }
        assert!(
            s.thrust > row.thrust,
            "{} m/s: rigid thrust {} below the table's",
            row.wind,
            s.thrust
        );
        if row.wind > 11.0 {
            let pitch = flutterscope::numeric::root::brent(
                |p| {
                    let at = Conditions { pitch: p, ..row.at };
                    solve(&rotor, &stations, &[], &at).unwrap().power - row.power
                },
                row.at.pitch,
                row.at.pitch + 10f64.to_radians(),
                1e-8,
            )
            .unwrap();
            let extra = (pitch - row.at.pitch).to_degrees();
            eprintln!(
                "    pitch for the table's power: {:.3}° (table {:.3}°, {extra:+.3}°)",
                pitch.to_degrees(),
                row.at.pitch.to_degrees()
            );
            assert!((1.5..4.0).contains(&extra), "{} m/s: {extra}°", row.wind);
        }
    }
}

/// The deflected blade against the same table: the `iea15mw` preset's static aeroelastic
/// equilibrium (docs/model.md §12.6) at the table's pitch and rotor speed, with the rotor's cone
/// (4°), tilt (6°) and the blade's prebend (4 m upwind at the tip) and its elastic flap bending the
/// axis the BEM sees (§12.2), and HAWC2's thrust–induction relation (`aero.high_thrust =
/// "madsen"`). The blade bends downwind and twists toward feather under load, which brings power
/// and thrust toward the table's at every wind speed from 7 m/s up; at 5 m/s (λ = 12.7, C_T ≈
/// 0.94) the induction relation decides the power: Buhl's leaves it 12.8 % short. The 5 % bound
/// is met for power from 5 to 10 m/s and at 17 m/s, and for thrust at 5, 7 and 17 m/s; not for
/// thrust at 9 and 10 m/s nor at 13 m/s (README, validation table; docs/model.md §12.4 says why). Each bound is what is
/// achieved, rounded up: losing the cone, tilt, prebend (in the aerodynamics or the structure),
/// deflected geometry or the induction relation breaks one of them.
#[test]
fn iea15mw_deflected_against_the_operation_table() {
    let p = flutterscope::preset::Preset::load("iea15mw", &[]).unwrap();
    assert_eq!(p.aero.high_thrust, HighThrust::Madsen);
    let blade = iea15mw();
    let rotor = Rotor {
        high_thrust: HighThrust::Madsen,
        ..rotor(&blade, 3.97)
    };
    let stations = AeroStation::gauss(&blade, 30).unwrap();
    // Largest |power|, |thrust| difference from the table achieved at each wind speed.
    let bounds = [
        (5.0, 0.034, 0.042),
        (7.0, 0.002, 0.045),
        (9.0, 0.021, 0.076),
        (10.0, 0.032, 0.092),
        (13.0, 0.066, 0.073),
        (17.0, 0.042, 0.040),
    ];
    for (row, (wind, power_bound, thrust_bound)) in iea15mw_table(&IEA_WINDS).iter().zip(bounds) {
        assert_eq!(row.wind, wind);
        let at = p.with("operating.wind_speed", row.wind).unwrap();
        let (ran_at, op) = steady(&at, Unsteadiness::QuasiSteady).unwrap();
        let rigid = solve(&rotor, &stations, &[], &row.at).unwrap();
        let error = |x: f64, table: f64| x / table - 1.0;
        let (power, thrust) = (
            error(op.flow.power, row.power),
            error(op.flow.thrust, row.thrust),
        );
        let [twist, flap, edge] = op.tip();
        eprintln!(
            "IEA 15MW {} m/s deflected: power {:+.2} %, thrust {:+.2} %; tip twist {:.2}°, flap {:.2} m, edge {:.2} m ({} passes)",
            row.wind,
            100.0 * power,
            100.0 * thrust,
            twist.to_degrees(),
            flap,
            edge,
            op.passes
        );
        // The table's pitch and rotor speed were applied.
        assert!((ran_at.pitch_rad() - row.at.pitch).abs() < 1e-9);
        assert!((ran_at.omega() - row.at.rotor_speed).abs() < 1e-9);
        // Toward feather and downwind under load, and the thrust eased by it.
        assert!(twist > 0.0 && flap > 0.0, "{} m/s", row.wind);
        assert!(op.flow.thrust < rigid.thrust, "{} m/s", row.wind);
        if row.wind >= 7.0 {
            assert!(
                thrust.abs() < error(rigid.thrust, row.thrust).abs(),
                "{} m/s",
                row.wind
            );
            assert!(
                power.abs() < error(rigid.power, row.power).abs(),
                "{} m/s",
                row.wind
            );
        }
        assert!(
            power.abs() < power_bound && thrust.abs() < thrust_bound,
            "{} m/s: power {power}, thrust {thrust}",
            row.wind
        );
    }
    // The same equilibrium with Buhl's relation at 5 m/s: the power 12.8 % short of the table's.
    let buhl = Preset::load("iea15mw", &["aero.high_thrust=buhl".to_string()]).unwrap();
    let row = &iea15mw_table(&[5.0])[0];
    let (_, op) = steady(
        &buhl.with("operating.wind_speed", 5.0).unwrap(),
        Unsteadiness::QuasiSteady,
    )
    .unwrap();
    let power = op.flow.power / row.power - 1.0;
    assert!(
        (-0.1285..-0.1265).contains(&power),
        "Buhl at 5 m/s: {power}"
    );
}

/// Cone, tilt and prebend as CCBlade takes them (docs/model.md §12.2): a straight blade coned by
/// β sits at `r cos β` from the shaft and its elements see `U cos τ cos β` normal to them; a
/// prebend leaning the axis upwind by `k` per metre adds `atan k` to the cone; thrust and torque
/// follow the turned loads. And β = τ = 0 without prebend is the axial BEM.
#[test]
fn cone_tilt_and_prebend_turn_the_inflow() {
    let blade = nrel5mw();
    let (straight, mut stations) = rig(&blade, 1.5, 20);
    let at = at(8.0, 9.0, 0.0);
    let plain = solve(&straight, &stations, &[], &at).unwrap();
    let (beta, tau) = (f64::to_radians(5.0), f64::to_radians(6.0));
    let coned = Rotor {
        precone: beta,
        shaft_tilt: tau,
        ..straight
    };
    let c = solve(&coned, &stations, &[], &at).unwrap();
    for (f, s) in c.stations.iter().zip(&stations) {
        assert!((f.radius - (1.5 + s.span) * beta.cos()).abs() < 1e-9);
        let normal = f.axial_velocity / (1.0 - f.axial_induction);
        assert!(
            (normal - 8.0 * tau.cos() * beta.cos()).abs() < 1e-9,
            "{normal}"
        );
    }
    // Less wind through a smaller disc: less power and thrust, here by a few per cent.
    assert!(c.power < plain.power && c.thrust < plain.thrust);
    assert!(c.power > 0.9 * plain.power);
    // A prebend leaning 0.05 m per metre upwind: the cone grows by atan(0.05) everywhere.
    for s in &mut stations {
        s.prebend = -0.05 * s.span;
    }
    let bent = solve(&straight, &stations, &[], &at).unwrap();
    let kappa = 0.05f64.atan();
    for (f, s) in bent.stations.iter().zip(&stations) {
        let normal = f.axial_velocity / (1.0 - f.axial_induction);
        assert!((normal - 8.0 * kappa.cos()).abs() < 1e-9, "{normal}");
        assert!((f.radius - (1.5 + s.span)).abs() < 1e-12);
    }
    // The same offset as elastic flap (downwind) cones the other way by the same angle.
    for s in &mut stations {
        s.prebend = 0.0;
    }
    let flap: Vec<Deflection> = stations
        .iter()
        .map(|s| Deflection {
            twist: 0.0,
            flap: 0.05 * s.span,
        })
        .collect();
    let flapped = solve(&straight, &stations, &flap, &at).unwrap();
    assert!((flapped.power - bent.power).abs() < 1e-6 * bent.power);
}

/// The prebend comes from `aero.prebend_file`'s `BlCrvAC`: the IEA 15MW tip 4 m upwind; a file
/// that is not an AeroDyn 15 blade file is refused with the key and the file named.
#[test]
fn prebend_from_the_aerodyn_file() {
    let p = Preset::load("iea15mw", &[]).unwrap();
    let blade = p.aero_blade().unwrap();
    let tip = blade.prebend_at(blade.span_range().1);
    assert!((tip + 3.999).abs() < 1e-3, "{tip}");
    assert!(blade.prebend_at(0.0).abs() < 0.01);
    let nrel = Preset::load("nrel5mw", &[]).unwrap();
    assert!(nrel.aero_blade().unwrap().prebend.is_empty());
    let e = Preset::load(
        "presets/iea15mw.toml",
        &["aero.prebend_file=blades/iea15mw/IEA_15MW_RWT_ae.dat".into()],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("aero.prebend_file")
            && e.contains("IEA_15MW_RWT_ae.dat")
            && e.contains("NumBlNds"),
        "{e}"
    );
}

#[test]
fn nrel5mw_rated_power() {
    let (rotor, stations) = rig(&nrel5mw(), 1.5, 30);
    let s = solve(&rotor, &stations, &[], &at(11.4, 12.1, 0.0)).unwrap();
    eprintln!(
        "NREL 5MW 11.4 m/s 12.1 rpm: power {:.1} kW, thrust {:.1} kN",
        s.power / 1e3,
        s.thrust / 1e3
    );
    assert!((s.power / 5.30e6 - 1.0).abs() < 0.05, "{}", s.power);
    // With the preset's precone (2.5°) and shaft tilt (5°).
    let p = Preset::load("nrel5mw", &[]).unwrap();
    let turned = rotor_of(&p, p.aero_blade().unwrap());
    assert_eq!((p.operating.precone, p.operating.shaft_tilt), (2.5, 5.0));
    let c = solve(&turned, &stations, &[], &at(11.4, 12.1, 0.0)).unwrap();
    eprintln!(
        "NREL 5MW 11.4 m/s 12.1 rpm, coned and tilted: power {:.1} kW, thrust {:.1} kN",
        c.power / 1e3,
        c.thrust / 1e3
    );
    assert!((c.power / 5.30e6 - 1.0).abs() < 0.05, "{}", c.power);
    assert!(c.power < s.power);
}

/// The AeroDyn 15 file of the NREL 5MW states its aerodynamic-centre offsets from the pitch axis
/// (`BlCrvAC` out of plane, `BlSwpAC` in plane): the chordwise offset `(PitchAxis − ¼) c` turned
/// by the twist. Our mapping from ElastoDyn's `PitchAxis` must give the same distance.
#[test]
fn nrel5mw_centre_ahead_of_the_pitch_axis_matches_the_aerodyn_offsets() {
    let blade = nrel5mw();
    let file = read_aerodyn_blade(&blades().join("nrel5mw/NRELOffshrBsline5MW_AeroDyn_blade.dat"))
        .unwrap();
    let mut worst: f64 = 0.0;
    for (node, row) in blade.nodes.iter().zip(&file.nodes) {
        let stated = row.bl_crv_ac.hypot(row.bl_swp_ac);
        worst = worst.max((node.ac_ahead - stated).abs());
        if stated > 0.05 {
            // Turned by the twist: the offset lies along the chord.
            let angle = row.bl_crv_ac.atan2(row.bl_swp_ac).to_degrees();
            assert!(
                (angle.abs() - (180.0 - row.bl_twist_deg)).abs() < 0.5,
                "span {}: offset at {angle}°, twist {}°",
                row.bl_spn,
                row.bl_twist_deg
            );
        }
    }
    eprintln!("NREL 5MW ac_ahead against AeroDyn's AC offsets: worst {worst:.2e} m");
    assert!(worst < 5e-3, "{worst}");
    // Root: PitchAxis 0.25, the centre on the axis; outboard 0.375: an eighth of the chord ahead.
    assert!(blade.nodes[0].ac_ahead.abs() < 1e-12);
    let tip = blade.nodes.last().unwrap();
    assert!((tip.ac_ahead - 0.125 * tip.chord).abs() < 1e-9);
    // Airfoil ids name aero.airfoils in order: the tip node (BlAFID 8) has NACA64's table.
    let c = tip.polar.at(-175f64.to_radians());
    assert!(
        (c.cl - 0.374).abs() < 1e-12 && (c.cd - 0.0341).abs() < 1e-12,
        "{c:?}"
    );
}

/// HAWC2: the centre a quarter chord ahead of the half-chord line, the twist from the AeroDyn
/// file, the polar linear in thickness between the two profiles that bracket the row's.
#[test]
fn iea15mw_hawc2_mapping() {
    let blade = iea15mw();
    for n in &blade.nodes {
        assert!((n.ac_ahead - 0.25 * n.chord).abs() < 1e-12);
    }
    assert!((blade.nodes[0].twist.to_degrees() - 15.594553).abs() < 1e-5);
    // Row 6: r = 24.96 m, 38.979 % thick, between the 36 % and 50 % profiles.
    let row = &blade.nodes[5];
    assert!((row.span - 24.96082665886324).abs() < 1e-9);
    let pc = read_pc(&blades().join("iea15mw/IEA_15MW_RWT_pc.dat")).unwrap();
    let set = &pc.sets[0];
    let (lo, hi) = (&set.profiles[5], &set.profiles[6]);
    assert_eq!((lo.thickness_pct, hi.thickness_pct), (36.0, 50.0));
    let w = (38.979_281_818_282_5 - 36.0) / 14.0;
    let lin = |alpha: &[f64], v: &[f64], a: f64| {
        let k = alpha.partition_point(|&x| x <= a);
        let t = (a - alpha[k - 1]) / (alpha[k] - alpha[k - 1]);
        v[k - 1] + t * (v[k] - v[k - 1])
    };
    for a in [-10.0, 0.0, 5.0, 12.0, 40.0] {
        let expected =
            (1.0 - w) * lin(&lo.alpha_deg, &lo.cl, a) + w * lin(&hi.alpha_deg, &hi.cl, a);
        let got = row.polar.at(f64::to_radians(a)).cl;
        assert!((got - expected).abs() < 1e-9, "α {a}: {got} vs {expected}");
    }
    // Outboard rows of one thickness share one polar.
    let n = blade.nodes.len();
    assert!(std::sync::Arc::ptr_eq(
        &blade.nodes[n - 1].polar,
        &blade.nodes[n - 2].polar
    ));
}

/// Every station converges over the whole operating envelope and beyond it: parked (Ω = 0),
/// idling, deep stall (low rotor speed in strong wind), feathered, and negative pitch; under both
/// thrust–induction relations (docs/model.md §12.2).
#[test]
fn bem_converges_at_every_station_parked_and_stalled() {
    let relations = [HighThrust::Buhl, HighThrust::Madsen];
    for (blade, hub, high_thrust) in [(nrel5mw(), 1.5), (iea15mw(), 3.97)]
        .into_iter()
        .flat_map(|(b, h)| relations.map(|r| (b.clone(), h, r)))
    {
        let (rotor, stations) = rig(&blade, hub, 30);
        let rotor = Rotor {
            high_thrust,
            ..rotor
        };
        let mut stalled = 0;
        let mut points = 0;
        for wind in [0.0, 3.0, 8.0, 15.0, 25.0, 50.0] {
            for rpm in [0.0, 1.0, 5.0, 12.0, 20.0] {
                for pitch in [-10.0, 0.0, 10.0, 45.0, 90.0] {
                    let at = at(wind, rpm, pitch);
                    let s = solve(&rotor, &stations, &[], &at).unwrap_or_else(|e| {
                        panic!(
                            "{} ({}) at {wind} m/s, {rpm} rpm, {pitch}°: {e}",
                            blade.origin,
                            high_thrust.name()
                        )
                    });
                    points += 1;
                    assert!(s.power.is_finite() && s.thrust.is_finite());
                    for f in &s.stations {
                        assert!(f.inflow_angle.is_finite() && f.axial_induction.is_finite());
                        if f.angle_of_attack > 20f64.to_radians()
                            && f.span > 0.3 * blade.span_range().1
                        {
                            stalled += 1;
                        }
                    }
                    if rpm == 0.0 && wind > 0.0 {
                        // Parked: the undisturbed flow, square to the rotor plane.
                        for f in &s.stations {
                            assert_eq!(f.axial_induction, 0.0);
                            assert!((f.inflow_angle - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
                        }
                        assert_eq!(s.power, 0.0);
                    }
                }
            }
        }
        assert!(
            stalled > 100,
            "{}: only {stalled} stalled outboard stations",
            blade.origin
        );
        assert_eq!(points, 150);
    }
}

/// The converged flow satisfies the momentum balance it was solved from: where momentum theory
/// holds (a < 0.4), the element's thrust per span equals the annulus' momentum flux
/// `4π r ρ U² a (1 − a) F` and its torque `4π r³ ρ U Ω a' (1 − a) F`.
#[test]
fn converged_elements_balance_momentum() {
    let (rotor, stations) = rig(&iea15mw(), 3.97, 30);
    let at = at(8.0, 5.6819, 0.0);
    let s = solve(&rotor, &stations, &[], &at).unwrap();
    let mut checked = 0;
    for f in s
        .stations
        .iter()
        .filter(|f| f.axial_induction > 0.01 && f.axial_induction < 0.4)
    {
        let (r, a, ap, big_f) = (
            f.radius,
            f.axial_induction,
            f.tangential_induction,
            f.loss_factor,
        );
        let rho_u = at.air_density * at.wind_speed;
        let thrust = 4.0 * std::f64::consts::PI * r * rho_u * at.wind_speed * a * (1.0 - a) * big_f;
        let torque = 4.0
            * std::f64::consts::PI
            * r.powi(3)
            * rho_u
            * at.rotor_speed
            * ap
            * (1.0 - a)
            * big_f;
        assert!(
            (3.0 * f.out_of_plane_load / thrust - 1.0).abs() < 1e-6,
            "r {r}"
        );
        assert!(
            (3.0 * f.in_plane_load * r / torque - 1.0).abs() < 1e-6,
            "r {r}"
        );
        checked += 1;
    }
    assert!(checked > 15, "{checked}");
}

/// The extra twist (elastic, toward feather) lowers every station's angle of attack by itself.
#[test]
fn extra_twist_lowers_the_angle_of_attack() {
    let (rotor, stations) = rig(&nrel5mw(), 1.5, 12);
    let at = at(0.0, 11.46, 0.0);
    let twist: Vec<Deflection> = (0..12)
        .map(|i| Deflection {
            twist: 0.01 * i as f64,
            flap: 0.0,
        })
        .collect();
    let plain = solve(&rotor, &stations, &[], &at).unwrap();
    let turned = solve(&rotor, &stations, &twist, &at).unwrap();
    for ((a, b), t) in plain.stations.iter().zip(&turned.stations).zip(&twist) {
        assert!((a.angle_of_attack - t.twist - b.angle_of_attack).abs() < 1e-12);
    }
    assert!(solve(&rotor, &stations, &twist[..3], &at).is_err());
}

fn load(toml: &str) -> Result<flutterscope::preset::ValidPreset, String> {
    Preset::from_toml(toml, "test.toml", &[]).map_err(|e| e.to_string())
}

const NREL_AERO: &str = r#"
[blade]
source = "beamdyn"
file = "presets/blades/nrel5mw/NRELOffshrBsline5MW_BeamDyn.dat"
hub_radius = 1.5
[aero]
model = "none"
blade_file = "presets/blades/nrel5mw/NRELOffshrBsline5MW_AeroDyn_blade.dat"
pitch_axis_file = "presets/blades/nrel5mw/NRELOffshrBsline5MW_Blade.dat"
"#;

/// Incomplete, mixed or mismatched aerodynamic keys, and broken files, are refused with the
/// keys (and the file and what was wrong) named.
#[test]
fn hostile_aerodynamic_keys_and_files_are_named() {
    let e = load(NREL_AERO).unwrap_err();
    assert!(
        e.contains("aero.airfoils") && e.contains("0") && e.contains("test.toml"),
        "{e}"
    );
    let two = NREL_AERO.replace(
        "[aero]",
        r#"[aero]
airfoils = ["presets/blades/nrel5mw/Airfoils/Cylinder1.dat", "presets/blades/nrel5mw/Airfoils/Cylinder2.dat"]"#,
    );
    let e = load(&two).unwrap_err();
    assert!(
        e.contains("BlAFID = 3")
            && e.contains("2 file(s)")
            && e.contains("NRELOffshrBsline5MW_AeroDyn_blade.dat"),
        "{e}"
    );
    let wrong_axis = two.replace(
        "NRELOffshrBsline5MW_Blade.dat",
        "NRELOffshrBsline5MW_BeamDyn.dat",
    );
    let e = load(&wrong_axis).unwrap_err();
    assert!(
        e.contains("aero.pitch_axis_file") && e.contains("NRELOffshrBsline5MW_BeamDyn.dat"),
        "{e}"
    );
    let mixed = NREL_AERO.replace("[aero]", "[aero]\nae_file = 'x'\npc_file = 'y'");
    assert!(load(&mixed).unwrap_err().contains("give one set"));
    let hawc2_on_beamdyn = r#"
[blade]
source = "beamdyn"
file = "presets/blades/nrel5mw/NRELOffshrBsline5MW_BeamDyn.dat"
[aero]
model = "none"
ae_file = "presets/blades/iea15mw/IEA_15MW_RWT_ae.dat"
pc_file = "presets/blades/iea15mw/IEA_15MW_RWT_pc.dat"
"#;
    assert!(load(hawc2_on_beamdyn)
        .unwrap_err()
        .contains("half-chord line"));
    let e = Preset::load("iea15mw", &["aero.high_thrust=glauert".into()])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("high_thrust") && e.contains("glauert") && e.contains("madsen"),
        "{e}"
    );
    let e = Preset::load("iea15mw", &["aero.ae_set=2".into()])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("aero.ae_set = 2") && e.contains("1 ae set(s)"),
        "{e}"
    );
    // The law sets the operation table's file aside; what the law itself needs is missing.
    let e = Preset::load("iea15mw", &["operating.schedule=law".into()])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("operating.schedule = \"law\" needs operating.rated_power"),
        "{e}"
    );
    let e = Preset::load("nrel5mw", &["operating.rotor_speed_min=13".into()])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("operating.rotor_speed_min = 13") && e.contains("operating.rotor_speed_max"),
        "{e}"
    );
    let e = Preset::load("iea15mw", &["operating.wind_speed=30".into()])
        .and_then(|p| flutterscope::model::operating::on_schedule(&p))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("outside the operating table") && e.contains("25"),
        "{e}"
    );
}

/// A thickness outside the pc set's profiles is refused, not extrapolated.
#[test]
fn thickness_outside_the_pc_set_is_refused() {
    use flutterscope::formats::hawc2_aero::{parse_ae, parse_pc};
    use flutterscope::physics::blade::hawc2::ChordTwist;
    use flutterscope::physics::rotor::files::from_hawc2;
    let ae = parse_ae("1\n1 2\n0 1 15 1\n10 1 20 1\n", "a.ae").unwrap();
    let pc = parse_pc(
        "1\n1\n1 3 18 x\n-10 -1 0.01 0\n0 0.2 0.01 0\n10 1.2 0.02 0\n",
        "p.pc",
    )
    .unwrap();
    let e = from_hawc2(&ae, "a.ae", 1, &pc, "p.pc", &ChordTwist::untwisted()).unwrap_err();
    let e = e.to_string();
    assert!(
        e.contains("a.ae") && e.contains("row 1") && e.contains("15 %"),
        "{e}"
    );
}

/// `flutterscope operating --json` of `preset` with `sets`, as JSON (the run must succeed).
fn operating_json(preset: &str, sets: &[String], vary: Option<&str>) -> serde_json::Value {
    let mut cmd = assert_cmd::Command::cargo_bin("flutterscope").unwrap();
    cmd.args(["operating", "--preset", preset, "--json"]);
    for s in sets {
        cmd.args(["--set", s]);
    }
    if let Some(v) = vary {
        cmd.args(["--vary", v]);
    }
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The IEA 15MW preset on a control law instead of its table: the table's rotor speeds
/// (5–7.56 rpm, tip speed ratio 9), `rated_power` the table's aerodynamic power above rated.
fn iea15mw_law(rated_power: f64) -> Vec<String> {
    [
        "operating.schedule=law".to_string(),
        "operating.schedule_file=".into(),
        format!("operating.rated_power={rated_power}"),
        "operating.tip_speed_ratio=9".into(),
        "operating.rotor_speed_min=5".into(),
        "operating.rotor_speed_max=7.559987".into(),
    ]
    .to_vec()
}

/// Largest |power / rated − 1| along `operating --vary operating.wind_speed=…` of `preset`.
fn power_curve_departure(preset: &str, sets: &[String], winds: &str, rated: f64) -> f64 {
    let json = operating_json(preset, sets, Some(&format!("operating.wind_speed={winds}")));
    let points = json["points"].as_array().unwrap();
    assert!(!points.is_empty());
    points
        .iter()
        .map(|p| {
            let power = p["power_w"].as_f64().unwrap();
            let pitch = p["pitch_deg"].as_f64().unwrap();
            assert!(pitch > 0.0, "{preset}: above rated at zero pitch: {p}");
            (power / rated - 1.0).abs()
        })
        .fold(0.0, f64::max)
}

/// Above rated the control law holds `operating.rated_power` on the blade the user sees: the
/// pitch is the one the deflected blade (static aeroelastic equilibrium, docs/model.md §12.3,
/// §12.6) needs, so the power curve is flat from rated to cut-out. Found on the rigid blade, the
/// pitch let the blade's twist toward feather take the power down to 3.76 MW at 20 m/s on the
/// NREL 5MW (5.296 MW rated) and 2.77 MW at 25 m/s on the IEA 15MW (15.665 MW). On both
/// real-blade presets and on a user's own preset file naming the shipped blade files.
#[test]
fn the_law_holds_rated_power_on_the_deflected_blade_to_cut_out() {
    let nrel = power_curve_departure("nrel5mw", &[], "12:25:1", 5.296e6);
    assert!(
        nrel < 0.005,
        "nrel5mw: power {:.3} % off rated",
        100.0 * nrel
    );
    let iea = power_curve_departure("iea15mw", &iea15mw_law(15.665e6), "12:25:1", 15.665e6);
    assert!(iea < 0.005, "iea15mw: power {:.3} % off rated", 100.0 * iea);
    // A user's preset in a directory of its own, naming the shipped files by absolute path.
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
    let text = std::fs::read_to_string(shipped.join("nrel5mw.toml"))
        .unwrap()
        .replace("\"blades/", &format!("\"{}/blades/", shipped.display()))
        .replace("name = \"nrel5mw\"", "name = \"my-turbine\"");
    let dir = std::env::temp_dir().join(format!("flutterscope-law-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("my-turbine.toml");
    std::fs::write(&file, text).unwrap();
    let own = power_curve_departure(file.to_str().unwrap(), &[], "13:25:4", 5.296e6);
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(
        own < 0.005,
        "own preset: power {:.3} % off rated",
        100.0 * own
    );
}

/// Above rated the power at a fixed pitch is ill conditioned (0.5° of twist moves it by 6 %), so
/// the IEA 15MW is compared with its HAWCStab2 table as the field compares: on the control law
/// with `rated_power` the table's aerodynamic power at each wind speed, the pitch our deflected
/// blade needs for it against the table's pitch, and the thrust at that pitch against the
/// table's (README, validation; docs/model.md §12.4). Below rated the comparison at the table's
/// setting stands (`iea15mw_deflected_against_the_operation_table`).
#[test]
fn iea15mw_law_pitch_and_thrust_against_the_operation_table() {
    let opt = read_opt(&blades().join("iea15mw/IEA_15MW_RWT_Onshore.opt")).unwrap();
    let (power, thrust) = (
        opt.aero_power_kw.as_ref().unwrap(),
        opt.aero_thrust_kn.as_ref().unwrap(),
    );
    for wind in [13.0, 15.0, 17.0, 21.0, 25.0] {
        let i = opt.wind_speed.iter().position(|&w| w == wind).unwrap();
        let mut sets = iea15mw_law(power[i] * 1e3);
        sets.push(format!("operating.wind_speed={wind}"));
        let json = operating_json("iea15mw", &sets, None);
        let pitch = json["pitch_deg"].as_f64().unwrap() - opt.pitch_deg[i];
        let ours = json["thrust_n"].as_f64().unwrap();
        let thrust_error = ours / (thrust[i] * 1e3) - 1.0;
        eprintln!(
            "IEA 15MW {wind} m/s on the law at the table's power: pitch {:.3}° (table {:.3}°, \
             {pitch:+.3}°), thrust {:.1} kN (table {:.1} kN, {:+.2} %)",
            pitch + opt.pitch_deg[i],
            opt.pitch_deg[i],
            ours / 1e3,
            thrust[i],
            100.0 * thrust_error
        );
        assert!(
            (json["power_w"].as_f64().unwrap() / (power[i] * 1e3) - 1.0).abs() < 1e-5,
            "{wind} m/s: {json}"
        );
        assert!(
            pitch.abs() < 0.5,
            "{wind} m/s: pitch {pitch:+.3}° off the table's"
        );
        assert!(
            thrust_error.abs() < 0.05,
            "{wind} m/s: thrust {:+.2} %",
            100.0 * thrust_error
        );
    }
}
