//! Strip aerodynamics (docs/model.md §5): one interface, one model per file.
//!
//! Every model is a [`StripModel`]: given one strip's rigid flow ([`Station`]), its local
//! kinematics (twist `φ`, flap `u`, edge `v` and their rates) and its own aerodynamic states `z`,
//! it returns the loads per unit span — the moment `m_φ` toward feather, the force `f_u` downwind
//! and the force `f_v` in the rotor plane toward the leading edge — and the state rates `ż`, with
//! their exact partial derivatives. Apparent-mass loads (proportional to `φ̈`, `ü`, `v̈`) are a
//! separate, constant matrix so the system can move them into its mass matrix.
//! The system (`physics::system`) does the spanwise Galerkin projection; a model never sees the
//! basis functions.
//!
//! Ordering convention, used everywhere in this interface: loads `[m_φ, f_u, f_v]`, kinematics
//! `[φ, u, v, φ̇, u̇, v̇]`, apparent-mass inputs `[φ̈, ü, v̈]` — torsion first, as in
//! `q = [q_φ; q_u]`. The paper's models (§5.1–§5.3) act on a blade without edge motion and leave
//! every edge entry zero; the blade-element model of a real blade (§12) fills them.
//!
//! Adding a model: implement [`StripModel`] in its own file, including `steady_states` (the
//! states that make `ż = 0` for a static deflection, with their derivative, so the equilibrium
//! solve needs no special case) and, if it is not affine and must be simulated as such (ONERA,
//! §5.3), `nonlinear_support`; then add it to `crate::model::aero::model_for`. A real blade's
//! section model is an `airfoil::AirfoilDynamics` instead, behind the one blade-element strip
//! (§12.5, §12.8).

pub mod airfoil;
pub mod blade_element;
pub mod onera;
pub mod polar;
pub mod quasi_steady;
pub mod theodorsen;

use crate::physics::inflow::Station;

/// Local kinematics of one strip, in the blade's sign conventions (docs/model.md §1).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Kinematics {
    /// Elastic twist φ (rad, toward feather).
    pub phi: f64,
    /// Flap displacement u (m, downwind).
    pub u: f64,
    /// Edge displacement v (m, in the rotor plane toward the leading edge: the direction of
    /// rotation).
    pub v: f64,
    /// φ̇ (rad/s).
    pub phi_dot: f64,
    /// u̇ (m/s).
    pub u_dot: f64,
    /// v̇ (m/s).
    pub v_dot: f64,
}

/// Loads per strip: `[m_φ, f_u, f_v]`.
pub const LOADS: usize = 3;
/// Kinematic inputs per strip: `[φ, u, v, φ̇, u̇, v̇]`; the rates start at [`RATES`].
pub const KINEMATICS: usize = 6;
/// Index of φ̇ in the kinematics (φ, u, v come first, their rates in the same order).
pub const RATES: usize = 3;

impl Kinematics {
    /// `[φ, u, v, φ̇, u̇, v̇]`.
    pub fn to_array(&self) -> [f64; KINEMATICS] {
        [
            self.phi,
            self.u,
            self.v,
            self.phi_dot,
            self.u_dot,
            self.v_dot,
        ]
    }
    pub fn from_array(k: [f64; KINEMATICS]) -> Kinematics {
        Kinematics {
            phi: k[0],
            u: k[1],
            v: k[2],
            phi_dot: k[3],
            u_dot: k[4],
            v_dot: k[5],
        }
    }
}

/// The per-length section and air data every strip model needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StripSection {
    /// Chord c (m).
    pub chord: f64,
    /// e_a = x_EA − x_AC (m), positive when the elastic axis is aft of the aerodynamic centre.
    pub ea_offset: f64,
    /// Air density ρ_a (kg/m³).
    pub air_density: f64,
    /// Lift-curve slope a0 (1/rad).
    pub lift_slope: f64,
    /// Profile drag coefficient C_D0.
    pub drag_coefficient: f64,
}

impl StripSection {
    /// Semichord b = c/2 (m).
    pub fn semichord(&self) -> f64 {
        0.5 * self.chord
    }
}

/// One strip's loads, state rates and (when asked) their partial derivatives. Sized once for a
/// model's state count and reused across stations, so the inner loop does not allocate.
#[derive(Debug, Clone, PartialEq)]
pub struct StripEval {
    /// `[m_φ, f_u, f_v]` per unit span (N·m/m, N/m, N/m), apparent mass excluded.
    pub loads: [f64; LOADS],
    /// ∂loads/∂[φ, u, v, φ̇, u̇, v̇].
    pub dloads_dk: [[f64; KINEMATICS]; LOADS],
    /// ∂loads/∂z, `[load][state]`.
    pub dloads_dz: [Vec<f64>; LOADS],
    /// ż.
    pub zdot: Vec<f64>,
    /// ∂ż/∂[φ, u, v, φ̇, u̇, v̇], one row per state.
    pub dzdot_dk: Vec<[f64; KINEMATICS]>,
    /// ∂ż/∂z, row-major `states × states`.
    pub dzdot_dz: Vec<f64>,
}

impl StripEval {
    pub fn new(states: usize) -> StripEval {
        StripEval {
            loads: [0.0; LOADS],
            dloads_dk: [[0.0; KINEMATICS]; LOADS],
            dloads_dz: std::array::from_fn(|_| vec![0.0; states]),
            zdot: vec![0.0; states],
            dzdot_dk: vec![[0.0; KINEMATICS]; states],
            dzdot_dz: vec![0.0; states * states],
        }
    }

    /// Zero everything (models then only write their non-zero entries).
    pub fn clear(&mut self) {
        self.loads = [0.0; LOADS];
        self.dloads_dk = [[0.0; KINEMATICS]; LOADS];
        for row in &mut self.dloads_dz {
            row.fill(0.0);
        }
        self.zdot.fill(0.0);
        self.dzdot_dk.fill([0.0; KINEMATICS]);
        self.dzdot_dz.fill(0.0);
    }
}

/// The steady aerodynamic states of one strip held at a static deflection.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyStates {
    /// z such that ż = 0 with no motion.
    pub z: Vec<f64>,
    /// ∂z/∂[φ, u, v], one row per state.
    pub dz_dk: Vec<[f64; RATES]>,
}

impl SteadyStates {
    pub fn new(states: usize) -> SteadyStates {
        SteadyStates {
            z: vec![0.0; states],
            dz_dk: vec![[0.0; RATES]; states],
        }
    }
}

/// Where a strip model is not affine, for the time stepper (docs/model.md §7): the local inputs its
/// nonlinear part reads and the local outputs it writes.
///
/// Local inputs are indexed `[φ, u, v, φ̇, u̇, v̇, z_0, z_1, …]`, local outputs
/// `[m_φ, f_u, f_v, ż_0, ż_1, …]`
/// (the interface's ordering). The contract: every output not listed is affine in every input
/// with constant coefficients, and every listed output is affine with constant coefficients in
/// the inputs not listed. The stepper then treats the listed part implicitly on a few scalars per
/// station and the rest exactly. Empty (the default) means the model is simulated linearised
/// about its equilibrium, as docs/model.md §7 prescribes for quasi-steady and Theodorsen.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct NonlinearSupport {
    pub inputs: Vec<usize>,
    pub outputs: Vec<usize>,
}

impl NonlinearSupport {
    /// Input index of φ.
    pub const TWIST: usize = 0;
    /// Input index of u.
    pub const FLAP: usize = 1;
    /// Input index of v.
    pub const EDGE: usize = 2;
    /// Input index of φ̇.
    pub const TWIST_RATE: usize = 3;
    /// Input index of u̇.
    pub const FLAP_RATE: usize = 4;
    /// Input index of v̇.
    pub const EDGE_RATE: usize = 5;
    /// Input index of the first aerodynamic state.
    pub const FIRST_STATE: usize = KINEMATICS;
    /// Output index of m_φ.
    pub const TWIST_LOAD: usize = 0;
    /// Output index of f_u.
    pub const FLAP_LOAD: usize = 1;
    /// Output index of f_v.
    pub const EDGE_LOAD: usize = 2;
    /// Output index of the first state rate.
    pub const FIRST_RATE: usize = LOADS;

    /// True when nothing is listed: the model is simulated linearised.
    pub fn is_affine(&self) -> bool {
        self.outputs.is_empty()
    }
}

/// A strip-theory aerodynamic model (docs/model.md §5).
pub trait StripModel: Send + Sync + std::fmt::Debug {
    /// The preset name of the model (`aero.model`).
    fn name(&self) -> &'static str;

    /// Aerodynamic states per station (0 for quasi-steady).
    fn states_per_station(&self) -> usize;

    /// Apparent-mass loads: `[m_φ, f_u, f_v] += M_a · [φ̈, ü, v̈]`, `M_a[load][accel]`. Constant
    /// in time; the system moves it to the left-hand side (mass matrix).
    fn apparent_mass(&self, _s: &Station) -> [[f64; RATES]; LOADS] {
        [[0.0; RATES]; LOADS]
    }

    /// Loads and state rates at kinematics `k` and states `z`; partial derivatives too when
    /// `jacobian` is true (otherwise those fields are left as they were).
    fn evaluate(&self, s: &Station, k: &Kinematics, z: &[f64], out: &mut StripEval, jacobian: bool);

    /// The states for which `ż = 0` when the strip is held at `deflection = [φ, u, v]` with no
    /// motion, and their derivative with respect to `[φ, u, v]`.
    fn steady_states(&self, s: &Station, deflection: [f64; RATES], out: &mut SteadyStates);

    /// The nonlinear part's support ([`NonlinearSupport`]); empty: simulated linearised.
    fn nonlinear_support(&self) -> NonlinearSupport {
        NonlinearSupport::default()
    }
}

/// `aero.model = "none"`: the structure alone, no loads, no states.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoAero;

impl StripModel for NoAero {
    fn name(&self) -> &'static str {
        "none"
    }
    fn states_per_station(&self) -> usize {
        0
    }
    fn evaluate(&self, _: &Station, _: &Kinematics, _: &[f64], out: &mut StripEval, _: bool) {
        out.clear();
    }
    fn steady_states(&self, _: &Station, _: [f64; RATES], _: &mut SteadyStates) {}
}

#[cfg(test)]
pub(crate) mod test_support {
    //! Central-difference checks shared by the model tests.
    use super::*;

    /// Compare every analytic partial derivative of `model` against central differences at
    /// kinematics `k` and states `z`; returns the largest relative mismatch.
    pub fn jacobian_mismatch(model: &dyn StripModel, s: &Station, k: Kinematics, z: &[f64]) -> f64 {
        let ns = model.states_per_station();
        let mut exact = StripEval::new(ns);
        model.evaluate(s, &k, z, &mut exact, true);
        let mut worst: f64 = 0.0;
        // Central differences of an output `f` carry round-off of about ε|f|/h: a slope far
        // below the output's own size is compared against that size instead.
        let output_size = exact
            .loads
            .iter()
            .chain(&exact.zdot)
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let mut compare = |analytic: f64, numeric: f64| {
            let scale = analytic
                .abs()
                .max(numeric.abs())
                .max(1e-6)
                .max(1e-3 * output_size);
            worst = worst.max((analytic - numeric).abs() / scale);
        };
        let h = 1e-6;
        for j in 0..KINEMATICS {
            let shifted = |d: f64| {
                let mut kk = k.to_array();
                kk[j] += d;
                let mut e = StripEval::new(ns);
                model.evaluate(s, &Kinematics::from_array(kk), z, &mut e, false);
                e
            };
            let (p, m) = (shifted(h), shifted(-h));
            for l in 0..LOADS {
                compare(exact.dloads_dk[l][j], (p.loads[l] - m.loads[l]) / (2.0 * h));
            }
            for i in 0..ns {
                compare(exact.dzdot_dk[i][j], (p.zdot[i] - m.zdot[i]) / (2.0 * h));
            }
        }
        for j in 0..ns {
            let shifted = |d: f64| {
                let mut zz = z.to_vec();
                zz[j] += d;
                let mut e = StripEval::new(ns);
                model.evaluate(s, &k, &zz, &mut e, false);
                e
            };
            let (p, m) = (shifted(h), shifted(-h));
            for l in 0..LOADS {
                compare(exact.dloads_dz[l][j], (p.loads[l] - m.loads[l]) / (2.0 * h));
            }
            for i in 0..ns {
                compare(
                    exact.dzdot_dz[i * ns + j],
                    (p.zdot[i] - m.zdot[i]) / (2.0 * h),
                );
            }
        }
        worst
    }

    pub fn station() -> Station {
        Station {
            index: 0,
            x: 3.0,
            weight: 0.5,
            radius: 3.5,
            v0: 42.0,
            psi: 0.35,
            alpha_r: 0.12,
        }
    }

    pub fn section() -> StripSection {
        StripSection {
            chord: 0.5,
            ea_offset: 0.06,
            air_density: 1.225,
            lift_slope: 6.0,
            drag_coefficient: 0.01,
        }
    }
}
