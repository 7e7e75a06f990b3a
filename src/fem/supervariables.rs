//! The elimination tree and column counts of a Cholesky factor from its pattern's
//! supervariables (issue 13, item 3).
//!
//! On the grid every free dof of a node couples with the node's other free dof and with the
//! same dofs elsewhere (both components of the nodes that share a cell with it,
//! [`super::SymCsc::pattern`]). Consecutive dofs of one node in an elimination order are
//! therefore *indistinguishable* (George and Liu, "Computer Solution of Large Sparse Positive
//! Definite Systems", 1981): the columns of L of such a run
//! share every row past the run, the first column of the run holds the run itself, and its
//! elimination tree is a chain. The tree and the column counts of the dof-level factor follow
//! from those of the quotient graph, in which each run is one vertex weighted by its size.
//! That graph has about a quarter of the pattern's entries, and the walk that counts the
//! columns (Liu 1986: each row of L is a subtree of the elimination tree, visited once)
//! costs the factor's entries of the quotient graph, about a quarter of the dof-level
//! walk's (`prefactorize_symbolic_cholesky` of faer, the largest part of the symbolic phase:
//! BENCHMARKS.md, "The symbolic phase on the node graph").

use faer::sparse::SymbolicSparseColMatRef;
use faer::traits::{Index, SignedIndex};

/// A vertex of the quotient graph that is no one's parent yet, or not visited yet.
const NONE: usize = usize::MAX;

/// The elimination tree (each column's parent, −1 at a root) and the column counts
/// (diagonal included) of the Cholesky factor of the pattern whose upper triangle is `upper`
/// (in elimination order, each column's rows ascending), as faer's
/// `simplicial::prefactorize_symbolic_cholesky` computes them. `starts` holds the first column
/// of each run of indistinguishable columns, ascending from 0 (each run ends where the next
/// starts, the last at the order's end): every column of a run must couple with the run's
/// other columns and with the same columns before the run.
pub fn elimination_tree<I: Index>(
    upper: SymbolicSparseColMatRef<'_, I>,
    starts: &[usize],
) -> (Vec<I::Signed>, Vec<I>) {
    let n = upper.ncols();
    let runs = starts.len();
    let end = |g: usize| starts.get(g + 1).copied().unwrap_or(n);
    // Indices of type I (u32 for the halves of K), to halve these arrays' memory.
    let none = I::truncate(NONE);
    let mut run_of = vec![I::truncate(0); n];
    for g in 0..runs {
        run_of[starts[g]..end(g)].fill(I::truncate(g));
    }
    // The quotient graph's elimination tree, and the number of dofs in each run's column of L
    // below the run (the sum of the sizes of the runs in its row subtrees); one record per run,
    // so that each step of the walk up the tree reads one cache line.
    #[derive(Clone, Copy)]
    struct Run<I> {
        parent: I,
        below: I,
        visited: I,
    }
    let mut tree = vec![
        Run {
            parent: none,
            below: I::truncate(0),
            visited: none,
        };
        runs
    ];
    for j in 0..runs {
        let (size, this) = (I::truncate(end(j) - starts[j]), I::truncate(j));
        tree[j].visited = this;
        // The run's first column holds its couplings with the earlier runs, each run's rows
        // next to each other.
        let mut previous = none;
        for &r in upper.row_idx_of_col_raw(starts[j]) {
            let mut i = run_of[r.zx()];
            if i >= this || i == previous {
                continue;
            }
            previous = i;
            // Row j of L is the subtree of the elimination tree from i up to j.
            while tree[i.zx()].visited != this {
                let run = &mut tree[i.zx()];
                if run.parent == none {
                    run.parent = this;
                }
                run.below += size;
                run.visited = this;
                i = run.parent;
            }
        }
    }
    let mut etree = vec![I::Signed::truncate(usize::MAX); n];
    let mut counts = vec![I::truncate(0); n];
    for g in 0..runs {
        let (first, last) = (starts[g], end(g) - 1);
        for d in first..=last {
            counts[d] = I::truncate(last + 1 - d + tree[g].below.zx());
            if d < last {
                etree[d] = I::Signed::truncate(d + 1);
            } else if tree[g].parent != none {
                etree[d] = I::Signed::truncate(starts[tree[g].parent.zx()]);
            }
        }
    }
    (etree, counts)
}

#[cfg(test)]
mod tests {
    use faer::dyn_stack::{MemBuffer, MemStack};
    use faer::sparse::linalg::cholesky::simplicial;

    use super::*;
    use crate::fem::ordering::nested_dissection;
    use crate::fem::{DofMap, SymCsc};
    use crate::mesh::{Element, Mesh};

    /// The upper triangle of `a`'s pattern with dof `order[p]` at position p, compressed
    /// columns, each column's rows ascending.
    fn upper_in_order(a: &SymCsc, order: &[usize]) -> (Vec<usize>, Vec<usize>) {
        let mut position = vec![0; a.n];
        for (p, &d) in order.iter().enumerate() {
            position[d] = p;
        }
        let mut columns = vec![Vec::new(); a.n];
        for c in 0..a.n {
            for &r in &a.row_idx[a.col_ptr[c]..a.col_ptr[c + 1]] {
                let (p, q) = (position[r], position[c]);
                columns[p.max(q)].push(p.min(q));
            }
        }
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        for mut rows in columns {
            rows.sort_unstable();
            row_idx.extend(rows);
            col_ptr.push(row_idx.len());
        }
        (col_ptr, row_idx)
    }

    /// On every element's grid, whole or half model, in the grid's nested dissection with
    /// Γ_C's normal dofs last (as the factorisations order K), the tree and the counts from
    /// the nodes' runs of dofs are those faer computes column by column.
    #[test]
    fn the_supervariables_give_faers_tree_and_counts() {
        // Whether a case had no run longer than one dof, and one with runs of two.
        let mut run_lengths = [false; 2];
        for element in Element::ALL {
            for (nx, ny, symmetric) in [
                (1, 1, true),
                (3, 2, false),
                (16, 8, true),
                (9, 5, false),
                (2, 12, true),
            ] {
                let mesh = Mesh::uniform(element, (0.0, 2.0, nx), (0.0, 1.0, ny), symmetric);
                let dofs = DofMap::model(&mesh);
                let a = SymCsc::pattern(&mesh, &dofs);
                let trace: Vec<usize> = mesh
                    .top_nodes()
                    .iter()
                    .map(|&t| dofs.free_index(2 * t + 1).unwrap())
                    .collect();
                let mut order = nested_dissection(&mesh, &dofs, &trace);
                order.extend_from_slice(&trace);
                let mut node_of = vec![0; a.n];
                for node in 0..mesh.n_nodes() {
                    for comp in 0..2 {
                        if let Some(d) = dofs.free_index(2 * node + comp) {
                            node_of[d] = node;
                        }
                    }
                }
                let starts: Vec<usize> = (0..a.n)
                    .filter(|&p| p == 0 || node_of[order[p]] != node_of[order[p - 1]])
                    .collect();
                let case = format!("{element:?} {nx}×{ny} symmetric {symmetric}");
                let longest = (0..starts.len())
                    .map(|g| starts.get(g + 1).copied().unwrap_or(a.n) - starts[g])
                    .max()
                    .unwrap();
                run_lengths[longest - 1] = true;
                let (col_ptr, row_idx) = upper_in_order(&a, &order);
                let upper = SymbolicSparseColMatRef::new_checked(a.n, a.n, &col_ptr, None, &row_idx);
                let (etree, counts) = elimination_tree(upper, &starts);
                let (mut faer_etree, mut faer_counts) = (vec![0isize; a.n], vec![0usize; a.n]);
                let mut mem = MemBuffer::new(simplicial::prefactorize_symbolic_cholesky_scratch::<usize>(
                    a.n,
                    row_idx.len(),
                ));
                simplicial::prefactorize_symbolic_cholesky(
                    &mut faer_etree,
                    &mut faer_counts,
                    upper,
                    MemStack::new(&mut mem),
                );
                assert_eq!(etree, faer_etree, "{case}");
                assert_eq!(counts, faer_counts, "{case}");
                // With u32 indices, as the halves of K have them.
                let narrow = |v: &[usize]| v.iter().map(|&i| i as u32).collect::<Vec<_>>();
                let (col_ptr, row_idx) = (narrow(&col_ptr), narrow(&row_idx));
                let upper = SymbolicSparseColMatRef::new_checked(a.n, a.n, &col_ptr, None, &row_idx);
                let (etree, counts) = elimination_tree(upper, &starts);
                assert_eq!(
                    etree,
                    faer_etree.iter().map(|&p| p as i32).collect::<Vec<_>>(),
                    "{case}"
                );
                assert_eq!(counts, narrow(&faer_counts), "{case}");
            }
        }
        assert_eq!(run_lengths, [true, true]);
    }
}
