//! The point couplings G = R K⁻¹ Rᵀ, R = [S; B], of one contact rule, from the layer's factor.

use std::sync::OnceLock;

use faer::Mat;

use super::layer::EdgePoint;
use crate::error::SolveError;

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
