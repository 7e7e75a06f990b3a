//! Assembly of the bilinear forms a(·,·) of (2) and (·,·)₁ of (7) into a sparse symmetric
//! matrix on the free dofs (lower triangle, compressed columns, ready for faer's Cholesky),
//! and the matrix-free operators used for reactions, loads and errors.
//!
//! Cell matrices depend only on a cell's size (and a P1 cell's diagonal), so each distinct
//! cell is integrated once (small dense work with nalgebra) and scattered everywhere it occurs.

use std::collections::HashMap;

use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use nalgebra::{DMatrix, Matrix4};

use super::basis::{QuadPoint, cell_points, exact_order};
use super::dofs::DofMap;
use crate::material::Material;
use crate::mesh::{Diagonal, Mesh};

/// How the elastic stiffness is integrated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Deserialize, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Integration {
    /// Exactly (2×2 Gauss for Q1, 3×3 for Q2).
    #[default]
    Full,
    /// Selective reduced integration: the volumetric part λ (div u)(div v) with one Gauss
    /// order less (1 point for Q1, 2×2 for Q2), the rest exactly. It removes the volumetric
    /// locking of Q1 as ν → 1/2 (the reduced-integration idea of the paper's references 2–4).
    /// A P1 triangle has constant strains, so it changes nothing there.
    Selective,
}

/// A bilinear form assembled cell by cell: ∫ ∇vᵀ C ∇u + m ∫ v·u.
#[derive(Clone, Copy, Debug)]
pub enum Form {
    /// a(u, v) of (2).
    Elasticity(Material, Integration),
    /// The H¹ inner product (u, v)₁ of (7).
    H1,
}

/// The cell matrix over the cell's dofs, ordered (u_x, u_y) node by node in tensor order.
pub fn cell_matrix(mesh: &Mesh, ci: usize, cj: usize, form: &Form) -> DMatrix<f64> {
    let pts = cell_points(mesh, ci, cj, exact_order(mesh.element));
    match *form {
        Form::H1 => integrate_cell(&pts, &Matrix4::identity(), 1.0),
        Form::Elasticity(m, Integration::Full) => integrate_cell(&pts, &m.tensor(), 0.0),
        Form::Elasticity(m, Integration::Selective) => {
            let volumetric = m.volumetric_tensor();
            let reduced = cell_points(mesh, ci, cj, exact_order(mesh.element) - 1);
            integrate_cell(&pts, &(m.tensor() - volumetric), 0.0) + integrate_cell(&reduced, &volumetric, 0.0)
        }
    }
}

fn integrate_cell(pts: &[QuadPoint], c: &Matrix4<f64>, mass: f64) -> DMatrix<f64> {
    let nn = pts[0].n.len();
    let mut k = DMatrix::zeros(2 * nn, 2 * nn);
    let mut g = DMatrix::zeros(4, 2 * nn);
    for q in pts {
        for (a, d) in q.grad.iter().enumerate() {
            g[(0, 2 * a)] = d[0];
            g[(1, 2 * a)] = d[1];
            g[(2, 2 * a + 1)] = d[0];
            g[(3, 2 * a + 1)] = d[1];
        }
        k += g.transpose() * (c * &g) * q.weight;
        if mass != 0.0 {
            for a in 0..nn {
                for b in 0..nn {
                    let m = mass * q.weight * q.n[a] * q.n[b];
                    k[(2 * a, 2 * b)] += m;
                    k[(2 * a + 1, 2 * b + 1)] += m;
                }
            }
        }
    }
    k
}

/// Cell matrices keyed by what they depend on: the cell's size and diagonal.
struct CellMatrices<'a> {
    mesh: &'a Mesh,
    form: Form,
    cache: HashMap<(u64, u64, bool), DMatrix<f64>>,
}

impl<'a> CellMatrices<'a> {
    fn new(mesh: &'a Mesh, form: Form) -> Self {
        CellMatrices {
            mesh,
            form,
            cache: HashMap::new(),
        }
    }

    fn get(&mut self, ci: usize, cj: usize) -> &DMatrix<f64> {
        let (x0, x1, y0, y1) = self.mesh.cell_rect(ci, cj);
        let rising = self.mesh.diagonal(ci) == Diagonal::Rising;
        let key = ((x1 - x0).to_bits(), (y1 - y0).to_bits(), rising);
        let (mesh, form) = (self.mesh, self.form);
        self.cache
            .entry(key)
            .or_insert_with(|| cell_matrix(mesh, ci, cj, &form))
    }
}

fn cells(mesh: &Mesh) -> impl Iterator<Item = (usize, usize)> + use<> {
    let (nx, ny) = (mesh.nx(), mesh.ny());
    (0..ny).flat_map(move |cj| (0..nx).map(move |ci| (ci, cj)))
}

fn cell_dofs(mesh: &Mesh, ci: usize, cj: usize) -> Vec<usize> {
    mesh.cell_nodes(ci, cj)
        .iter()
        .flat_map(|&n| [2 * n, 2 * n + 1])
        .collect()
}

/// A symmetric sparse matrix stored as its lower triangle in compressed columns.
#[derive(Clone, Debug)]
pub struct SymCsc {
    /// The order of the matrix (free dofs).
    pub n: usize,
    /// Start of each column in `row_idx` and `values`, n + 1 entries.
    pub col_ptr: Vec<usize>,
    /// Row of each stored entry, ascending within a column, row ≥ column.
    pub row_idx: Vec<usize>,
    /// The stored entries, as `row_idx`.
    pub values: Vec<f64>,
}

impl SymCsc {
    /// The pattern of every form on `mesh` restricted to the free dofs: two dofs couple when
    /// their nodes share a cell.
    pub fn pattern(mesh: &Mesh, dofs: &DofMap) -> Self {
        let mut adjacency: Vec<Vec<usize>> = vec![Vec::new(); mesh.n_nodes()];
        for (ci, cj) in cells(mesh) {
            let nodes = mesh.cell_nodes(ci, cj);
            for &a in &nodes {
                adjacency[a].extend_from_slice(&nodes);
            }
        }
        let n = dofs.n_free();
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for (node, adj) in adjacency.iter_mut().enumerate() {
            adj.sort_unstable();
            adj.dedup();
            for comp in 0..2 {
                let Some(c) = dofs.free_index(2 * node + comp) else {
                    continue;
                };
                for &m in adj.iter() {
                    for b in 0..2 {
                        if let Some(r) = dofs.free_index(2 * m + b).filter(|&r| r >= c) {
                            row_idx.push(r);
                        }
                    }
                }
                col_ptr.push(row_idx.len());
            }
        }
        let values = vec![0.0; row_idx.len()];
        SymCsc {
            n,
            col_ptr,
            row_idx,
            values,
        }
    }

    /// Position of entry (row, col), row ≥ col, in `values`, if it is in the pattern.
    pub fn position(&self, row: usize, col: usize) -> Option<usize> {
        let (lo, hi) = (self.col_ptr[col], self.col_ptr[col + 1]);
        let k = lo + self.row_idx[lo..hi].partition_point(|&r| r < row);
        (k < hi && self.row_idx[k] == row).then_some(k)
    }

    /// The number of stored entries (the lower triangle).
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// A faer view of the lower triangle's pattern.
    pub fn symbolic(&self) -> SymbolicSparseColMatRef<'_, usize> {
        SymbolicSparseColMatRef::new_checked(self.n, self.n, &self.col_ptr, None, &self.row_idx)
    }

    /// A faer view of the lower triangle with the given values (same pattern).
    pub fn view<'a>(&'a self, values: &'a [f64]) -> SparseColMatRef<'a, usize, f64> {
        SparseColMatRef::new(self.symbolic(), values)
    }

    /// y = A x for the full symmetric matrix.
    pub fn mul(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.n];
        for c in 0..self.n {
            let (lo, hi) = (self.col_ptr[c], self.col_ptr[c + 1]);
            let xc = x[c];
            let mut acc = 0.0;
            for k in lo..hi {
                let (r, v) = (self.row_idx[k], self.values[k]);
                y[r] += v * xc;
                if r != c {
                    acc += v * x[r];
                }
            }
            y[c] += acc;
        }
        y
    }
}

/// Assemble `form` on the free dofs of `dofs`.
pub fn assemble(mesh: &Mesh, dofs: &DofMap, form: Form) -> SymCsc {
    let mut a = SymCsc::pattern(mesh, dofs);
    let mut cellmats = CellMatrices::new(mesh, form);
    for (ci, cj) in cells(mesh) {
        let free: Vec<Option<usize>> = cell_dofs(mesh, ci, cj)
            .iter()
            .map(|&g| dofs.free_index(g))
            .collect();
        let ke = cellmats.get(ci, cj);
        for (q, c) in free.iter().enumerate() {
            let Some(c) = *c else { continue };
            let (lo, hi) = (a.col_ptr[c], a.col_ptr[c + 1]);
            for (p, r) in free.iter().enumerate() {
                let Some(r) = r.filter(|&r| r >= c) else { continue };
                let k = lo + a.row_idx[lo..hi].partition_point(|&x| x < r);
                a.values[k] += ke[(p, q)];
            }
        }
    }
    a
}

/// K u on every dof (constraints ignored): the internal force, whose entries on the
/// Dirichlet dofs are the reactions.
pub fn apply(mesh: &Mesh, form: Form, u: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; u.len()];
    let mut cellmats = CellMatrices::new(mesh, form);
    for (ci, cj) in cells(mesh) {
        let dofs = cell_dofs(mesh, ci, cj);
        let ue = nalgebra::DVector::from_iterator(dofs.len(), dofs.iter().map(|&g| u[g]));
        let fe = cellmats.get(ci, cj) * ue;
        for (k, &g) in dofs.iter().enumerate() {
            y[g] += fe[k];
        }
    }
    y
}

/// The load vector ∫ f·v of a body force on every dof, with `n` Gauss points per direction.
pub fn body_load(mesh: &Mesh, f: impl Fn(f64, f64) -> [f64; 2], n: usize) -> Vec<f64> {
    let mut y = vec![0.0; 2 * mesh.n_nodes()];
    for (ci, cj) in cells(mesh) {
        let nodes = mesh.cell_nodes(ci, cj);
        for q in cell_points(mesh, ci, cj, n) {
            let fx = f(q.x, q.y);
            for (k, &node) in nodes.iter().enumerate() {
                y[2 * node] += q.weight * q.n[k] * fx[0];
                y[2 * node + 1] += q.weight * q.n[k] * fx[1];
            }
        }
    }
    y
}

/// ‖u − u_h‖₁ and ‖u‖₁ of (7) for an exact field `u` with gradient `grad` (rows ∂/∂x, ∂/∂y
/// of u_x, then of u_y), integrated with `n` Gauss points per direction.
pub fn h1_error(
    mesh: &Mesh,
    uh: &[f64],
    u: impl Fn(f64, f64) -> [f64; 2],
    grad: impl Fn(f64, f64) -> [f64; 4],
    n: usize,
) -> (f64, f64) {
    let (mut err, mut norm) = (0.0, 0.0);
    for (ci, cj) in cells(mesh) {
        let nodes = mesh.cell_nodes(ci, cj);
        for q in cell_points(mesh, ci, cj, n) {
            let mut val = [0.0; 2];
            let mut g = [0.0; 4];
            for (k, &node) in nodes.iter().enumerate() {
                for c in 0..2 {
                    let d = uh[2 * node + c];
                    val[c] += q.n[k] * d;
                    g[2 * c] += q.grad[k][0] * d;
                    g[2 * c + 1] += q.grad[k][1] * d;
                }
            }
            let (ue, ge) = (u(q.x, q.y), grad(q.x, q.y));
            let sq = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>();
            err += q.weight * (sq(&val, &ue) + sq(&g, &ge));
            norm += q.weight * (ue.iter().chain(&ge).map(|v| v * v).sum::<f64>());
        }
    }
    (err.sqrt(), norm.sqrt())
}
