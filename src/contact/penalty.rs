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

use std::collections::HashSet;
use std::ops::ControlFlow;

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

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

/// The stopping rules of the active-set Newton iteration.
#[derive(Clone, Copy, Debug)]
pub struct NewtonOptions {
    /// The most Newton iterations before giving up (not converged).
    pub max_iterations: usize,
    /// Relative residual ‖Bᵀ(Wp − y)‖ / ‖BᵀWp‖ below which an unchanged active set is accepted
    /// (plus the floor that round-off in u_n − g sets at small ε).
    pub rtol: f64,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions {
            max_iterations: 100,
            rtol: 1e-9,
        }
    }
}

/// The state after `iteration` Newton steps, reported to the caller as it goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iteration {
    /// Newton steps taken so far.
    pub iteration: usize,
    /// The relative residual of [`NewtonOptions::rtol`] after them.
    pub residual: f64,
    /// The number of active points (u_n − g > 0).
    pub active: usize,
    /// The line search step that led here (1 for a full Newton step).
    pub step: f64,
}

/// The result of an active-set Newton solve on the rule's points.
#[derive(Clone, Debug)]
pub struct NewtonResult {
    /// Contact forces y = W p at the rule's points (the warm start of a later solve).
    pub forces: Vec<f64>,
    /// u_n − g at the contact points.
    pub violation: Vec<f64>,
    /// Newton iterations taken.
    pub iterations: usize,
    /// Whether the convergence test of [`NewtonOptions`] was met.
    pub converged: bool,
    /// The final relative residual ([`NewtonOptions::rtol`]).
    pub residual: f64,
    /// Every iteration, in order.
    pub history: Vec<Iteration>,
    /// Why the solve did not converge, when it did not.
    pub diagnosis: Option<String>,
}

use crate::error::SolveError;

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

/// Why an iteration stopped short: the iteration limit, or a residual that is not finite.
pub(crate) fn stalled(iterations: usize, residual: f64) -> String {
    if residual.is_finite() {
        format!("no convergence in {iterations} Newton iterations (relative residual {residual:.1e})")
    } else {
        "the residual is not finite".to_string()
    }
}

/// One iterate of an active-set Newton on the contact forces, at the rule's points.
pub(crate) struct Iterate<'a> {
    /// u_n − g (or a positive multiple of it): the point is active where it is > 0.
    pub gap: &'a [f64],
    /// The round-off in `gap` ([`round_off`]).
    pub noise: &'a [f64],
    /// In force units: the forces the displacement implies, the forces assumed, the mismatch
    /// of the two (the residual R), and the round-off floor of the implied forces.
    pub implied: &'a [f64],
    pub assumed: &'a [f64],
    pub mismatch: &'a [f64],
    pub floor: &'a [f64],
}

/// What [`Progress::measure`] finds of an iterate.
pub(crate) struct Measure {
    /// The active set: the points with `gap` > 0.
    pub active: Vec<bool>,
    /// ‖R‖ relative to the larger of the implied and the assumed forces (0 with no force).
    pub residual: f64,
    /// The active set is the previous iterate's, but for points whose sign is round-off.
    pub settled: bool,
    /// ‖R‖ within the relative tolerance plus the round-off floor.
    pub accurate: bool,
    /// Round-off alone could account for forces as large as the forces themselves: no
    /// iterate can be certified (the penalty's ε too small for double precision).
    pub swamped: bool,
}

/// The bookkeeping of an active-set Newton iteration, shared by the penalty (11), the exact
/// multipliers ([`super::signorini`]) and Nitsche ([`super::nitsche`]): each iteration
/// recorded and reported as it goes (the caller may cancel), the active sets seen (a repeated
/// one calls for a damped step), the convergence test, and the result.
pub(crate) struct Progress<'a> {
    opts: &'a NewtonOptions,
    on_iteration: &'a mut dyn FnMut(&Iteration) -> ControlFlow<()>,
    history: Vec<Iteration>,
    previous: Option<Vec<bool>>,
    seen: HashSet<Vec<bool>>,
}

impl<'a> Progress<'a> {
    pub fn new(
        opts: &'a NewtonOptions,
        on_iteration: &'a mut dyn FnMut(&Iteration) -> ControlFlow<()>,
    ) -> Self {
        Progress {
            opts,
            on_iteration,
            history: Vec::new(),
            previous: None,
            seen: HashSet::new(),
        }
    }

    /// Record iteration `iteration` (reached by `step`) and report it; the caller's break is
    /// [`SolveError::Cancelled`].
    pub fn record(
        &mut self,
        iteration: usize,
        residual: f64,
        active: &[bool],
        step: f64,
    ) -> Result<(), SolveError> {
        let info = Iteration {
            iteration,
            residual,
            active: active.iter().filter(|&&a| a).count(),
            step,
        };
        self.history.push(info);
        if (self.on_iteration)(&info).is_break() {
            return Err(SolveError::Cancelled);
        }
        Ok(())
    }

    /// Measure the iterate `x` against the tolerance and the previous active set, and
    /// [`Progress::record`] it.
    pub fn measure(&mut self, iteration: usize, step: f64, x: &Iterate) -> Result<Measure, SolveError> {
        let norm = |v: &[f64]| dot(v, v).sqrt();
        let active: Vec<bool> = x.gap.iter().map(|&v| v > 0.0).collect();
        let scale = norm(x.implied).max(norm(x.assumed));
        let residual = if scale > 0.0 {
            norm(x.mismatch) / scale
        } else {
            0.0
        };
        self.record(iteration, residual, &active, step)?;
        let settled = self.previous.as_ref().is_none_or(|prev| {
            (0..active.len()).all(|q| prev[q] == active[q] || x.gap[q].abs() <= x.noise[q])
        });
        let floor = norm(x.floor);
        Ok(Measure {
            active,
            residual,
            settled,
            accurate: norm(x.mismatch) <= self.opts.rtol * scale + floor,
            swamped: scale > 0.0 && floor > 0.5 * scale,
        })
    }

    /// Whether `active` was seen before (and remember it).
    pub fn repeated(&mut self, active: &[bool]) -> bool {
        !self.seen.insert(active.to_vec())
    }

    /// On to the next iterate: `active` becomes the previous active set.
    pub fn advance(&mut self, active: Vec<bool>) {
        self.previous = Some(active);
    }

    /// The result after `iterations` iterations, with the history recorded.
    pub fn finish(
        self,
        forces: Vec<f64>,
        violation: Vec<f64>,
        iterations: usize,
        converged: bool,
        residual: f64,
        diagnosis: Option<String>,
    ) -> NewtonResult {
        NewtonResult {
            forces,
            violation,
            iterations,
            converged,
            residual,
            history: self.history,
            diagnosis,
        }
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
    let inv_eps = 1.0 / pb.epsilon;
    let d = pb.free_violation;
    let mut y = initial
        .filter(|y| y.len() == n)
        .map_or_else(|| vec![0.0; n], <[f64]>::to_vec);
    let mut progress = Progress::new(opts, on_iteration);
    let mut step = 1.0;
    for it in 0.. {
        let support: Vec<usize> = (0..n).filter(|&q| y[q] != 0.0).collect();
        let gy = apply(pb.coupling, &y, &support);
        let s: Vec<f64> = (0..n).map(|q| d[q] - gy[q]).collect();
        let noise = round_off(d, &gy);
        // R = Bᵀ(Wp − y): the contact forces the displacement implies against those assumed.
        let force: Vec<f64> = (0..n).map(|q| pb.weight[q] * s[q].max(0.0) * inv_eps).collect();
        let mismatch: Vec<f64> = (0..n).map(|q| force[q] - y[q]).collect();
        let floor: Vec<f64> = (0..n).map(|q| pb.weight[q] * noise[q] * inv_eps).collect();
        let m = progress.measure(
            it,
            step,
            &Iterate {
                gap: &s,
                noise: &noise,
                implied: &force,
                assumed: &y,
                mismatch: &mismatch,
                floor: &floor,
            },
        )?;
        let done = m.accurate && m.settled && !m.swamped;
        if done || m.swamped || it == opts.max_iterations || !m.residual.is_finite() {
            let diagnosis = (!done).then(|| {
                if m.swamped {
                    format!(
                        "ε = {:e} is below what double precision resolves here: round-off in u_n − g, amplified by 1/ε, is as large as the contact forces; use a larger ε (or --kappa), or ε = 0 for the exact constraint",
                        pb.epsilon
                    )
                } else {
                    stalled(it, m.residual)
                }
            });
            return Ok(progress.finish(y, s, it, done, m.residual, diagnosis));
        }
        let a: Vec<usize> = (0..n).filter(|&q| m.active[q]).collect();
        let target = active_forces(pb, &a);
        step = 1.0;
        if progress.repeated(&m.active) {
            let delta: Vec<f64> = (0..n).map(|q| target[q] - y[q]).collect();
            let moved: Vec<usize> = (0..n).filter(|&q| delta[q] != 0.0).collect();
            let gd = apply(pb.coupling, &delta, &moved);
            let b: Vec<f64> = gd.iter().map(|v| -v).collect();
            step = exact_step(&s, &b, pb.weight, inv_eps, dot(&y, &gd), dot(&delta, &gd));
        }
        for q in 0..n {
            y[q] += step * (target[q] - y[q]);
        }
        progress.advance(m.active);
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

    /// The bookkeeping on a hand-made iterate: implied forces (3, 0) against assumed (0, 4)
    /// give R = (3, −4), ‖R‖ = 5 against the scale max(3, 4) = 4; a floor of norm 3 > 4/2
    /// swamps them; a sign change within the noise keeps the active set settled.
    #[test]
    fn progress_measures_by_hand() {
        let opts = NewtonOptions::default();
        let mut calls = 0;
        let mut report = |_: &Iteration| {
            calls += 1;
            if calls < 4 {
                ControlFlow::Continue(())
            } else {
                ControlFlow::Break(())
            }
        };
        let mut progress = Progress::new(&opts, &mut report);
        let zero = [0.0, 0.0];
        let at = |gap, noise, floor| Iterate {
            gap,
            noise,
            implied: &[3.0, 0.0],
            assumed: &[0.0, 4.0],
            mismatch: &[3.0, -4.0],
            floor,
        };
        let m = progress.measure(0, 1.0, &at(&[1.0, -1.0], &zero, &zero)).unwrap();
        assert_eq!(m.active, [true, false]);
        assert_eq!(m.residual, 1.25);
        assert!(m.settled && !m.accurate && !m.swamped);
        assert!(!progress.repeated(&m.active) && progress.repeated(&m.active));
        progress.advance(m.active);
        // The first point turns inactive by more than its noise: not settled.
        let m = progress
            .measure(1, 0.5, &at(&[-1.0, -1.0], &zero, &zero))
            .unwrap();
        assert!(!m.settled);
        // … by no more than its noise: settled; a floor of norm 3 swamps the scale 4.
        let m = progress
            .measure(2, 1.0, &at(&[-1.0, -1.0], &[1.0, 0.0], &[3.0, 0.0]))
            .unwrap();
        assert!(m.settled && m.swamped && !m.accurate);
        // The fourth report is cancelled; the history keeps every iteration recorded.
        assert!(matches!(
            progress.measure(3, 1.0, &at(&zero, &zero, &zero)),
            Err(SolveError::Cancelled)
        ));
        let result = progress.finish(vec![], vec![], 3, false, 1.5, Some(stalled(3, 1.5)));
        let steps: Vec<f64> = result.history.iter().map(|i| i.step).collect();
        assert_eq!(steps, [1.0, 0.5, 1.0, 1.0]);
        assert_eq!(
            result.diagnosis.as_deref(),
            Some("no convergence in 3 Newton iterations (relative residual 1.5e0)")
        );
        assert_eq!(stalled(3, f64::NAN), "the residual is not finite");
    }

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
