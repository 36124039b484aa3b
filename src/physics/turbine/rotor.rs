//! The rotor in the blades' own rotating frames (docs/model.md §13.2–§13.3): N identical blades,
//! each in the coordinates of its modes, and the drivetrain's angles. A [`Structure`] the
//! aeroelastic system builds on as it does on one blade: its strips are the blade's, once per
//! blade ([`Structure::station_rows`]), and the rotor's azimuth moves every strip in the edge
//! direction by its radius.
//!
//! Coordinates: blade k's mode j at `k·K + j`, then the drivetrain's `θ_r` (and `θ_g`). The mass
//! couples each mode with `θ_r` by its share of the rigid rotation (`φ_jᵀ M r`); `θ_r` carries
//! the hub's and the N blades' inertia about the shaft. Turning faster pulls a curved or
//! deflected blade outward, and a blade moving radially changes the rotor's angular momentum:
//! the skew pair `±2Ω g` between the modes and `θ_r`, `g = f − K_Ω q*` the radial load per Ω²
//! on the blade at its equilibrium `q*`.

use super::drivetrain::{Drivetrain, Generator};
use super::inputs::RotorInputs;
use super::tower::{strip_rows, Apex, Tower, APEX_MOTIONS, GRAVITY};
use crate::error::{Error, Result};
use crate::physics::blade::fem::Rigid;
use crate::physics::section::SectionProps;
use crate::physics::structure::RotorCoupling;
use crate::physics::structure::{kinetic_energy, MotionRows, NaturalMode, Shares, Structure};
use nalgebra::{Complex, DMatrix, DVector};
use std::f64::consts::TAU;
use std::sync::Arc;

/// Which of the blade's modes a rotor's blades hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Part {
    /// The retained ones, the blade structure's own coordinates.
    Retained,
    /// The ones it leaves out ([`Structure::left_out`]), for the static correction.
    LeftOut,
}

/// N blades and the drivetrain, in the blades' rotating frames.
pub struct Rotor {
    blade: Arc<dyn Structure>,
    part: Part,
    blades: usize,
    /// Modes per blade.
    per_blade: usize,
    drivetrain: Option<Drivetrain>,
    /// The tower, on one.
    tower: Option<Tower>,
    /// Blade 0's azimuth (rad).
    azimuth: f64,
    mass: DMatrix<f64>,
    stiffness: DMatrix<f64>,
    /// Structural and gyroscopic together, as the system reads them.
    damping: DMatrix<f64>,
    /// The part of the damping that is the rotation's (Coriolis) and no material's: kept in
    /// vacuo, where the structural damping is left out.
    gyroscopic: DMatrix<f64>,
    static_load: DVector<f64>,
    family_energy: [DMatrix<f64>; 3],
    /// The left-out modes of every blade, where the blade leaves some out.
    left_out: Option<Box<Rotor>>,
}

impl Rotor {
    /// `inputs.blades` copies of `blade` (modes at the rotor speed, its equilibrium
    /// coordinates `q_eq`) on the drivetrain and support of `inputs`, blade 0 at `azimuth`
    /// (rad, zero up). On a rigid support nothing depends on the azimuth; on a tower the
    /// blades' coupling with it turns with them (docs/model.md §13.6).
    pub fn new(
        blade: Arc<dyn Structure>,
        inputs: &RotorInputs,
        q_eq: &DVector<f64>,
        azimuth: f64,
    ) -> Result<Rotor> {
        let coupling = blade.rotor_coupling().ok_or_else(|| {
            Error::numerical(
                "a rotor needs a tabulated blade (the paper's blade has no edge motion)",
            )
        })?;
        let (blades, omega) = (inputs.blades, inputs.rotor_speed);
        if blades < 3 {
            return Err(Error::numerical(format!(
                "a rotor of {blades} blades: the multi-blade transform needs at least 3"
            )));
        }
        let k = blade.coordinates();
        if q_eq.len() != k {
            return Err(Error::numerical(format!(
                "rotor: the blade's equilibrium has {} coordinates, the blade {k}",
                q_eq.len()
            )));
        }
        let left_out = blade
            .left_out()
            .map(|rest| Box::new(Rotor::left_out_of(Arc::clone(&blade), blades, rest)));
        let drivetrain = inputs.drivetrain.clone();
        let fixed = drivetrain.as_ref().map_or(0, Drivetrain::coordinates);
        let on_tower = inputs.support.as_ref().map_or(0, |s| s.tower.coordinates());
        let n = blades * k + fixed + on_tower;
        let mut m = RotorMatrices::zeros(n);
        let own_load = blade.static_load();
        for b in 0..blades {
            let at = b * k;
            m.mass.view_mut((at, at), (k, k)).copy_from(blade.mass());
            m.stiffness
                .view_mut((at, at), (k, k))
                .copy_from(&blade.stiffness());
            m.damping
                .view_mut((at, at), (k, k))
                .copy_from(blade.damping());
            m.static_load.rows_mut(at, k).copy_from(&own_load);
        }
        let rigid = |j: usize, r: Rigid| coupling.rigid[(j, r as usize)];
        let rigid_mass = |a: Rigid, b: Rigid| coupling.rigid_mass[(a as usize, b as usize)];
        let blade_inertia = rigid_mass(Rigid::Rotation, Rigid::Rotation);
        // Turning faster pulls a curved or deflected blade outward: the radial load per Ω² at
        // the equilibrium, which meets every rotation about the shaft (§13.2).
        let radial = &coupling.centrifugal_load - &coupling.centrifugal_stiffness * q_eq;
        // Every coordinate that turns the blades about the shaft, with its weight: the
        // drivetrain's azimuth, the nacelle's roll.
        let mut turning: Vec<DVector<f64>> = Vec::new();
        if let Some(d) = &drivetrain {
            let at = blades * k;
            let [dm, ds, dc] = d.matrices();
            m.mass.view_mut((at, at), (fixed, fixed)).copy_from(&dm);
            m.stiffness
                .view_mut((at, at), (fixed, fixed))
                .copy_from(&ds);
            m.damping.view_mut((at, at), (fixed, fixed)).copy_from(&dc);
            let mut azimuth_row = DVector::zeros(n);
            azimuth_row[at] = 1.0;
            turning.push(azimuth_row);
        }
        if let Some(support) = &inputs.support {
            let at = blades * k + fixed;
            let tower = &support.tower;
            let t = tower.coordinates();
            m.mass.view_mut((at, at), (t, t)).copy_from(&tower.mass);
            m.stiffness
                .view_mut((at, at), (t, t))
                .copy_from(&tower.stiffness);
            m.damping
                .view_mut((at, at), (t, t))
                .copy_from(&tower.damping);
            // The blades' weight on the tower top.
            let blade_mass = rigid_mass(Rigid::Flap, Rigid::Flap);
            let mut tt = m.stiffness.view_mut((at, at), (t, t));
            tt -= GRAVITY * blades as f64 * blade_mass * &tower.sag;
            let mut roll = DVector::zeros(n);
            roll.rows_mut(at, t)
                .copy_from(&tower.apex.row(Apex::Roll as usize).transpose());
            // The hub and the generator turn with the nacelle's roll: `½ J_h (θ̇_r + θ̇_x)²`
            // and `½ J_gen (N θ̇_g + θ̇_x)²` (θ_g = θ_r − δ with the generator free, held at
            // zero with it locked, θ_r itself with no drivetrain).
            let (jh, jgen, ratio) = (
                support.hub_inertia,
                support.generator_inertia,
                support.gear_ratio,
            );
            m.add_outer(&roll, &roll, jh + jgen);
            if let Some(d) = &drivetrain {
                let r = blades * k;
                let mut azimuth_row = DVector::zeros(n);
                azimuth_row[r] = 1.0;
                m.add_symmetric(&azimuth_row, &roll, jh);
                if d.generator == Generator::Free {
                    let mut generator = DVector::zeros(n);
                    generator[r] = 1.0;
                    generator[r + 1] = -1.0;
                    m.add_symmetric(&generator, &roll, jgen * ratio);
                }
            }
            turning.push(roll);
            for b in 0..blades {
                let psi = azimuth + TAU * b as f64 / blades as f64;
                on_tower_blade(&mut m, &coupling, tower, b * k, at, psi, omega);
            }
        }
        for (i, a) in turning.iter().enumerate() {
            // The blades turn by the sum of every turning coordinate.
            let weight = blades as f64 * blade_inertia;
            m.add_outer(a, a, weight);
            for b in &turning[i + 1..] {
                m.add_symmetric(a, b, weight);
            }
            for b in 0..blades {
                for j in 0..k {
                    let mut mode = DVector::zeros(n);
                    mode[b * k + j] = 1.0;
                    m.add_symmetric(&mode, a, rigid(j, Rigid::Rotation));
                    // `∓2Ω g`: a blade moving radially changes the rotor's angular momentum.
                    let g = 2.0 * omega * radial[j];
                    m.add_gyroscopic(a, &mode, g);
                }
            }
        }
        Ok(Rotor {
            blade,
            part: Part::Retained,
            blades,
            per_blade: k,
            drivetrain,
            tower: inputs.support.as_ref().map(|s| s.tower.clone()),
            azimuth,
            mass: m.mass,
            stiffness: m.stiffness,
            damping: &m.damping + &m.gyroscopic,
            gyroscopic: m.gyroscopic,
            static_load: m.static_load,
            family_energy: coupling.family_energy,
            left_out,
        })
    }

    /// The left-out modes of `blades` copies of `blade` (`rest`, per blade): stiffness,
    /// damping, rows and static load, all the left-out modes' correction reads.
    fn left_out_of(blade: Arc<dyn Structure>, blades: usize, rest: &dyn Structure) -> Rotor {
        let (stiffness, load) = (rest.stiffness(), rest.static_load());
        let count = load.len();
        let n = blades * count;
        let mut k = DMatrix::zeros(n, n);
        let mut c = DMatrix::zeros(n, n);
        let mut static_load = DVector::zeros(n);
        for b in 0..blades {
            let at = b * count;
            k.view_mut((at, at), (count, count)).copy_from(&stiffness);
            c.view_mut((at, at), (count, count))
                .copy_from(rest.damping());
            static_load.rows_mut(at, count).copy_from(&load);
        }
        Rotor {
            blade,
            part: Part::LeftOut,
            blades,
            per_blade: count,
            drivetrain: None,
            tower: None,
            azimuth: 0.0,
            mass: DMatrix::identity(n, n),
            stiffness: k,
            damping: c,
            gyroscopic: DMatrix::zeros(n, n),
            static_load,
            family_energy: [(); 3].map(|_| DMatrix::zeros(count, count)),
            left_out: None,
        }
    }

    /// The blade structure whose modes the blades hold.
    fn body(&self) -> &dyn Structure {
        match self.part {
            Part::Retained => self.blade.as_ref(),
            // Built only from a blade that leaves modes out; its own blade otherwise.
            Part::LeftOut => self.blade.left_out().unwrap_or(self.blade.as_ref()),
        }
    }

    pub fn blades(&self) -> usize {
        self.blades
    }

    /// Modes per blade.
    pub fn per_blade(&self) -> usize {
        self.per_blade
    }

    pub fn drivetrain(&self) -> Option<&Drivetrain> {
        self.drivetrain.as_ref()
    }

    /// The blade structure the rotor is made of.
    pub fn blade(&self) -> &Arc<dyn Structure> {
        &self.blade
    }

    /// The kinetic energy of flap, edge and twist between one blade's modes.
    pub fn family_energy(&self) -> &[DMatrix<f64>; 3] {
        &self.family_energy
    }

    /// The first drivetrain coordinate (`θ_r`).
    pub fn drivetrain_at(&self) -> usize {
        self.blades * self.per_blade
    }

    /// The drivetrain's coordinates (0 without one).
    pub fn drivetrain_coordinates(&self) -> usize {
        self.drivetrain.as_ref().map_or(0, Drivetrain::coordinates)
    }

    /// The first tower coordinate and the tower, on one.
    pub fn tower(&self) -> Option<(usize, &Tower)> {
        let at = self.drivetrain_at() + self.drivetrain_coordinates();
        self.tower.as_ref().map(|tower| (at, tower))
    }

    /// The rotation's part of the damping ([`Rotor::damping`] less the structure's).
    pub fn gyroscopic(&self) -> &DMatrix<f64> {
        &self.gyroscopic
    }

    /// Blade `b`'s rows in `rows` (one blade's, at span `x`), with the azimuth's edge motion.
    fn rows_of_blade(&self, b: usize, x: f64, blade: &MotionRows) -> MotionRows {
        let n = self.coordinates();
        let k = self.per_blade;
        let mut rows = MotionRows::zeros(n);
        rows.twist.rows_mut(b * k, k).copy_from(&blade.twist);
        rows.flap.rows_mut(b * k, k).copy_from(&blade.flap);
        rows.edge.rows_mut(b * k, k).copy_from(&blade.edge);
        let radius = self.hub_radius() + x;
        if self.drivetrain.is_some() {
            rows.edge[self.drivetrain_at()] = radius;
        }
        if let Some((at, tower)) = self.tower() {
            let psi = self.azimuth + TAU * b as f64 / self.blades as f64;
            let [flap, edge] = strip_rows(&tower.apex, psi, radius);
            rows.flap.rows_mut(at, flap.len()).copy_from(&flap);
            rows.edge.rows_mut(at, edge.len()).copy_from(&edge);
        }
        rows
    }

    /// Kinetic energies of flap, edge and twist in rotating-frame coordinates `q`: the blades'
    /// own, and the rotor's rotation as edge motion (it moves every section in the edge
    /// direction).
    fn energies(&self, q: &[Complex<f64>]) -> [f64; 3] {
        let k = self.per_blade;
        let mut e = [0.0; 3];
        for b in 0..self.blades {
            let block = &q[b * k..(b + 1) * k];
            for (acc, m) in e.iter_mut().zip(&self.family_energy) {
                *acc += kinetic_energy(m, block);
            }
        }
        if self.drivetrain.is_some() {
            let at = self.drivetrain_at();
            e[1] += self.mass[(at, at)] * q[at].norm_sqr();
        }
        if let Some((at, tower)) = self.tower() {
            let [fore_aft, side_side, torsion] = tower.plane_energies(&self.mass, at, q);
            e[0] += fore_aft;
            e[1] += side_side;
            e[2] += torsion;
        }
        e
    }
}

impl Structure for Rotor {
    fn coordinates(&self) -> usize {
        self.mass.nrows()
    }
    fn length(&self) -> f64 {
        self.body().length()
    }
    fn hub_radius(&self) -> f64 {
        self.body().hub_radius()
    }
    fn mass(&self) -> &DMatrix<f64> {
        &self.mass
    }
    fn stiffness(&self) -> DMatrix<f64> {
        self.stiffness.clone()
    }
    fn damping(&self) -> &DMatrix<f64> {
        &self.damping
    }
    /// Blade 0's.
    fn motion_rows(&self, x: f64) -> MotionRows {
        self.rows_of_blade(0, x, &self.body().motion_rows(x))
    }
    /// `xs` holds one blade's positions once per blade, blade after blade.
    fn station_rows(&self, xs: &[f64]) -> Vec<MotionRows> {
        let per = xs.len() / self.blades;
        let blade = self.body().station_rows(&xs[..per]);
        xs.iter()
            .enumerate()
            .map(|(i, &x)| {
                let b = (i / per.max(1)).min(self.blades - 1);
                self.rows_of_blade(b, x, &blade[i % per.max(1)])
            })
            .collect()
    }
    /// The rotor's modes are named in the ground frame ([`super::ground::GroundRotor`]); in the
    /// blades' rotating frames they are not one structure's modes.
    fn natural_modes(&self) -> Result<Vec<NaturalMode>> {
        Err(Error::numerical(
            "the rotor's modes are named in the ground frame, not in the blades' rotating frames",
        ))
    }
    fn shares(&self, q: &[Complex<f64>]) -> Shares {
        let [f, e, t] = self.energies(q);
        Shares::from_energies(f, e, t)
    }
    /// Blade 0's.
    fn kick_shapes(&self) -> [DVector<f64>; 2] {
        let n = self.coordinates();
        self.body().kick_shapes().map(|s| {
            let mut v = DVector::zeros(n);
            v.rows_mut(0, s.len()).copy_from(&s);
            v
        })
    }
    fn uniform_section(&self) -> Option<&SectionProps> {
        None
    }
    fn span_points(&self) -> Vec<f64> {
        self.body().span_points()
    }
    fn static_load(&self) -> DVector<f64> {
        self.static_load.clone()
    }
    fn left_out(&self) -> Option<&dyn Structure> {
        self.left_out.as_deref().map(|r| r as &dyn Structure)
    }
    /// On a rigid support nothing depends on the azimuth; on a tower the blades' coupling with
    /// it turns with them.
    fn time_invariant(&self) -> bool {
        self.tower.is_none()
    }
}

/// The rotor's matrices as they are built up.
struct RotorMatrices {
    mass: DMatrix<f64>,
    stiffness: DMatrix<f64>,
    damping: DMatrix<f64>,
    gyroscopic: DMatrix<f64>,
    static_load: DVector<f64>,
}

impl RotorMatrices {
    fn zeros(n: usize) -> RotorMatrices {
        RotorMatrices {
            mass: DMatrix::zeros(n, n),
            stiffness: DMatrix::zeros(n, n),
            damping: DMatrix::zeros(n, n),
            gyroscopic: DMatrix::zeros(n, n),
            static_load: DVector::zeros(n),
        }
    }

    /// `M += w x xᵀ`-type kinetic energy `½ w (x·q̇)(y·q̇)`: `M += w x yᵀ`.
    fn add_outer(&mut self, x: &DVector<f64>, y: &DVector<f64>, w: f64) {
        self.mass += w * x * y.transpose();
    }

    /// `M += w (x yᵀ + y xᵀ)`: the kinetic energy `w (x·q̇)(y·q̇)`.
    fn add_symmetric(&mut self, x: &DVector<f64>, y: &DVector<f64>, w: f64) {
        self.mass += w * (x * y.transpose() + y * x.transpose());
    }

    /// `G += g (x yᵀ − y xᵀ)`: a skew (gyroscopic) pair.
    fn add_gyroscopic(&mut self, x: &DVector<f64>, y: &DVector<f64>, g: f64) {
        self.gyroscopic += g * (x * y.transpose() - y * x.transpose());
    }
}

/// Blade `b` (its modes from coordinate `blade_at`) at azimuth `psi` on the tower (its
/// coordinates from `tower_at`), the rotor at `omega` (rad/s): the blade's rigid motion with
/// the apex and its modes' coupling with it (docs/model.md §13.6). In apex motions
/// `h = (u_x, u_y, u_z, θ_x, θ_y, θ_z)`, with `P_f`, `P_e` the modes' shares of a rigid flap and
/// edge translation and `S_f` of a rigid tilt (`c = cos ψ`, `s = sin ψ`); the yaw swings the
/// blade downwind by `r sin ψ` as the tilt does by `r cos ψ`, so its terms are the tilt's at
/// `ψ − 90°`:
///
/// - mass `M[q, h] = [P_f, −c P_e, −s P_e, ·, c S_f, s S_f]` (the roll is a turning
///   coordinate, coupled with the others by [`Rotor::new`]);
/// - Coriolis `C[q, θ_y] = −2Ω s S_f`, `C[q, θ_z] = 2Ω c S_f`, `C[u_y, q] = 2Ω s P_eᵀ`,
///   `C[u_z, q] = −2Ω c P_eᵀ`;
/// - the centrifugal pull of a blade moving in the edge direction and of one swinging
///   downwind, on the hub: `K[u_y, q] = Ω² c P_eᵀ`, `K[u_z, q] = Ω² s P_eᵀ`,
///   `K[θ_y, q] = Ω² c S_fᵀ`, `K[θ_z, q] = Ω² s S_fᵀ`;
/// - the blade's rigid mass at the apex: its mass on every translation, `[c², cs; cs, s²] J`
///   on the tilt and yaw (J its second moment about the apex), its first moment between
///   translation and turn;
/// - its spin's gyroscopic moment: tilting the spinning blade yaws it, `G[θ_y, θ_z] = J_x Ω =
///   −G[θ_z, θ_y]` (`J_x` its moment of inertia about the shaft).
fn on_tower_blade(
    m: &mut RotorMatrices,
    coupling: &RotorCoupling,
    tower: &Tower,
    blade_at: usize,
    tower_at: usize,
    psi: f64,
    omega: f64,
) {
    let k = coupling.rigid.nrows();
    let t = tower.coordinates();
    let (c, s) = (psi.cos(), psi.sin());
    let col = |r: Rigid| coupling.rigid.column(r as usize).into_owned();
    let (pf, pe, sf) = (col(Rigid::Flap), col(Rigid::Edge), col(Rigid::Tilt));
    let rm = |a: Rigid, b: Rigid| coupling.rigid_mass[(a as usize, b as usize)];
    let a = |h: Apex| h as usize;

    let mut coupled = DMatrix::zeros(k, APEX_MOTIONS);
    coupled.set_column(a(Apex::X), &pf);
    coupled.set_column(a(Apex::Y), &(-c * &pe));
    coupled.set_column(a(Apex::Z), &(-s * &pe));
    coupled.set_column(a(Apex::Tilt), &(c * &sf));
    coupled.set_column(a(Apex::Yaw), &(s * &sf));
    let mut coriolis_on_blade = DMatrix::zeros(k, APEX_MOTIONS);
    coriolis_on_blade.set_column(a(Apex::Tilt), &(-2.0 * omega * s * &sf));
    coriolis_on_blade.set_column(a(Apex::Yaw), &(2.0 * omega * c * &sf));
    let mut coriolis_on_hub = DMatrix::zeros(APEX_MOTIONS, k);
    coriolis_on_hub.set_row(a(Apex::Y), &(2.0 * omega * s * pe.transpose()));
    coriolis_on_hub.set_row(a(Apex::Z), &(-2.0 * omega * c * pe.transpose()));
    let w2 = omega * omega;
    let mut pull = DMatrix::zeros(APEX_MOTIONS, k);
    pull.set_row(a(Apex::Y), &(w2 * c * pe.transpose()));
    pull.set_row(a(Apex::Z), &(w2 * s * pe.transpose()));
    pull.set_row(a(Apex::Tilt), &(w2 * c * sf.transpose()));
    pull.set_row(a(Apex::Yaw), &(w2 * s * sf.transpose()));

    let mass = rm(Rigid::Flap, Rigid::Flap);
    let first = rm(Rigid::Edge, Rigid::Rotation);
    let mut hub = DMatrix::zeros(APEX_MOTIONS, APEX_MOTIONS);
    for h in [Apex::X, Apex::Y, Apex::Z] {
        hub[(a(h), a(h))] = mass;
    }
    let tilt_inertia = rm(Rigid::Tilt, Rigid::Tilt);
    hub[(a(Apex::Tilt), a(Apex::Tilt))] = c * c * tilt_inertia;
    hub[(a(Apex::Yaw), a(Apex::Yaw))] = s * s * tilt_inertia;
    let mut pair = |i: Apex, j: Apex, v: f64| {
        hub[(a(i), a(j))] += v;
        hub[(a(j), a(i))] += v;
    };
    pair(Apex::X, Apex::Tilt, c * rm(Rigid::Flap, Rigid::Tilt));
    pair(Apex::Y, Apex::Roll, -c * first);
    pair(Apex::Z, Apex::Roll, -s * first);
    pair(Apex::Roll, Apex::Tilt, c * rm(Rigid::Rotation, Rigid::Tilt));
    pair(Apex::X, Apex::Yaw, s * rm(Rigid::Flap, Rigid::Tilt));
    pair(Apex::Roll, Apex::Yaw, s * rm(Rigid::Rotation, Rigid::Tilt));
    pair(Apex::Tilt, Apex::Yaw, c * s * tilt_inertia);
    let mut spin = DMatrix::zeros(APEX_MOTIONS, APEX_MOTIONS);
    let spin_moment = omega * rm(Rigid::Rotation, Rigid::Rotation);
    spin[(a(Apex::Tilt), a(Apex::Yaw))] = spin_moment;
    spin[(a(Apex::Yaw), a(Apex::Tilt))] = -spin_moment;
    // The roll's own inertia is a turning coordinate's ([`Rotor::new`]).

    let v = &tower.apex;
    let blade_tower = &coupled * v;
    m.mass
        .view_mut((blade_at, tower_at), (k, t))
        .copy_from(&blade_tower);
    m.mass
        .view_mut((tower_at, blade_at), (t, k))
        .copy_from(&blade_tower.transpose());
    let mut tt = m.mass.view_mut((tower_at, tower_at), (t, t));
    tt += v.transpose() * &hub * v;
    m.gyroscopic
        .view_mut((blade_at, tower_at), (k, t))
        .copy_from(&(&coriolis_on_blade * v));
    m.gyroscopic
        .view_mut((tower_at, blade_at), (t, k))
        .copy_from(&(v.transpose() * &coriolis_on_hub));
    let mut tt = m.gyroscopic.view_mut((tower_at, tower_at), (t, t));
    tt += v.transpose() * &spin * v;
    m.stiffness
        .view_mut((tower_at, blade_at), (t, k))
        .copy_from(&(v.transpose() * &pull));
}
