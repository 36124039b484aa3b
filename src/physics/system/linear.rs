//! The system linearised about its equilibrium (docs/model.md §6): the state matrix.

use super::{check_finite, StripScratch, System};
use crate::error::{Error, Result};
use crate::numeric::lu::Lu;
use crate::physics::aero::{LOADS, RATES};
use crate::physics::structure::Structure;
use nalgebra::{DMatrix, DVector};
use std::sync::Arc;

/// The linearised system about its equilibrium: `ẋ = A (x − x*)`.
#[derive(Clone)]
pub struct LinearSystem {
    pub a: DMatrix<f64>,
    /// Equilibrium state x*.
    pub x_eq: DVector<f64>,
    /// Structural coordinates 2N (q); the state is `[q (2N), q̇ (2N), z (n_aero)]`.
    pub nq: usize,
    pub n_aero: usize,
    /// Tip twist φ(L) = `tip_twist · q` and tip flap u(L) = `tip_flap · q` (`n_q` each).
    pub tip_twist: DVector<f64>,
    pub tip_flap: DVector<f64>,
    /// The left-out modes' static tip twist and flap (docs/model.md §12.6), added to every state's.
    pub tip_offset: [f64; 2],
    /// A rotor's ground coordinates: blade 1 turns through them, and its tip rows and kick
    /// shapes with it (`tip_twist`, `tip_flap` are then blade 1's at zero azimuth).
    pub turning: Option<Arc<TurningBlade>>,
    pub structure: Arc<dyn Structure>,
}

/// Rows that turn with the rotor: `r(ψ) = r₀ + cos ψ r_c + sin ψ r_s`, what a rotor's ground
/// coordinates give of one blade's motion at azimuth ψ (docs/model.md §13.8).
#[derive(Clone)]
pub struct Azimuthal<const N: usize> {
    constant: [DVector<f64>; N],
    cos: [DVector<f64>; N],
    sin: [DVector<f64>; N],
}

impl<const N: usize> Azimuthal<N> {
    /// From rows affine in `cos ψ` and `sin ψ`, sampled at 0, 90° and 180°.
    pub fn sampled(rows_at: impl Fn(f64) -> [DVector<f64>; N]) -> Azimuthal<N> {
        use std::f64::consts::{FRAC_PI_2, PI};
        let (zero, quarter, half) = (rows_at(0.0), rows_at(FRAC_PI_2), rows_at(PI));
        let constant: [DVector<f64>; N] = std::array::from_fn(|i| (&zero[i] + &half[i]) * 0.5);
        Azimuthal {
            cos: std::array::from_fn(|i| (&zero[i] - &half[i]) * 0.5),
            sin: std::array::from_fn(|i| &quarter[i] - &constant[i]),
            constant,
        }
    }

    /// The rows at azimuth `psi` (rad).
    pub fn at(&self, psi: f64) -> [DVector<f64>; N] {
        let (c, s) = (psi.cos(), psi.sin());
        std::array::from_fn(|i| &self.constant[i] + &self.cos[i] * c + &self.sin[i] * s)
    }
}

/// Blade 1 of a rotor seen from its ground coordinates, at azimuth `Ω t`.
#[derive(Clone)]
pub struct TurningBlade {
    /// Ω (rad/s).
    pub rotor_speed: f64,
    /// Tip twist and tip flap rows.
    pub tip: Azimuthal<2>,
    /// The first torsion and first flap shapes of blade 1 alone, over `[q, q̇]`: kicked
    /// without moving the other blades or any blade's rate.
    pub kick: Azimuthal<2>,
}

impl System {
    /// Equilibrium and the state matrix there.
    pub fn linearise(&self) -> Result<LinearSystem> {
        self.linearise_at(None)
    }

    /// The state matrix at `known`, an equilibrium of this system found while building it
    /// (`crate::model::system_with_equilibrium`), or at the one solved here when there is none.
    pub fn linearise_at(&self, known: Option<DVector<f64>>) -> Result<LinearSystem> {
        let x_eq = match known {
            Some(x) => x,
            None => self.equilibrium()?,
        };
        let mut a = self.jacobian(&x_eq);
        self.condense_left_out(&x_eq, &mut a)?;
        check_finite("state matrix", &a)?;
        Ok(self.tangent(x_eq, a))
    }

    /// Adds to the state matrix `a` at `x` the left-out modes' quasi-static response
    /// (docs/model.md §12.6): their coordinates follow the strip loads without inertia,
    /// `δp = (Λ − ∂Q_R/∂p)⁻¹ (∂Q_R/∂q δq + ∂Q_R/∂q̇ δq̇ + ∂Q_R/∂z δz)`, and move the strips'
    /// positions, so the retained loads gain `∂Q/∂p δp` and the lag states `∂G/∂p δp`. At zero
    /// frequency the condensed system is the whole basis's; the left-out modes' own rates,
    /// inertia and apparent mass are left out. Nothing where the structure leaves no mode out.
    ///
    /// Each station moves few of the coordinates and few of the left-out modes (a rotor's
    /// station its own blade's), so its terms are formed on those alone: the rank-3 products
    /// `L D Rᵀ` of its left-out rows `L`, load derivatives `D` and kinematic rows `R`, gathered
    /// on their nonzero entries and summed over the stations that share them ([`StationGroup`])
    /// by one matrix product. The left-out modes that no station couples (another blade's)
    /// answer apart: `Λ − ∂Q_R/∂p` is solved block by block.
    fn condense_left_out(&self, x: &DVector<f64>, a: &mut DMatrix<f64>) -> Result<()> {
        let Some(left_out) = self.left_out.as_deref() else {
            return Ok(());
        };
        let (nq, na, ns, m) = (self.nq(), self.n_aero(), self.ns, left_out.len());
        let inputs = 2 * nq + na;
        // ∂Q_R/∂[q, q̇, z] (m × inputs), ∂Q_R/∂p, ∂Q/∂p, ∂G/∂p.
        let mut qr = DMatrix::zeros(m, inputs);
        let mut qr_p = DMatrix::from_diagonal(left_out.stiffness());
        let mut qk_p = DMatrix::zeros(nq, m);
        let mut g_p = DMatrix::zeros(na, m);
        // The same per unit of the left-out modes' rates, for their dynamics, where they are
        // taken.
        let dynamic = self.structure.time_invariant();
        let mut rates = dynamic.then(|| LeftOutRates {
            own: -left_out.damping(),
            retained: DMatrix::zeros(nq, m),
            lags: DMatrix::zeros(na, m),
        });
        let mut blocks = Blocks::new(m);
        let mut groups: Vec<StationGroup> = Vec::new();
        let (q, v, z) = self.split(x);
        let mut scratch = StripScratch::new(ns);
        for (si, s) in self.stations.iter().enumerate() {
            let eval = self.evaluate_station(si, (q, v, z), 1.0, true, &mut scratch);
            let left = Gathered::of(left_out.rows_at(si));
            let rows = Gathered::of(self.kinematic_rows(si));
            blocks.join(&left.entries);
            let w = s.weight;
            let d = |offset: usize| -> [[f64; RATES]; LOADS] {
                std::array::from_fn(|l| std::array::from_fn(|j| w * eval.dloads_dk[l][j + offset]))
            };
            let (position, rate) = (d(0), d(RATES));
            // L D (each left-out mode's load per unit of each rate), R D likewise: stacked with
            // the other stations of the same entries, multiplied out once per group below.
            let group = match groups
                .iter()
                .position(|g| g.left == left.entries && g.rows == rows.entries)
            {
                Some(g) => g,
                None => {
                    groups.push(StationGroup::new(
                        left.entries.clone(),
                        rows.entries.clone(),
                    ));
                    groups.len() - 1
                }
            };
            let g = &mut groups[group];
            for j in 0..RATES {
                g.left_position
                    .extend(left.values.iter().map(|v| lp(v, &position, j)));
                g.left_rate
                    .extend(left.values.iter().map(|v| lp(v, &rate, j)));
                g.left_values.extend(left.values.iter().map(|v| v[j]));
                g.rows_position
                    .extend(rows.values.iter().map(|v| lp(v, &position, j)));
                if dynamic {
                    g.rows_rate
                        .extend(rows.values.iter().map(|v| lp(v, &rate, j)));
                }
                g.rows_values.extend(rows.values.iter().map(|v| v[j]));
            }
            for lag in 0..ns {
                let dz: [f64; LOADS] = std::array::from_fn(|l| w * eval.dloads_dz[l][lag]);
                let dzdot: [f64; RATES] = std::array::from_fn(|j| eval.dzdot_dk[lag][j]);
                for (i, &r) in left.entries.iter().enumerate() {
                    qr[(r, 2 * nq + si * ns + lag)] += dot3(&left.values[i], &dz);
                    g_p[(si * ns + lag, r)] += dot3(&left.values[i], &dzdot);
                }
                if let Some(rates) = rates.as_mut() {
                    let dzdot_rate: [f64; RATES] =
                        std::array::from_fn(|j| eval.dzdot_dk[lag][j + RATES]);
                    for (i, &r) in left.entries.iter().enumerate() {
                        rates.lags[(si * ns + lag, r)] += dot3(&left.values[i], &dzdot_rate);
                    }
                }
            }
        }
        for g in &groups {
            let [left_position, left_rate, left_values, rows_position, rows_rate, rows_values] =
                g.matrices();
            let by_rows = |l: &DMatrix<f64>| l * rows_values.transpose();
            let (position_terms, rate_terms) = (by_rows(&left_position), by_rows(&left_rate));
            let by_left = |l: &DMatrix<f64>| l * left_values.transpose();
            let (hub_terms, own_terms) = (by_left(&rows_position), by_left(&left_position));
            for (k, &c) in g.rows.iter().enumerate() {
                for (i, &r) in g.left.iter().enumerate() {
                    qr[(r, c)] += position_terms[(i, k)];
                    qr[(r, nq + c)] += rate_terms[(i, k)];
                    qk_p[(c, r)] += hub_terms[(k, i)];
                }
            }
            for (k, &c) in g.left.iter().enumerate() {
                for (i, &r) in g.left.iter().enumerate() {
                    qr_p[(r, c)] -= own_terms[(i, k)];
                }
            }
            if let Some(rates) = rates.as_mut() {
                let (hub_rate_terms, own_rate_terms) = (by_left(&rows_rate), by_left(&left_rate));
                for (k, &c) in g.rows.iter().enumerate() {
                    for (i, &r) in g.left.iter().enumerate() {
                        rates.retained[(c, r)] += hub_rate_terms[(k, i)];
                    }
                }
                for (k, &c) in g.left.iter().enumerate() {
                    for (i, &r) in g.left.iter().enumerate() {
                        rates.own[(r, c)] += own_rate_terms[(i, k)];
                    }
                }
            }
        }
        // Each block answers only the inputs its modes feel (its blade's coordinates and lag
        // states and the hub's) and moves only the accelerations and its blade's lag rates:
        // solved and multiplied on those alone (a turbine's three blocks touch a third each).
        let inertial = &self.mass_inv * &qk_p;
        let mut quasi_static = DMatrix::zeros(if dynamic { m } else { 0 }, inputs);
        let mut factors = Vec::new();
        for block in blocks.members() {
            let inputs_felt: Vec<usize> = (0..inputs)
                .filter(|&c| block.iter().any(|&r| qr[(r, c)] != 0.0))
                .collect();
            let lags_moved: Vec<usize> = (0..na)
                .filter(|&l| block.iter().any(|&r| g_p[(l, r)] != 0.0))
                .collect();
            let b = block.len();
            let rhs = DMatrix::from_fn(b, inputs_felt.len(), |i, k| qr[(block[i], inputs_felt[k])]);
            let lu = Lu::of_matrix(&qr_p.select_rows(&block).select_columns(&block));
            let response = lu.solve(&rhs).ok_or_else(singular)?;
            let moves =
                DMatrix::from_fn(nq + lags_moved.len(), b, |i, j| match i.checked_sub(nq) {
                    None => inertial[(i, block[j])],
                    Some(l) => g_p[(lags_moved[l], block[j])],
                });
            let added = moves * &response;
            if dynamic {
                for (k, &c) in inputs_felt.iter().enumerate() {
                    for (i, &r) in block.iter().enumerate() {
                        quasi_static[(r, c)] = response[(i, k)];
                    }
                }
                factors.push((block, lu));
            }
            for (k, &c) in inputs_felt.iter().enumerate() {
                for i in 0..nq {
                    a[(nq + i, c)] += added[(i, k)];
                }
                for (l, &lag) in lags_moved.iter().enumerate() {
                    a[(2 * nq + lag, c)] += added[(nq + l, k)];
                }
            }
        }
        if let Some(mut rates) = rates {
            rates.retained = &self.mass_inv * &rates.retained;
            let moves = LeftOutMoves {
                stiffness_less_air: factors,
                retained: inertial,
                lags: g_p,
                rates,
            };
            moves.with_dynamics(a, nq, &quasi_static)?;
        }
        Ok(())
    }

    /// The tangent system `ẋ ≈ A (x − x_r)` about a state `x_r` with its Jacobian `a` (the
    /// equilibrium for [`System::linearise`]; any reference state for the time stepper).
    pub fn tangent(&self, x_ref: DVector<f64>, a: DMatrix<f64>) -> LinearSystem {
        LinearSystem {
            a,
            x_eq: x_ref,
            nq: self.nq(),
            n_aero: self.n_aero(),
            tip_twist: self.tip_rows[0].clone(),
            tip_flap: self.tip_rows[1].clone(),
            tip_offset: {
                let [phi, u, _] = self.tip_offset();
                [phi, u]
            },
            turning: None,
            structure: Arc::clone(&self.structure),
        }
    }
}

impl LinearSystem {
    /// Length of the state vector.
    pub fn dim(&self) -> usize {
        self.a.nrows()
    }
    /// Tip twist and flap of a state at time `t` (s): blade 1's, at azimuth `Ω t` on a rotor.
    pub fn tip_at(&self, x: &DVector<f64>, t: f64) -> (f64, f64) {
        let q = x.rows(0, self.nq);
        let [phi, u] = self.tip_offset;
        let [twist, flap] = self.tip_rows_at(t);
        (twist.dot(&q) + phi, flap.dot(&q) + u)
    }

    /// Tip twist and flap rows over the coordinates at time `t` (s).
    pub fn tip_rows_at(&self, t: f64) -> [DVector<f64>; 2] {
        match &self.turning {
            Some(blade) => blade.tip.at(blade.rotor_speed * t),
            None => [self.tip_twist.clone(), self.tip_flap.clone()],
        }
    }

    /// The shapes a tip kick at time `t` (s) excites over `[q, q̇]` (blade 1's alone on a
    /// rotor; a blade's own moves no rate).
    pub fn kick_shapes_at(&self, t: f64) -> [DVector<f64>; 2] {
        match &self.turning {
            Some(blade) => blade.kick.at(blade.rotor_speed * t),
            None => self.structure.kick_shapes().map(|q| {
                let mut v = DVector::zeros(2 * self.nq);
                v.rows_mut(0, self.nq).copy_from(&q);
                v
            }),
        }
    }
}

/// The left-out modes' stiffness less the air's, singular: no response to the strip loads.
fn singular() -> Error {
    Error::numerical("the left-out modes' response: their stiffness less the air's is singular")
}

/// What the left-out modes' own rates move, per unit of each.
struct LeftOutRates {
    /// Their generalised loads, `∂Q_R/∂ṗ − C_R` (the air's damping less the structure's).
    own: DMatrix<f64>,
    /// The retained accelerations, `M⁻¹ ∂Q/∂ṗ`.
    retained: DMatrix<f64>,
    /// The lag states' rates, `∂G/∂ṗ`.
    lags: DMatrix<f64>,
}

/// The left-out modes' terms in the state matrix.
struct LeftOutMoves {
    /// `Λ − ∂Q_R/∂p`, factored block by block (each block's modes in order).
    stiffness_less_air: Vec<(Vec<usize>, Lu)>,
    /// The retained accelerations per unit of their coordinates, `M⁻¹ ∂Q/∂p`.
    retained: DMatrix<f64>,
    /// The lag states' rates per unit of their coordinates, `∂G/∂p`.
    lags: DMatrix<f64>,
    rates: LeftOutRates,
}

impl LeftOutMoves {
    /// The state matrix `a` with the left-out modes' rates and inertia (docs/model.md §12.6):
    /// their coordinates answer `p̈ + C_R ṗ + (Λ − ∂Q_R/∂p) p = ∂Q_R/∂x x + ∂Q_R/∂ṗ ṗ`, with
    /// `ṗ = G A x` and `p̈ = G A² x` taken from the quasi-static response `p = G x` and the
    /// state matrix `A` it gives (`quasi_static` and `a` on entry): the improved reduced system
    /// of O'Callahan, here with the air's damping. The response gains `(Λ − ∂Q_R/∂p)⁻¹` of
    /// the rates' loads, and `a` what that and the rates move. One step: iterated (Friswell,
    /// Garvey & Penny 1995), it settles no nearer the whole basis's roots here, for twice the
    /// cost (§12.6).
    fn with_dynamics(
        self,
        a: &mut DMatrix<f64>,
        nq: usize,
        quasi_static: &DMatrix<f64>,
    ) -> Result<()> {
        let LeftOutMoves {
            stiffness_less_air,
            retained,
            lags,
            rates,
        } = self;
        let na = a.nrows() - 2 * nq;
        let rate = quasi_static * &*a;
        let load = &rates.own * &rate - &rate * &*a;
        let mut dynamic_response = DMatrix::zeros(load.nrows(), load.ncols());
        for (block, lu) in &stiffness_less_air {
            let solved = lu.solve(&load.select_rows(block)).ok_or_else(singular)?;
            for (i, &r) in block.iter().enumerate() {
                dynamic_response.row_mut(r).copy_from(&solved.row(i));
            }
        }
        let mut accelerations = a.rows_mut(nq, nq);
        accelerations += &retained * &dynamic_response + &rates.retained * &rate;
        let mut lag_rates = a.rows_mut(2 * nq, na);
        lag_rates += &lags * &dynamic_response + &rates.lags * &rate;
        Ok(())
    }
}

/// Three rows on the entries where any of them is nonzero: each entry's three values.
struct Gathered {
    entries: Vec<usize>,
    values: Vec<[f64; RATES]>,
}

impl Gathered {
    fn of(rows: &[DVector<f64>; RATES]) -> Gathered {
        let entries: Vec<usize> = (0..rows[0].len())
            .filter(|&i| rows.iter().any(|r| r[i] != 0.0))
            .collect();
        let values = entries
            .iter()
            .map(|&i| std::array::from_fn(|j| rows[j][i]))
            .collect();
        Gathered { entries, values }
    }
}

/// Column `j` of `v D`: the load per unit of rate `j` through derivatives `d`.
fn lp(v: &[f64; RATES], d: &[[f64; RATES]; LOADS], j: usize) -> f64 {
    (0..LOADS).map(|l| v[l] * d[l][j]).sum()
}

/// Stations whose left-out rows and kinematic rows have the same nonzero entries (a blade's
/// stations, on a rotor each blade's): their rank-3 terms stacked side by side, three columns a
/// station, so that `Σ L D Rᵀ` over them is one matrix product.
struct StationGroup {
    left: Vec<usize>,
    rows: Vec<usize>,
    left_position: Vec<f64>,
    left_rate: Vec<f64>,
    left_values: Vec<f64>,
    rows_position: Vec<f64>,
    rows_rate: Vec<f64>,
    rows_values: Vec<f64>,
}

impl StationGroup {
    fn new(left: Vec<usize>, rows: Vec<usize>) -> StationGroup {
        StationGroup {
            left,
            rows,
            left_position: Vec::new(),
            left_rate: Vec::new(),
            left_values: Vec::new(),
            rows_position: Vec::new(),
            rows_rate: Vec::new(),
            rows_values: Vec::new(),
        }
    }

    /// `L D_position`, `L D_rate`, `L`, `R D_position`, `R D_rate`, `R`, each entries × (3 ×
    /// stations).
    fn matrices(&self) -> [DMatrix<f64>; 6] {
        let (nl, nr) = (self.left.len(), self.rows.len());
        let on = |entries: usize, values: &[f64]| {
            DMatrix::from_column_slice(entries, values.len() / entries.max(1), values)
        };
        [
            on(nl, &self.left_position),
            on(nl, &self.left_rate),
            on(nl, &self.left_values),
            on(nr, &self.rows_position),
            on(nr, &self.rows_rate),
            on(nr, &self.rows_values),
        ]
    }
}

fn dot3(a: &[f64; RATES], b: &[f64; RATES]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// A partition of `0..n` into the sets some group joined, transitively (union–find).
struct Blocks {
    parent: Vec<usize>,
}

impl Blocks {
    fn new(n: usize) -> Blocks {
        Blocks {
            parent: (0..n).collect(),
        }
    }

    fn root(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    fn join(&mut self, group: &[usize]) {
        if let Some((&first, rest)) = group.split_first() {
            let to = self.root(first);
            for &i in rest {
                let from = self.root(i);
                self.parent[from] = to;
            }
        }
    }

    /// Each block's members, ascending.
    fn members(mut self) -> Vec<Vec<usize>> {
        let n = self.parent.len();
        let mut by_root: Vec<Vec<usize>> = vec![Vec::new(); n];
        for i in 0..n {
            let r = self.root(i);
            by_root[r].push(i);
        }
        by_root.into_iter().filter(|b| !b.is_empty()).collect()
    }
}
