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
/// derivatives at ξ, in the first p + 1 entries (the rest 0), without allocating: the error
/// integrals call it at every point of a reference mesh.
pub fn lagrange_1d(p: usize, xi: f64) -> ([f64; 3], [f64; 3]) {
    match p {
        1 => ([(1.0 - xi) / 2.0, (1.0 + xi) / 2.0, 0.0], [-0.5, 0.5, 0.0]),
        2 => (
            [xi * (xi - 1.0) / 2.0, 1.0 - xi * xi, xi * (xi + 1.0) / 2.0],
            [xi - 0.5, -2.0 * xi, xi + 0.5],
        ),
        _ => unreachable!("only degrees 1 and 2 are used"),
    }
}

/// The most nodes of a cell (Q2's nine).
const MAX_CELL_NODES: usize = 9;

/// A cell's nodes in tensor order ([`Mesh::cell_node_iter`]) in a fixed array (the entries
/// past the cell's node count 0).
fn cell_node_array(mesh: &Mesh, ci: usize, cj: usize) -> [usize; MAX_CELL_NODES] {
    let mut nodes = [0; MAX_CELL_NODES];
    for (slot, node) in nodes.iter_mut().zip(mesh.cell_node_iter(ci, cj)) {
        *slot = node;
    }
    nodes
}

/// The value and gradient (∂/∂x, ∂/∂y of u_x, then of u_y) of the field `u` (all dofs,
/// node-major) at a quadrature point of the cell whose nodes are `nodes` (tensor order, as
/// the point's shape functions).
pub fn field_at(point: &QuadPoint, nodes: &[usize], u: &[f64]) -> ([f64; 2], [f64; 4]) {
    let (mut val, mut grad) = ([0.0; 2], [0.0; 4]);
    for ((&node, &n), g) in nodes.iter().zip(&point.n).zip(&point.grad) {
        add_node(&mut val, &mut grad, u, node, n, *g);
    }
    (val, grad)
}

/// Add one node's shape function (value `n`, gradient `g`) times its dofs in `u` to a field's
/// value and gradient.
fn add_node(val: &mut [f64; 2], grad: &mut [f64; 4], u: &[f64], node: usize, n: f64, g: [f64; 2]) {
    for c in 0..2 {
        let d = u[2 * node + c];
        val[c] += n * d;
        grad[2 * c] += g[0] * d;
        grad[2 * c + 1] += g[1] * d;
    }
}

/// Quadrature points of cell (ci, cj) with an `n`-point Gauss rule per direction (per
/// collapsed direction of each triangle for P1).
pub fn cell_points(mesh: &Mesh, ci: usize, cj: usize, n: usize) -> Vec<QuadPoint> {
    let mut out = Vec::new();
    CellRule::new(mesh.element, n).points_into(mesh, ci, cj, &mut out);
    out
}

/// An `n`-point rule per direction of an element's cells, tabulated once on the reference
/// square (Q1, Q2: the 1-D Gauss points and the 1-D Lagrange basis there) or triangle (P1), so
/// that a loop over many cells computes no rule and, through [`CellRule::points_into`],
/// allocates nothing after its first cell.
pub struct CellRule {
    element: Element,
    /// Q1, Q2: the 1-D Gauss points ξ with weights, and the 1-D basis (values, derivatives) at
    /// each.
    gauss: Vec<(f64, f64)>,
    lagrange: Vec<([f64; 3], [f64; 3])>,
    /// P1: the collapsed Gauss rule (r, s, w) of a triangle.
    triangle: Vec<(f64, f64, f64)>,
}

impl CellRule {
    /// The rule of `n` points per direction for `element`'s cells.
    pub fn new(element: Element, n: usize) -> Self {
        match element {
            Element::Q1 | Element::Q2 => {
                let gauss = gauss_legendre(n);
                let lagrange = gauss
                    .iter()
                    .map(|&(xi, _)| lagrange_1d(element.order(), xi))
                    .collect();
                CellRule {
                    element,
                    gauss,
                    lagrange,
                    triangle: Vec::new(),
                }
            }
            Element::P1 => CellRule {
                element,
                gauss: Vec::new(),
                lagrange: Vec::new(),
                triangle: triangle_rule(n),
            },
        }
    }

    /// Cell (ci, cj)'s points in `out`, whose points' buffers are reused.
    pub fn points_into(&self, mesh: &Mesh, ci: usize, cj: usize, out: &mut Vec<QuadPoint>) {
        debug_assert_eq!(mesh.element, self.element);
        let (x0, x1, y0, y1) = mesh.cell_rect(ci, cj);
        let (a, b) = (x1 - x0, y1 - y0);
        let mut used = 0;
        match self.element {
            Element::Q1 | Element::Q2 => {
                let p = self.element.order();
                for (&(eta, wy), (ny, dy)) in self.gauss.iter().zip(&self.lagrange) {
                    for (&(xi, wx), (nx, dx)) in self.gauss.iter().zip(&self.lagrange) {
                        let q = next_point(
                            out,
                            &mut used,
                            x0 + a * (xi + 1.0) / 2.0,
                            y0 + b * (eta + 1.0) / 2.0,
                            wx * wy * a * b / 4.0,
                        );
                        for lj in 0..=p {
                            for li in 0..=p {
                                q.n.push(nx[li] * ny[lj]);
                                q.grad
                                    .push([dx[li] * ny[lj] * 2.0 / a, nx[li] * dy[lj] * 2.0 / b]);
                            }
                        }
                    }
                }
            }
            Element::P1 => {
                // Cell corners in tensor order: 0 = (x0,y0), 1 = (x1,y0), 2 = (x0,y1), 3 = (x1,y1).
                let corners = [(x0, y0), (x1, y0), (x0, y1), (x1, y1)];
                let triangles: [[usize; 3]; 2] = match mesh.diagonal(ci) {
                    Diagonal::Rising => [[0, 1, 3], [0, 3, 2]],
                    Diagonal::Falling => [[0, 1, 2], [1, 3, 2]],
                };
                for tri in triangles {
                    let [p0, p1, p2] = tri.map(|k| corners[k]);
                    let det = (p1.0 - p0.0) * (p2.1 - p0.1) - (p2.0 - p0.0) * (p1.1 - p0.1);
                    // Gradients of the barycentric coordinates λ1, λ2 (λ0 = 1 − λ1 − λ2).
                    let g1 = [(p2.1 - p0.1) / det, -(p2.0 - p0.0) / det];
                    let g2 = [-(p1.1 - p0.1) / det, (p1.0 - p0.0) / det];
                    let g0 = [-g1[0] - g2[0], -g1[1] - g2[1]];
                    for &(r, s, w) in &self.triangle {
                        let q = next_point(
                            out,
                            &mut used,
                            p0.0 + r * (p1.0 - p0.0) + s * (p2.0 - p0.0),
                            p0.1 + r * (p1.1 - p0.1) + s * (p2.1 - p0.1),
                            w * det.abs(),
                        );
                        q.n.resize(4, 0.0);
                        q.grad.resize(4, [0.0; 2]);
                        for (k, (l, g)) in [(1.0 - r - s, g0), (r, g1), (s, g2)].into_iter().enumerate() {
                            q.n[tri[k]] = l;
                            q.grad[tri[k]] = g;
                        }
                    }
                }
            }
        }
        out.truncate(used);
    }
}

/// The point after the `used` ones of `out` (a reused one, its shape functions cleared, or a
/// new one), at (x, y) with `weight`.
fn next_point<'a>(
    out: &'a mut Vec<QuadPoint>,
    used: &mut usize,
    x: f64,
    y: f64,
    weight: f64,
) -> &'a mut QuadPoint {
    if *used == out.len() {
        out.push(QuadPoint {
            x,
            y,
            weight,
            n: Vec::new(),
            grad: Vec::new(),
        });
    }
    let q = &mut out[*used];
    *used += 1;
    (q.x, q.y, q.weight) = (x, y, weight);
    q.n.clear();
    q.grad.clear();
    q
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
    let nodes = cell_node_array(mesh, ci, cj);
    let (mut val, mut grad) = ([0.0; 2], [0.0; 4]);
    let mut add = |k: usize, n: f64, g: [f64; 2]| add_node(&mut val, &mut grad, u, nodes[k], n, g);
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

    /// One [`CellRule`] walked over cells of different sizes with one reused buffer gives at
    /// every point the weight of the cell's area share and, through [`field_at`], the field
    /// that [`evaluate`] finds from the point's coordinates alone (another path: locate the
    /// cell, map back to the reference cell, evaluate the basis there).
    #[test]
    fn a_reused_cell_rule_gives_each_cells_points() {
        for el in Element::ALL {
            let m = Mesh::from_lines(el, vec![-1.0, -0.2, 0.5, 2.0], vec![0.0, 0.7, 1.0], false);
            let w: Vec<f64> = (0..2 * m.n_nodes())
                .map(|k| ((k * 37 % 11) as f64).sin())
                .collect();
            let rule = CellRule::new(el, 4);
            let mut quad = Vec::new();
            for cj in [1, 0] {
                for ci in [2, 0, 1] {
                    rule.points_into(&m, ci, cj, &mut quad);
                    let (x0, x1, y0, y1) = m.cell_rect(ci, cj);
                    let area: f64 = quad.iter().map(|q| q.weight).sum();
                    assert!(
                        (area - (x1 - x0) * (y1 - y0)).abs() < 1e-14,
                        "{el:?} cell ({ci}, {cj})"
                    );
                    let nodes = m.cell_nodes(ci, cj);
                    for q in &quad {
                        assert!(q.x > x0 && q.x < x1 && q.y > y0 && q.y < y1);
                        let (v, g) = field_at(q, &nodes, &w);
                        let (ve, ge) = evaluate(&m, &w, q.x, q.y);
                        for (a, b) in v.iter().chain(&g).zip(ve.iter().chain(&ge)) {
                            assert!((a - b).abs() < 1e-12, "{el:?} cell ({ci}, {cj}): {a} against {b}");
                        }
                    }
                }
            }
        }
    }
}
