//! The stress in the body under the contact: σ = E : ε(u) at the quadrature points of every
//! element (the tensor E_ijkh of (2), (6) acting on the displacement gradient of a solution of
//! (11)), a continuous nodal field recovered from them, and the quantities a contact-mechanics
//! class draws: von Mises, the principal shear τ₁ = (σ₁ − σ₂)/2 and σ_yy.
//!
//! **Recovery: the L² projection.** The nodal field σ̂ in the displacement's own space (Q1,
//! Q2 or P1, one scalar per node and component) minimises ‖σ̂ − σ_h‖_{L²(Ω)}:
//! M σ̂ = ∫ N σ_h with the consistent mass matrix M, solved by diagonally preconditioned
//! conjugate gradients. It was chosen over superconvergent patch recovery (SPR) because it is one
//! rule for the three elements and for nodes inside and on the boundary alike: SPR's
//! superconvergent sampling points are known for Q1 and Q2 on regular patches but not for
//! the split P1 cells, and its boundary nodes (Γ_C, where the traction check compares σ̂_yy
//! with −p̄, and the symmetry line, where the Hertz check reads τ₁) have no patch of their own
//! and must borrow one from the interior. The projection reproduces any stress field of the
//! element's space exactly (the patch test) and is variationally consistent, so the checks
//! of `tests/numerics/stresses.rs` measure it without special cases.
//!
//! **Plane strain**: ε_zz = 0 gives σ_zz = λ(ε_xx + ε_yy) = ν(σ_xx + σ_yy), which enters von
//! Mises; in plane stress σ_zz = 0.
//!
//! **Selective integration** (`Integration::Selective`): the stiffness takes its volumetric
//! part λ div u at the reduced Gauss points, so the stress does too: the volumetric stress is
//! the interpolant through the reduced points (a constant per Q1 element, bilinear per Q2
//! element) and the rest is taken at the full points. For Q1 this is exactly the stress of
//! the stiffness (so equilibrium holds to round-off); for Q2 it is its bilinear interpolant.

use crate::fem::Integration;
use crate::fem::basis::{QuadPoint, cell_points, evaluate, exact_order};
use crate::material::{Material, Plane};
use crate::mesh::{Element, Mesh};

mod projection;
use projection::project;

/// A plane stress state with its out-of-plane normal stress.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stress {
    /// σ_xx.
    pub xx: f64,
    /// σ_yy.
    pub yy: f64,
    /// σ_xy.
    pub xy: f64,
    /// ν(σ_xx + σ_yy) in plane strain, 0 in plane stress.
    pub zz: f64,
}

impl Stress {
    /// σ = E : ε for the displacement gradient ordered (u_x,x, u_x,y, u_y,x, u_y,y), with
    /// `volumetric` (λ div u) taken from elsewhere when given (selective integration).
    pub(crate) fn of_gradient(material: &Material, grad: [f64; 4], volumetric: Option<f64>) -> Stress {
        let (lambda, mu) = material.lame();
        let div = grad[0] + grad[3];
        let vol = volumetric.unwrap_or(lambda * div);
        let zz = match material.plane {
            Plane::Strain => vol,
            Plane::Stress => 0.0,
        };
        Stress {
            xx: vol + 2.0 * mu * grad[0],
            yy: vol + 2.0 * mu * grad[3],
            xy: mu * (grad[1] + grad[2]),
            zz,
        }
    }

    /// The radius of Mohr's circle in the plane, τ₁ = (σ₁ − σ₂)/2 = √(((σ_xx − σ_yy)/2)² + σ_xy²).
    pub fn principal_shear(&self) -> f64 {
        (0.5 * (self.xx - self.yy)).hypot(self.xy)
    }

    /// The in-plane principal stresses σ₁ ≥ σ₂.
    pub fn principal(&self) -> (f64, f64) {
        let (c, r) = (0.5 * (self.xx + self.yy), self.principal_shear());
        (c + r, c - r)
    }

    /// von Mises: √(½[(σ_xx − σ_yy)² + (σ_yy − σ_zz)² + (σ_zz − σ_xx)²] + 3σ_xy²).
    pub fn von_mises(&self) -> f64 {
        let (a, b, c) = (self.xx - self.yy, self.yy - self.zz, self.zz - self.xx);
        (0.5 * (a * a + b * b + c * c) + 3.0 * self.xy * self.xy).sqrt()
    }

    /// The value of `q`.
    pub fn get(&self, q: Quantity) -> f64 {
        match q {
            Quantity::VonMises => self.von_mises(),
            Quantity::PrincipalShear => self.principal_shear(),
            Quantity::SigmaYy => self.yy,
        }
    }

    fn add_scaled(&mut self, s: &Stress, w: f64) {
        self.xx += w * s.xx;
        self.yy += w * s.yy;
        self.xy += w * s.xy;
        self.zz += w * s.zz;
    }

    fn scaled(mut self, w: f64) -> Stress {
        self.xx *= w;
        self.yy *= w;
        self.xy *= w;
        self.zz *= w;
        self
    }
}

/// The scalar quantities shown and exported.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Quantity {
    /// The von Mises stress, with σ_zz ([`Stress::zz`]).
    VonMises,
    /// τ₁ = (σ₁ − σ₂)/2, whose maximum lies below the surface under a cylinder (Johnson §4.2).
    PrincipalShear,
    /// The normal stress on horizontal planes; −p on Γ_C.
    SigmaYy,
}

impl Quantity {
    /// Every quantity, in the order [`Quantity::next`] cycles through.
    pub const ALL: [Quantity; 3] = [Quantity::PrincipalShear, Quantity::VonMises, Quantity::SigmaYy];

    /// A short name, also the array name in the VTU export.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::VonMises => "von_mises",
            Quantity::PrincipalShear => "tau1",
            Quantity::SigmaYy => "sigma_yy",
        }
    }

    /// The symbol for a display.
    pub fn symbol(self) -> &'static str {
        match self {
            Quantity::VonMises => "σ_vM",
            Quantity::PrincipalShear => "τ₁",
            Quantity::SigmaYy => "σ_yy",
        }
    }

    /// The next quantity in [`Quantity::ALL`], cyclically.
    pub fn next(self) -> Quantity {
        let i = Quantity::ALL.iter().position(|&q| q == self).unwrap_or(0);
        Quantity::ALL[(i + 1) % Quantity::ALL.len()]
    }
}

/// σ at one quadrature point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StressPoint {
    /// Its x.
    pub x: f64,
    /// Its y.
    pub y: f64,
    /// The quadrature weight including the Jacobian.
    pub weight: f64,
    /// σ there.
    pub stress: Stress,
}

/// Where a quantity is largest in magnitude, and its value there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Peak {
    /// The quantity.
    pub quantity: Quantity,
    /// Signed (σ_yy is negative in compression).
    pub value: f64,
    /// Where: x.
    pub x: f64,
    /// Where: y.
    pub y: f64,
    /// Below the contact side Γ_C (y = top).
    pub depth: f64,
}

/// Why the stresses of a displacement could not be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StressError {
    /// The displacement is not one value per dof of the mesh.
    #[error("the displacement has {got} values; the mesh has {expected} dofs")]
    Length {
        /// The length of the displacement given.
        got: usize,
        /// The mesh's dofs, 2 per node.
        expected: usize,
    },
    /// The L² projection's conjugate gradients did not converge.
    #[error(
        "the L² projection of the stresses failed: conjugate gradients did not reach a relative residual of {tolerance:e} in {iterations} iterations"
    )]
    Projection {
        /// The iterations taken.
        iterations: usize,
        /// The relative residual asked for.
        tolerance: f64,
    },
}

/// The stresses of a displacement field on a mesh.
#[derive(Clone, Debug)]
pub struct StressField {
    /// The element of the mesh.
    pub element: Element,
    /// σ at the quadrature points of each element (cells row by row from the bottom, x fastest;
    /// a P1 cell's two triangles one after the other).
    pub elements: Vec<Vec<StressPoint>>,
    /// The recovered (L²-projected) σ̂ at every mesh node.
    pub nodal: Vec<Stress>,
    /// σ̂ packed node-major as two-component fields (xx, yy) and (xy, zz), for interpolation.
    packed: [Vec<f64>; 2],
    top: f64,
}

/// The cells of `mesh` in element order: row by row from the bottom, x fastest.
fn cells(mesh: &Mesh) -> impl Iterator<Item = (usize, usize)> + use<> {
    let (nx, ny) = (mesh.nx(), mesh.ny());
    (0..ny).flat_map(move |cj| (0..nx).map(move |ci| (ci, cj)))
}

/// The displacement gradient (u_x,x, u_x,y, u_y,x, u_y,y) at `q` from the cell's nodal values.
fn gradient(q: &QuadPoint, nodes: &[usize], u: &[f64]) -> [f64; 4] {
    let mut g = [0.0; 4];
    for (&n, d) in nodes.iter().zip(&q.grad) {
        for c in 0..2 {
            g[2 * c] += d[0] * u[2 * n + c];
            g[2 * c + 1] += d[1] * u[2 * n + c];
        }
    }
    g
}

/// λ div u at each full point of a Q1/Q2 cell, taken from the reduced Gauss points: their
/// constant (one point) or the bilinear function through them (2×2 points).
fn reduced_volumetric(
    mesh: &Mesh,
    ci: usize,
    cj: usize,
    lambda: f64,
    u: &[f64],
    full: &[QuadPoint],
) -> Vec<f64> {
    let nodes = mesh.cell_nodes(ci, cj);
    let reduced = cell_points(mesh, ci, cj, exact_order(mesh.element) - 1);
    let vol: Vec<f64> = reduced
        .iter()
        .map(|q| {
            let g = gradient(q, &nodes, u);
            lambda * (g[0] + g[3])
        })
        .collect();
    if vol.len() == 1 {
        return vec![vol[0]; full.len()];
    }
    // 2×2 points, x fastest: bilinear interpolation in the cell's own coordinates.
    let (x0, x1) = (reduced[0].x, reduced[1].x);
    let (y0, y1) = (reduced[0].y, reduced[2].y);
    full.iter()
        .map(|q| {
            let (s, t) = ((q.x - x0) / (x1 - x0), (q.y - y0) / (y1 - y0));
            (1.0 - t) * ((1.0 - s) * vol[0] + s * vol[1]) + t * ((1.0 - s) * vol[2] + s * vol[3])
        })
        .collect()
}

/// σ at the quadrature points of every element (the stiffness's own points: 2×2 Gauss for
/// Q1, 3×3 for Q2, the degree-2 rule on each P1 triangle) for the displacement `u` on every
/// dof, node-major (as [`crate::contact::solution::Solution::displacement`] gives it).
pub fn quadrature_stresses(
    mesh: &Mesh,
    material: &Material,
    integration: Integration,
    u: &[f64],
) -> Vec<Vec<StressPoint>> {
    let (lambda, _) = material.lame();
    let mut out = Vec::with_capacity(mesh.n_elements());
    for (ci, cj) in cells(mesh) {
        let nodes = mesh.cell_nodes(ci, cj);
        let pts = cell_points(mesh, ci, cj, exact_order(mesh.element));
        let volumetric = match (integration, mesh.element) {
            (Integration::Selective, Element::Q1 | Element::Q2) => {
                Some(reduced_volumetric(mesh, ci, cj, lambda, u, &pts))
            }
            _ => None,
        };
        let stresses: Vec<StressPoint> = pts
            .iter()
            .enumerate()
            .map(|(k, q)| StressPoint {
                x: q.x,
                y: q.y,
                weight: q.weight,
                stress: Stress::of_gradient(
                    material,
                    gradient(q, &nodes, u),
                    volumetric.as_ref().map(|v| v[k]),
                ),
            })
            .collect();
        if mesh.element == Element::P1 {
            // The first half of the points lie in the first triangle (see `cell_points`).
            let half = stresses.len() / 2;
            out.push(stresses[..half].to_vec());
            out.push(stresses[half..].to_vec());
        } else {
            out.push(stresses);
        }
    }
    out
}

impl StressField {
    /// The stresses of the displacement `u` (every dof, node-major) on `mesh`.
    ///
    /// # Errors
    ///
    /// `u` does not have the mesh's dofs, or the L² projection did not converge ([`StressError`]).
    pub fn new(
        mesh: &Mesh,
        material: &Material,
        integration: Integration,
        u: &[f64],
    ) -> Result<Self, StressError> {
        if u.len() != 2 * mesh.n_nodes() {
            return Err(StressError::Length {
                got: u.len(),
                expected: 2 * mesh.n_nodes(),
            });
        }
        let elements = quadrature_stresses(mesh, material, integration, u);
        let nodal = project(mesh, &elements)?;
        let packed = [
            nodal.iter().flat_map(|s| [s.xx, s.yy]).collect(),
            nodal.iter().flat_map(|s| [s.xy, s.zz]).collect(),
        ];
        Ok(StressField {
            element: mesh.element,
            elements,
            nodal,
            packed,
            top: mesh.ys[mesh.ys.len() - 1],
        })
    }

    /// The recovered σ̂ at (x, y), interpolated by the element's shape functions.
    pub fn at(&self, mesh: &Mesh, x: f64, y: f64) -> Stress {
        let (a, _) = evaluate(mesh, &self.packed[0], x, y);
        let (b, _) = evaluate(mesh, &self.packed[1], x, y);
        Stress {
            xx: a[0],
            yy: a[1],
            xy: b[0],
            zz: b[1],
        }
    }

    /// The element averages (1/|e|) ∫_e σ_h.
    pub fn element_averages(&self) -> Vec<Stress> {
        self.elements
            .iter()
            .map(|pts| {
                let mut s = Stress::default();
                let mut area = 0.0;
                for p in pts {
                    s.add_scaled(&p.stress, p.weight);
                    area += p.weight;
                }
                s.scaled(1.0 / area)
            })
            .collect()
    }

    /// Where |q| of the recovered field is largest: the extreme node, its position refined by
    /// the parabola through it and its two neighbours along each node line (when both exist and
    /// the parabola has its extreme between them), its value that parabola's extreme.
    pub fn peak(&self, mesh: &Mesh, q: Quantity) -> Peak {
        let values: Vec<f64> = self.nodal.iter().map(|s| s.get(q)).collect();
        let best = (0..values.len())
            .filter(|&n| values[n].is_finite())
            .max_by(|&a, &b| values[a].abs().total_cmp(&values[b].abs()))
            .unwrap_or(0);
        let nnx = mesh.nnx();
        let (i, j) = (best % nnx, best / nnx);
        let (mut x, mut y) = mesh.node_coords(best);
        let mut value = values[best];
        if 0 < i && i + 1 < nnx {
            let (xv, fv) = vertex(
                [mesh.node_x[i - 1], mesh.node_x[i], mesh.node_x[i + 1]],
                [values[best - 1], values[best], values[best + 1]],
            );
            x = xv;
            value = if fv.abs() > value.abs() { fv } else { value };
        }
        let nny = mesh.node_y.len();
        if 0 < j && j + 1 < nny {
            let (yv, fv) = vertex(
                [mesh.node_y[j - 1], mesh.node_y[j], mesh.node_y[j + 1]],
                [values[best - nnx], values[best], values[best + nnx]],
            );
            y = yv;
            value = if fv.abs() > value.abs() { fv } else { value };
        }
        Peak {
            quantity: q,
            value,
            x,
            y,
            depth: self.top - y,
        }
    }
}

/// The extreme (position, value) of the parabola through three points with t₀ < t₁ < t₂ and
/// |f₁| the largest; (t₁, f₁) when the parabola is flat or its extreme falls outside [t₀, t₂].
fn vertex(t: [f64; 3], f: [f64; 3]) -> (f64, f64) {
    // Newton's divided differences: p(s) = f₀ + d₁(s − t₀) + d₂(s − t₀)(s − t₁).
    let d01 = (f[1] - f[0]) / (t[1] - t[0]);
    let d12 = (f[2] - f[1]) / (t[2] - t[1]);
    let d2 = (d12 - d01) / (t[2] - t[0]);
    // p'(s) = d01 + d2(2s − t₀ − t₁) = 0.
    if d2 == 0.0 || !d2.is_finite() {
        return (t[1], f[1]);
    }
    let s = (t[0] + t[1]) / 2.0 - d01 / (2.0 * d2);
    if !(t[0]..=t[2]).contains(&s) {
        return (t[1], f[1]);
    }
    (s, f[0] + d01 * (s - t[0]) + d2 * (s - t[0]) * (s - t[1]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parabola_vertex_by_hand() {
        // f = 1 − (t − 0.3)² through t = 0, 0.5, 1.5: the vertex (0.3, 1).
        let f = |t: f64| 1.0 - (t - 0.3) * (t - 0.3);
        let (t, v) = vertex([0.0, 0.5, 1.5], [f(0.0), f(0.5), f(1.5)]);
        assert!((t - 0.3).abs() < 1e-14 && (v - 1.0).abs() < 1e-14, "{t} {v}");
        // A straight line has no vertex: the middle point stays.
        assert_eq!(vertex([0.0, 1.0, 2.0], [1.0, 2.0, 3.0]), (1.0, 2.0));
    }

    #[test]
    fn quantities_by_hand() {
        // σ_xx = 3, σ_yy = −1, σ_xy = 0 ⇒ τ₁ = 2, σ₁ = 3, σ₂ = −1; σ_zz = 0.6 (ν = 0.3, plane
        // strain): von Mises √(½(16 + 2.56 + 5.76)) = √12.16.
        let s = Stress {
            xx: 3.0,
            yy: -1.0,
            xy: 0.0,
            zz: 0.6,
        };
        assert_eq!(s.principal_shear(), 2.0);
        assert_eq!(s.principal(), (3.0, -1.0));
        assert!((s.von_mises() - 12.16f64.sqrt()).abs() < 1e-14);
        // Pure shear τ: von Mises √3 τ, τ₁ = τ.
        let t = Stress {
            xy: 2.0,
            ..Stress::default()
        };
        assert!((t.von_mises() - 2.0 * 3f64.sqrt()).abs() < 1e-14);
        assert_eq!(t.principal_shear(), 2.0);
        assert_eq!(Quantity::SigmaYy.next(), Quantity::PrincipalShear);
    }
}
