//! The values of a trace factor as blocks of consecutive columns, L = [L₁₁ 0; L₂₁ L₂₂], and the
//! compliance of the trace from its Schur factor L₂₂.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::traits::Index;
use faer::{Accum, Mat, MatMut, MatRef, Par};

use super::Layout;

/// The values of a factor L (in elimination order) as blocks of consecutive columns, with
/// L = [L₁₁ 0; L₂₁ L₂₂] split after its first `n_interior` columns.
pub(in crate::fem) struct Blocks<'a, I: Index> {
    layout: Layout<'a, I>,
    values: &'a [f64],
    n_interior: usize,
}

impl<'a, I: Index> Blocks<'a, I> {
    /// The blocks of the factor `values` laid out as `layout`.
    pub(in crate::fem) fn new(layout: Layout<'a, I>, values: &'a [f64], n_interior: usize) -> Self {
        Blocks {
            layout,
            values,
            n_interior,
        }
    }

    /// The number of blocks of columns of L ([`Blocks::block`]).
    fn n_blocks(&self) -> usize {
        match self.layout {
            Layout::Supernodal(sym) => sym.n_supernodes(),
            Layout::Simplicial(sym) => sym.nrows(),
            Layout::Grid(sup) => sup.n_supernodes(),
        }
    }

    /// The `s`-th block of consecutive columns of L (in elimination order): a supernode, or
    /// one column of the simplicial layout (whose first stored row is the diagonal).
    fn block(&self, s: usize) -> Block<'a, I> {
        match self.layout {
            Layout::Supernodal(sym) => {
                let node = SupernodalLltRef::new(sym, self.values).supernode(s);
                Block {
                    start: node.start(),
                    val: node.val(),
                    below: node.pattern(),
                }
            }
            Layout::Simplicial(sym) => {
                let (lo, hi) = (sym.col_ptr()[s].zx(), sym.col_ptr()[s + 1].zx());
                Block {
                    start: s,
                    val: MatRef::from_column_major_slice(&self.values[lo..hi], hi - lo, 1),
                    below: &sym.row_idx()[lo + 1..hi],
                }
            }
            Layout::Grid(sup) => {
                let (columns, below) = (sup.columns(s), sup.pattern(s));
                Block {
                    start: columns.start,
                    val: MatRef::from_column_major_slice(
                        &self.values[sup.values(s)],
                        columns.len() + below.len(),
                        columns.len(),
                    ),
                    below,
                }
            }
        }
    }

    /// Forward elimination of the interior, in elimination order: with
    /// L = [L₁₁ 0; L₂₁ L₂₂] split after the interior and x = [f₁; f₂],
    /// x ← [L₁₁⁻¹ f₁; f₂ − L₂₁ L₁₁⁻¹ f₁] (the trace's right-hand side of the Schur complement
    /// system, since L₂₁ L₁₁⁻¹ = A₂₁ A₁₁⁻¹ L₁₁).
    pub(in crate::fem) fn eliminate_interior(&self, mut x: MatMut<'_, f64>) {
        let n0 = self.n_interior;
        let mut tmp = Mat::<f64>::zeros(0, 0);
        for s in 0..self.n_blocks() {
            let b = self.block(s);
            if b.start >= n0 {
                break;
            }
            let width = b.val.ncols();
            let m = width.min(n0 - b.start);
            let (head, tail) = x.rb_mut().split_at_row_mut(b.start + m);
            let mut top = head.subrows_mut(b.start, m);
            triangular_solve::solve_lower_triangular_in_place(
                b.val.submatrix(0, 0, m, m),
                top.rb_mut(),
                Par::Seq,
            );
            // The block's own columns after the interior (trace rows), then the rows below.
            matmul(
                tail.subrows_mut(0, width - m),
                Accum::Add,
                b.val.submatrix(m, 0, width - m, m),
                top.rb(),
                -1.0,
                Par::Seq,
            );
            tmp.resize_with(b.below.len(), top.ncols(), |_, _| 0.0);
            matmul(
                tmp.as_mut(),
                Accum::Replace,
                b.val.submatrix(width, 0, b.below.len(), m),
                top.rb(),
                1.0,
                Par::Seq,
            );
            for j in 0..x.ncols() {
                for (k, &row) in b.below.iter().enumerate() {
                    x[(row.zx(), j)] -= tmp[(k, j)];
                }
            }
        }
    }

    /// Back substitution of the interior, in elimination order: with x = [y₁; u₂] (u₂ the
    /// trace's solution), x ← [L₁₁⁻ᵀ (y₁ − L₂₁ᵀ u₂); u₂], which completes A u = f after
    /// [`Blocks::eliminate_interior`].
    pub(in crate::fem) fn back_substitute_interior(&self, mut x: MatMut<'_, f64>) {
        let n0 = self.n_interior;
        let mut tmp = Mat::<f64>::zeros(0, 0);
        for s in (0..self.n_blocks()).rev() {
            let b = self.block(s);
            if b.start >= n0 {
                continue;
            }
            let width = b.val.ncols();
            let m = width.min(n0 - b.start);
            tmp.resize_with(b.below.len(), x.ncols(), |_, _| 0.0);
            for j in 0..x.ncols() {
                for (k, &row) in b.below.iter().enumerate() {
                    tmp[(k, j)] = x[(row.zx(), j)];
                }
            }
            let (head, tail) = x.rb_mut().split_at_row_mut(b.start + m);
            let mut top = head.subrows_mut(b.start, m);
            matmul(
                top.rb_mut(),
                Accum::Add,
                b.val.submatrix(m, 0, width - m, m).transpose(),
                tail.rb().subrows(0, width - m),
                -1.0,
                Par::Seq,
            );
            matmul(
                top.rb_mut(),
                Accum::Add,
                b.val.submatrix(width, 0, b.below.len(), m).transpose(),
                tmp.as_ref(),
                -1.0,
                Par::Seq,
            );
            triangular_solve::solve_upper_triangular_in_place(
                b.val.submatrix(0, 0, m, m).transpose(),
                top,
                Par::Seq,
            );
        }
    }

    /// The trailing block of the values, L₂₂ (the columns from `n_interior` on), its lower
    /// triangle: the Schur complement's Cholesky factor after a whole factorisation, the Schur
    /// complement itself after [`super::partial`]'s.
    pub(in crate::fem) fn trailing_block(&self) -> Mat<f64> {
        let nc = self.layout_nrows() - self.n_interior;
        let mut l = Mat::<f64>::zeros(nc, nc);
        self.for_each_trailing(|i, j, v| l[(i, j)] = v);
        l
    }

    /// Each stored entry (i, j, value) of the trailing block (i ≥ j, both counted from
    /// `n_interior`).
    pub(in crate::fem) fn for_each_trailing(&self, mut entry: impl FnMut(usize, usize, f64)) {
        let n0 = self.n_interior;
        for s in 0..self.n_blocks() {
            let b = self.block(s);
            let width = b.val.ncols();
            for jc in (0..width).filter(|&jc| b.start + jc >= n0) {
                let j = b.start + jc - n0;
                for ir in jc..width {
                    entry(b.start + ir - n0, j, b.val[(ir, jc)]);
                }
                for (p, &row) in b.below.iter().enumerate() {
                    entry(row.zx() - n0, j, b.val[(width + p, jc)]);
                }
            }
        }
    }

    /// The order of L.
    fn layout_nrows(&self) -> usize {
        match self.layout {
            Layout::Supernodal(sym) => sym.nrows(),
            Layout::Simplicial(sym) => sym.nrows(),
            Layout::Grid(sup) => sup.nrows(),
        }
    }
}

/// Consecutive columns start.. of a factor L: `val` holds their rows from the diagonal down
/// (the diagonal block, then the rows `below`).
pub(in crate::fem) struct Block<'a, I> {
    start: usize,
    val: MatRef<'a, f64>,
    below: &'a [I],
}

/// C = S⁻¹ = L⁻ᵀ L⁻¹ from the Cholesky factor L of S (lower triangle read), on `par`: L's
/// triangular inverse, then the product of two triangles (faer's `llt::inverse`, 2n³/3 flops
/// against 3n³ for solves with the identity and a full product), mirrored, so that C is
/// exactly symmetric.
pub(in crate::fem) fn compliance_of(l: MatRef<'_, f64>, par: Par) -> Mat<f64> {
    let nc = l.nrows();
    let mut c = Mat::<f64>::zeros(nc, nc);
    let mut mem = MemBuffer::new(llt::inverse::inverse_scratch::<f64>(nc, par));
    llt::inverse::inverse(c.as_mut(), l, par, MemStack::new(&mut mem));
    for j in 1..nc {
        for i in 0..j {
            c[(i, j)] = c[(j, i)];
        }
    }
    c
}
