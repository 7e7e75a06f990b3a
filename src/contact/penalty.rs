//! The penalised problem (8), (11) solved by semismooth Newton (DESIGN §3).
//!
//! Minimise Π(u) = ½ uᵀKu − fᵀu + (1/2ε) Σ_q w_q ((Bu − g)_q⁺)², whose gradient is the
//! residual of (11), R(u) = Ku − f + (1/ε) BᵀW(Bu − g)⁺. Each step solves with the Jacobian
//! K + (1/ε) B_AᵀW_A B_A of the active points A (where u_n > g), refactorised numerically on
//! the stiffness's symbolic factorisation, and a backtracking line search on Π makes it
//! converge from any start. Converged means the active set did not change over the last step
//! and ‖R‖ is below a relative tolerance; anything else is reported as not converged.

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

        // Backtracking (Armijo) on Π along d; Π is a convex piecewise quadratic in t.
        let kd = k.mul(&d);
        let bd = pb.trace.apply(&d);
        let (lin, quad) = (dot(&ku, &d) - dot(pb.load, &d), dot(&d, &kd));
        let energy = |t: f64| {
            let pen: f64 = (0..s.len())
                .map(|q| pb.weight[q] * (s[q] + t * bd[q]).max(0.0).powi(2))
                .sum();
            t * lin + 0.5 * t * t * quad + 0.5 * inv_eps * pen
        };
        let slope = dot(&r, &d);
        let e0 = energy(0.0);
        step = 1.0;
        if slope < 0.0 {
            while energy(step) > e0 + 1e-4 * step * slope && step > 1e-12 {
                step *= 0.5;
            }
        }
        for (ui, di) in u.iter_mut().zip(&d) {
            *ui += step * di;
        }
        previous_active = Some(active);
    }
    unreachable!("the loop returns")
}
