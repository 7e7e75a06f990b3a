//! The penalised problem (8), (11) solved by semismooth Newton (docs/design.md §3), condensed onto
//! the contact points.
//!
//! Minimise Π(u) = ½ uᵀKu − fᵀu + (1/2ε) Σ_q w_q ((Bu − g)_q⁺)², whose gradient is the
//! residual of (11), R(u) = Ku − f + (1/ε) BᵀW(Bu − g)⁺. Every Newton iterate has the form
//! u = u₀ − K⁻¹Bᵀy with u₀ = K⁻¹f and y the contact forces at the rule's points, so the whole
//! iteration lives in y: with G = B K⁻¹ Bᵀ = T C Tᵀ (C the trace compliance of K, T the trace
//! of the rule's points) and d = Bu₀ − g, u_n − g = d − Gy, and the Newton step with the
//! Jacobian K + (1/ε) B_AᵀW_A B_A of the active points A (where u_n > g) is the solution of
//!
//!   (ε W_A⁻¹ + G_AA) y_A = d_A,  y = 0 off A,
//!
//! a dense system of the active set's size: K is never refactorised. Steps are full (the
//! primal–dual active-set method) until an active set repeats; then the exact line search on
//! Π(u(y)) = ½ yᵀGy + (1/2ε) Σ w ((d − Gy)⁺)² + const breaks the cycle, so the iteration
//! converges from any start. (A monotone line search on every step is far slower at small ε:
//! the valley of Π is so narrow that a wrong active set allows only tiny steps.) Converged
//! means the active set did not change over the last step and the residual is below a
//! relative tolerance; anything else is reported as not converged.

use std::ops::ControlFlow;

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use super::newton::{
    self, Assessment, ForceBalance, Iteration, NewtonOptions, NewtonResult, SemismoothLaw, Verdict, count,
};
use crate::error::{Diagnosis, SolveError};

/// One instance of (11), condensed onto the rule's points.
pub struct Penalty<'a> {
    /// G = B K⁻¹ Bᵀ between the rule's points.
    pub coupling: &'a Mat<f64>,
    /// d = B u₀ − g: the gap violation with no contact forces.
    pub free_violation: &'a [f64],
    /// Rule weights w_q.
    pub weight: &'a [f64],
    /// The penalty parameter ε > 0 of (8).
    pub epsilon: f64,
}

/// Relative size of the round-off in s = d − Gy (a few units in the last place).
const ROUNDOFF: f64 = 16.0 * f64::EPSILON;

pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// G y for y supported on `support`.
pub(crate) fn apply(g: &Mat<f64>, y: &[f64], support: &[usize]) -> Vec<f64> {
    let mut out = vec![0.0; g.nrows()];
    for &j in support {
        let col = g.col(j);
        let yj = y[j];
        for (i, o) in out.iter_mut().enumerate() {
            *o += col[i] * yj;
        }
    }
    out
}

/// Solve (ε W_A⁻¹ + G_AA) y_A = d_A for the active points `a` (G_AA y_A = d_A for ε = 0).
pub(crate) fn active_forces(pb: &Penalty, a: &[usize]) -> Vec<f64> {
    let n = pb.coupling.nrows();
    let mut y = vec![0.0; n];
    if a.is_empty() {
        return y;
    }
    let m = active_block(pb.coupling, a, |q| pb.epsilon / pb.weight[q]);
    let rhs = Mat::<f64>::from_fn(a.len(), 1, |i, _| pb.free_violation[a[i]]);
    let sol = match m.llt(Side::Lower) {
        Ok(llt) => llt.solve(&rhs),
        // G is positive semi-definite and εW⁻¹ positive: only round-off can get here.
        Err(_) => m.lblt(Side::Lower).solve(&rhs),
    };
    for (i, &q) in a.iter().enumerate() {
        y[q] = sol[(i, 0)];
    }
    y
}

/// M_AA + diag(δ_q, q ∈ A): the rows and columns `a` of `m`, with `diagonal(q)` added where
/// row and column are the point q; gathered a column at a time (the active-set systems of the
/// penalty's and Nitsche's Newton).
pub(crate) fn active_block(m: &Mat<f64>, a: &[usize], diagonal: impl Fn(usize) -> f64) -> Mat<f64> {
    let mut block = Mat::<f64>::zeros(a.len(), a.len());
    for (j, &q) in a.iter().enumerate() {
        let column = m.col_as_slice(q);
        let out = block.col_as_slice_mut(j);
        for (o, &p) in out.iter_mut().zip(a) {
            *o = column[p];
        }
        out[j] += diagonal(q);
    }
    block
}

/// Round-off in s = d − Gy at each point, a difference of O(|d|) numbers (`gy` = Gy): below
/// it the sign of s and the residual are noise, amplified by 1/ε in the forces. A point the
/// obstacle never reaches (d = −∞) has none.
pub(crate) fn round_off(d: &[f64], gy: &[f64]) -> Vec<f64> {
    d.iter()
        .zip(gy)
        .map(|(&dq, &gq)| {
            if dq.is_finite() {
                ROUNDOFF * (dq.abs() + gq.abs())
            } else {
                0.0
            }
        })
        .collect()
}

/// The penalty's law (11) on the contact forces y at the rule's points ([`newton::drive`]).
struct PenaltyLaw<'a, 'b>(&'b Penalty<'a>);

/// What the penalty's law computes of an iterate y: s = d − Gy.
struct Violation {
    s: Vec<f64>,
}

impl SemismoothLaw for PenaltyLaw<'_, '_> {
    type States = Vec<bool>;
    type Values = Violation;

    fn assess(
        &self,
        y: &[f64],
        previous: Option<&Vec<bool>>,
        opts: &NewtonOptions,
    ) -> Assessment<Vec<bool>, Violation> {
        let pb = self.0;
        let n = y.len();
        let inv_eps = 1.0 / pb.epsilon;
        let d = pb.free_violation;
        let support: Vec<usize> = (0..n).filter(|&q| y[q] != 0.0).collect();
        let gy = apply(pb.coupling, y, &support);
        let s: Vec<f64> = (0..n).map(|q| d[q] - gy[q]).collect();
        let noise = round_off(d, &gy);
        // R = Bᵀ(Wp − y): the contact forces the displacement implies against those assumed.
        let force: Vec<f64> = (0..n).map(|q| pb.weight[q] * s[q].max(0.0) * inv_eps).collect();
        let mismatch: Vec<f64> = (0..n).map(|q| force[q] - y[q]).collect();
        let floor: Vec<f64> = (0..n).map(|q| pb.weight[q] * noise[q] * inv_eps).collect();
        let m = ForceBalance {
            gap: &s,
            noise: &noise,
            implied: &force,
            assumed: y,
            mismatch: &mismatch,
            floor: &floor,
        }
        .measure(previous, opts.rtol);
        let verdict = if m.accurate && m.settled && !m.swamped {
            Verdict::Converged
        } else if m.swamped {
            Verdict::Fail(Diagnosis::Swamped { epsilon: pb.epsilon })
        } else {
            Verdict::Continue
        };
        Assessment {
            active: count(&m.active),
            states: m.active,
            residual: m.residual,
            verdict,
            values: Violation { s },
        }
    }

    fn target(&self, _: &[f64], now: &Assessment<Vec<bool>, Violation>) -> Result<Vec<f64>, Diagnosis> {
        let a: Vec<usize> = (0..now.states.len()).filter(|&q| now.states[q]).collect();
        Ok(active_forces(self.0, &a))
    }

    /// Full steps until an active set repeats; then the exact line search on Π(u(y)).
    fn step(&self, y: &[f64], target: &[f64], now: &Assessment<Vec<bool>, Violation>, repeated: bool) -> f64 {
        if !repeated {
            return 1.0;
        }
        let pb = self.0;
        let n = y.len();
        let delta: Vec<f64> = (0..n).map(|q| target[q] - y[q]).collect();
        let moved: Vec<usize> = (0..n).filter(|&q| delta[q] != 0.0).collect();
        let gd = apply(pb.coupling, &delta, &moved);
        let b: Vec<f64> = gd.iter().map(|v| -v).collect();
        exact_step(
            &now.values.s,
            &b,
            pb.weight,
            1.0 / pb.epsilon,
            dot(y, &gd),
            dot(&delta, &gd),
        )
    }
}

/// Solve (11) from the contact forces `initial` (none when None), reporting each iteration
/// to `on_iteration`, which may cancel the solve.
pub fn solve(
    pb: &Penalty,
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<NewtonResult, SolveError> {
    let n = pb.coupling.nrows();
    let y = initial
        .filter(|y| y.len() == n)
        .map_or_else(|| vec![0.0; n], <[f64]>::to_vec);
    let outcome = newton::drive(&PenaltyLaw(pb), y, opts, on_iteration)?;
    let (y, s) = (outcome.x.clone(), outcome.last.values.s.clone());
    Ok(outcome.result(y, s))
}

/// The exact minimiser t ≥ 0 of the convex piecewise quadratic
/// φ(t) = t·lin + ½t²·quad + (1/2ε) Σ w_q ((s_q + t·b_q)⁺)², found by walking its breakpoints.
fn exact_step(s: &[f64], b: &[f64], w: &[f64], inv_eps: f64, lin: f64, quad: f64) -> f64 {
    // φ'(t) = lin + t·quad + (1/ε) Σ_{s_q + t b_q > 0} w_q b_q (s_q + t b_q): piecewise linear,
    // non-decreasing. Its slope and intercept change where s_q + t b_q crosses 0.
    let (mut a, mut c) = (lin, quad); // φ'(t) = a + c t on the current piece
    let mut events: Vec<(f64, usize)> = Vec::new();
    for q in 0..s.len() {
        if !s[q].is_finite() || b[q] == 0.0 {
            if s[q] > 0.0 && s[q].is_finite() {
                a += inv_eps * w[q] * b[q] * s[q];
            }
            continue;
        }
        let cross = -s[q] / b[q];
        let on_now = s[q] > 0.0 || (s[q] == 0.0 && b[q] > 0.0);
        if on_now {
            a += inv_eps * w[q] * b[q] * s[q];
            c += inv_eps * w[q] * b[q] * b[q];
        }
        if cross > 0.0 {
            events.push((cross, q));
        }
    }
    events.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut t0 = 0.0;
    for (t1, q) in events {
        // Zero of a + c t on [t0, t1]?
        if c > 0.0 && a + c * t1 >= 0.0 {
            return (-a / c).max(t0);
        }
        // Crossing t1 toggles point q.
        let (wq, bq, sq) = (inv_eps * w[q], b[q], s[q]);
        if bq > 0.0 {
            a += wq * bq * sq;
            c += wq * bq * bq;
        } else {
            a -= wq * bq * sq;
            c -= wq * bq * bq;
        }
        t0 = t1;
    }
    if c > 0.0 { (-a / c).max(t0) } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_step_minimises_the_piecewise_quadratic() {
        let s = [0.3, -0.2, -1.0, 0.05, f64::NEG_INFINITY];
        let b = [-0.5, 0.4, 0.9, 0.0, 1.0];
        let w = [1.0, 2.0, 0.5, 1.5, 1.0];
        let (inv_eps, lin, quad) = (10.0, -3.0, 0.7);
        let phi = |t: f64| {
            t * lin
                + 0.5 * t * t * quad
                + 0.5
                    * inv_eps
                    * (0..5)
                        .map(|q| w[q] * (s[q] + t * b[q]).max(0.0).powi(2))
                        .sum::<f64>()
        };
        let t = exact_step(&s, &b, &w, inv_eps, lin, quad);
        // Brute force on a fine grid: nothing beats the exact step.
        let best = (0..=400_000)
            .map(|i| i as f64 * 1e-5)
            .fold(f64::INFINITY, |m, t| m.min(phi(t)));
        assert!(phi(t) <= best + 1e-12, "t = {t}: φ = {} > {best}", phi(t));
        assert!(t > 0.0);
    }
}
