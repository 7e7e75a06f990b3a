//! The semismooth Newton on the scaled forces ỹ at the edge points (module doc of [`super`]).

use std::ops::ControlFlow;

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use super::operator::Operator;
use crate::contact::newton::{
    Assessment, ForceBalance, Iteration, NewtonOptions, NewtonResult, SemismoothLaw, Verdict, drive,
};
use crate::contact::penalty::{active_block, dot, round_off};
use crate::error::{Diagnosis, SolveError};

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

/// Nitsche's law on the scaled forces ỹ at the edge points (module doc of [`super`]).
struct NitscheLaw<'a> {
    op: &'a Operator,
    /// c_q = w_q / γ_q.
    c: &'a [f64],
    /// d = −Γg.
    d: &'a [f64],
}

/// What Nitsche's law computes of an iterate ỹ.
struct Values {
    /// v = d − H ỹ.
    v: Vec<f64>,
    /// The residual Γ(c v⁺ − ỹ).
    r: Vec<f64>,
}

impl NitscheLaw<'_> {
    /// v, H ỹ and the residual Γ(c v⁺ − ỹ) of ỹ = `y`.
    fn mismatch(&self, y: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let (gamma, c) = (&self.op.gamma, self.c);
        let (v, hy) = gap_function(&self.op.h, self.d, y);
        let r = (0..y.len())
            .map(|q| gamma[q] * (c[q] * v[q].max(0.0) - y[q]))
            .collect();
        (v, hy, r)
    }
}

impl SemismoothLaw for NitscheLaw<'_> {
    type States = Vec<bool>;
    type Values = Values;

    fn assess(
        &self,
        y: &[f64],
        previous: Option<&Vec<bool>>,
        opts: &NewtonOptions,
    ) -> Assessment<Vec<bool>, Values> {
        let (gamma, c) = (&self.op.gamma, self.c);
        let n = y.len();
        let (v, hy, r) = self.mismatch(y);
        // In force units: the contact forces w p against Γỹ, and the round-off floor in v.
        let force: Vec<f64> = (0..n).map(|q| gamma[q] * c[q] * v[q].max(0.0)).collect();
        let scaled: Vec<f64> = (0..n).map(|q| gamma[q] * y[q]).collect();
        let noise = round_off(self.d, &hy);
        let floor: Vec<f64> = (0..n).map(|q| gamma[q] * c[q] * noise[q]).collect();
        let m = ForceBalance {
            gap: &v,
            noise: &noise,
            implied: &force,
            assumed: &scaled,
            mismatch: &r,
            floor: &floor,
        }
        .measure(previous, opts.rtol);
        let verdict = if m.settled && m.accurate && m.residual.is_finite() {
            Verdict::Converged
        } else {
            Verdict::Continue
        };
        m.assessment(verdict, Values { v, r })
    }

    fn target(&self, _: &[f64], now: &Assessment<Vec<bool>, Values>) -> Result<Vec<f64>, Diagnosis> {
        let a: Vec<usize> = (0..now.states.len()).filter(|&q| now.states[q]).collect();
        let params = &self.op.params;
        active_forces(&self.op.h, self.c, self.d, &a, params.theta == 1.0).ok_or(Diagnosis::Singular {
            theta: params.theta,
            gamma0: params.gamma0,
        })
    }

    /// Full steps; when an active set repeats, the step is halved until the residual
    /// ‖c v⁺ − ỹ‖ decreases.
    fn step(&self, y: &[f64], target: &[f64], now: &Assessment<Vec<bool>, Values>, repeated: bool) -> f64 {
        if !repeated {
            return 1.0;
        }
        let norm = |v: &[f64]| dot(v, v).sqrt();
        let n = y.len();
        let delta: Vec<f64> = (0..n).map(|q| target[q] - y[q]).collect();
        let r0 = norm(&now.values.r);
        let mut step = 0.5;
        while step > 1e-12 {
            let trial: Vec<f64> = (0..n).map(|q| y[q] + step * delta[q]).collect();
            if norm(&self.mismatch(&trial).2) < r0 {
                break;
            }
            step *= 0.5;
        }
        step
    }
}

/// The semismooth Newton on the scaled forces ỹ (module doc) from the forces `initial`:
/// ỹ, v = d − Hỹ and the result (its forces Γỹ, no violation).
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
    let y: Vec<f64> = initial
        .filter(|y| y.len() == n && y.iter().all(|v| v.is_finite()))
        .map_or_else(
            || vec![0.0; n],
            |y0| y0.iter().zip(gamma).map(|(a, g)| a / g).collect(),
        );
    let outcome = drive(&NitscheLaw { op, c, d }, y, opts, on_iteration)?;
    let y = outcome.x.clone();
    let v = outcome.last.values.v.clone();
    let scaled: Vec<f64> = (0..n).map(|q| gamma[q] * y[q]).collect();
    Ok((y, v, outcome.result(scaled, Vec::new())))
}
