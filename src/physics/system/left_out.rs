//! The static correction of a truncated modal basis (docs/model.md §12.6): the modes the
//! structure's coordinates leave out ([`Structure::left_out`]) answer the strip loads
//! statically, `p = Λ⁻¹ (Σ_s w_s Σ_l L_l,s r_l,s + f)` with `Λ = diag ω_j²`, and their motion at
//! the stations, `r_s · p`, is added to the retained modes' motion wherever the strips and the
//! outputs read a position. Their dynamics are left out: they sit far above the frequencies of
//! interest, where their static response is their response.

use crate::error::{Error, Result};
use crate::physics::aero::RATES;
use crate::physics::inflow::Station;
use crate::physics::structure::Structure;
use nalgebra::{DMatrix, DVector};

/// The left-out modes as the stations see them.
pub(super) struct LeftOut {
    /// Their rows `e_φ, e_u, e_v` at each station.
    rows: Vec<[DVector<f64>; RATES]>,
    /// The same at the tip.
    tip_rows: [DVector<f64>; RATES],
    /// `ω_j²`: each mode's stiffness.
    stiffness: DVector<f64>,
    /// Their structural damping matrix (modal: `2ζ_jω_j` on the diagonal).
    damping: DMatrix<f64>,
    /// Their share of the structure's own static load (the centrifugal pull on a curved axis).
    static_load: DVector<f64>,
    /// Their static response to it, `[φ, u, v]` at each station: the part of every offset the
    /// strip loads do not change.
    fixed: Vec<[f64; RATES]>,
    /// Per mode, the largest twist (rad) or flap over `reach` (m/m) it gives at a station per
    /// unit coordinate: the scale on which the operating point's passes compare coordinates.
    scale: DVector<f64>,
}

/// The motion the left-out modes' static coordinates give.
#[derive(Clone)]
pub(super) struct Offsets {
    /// `[φ, u, v]` at each station from the structure's own static load (which the
    /// equilibrium's load continuation never ramps) …
    pub fixed: Vec<[f64; RATES]>,
    /// … and from the strip loads.
    pub loaded: Vec<[f64; RATES]>,
    /// `[φ, u, v]` at the tip, all of it.
    pub tip: [f64; RATES],
}

impl LeftOut {
    /// What `structure` leaves out, at `stations`; none where its basis is complete.
    pub fn of(structure: &dyn Structure, stations: &[Station]) -> Result<Option<LeftOut>> {
        let Some(rest) = structure.left_out() else {
            return Ok(None);
        };
        let motion = |x: f64| {
            let r = rest.motion_rows(x);
            [r.twist, r.flap, r.edge]
        };
        let stiffness = rest.stiffness().diagonal();
        if !stiffness.iter().all(|k| k.is_finite() && *k > 0.0) {
            return Err(Error::numerical(
                "the truncated basis's static correction: a left-out mode has no stiffness",
            ));
        }
        let static_load = rest.static_load();
        if !static_load.iter().all(|v| v.is_finite()) {
            return Err(Error::numerical(
                "non-finite centrifugal load on the left-out modes",
            ));
        }
        let xs: Vec<f64> = stations.iter().map(|s| s.x).collect();
        let rows: Vec<_> = rest
            .station_rows(&xs)
            .into_iter()
            .map(|r| [r.twist, r.flap, r.edge])
            .collect();
        let reach = structure.hub_radius() + structure.length();
        let scale = DVector::from_fn(stiffness.len(), |j, _| {
            rows.iter().fold(0.0, |m: f64, [twist, flap, _]| {
                m.max(twist[j].abs()).max(flap[j].abs() / reach)
            })
        });
        let own = static_load.component_div(&stiffness);
        let fixed = rows.iter().map(|r| motion_of(r, &own)).collect();
        Ok(Some(LeftOut {
            tip_rows: motion(structure.length()),
            rows,
            stiffness,
            damping: rest.damping().clone(),
            static_load,
            fixed,
            scale,
        }))
    }

    /// The motion coordinates `p` give at the stations and the tip.
    pub fn offsets(&self, p: &DVector<f64>) -> Offsets {
        Offsets {
            loaded: (self.rows.iter().zip(&self.fixed))
                .map(|(r, fixed)| {
                    let mut d = motion_of(r, p);
                    for (d, f) in d.iter_mut().zip(fixed) {
                        *d -= f;
                    }
                    d
                })
                .collect(),
            fixed: self.fixed.clone(),
            tip: motion_of(&self.tip_rows, p),
        }
    }

    /// `p` scaled to the twist (rad) it gives: what the passes compare.
    pub fn scaled(&self, p: &DVector<f64>) -> DVector<f64> {
        p.component_mul(&self.scale)
    }

    /// The inverse of [`LeftOut::scaled`] (a mode with no motion at any station keeps scale 0
    /// and coordinate 0).
    pub fn unscaled(&self, scaled: &[f64]) -> DVector<f64> {
        DVector::from_fn(self.scale.len(), |j, _| {
            if self.scale[j] > 0.0 {
                scaled[j] / self.scale[j]
            } else {
                0.0
            }
        })
    }

    pub fn len(&self) -> usize {
        self.stiffness.len()
    }

    /// The generalised load on the left-out modes before any strip: the structure's own.
    pub fn own_load(&self) -> DVector<f64> {
        self.static_load.clone()
    }

    /// Adds station `si`'s strip loads `[m_φ, f_u, f_v]` (per length, weight `w`) to `force`.
    pub fn add_strip(&self, force: &mut DVector<f64>, si: usize, w: f64, loads: &[f64]) {
        for (load, row) in loads.iter().zip(&self.rows[si]) {
            force.axpy(w * load, row, 1.0);
        }
    }

    /// The rows `e_φ, e_u, e_v` of the left-out modes at station `si`.
    pub fn rows_at(&self, si: usize) -> &[DVector<f64>; RATES] {
        &self.rows[si]
    }

    /// `ω_j²` of each left-out mode.
    pub fn stiffness(&self) -> &DVector<f64> {
        &self.stiffness
    }

    /// Their structural damping matrix.
    pub fn damping(&self) -> &DMatrix<f64> {
        &self.damping
    }

    /// The static coordinates under generalised load `force`.
    pub fn coordinates(&self, force: DVector<f64>) -> DVector<f64> {
        force.component_div(&self.stiffness)
    }
}

/// `[φ, u, v]` of coordinates `p` on `rows`.
fn motion_of(rows: &[DVector<f64>; RATES], p: &DVector<f64>) -> [f64; RATES] {
    rows.each_ref().map(|r| r.dot(p))
}
