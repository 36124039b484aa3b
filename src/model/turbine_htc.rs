//! A HAWC2 model's turbine (`turbine.source = "hawc2"`, docs/model.md §13.7): its htc's
//! bodies placed as its `orientation` block places them, read into the plain inputs of
//! [`crate::physics::turbine`]: the tower body as a beam ([`Tower::from_beam`]), the bodies
//! between it and the shaft's bearing as one rigid nacelle with their concentrated masses, the
//! shaft's torsion as the drivetrain's spring, its end masses' inertia about it as the
//! generator's (first node) and the hub's (last node), and a blade for every body the shaft
//! carries.

use crate::error::{Error, Result};
use crate::formats::hawc2_st::{StFile, StRows};
use crate::formats::htc::{C2Section, TimoshenkoInput};
use crate::formats::htc_turbine::{HtcTurbine, NodeRef, TurbineBody};
use crate::physics::blade::hawc2::{from_hawc2_st, ChordTwist};
use crate::physics::blade::modal::StiffnessFactors;
use crate::physics::blade::source::{htc_damping, SourceDamping};
use crate::physics::turbine::drivetrain::{Drivetrain, Generator};
use crate::physics::turbine::tower::{Tower, TowerTop};
use crate::physics::turbine::tower_beam::{BeamTowerInputs, TOWER_ELEMENTS};
use crate::physics::turbine::Support;
use nalgebra::{Matrix3, Vector3};

/// What a HAWC2 model gives the rotor and the turbine.
#[derive(Debug, Clone, PartialEq)]
pub struct Hawc2Turbine {
    /// Bodies on the shaft's last node (the hubs).
    pub blades: usize,
    /// The generator as the preset sets it later.
    pub drivetrain: Drivetrain,
    /// Read only for `turbine.model = "turbine"`.
    pub support: Option<Support>,
    /// The shaft's tilt and the hubs' cone (deg), as the orientations give them: not modelled
    /// (docs/model.md §13.6), reported.
    pub tilt_deg: f64,
}

/// A body's frame in HAWC2's global axes (x lateral, y downwind, z down): where its `c2_def`'s
/// origin is and how it is turned.
#[derive(Debug, Clone, Copy)]
struct Frame {
    origin: Vector3<f64>,
    turn: Matrix3<f64>,
}

impl Frame {
    fn node(&self, body: &TurbineBody, node: NodeRef) -> Vector3<f64> {
        self.origin + self.turn * c2_point(&body.c2_def[node_index(body, node)])
    }
}

fn node_index(body: &TurbineBody, node: NodeRef) -> usize {
    match node {
        NodeRef::Last => body.c2_def.len() - 1,
        NodeRef::Number(n) => (n - 1).min(body.c2_def.len() - 1),
    }
}

fn c2_point(s: &C2Section) -> Vector3<f64> {
    Vector3::new(s.x, s.y, s.z)
}

/// HAWC2's `eulerang`s in order: each turns the frame about its own x, then y, then z (deg).
fn turned(mut turn: Matrix3<f64>, angles: &[[f64; 3]]) -> Matrix3<f64> {
    for [x, y, z] in angles {
        let axis = |v: Vector3<f64>, deg: f64| {
            *nalgebra::Rotation3::from_axis_angle(
                &nalgebra::Unit::new_normalize(v),
                deg.to_radians(),
            )
            .matrix()
        };
        turn = turn * axis(Vector3::x(), *x) * axis(Vector3::y(), *y) * axis(Vector3::z(), *z);
    }
    turn
}

/// HAWC2's global axes in the tower's (x downwind, y lateral, z up).
fn ours(v: Vector3<f64>) -> Vector3<f64> {
    Vector3::new(v.y, v.x, -v.z)
}

fn ours_tensor(t: Matrix3<f64>) -> Matrix3<f64> {
    let p = Matrix3::new(0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0);
    p * t * p.transpose()
}

/// The turbine `htc` describes; its st files through `st` (a body's `timoschenko_input`);
/// the tower only `with_tower`.
pub fn hawc2_turbine(
    htc: &HtcTurbine,
    st: &mut dyn FnMut(&TimoshenkoInput) -> Result<StFile>,
    with_tower: bool,
) -> Result<Hawc2Turbine> {
    let frames = frames(htc)?;
    let frame = |name: &str| frames.iter().find(|f| f.0 == name).map(|f| f.1);
    let body = |name: &str| {
        htc.body(name)
            .ok_or_else(|| Error::format(&htc.file, 0, format!("no main_body named '{name}'")))
    };
    let bearings: Vec<_> = htc
        .constraints
        .iter()
        .filter(|c| c.kind == "bearing1" || c.kind == "bearing3")
        .collect();
    let [bearing] = bearings.as_slice() else {
        let listed: Vec<String> = htc
            .constraints
            .iter()
            .map(|c| format!("{} {} ({} → {})", c.kind, c.name, c.parent, c.child))
            .collect();
        return Err(Error::format(
            &htc.file,
            0,
            format!(
                "the turbine needs exactly one shaft bearing (a bearing1 or bearing3 constraint), \
                 found {}: {}",
                bearings.len(),
                listed.join(", ")
            ),
        ));
    };
    let shaft = body(&bearing.child)?;
    let shaft_frame = frame(&shaft.name).ok_or_else(|| unplaced(htc, &shaft.name))?;
    // The nacelle's bodies: from the bearing's first body down to the tower.
    let tower = body(&htc.base.body)?;
    let mut nacelle = Vec::new();
    let mut at = bearing.parent.clone();
    while at != tower.name {
        if nacelle.len() > htc.bodies.len() {
            return Err(Error::format(
                &htc.file,
                0,
                "the orientations go round in a circle",
            ));
        }
        nacelle.push(body(&at)?);
        at = htc
            .relatives
            .iter()
            .find(|r| r.child == at)
            .map(|r| r.parent.clone())
            .ok_or_else(|| {
                Error::format(
                    &bearing.file,
                    bearing.line,
                    format!(
                        "the shaft bearing's body '{}' does not hang on the tower '{}' through \
                         the orientation block",
                        bearing.parent, tower.name
                    ),
                )
            })?;
    }
    let hubs = htc
        .relatives
        .iter()
        .filter(|r| r.parent == shaft.name)
        .count();
    let (stiffness, damping) = shaft_spring(shaft, st)?;
    let shaft_inertia = |first: bool| -> f64 {
        shaft
            .masses
            .iter()
            .filter(|m| (m.node == 1) == first)
            .map(|m| m.inertia[2][2])
            .sum()
    };
    if let Some(m) = shaft
        .masses
        .iter()
        .find(|m| m.node != 1 && m.node != shaft.c2_def.len())
    {
        return Err(Error::format(
            &m.file,
            m.line,
            "a concentrated mass on the shaft between its ends is not modelled (the shaft is one \
             torsional spring between the generator's node 1 and the hub's last node)",
        ));
    }
    let drivetrain = Drivetrain {
        hub_inertia: shaft_inertia(false),
        generator_inertia: shaft_inertia(true),
        stiffness,
        damping,
        generator: Generator::Free,
        torque_slope: 0.0,
    };
    let axis = shaft_frame.turn * Vector3::z();
    let tilt_deg = (-axis.z)
        .atan2((axis.x.powi(2) + axis.y.powi(2)).sqrt())
        .to_degrees();
    let support = if with_tower {
        let tower_frame = frame(&tower.name).ok_or_else(|| unplaced(htc, &tower.name))?;
        let top_point = tower_frame.node(tower, NodeRef::Last);
        let apex = ours(shaft_frame.node(shaft, NodeRef::Last) - top_point);
        // Every mass that does not turn with the rotor, and the rotor side's masses but for
        // their inertia about the shaft (the drivetrain's).
        let mut rigid: Vec<(f64, Vector3<f64>, Matrix3<f64>)> = Vec::new();
        for b in nacelle.iter().copied().chain([shaft]) {
            let f = frame(&b.name).ok_or_else(|| unplaced(htc, &b.name))?;
            for m in &b.masses {
                let mut inertia = Matrix3::from_fn(|i, j| m.inertia[i][j]);
                if b.name == shaft.name {
                    inertia[(2, 2)] = 0.0;
                }
                let at = f.node(b, NodeRef::Number(m.node)) + f.turn * Vector3::from(m.offset);
                rigid.push((
                    m.mass,
                    ours(at - top_point),
                    ours_tensor(f.turn * inertia * f.turn.transpose()),
                ));
            }
        }
        let top = nacelle_top(&rigid, apex);
        let length = curve_length(&tower.c2_def);
        straight_tower(tower, htc)?;
        let input = tower.timoshenko.as_ref().ok_or_else(|| {
            Error::format(
                &tower.file,
                tower.line,
                "the tower body has no timoschenko_input",
            )
        })?;
        let st_file = st(input)?;
        let mut table = from_hawc2_st(
            &st_file,
            input.set,
            input.subset,
            &ChordTwist::untwisted(),
            0.0,
        )?;
        // HAWC2 lays the st file's r along the body's length.
        let r_last = table.sections.last().map_or(length, |s| s.z);
        for s in &mut table.sections {
            s.z *= length / r_last;
        }
        let damping = match tower.damping.as_ref().map(htc_damping).transpose()? {
            Some(SourceDamping::StiffnessProportional(f)) => f,
            _ => StiffnessFactors {
                shear: [0.0; 2],
                flap: 0.0,
                edge: 0.0,
                torsion: 0.0,
            },
        };
        let inputs = BeamTowerInputs {
            table,
            damping,
            elements: TOWER_ELEMENTS,
        };
        let tower = Tower::from_beam(&inputs, &top)?;
        Some(Support {
            tower,
            hub_inertia: drivetrain.hub_inertia,
            generator_inertia: drivetrain.generator_inertia,
            gear_ratio: 1.0,
        })
    } else {
        None
    };
    Ok(Hawc2Turbine {
        blades: hubs,
        drivetrain: drivetrain.checked()?,
        support,
        tilt_deg,
    })
}

/// Each body's frame, from the base through the relatives.
fn frames(htc: &HtcTurbine) -> Result<Vec<(String, Frame)>> {
    let base = htc
        .body(&htc.base.body)
        .ok_or_else(|| unplaced(htc, &htc.base.body))?;
    let turn = turned(Matrix3::identity(), &htc.base.eulerang);
    let origin = Vector3::from(htc.base.inipos) - turn * c2_point(&base.c2_def[0]);
    let mut frames = vec![(base.name.clone(), Frame { origin, turn })];
    let mut left: Vec<_> = htc.relatives.iter().collect();
    while !left.is_empty() {
        let before = left.len();
        left.retain(|r| {
            let Some(parent) = frames.iter().find(|f| f.0 == r.parent).map(|f| f.1) else {
                return true;
            };
            let (Some(pb), Some(cb)) = (htc.body(&r.parent), htc.body(&r.child)) else {
                return true;
            };
            let at = parent.node(pb, r.parent_node);
            let turn = turned(parent.turn, &r.eulerang);
            let origin = at - turn * c2_point(&cb.c2_def[node_index(cb, r.child_node)]);
            frames.push((r.child.clone(), Frame { origin, turn }));
            false
        });
        if left.len() == before {
            let r = left[0];
            return Err(Error::format(
                &r.file,
                r.line,
                format!(
                    "relative: body '{}' is not placed by the base or an earlier relative",
                    r.parent
                ),
            ));
        }
    }
    Ok(frames)
}

fn unplaced(htc: &HtcTurbine, name: &str) -> Error {
    Error::format(
        &htc.file,
        0,
        format!("body '{name}' is not placed by the orientation block"),
    )
}

/// The rigid bodies `(mass, position, inertia about their centre)` (tower-top frame) as one:
/// on the tower top with the apex at `apex`.
fn nacelle_top(rigid: &[(f64, Vector3<f64>, Matrix3<f64>)], apex: Vector3<f64>) -> TowerTop {
    let mass: f64 = rigid.iter().map(|r| r.0).sum();
    let centre = if mass > 0.0 {
        rigid.iter().map(|r| r.0 * r.1).sum::<Vector3<f64>>() / mass
    } else {
        Vector3::zeros()
    };
    let mut inertia = Matrix3::zeros();
    for (m, at, own) in rigid {
        let d = at - centre;
        inertia += own + *m * (Matrix3::identity() * d.norm_squared() - d * d.transpose());
    }
    TowerTop {
        yaw_bearing_mass: 0.0,
        nacelle_mass: mass,
        nacelle_cm: [centre.x, centre.y, centre.z],
        nacelle_inertia: std::array::from_fn(|i| std::array::from_fn(|j| inertia[(i, j)])),
        hub_mass: 0.0,
        hub_cm: 0.0,
        overhang: apex.x,
        shaft_height: apex.z,
    }
}

/// The shaft body's torsional stiffness `1 / ∫ ds / GJ` over its length (N·m/rad) and its
/// damping (`kz` of its damping statement times the stiffness).
fn shaft_spring(
    shaft: &TurbineBody,
    st: &mut dyn FnMut(&TimoshenkoInput) -> Result<StFile>,
) -> Result<(f64, f64)> {
    let input = shaft.timoshenko.as_ref().ok_or_else(|| {
        Error::format(
            &shaft.file,
            shaft.line,
            "the shaft body has no timoschenko_input",
        )
    })?;
    let file = st(input)?;
    let rows = &file.subset(input.set, input.subset)?.rows;
    let points: Vec<(f64, f64, usize)> = match rows {
        StRows::Classic(rows) => rows.iter().map(|r| (r.r, r.g * r.i_p, r.line)).collect(),
        StRows::FullyPopulated(rows) => rows
            .iter()
            .map(|r| (r.r, r.stiffness()[5][5], r.line))
            .collect(),
    };
    if let Some(p) = points.iter().find(|p| !(p.1.is_finite() && p.1 > 0.0)) {
        return Err(Error::format(
            &file.path,
            p.2,
            format!(
                "the shaft's torsional stiffness G·I_p is {}; it must be positive",
                p.1
            ),
        ));
    }
    let length = curve_length(&shaft.c2_def);
    let r_last = points.last().map_or(0.0, |p| p.0);
    if points.len() < 2 || r_last <= 0.0 {
        return Err(Error::format(
            &file.path,
            0,
            "the shaft's st subset needs at least two rows along its length",
        ));
    }
    // The trapezoid on the compliance, the st's r laid along the body's length.
    let compliance: f64 = points
        .windows(2)
        .map(|w| (w[1].0 - w[0].0) * length / r_last * 0.5 * (1.0 / w[0].1 + 1.0 / w[1].1))
        .sum();
    let stiffness = 1.0 / compliance;
    let kz = match shaft.damping.as_ref().map(htc_damping).transpose()? {
        Some(SourceDamping::StiffnessProportional(f)) => f.torsion,
        _ => 0.0,
    };
    Ok((stiffness, kz * stiffness))
}

fn curve_length(c2: &[C2Section]) -> f64 {
    c2.windows(2)
        .map(|w| (c2_point(&w[1]) - c2_point(&w[0])).norm())
        .sum()
}

/// The tower's `c2_def` must run straight along its z, its base unturned (a leaning or curved
/// tower is not modelled).
fn straight_tower(tower: &TurbineBody, htc: &HtcTurbine) -> Result<()> {
    if let Some(s) = tower.c2_def.iter().find(|s| s.x != 0.0 || s.y != 0.0) {
        return Err(Error::format(
            &tower.file,
            s.line,
            format!(
                "the tower's c2_def leaves its z axis (x = {}, y = {}): a curved or leaning tower \
                 is not modelled",
                s.x, s.y
            ),
        ));
    }
    if htc.base.eulerang.iter().flatten().any(|&a| a != 0.0) {
        return Err(Error::format(
            &htc.base.file,
            htc.base.line,
            "the tower's base is turned (body_eulerang not 0 0 0): not modelled",
        ));
    }
    Ok(())
}
