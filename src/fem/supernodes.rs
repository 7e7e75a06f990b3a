//! The supernodes of a half's Cholesky factor read from the grid's nested dissection, with no
//! symbolic analysis of the matrix.
//!
//! Each block of [`super::ordering::Dissection`] (a separator, or a small part) is one
//! supernode: its columns of L are stored as one dense block, the diagonal block and then
//! the rows below it. When a block is eliminated, so is the whole part P it closes, and the
//! rows of its columns are the later dofs of P's closure
//! ([`super::ordering::Part::closure`]): the ring of nodes around P (on the separators of the
//! parts that hold P, or on the interface) and the interface dofs of P's own nodes (the
//! trace). Eliminating P, which is connected, reaches
//! every one of them and nothing else (George and Liu 1981: the structure of a column of L is
//! the reach of its node through the nodes eliminated before it), so these are exactly the
//! rows of the block's columns of L. For a separator every column has them all, as in faer's
//! fundamental supernodes; a small part (at most 16 nodes) is one block, stored dense, as
//! faer's relaxed supernodes merged small ones. The interface Γ_h is the last supernode, with
//! no rows below it.
//!
//! This replaces faer's analysis of the same pattern (an elimination tree, column counts, then
//! supernodes); the time it saves is in BENCHMARKS.md, "Supernodes from the grid".

use std::ops::Range;

use faer::traits::Index;

use super::error::FemError;
use super::ordering::Dissection;
use crate::mesh::Mesh;

/// A supernodal layout: supernodes of consecutive columns, each with the rows below its
/// diagonal block, and where each one's values lie in the factor's storage.
pub(super) struct Supernodes<I: Index> {
    /// The first column of each supernode, then the order of the matrix.
    begin: Vec<usize>,
    /// The rows of supernode s below its diagonal block, ascending:
    /// `rows[row_ptr[s]..row_ptr[s + 1]]`.
    row_ptr: Vec<usize>,
    rows: Vec<I>,
    /// Where supernode s's values lie in the factor (its columns one after the other, each
    /// from the diagonal block's first row down): `val_ptr[s]..val_ptr[s + 1]`.
    val_ptr: Vec<usize>,
}

impl<I: Index> Supernodes<I> {
    /// The layout of the supernodes that start at `begin` (ascending from 0, each ending where
    /// the next starts, the last at `n`), the rows of each given by `rows_of` (which appends
    /// them, each once, in any order; each after the supernode's columns and before `n`).
    pub(super) fn new(
        mut begin: Vec<usize>,
        n: usize,
        mut rows_of: impl FnMut(usize, &mut Vec<I>),
    ) -> Result<Self, FemError> {
        begin.push(n);
        let n_supernodes = begin.len() - 1;
        let mut row_ptr = Vec::with_capacity(n_supernodes + 1);
        let mut val_ptr = Vec::with_capacity(n_supernodes + 1);
        let (mut rows, mut values) = (Vec::new(), 0usize);
        row_ptr.push(0);
        val_ptr.push(0);
        for s in 0..n_supernodes {
            let (start, end) = (begin[s], begin[s + 1]);
            let first = rows.len();
            rows_of(s, &mut rows);
            let own = &mut rows[first..];
            own.sort_unstable();
            debug_assert!(
                start < end
                    && own.first().is_none_or(|r| r.zx() >= end)
                    && own.last().is_none_or(|r| r.zx() < n)
                    && own.windows(2).all(|w| w[0] < w[1])
            );
            let width = end - start;
            values = (width + own.len())
                .checked_mul(width)
                .and_then(|v| v.checked_add(values))
                .ok_or(FemError::OutOfMemory("the supernodes"))?;
            row_ptr.push(rows.len());
            val_ptr.push(values);
        }
        Ok(Supernodes {
            begin,
            row_ptr,
            rows,
            val_ptr,
        })
    }

    /// The number of supernodes.
    pub(super) fn n_supernodes(&self) -> usize {
        self.begin.len() - 1
    }

    /// The order of the matrix.
    pub(super) fn nrows(&self) -> usize {
        self.begin[self.n_supernodes()]
    }

    /// The columns of supernode `s`.
    pub(super) fn columns(&self, s: usize) -> Range<usize> {
        self.begin[s]..self.begin[s + 1]
    }

    /// The rows of supernode `s` below its diagonal block, ascending.
    pub(super) fn pattern(&self, s: usize) -> &[I] {
        &self.rows[self.row_ptr[s]..self.row_ptr[s + 1]]
    }

    /// Where supernode `s`'s values lie in the factor.
    pub(super) fn values(&self, s: usize) -> Range<usize> {
        self.val_ptr[s]..self.val_ptr[s + 1]
    }

    /// The number of stored values of the factor.
    pub(super) fn len_val(&self) -> usize {
        self.val_ptr[self.n_supernodes()]
    }
}

/// The supernodes of a half's factor in the elimination order `dissection.order` followed by
/// the interface, from the grid alone (the module's doc). `position` gives each dof of the
/// half and its interface its place in that order (u32::MAX for the others, none of which
/// lies in a block's closure), `interface` holds each interface place's node, and `n` is the
/// order of the half's matrix.
pub(super) fn of_dissection(
    mesh: &Mesh,
    dofs_of: impl Fn(usize) -> [Option<usize>; 2],
    dissection: &Dissection,
    position: &[u32],
    interface: &[usize],
    n: usize,
) -> Result<Supernodes<u32>, FemError> {
    let (nnx, nny) = (mesh.nnx(), mesh.node_y.len());
    let n_interior = dissection.order.len();
    // The interface's places by node row and column, to find those inside a part.
    let mut inside: Vec<(usize, usize, u32)> = interface
        .iter()
        .enumerate()
        .map(|(t, &node)| (node / nnx, node % nnx, (n_interior + t) as u32))
        .collect();
    inside.sort_unstable();
    let mut begin: Vec<usize> = std::iter::once(0)
        .chain(dissection.blocks.iter().map(|&(end, _)| end))
        .collect();
    // The interface, when it has dofs, is the last supernode; the last block ends there.
    begin.pop();
    if n > n_interior {
        begin.push(n_interior);
    }
    Supernodes::new(begin, n, |s, rows| {
        let Some(&(end, part)) = dissection.blocks.get(s) else {
            return;
        };
        let mut push = |node: usize| {
            for d in dofs_of(node).into_iter().flatten() {
                let p = position[d];
                if p != u32::MAX && p as usize >= end {
                    rows.push(p);
                }
            }
        };
        // The ring: the closure's nodes outside the part, the rows below and above it, then
        // the columns beside it.
        let ring = part.closure(nnx, nny);
        for j in [ring.j.0, ring.j.1 - 1] {
            if !(part.j.0..part.j.1).contains(&j) {
                (ring.i.0..ring.i.1).for_each(|i| push(mesh.node(i, j)));
            }
        }
        for i in [ring.i.0, ring.i.1 - 1] {
            if !(part.i.0..part.i.1).contains(&i) {
                (part.j.0..part.j.1).for_each(|j| push(mesh.node(i, j)));
            }
        }
        // The interface's dofs on the part's own nodes.
        let from = inside.partition_point(|&(j, _, _)| j < part.j.0);
        let to = inside.partition_point(|&(j, _, _)| j < part.j.1);
        rows.extend(
            inside[from..to]
                .iter()
                .filter(|&&(_, i, _)| (part.i.0..part.i.1).contains(&i))
                .map(|&(_, _, p)| p),
        );
    })
}
