//! A subdomain's partial Cholesky factorisation: its interior eliminated, the Schur
//! complement on its interface left in place.
//!
//! A half h of [`super::split`] orders K_h = [K₁₁ K₁₂; K₂₁ K₂₂] with its interface Γ_h last and
//! needs L₁₁ L₁₁ᵀ = K₁₁ and L₂₁ = K₂₁ L₁₁⁻ᵀ for its solves, and S_h = K₂₂ − L₂₁ L₂₁ᵀ for the
//! interface's S. A whole Cholesky factorisation forms S_h on the way and then factorises it
//! (L₂₂ L₂₂ᵀ = S_h), which the split had to multiply out again: two dense steps of |Γ_h|³/6
//! multiply-adds each for nothing (measured in BENCHMARKS.md, "Halves that stop before Γ"). This is
//! faer's left-looking supernodal factorisation (`factorize_supernodal_numeric_llt`) on the
//! supernodes the grid gives ([`super::supernodes`]), Γ_h the last, which is neither
//! factorised nor sends updates: the trailing block of the factor's storage ends as S_h's
//! lower triangle.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::linalg::triangular_solve;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::traits::Index;
use faer::{MatMut, MatRef, Par};

use super::condense::{Blocks, Layout, factor_storage};
use super::error::FemError;
use super::gather::{Kernel, subtract_lower_product};
use super::supernodes::Supernodes;

/// The supernodes of a matrix in elimination order whose last dofs are the interface, a
/// supernode of their own (cheap to clone).
#[derive(Clone)]
pub(super) struct PartialOrdering<I: Index> {
    supernodes: Arc<Supernodes<I>>,
    /// The number of dofs eliminated before the interface.
    n_interior: usize,
    /// Which supernodes update which ([`descendants`]), read once per factorisation.
    descendants: Arc<Descendants<I>>,
}

/// For each supernode s, the supernodes below it whose columns update it: compressed rows,
/// `of[start[s]..start[s + 1]]` ascending (faer keeps the same structure, private, in its
/// supernodal analysis).
struct Descendants<I: Index> {
    start: Vec<usize>,
    of: Vec<I>,
}

impl<I: Index> PartialOrdering<I> {
    /// The ordering of the supernodes `supernodes`, the interface being those from column
    /// `n_interior` on (a supernode's first column).
    pub(super) fn new(supernodes: Supernodes<I>, n_interior: usize) -> Self {
        debug_assert!(
            (0..supernodes.n_supernodes()).any(|s| supernodes.columns(s).start == n_interior)
                || n_interior == supernodes.nrows()
        );
        PartialOrdering {
            descendants: Arc::new(descendants(&supernodes, n_interior)),
            supernodes: Arc::new(supernodes),
            n_interior,
        }
    }

    /// The supernodes.
    #[cfg(test)]
    pub(super) fn supernodes(&self) -> &Supernodes<I> {
        &self.supernodes
    }

    /// The number of stored values of the factor (the interface's block included).
    pub(super) fn factor_len(&self) -> usize {
        self.supernodes.len_val()
    }

    /// Floating point operations of one [`PartialFactor`]: George and Liu's Σ c_j² over the
    /// interior's columns of L alone ([`super::condense::factor_flops`] counts every column),
    /// since the interface's columns are neither factorised nor send updates.
    pub(super) fn factor_flops(&self) -> f64 {
        let supernodes = &*self.supernodes;
        (0..supernodes.n_supernodes())
            .filter(|&s| supernodes.columns(s).start < self.n_interior)
            .map(|s| {
                let below = supernodes.pattern(s).len();
                let width = supernodes.columns(s).len();
                (0..width)
                    .map(|i| ((width - i + below) as f64).powi(2))
                    .sum::<f64>()
            })
            .sum()
    }
}

/// The factor of a [`PartialOrdering`]'s interior, with the Schur complement on the interface
/// in its trailing block.
pub(super) struct PartialFactor<I: Index> {
    ordering: PartialOrdering<I>,
    values: Vec<f64>,
}

impl<I: Index> PartialFactor<I> {
    /// Factorise the interior of the matrix with the pattern `pattern` (in elimination order,
    /// its own values not read) and the entries `values`, on one thread, in `storage`'s
    /// memory (its contents discarded).
    pub(super) fn new(
        ordering: &PartialOrdering<I>,
        pattern: SymbolicSparseColMatRef<'_, I>,
        values: &[f64],
        storage: Vec<f64>,
    ) -> Result<Self, FemError> {
        Self::with_kernel(ordering, pattern, values, storage, Kernel::detect())
    }

    /// As [`PartialFactor::new`], the updates multiplied by `kernel`.
    pub(super) fn with_kernel(
        ordering: &PartialOrdering<I>,
        pattern: SymbolicSparseColMatRef<'_, I>,
        values: &[f64],
        storage: Vec<f64>,
        kernel: Kernel,
    ) -> Result<Self, FemError> {
        let supernodes = &*ordering.supernodes;
        let widest = (0..supernodes.n_supernodes())
            .map(|s| supernodes.columns(s).len())
            .max()
            .unwrap_or(0);
        let scratch = llt::factor::cholesky_in_place_scratch::<f64>(widest, Par::Seq, Default::default());
        let mut factor = factor_storage(supernodes.len_val(), scratch, pattern.nrows(), storage)?;
        let mut mem = MemBuffer::try_new(scratch)
            .map_err(|_| FemError::OutOfMemory("the factorisation's workspace"))?;
        factorize_interior(
            &mut factor,
            SparseColMatRef::new(pattern, values),
            ordering,
            MemStack::new(&mut mem),
            kernel,
        )?;
        Ok(PartialFactor {
            ordering: ordering.clone(),
            values: factor,
        })
    }

    fn blocks(&self) -> Blocks<'_, I> {
        Blocks::new(
            Layout::Grid(&self.ordering.supernodes),
            &self.values,
            self.ordering.n_interior,
        )
    }

    /// Forward elimination of the interior ([`Blocks::eliminate_interior`]).
    pub(super) fn eliminate_interior(&self, x: MatMut<'_, f64>) {
        self.blocks().eliminate_interior(x);
    }

    /// Back substitution of the interior ([`Blocks::back_substitute_interior`]).
    pub(super) fn back_substitute_interior(&self, x: MatMut<'_, f64>) {
        self.blocks().back_substitute_interior(x);
    }

    /// Each stored entry (i, j, value), i ≥ j, of the Schur complement S = K₂₂ − L₂₁ L₂₁ᵀ on
    /// the interface (i and j its positions in the interface).
    pub(super) fn for_each_schur_entry(&self, entry: impl FnMut(usize, usize, f64)) {
        self.blocks().for_each_trailing(entry);
    }
}

/// faer's left-looking supernodal Cholesky factorisation of `a` (lower triangle, in
/// elimination order) into `values` (zero, as long as `ordering`'s factor), of the supernodes
/// before its interface alone: each supernode gathers its entries of `a` and the updates of
/// the supernodes below it, then, if it is not the interface's, factorises its columns (a
/// dense Cholesky factor, then a triangular solve for the rows under them). The interface's
/// supernode is neither factorised nor propagated, so it ends as the Schur complement's lower
/// triangle.
fn factorize_interior<I: Index>(
    values: &mut [f64],
    a: SparseColMatRef<'_, I, f64>,
    ordering: &PartialOrdering<I>,
    stack: &mut MemStack,
    kernel: Kernel,
) -> Result<(), FemError> {
    let (supernodes, descendants) = (&*ordering.supernodes, &*ordering.descendants);
    // Where each row of the current supernode's pattern lies in its block.
    let none = I::truncate(usize::MAX);
    let mut local = vec![none; supernodes.nrows()];
    let (mut row_idx, mut product) = (Vec::<I>::new(), Vec::new());
    for s in 0..supernodes.n_supernodes() {
        let columns = supernodes.columns(s);
        let (s_start, s_end) = (columns.start, columns.end);
        let s_pattern = supernodes.pattern(s);
        let s_ncols = s_end - s_start;
        let s_nrows = s_pattern.len() + s_ncols;
        for (i, &row) in s_pattern.iter().enumerate() {
            local[row.zx()] = I::truncate(i + s_ncols);
        }
        let s_values = supernodes.values(s);
        let (head, tail) = values.split_at_mut(s_values.start);
        let head = &*head;
        let mut ls = MatMut::from_column_major_slice_mut(&mut tail[..s_values.len()], s_nrows, s_ncols);
        for j in s_start..s_end {
            for (i, &v) in a.row_idx_of_col(j).zip(a.val_of_col(j)) {
                if i >= j {
                    let row = if i >= s_end { local[i].zx() } else { i - s_start };
                    ls[(row, j - s_start)] += v;
                }
            }
        }
        for d in descendants.of[descendants.start[s]..descendants.start[s + 1]]
            .iter()
            .map(|d| d.zx())
        {
            let d_start = supernodes.columns(d).start;
            let d_pattern = supernodes.pattern(d);
            let d_ncols = supernodes.columns(d).len();
            let ld = MatRef::from_column_major_slice(
                &head[supernodes.values(d)],
                d_pattern.len() + d_ncols,
                d_ncols,
            );
            // d's rows in s's columns (mid) and below them.
            let first = d_pattern.partition_point(|r| r.zx() < s_start);
            let mid = d_pattern[first..].partition_point(|r| r.zx() < s_end);
            let rows = d_pattern.len() - first;
            let ld_mid_bot = ld.submatrix(d_ncols + first, 0, rows, d_ncols);
            // Where each of those rows and columns lies in s's block.
            row_idx.clear();
            row_idx.extend(d_pattern[first..].iter().enumerate().map(|(i, r)| {
                if i < mid {
                    I::truncate(r.zx() - s_start)
                } else {
                    local[r.zx()]
                }
            }));
            debug_assert!(!row_idx.contains(&none), "{d_start}: a row outside s's pattern");
            subtract_lower_product(
                ls.rb_mut(),
                &row_idx,
                &row_idx[..mid],
                ld_mid_bot,
                ld_mid_bot.subrows(0, mid),
                kernel,
                &mut product,
            );
        }
        if s_start < ordering.n_interior {
            let (mut top, mut bot) = ls.rb_mut().split_at_row_mut(s_ncols);
            llt::factor::cholesky_in_place(
                top.rb_mut(),
                Default::default(),
                Par::Seq,
                stack,
                Default::default(),
            )
            .map_err(FemError::from)?;
            triangular_solve::solve_lower_triangular_in_place(
                top.rb(),
                bot.rb_mut().transpose_mut(),
                Par::Seq,
            );
        }
        for &row in s_pattern {
            local[row.zx()] = none;
        }
    }
    Ok(())
}

/// For each supernode s, the supernodes d < s that update it (rows of d's pattern in s's
/// columns), ascending; the interface's supernode updates none.
fn descendants<I: Index>(supernodes: &Supernodes<I>, n_interior: usize) -> Descendants<I> {
    let n_supernodes = supernodes.n_supernodes();
    let mut supernode_of = vec![I::truncate(0); supernodes.nrows()];
    for s in 0..n_supernodes {
        supernode_of[supernodes.columns(s)].fill(I::truncate(s));
    }
    let supernode_of = &supernode_of;
    // Each d's pattern is ascending: the supernodes it updates, each once.
    let updated = |d: usize| {
        let mut last = usize::MAX;
        supernodes.pattern(d).iter().filter_map(move |r| {
            let s = supernode_of[r.zx()].zx();
            (s != last).then(|| {
                last = s;
                s
            })
        })
    };
    let updating = || (0..n_supernodes).filter(|&d| supernodes.columns(d).start < n_interior);
    let mut start = vec![0usize; n_supernodes + 1];
    for d in updating() {
        for s in updated(d) {
            start[s + 1] += 1;
        }
    }
    for s in 0..n_supernodes {
        start[s + 1] += start[s];
    }
    let mut next = start.clone();
    let mut of = vec![I::truncate(0); start[n_supernodes]];
    for d in updating() {
        for s in updated(d) {
            of[next[s]] = I::truncate(d);
            next[s] += 1;
        }
    }
    Descendants { start, of }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a dense pattern of order 5 with 2 interface dofs, the partial factorisation's flops
    /// are those of the 3 interior columns (c = 5, 4, 3), not the whole factor's Σ_{c=1}^{5} c².
    #[test]
    fn the_flops_count_the_interior_columns() {
        let supernodes = Supernodes::<u32>::new(vec![0, 3], 5, |s, rows| {
            if s == 0 {
                rows.extend([4, 3]);
            }
        })
        .unwrap();
        let ordering = PartialOrdering::new(supernodes, 3);
        assert_eq!(ordering.factor_flops(), 25.0 + 16.0 + 9.0);
        // Each supernode's diagonal block stored square: 5 × 3 and 2 × 2.
        assert_eq!(ordering.factor_len(), 15 + 4);
    }
}
