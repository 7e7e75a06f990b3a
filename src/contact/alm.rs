//! The augmented Lagrangian method (docs/design.md §10): the exact constraint u_n − g ≤ 0 at
//! the rule's points, reached at a finite, well-conditioned penalty parameter ε by Uzawa
//! updates of the multiplier λ (the contact pressure per unit length at the points) around the
//! penalty Newton of [`super::penalty`].
//!
//! With λ_k fixed, the inner problem minimises the augmented Lagrangian
//! ½uᵀKu − fᵀu + (1/2ε) Σ_q w_q ((u_n − g + ελ_k)_q⁺)², whose contact pressure is
//! (λ_k + (u_n − g)/ε)⁺: it is the penalty problem (11) with the violation shifted by ελ_k,
//! i.e. the free violation d = Bu₀ − g replaced by d + ελ_k, on the same condensed operator
//! G = B K⁻¹ Bᵀ. Its solution gives the next multiplier λ_{k+1} = (λ_k + (u_n − g)/ε)⁺
//! (Uzawa, Powell–Hestenes–Rockafellar). At a fixed point λ = (λ + s/ε)⁺, which is exactly
//! the complementarity λ ≥ 0, s ≤ 0, λ·s = 0 of the exact constraint: no penalty error.
//!
//! Why Uzawa around the penalty Newton, and a Newton step on the multiplier only where it is
//! unique: the inner problem is the penalty problem, well posed for *every* rule, also those
//! whose points outnumber the normal displacements (M2 = Q1 + gauss2, Q1 + simpson). There
//! G_AA is singular, the exact multipliers are not unique, and a Newton step on them
//! (Alart–Curnier, or [`super::signorini`]) has no unique solution; Uzawa still converges in u,
//! and which of the many multipliers it ends at depends on the start and the path. Its price
//! is a linear rate: each update multiplies the multiplier's error in a mode of compliance σ
//! (displacement per unit pressure) by ε/(ε + σ), slow for the fine modes, and with a kernel
//! the multiplier also drifts along it at the rate s/ε (one point of an edge penetrating, the
//! other separated, the edge's nodal forces unchanged): there a small ε (κ = εE/h ≈ 1e-5)
//! converges in a few updates, ε = 1e-3 may not in [`MAX_OUTER`]. Where the multipliers are
//! unique (`unique`), once the active set A repeats between two updates, the Newton step on
//! the multiplier jumps to the updates' fixed point on A, G_AA y_A = d_A, dropping points
//! whose force comes out as tension (the primal–dual active-set rule); the next update checks
//! it. On the paper's problem at ε = 1e-3 this takes 3 to 7 updates at levels 0–5, each one
//! or two warm-started inner Newton steps (tests/numerics/methods.rs, docs/convergence.md).
//!
//! Stopping test: the relative change of the contact forces ‖W(λ_{k+1} − λ_k)‖/‖Wλ_{k+1}‖ —
//! the penetration of the active points in force units, ‖W s⁺‖/ε — below the tolerance, plus
//! the floor that round-off in s sets (as in [`super::penalty`]).

use std::collections::HashSet;
use std::ops::ControlFlow;

use super::newton::{Iteration, NewtonOptions, NewtonResult, norm};
use super::penalty::{self, Penalty, active_forces};
use crate::error::{Diagnosis, SolveError};

/// The largest number of outer (multiplier) updates.
pub const MAX_OUTER: usize = 500;

/// Relative size of the round-off in s = d − Gy, as in [`super::penalty`].
const ROUNDOFF: f64 = 16.0 * f64::EPSILON;

/// The ALM's answer: the last inner Newton's result (forces y = Wλ, violation u_n − g, the
/// inner iterations summed) and the number of multiplier updates.
#[derive(Clone, Debug)]
pub struct AlmResult {
    /// The last inner Newton's result, its iterations summed over the updates.
    pub newton: NewtonResult,
    /// Multiplier updates (outer iterations).
    pub outer: usize,
}

/// Solve the exact-constraint problem by the augmented Lagrangian at `pb.epsilon` > 0, to the
/// relative `tolerance` on the multiplier's change, from the contact forces `initial` when
/// given; each inner Newton iteration is reported to `on_iteration`, which may cancel.
/// `unique`: the rule has no more points than normal displacements, so that the Newton step on
/// the multiplier is well defined (otherwise plain Uzawa).
pub fn solve(
    pb: &Penalty,
    unique: bool,
    tolerance: f64,
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<AlmResult, SolveError> {
    let n = pb.coupling.nrows();
    let eps = pb.epsilon;
    let w = pb.weight;
    let d = pb.free_violation;
    let mut forces: Vec<f64> = initial
        .filter(|y| y.len() == n)
        .map_or_else(|| vec![0.0; n], |y| y.iter().map(|v| v.max(0.0)).collect());
    // λ per unit length.
    let mut lambda: Vec<f64> = (0..n).map(|q| forces[q] / w[q]).collect();
    // The inner solve must be more accurate than the outer test, else a warm start that
    // already meets the inner test is accepted unchanged and the updates stall.
    let inner_opts = NewtonOptions {
        rtol: opts.rtol.min(0.01 * tolerance),
        ..*opts
    };
    let mut inner_total = 0;
    let mut history = Vec::new();
    let mut previous_active: Option<Vec<bool>> = None;
    let mut tried: HashSet<Vec<usize>> = HashSet::new();
    for outer in 1..=MAX_OUTER {
        let shifted: Vec<f64> = (0..n).map(|q| d[q] + eps * lambda[q]).collect();
        let inner = Penalty {
            free_violation: &shifted,
            ..*pb
        };
        let mut result = penalty::solve(&inner, Some(&forces), &inner_opts, on_iteration)?;
        inner_total += result.iterations;
        history.append(&mut result.history);
        // λ_{k+1} = (λ_k + s/ε)⁺ with s = u_n − g: the inner problem's raw pressure.
        let next: Vec<f64> = result.violation.iter().map(|&v| v.max(0.0) / eps).collect();
        let violation: Vec<f64> = (0..n).map(|q| result.violation[q] - eps * lambda[q]).collect();
        let change: Vec<f64> = (0..n).map(|q| w[q] * (next[q] - lambda[q])).collect();
        let size: Vec<f64> = (0..n).map(|q| w[q] * next[q]).collect();
        // Round-off in s (and so in s/ε) below which the change is noise, where the point may
        // be active: one out of contact by more than it has λ_{k+1} = 0 exactly (a far point's
        // round-off O(|g|) loosened the test until a press of 1e-12 stopped at the penalty's
        // answer, P 1.6e-3 low).
        let floor: Vec<f64> = (0..n)
            .map(|q| {
                let noise = ROUNDOFF * (d[q].abs() + (eps * lambda[q]).abs());
                if d[q].is_finite() && result.violation[q] > -noise {
                    w[q] * noise / eps
                } else {
                    0.0
                }
            })
            .collect();
        let scale = norm(&size);
        let residual = if scale > 0.0 {
            norm(&change) / scale
        } else {
            norm(&change)
        };
        let done = result.converged && norm(&change) <= tolerance * scale + norm(&floor);
        let active: Vec<bool> = next.iter().map(|&l| l > 0.0).collect();
        lambda = next;
        forces = result.forces.clone();
        // The Newton step on the multiplier (Alart–Curnier) once the active set repeats: the
        // fixed point of the updates on A, G_AA y_A = d_A, with the points whose force comes
        // out as tension dropped from A until every force is a compression (the primal–dual
        // active-set rule). The next update checks it and corrects A if need be; an A already
        // jumped to is not jumped to again (no cycle).
        if unique && !done && previous_active.as_ref() == Some(&active) {
            let mut a: Vec<usize> = (0..n).filter(|&q| active[q]).collect();
            let exact = Penalty { epsilon: 0.0, ..*pb };
            let y = loop {
                let y = active_forces(&exact, &a);
                let before = a.len();
                a.retain(|&q| y[q] >= 0.0);
                if a.len() == before {
                    break y;
                }
            };
            if y.iter().all(|v| v.is_finite()) && tried.insert(a) {
                lambda = (0..n).map(|q| y[q] / w[q]).collect();
                forces = y;
            }
        }
        previous_active = Some(active);
        if done || !result.converged || !residual.is_finite() || outer == MAX_OUTER {
            let diagnosis = if done {
                None
            } else if let Some(inner) = result.failure() {
                Some(Diagnosis::Inner {
                    outer,
                    inner: Box::new(inner),
                })
            } else {
                Some(Diagnosis::Updates {
                    updates: outer,
                    change: residual,
                })
            };
            let newton = NewtonResult {
                forces,
                violation,
                iterations: inner_total,
                converged: done,
                residual,
                history,
                diagnosis,
            };
            return Ok(AlmResult { newton, outer });
        }
    }
    unreachable!("the loop returns at MAX_OUTER")
}
