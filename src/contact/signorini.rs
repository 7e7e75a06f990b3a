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

use super::newton::{
    Assessment, Iteration, NewtonOptions, NewtonResult, SemismoothLaw, Verdict, count, norm,
};
use super::penalty::{Penalty, active_forces, apply, on_points};
use crate::error::{Diagnosis, SolveError};

/// The complementarity law on the multipliers y at the rule's points (`.0` at ε = 0).
struct Complementarity<'a, 'b>(&'b Penalty<'a>);

impl SemismoothLaw for Complementarity<'_, '_> {
    type States = Vec<bool>;
    /// s = u_n − g = d − Gy.
    type Values = Vec<f64>;
    const CYCLE_STOPS: bool = true;

    /// The active set A = {q : y_q + c_q s_q > 0}, c_q = 1/G_qq, and the natural residual.
    fn assess(
        &self,
        y: &[f64],
        _: Option<&Vec<bool>>,
        opts: &NewtonOptions,
    ) -> Assessment<Vec<bool>, Vec<f64>> {
        let g = self.0.coupling;
        let d = self.0.free_violation;
        let n = y.len();
        let support: Vec<usize> = (0..n).filter(|&q| y[q] != 0.0).collect();
        let gy = apply(g, y, &support);
        let s: Vec<f64> = (0..n).map(|q| d[q] - gy[q]).collect();
        let active: Vec<bool> = (0..n).map(|q| y[q] + s[q] / g[(q, q)] > 0.0).collect();
        // The natural residual of the complementarity, y − (y + c s)⁺ in force units: zero
        // exactly when y ≥ 0, s ≤ 0 and y s = 0. On an iterate of this method (s = 0 on A,
        // y = 0 off it) it is the penetration c s⁺ and the tension y⁻; from another start it
        // also sees a force pressing across a gap (y > 0 where s < 0).
        let bad: Vec<f64> = (0..n)
            .map(|q| (y[q] - (y[q] + s[q] / g[(q, q)]).max(0.0)).abs())
            .collect();
        // Relative to the forces; from zero forces, a penetration of any size is the whole of
        // the answer still missing (1), not a residual in force units to compare with rtol.
        let scale = norm(y);
        let missing = norm(&bad);
        let residual = if scale > 0.0 {
            missing / scale
        } else if missing > 0.0 {
            1.0
        } else {
            0.0
        };
        Assessment {
            active: count(&active),
            states: active,
            residual,
            verdict: if residual <= opts.rtol {
                Verdict::Converged
            } else {
                Verdict::Continue
            },
            values: s,
        }
    }

    /// G_AA y_A = d_A, y = 0 off A.
    fn target(&self, _: &[f64], now: &Assessment<Vec<bool>, Vec<f64>>) -> Result<Vec<f64>, Diagnosis> {
        let exact = Penalty {
            epsilon: 0.0,
            ..*self.0
        };
        let a: Vec<usize> = (0..now.states.len()).filter(|&q| now.states[q]).collect();
        Ok(active_forces(&exact, &a))
    }

    /// The primal–dual active-set method takes the target itself.
    fn update(&self, y: &mut Vec<f64>, target: Vec<f64>, _: f64) {
        *y = target;
    }
}

/// Solve the exact-constraint problem (`pb.epsilon` is ignored), from the multipliers
/// `initial` when given.
pub fn solve_exact(
    pb: &Penalty,
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<NewtonResult, SolveError> {
    on_points(&Complementarity(pb), pb, initial, opts, on_iteration)
}
