//! The penalised problem (8), (11) solved by semismooth Newton (DESIGN §3).
//!
//! Minimise Π(u) = ½ uᵀKu − fᵀu + (1/2ε) Σ_q w_q ((Bu − g)_q⁺)², whose gradient is the
//! residual of (11), R(u) = Ku − f + (1/ε) BᵀW(Bu − g)⁺. Each step solves with the Jacobian
//! K + (1/ε) B_AᵀW_A B_A of the active points A (where u_n > g), refactorised numerically on
//! the stiffness's symbolic factorisation. Steps are full (the primal–dual active-set method)
//! until an active set repeats; then the exact line search on Π breaks the cycle, so that the
//! iteration converges from any start. (A monotone line search on every step is far slower at
//! small ε: the valley of Π is so narrow that a wrong active set allows only tiny steps.) Converged means the active set did not change over the last step
//! and ‖R‖ is below a relative tolerance; anything else is reported as not converged.

use std::collections::HashSet;
use std::ops::ControlFlow;
use std::time::Instant;

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::{MatMut, Side};

use crate::fem::SymCsc;

/// The trace operator B on the free dofs: for each contact point, the free dofs and the
/// coefficients giving u_n there.
#[derive(Clone, Debug, Default)]
pub struct Trace {
    pub rows: Vec<Vec<(usize, f64)>>,
}

impl Trace {
    pub fn apply(&self, u: &[f64]) -> Vec<f64> {
        self.rows
            .iter()
            .map(|row| row.iter().map(|&(d, c)| c * u[d]).sum())
            .collect()
    }

    /// y += Bᵀ x.
    pub fn add_transpose(&self, x: &[f64], y: &mut [f64]) {
        for (row, &xq) in self.rows.iter().zip(x) {
            for &(d, c) in row {
                y[d] += c * xq;
            }
        }
    }
}

/// One instance of (11) on a mesh.
pub struct Penalty<'a> {
    /// K on the free dofs.
    pub stiffness: &'a SymCsc,
    /// Its symbolic Cholesky factorisation (shared by every Jacobian: same pattern).
    pub symbolic: &'a SymbolicLlt<usize>,
    /// f on the free dofs.
    pub load: &'a [f64],
    pub trace: &'a Trace,
    /// Rule weights w_q and gap g(x_q) at the contact points.
    pub weight: &'a [f64],
    pub gap: &'a [f64],
    pub epsilon: f64,
}

#[derive(Clone, Copy, Debug)]
pub struct NewtonOptions {
    pub max_iterations: usize,
    /// Relative residual ‖R‖ / max(‖Ku‖, ‖f‖, ‖BᵀWp‖) below which an unchanged active set is
    /// accepted as converged.
    pub rtol: f64,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions {
            max_iterations: 60,
            rtol: 1e-9,
        }
    }
}

/// The state after `iteration` Newton steps, reported to the caller as it goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iteration {
    pub iteration: usize,
    pub residual: f64,
    pub active: usize,
    /// The line search step that led here (1 for a full Newton step).
    pub step: f64,
}

#[derive(Clone, Debug)]
pub struct NewtonResult {
    /// Displacement on the free dofs.
    pub u: Vec<f64>,
    /// u_n − g at the contact points.
    pub violation: Vec<f64>,
    pub iterations: usize,
    pub converged: bool,
    pub residual: f64,
    pub history: Vec<Iteration>,
    pub factorization_ms: f64,
}

#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    #[error("the solve was cancelled")]
    Cancelled,
    #[error("the Jacobian is not positive definite ({0}); is the body held against rigid motion?")]
    Factorization(String),
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// Positions in the stiffness's values of the penalty contributions of each contact point:
/// (position, product of the two trace coefficients).
fn penalty_positions(k: &SymCsc, trace: &Trace) -> Vec<Vec<(usize, f64)>> {
    trace
        .rows
        .iter()
        .map(|row| {
            let mut out = Vec::with_capacity(row.len() * row.len());
            for &(r, cr) in row {
                for &(c, cc) in row {
                    if r >= c {
                        let pos = k.position(r, c).expect("trace dofs of one edge share a cell");
                        out.push((pos, cr * cc));
                    }
                }
            }
            out
        })
        .collect()
}

/// Solve (11) from `initial` (zero when None), reporting each iteration to `on_iteration`,
/// which may cancel the solve.
pub fn solve(
    pb: &Penalty,
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<NewtonResult, SolveError> {
    let k = pb.stiffness;
    let n = k.n;
    let inv_eps = 1.0 / pb.epsilon;
    let mut u = initial.map_or_else(|| vec![0.0; n], <[f64]>::to_vec);
    let positions = penalty_positions(k, pb.trace);
    let mut previous_active: Option<Vec<bool>> = None;
    let mut history = Vec::new();
    let mut factorization_ms = 0.0;
    let mut step = 1.0;
    let mut seen: HashSet<Vec<bool>> = HashSet::new();
    for it in 0.. {
        let ku = k.mul(&u);
        let bu = pb.trace.apply(&u);
        let s: Vec<f64> = bu.iter().zip(pb.gap).map(|(v, g)| v - g).collect();
        let active: Vec<bool> = s.iter().map(|&v| v > 0.0).collect();
        let force: Vec<f64> = s
            .iter()
            .zip(pb.weight)
            .map(|(&v, w)| w * v.max(0.0) * inv_eps)
            .collect();
        let mut contact = vec![0.0; n];
        pb.trace.add_transpose(&force, &mut contact);
        let r: Vec<f64> = (0..n).map(|i| ku[i] - pb.load[i] + contact[i]).collect();
        let scale = norm(&ku).max(norm(pb.load)).max(norm(&contact));
        let residual = if scale > 0.0 { norm(&r) / scale } else { 0.0 };
        let info = Iteration {
            iteration: it,
            residual,
            active: active.iter().filter(|&&a| a).count(),
            step,
        };
        history.push(info);
        if on_iteration(&info).is_break() {
            return Err(SolveError::Cancelled);
        }
        let settled = previous_active.as_ref().is_none_or(|prev| *prev == active);
        if residual <= opts.rtol && settled {
            return Ok(NewtonResult {
                u,
                violation: s,
                iterations: it,
                converged: true,
                residual,
                history,
                factorization_ms,
            });
        }
        if it == opts.max_iterations || !residual.is_finite() {
            return Ok(NewtonResult {
                u,
                violation: s,
                iterations: it,
                converged: false,
                residual,
                history,
                factorization_ms,
            });
        }

        // Newton direction: (K + (1/ε) B_AᵀW_A B_A) d = −R.
        let t0 = Instant::now();
        let mut values = k.values.clone();
        for (q, pos) in positions.iter().enumerate().filter(|(q, _)| active[*q]) {
            for &(p, c) in pos {
                values[p] += pb.weight[q] * inv_eps * c;
            }
        }
        let llt = Llt::try_new_with_symbolic(pb.symbolic.clone(), k.view(&values), Side::Lower)
            .map_err(|e| SolveError::Factorization(format!("{e:?}")))?;
        let mut d: Vec<f64> = r.iter().map(|v| -v).collect();
        llt.solve_in_place(MatMut::from_column_major_slice_mut(&mut d, n, 1));
        factorization_ms += t0.elapsed().as_secs_f64() * 1e3;

        // Full semismooth Newton steps (a primal–dual active-set iteration) unless this
        // active set was met before: then the iteration may cycle, and the exact minimiser of
        // the convex Π along d is taken instead, which decreases Π strictly.
        step = 1.0;
        if !seen.insert(active.clone()) {
            let kd = k.mul(&d);
            let bd = pb.trace.apply(&d);
            let lin = dot(&ku, &d) - dot(pb.load, &d);
            step = exact_step(&s, &bd, pb.weight, inv_eps, lin, dot(&d, &kd));
        }
        for (ui, di) in u.iter_mut().zip(&d) {
            *ui += step * di;
        }
        previous_active = Some(active);
    }
    unreachable!("the loop returns")
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
