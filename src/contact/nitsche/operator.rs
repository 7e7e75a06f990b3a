//! The operator of one (rule, θ, γ₀): H = P_1 K_θ⁻¹ P_θᵀ by Woodbury's formula from the couplings
//! (module doc of [`super`]), and the maps back to σ_n.

use std::sync::Arc;

use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::{Accum, ColRef, Mat, Par, Side};

use super::couplings::Couplings;
use super::{NitscheParams, cache, couplings};
use crate::contact::{ContactPoints, Rule};
use crate::discretization::Discretization;
use crate::error::{InputFault, SolveError};

/// Everything one (rule, θ, γ₀) needs: H and the maps back to σ_n.
pub(super) struct Operator {
    rule: Rule,
    pub(super) params: NitscheParams,
    pub(super) couplings: Arc<Couplings>,
    pub(super) gamma: Vec<f64>,
    /// H = P_1 K_θ⁻¹ P_θᵀ: P_1 u = H ỹ for the scaled forces ỹ = Γ⁻¹y.
    pub(super) h: Mat<f64>,
    /// V = S K⁻¹ P_θᵀ: σ = (V + G_SS ZV) ỹ.
    v: Mat<f64>,
    /// Woodbury's correction ZV, for θ ≠ 0.
    correction: Option<Correction>,
}

/// ZV = θ C^½ N⁻¹ C^½ V (module doc) kept as N's Cholesky factor L (N = L Lᵀ) and
/// M = L⁻¹ C^½ V: ZV ỹ = θ C^½ L⁻ᵀ (M ỹ) costs a product and a triangular solve with one
/// right-hand side, and the operator one triangular solve with n right-hand sides fewer than
/// forming ZV.
pub(super) struct Correction {
    /// C^½, C = W Γ⁻¹ (W the weights).
    c_half: Vec<f64>,
    /// L, N's Cholesky factor.
    n_factor: Mat<f64>,
    /// M = L⁻¹ C^½ V.
    m: Mat<f64>,
}

impl Correction {
    /// ZV ỹ.
    fn zv(&self, theta: f64, y: &[f64]) -> Vec<f64> {
        let mut t = Mat::<f64>::zeros(y.len(), 1);
        faer::linalg::matmul::matmul(
            t.as_mut(),
            Accum::Replace,
            self.m.as_ref(),
            ColRef::from_slice(y).as_mat(),
            1.0,
            Par::Seq,
        );
        faer::linalg::triangular_solve::solve_upper_triangular_in_place(
            self.n_factor.transpose(),
            t.as_mut(),
            Par::Seq,
        );
        (0..y.len()).map(|i| theta * self.c_half[i] * t[(i, 0)]).collect()
    }
}

impl Operator {
    /// H, V and Woodbury's correction for θ, γ₀ (module doc): dense work on the points only.
    fn new(rule: Rule, cp: Arc<Couplings>, params: NitscheParams, young: f64) -> Result<Self, SolveError> {
        let n = cp.n();
        let theta = params.theta;
        let gamma: Vec<f64> = cp.points.iter().map(|q| params.gamma0 * young / q.h).collect();
        // c = W Γ⁻¹, D = θ c.
        let c: Vec<f64> = cp.points.iter().zip(&gamma).map(|(q, g)| q.weight / g).collect();
        // P_1 K⁻¹ P_θᵀ, U = P_1 K⁻¹ Sᵀ and V = S K⁻¹ P_θᵀ.
        let mut h = Mat::<f64>::from_fn(n, n, |i, j| {
            theta * cp.ss(i, j) - cp.sb(i, j) * gamma[j] - gamma[i] * theta * cp.bs(i, j)
                + gamma[i] * cp.bb(i, j) * gamma[j]
        });
        let v = Mat::<f64>::from_fn(n, n, |i, j| theta * cp.ss(i, j) - cp.sb(i, j) * gamma[j]);
        // Well-posedness: on every active set the symmetric part of the Jacobian is at least
        // K − κ (1/γ) SᵀWS with κ = (1 + θ)²/4 (Young's inequality on (1 + θ) σ_n v_n), so it
        // is positive definite for γ₀ > κ γ₀*; θ = −1 needs nothing.
        let kappa = (1.0 + theta).powi(2) / 4.0;
        let scaled = cp.scaled_ss(&c);
        let shifted = |factor: f64| {
            Mat::<f64>::from_fn(n, n, |i, j| f64::from(u8::from(i == j)) - factor * scaled[(i, j)])
        };
        // λ_max(C_γ^½ G_SS C_γ^½) = γ₀*/γ₀: computed only to say what γ₀ would do.
        let refused = || {
            let threshold = scaled
                .self_adjoint_eigenvalues(Side::Lower)
                .ok()
                .and_then(|e| e.last().copied())
                .map(|l| l * params.gamma0);
            SolveError::from(InputFault::Unstable {
                gamma0: params.gamma0,
                theta,
                threshold,
            })
        };
        if kappa > 0.0 && kappa != theta && shifted(kappa).llt(Side::Lower).is_err() {
            return Err(refused());
        }
        let mut correction = None;
        if theta != 0.0 {
            // Z = (I − D G_SS)⁻¹ D = θ C^½ N⁻¹ C^½ with N = I − θ C^½ G_SS C^½ = L Lᵀ symmetric,
            // positive definite when the check above passed (θ ≤ κ). With W = L⁻¹ C^½ V,
            // U Z V = θ (L⁻¹ C^½ Uᵀ)ᵀ W.
            let r: Vec<f64> = c.iter().map(|v| v.sqrt()).collect();
            let l = shifted(theta)
                .llt(Side::Lower)
                .map_err(|_| refused())?
                .L()
                .to_owned();
            drop(scaled);
            let par = crate::fem::dense_parallelism(n);
            let lower = |mut m: Mat<f64>| {
                faer::linalg::triangular_solve::solve_lower_triangular_in_place(l.as_ref(), m.as_mut(), par);
                m
            };
            let w = lower(Mat::<f64>::from_fn(n, n, |i, j| r[i] * v[(i, j)]));
            if theta == 1.0 {
                // Uᵀ = V (G is symmetric), so U Z V = MᵀM (M is `w` here): symmetric, its lower half alone.
                let mut wtw = Mat::<f64>::zeros(n, n);
                triangular::matmul(
                    wtw.as_mut(),
                    BlockStructure::TriangularLower,
                    Accum::Replace,
                    w.transpose(),
                    BlockStructure::Rectangular,
                    w.as_ref(),
                    BlockStructure::Rectangular,
                    1.0,
                    par,
                );
                for j in 0..n {
                    h[(j, j)] += wtw[(j, j)];
                    for i in j + 1..n {
                        h[(i, j)] += wtw[(i, j)];
                        h[(j, i)] += wtw[(i, j)];
                    }
                }
            } else {
                // C^½ Uᵀ, U = P_1 K⁻¹ Sᵀ = G_SS − Γ G_BS.
                let x = lower(Mat::<f64>::from_fn(n, n, |i, j| {
                    r[i] * (cp.ss(j, i) - gamma[j] * cp.bs(j, i))
                }));
                faer::linalg::matmul::matmul(h.as_mut(), Accum::Add, x.transpose(), w.as_ref(), theta, par);
            }
            correction = Some(Correction {
                c_half: r,
                n_factor: l,
                m: w,
            });
        }
        Ok(Operator {
            rule,
            params,
            couplings: cp,
            gamma,
            h,
            v,
            correction,
        })
    }

    /// The operator for (rule, θ, γ₀) on `disc`, reusing the last one when it matches.
    pub(super) fn of(
        disc: &Discretization,
        points: &ContactPoints,
        params: NitscheParams,
    ) -> Result<Arc<Self>, SolveError> {
        let cp = couplings(disc, points)?;
        let cache = cache(disc);
        let mut last = cache.operator.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(op) = last.as_ref()
            && op.rule == points.rule
            && op.params == params
            && Arc::ptr_eq(&op.couplings, &cp)
        {
            return Ok(op.clone());
        }
        let op = Arc::new(Operator::new(points.rule, cp, params, disc.material.young)?);
        *last = Some(op.clone());
        Ok(op)
    }

    /// u_n at the edge points and u_y at Γ_C's vertices for the scaled forces ỹ, and the
    /// nodal load f of K u = f.
    pub(super) fn fields(&self, y: &[f64], n_dofs: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let cp = &self.couplings;
        let n = cp.n();
        let theta = self.params.theta;
        let (g, col) = (cp.g.as_ref(), ColRef::from_slice);
        let (ss, bs, bb) = (
            g.submatrix(0, 0, n, n),
            g.submatrix(n, 0, n, n),
            g.submatrix(n, n, n, n),
        );
        // σ = (V + G_SS ZV) ỹ.
        let zvy = self.correction.as_ref().map(|c| c.zv(theta, y));
        let mut sigma = &self.v * col(y);
        if let Some(zvy) = &zvy {
            sigma += ss * col(zvy);
        }
        // K u = Sᵀ a + Bᵀ b with a = Dσ + θỹ, b = −Γỹ.
        let a: Vec<f64> = (0..n)
            .map(|q| theta * (cp.points[q].weight / self.gamma[q] * sigma[q] + y[q]))
            .collect();
        let b: Vec<f64> = (0..n).map(|q| -self.gamma[q] * y[q]).collect();
        let normal = bs * col(&a) + bb * col(&b);
        let (vertices, e) = (cp.vertex.nrows(), cp.vertex.as_ref());
        let vertex_uy = e.submatrix(0, 0, vertices, n) * col(&a) + e.submatrix(0, n, vertices, n) * col(&b);
        let normal: Vec<f64> = normal.iter().copied().collect();
        let vertex_uy: Vec<f64> = vertex_uy.iter().copied().collect();
        let mut f = vec![0.0; n_dofs];
        for (q, pt) in cp.points.iter().enumerate() {
            for &(d, c) in &pt.sigma {
                f[d] += c * a[q];
            }
            for &(d, c) in &pt.normal {
                f[d] += c * b[q];
            }
        }
        (normal, vertex_uy, f)
    }
}
