//! The discrete Babuška–Brezzi (inf-sup) constants of (13) and (21), as docs/design.md §5 defines
//! them:
//!
//!   β_h² = λ_min(B A⁻¹ Bᵀ, M),   β̄_h² = λ_min(B A⁻¹ Bᵀ, Sᵀ M₁ S),
//!
//! A the H¹ Gram matrix of (7) on V_h, B_kj = I(φ_k^Q, (ψ_j)_n), M the exact L²(Γ_C) Gram
//! matrix of Q_h, S the smoothing q ↦ q̄ of (17) and M₁ the P1 mass matrix on Γ_C.
//!
//! Only the normal dofs on Γ_C enter B, so A⁻¹ is needed on those alone: the *trace
//! compliance* C = E A⁻¹ Eᵀ (E selecting u_y on Γ_C), read from one factorisation of A on
//! the stiffness's ordering (same pattern, Γ_C dofs last: see [`crate::fem::condense`]).
//! Every rule then costs only small dense work: B A⁻¹ Bᵀ = W T C Tᵀ W.

use faer::{Mat, Side};

use crate::contact::{ContactPoints, Rule, smoothed_pressure};
use crate::error::SolveError;
use crate::fem::condense::TraceFactor;
use crate::fem::quadrature::gauss_legendre;
use crate::fem::{Form, assemble};
use crate::solve::Discretization;

/// The estimate for one element × rule pair on one mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct InfSup {
    pub h: f64,
    pub beta: f64,
    pub beta_over_sqrt_h: f64,
    pub beta_bar: f64,
    pub beta_bar_over_sqrt_h: f64,
    /// Why β_h = 0 when Q_h has a kernel (more pressure dofs than normal-trace dofs).
    pub kernel: Option<String>,
}

/// C = E A⁻¹ Eᵀ on the Γ_C normal dofs (rule-independent, one per mesh).
pub struct TraceCompliance {
    pub c: Mat<f64>,
}

impl TraceCompliance {
    /// Assemble A on the mesh and condense it onto Γ_C on the stiffness's ordering.
    pub fn new(disc: &Discretization) -> Result<Self, SolveError> {
        let a = assemble(&disc.mesh, &disc.dofs, Form::H1);
        let factor = TraceFactor::new(&disc.ordering, &a)
            .map_err(|e| SolveError::Factorization(format!("the H¹ Gram matrix: {e}")))?;
        Ok(TraceCompliance {
            c: factor.compliance(),
        })
    }
}

/// The exact L²(Γ_C) Gram matrix of Q_h: on each edge, the Lagrange functions through the
/// rule's points of that edge, integrated exactly (3-point Gauss; degree ≤ 4).
pub fn pressure_mass(cp: &ContactPoints) -> Mat<f64> {
    let n = cp.len();
    let mut m = Mat::<f64>::zeros(n, n);
    let gauss = gauss_legendre(3);
    for (e, pts) in cp.edge_points.iter().enumerate() {
        let h = cp.vertex_x[e + 1] - cp.vertex_x[e];
        for &(xi, w) in &gauss {
            let phi = cp.edge_basis(e, (xi + 1.0) / 2.0);
            for a in 0..pts.len() {
                for b in 0..pts.len() {
                    m[(pts[a], pts[b])] += w / 2.0 * h * phi[a] * phi[b];
                }
            }
        }
    }
    m
}

/// The P1 mass matrix on the vertices of Γ_C.
pub fn p1_mass(x: &[f64]) -> Mat<f64> {
    let mut m = Mat::<f64>::zeros(x.len(), x.len());
    for e in 0..x.len() - 1 {
        let h = x[e + 1] - x[e];
        m[(e, e)] += h / 3.0;
        m[(e + 1, e + 1)] += h / 3.0;
        m[(e, e + 1)] += h / 6.0;
        m[(e + 1, e)] += h / 6.0;
    }
    m
}

/// The smoothing map S: q ↦ q̄ as a (vertices × points) matrix.
pub fn smoothing_matrix(cp: &ContactPoints) -> Mat<f64> {
    let mut s = Mat::<f64>::zeros(cp.vertex_x.len(), cp.len());
    let mut unit = vec![0.0; cp.len()];
    for k in 0..cp.len() {
        unit[k] = 1.0;
        for (i, v) in smoothed_pressure(cp, &unit).into_iter().enumerate() {
            s[(i, k)] = v;
        }
        unit[k] = 0.0;
    }
    s
}

/// B A⁻¹ Bᵀ = W T C Tᵀ W for the rule's points.
pub fn schur(cp: &ContactPoints, compliance: &Mat<f64>) -> Mat<f64> {
    let nc = compliance.nrows();
    let b = Mat::<f64>::from_fn(cp.len(), nc, |k, j| {
        let q = &cp.points[k];
        q.nodes
            .iter()
            .zip(&q.trace)
            .filter(|(n, _)| **n == j)
            .map(|(_, t)| q.weight * t)
            .sum()
    });
    &b * compliance * b.transpose()
}

/// λ_min(S, N) over the vectors with Nq ≠ 0 (N symmetric positive semi-definite): with
/// N = U D Uᵀ and Z = U_+ D_+^(−1/2) over its positive eigenvalues, λ_min(Zᵀ S Z).
pub fn min_generalized_eigenvalue(s: &Mat<f64>, n: &Mat<f64>) -> Result<f64, SolveError> {
    let evd = n
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| SolveError::Eigen(format!("{e:?}")))?;
    let d = evd.S().column_vector();
    let top = (0..d.nrows()).map(|i| d[i]).fold(0.0, f64::max);
    let keep: Vec<usize> = (0..d.nrows()).filter(|&i| d[i] > 1e-12 * top).collect();
    let u = evd.U();
    let z = Mat::<f64>::from_fn(n.nrows(), keep.len(), |r, c| u[(r, keep[c])] / d[keep[c]].sqrt());
    let reduced = z.transpose() * s * &z;
    let lam = reduced
        .self_adjoint_eigenvalues(Side::Lower)
        .map_err(|e| SolveError::Eigen(format!("{e:?}")))?;
    Ok(lam.first().copied().unwrap_or(0.0).max(0.0))
}

/// β_h, β̄_h and their ratios to √h for `rule` on `disc`, from its trace compliance.
pub fn estimate(
    disc: &Discretization,
    compliance: &TraceCompliance,
    rule: Rule,
) -> Result<InfSup, SolveError> {
    let cp = disc.contact_points(rule);
    let h = disc.mesh.h();
    let s = schur(&cp, &compliance.c);
    let n_trace = disc.contact_dofs.len();
    let kernel = (cp.len() > n_trace).then(|| {
        format!(
            "Q_h has {} dofs but the normal trace only {n_trace}: a kernel of dimension {}",
            cp.len(),
            cp.len() - n_trace
        )
    });
    let beta = if kernel.is_some() {
        0.0
    } else {
        min_generalized_eigenvalue(&s, &pressure_mass(&cp))?.sqrt()
    };
    let smooth = smoothing_matrix(&cp);
    let n_bar = smooth.transpose() * p1_mass(&cp.vertex_x) * &smooth;
    let beta_bar = min_generalized_eigenvalue(&s, &n_bar)?.sqrt();
    Ok(InfSup {
        h,
        beta,
        beta_over_sqrt_h: beta / h.sqrt(),
        beta_bar,
        beta_bar_over_sqrt_h: beta_bar / h.sqrt(),
        kernel,
    })
}

/// The estimate for one rule (computes the trace compliance; reuse [`TraceCompliance`] and
/// [`estimate`] for several rules on one mesh).
pub fn inf_sup(disc: &Discretization, rule: Rule) -> Result<InfSup, SolveError> {
    estimate(disc, &TraceCompliance::new(disc)?, rule)
}
