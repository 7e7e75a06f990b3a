//! Isotropic linear elasticity in the plane (docs/design.md §1): the tensor E_ijkh of (2), (6).

use serde::{Deserialize, Serialize};

/// Plane strain (the paper's) or plane stress.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Plane {
    /// Plane strain, ε_zz = 0 (the paper's).
    Strain,
    /// Plane stress, σ_zz = 0.
    Stress,
}

/// An isotropic linear elastic material (docs/design.md §1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Young's modulus E > 0.
    pub young: f64,
    /// Poisson's ratio, −1 < ν < 1/2.
    pub poisson: f64,
    /// Plane strain or plane stress.
    pub plane: Plane,
}

impl Material {
    /// Lamé's (λ, μ) of the two-dimensional model: plane stress uses λ* = 2λμ/(λ + 2μ).
    pub fn lame(&self) -> (f64, f64) {
        let (e, nu) = (self.young, self.poisson);
        let mu = e / (2.0 * (1.0 + nu));
        let lambda = match self.plane {
            Plane::Strain => e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            Plane::Stress => e * nu / (1.0 - nu * nu),
        };
        (lambda, mu)
    }

    /// The volumetric part λ δ_ij δ_kh of [`Material::tensor`]: λ (div u)(div v).
    pub fn volumetric_tensor(&self) -> nalgebra::Matrix4<f64> {
        let tr = nalgebra::Vector4::new(1.0, 0.0, 0.0, 1.0);
        tr * tr.transpose() * self.lame().0
    }

    /// E_ijkh acting on the displacement gradient ordered (u_x,x, u_x,y, u_y,x, u_y,y), so that
    /// a(u, v) of (2) is ∫ ∇vᵀ C ∇u.
    pub fn tensor(&self) -> nalgebra::Matrix4<f64> {
        let (lambda, mu) = self.lame();
        let tr = nalgebra::Vector4::new(1.0, 0.0, 0.0, 1.0);
        let shear = nalgebra::Vector4::new(0.0, 1.0, 1.0, 0.0);
        let normal = nalgebra::Matrix4::from_diagonal(&nalgebra::Vector4::new(1.0, 0.0, 0.0, 1.0));
        tr * tr.transpose() * lambda + normal * (2.0 * mu) + shear * shear.transpose() * mu
    }
}

/// The range of the dimensionless penalty κ = ε·E/h (the penalty stiffness w/ε against the
/// body's stiffness E, per unit length) that riplab accepts. Below 1e-20 the products of the
/// penalty (1/ε times squares of violations) leave double precision; round-off already swamps
/// the contact forces near κ = 1e-13 (STABILITY.md), which the Newton test reports. Above
/// 1e10 the penalty carries no load worth computing.
pub const KAPPA_RANGE: (f64, f64) = (1e-20, 1e10);

/// The penalty parameters ε > 0 accepted on a mesh of cell size `h` for Young's modulus
/// `young`: [`KAPPA_RANGE`] times h/E.
pub fn epsilon_range(young: f64, h: f64) -> (f64, f64) {
    (KAPPA_RANGE.0 * h / young, KAPPA_RANGE.1 * h / young)
}
