//! The L² projection of the quadrature stresses onto the vertices: the consistent mass matrix
//! solved by preconditioned conjugate gradients, cell by cell.

use std::collections::HashMap;

use super::{Stress, StressError, StressPoint, cells};
use crate::fem::basis::{cell_points, exact_order};
use crate::mesh::{Diagonal, Element, Mesh};

/// The L² projection of the quadrature stresses onto the nodal space: M σ̂ = ∫ N σ_h, the
/// mass matrix integrated by the same points (exact for Q1, Q2 and P1 on rectangles).
///
/// Solved by conjugate gradients preconditioned with M's diagonal, cell by cell without
/// assembling M (one cell mass matrix per distinct cell shape): the diagonally scaled
/// consistent mass matrix has a condition number bounded independently of h and of the
/// grading (Wathen 1987: its eigenvalues lie in [1/4, 9/4] for Q1 rectangles), so a few
/// dozen iterations reach round-off at any level, where a sparse Cholesky factorisation
/// would cost more than everything else here.
pub(super) fn project(mesh: &Mesh, elements: &[Vec<StressPoint>]) -> Result<Vec<Stress>, StressError> {
    let n = mesh.n_nodes();
    let per_cell = if mesh.element == Element::P1 { 2 } else { 1 };
    let mut shapes: HashMap<(u64, u64, bool), usize> = HashMap::new();
    let mut masses: Vec<Vec<f64>> = Vec::new();
    let mut cell_shape = Vec::with_capacity(mesh.n_cells());
    let mut connectivity = Vec::new();
    let mut rhs = vec![[0.0; 4]; n];
    let mut diagonal = vec![0.0; n];
    for (ci, cj) in cells(mesh) {
        let nodes = mesh.cell_nodes(ci, cj);
        let nn = nodes.len();
        let pts = cell_points(mesh, ci, cj, exact_order(mesh.element));
        let (x0, x1, y0, y1) = mesh.cell_rect(ci, cj);
        let key = (
            (x1 - x0).to_bits(),
            (y1 - y0).to_bits(),
            mesh.diagonal(ci) == Diagonal::Rising,
        );
        let k = *shapes.entry(key).or_insert_with(|| {
            let mut m = vec![0.0; nn * nn];
            for q in &pts {
                for a in 0..nn {
                    for b in 0..nn {
                        m[a * nn + b] += q.weight * q.n[a] * q.n[b];
                    }
                }
            }
            masses.push(m);
            masses.len() - 1
        });
        for (a, &na) in nodes.iter().enumerate() {
            diagonal[na] += masses[k][a * nn + a];
        }
        let e = per_cell * (cj * mesh.nx() + ci);
        let stresses = elements[e..e + per_cell].iter().flatten();
        for (q, sp) in pts.iter().zip(stresses) {
            let s = &sp.stress;
            for (&node, &na) in nodes.iter().zip(&q.n) {
                for (r, v) in rhs[node].iter_mut().zip([s.xx, s.yy, s.xy, s.zz]) {
                    *r += q.weight * na * v;
                }
            }
        }
        cell_shape.push(k);
        connectivity.extend(nodes);
    }
    let nn = connectivity.len() / mesh.n_cells().max(1);
    let apply = |x: &[[f64; 4]], y: &mut [[f64; 4]]| {
        y.iter_mut().for_each(|v| *v = [0.0; 4]);
        for (nodes, &k) in connectivity.chunks(nn).zip(&cell_shape) {
            let m = &masses[k];
            for (a, &na) in nodes.iter().enumerate() {
                let mut acc = [0.0; 4];
                for (b, &nb) in nodes.iter().enumerate() {
                    let w = m[a * nn + b];
                    for c in 0..4 {
                        acc[c] += w * x[nb][c];
                    }
                }
                for c in 0..4 {
                    y[na][c] += acc[c];
                }
            }
        }
    };
    let solution = conjugate_gradients(&apply, &diagonal, &rhs)?;
    Ok(solution
        .into_iter()
        .map(|v| Stress {
            xx: v[0],
            yy: v[1],
            xy: v[2],
            zz: v[3],
        })
        .collect())
}

/// One row of four right-hand sides (σ_xx, σ_yy, σ_xy, σ_zz).
pub(super) type Columns = [f64; 4];

/// Solve A x = b for four right-hand sides at once by conjugate gradients preconditioned with
/// A's `diagonal`, to a relative residual of 1e-13 in each column.
pub(super) fn conjugate_gradients(
    apply: &dyn Fn(&[Columns], &mut [Columns]),
    diagonal: &[f64],
    b: &[[f64; 4]],
) -> Result<Vec<[f64; 4]>, StressError> {
    const TOLERANCE: f64 = 1e-13;
    const MAX_ITERATIONS: usize = 1000;
    let n = b.len();
    let dot = |u: &[[f64; 4]], v: &[[f64; 4]]| -> [f64; 4] {
        let mut s = [0.0; 4];
        for (x, y) in u.iter().zip(v) {
            for c in 0..4 {
                s[c] += x[c] * y[c];
            }
        }
        s
    };
    let precondition =
        |r: &[[f64; 4]]| -> Vec<[f64; 4]> { r.iter().zip(diagonal).map(|(v, d)| v.map(|x| x / d)).collect() };
    let norm_b = dot(b, b).map(f64::sqrt);
    let mut x = vec![[0.0; 4]; n];
    let mut r = b.to_vec();
    let mut z = precondition(&r);
    let mut p = z.clone();
    let mut rz = dot(&r, &z);
    let mut ap = vec![[0.0; 4]; n];
    for _ in 0..MAX_ITERATIONS {
        let rr = dot(&r, &r);
        if (0..4).all(|c| rr[c].sqrt() <= TOLERANCE * norm_b[c]) {
            return Ok(x);
        }
        apply(&p, &mut ap);
        let pap = dot(&p, &ap);
        let alpha: [f64; 4] = std::array::from_fn(|c| if pap[c] > 0.0 { rz[c] / pap[c] } else { 0.0 });
        for i in 0..n {
            for c in 0..4 {
                x[i][c] += alpha[c] * p[i][c];
                r[i][c] -= alpha[c] * ap[i][c];
            }
        }
        z = precondition(&r);
        let rz_next = dot(&r, &z);
        let beta: [f64; 4] = std::array::from_fn(|c| if rz[c] > 0.0 { rz_next[c] / rz[c] } else { 0.0 });
        for i in 0..n {
            for c in 0..4 {
                p[i][c] = z[i][c] + beta[c] * p[i][c];
            }
        }
        rz = rz_next;
    }
    Err(StressError::Projection {
        iterations: MAX_ITERATIONS,
        tolerance: TOLERANCE,
    })
}
