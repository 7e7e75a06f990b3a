//! Shape functions of a cell evaluated at quadrature points in physical coordinates.
//!
//! Every element kind is handled per *cell* (see [`crate::mesh`]): Q1 and Q2 are tensor
//! Lagrange bases on the rectangle; a P1 cell is its two triangles, each with its three linear
//! shape functions embedded in the cell's four nodes.

use super::quadrature::{gauss_legendre, triangle_rule};
use crate::mesh::{Diagonal, Element, Mesh};

/// One quadrature point of a cell: position, weight (including the Jacobian), and the value
/// and gradient of every cell shape function there.
#[derive(Clone, Debug)]
pub struct QuadPoint {
    /// Its x in physical coordinates.
    pub x: f64,
    /// Its y in physical coordinates.
    pub y: f64,
    /// The quadrature weight times the Jacobian.
    pub weight: f64,
    /// The value of each cell shape function.
    pub n: Vec<f64>,
    /// The gradient (∂/∂x, ∂/∂y) of each cell shape function.
    pub grad: Vec<[f64; 2]>,
}

/// 1-D Lagrange basis of degree `p` (1 or 2) on equispaced nodes of [−1, 1]: values and
/// derivatives at ξ.
pub fn lagrange_1d(p: usize, xi: f64) -> (Vec<f64>, Vec<f64>) {
    match p {
        1 => (vec![(1.0 - xi) / 2.0, (1.0 + xi) / 2.0], vec![-0.5, 0.5]),
        2 => (
            vec![xi * (xi - 1.0) / 2.0, 1.0 - xi * xi, xi * (xi + 1.0) / 2.0],
            vec![xi - 0.5, -2.0 * xi, xi + 0.5],
        ),
        _ => unreachable!("only degrees 1 and 2 are used"),
    }
}

/// Quadrature points of cell (ci, cj) with an `n`-point Gauss rule per direction (per
/// collapsed direction of each triangle for P1).
pub fn cell_points(mesh: &Mesh, ci: usize, cj: usize, n: usize) -> Vec<QuadPoint> {
    let (x0, x1, y0, y1) = mesh.cell_rect(ci, cj);
    let (a, b) = (x1 - x0, y1 - y0);
    match mesh.element {
        Element::Q1 | Element::Q2 => {
            let p = mesh.element.order();
            let g = gauss_legendre(n);
            let mut out = Vec::with_capacity(n * n);
            for &(eta, wy) in &g {
                let (ny, dy) = lagrange_1d(p, eta);
                for &(xi, wx) in &g {
                    let (nx, dx) = lagrange_1d(p, xi);
                    let mut vals = Vec::with_capacity((p + 1) * (p + 1));
                    let mut grad = Vec::with_capacity((p + 1) * (p + 1));
                    for lj in 0..=p {
                        for li in 0..=p {
                            vals.push(nx[li] * ny[lj]);
                            grad.push([dx[li] * ny[lj] * 2.0 / a, nx[li] * dy[lj] * 2.0 / b]);
                        }
                    }
                    out.push(QuadPoint {
                        x: x0 + a * (xi + 1.0) / 2.0,
                        y: y0 + b * (eta + 1.0) / 2.0,
                        weight: wx * wy * a * b / 4.0,
                        n: vals,
                        grad,
                    });
                }
            }
            out
        }
        Element::P1 => {
            // Cell corners in tensor order: 0 = (x0,y0), 1 = (x1,y0), 2 = (x0,y1), 3 = (x1,y1).
            let corners = [(x0, y0), (x1, y0), (x0, y1), (x1, y1)];
            let triangles: [[usize; 3]; 2] = match mesh.diagonal(ci) {
                Diagonal::Rising => [[0, 1, 3], [0, 3, 2]],
                Diagonal::Falling => [[0, 1, 2], [1, 3, 2]],
            };
            let rule = triangle_rule(n);
            let mut out = Vec::with_capacity(2 * rule.len());
            for tri in triangles {
                let [p0, p1, p2] = tri.map(|k| corners[k]);
                let det = (p1.0 - p0.0) * (p2.1 - p0.1) - (p2.0 - p0.0) * (p1.1 - p0.1);
                // Gradients of the barycentric coordinates λ1, λ2 (λ0 = 1 − λ1 − λ2).
                let g1 = [(p2.1 - p0.1) / det, -(p2.0 - p0.0) / det];
                let g2 = [-(p1.1 - p0.1) / det, (p1.0 - p0.0) / det];
                let g0 = [-g1[0] - g2[0], -g1[1] - g2[1]];
                for &(r, s, w) in &rule {
                    let mut vals = vec![0.0; 4];
                    let mut grad = vec![[0.0; 2]; 4];
                    for (k, (l, g)) in [(1.0 - r - s, g0), (r, g1), (s, g2)].into_iter().enumerate() {
                        vals[tri[k]] = l;
                        grad[tri[k]] = g;
                    }
                    out.push(QuadPoint {
                        x: p0.0 + r * (p1.0 - p0.0) + s * (p2.0 - p0.0),
                        y: p0.1 + r * (p1.1 - p0.1) + s * (p2.1 - p0.1),
                        weight: w * det.abs(),
                        n: vals,
                        grad,
                    });
                }
            }
            out
        }
    }
}

/// The number of Gauss points per direction that integrates the stiffness and the mass
/// matrix of the element exactly on rectangles (2×2 for Q1, 3×3 for Q2; degree 2 on P1).
pub fn exact_order(element: Element) -> usize {
    match element {
        Element::Q1 | Element::P1 => 2,
        Element::Q2 => 3,
    }
}

/// Locate x among ascending lines: the interval index i with lines[i] ≤ x ≤ lines[i+1].
fn interval(lines: &[f64], x: f64) -> usize {
    lines.partition_point(|&l| l <= x).clamp(1, lines.len() - 1) - 1
}

/// The value and gradient (∂/∂x, ∂/∂y of u_x, then of u_y) at (x, y) of the field `u` (all
/// dofs, node-major) on `mesh`, from the shape functions of the cell that contains the point.
pub fn evaluate(mesh: &Mesh, u: &[f64], x: f64, y: f64) -> ([f64; 2], [f64; 4]) {
    let (ci, cj) = (interval(&mesh.xs, x), interval(&mesh.ys, y));
    let (x0, x1, y0, y1) = mesh.cell_rect(ci, cj);
    let nodes = mesh.cell_nodes(ci, cj);
    let (mut val, mut grad) = ([0.0; 2], [0.0; 4]);
    let mut add = |k: usize, n: f64, g: [f64; 2]| {
        for c in 0..2 {
            let d = u[2 * nodes[k] + c];
            val[c] += n * d;
            grad[2 * c] += g[0] * d;
            grad[2 * c + 1] += g[1] * d;
        }
    };
    let (a, b) = (x1 - x0, y1 - y0);
    let (xi, eta) = (2.0 * (x - x0) / a - 1.0, 2.0 * (y - y0) / b - 1.0);
    match mesh.element {
        Element::Q1 | Element::Q2 => {
            let p = mesh.element.order();
            let ((nx, dx), (ny, dy)) = (lagrange_1d(p, xi), lagrange_1d(p, eta));
            for lj in 0..=p {
                for li in 0..=p {
                    add(
                        lj * (p + 1) + li,
                        nx[li] * ny[lj],
                        [dx[li] * ny[lj] * 2.0 / a, nx[li] * dy[lj] * 2.0 / b],
                    );
                }
            }
        }
        Element::P1 => {
            // Local coordinates (r, s) ∈ [0, 1]² of the cell and the triangle holding them.
            let (r, s) = ((xi + 1.0) / 2.0, (eta + 1.0) / 2.0);
            let (gx, gy) = (1.0 / a, 1.0 / b);
            match (mesh.diagonal(ci), s <= r) {
                // Rising: (0,1,3) below the diagonal, (0,3,2) above.
                (Diagonal::Rising, true) => {
                    add(0, 1.0 - r, [-gx, 0.0]);
                    add(1, r - s, [gx, -gy]);
                    add(3, s, [0.0, gy]);
                }
                (Diagonal::Rising, false) => {
                    add(0, 1.0 - s, [0.0, -gy]);
                    add(3, r, [gx, 0.0]);
                    add(2, s - r, [-gx, gy]);
                }
                // Falling: (0,1,2) below r + s = 1, (1,3,2) above.
                (Diagonal::Falling, _) if r + s <= 1.0 => {
                    add(0, 1.0 - r - s, [-gx, -gy]);
                    add(1, r, [gx, 0.0]);
                    add(2, s, [0.0, gy]);
                }
                (Diagonal::Falling, _) => {
                    add(1, 1.0 - s, [0.0, -gy]);
                    add(3, r + s - 1.0, [gx, gy]);
                    add(2, 1.0 - r, [-gx, 0.0]);
                }
            }
        }
    }
    (val, grad)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_functions_partition_unity_and_weights_give_area() {
        for el in Element::ALL {
            let m = Mesh::uniform(el, (-1.0, 2.0, 3), (0.0, 2.0, 1), false);
            for ci in 0..3 {
                let pts = cell_points(&m, ci, 0, 3);
                let area: f64 = pts.iter().map(|q| q.weight).sum();
                assert!((area - 2.0).abs() < 1e-14, "{el:?}: area {area}");
                for q in &pts {
                    assert!((q.n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
                    let gx: f64 = q.grad.iter().map(|g| g[0]).sum();
                    let gy: f64 = q.grad.iter().map(|g| g[1]).sum();
                    assert!(gx.abs() < 1e-13 && gy.abs() < 1e-13);
                    // x = Σ x_k N_k reproduces the point (isoparametric consistency).
                    let nodes = m.cell_nodes(ci, 0);
                    let x: f64 = nodes.iter().zip(&q.n).map(|(&k, n)| m.node_coords(k).0 * n).sum();
                    assert!((x - q.x).abs() < 1e-14);
                }
            }
        }
    }

    /// Every element reproduces a linear field and its gradient anywhere, and matches its own
    /// quadrature-point values.
    #[test]
    fn evaluates_fields_exactly() {
        let lin = |x: f64, y: f64| [0.2 + 1.5 * x - 0.3 * y, -0.1 + 0.4 * x + 2.0 * y];
        for el in Element::ALL {
            let m = Mesh::from_lines(el, vec![-1.0, -0.2, 0.5, 2.0], vec![0.0, 0.7, 1.0], false);
            let u: Vec<f64> = (0..m.n_nodes())
                .flat_map(|n| {
                    let (x, y) = m.node_coords(n);
                    lin(x, y)
                })
                .collect();
            for (x, y) in [
                (-1.0, 0.0),
                (-0.7, 0.1),
                (0.1, 0.95),
                (1.9, 0.71),
                (2.0, 1.0),
                (0.5, 0.7),
            ] {
                let (v, g) = evaluate(&m, &u, x, y);
                let e = lin(x, y);
                assert!(
                    (v[0] - e[0]).abs() < 1e-13 && (v[1] - e[1]).abs() < 1e-13,
                    "{el:?} at ({x},{y})"
                );
                for (a, b) in g.iter().zip([1.5, -0.3, 0.4, 2.0]) {
                    assert!((a - b).abs() < 1e-12, "{el:?} gradient at ({x},{y})");
                }
            }
            // A non-polynomial nodal field: evaluation agrees with the quadrature points' sums.
            let w: Vec<f64> = (0..2 * m.n_nodes())
                .map(|k| ((k * 37 % 11) as f64).sin())
                .collect();
            for q in cell_points(&m, 1, 0, 3) {
                let nodes = m.cell_nodes(1, 0);
                let direct: f64 = nodes.iter().zip(&q.n).map(|(&k, n)| n * w[2 * k + 1]).sum();
                assert!((evaluate(&m, &w, q.x, q.y).0[1] - direct).abs() < 1e-13, "{el:?}");
            }
        }
    }
}
