//! The multi-blade coordinate transform (Coleman; MBC3 as Bir 2008, NREL/TP-500-42553, states
//! it), on plain first-order systems; docs/architecture.md, "The turbine", says where it sits.
//!
//! A rotor of N blades carries each rotating quantity once per blade, `q_k` at azimuth
//! `ψ_k = ψ + 2πk/N`. Written as `q_k = a_0 + Σ_n (a_cn cos nψ_k + a_sn sin nψ_k) [+ a_d (−1)^k]`
//! (n = 1 … ⌊(N−1)/2⌋, the differential `a_d` for even N only) it becomes collective, cyclic and
//! differential coordinates in the ground frame: `q = T1(ψ) a`. A first-order system
//! `ẋ = A x` whose states are rotating quantities (and fixed-frame ones, left as they are) then
//! reads `ẏ = A_nr y` with `x = T(ψ) y` and
//!
//! `A_nr = T⁻¹ (A T − Ω dT/dψ)`,
//!
//! where a state that is the rate of a rotating displacement also picks up `Ω dT1/dψ` of that
//! displacement's coordinates (`q̇ = T1 ȧ + Ω T1' a`). For an isotropic rotor of three or more
//! blades in uniform inflow `A_nr` does not depend on ψ; otherwise [`MultiBlade::average`]
//! averages it over the azimuth and says how much it varied.

use crate::error::{Error, Result};
use nalgebra::DMatrix;
use std::f64::consts::TAU;

/// One rotating quantity: its state index on each blade, in blade order. In the ground frame the
/// same indices hold its collective, cosine and sine (and differential) coordinates, in the order
/// `a_0, a_c1, a_s1, a_c2, a_s2, …, [a_d]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Rotating {
    pub states: Vec<usize>,
    /// The group whose rate this is (a blade mode's velocity is the rate of its displacement),
    /// by its position in [`MultiBlade::new`]'s list; `None` for a displacement or a
    /// first-order state (an aerodynamic lag).
    pub rate_of: Option<usize>,
}

/// The layout of a first-order system's rotating states, and its transform.
#[derive(Debug, Clone)]
pub struct MultiBlade {
    blades: usize,
    dim: usize,
    groups: Vec<Rotating>,
}

impl MultiBlade {
    /// A system of `dim` states whose rotating quantities are `groups` (every other state is in
    /// the fixed frame). Each group lists one state per blade, the same number of blades (at
    /// least 3) in all; no state belongs to two groups; a rate names an earlier group.
    pub fn new(dim: usize, groups: Vec<Rotating>) -> Result<MultiBlade> {
        let blades = groups.first().map_or(0, |g| g.states.len());
        if blades < 3 {
            return Err(Error::numerical(format!(
                "multi-blade transform: {blades} blades; it needs at least 3 (and one rotating quantity)"
            )));
        }
        let mut owner = vec![None; dim];
        for (gi, g) in groups.iter().enumerate() {
            if g.states.len() != blades {
                return Err(Error::numerical(format!(
                    "multi-blade transform: quantity {gi} has {} blades, the first {blades}",
                    g.states.len()
                )));
            }
            if let Some(r) = g.rate_of {
                if r >= gi {
                    return Err(Error::numerical(format!(
                        "multi-blade transform: quantity {gi} is the rate of quantity {r}, which must come before it"
                    )));
                }
            }
            for &s in &g.states {
                match owner.get_mut(s) {
                    None => {
                        return Err(Error::numerical(format!(
                            "multi-blade transform: state {s} of quantity {gi} is beyond the system's {dim} states"
                        )))
                    }
                    Some(Some(other)) => {
                        return Err(Error::numerical(format!(
                            "multi-blade transform: state {s} belongs to quantities {other} and {gi}"
                        )))
                    }
                    Some(o) => *o = Some(gi),
                }
            }
        }
        Ok(MultiBlade {
            blades,
            dim,
            groups,
        })
    }

    pub fn blades(&self) -> usize {
        self.blades
    }

    /// `T(ψ)`: ground-frame coordinates to rotating-frame states, `x = T y`.
    pub fn to_rotating(&self, psi: f64, omega: f64) -> DMatrix<f64> {
        let mut t = DMatrix::identity(self.dim, self.dim);
        let t1 = t1(self.blades, psi);
        let dt1 = t1_rate(self.blades, psi);
        for g in &self.groups {
            place(&mut t, &g.states, &g.states, &t1);
            if let Some(r) = g.rate_of {
                place(&mut t, &g.states, &self.groups[r].states, &(omega * &dt1));
            }
        }
        t
    }

    /// `dT/dt = Ω dT/dψ` at azimuth `ψ` and rotor speed `omega` (rad/s).
    fn rate(&self, psi: f64, omega: f64) -> DMatrix<f64> {
        let mut t = DMatrix::zeros(self.dim, self.dim);
        let dt1 = omega * t1_rate(self.blades, psi);
        let ddt1 = omega * omega * t1_second(self.blades, psi);
        for g in &self.groups {
            place(&mut t, &g.states, &g.states, &dt1);
            if let Some(r) = g.rate_of {
                place(&mut t, &g.states, &self.groups[r].states, &ddt1);
            }
        }
        t
    }

    /// `T(ψ)⁻¹`: rotating-frame states to ground-frame coordinates. Exact and cheap: the
    /// inverse of `T1` is its scaled transpose, and a rate's block inverts by substitution.
    pub fn to_ground(&self, psi: f64, omega: f64) -> DMatrix<f64> {
        let mut t = DMatrix::identity(self.dim, self.dim);
        let inv = t1_inverse(self.blades, psi);
        let dt1 = t1_rate(self.blades, psi);
        for g in &self.groups {
            place(&mut t, &g.states, &g.states, &inv);
            if let Some(r) = g.rate_of {
                // a = T1⁻¹ (ẋ − Ω T1' a_r), with a_r = T1⁻¹ x_r.
                let coupling = -omega * &inv * &dt1 * &inv;
                place(&mut t, &g.states, &self.groups[r].states, &coupling);
            }
        }
        t
    }

    /// `A_nr(ψ) = T⁻¹ (A T − Ω dT/dψ)`: the state matrix `a` of the rotating-frame states at
    /// azimuth `ψ` in the ground frame.
    pub fn transform(&self, a: &DMatrix<f64>, psi: f64, omega: f64) -> Result<DMatrix<f64>> {
        if a.shape() != (self.dim, self.dim) {
            return Err(Error::numerical(format!(
                "multi-blade transform: a {}×{} state matrix for a layout of {} states",
                a.nrows(),
                a.ncols(),
                self.dim
            )));
        }
        // T and T⁻¹ hold a block per rotating quantity and the identity elsewhere: a few
        // entries per row and column, so each product costs O(n) per entry of A, not O(n²).
        let t = self.to_rotating(psi, omega);
        let rotated = times_sparse(a, &t) - self.rate(psi, omega);
        // T⁻¹ M = (Mᵀ T⁻ᵀ)ᵀ.
        let back = self.to_ground(psi, omega).transpose();
        Ok(times_sparse(&rotated.transpose(), &back).transpose())
    }

    /// The ground-frame state matrix averaged over `azimuths` equally spaced azimuths of one
    /// revolution (the rotating-frame matrix `a_at(ψ)` at each), and the largest relative
    /// departure of any azimuth's from the average (`max |A_nr(ψ) − Ā| / max |Ā|`, 0 for an
    /// isotropic rotor): how periodic the averaged system was.
    pub fn average(
        &self,
        azimuths: usize,
        omega: f64,
        mut a_at: impl FnMut(f64) -> Result<DMatrix<f64>>,
    ) -> Result<(DMatrix<f64>, f64)> {
        if azimuths == 0 {
            return Err(Error::numerical(
                "multi-blade average over no azimuth: it needs at least one",
            ));
        }
        let each = (0..azimuths)
            .map(|i| {
                let psi = TAU * i as f64 / azimuths as f64;
                self.transform(&a_at(psi)?, psi, omega)
            })
            .collect::<Result<Vec<_>>>()?;
        let mean = each
            .iter()
            .fold(DMatrix::zeros(self.dim, self.dim), |acc, m| acc + m)
            / azimuths as f64;
        let scale = mean.amax().max(f64::MIN_POSITIVE);
        let spread = each
            .iter()
            .map(|m| (m - &mean).amax() / scale)
            .fold(0.0, f64::max);
        Ok((mean, spread))
    }
}

/// Writes `block` into `t` at rows `rows`, columns `cols`.
/// `a t` for a `t` with few nonzero entries in each column.
fn times_sparse(a: &DMatrix<f64>, t: &DMatrix<f64>) -> DMatrix<f64> {
    let mut out = DMatrix::zeros(a.nrows(), t.ncols());
    for c in 0..t.ncols() {
        let mut column = out.column_mut(c);
        for (r, &v) in t.column(c).iter().enumerate() {
            if v != 0.0 {
                column.axpy(v, &a.column(r), 1.0);
            }
        }
    }
    out
}

fn place(t: &mut DMatrix<f64>, rows: &[usize], cols: &[usize], block: &DMatrix<f64>) {
    for (i, &r) in rows.iter().enumerate() {
        for (j, &c) in cols.iter().enumerate() {
            t[(r, c)] = block[(i, j)];
        }
    }
}

/// The harmonic of column `j` of `T1` for `n` blades: 0 for the collective, then `(h, cos)`,
/// `(h, sin)` for h = 1, 2, …, and the differential (`(−1)^k`) last for even `n`.
enum Column {
    Collective,
    Cos(f64),
    Sin(f64),
    Differential,
}

fn column(n: usize, j: usize) -> Column {
    match j {
        0 => Column::Collective,
        j if n % 2 == 0 && j == n - 1 => Column::Differential,
        j => {
            let h = j.div_ceil(2) as f64;
            if j % 2 == 1 {
                Column::Cos(h)
            } else {
                Column::Sin(h)
            }
        }
    }
}

/// Blade `k`'s azimuth.
fn azimuth(n: usize, k: usize, psi: f64) -> f64 {
    psi + TAU * k as f64 / n as f64
}

/// The `d`-th ψ-derivative of `T1(ψ)` for `n` blades (`d` = 0, 1, 2).
fn t1_derivative(n: usize, psi: f64, d: u32) -> DMatrix<f64> {
    DMatrix::from_fn(n, n, |k, j| {
        let p = azimuth(n, k, psi);
        match column(n, j) {
            Column::Collective => f64::from(u8::from(d == 0)),
            Column::Differential => {
                let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
                sign * f64::from(u8::from(d == 0))
            }
            // d^d/dψ^d of cos(hψ), sin(hψ): h^d times the function a quarter turn ahead per d.
            Column::Cos(h) => h.powi(d as i32) * (h * p + f64::from(d) * TAU / 4.0).cos(),
            Column::Sin(h) => h.powi(d as i32) * (h * p + f64::from(d) * TAU / 4.0).sin(),
        }
    })
}

/// `T1(ψ)`: row k `[1, cos ψ_k, sin ψ_k, cos 2ψ_k, sin 2ψ_k, …, [(−1)^k]]`.
pub fn t1(n: usize, psi: f64) -> DMatrix<f64> {
    t1_derivative(n, psi, 0)
}

/// `dT1/dψ`.
pub fn t1_rate(n: usize, psi: f64) -> DMatrix<f64> {
    t1_derivative(n, psi, 1)
}

/// `d²T1/dψ²`.
pub fn t1_second(n: usize, psi: f64) -> DMatrix<f64> {
    t1_derivative(n, psi, 2)
}

/// `T1(ψ)⁻¹`: the columns of `T1` are orthogonal over the blades (`Σ_k cos² = n/2`, the
/// collective's and differential's `n`), so the inverse is the transpose scaled row by row.
pub fn t1_inverse(n: usize, psi: f64) -> DMatrix<f64> {
    let mut inv = t1(n, psi).transpose();
    for j in 0..n {
        let scale = match column(n, j) {
            Column::Collective | Column::Differential => 1.0 / n as f64,
            Column::Cos(_) | Column::Sin(_) => 2.0 / n as f64,
        };
        inv.row_mut(j).scale_mut(scale);
    }
    inv
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn t1_inverse_is_the_inverse_for_three_to_six_blades() {
        for n in 3..=6 {
            for psi in [0.0, 0.3, 2.0, -1.1] {
                let e = (t1_inverse(n, psi) * t1(n, psi) - DMatrix::identity(n, n)).amax();
                assert!(e < 1e-14, "{n} blades at ψ = {psi}: {e:e}");
            }
        }
    }

    #[test]
    fn the_derivatives_of_t1_match_central_differences() {
        let h = 1e-5;
        for n in [3, 4, 5] {
            let psi = 0.7;
            let fd = (t1(n, psi + h) - t1(n, psi - h)) / (2.0 * h);
            assert!((fd - t1_rate(n, psi)).amax() < 1e-9, "{n} blades");
            let fd2 = (t1_rate(n, psi + h) - t1_rate(n, psi - h)) / (2.0 * h);
            assert!((fd2 - t1_second(n, psi)).amax() < 1e-9, "{n} blades");
        }
    }

    #[test]
    fn the_full_transform_inverts_with_rates() {
        // Two fixed states, a displacement and its rate on three blades, a lag state on three.
        let groups = vec![
            Rotating {
                states: vec![2, 3, 4],
                rate_of: None,
            },
            Rotating {
                states: vec![5, 6, 7],
                rate_of: Some(0),
            },
            Rotating {
                states: vec![8, 9, 10],
                rate_of: None,
            },
        ];
        let mb = MultiBlade::new(11, groups).unwrap();
        let (psi, omega) = (0.9, 1.3);
        let e = (mb.to_ground(psi, omega) * mb.to_rotating(psi, omega) - DMatrix::identity(11, 11))
            .amax();
        assert!(e < 1e-14, "{e:e}");
    }

    /// Three edge oscillators on a support that translates side–side: blade k feels the
    /// support's acceleration along its edge direction, `cos ψ_k`, and the support the blades'
    /// inertia back. Periodic in the rotating frame; `support` = 0 leaves the blades alone.
    fn rotor_on_a_support(psi: f64, support: f64) -> DMatrix<f64> {
        let (n, mb, kb, cb) = (3, 1.0, 40.0, 0.2);
        let (ms, ks, cs) = (5.0, 30.0, 0.5);
        let dim = n + 1;
        let mut m = DMatrix::zeros(dim, dim);
        let mut k = DMatrix::zeros(dim, dim);
        let mut c = DMatrix::zeros(dim, dim);
        m[(0, 0)] = ms;
        k[(0, 0)] = ks;
        c[(0, 0)] = cs;
        for b in 0..n {
            let cos = azimuth(n, b, psi).cos() * support;
            m[(0, 0)] += mb * cos * cos;
            m[(0, b + 1)] = mb * cos;
            m[(b + 1, 0)] = mb * cos;
            m[(b + 1, b + 1)] = mb;
            k[(b + 1, b + 1)] = kb;
            c[(b + 1, b + 1)] = cb;
        }
        let inv = m.try_inverse().unwrap();
        let mut a = DMatrix::zeros(2 * dim, 2 * dim);
        a.view_mut((0, dim), (dim, dim)).fill_with_identity();
        a.view_mut((dim, 0), (dim, dim)).copy_from(&(-&inv * k));
        a.view_mut((dim, dim), (dim, dim)).copy_from(&(-&inv * c));
        a
    }

    /// `ẋ = A(t) x` from `x0` (one column per solution) over `[0, t_end]` by classical RK4 in
    /// 20,000 steps, far below every time scale of the test systems.
    fn rk4(a: impl Fn(f64) -> DMatrix<f64>, x0: DMatrix<f64>, t_end: f64) -> DMatrix<f64> {
        let steps = 20_000;
        let h = t_end / steps as f64;
        let mut x = x0;
        for i in 0..steps {
            let t = i as f64 * h;
            let (a0, a1, a2) = (a(t), a(t + 0.5 * h), a(t + h));
            let k1 = &a0 * &x;
            let k2 = &a1 * (&x + 0.5 * h * &k1);
            let k3 = &a1 * (&x + 0.5 * h * &k2);
            let k4 = &a2 * (&x + h * &k3);
            x += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        }
        x
    }

    fn rotor_layout() -> MultiBlade {
        MultiBlade::new(
            8,
            vec![
                Rotating {
                    states: vec![1, 2, 3],
                    rate_of: None,
                },
                Rotating {
                    states: vec![5, 6, 7],
                    rate_of: Some(0),
                },
            ],
        )
        .unwrap()
    }

    /// Uncoupled identical blades: the collective keeps the blade's root λ, the cyclic pair moves
    /// to λ ± iΩ (the backward and forward whirls seen from the ground).
    #[test]
    fn free_blades_whirl_at_their_frequency_plus_and_minus_the_rotor_speed() {
        let omega = 1.7;
        let mb = rotor_layout();
        let a = rotor_on_a_support(0.4, 0.0);
        let nr = mb.transform(&a, 0.4, omega).unwrap();
        let blade = crate::numeric::eigen_decomposition(&a).unwrap().values;
        let ground = crate::numeric::eigen_decomposition(&nr).unwrap().values;
        // The blade's own root (the support's are the same in both frames).
        let lambda = blade
            .iter()
            .copied()
            .find(|l| (l.im - 40f64.sqrt()).abs() < 0.1)
            .unwrap();
        for shift in [0.0, omega, -omega] {
            let want = lambda + nalgebra::Complex::new(0.0, shift);
            let found = ground
                .iter()
                .map(|g| (g - want).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(
                found < 1e-9 * want.norm(),
                "λ {want}: nearest off by {found:e}"
            );
        }
    }

    /// Coupled to the support the rotating-frame system is periodic; in the ground frame it is
    /// one constant matrix at every azimuth, and the average says so.
    #[test]
    fn an_isotropic_rotor_on_a_support_is_time_invariant_in_the_ground_frame() {
        let omega = 1.7;
        let mb = rotor_layout();
        let reference = mb
            .transform(&rotor_on_a_support(0.0, 1.0), 0.0, omega)
            .unwrap();
        for psi in [0.3, 1.9, 4.4] {
            let a = rotor_on_a_support(psi, 1.0);
            let moved = (mb.transform(&a, psi, omega).unwrap() - &reference).amax();
            assert!(moved < 1e-12 * reference.amax(), "ψ = {psi}: {moved:e}");
            // Periodic in the rotating frame: the blades see the support differently at each ψ.
            let rotating = (&a - rotor_on_a_support(0.0, 1.0)).amax();
            assert!(rotating > 1e-3, "ψ = {psi}");
        }
        let (mean, spread) = mb
            .average(12, omega, |psi| Ok(rotor_on_a_support(psi, 1.0)))
            .unwrap();
        assert!(
            spread < 1e-12 && (mean - reference).amax() < 1e-12,
            "{spread:e}"
        );
    }

    /// The ground-frame roots against Floquet theory on the periodic rotating-frame system: over
    /// one revolution `T = 2π/Ω` the monodromy matrix (the state transition, integrated by RK4)
    /// has the multipliers `exp(λ T)` of the constant ground-frame matrix, since
    /// the transform itself returns to the identity after a revolution.
    #[test]
    fn the_ground_frame_roots_are_the_floquet_multipliers_of_the_periodic_system() {
        let omega = 1.7;
        let mb = rotor_layout();
        let nr = mb
            .transform(&rotor_on_a_support(0.0, 1.0), 0.0, omega)
            .unwrap();
        let period = TAU / omega;
        let phi = rk4(
            |t| rotor_on_a_support(omega * t, 1.0),
            DMatrix::identity(8, 8),
            period,
        );
        // One root of each conjugate pair is listed; a multiplier's phase may land either side.
        let multipliers = crate::numeric::eigen_decomposition(&phi).unwrap().values;
        for l in crate::numeric::eigen_decomposition(&nr).unwrap().values {
            let want = (l * period).exp();
            let found = multipliers
                .iter()
                .flat_map(|m| [(m - want).norm(), (m.conj() - want).norm()])
                .fold(f64::INFINITY, f64::min);
            assert!(found < 1e-8, "λ {l}: multiplier {want} off by {found:e}");
        }
    }

    /// The transform is the change of variables it claims: the rotating-frame trajectory from
    /// `x0`, integrated through the periodic system by RK4, equals `T(ψ(t)) e^{A_nr t} T(ψ0)⁻¹ x0`
    /// at a time that is no whole number of revolutions (where a transform turning the wrong
    /// way would still agree on the multipliers: they are blind to shifts of ±iΩ).
    #[test]
    fn the_ground_frame_solution_is_the_rotating_frame_trajectory() {
        let (omega, psi0) = (1.7, 0.4);
        let mb = rotor_layout();
        let nr = mb
            .transform(&rotor_on_a_support(psi0, 1.0), psi0, omega)
            .unwrap();
        let t_end = 1.3;
        let x0 = DMatrix::from_column_slice(8, 1, &[0.1, 0.3, -0.2, 0.05, 0.0, 0.4, 0.1, -0.3]);
        let x = rk4(
            |t| rotor_on_a_support(psi0 + omega * t, 1.0),
            x0.clone(),
            t_end,
        );
        let ground = (nr * t_end).exp() * mb.to_ground(psi0, omega) * &x0;
        let back = mb.to_rotating(psi0 + omega * t_end, omega) * ground;
        let e = (&back - &x).amax() / x.amax();
        assert!(e < 1e-9, "{e:e}");
    }

    /// A rotor with one blade stiffer than the others stays periodic in the ground frame: the
    /// average reports it.
    #[test]
    fn an_anisotropic_rotor_reports_its_spread() {
        let omega = 1.7;
        let mb = rotor_layout();
        let (_, spread) = mb
            .average(12, omega, |psi| {
                let mut a = rotor_on_a_support(psi, 1.0);
                // Blade 0 10 % stiffer: its row of −M⁻¹K scaled, close enough for the purpose.
                a[(5, 1)] *= 1.1;
                Ok(a)
            })
            .unwrap();
        assert!(spread > 1e-3, "{spread:e}");
    }

    #[test]
    fn a_bad_layout_is_named() {
        let g = |states: Vec<usize>, rate_of| Rotating { states, rate_of };
        let e = MultiBlade::new(4, vec![g(vec![0, 1], None)]).unwrap_err();
        assert!(e.to_string().contains("2 blades"), "{e}");
        let e = MultiBlade::new(4, vec![g(vec![0, 1, 4], None)]).unwrap_err();
        assert!(
            e.to_string().contains("beyond the system's 4 states"),
            "{e}"
        );
        let e =
            MultiBlade::new(6, vec![g(vec![0, 1, 2], None), g(vec![2, 3, 4], None)]).unwrap_err();
        assert!(
            e.to_string()
                .contains("state 2 belongs to quantities 0 and 1"),
            "{e}"
        );
        let e = MultiBlade::new(6, vec![g(vec![0, 1, 2], Some(0))]).unwrap_err();
        assert!(e.to_string().contains("must come before it"), "{e}");
    }
}
