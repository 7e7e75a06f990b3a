//! The semismooth Newton on the scaled forces ỹ at the edge points (module doc of [`super`]).

use std::ops::ControlFlow;

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use super::operator::Operator;
use crate::contact::penalty::{
    Iterate, Iteration, NewtonOptions, NewtonResult, Progress, active_block, dot, round_off, stalled,
};
use crate::error::SolveError;

/// ỹ_A from (W_A⁻¹Γ_A + H_AA) ỹ_A = d_A, zero off A (None when the system is singular). For
/// θ = 1 (`symmetric`) H = P_1 K_1⁻¹ P_1ᵀ, and the matrix is positive definite where the method
/// is stable (module doc): Cholesky, half of LU's work, with LU where Cholesky fails.
pub(super) fn active_forces(
    h: &Mat<f64>,
    c: &[f64],
    d: &[f64],
    a: &[usize],
    symmetric: bool,
) -> Option<Vec<f64>> {
    let mut y = vec![0.0; h.nrows()];
    if a.is_empty() {
        return Some(y);
    }
    let m = active_block(h, a, |q| 1.0 / c[q]);
    let rhs = Mat::<f64>::from_fn(a.len(), 1, |i, _| d[a[i]]);
    let sol = symmetric
        .then(|| m.llt(Side::Lower).ok())
        .flatten()
        .map_or_else(|| m.partial_piv_lu().solve(&rhs), |llt| llt.solve(&rhs));
    for (i, &q) in a.iter().enumerate() {
        y[q] = sol[(i, 0)];
    }
    y.iter().all(|v| v.is_finite()).then_some(y)
}

/// v = d − H ỹ for ỹ supported on `support`.
pub(super) fn gap_function(h: &Mat<f64>, d: &[f64], y: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = d.len();
    let mut hy = vec![0.0; n];
    for j in (0..n).filter(|&j| y[j] != 0.0) {
        let col = h.col(j);
        for (i, o) in hy.iter_mut().enumerate() {
            *o += col[i] * y[j];
        }
    }
    ((0..n).map(|q| d[q] - hy[q]).collect(), hy)
}

/// The semismooth Newton on the scaled forces ỹ (module doc): full steps; when an active set
/// repeats, the step is halved until the residual ‖c v⁺ − ỹ‖ decreases.
pub(super) fn newton(
    op: &Operator,
    c: &[f64],
    d: &[f64],
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<(Vec<f64>, Vec<f64>, NewtonResult), SolveError> {
    let n = d.len();
    let gamma = &op.gamma;
    // The forces y = Γỹ are the state kept between solves.
    let mut y: Vec<f64> = initial
        .filter(|y| y.len() == n && y.iter().all(|v| v.is_finite()))
        .map_or_else(
            || vec![0.0; n],
            |y0| y0.iter().zip(gamma).map(|(a, g)| a / g).collect(),
        );
    let mismatch = |y: &[f64]| -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let (v, hy) = gap_function(&op.h, d, y);
        let r = (0..n).map(|q| gamma[q] * (c[q] * v[q].max(0.0) - y[q])).collect();
        (v, hy, r)
    };
    let norm = |v: &[f64]| dot(v, v).sqrt();
    let mut progress = Progress::new(opts, on_iteration);
    let mut step = 1.0;
    for it in 0.. {
        let (v, hy, r) = mismatch(&y);
        // In force units: the contact forces w p against Γỹ, and the round-off floor in v.
        let force: Vec<f64> = (0..n).map(|q| gamma[q] * c[q] * v[q].max(0.0)).collect();
        let scaled: Vec<f64> = (0..n).map(|q| gamma[q] * y[q]).collect();
        let noise = round_off(d, &hy);
        let floor: Vec<f64> = (0..n).map(|q| gamma[q] * c[q] * noise[q]).collect();
        let m = progress.measure(
            it,
            step,
            &Iterate {
                gap: &v,
                noise: &noise,
                implied: &force,
                assumed: &scaled,
                mismatch: &r,
                floor: &floor,
            },
        )?;
        let done = m.settled && m.accurate && m.residual.is_finite();
        let a: Vec<usize> = (0..n).filter(|&q| m.active[q]).collect();
        let stop = done || it == opts.max_iterations || !m.residual.is_finite();
        let target = if stop {
            None
        } else {
            active_forces(&op.h, c, d, &a, op.params.theta == 1.0)
        };
        let Some(target) = target else {
            let diagnosis = (!done).then(|| {
                if stop {
                    stalled(it, m.residual)
                } else {
                    format!(
                        "the Newton system of the active set is singular (θ = {}, γ₀ = {}): choose a larger γ₀",
                        op.params.theta, op.params.gamma0
                    )
                }
            });
            let result = progress.finish(scaled, Vec::new(), it, done, m.residual, diagnosis);
            return Ok((y, v, result));
        };
        step = 1.0;
        let delta: Vec<f64> = (0..n).map(|q| target[q] - y[q]).collect();
        if progress.repeated(&m.active) {
            // A repeated active set: halve the step until the residual decreases.
            let r0 = norm(&r);
            step = 0.5;
            while step > 1e-12 {
                let trial: Vec<f64> = (0..n).map(|q| y[q] + step * delta[q]).collect();
                if norm(&mismatch(&trial).2) < r0 {
                    break;
                }
                step *= 0.5;
            }
        }
        for q in 0..n {
            y[q] += step * delta[q];
        }
        progress.advance(m.active);
    }
    unreachable!("the loop returns")
}
