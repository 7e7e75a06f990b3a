//! The point couplings G = R K⁻¹ Rᵀ, R = [S; B], of one contact rule, from the layer's factor.

use std::sync::OnceLock;

use faer::{Accum, Mat};

use super::layer::{EdgePoint, Layer};
use crate::error::SolveError;

/// Columns per triangular solve in [`Layer::couplings`].
const SOLVE_BLOCK: usize = 64;

/// G = R K⁻¹ Rᵀ for R = [S; B] at the edge points of one rule.
pub(super) struct Couplings {
    pub(super) points: Vec<EdgePoint>,
    pub(super) g: Mat<f64>,
    /// E K⁻¹ Rᵀ, E the u_y of Γ_C's vertices: their displacement under the point loads.
    pub(super) vertex: Mat<f64>,
    /// γ₀* ([`stability_threshold`]) or why it could not be computed, when first asked.
    pub(super) threshold: OnceLock<Result<f64, SolveError>>,
}

impl Couplings {
    pub(super) fn n(&self) -> usize {
        self.points.len()
    }
    /// The blocks of G: (σ, σ), (σ, u_n), (u_n, σ), (u_n, u_n).
    pub(super) fn ss(&self, i: usize, j: usize) -> f64 {
        self.g[(i, j)]
    }
    pub(super) fn sb(&self, i: usize, j: usize) -> f64 {
        self.g[(i, self.n() + j)]
    }
    pub(super) fn bs(&self, i: usize, j: usize) -> f64 {
        self.g[(self.n() + i, j)]
    }
    pub(super) fn bb(&self, i: usize, j: usize) -> f64 {
        self.g[(self.n() + i, self.n() + j)]
    }
    /// C^½ G_SS C^½ with C = diag(c).
    pub(super) fn scaled_ss(&self, c: &[f64]) -> Mat<f64> {
        let r: Vec<f64> = c.iter().map(|v| v.sqrt()).collect();
        Mat::<f64>::from_fn(self.n(), self.n(), |i, j| r[i] * self.ss(i, j) * r[j])
    }
}

impl Layer {
    /// G = R K⁻¹ Rᵀ for the σ_n rows then the u_n rows of `points`, and E K⁻¹ Rᵀ for the
    /// u_y dofs `vertices` of Γ_C's vertices.
    pub(super) fn couplings(&self, points: Vec<EdgePoint>, vertices: &[usize]) -> Couplings {
        let n = points.len();
        let nb = self.l.nrows();
        let mut x = Mat::<f64>::zeros(nb, 2 * n + vertices.len());
        for (q, pt) in points.iter().enumerate() {
            for &(d, c) in &pt.sigma {
                x[(self.position[d], q)] += c;
            }
            for &(d, c) in &pt.normal {
                x[(self.position[d], n + q)] += c;
            }
        }
        for (k, &d) in vertices.iter().enumerate() {
            x[(self.position[d], 2 * n + k)] = 1.0;
        }
        let par = crate::fem::dense_parallelism(nb);
        // L⁻¹ keeps a column's leading zeros: solve each block of columns with the trailing
        // part of L below its first non-zero row (about a third of the full solve's work).
        let m = x.ncols();
        let first: Vec<usize> = (0..m)
            .map(|j| (0..nb).find(|&i| x[(i, j)] != 0.0).unwrap_or(nb))
            .collect();
        let mut j0 = 0;
        while j0 < m {
            let width = SOLVE_BLOCK.min(m - j0);
            let k = first[j0..j0 + width].iter().copied().min().unwrap_or(nb);
            faer::linalg::triangular_solve::solve_lower_triangular_in_place(
                self.l.as_ref().submatrix(k, k, nb - k, nb - k),
                x.as_mut().submatrix_mut(k, j0, nb - k, width),
                par,
            );
            j0 += width;
        }
        let (rows, ends) = x.as_ref().split_at_col(2 * n);
        let mut g = Mat::<f64>::zeros(2 * n, 2 * n);
        faer::linalg::matmul::matmul(g.as_mut(), Accum::Replace, rows.transpose(), rows, 1.0, par);
        let mut vertex = Mat::<f64>::zeros(vertices.len(), 2 * n);
        faer::linalg::matmul::matmul(vertex.as_mut(), Accum::Replace, ends.transpose(), rows, 1.0, par);
        Couplings {
            points,
            g,
            vertex,
            threshold: OnceLock::new(),
        }
    }
}
