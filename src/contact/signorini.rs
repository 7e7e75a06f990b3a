//! The exact-constraint limit ε → 0 of (11): the Signorini problem (1) with the constraint
//! u_n ≤ g imposed at the rule's points by Lagrange multipliers, the contact forces y ≥ 0.
//!
//! Solved by the primal–dual active-set method (semismooth Newton on the complementarity
//! y ≥ 0, s = u_n − g ≤ 0, y·s = 0) on the condensed operator G = B K⁻¹ Bᵀ of
//! [`super::penalty`]: with A = {q : y_q + c_q s_q > 0}, c_q = 1/G_qq, solve G_AA y_A = d_A,
//! y = 0 off A, until A repeats itself. With the trapezoid rule (Simpson for Q2) these are
//! nodal multipliers: the exact-constraint twin of M3 (M4), riplab's reference solution.
//! A rule whose points outnumber the normal trace dofs (a kernel) has no unique multipliers
//! and is refused.

use std::ops::ControlFlow;

use super::penalty::{Iteration, NewtonOptions, NewtonResult, Penalty, Progress, active_forces, apply, dot};
use crate::error::SolveError;

/// Solve the exact-constraint problem (`pb.epsilon` is ignored), from the multipliers
/// `initial` when given.
pub fn solve_exact(
    pb: &Penalty,
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<NewtonResult, SolveError> {
    let g = pb.coupling;
    let n = g.nrows();
    let d = pb.free_violation;
    let exact = Penalty { epsilon: 0.0, ..*pb };
    let mut y = initial
        .filter(|y| y.len() == n)
        .map_or_else(|| vec![0.0; n], <[f64]>::to_vec);
    let mut progress = Progress::new(opts, on_iteration);
    for it in 0.. {
        let support: Vec<usize> = (0..n).filter(|&q| y[q] != 0.0).collect();
        let gy = apply(g, &y, &support);
        let s: Vec<f64> = (0..n).map(|q| d[q] - gy[q]).collect();
        let active: Vec<bool> = (0..n).map(|q| y[q] + s[q] / g[(q, q)] > 0.0).collect();
        // The natural residual of the complementarity, y − (y + c s)⁺ in force units: zero
        // exactly when y ≥ 0, s ≤ 0 and y s = 0. On an iterate of this method (s = 0 on A,
        // y = 0 off it) it is the penetration c s⁺ and the tension y⁻; from another start it
        // also sees a force pressing across a gap (y > 0 where s < 0).
        let bad: Vec<f64> = (0..n)
            .map(|q| (y[q] - (y[q] + s[q] / g[(q, q)]).max(0.0)).abs())
            .collect();
        let scale = dot(&y, &y).sqrt();
        let residual = if scale > 0.0 {
            dot(&bad, &bad).sqrt() / scale
        } else {
            dot(&bad, &bad).sqrt()
        };
        progress.record(it, residual, &active, 1.0)?;
        let repeated = progress.repeated(&active);
        let done = residual <= opts.rtol;
        if done || repeated || it == opts.max_iterations || !residual.is_finite() {
            let diagnosis = (!done).then(|| {
                if repeated {
                    format!("the active set cycles (after {it} iterations, relative residual {residual:.1e})")
                } else {
                    format!("no convergence in {it} iterations (relative residual {residual:.1e})")
                }
            });
            return Ok(progress.finish(y, s, it, done, residual, diagnosis));
        }
        let a: Vec<usize> = (0..n).filter(|&q| active[q]).collect();
        y = active_forces(&exact, &a);
    }
    unreachable!("the loop returns")
}
