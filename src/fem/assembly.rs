//! Assembly of the bilinear forms a(·,·) of (2) and (·,·)₁ of (7) into a sparse symmetric
//! matrix on the free dofs (lower triangle, compressed columns, ready for faer's Cholesky),
//! and the matrix-free operators used for reactions, loads and errors.
//!
//! Cell matrices depend only on a cell's size (and a P1 cell's diagonal), so each distinct
//! cell is integrated once (small dense work with nalgebra) and scattered everywhere it occurs.

use std::collections::HashMap;

use faer::Par;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use nalgebra::{DMatrix, Matrix4};

use super::basis::{QuadPoint, cell_points, exact_order};
use super::dofs::DofMap;
use crate::material::Material;
use crate::mesh::{Diagonal, Mesh};

/// How the elastic stiffness is integrated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
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

/// What a cell matrix depends on: the cell's width, height and diagonal.
type CellKey = (u64, u64, bool);

/// Cell matrices keyed by what they depend on ([`CellKey`]); the last one asked for is found
/// without hashing (neighbouring cells share it on the grid's uniform stretches).
struct CellMatrices<'a> {
    mesh: &'a Mesh,
    form: Form,
    index: HashMap<CellKey, usize>,
    matrices: Vec<DMatrix<f64>>,
    last: Option<(CellKey, usize)>,
}

impl<'a> CellMatrices<'a> {
    fn new(mesh: &'a Mesh, form: Form) -> Self {
        CellMatrices {
            mesh,
            form,
            index: HashMap::new(),
            matrices: Vec::new(),
            last: None,
        }
    }

    fn get(&mut self, ci: usize, cj: usize) -> &DMatrix<f64> {
        let (x0, x1, y0, y1) = self.mesh.cell_rect(ci, cj);
        let rising = self.mesh.diagonal(ci) == Diagonal::Rising;
        let key = ((x1 - x0).to_bits(), (y1 - y0).to_bits(), rising);
        let k = match self.last {
            Some((last, k)) if last == key => k,
            _ => {
                let (mesh, form, matrices) = (self.mesh, self.form, &mut self.matrices);
                let k = *self.index.entry(key).or_insert_with(|| {
                    matrices.push(cell_matrix(mesh, ci, cj, &form));
                    matrices.len() - 1
                });
                self.last = Some((key, k));
                k
            }
        };
        &self.matrices[k]
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
    /// their nodes share a cell. On the grid, the nodes that share a cell with node (i, j) are
    /// a rectangle of nodes (`coupled_nodes` in each direction), so each column's rows are
    /// read off in ascending order without adjacency lists.
    pub fn pattern(mesh: &Mesh, dofs: &DofMap) -> Self {
        let (nnx, nny, p) = (mesh.nnx(), mesh.node_y.len(), mesh.element.order());
        let n = dofs.n_free();
        // Each dof couples with at most (2p + 1)² nodes' two dofs; about half are below it.
        let per_column = (2 * p + 1) * (2 * p + 1) + 1;
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::with_capacity(n * per_column);
        col_ptr.push(0);
        for j in 0..nny {
            let rows_j = coupled_nodes(j, nny, p);
            for i in 0..nnx {
                let rows_i = coupled_nodes(i, nnx, p);
                let node = mesh.node(i, j);
                for comp in 0..2 {
                    let Some(c) = dofs.free_index(2 * node + comp) else {
                        continue;
                    };
                    for jj in rows_j.clone() {
                        for ii in rows_i.clone() {
                            let m = mesh.node(ii, jj);
                            for b in 0..2 {
                                if let Some(r) = dofs.free_index(2 * m + b).filter(|&r| r >= c) {
                                    row_idx.push(r);
                                }
                            }
                        }
                    }
                    col_ptr.push(row_idx.len());
                }
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

/// The node indices along one grid direction (`count` nodes, element order `p`) that share a
/// cell with node `i`: the cells on both sides of a vertex line (i a multiple of p), the one
/// cell around an inner node of a Q2 cell otherwise.
fn coupled_nodes(i: usize, count: usize, p: usize) -> std::ops::RangeInclusive<usize> {
    let first = i - i % p;
    if i.is_multiple_of(p) {
        first.saturating_sub(p)..=(first + p).min(count - 1)
    } else {
        first..=first + p
    }
}

/// Assemble `form` on the free dofs of `dofs`: the pattern ([`SymCsc::pattern`]), then the
/// cell matrices scattered into it, the columns of the lower and the upper node rows on two
/// threads when [`super::set_threads`] allows and the mesh is large enough to gain (50,000
/// unknowns, as the factorisation); each thread writes only its own columns, so the sums, and
/// the bits, do not depend on the threads.
pub fn assemble(mesh: &Mesh, dofs: &DofMap, form: Form) -> SymCsc {
    let mut a = SymCsc::pattern(mesh, dofs);
    // The columns of the node rows below `split` and from it on.
    let split = mesh.node_y.len() / 2;
    let first_upper = (2 * mesh.node(0, split)..2 * mesh.n_nodes())
        .find_map(|g| dofs.free_index(g))
        .unwrap_or(a.n);
    let (lower, upper) = a.values.split_at_mut(a.col_ptr[first_upper]);
    let (pattern, p) = ((&a.col_ptr[..], &a.row_idx[..]), mesh.element.order());
    // A cell spans the node rows cj·p ..= cj·p + p.
    let cells_lower = (0..mesh.ny()).filter(|&cj| cj * p < split);
    let cells_upper = (0..mesh.ny()).filter(|&cj| cj * p + p >= split);
    let lower = || scatter(mesh, dofs, form, pattern, (0, first_upper), lower, cells_lower);
    let upper = || scatter(mesh, dofs, form, pattern, (first_upper, a.n), upper, cells_upper);
    if super::sparse_parallelism(a.n) == Par::Seq {
        lower();
        upper();
    } else {
        super::join(lower, upper);
    }
    a
}

/// Add the cell matrices of the cell rows `cell_rows` into `values`, the values of the
/// columns `columns.0 ≤ c < columns.1` of the pattern (`col_ptr`, `row_idx`); entries of other
/// columns are left to their owner.
fn scatter(
    mesh: &Mesh,
    dofs: &DofMap,
    form: Form,
    (col_ptr, row_idx): (&[usize], &[usize]),
    columns: (usize, usize),
    values: &mut [f64],
    cell_rows: impl Iterator<Item = usize>,
) {
    let offset = col_ptr[columns.0];
    let mut cellmats = CellMatrices::new(mesh, form);
    // The cell's free dofs and their rows in the cell matrix (two dofs for each of at most 9
    // nodes, Q2's): ascending, as the cell's nodes are (tensor order, row by row) and the free
    // dofs are numbered node by node.
    let mut free = [(0usize, 0usize); 2 * 9];
    for cj in cell_rows {
        for ci in 0..mesh.nx() {
            let mut count = 0;
            for (local, node) in mesh.cell_node_iter(ci, cj).enumerate() {
                for comp in 0..2 {
                    if let Some(d) = dofs.free_index(2 * node + comp) {
                        free[count] = (d, 2 * local + comp);
                        count += 1;
                    }
                }
            }
            let free = &free[..count];
            let ke = cellmats.get(ci, cj);
            for (q, &(c, lq)) in free.iter().enumerate() {
                if !(columns.0..columns.1).contains(&c) {
                    continue;
                }
                // The rows r ≥ c of the cell, ascending, met in one walk down the column.
                let (lo, hi) = (col_ptr[c], col_ptr[c + 1]);
                let rows = &row_idx[lo..hi];
                let mut k = 0;
                for &(r, lp) in &free[q..] {
                    while rows[k] < r {
                        k += 1;
                    }
                    values[lo + k - offset] += ke[(lp, lq)];
                }
            }
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Plane;
    use crate::mesh::Element;

    /// Meshes of every element, full and half models, from one cell to several across and up.
    fn meshes() -> Vec<(Mesh, DofMap)> {
        let mut out = Vec::new();
        for element in Element::ALL {
            for (nx, ny) in [(1, 1), (2, 1), (1, 3), (3, 5), (4, 4)] {
                for symmetric in [false, true] {
                    let mesh = Mesh::uniform(element, (0.0, 3.0, nx), (0.0, 2.0, ny), symmetric);
                    let dofs = DofMap::model(&mesh);
                    out.push((mesh, dofs));
                }
            }
        }
        out
    }

    /// The grid's pattern is the one of its cells: each free dof's column holds, ascending,
    /// the free dofs below the diagonal of every node that shares a cell with its node (read
    /// here from the cells' node lists, not from the grid's rectangles).
    #[test]
    fn the_pattern_is_the_cells_adjacency() {
        for (mesh, dofs) in meshes() {
            let mut adjacency: Vec<Vec<usize>> = vec![Vec::new(); mesh.n_nodes()];
            for (ci, cj) in cells(&mesh) {
                let nodes = mesh.cell_nodes(ci, cj);
                for &a in &nodes {
                    adjacency[a].extend_from_slice(&nodes);
                }
            }
            let mut col_ptr = vec![0];
            let mut row_idx = Vec::new();
            for (node, adj) in adjacency.iter_mut().enumerate() {
                adj.sort_unstable();
                adj.dedup();
                for c in (0..2).filter_map(|comp| dofs.free_index(2 * node + comp)) {
                    let rows = adj.iter().flat_map(|&m| [2 * m, 2 * m + 1]);
                    row_idx.extend(rows.filter_map(|g| dofs.free_index(g)).filter(|&r| r >= c));
                    col_ptr.push(row_idx.len());
                }
            }
            let a = SymCsc::pattern(&mesh, &dofs);
            let what = format!("{:?} {}×{}", mesh.element, mesh.nx(), mesh.ny());
            assert_eq!(a.col_ptr, col_ptr, "{what}");
            assert_eq!(a.row_idx, row_idx, "{what}");
        }
    }

    /// Each entry is the sum of its cells' contributions in the cells' order, to the bit: the
    /// two column ranges (lower and upper node rows) miss no cell and count none twice.
    #[test]
    fn each_entry_sums_its_cells_in_order() {
        let material = Material {
            young: 210.0,
            poisson: 0.3,
            plane: Plane::Strain,
        };
        for (mesh, dofs) in meshes() {
            for form in [Form::Elasticity(material, Integration::Full), Form::H1] {
                let mut expected = SymCsc::pattern(&mesh, &dofs);
                for (ci, cj) in cells(&mesh) {
                    let ke = cell_matrix(&mesh, ci, cj, &form);
                    let free: Vec<Option<usize>> = cell_dofs(&mesh, ci, cj)
                        .iter()
                        .map(|&g| dofs.free_index(g))
                        .collect();
                    for (q, c) in free.iter().enumerate() {
                        for (p, r) in free.iter().enumerate() {
                            if let (Some(c), Some(r)) = (*c, *r)
                                && r >= c
                            {
                                let k = expected.position(r, c).unwrap();
                                expected.values[k] += ke[(p, q)];
                            }
                        }
                    }
                }
                let a = assemble(&mesh, &dofs, form);
                let differ = a
                    .values
                    .iter()
                    .zip(&expected.values)
                    .filter(|(x, y)| x.to_bits() != y.to_bits())
                    .count();
                assert_eq!(
                    differ,
                    0,
                    "{:?} {}×{} {form:?}",
                    mesh.element,
                    mesh.nx(),
                    mesh.ny()
                );
            }
        }
    }
}
