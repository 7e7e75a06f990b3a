//! K factorised as two subdomains, one per core.
//!
//! The grid's middle node column ([`super::ordering::middle_column`]) splits the free dofs into
//! L (left of it), R (right of it) and Γ: the column's own dofs J and the trace T (Γ_C's normal
//! dofs). No cell has nodes on both sides of a node column, so no entry of K couples L and R:
//!
//!   K = [K_LL 0 K_LΓ; 0 K_RR K_RΓ; K_ΓL K_ΓR K_ΓΓ],
//!   S = K_ΓΓ − K_ΓL K_LL⁻¹ K_LΓ − K_ΓR K_RR⁻¹ K_RΓ   (K's Schur complement on Γ).
//!
//! Each half h factorises the interior of the principal submatrix K_h = K[h ∪ Γ_h] (Γ_h: J and
//! the trace dofs on its side of the column, the only dofs of Γ that couple with h; SPD as K is)
//! with Γ_h last, on a thread of its own: the grid's nested dissection of the half, then Γ_h.
//! The factorisation stops before Γ_h (`src/fem/partial.rs`), whose block is left as
//! S_h = K[Γ_h, Γ_h] − K_Γh K_hh⁻¹ K_hΓ, so that
//!
//!   S = S_L + S_R − K on (Γ_L ∩ Γ_R)²
//!
//! (the column's dofs, where both halves count K). S is dense, ordered J then T; the trailing
//! block of its Cholesky factor is the Schur complement factor on the trace that a single
//! factor's trailing block is ([`super::condense`]), and the compliance C = S_T⁻¹ follows.
//! Without a middle column, or below [`super::factor::SPLIT_UNKNOWNS`] unknowns, the whole grid
//! is one part ([`SplitOrdering::whole`]): Γ is the trace alone and S its Schur complement.
//! A solve eliminates L and R (each half's forward substitution), solves with S on Γ and
//! back-substitutes each half.

use std::sync::Arc;

use faer::sparse::SymbolicSparseColMatRef;

use super::SymCsc;
use super::dofs::DofMap;
use super::error::FemError;
use super::ordering::{middle_column, nested_dissection_of_columns};
use super::partial::PartialOrdering;
use super::supernodes::of_dissection;
use crate::mesh::Mesh;

mod factor;
pub use factor::{SplitFactor, SplitValues};

/// The analysis of both halves, or of the whole grid as one part (one per mesh; cheap to
/// clone).
#[derive(Clone)]
pub struct SplitOrdering(Arc<Split>);

struct Split {
    /// The number of free dofs of K.
    n: usize,
    /// Γ: the column's dofs J, then the trace in the caller's order.
    gamma: Vec<usize>,
    /// The number of trace dofs (the last of Γ).
    n_trace: usize,
    /// The left and the right half, or the whole grid as one part.
    halves: Vec<Half>,
    /// K's entries on (Γ_L ∩ Γ_R)², its lower triangle: (row in Γ, column in Γ, position in
    /// K's values).
    overlap: Vec<(usize, usize, usize)>,
}

/// One half h: the principal submatrix K[h ∪ Γ_h] and its analysis.
struct Half {
    /// The order of K_h.
    n: usize,
    /// The pattern of K_h's lower triangle in elimination order (h, then Γ_h), compressed
    /// columns (each column's rows unsorted); u32 indices, as every index of K fits
    /// ([`Half::new`]).
    col_ptr: Vec<u32>,
    row_idx: Vec<u32>,
    /// The position in K's values of each entry of the pattern.
    gather: Vec<u32>,
    /// The analysis of K_h (in its own order, Γ_h last).
    ordering: PartialOrdering<u32>,
    /// The dof of K at each elimination position of h.
    interior: Vec<usize>,
    /// The index in Γ of each trailing position (Γ_h, ascending in Γ).
    gamma: Vec<usize>,
}

impl SplitOrdering {
    /// Analyse `a`, the form on `mesh` over `dofs`, as two halves beside the grid's middle
    /// column with Γ = (the column's dofs, `trace`) last; None when the grid has no middle
    /// column. The halves are analysed on two threads when [`super::set_threads`] allows.
    pub fn new(a: &SymCsc, mesh: &Mesh, dofs: &DofMap, trace: &[usize]) -> Result<Option<Self>, FemError> {
        match middle_column(mesh) {
            Some(s) => Self::beside(a, mesh, dofs, trace, Some(s)).map(Some),
            None => Ok(None),
        }
    }

    /// Analyse `a` as one part, the whole grid, with Γ = `trace` last: one partial factor of
    /// the grid's nested dissection, and S the Schur complement on the trace.
    pub fn whole(a: &SymCsc, mesh: &Mesh, dofs: &DofMap, trace: &[usize]) -> Result<Self, FemError> {
        Self::beside(a, mesh, dofs, trace, None)
    }

    /// The halves beside the node column `middle`, or the whole grid as one part.
    fn beside(
        a: &SymCsc,
        mesh: &Mesh,
        dofs: &DofMap,
        trace: &[usize],
        middle: Option<usize>,
    ) -> Result<Self, FemError> {
        let n = a.n;
        // Every index here and in the halves (a node, a dof, an entry of K_h, a position in
        // K's values) is less than K's number of entries or the mesh's number of nodes: when
        // those fit in u32, so do they all. They do up to 4·10⁹, 64 GB of K, which the memory
        // guard refuses long before.
        if u32::try_from(a.nnz()).is_err() || u32::try_from(mesh.n_nodes()).is_err() {
            return Err(FemError::OutOfMemory("the ordering"));
        }
        // The node and the node column of every free dof, and Γ's index of Γ's dofs.
        let mut node_of = vec![0u32; n];
        let mut column = vec![0usize; n];
        let mut gamma = Vec::new();
        for j in 0..mesh.node_y.len() {
            for i in 0..mesh.nnx() {
                let node = mesh.node(i, j);
                for comp in 0..2 {
                    if let Some(d) = dofs.free_index(2 * node + comp) {
                        node_of[d] = node as u32;
                        column[d] = i;
                        if Some(i) == middle {
                            gamma.push(d);
                        }
                    }
                }
            }
        }
        let mut in_gamma = vec![usize::MAX; n];
        for &d in trace {
            in_gamma[d] = 0;
        }
        gamma.retain(|&d| in_gamma[d] == usize::MAX);
        gamma.extend_from_slice(trace);
        for (k, &d) in gamma.iter().enumerate() {
            in_gamma[d] = k;
        }
        let n_columns = mesh.nnx();
        let at = Dofs {
            node: &node_of,
            column: &column,
        };
        let parts = match middle {
            Some(s) => vec![(0, s), (s + 1, n_columns)],
            None => vec![(0, n_columns)],
        };
        let halves = each(parts, |columns| {
            Half::new(a, mesh, dofs, trace, columns, middle, at, &gamma)
        });
        let mut overlap = Vec::new();
        for &c in gamma.iter().filter(|&&d| Some(column[d]) == middle) {
            for k in a.col_ptr[c]..a.col_ptr[c + 1] {
                let r = a.row_idx[k];
                if in_gamma[r] != usize::MAX && Some(column[r]) == middle {
                    overlap.push((in_gamma[r], in_gamma[c], k));
                }
            }
        }
        Ok(SplitOrdering(Arc::new(Split {
            n,
            n_trace: trace.len(),
            gamma,
            halves: halves.into_iter().collect::<Result<_, _>>()?,
            overlap,
        })))
    }

    /// The stored values of both halves' factors and of S's dense factor (its lower triangle).
    pub fn factor_len(&self) -> usize {
        let ng = self.0.gamma.len();
        self.0
            .halves
            .iter()
            .map(|h| h.ordering.factor_len())
            .sum::<usize>()
            + ng * (ng + 1) / 2
    }

    /// Floating point operations of one factorisation ([`super::condense::factor_flops`]): both
    /// halves' interiors, and S's dense Cholesky factor (Σ_{c=1}^{|Γ|} c²).
    pub fn factor_flops(&self) -> f64 {
        let dense: f64 = (1..=self.0.gamma.len()).map(|c| (c as f64) * (c as f64)).sum();
        self.0
            .halves
            .iter()
            .map(|h| h.ordering.factor_flops())
            .sum::<f64>()
            + dense
    }
}

/// `f` of each item, side by side on two threads when there are two and
/// [`super::set_threads`] allows ([`super::join`]), in the items' order.
fn each<A: Send, T: Send>(items: Vec<A>, f: impl Fn(A) -> T + Sync) -> Vec<T> {
    match <[A; 2]>::try_from(items) {
        Ok([a, b]) => {
            let (a, b) = super::join(|| f(a), || f(b));
            vec![a, b]
        }
        Err(items) => items.into_iter().map(f).collect(),
    }
}

/// Where each free dof of K lies: its node, and the node's column in the grid.
#[derive(Clone, Copy)]
struct Dofs<'a> {
    node: &'a [u32],
    column: &'a [usize],
}

impl Half {
    /// The half of the node columns `columns` beside the middle column `s` (or the whole grid,
    /// with no middle column); `at` tells where
    /// each dof lies and `gamma` is Γ's dofs.
    #[allow(clippy::too_many_arguments)]
    fn new(
        a: &SymCsc,
        mesh: &Mesh,
        dofs: &DofMap,
        trace: &[usize],
        columns: (usize, usize),
        s: Option<usize>,
        at: Dofs<'_>,
        gamma: &[usize],
    ) -> Result<Self, FemError> {
        let column = at.column;
        // h ∪ Γ_h in elimination order: the half's nested dissection, then the dofs of Γ on
        // the middle column or in the half's columns.
        let dissection = nested_dissection_of_columns(mesh, dofs, trace, columns);
        let interior = &dissection.order;
        let inside = |d: usize| (columns.0..columns.1).contains(&column[d]) || Some(column[d]) == s;
        let half_gamma: Vec<usize> = (0..gamma.len()).filter(|&g| inside(gamma[g])).collect();
        // h ∪ Γ_h's dofs in elimination order, and each one's position in it.
        let members: Vec<usize> = interior
            .iter()
            .copied()
            .chain(half_gamma.iter().map(|&g| gamma[g]))
            .collect();
        let n_h = members.len();
        // Each index fits in u32 ([`SplitOrdering::new`]).
        let narrow = |i: usize| i as u32;
        const OUTSIDE: u32 = u32::MAX;
        let mut position = vec![OUTSIDE; a.n];
        for (p, &d) in members.iter().enumerate() {
            position[d] = narrow(p);
        }
        // K_h's lower triangle in that order (so that faer need not permute it): entry (r, c)
        // of K goes to column min(p_r, p_c). Only the half's own columns of K are read: the
        // other half's entries never couple with it. The rows of a column are left unsorted:
        // the analysis reads the transpose, sorted as it is built, and the factorisation
        // gathers K_h's entries in any order (sorting them took 3% of a level-6 solve's
        // instructions, BENCHMARKS.md).
        let mut col_ptr = vec![0usize; n_h + 1];
        let position = &position;
        let entries = |pc: usize, c: usize| {
            (a.col_ptr[c]..a.col_ptr[c + 1])
                .map(move |k| (position[a.row_idx[k]], k))
                .filter(|&(pr, _)| pr != OUTSIDE)
                .map(move |(pr, k)| (pr as usize, pc, k))
        };
        for (pc, &c) in members.iter().enumerate() {
            for (pr, pc, _) in entries(pc, c) {
                col_ptr[pr.min(pc) + 1] += 1;
            }
        }
        for j in 0..n_h {
            col_ptr[j + 1] += col_ptr[j];
        }
        // Rows and positions are written straight into their final arrays: no array of pairs
        // the size of K_h, which at level 8 was 0.3 GB of fresh memory per half (BENCHMARKS.md,
        // "Fresh memory").
        let mut next = col_ptr.clone();
        let mut row_idx = vec![0u32; col_ptr[n_h]];
        let mut gather = vec![0u32; col_ptr[n_h]];
        for (pc, &c) in members.iter().enumerate() {
            for (pr, pc, k) in entries(pc, c) {
                let j = pr.min(pc);
                row_idx[next[j]] = narrow(pr.max(pc));
                gather[next[j]] = narrow(k);
                next[j] += 1;
            }
        }
        let col_ptr: Vec<u32> = col_ptr.into_iter().map(narrow).collect();
        // The factor's supernodes from the dissection's blocks, Γ_h the last.
        let n_interior = interior.len();
        let interface: Vec<usize> = members[n_interior..]
            .iter()
            .map(|&d| at.node[d] as usize)
            .collect();
        let node_dofs = |node: usize| [0, 1].map(|comp| dofs.free_index(2 * node + comp));
        let supernodes = of_dissection(mesh, node_dofs, &dissection, position, &interface, n_h)?;
        Ok(Half {
            n: n_h,
            col_ptr,
            row_idx,
            gather,
            ordering: PartialOrdering::new(supernodes, n_interior),
            interior: dissection.order,
            gamma: half_gamma,
        })
    }

    /// K_h's pattern (lower triangle, elimination order; each column's rows unsorted).
    fn pattern(&self) -> SymbolicSparseColMatRef<'_, u32> {
        SymbolicSparseColMatRef::new_unsorted_checked(self.n, self.n, &self.col_ptr, None, &self.row_idx)
    }
}

impl SplitOrdering {
    /// The entries of `a` (with the pattern this ordering analysed) that its factorisation
    /// reads.
    pub fn values(&self, a: &SymCsc) -> SplitValues {
        let split = &*self.0;
        let gather = |h: &Half| h.gather.iter().map(|&k| a.values[k as usize]).collect();
        SplitValues {
            halves: each(split.halves.iter().collect(), gather),
            overlap: split.overlap.iter().map(|&(_, _, k)| a.values[k]).collect(),
            storage: Vec::new(),
        }
    }

    /// As [`SplitOrdering::values`], giving up `a`: its two largest arrays, the values and the
    /// row indices (both eight bytes an entry), become the memory of the halves' factors, which
    /// grow them in place (the pages K touched are not faulted in again).
    pub fn values_of(&self, a: SymCsc) -> SplitValues {
        let mut values = self.values(&a);
        let SymCsc {
            values: k_values,
            row_idx,
            ..
        } = a;
        // Where usize is not eight bytes the row indices are simply freed.
        let row_idx = bytemuck::allocation::try_cast_vec(row_idx).unwrap_or_default();
        values.storage = vec![k_values, row_idx];
        values
    }
}

#[cfg(test)]
mod tests {
    use faer::Mat;

    use super::super::partial::PartialFactor;
    use super::*;
    use crate::fem::{Form, assemble};
    use crate::mesh::Element;

    use crate::fem::gather::Kernel;
    use nalgebra::DMatrix;

    /// The H¹ form on an nx × ny grid of `element`, with its two halves' and its one part's
    /// analyses (the model's contact dofs last).
    fn both_kinds(element: Element, nx: usize, ny: usize, symmetric: bool) -> (SymCsc, [SplitOrdering; 2]) {
        let mesh = Mesh::uniform(element, (0.0, 2.0, nx), (0.0, 1.0, ny), symmetric);
        let dofs = DofMap::model(&mesh);
        let k = assemble(&mesh, &dofs, Form::H1);
        let trace = dofs.contact_dofs(&mesh);
        let halves = SplitOrdering::new(&k, &mesh, &dofs, &trace).unwrap().unwrap();
        let whole = SplitOrdering::whole(&k, &mesh, &dofs, &trace).unwrap();
        (k, [halves, whole])
    }

    /// Each half's K_h, dense, from its pattern (lower triangle, elimination order).
    fn dense(h: &Half, k: &SymCsc) -> DMatrix<f64> {
        let mut a = DMatrix::zeros(h.n, h.n);
        for c in 0..h.n {
            for t in h.col_ptr[c] as usize..h.col_ptr[c + 1] as usize {
                let (r, v) = (h.row_idx[t] as usize, k.values[h.gather[t] as usize]);
                a[(r, c)] = v;
                a[(c, r)] = v;
            }
        }
        a
    }

    /// The supernodes read from the grid (`super::supernodes`) hold the exact pattern of each
    /// half's factor: each supernode's rows below it are the union of its columns' rows of L
    /// past it, L's rows found by eliminating K_h's graph one vertex at a time (each vertex's
    /// later neighbours become a clique), for every element, on grids with odd and even node
    /// counts, with and without the mirror symmetry; and so do the whole grid's as one part.
    /// Γ_h is the last supernode, alone.
    #[test]
    fn the_grids_supernodes_hold_the_factors_pattern() {
        use std::collections::BTreeSet;
        for element in Element::ALL {
            for (nx, ny, symmetric) in [(12, 6, true), (9, 7, false), (24, 13, true), (6, 17, false)] {
                let (_, [halves, whole]) = both_kinds(element, nx, ny, symmetric);
                for h in halves.0.halves.iter().chain(&whole.0.halves) {
                    let mut later: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); h.n];
                    for c in 0..h.n {
                        for t in h.col_ptr[c] as usize..h.col_ptr[c + 1] as usize {
                            let r = h.row_idx[t] as usize;
                            if r != c {
                                later[r.min(c)].insert(r.max(c));
                            }
                        }
                    }
                    for j in 0..h.n {
                        let rows: Vec<usize> = later[j].iter().copied().collect();
                        for (a, &r) in rows.iter().enumerate() {
                            later[r].extend(rows[a + 1..].iter().copied());
                        }
                    }
                    let sup = h.ordering.supernodes();
                    let last = sup.n_supernodes() - 1;
                    assert_eq!(sup.columns(last), h.interior.len()..h.n);
                    assert!(sup.pattern(last).is_empty());
                    for s in 0..sup.n_supernodes() {
                        let end = sup.columns(s).end;
                        let exact: Vec<usize> = sup
                            .columns(s)
                            .flat_map(|j| later[j].iter().copied())
                            .filter(|&r| r >= end)
                            .collect::<BTreeSet<_>>()
                            .into_iter()
                            .collect();
                        let pattern: Vec<usize> = sup.pattern(s).iter().map(|&r| r as usize).collect();
                        assert_eq!(pattern, exact, "{element:?} {nx}×{ny} supernode {s} of {last}");
                    }
                }
            }
        }
    }

    /// Each half's partial factor (and the whole grid's, as one part) leaves the Schur
    /// complement S_h = K₂₂ − K₂₁ K₁₁⁻¹ K₁₂ of K_h on Γ_h, equal to a dense computation's,
    /// with faer's gather-scatter kernel and with the dense product alike; and it eliminates the interior so that a solve with S_h and the
    /// back substitution solve with K_h.
    #[test]
    fn each_halfs_partial_factor_leaves_its_schur_complement() {
        for element in Element::ALL {
            for (nx, ny) in [(12, 6), (24, 13)] {
                let (k, [halves, whole]) = both_kinds(element, nx, ny, true);
                for h in halves.0.halves.iter().chain(&whole.0.halves) {
                    let a = dense(h, &k);
                    let n0 = h.interior.len();
                    let ng = h.n - n0;
                    let k11 = a.view((0, 0), (n0, n0)).into_owned().cholesky().unwrap();
                    let k12 = a.view((0, n0), (n0, ng)).into_owned();
                    let expect = a.view((n0, n0), (ng, ng)) - k12.transpose() * k11.solve(&k12);
                    let scale = expect.amax();
                    let values: Vec<f64> = h.gather.iter().map(|&t| k.values[t as usize]).collect();
                    for kernel in [Kernel::detect(), Kernel::Dense] {
                        let f =
                            PartialFactor::with_kernel(&h.ordering, h.pattern(), &values, Vec::new(), kernel)
                                .unwrap();
                        let mut s_h = DMatrix::zeros(ng, ng);
                        f.for_each_schur_entry(|i, j, v| s_h[(i, j)] = v);
                        for j in 0..ng {
                            for i in j..ng {
                                assert!(
                                    (s_h[(i, j)] - expect[(i, j)]).abs() <= 1e-12 * scale,
                                    "{element:?} {nx}×{ny} {kernel:?}: S_h[{i},{j}]"
                                );
                            }
                        }
                        // K_h x = b: eliminate, solve with S_h on Γ_h, back-substitute.
                        let x: Vec<f64> = (0..h.n).map(|i| ((i * 7919) % 113) as f64 - 56.0).collect();
                        let b = &a * nalgebra::DVector::from_column_slice(&x);
                        let mut u = Mat::<f64>::from_fn(h.n, 1, |i, _| b[i]);
                        f.eliminate_interior(u.as_mut());
                        let s_full = DMatrix::from_fn(ng, ng, |i, j| s_h[(i.max(j), i.min(j))]);
                        let trailing = nalgebra::DVector::from_fn(ng, |i, _| u[(n0 + i, 0)]);
                        let solved = s_full.cholesky().unwrap().solve(&trailing);
                        for (i, v) in solved.iter().enumerate() {
                            u[(n0 + i, 0)] = *v;
                        }
                        f.back_substitute_interior(u.as_mut());
                        let error = (0..h.n).map(|i| (u[(i, 0)] - x[i]).abs()).fold(0.0, f64::max);
                        assert!(error < 1e-9 * 56.0, "{element:?} {nx}×{ny} {kernel:?}: {error:e}");
                    }
                }
            }
        }
    }
}
