//! The laws at the rule's points (docs/design.md §11): one shift step's problem condensed
//! onto the points, and what an iterate (y, z) of normal and tangential forces implies.
//!
//! With s = d − G_nn y + G_nt z (u_n − g) and r = e − G_tn y + G_tt z − ξ (the body's u_x
//! relative to the obstacle), the step's slip is v = r − r̂ (r̂: the anchor, where the point
//! last stuck). The forces an iterate implies are, for the exact multipliers (Alart–Curnier's
//! form, c_n = 1/(G_nn)_qq, c_t = 1/(G_tt)_qq)
//!
//!   y* = (y + c_n s)⁺,   z* = proj_b(z − c_t v),
//!
//! and for the penalty (ε, ε_t), whose laws y = (w/ε) s⁺ and z = proj_b(−(w/ε_t) v) are the
//! same complementarity on the regularised gaps s − (ε/w) y and v + (ε_t/w) z,
//! y* = (y + c_n(s − (ε/w)y))⁺, z* = proj_b(z − c_t(v + (ε_t/w)z)) with c_n = 1/((G_nn)_qq + ε/w),
//! c_t = 1/((G_tt)_qq + ε_t/w); b = μ y* (Coulomb) or w g where the point is in contact
//! (Tresca), proj_b(τ) = max(−b, min(b, τ)). The solution is the fixed point y = y*, z = z*;
//! the natural residual is (y − y*, z − z*) in force units.

use std::sync::Arc;

use faer::Mat;

use super::State;
use crate::contact::newton::norm;

/// Relative size of the round-off in s and r (a few units in the last place), as in
/// [`crate::contact::penalty`].
const ROUNDOFF: f64 = 16.0 * f64::EPSILON;

/// The blocks of 𝔾 = P K⁻¹ Pᵀ between a rule's points.
pub struct Couplings {
    /// G_nn = T C_nn Tᵀ: normal displacement per normal force.
    pub g_nn: Arc<Mat<f64>>,
    /// G_nt = T C_nt Tᵀ: normal displacement per tangential force (G_tn = G_ntᵀ).
    pub g_nt: Mat<f64>,
    /// G_tt = T C_tt Tᵀ: tangential displacement per tangential force.
    pub g_tt: Mat<f64>,
}

/// How both constraints are imposed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Imposition {
    /// Exact multipliers (ε = 0).
    Exact,
    /// The penalty, normal ε and tangential ε_t.
    Penalty {
        /// The normal penalty ε.
        epsilon: f64,
        /// The tangential penalty ε_t.
        epsilon_t: f64,
    },
}

/// The bound b of the tangential force at each point.
#[derive(Clone, Copy, Debug)]
pub enum Bound<'a> {
    /// Coulomb: b = μ y.
    Coulomb(f64),
    /// Tresca: b = w_q g_q at the points in contact, g_q per point (per unit length).
    Tresca(&'a [f64]),
}

/// One shift step's problem on the rule's points.
pub struct StepProblem<'a> {
    /// G_nn, G_nt, G_tt between the points.
    pub couplings: &'a Couplings,
    /// d = B_n u₀ − g (the ALM adds ελ_n).
    pub d: &'a [f64],
    /// e = B_t u₀: the tangential trace with no contact force.
    pub e: &'a [f64],
    /// The rule's weights.
    pub weight: &'a [f64],
    /// The law's bound.
    pub bound: Bound<'a>,
    /// Exact or penalised.
    pub imposition: Imposition,
    /// The obstacle's shift ξ at this step.
    pub shift: f64,
    /// The anchors r̂ (the ALM adds ε_t λ_t).
    pub anchor: &'a [f64],
}

/// What an iterate implies.
pub struct Eval {
    /// u_n − g at the points.
    pub s: Vec<f64>,
    /// The relative tangential displacement r.
    pub r: Vec<f64>,
    /// The forces the iterate implies, y* and z*.
    pub implied_y: Vec<f64>,
    /// See `implied_y`.
    pub implied_z: Vec<f64>,
    /// Each point's state, and the sign σ of its trial traction.
    pub states: Vec<State>,
    /// σ = sign of the trial traction τ (±1).
    pub sign: Vec<f64>,
    /// The round-off floor of the implied forces (force units).
    pub floor: Vec<f64>,
}

impl Eval {
    /// The states as codes (open 0, stick 1, slip along + 2, slip along − 3): a change of the
    /// slip's direction is a change of state.
    pub fn codes(&self) -> Vec<u8> {
        self.states
            .iter()
            .zip(&self.sign)
            .map(|(s, &sg)| match s {
                State::Open => 0,
                State::Stick => 1,
                State::Slip if sg > 0.0 => 2,
                State::Slip => 3,
            })
            .collect()
    }

    /// The natural residual's norm ‖(y − y*, z − z*)‖, its scale max(‖(y*, z*)‖, ‖(y, z)‖)
    /// and the norm of the round-off floor.
    /// Each norm is scaled by its largest entry ([`norm`]): forces of 1e-297 do not square to 0.
    pub fn residual(&self, y: &[f64], z: &[f64]) -> (f64, f64, f64) {
        let pair = |a: &[f64], b: &[f64]| norm(&[a, b].concat());
        let diff: Vec<f64> = (0..y.len())
            .flat_map(|q| [y[q] - self.implied_y[q], z[q] - self.implied_z[q]])
            .collect();
        let scale = pair(&self.implied_y, &self.implied_z).max(pair(y, z));
        (norm(&diff), scale, norm(&self.floor))
    }
}

impl StepProblem<'_> {
    /// The number of points.
    pub fn len(&self) -> usize {
        self.d.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.d.is_empty()
    }

    /// s and r of the iterate (y, z), with their round-off.
    pub fn displacements(&self, y: &[f64], z: &[f64]) -> [Vec<f64>; 4] {
        let n = self.len();
        let c = self.couplings;
        let mut s = self.d.to_vec();
        let mut r: Vec<f64> = self.e.iter().map(|e| e - self.shift).collect();
        let (mut ns, mut nr) = (vec![0.0; n], vec![0.0; n]);
        for q in 0..n {
            let (yq, zq) = (y[q], z[q]);
            if yq == 0.0 && zq == 0.0 {
                continue;
            }
            let (nn, nt, tt) = (
                c.g_nn.col_as_slice(q),
                c.g_nt.col_as_slice(q),
                c.g_tt.col_as_slice(q),
            );
            for p in 0..n {
                // (G_tn y)_p = Σ_q (G_nt)_qp y_q.
                let (a, b, tn, d) = (nn[p] * yq, nt[p] * zq, c.g_nt[(q, p)] * yq, tt[p] * zq);
                s[p] += b - a;
                r[p] += d - tn;
                ns[p] += a.abs() + b.abs();
                nr[p] += tn.abs() + d.abs();
            }
        }
        for q in 0..n {
            // A point the obstacle never reaches (d = −∞) has no round-off.
            ns[q] = if self.d[q].is_finite() {
                ROUNDOFF * (ns[q] + self.d[q].abs())
            } else {
                0.0
            };
            nr[q] = ROUNDOFF * (nr[q] + self.e[q].abs() + self.shift.abs() + self.anchor[q].abs());
        }
        [s, r, ns, nr]
    }

    /// What the iterate (y, z) implies.
    pub fn evaluate(&self, y: &[f64], z: &[f64]) -> Eval {
        let n = self.len();
        let [s, r, ns, nr] = self.displacements(y, z);
        let g = self.couplings;
        let mut out = Eval {
            implied_y: vec![0.0; n],
            implied_z: vec![0.0; n],
            states: vec![State::Open; n],
            sign: vec![1.0; n],
            floor: vec![0.0; n],
            s,
            r,
        };
        for q in 0..n {
            let w = self.weight[q];
            let v = out.r[q] - self.anchor[q];
            let (trial_y, tau, (kn, kt)) = match self.imposition {
                Imposition::Exact => {
                    let (cn, ct) = (1.0 / g.g_nn[(q, q)], 1.0 / g.g_tt[(q, q)]);
                    (y[q] + cn * out.s[q], z[q] - ct * v, (cn, ct))
                }
                Imposition::Penalty { epsilon, epsilon_t } => {
                    // y = (w/ε)s⁺ ⇔ y = (y + c_n(s − (ε/w)y))⁺ for any c_n > 0, and
                    // z = proj_b(−(w/ε_t)v) ⇔ z = proj_b(z − c_t(v + (ε_t/w)z)): the same
                    // Alart–Curnier form on the regularised gaps, scaled by their diagonal
                    // (the raw (w/ε)s decides the states far too sharply at small ε).
                    let (dn, dt) = (epsilon / w, epsilon_t / w);
                    let (cn, ct) = (1.0 / (g.g_nn[(q, q)] + dn), 1.0 / (g.g_tt[(q, q)] + dt));
                    (
                        y[q] + cn * (out.s[q] - dn * y[q]),
                        z[q] - ct * (v + dt * z[q]),
                        (cn, ct),
                    )
                }
            };
            // Round-off counts where the point may be in contact: one open by more than its
            // noise implies (0, 0) exactly (docs/design.md §11; a far point's round-off O(|g|)
            // swamped a press of 1e-300).
            let noise_y = kn * ns[q];
            if trial_y > -noise_y {
                out.floor[q] = noise_y + kt * nr[q];
            }
            if trial_y.is_nan() || tau.is_nan() {
                out.implied_y[q] = f64::NAN;
                continue;
            }
            if trial_y <= 0.0 {
                continue;
            }
            out.implied_y[q] = trial_y;
            let b = match self.bound {
                Bound::Coulomb(mu) => mu * trial_y,
                Bound::Tresca(g) => w * g[q],
            };
            out.sign[q] = if tau < 0.0 { -1.0 } else { 1.0 };
            if b > 0.0 && tau.abs() <= b {
                out.states[q] = State::Stick;
                out.implied_z[q] = tau;
            } else {
                out.states[q] = State::Slip;
                out.implied_z[q] = out.sign[q] * b;
            }
        }
        out
    }
}
