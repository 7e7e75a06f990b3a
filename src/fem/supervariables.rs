//! The elimination tree and column counts of a Cholesky factor from its pattern's
//! supervariables (issue 13, item 3).
//!
//! On the grid every free dof of a node couples with the node's other free dof and with the
//! same dofs elsewhere (both components of the nodes that share a cell with it,
//! [`super::SymCsc::pattern`]). Consecutive dofs of one node in an elimination order are
//! therefore *indistinguishable* (George and Liu, "Computer Solution of Large Sparse Positive
//! Definite Systems", 1981): the columns of L of such a run share every row past the run, the
//! first column of the run holds the run itself, and its elimination tree is a chain. The
//! tree and the column counts of the dof-level factor follow from those of the quotient graph,
//! in which each run is one vertex weighted by its size. That graph has about a quarter of the
//! pattern's entries, and the walk that counts the columns (Liu 1986: each row of L is a
//! subtree of the elimination tree, visited once) costs the quotient graph's factor entries,
//! about a quarter of the dof-level walk's (faer's `prefactorize_symbolic_cholesky`, before
//! this the largest part of the symbolic phase: BENCHMARKS.md, "The symbolic phase on the
//! node graph"). The runs are checked against the pattern first (one pass over it), since
//! faer takes the tree on trust.

use faer::sparse::SymbolicSparseColMatRef;
use faer::traits::{Index, SignedIndex};

/// A vertex of the quotient graph that is no one's parent yet, or not visited yet.
const NONE: usize = usize::MAX;

/// The elimination tree (each column's parent, −1 at a root) and the column counts
/// (diagonal included) of the Cholesky factor of the pattern whose upper triangle is `upper`
/// (in elimination order, each column's rows ascending), as faer's
/// `simplicial::prefactorize_symbolic_cholesky` computes them. `starts` holds the first column
/// of each run of columns meant to be indistinguishable, ascending from 0 (each run ends where
/// the next starts, the last at the order's end). None when a run is not: when one of its
/// columns does not couple with all the run's columns, itself included, or with the same
/// columns before the run, or a later column couples with part of it only.
pub fn elimination_tree<I: Index>(
    upper: SymbolicSparseColMatRef<'_, I>,
    starts: &[usize],
) -> Option<(Vec<I::Signed>, Vec<I>)> {
    let n = upper.ncols();
    let runs = starts.len();
    let runs_cover_the_order = match starts.last() {
        None => n == 0,
        Some(&last) => starts[0] == 0 && starts.windows(2).all(|w| w[0] < w[1]) && last < n,
    };
    if !runs_cover_the_order {
        return None;
    }
    let end = |g: usize| starts.get(g + 1).copied().unwrap_or(n);
    // Indices of type I (u32 for the halves of K), to halve these arrays' memory.
    let none = I::truncate(NONE);
    let mut run_of = vec![I::truncate(0); n];
    for g in 0..runs {
        run_of[starts[g]..end(g)].fill(I::truncate(g));
    }
    if !indistinguishable(upper, starts, &run_of) {
        return None;
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
    Some((etree, counts))
}

/// Whether each run of `starts` (`run_of`: each column's run) holds indistinguishable columns
/// of `upper`: each column's rows are, run by run, either a whole earlier run or none of it,
/// then every column of its own run up to itself; and each column of a run has the rows of the
/// run's first column before the run.
fn indistinguishable<I: Index>(
    upper: SymbolicSparseColMatRef<'_, I>,
    starts: &[usize],
    run_of: &[I],
) -> bool {
    let n = upper.ncols();
    let end = |g: usize| starts.get(g + 1).copied().unwrap_or(n);
    for c in 0..n {
        let own = run_of[c].zx();
        let rows = upper.row_idx_of_col_raw(c);
        let mut k = 0;
        while k < rows.len() {
            let r = rows[k].zx();
            let g = run_of[r].zx();
            if g >= own {
                break;
            }
            let (first, len) = (starts[g], end(g) - starts[g]);
            if r != first || k + len > rows.len() || (1..len).any(|t| rows[k + t].zx() != first + t) {
                return false;
            }
            k += len;
        }
        let first = starts[own];
        if rows.len() - k != c + 1 - first || (k..rows.len()).any(|t| rows[t].zx() != first + t - k) {
            return false;
        }
    }
    starts.iter().enumerate().all(|(g, &first)| {
        let before = |c: usize| {
            let rows = upper.row_idx_of_col_raw(c);
            &rows[..rows.partition_point(|r| r.zx() < first)]
        };
        (first + 1..end(g)).all(|c| before(c) == before(first))
    })
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

    /// The upper triangle of K's pattern on an `nx`×`ny` grid of `element` in the order of
    /// the factorisations (the grid's nested dissection, Γ_C's normal dofs last), compressed
    /// columns, and the first position of each run of one node's dofs.
    fn grid_case(
        element: Element,
        nx: usize,
        ny: usize,
        symmetric: bool,
    ) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
        let mesh = Mesh::uniform(element, (0.0, 2.0, nx), (0.0, 1.0, ny), symmetric);
        let dofs = DofMap::model(&mesh);
        let a = SymCsc::pattern(&mesh, &dofs);
        let trace = dofs.contact_dofs(&mesh);
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
        let starts = (0..a.n)
            .filter(|&p| p == 0 || node_of[order[p]] != node_of[order[p - 1]])
            .collect();
        let (col_ptr, row_idx) = upper_in_order(&a, &order);
        (col_ptr, row_idx, starts)
    }

    /// faer's elimination tree and column counts of the pattern `upper`.
    fn faers(upper: SymbolicSparseColMatRef<'_, usize>) -> (Vec<isize>, Vec<usize>) {
        let n = upper.ncols();
        let (mut etree, mut counts) = (vec![0isize; n], vec![0usize; n]);
        let mut mem = MemBuffer::new(simplicial::prefactorize_symbolic_cholesky_scratch::<usize>(
            n,
            upper.row_idx().len(),
        ));
        simplicial::prefactorize_symbolic_cholesky(&mut etree, &mut counts, upper, MemStack::new(&mut mem));
        (etree, counts)
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
                let case = format!("{element:?} {nx}×{ny} symmetric {symmetric}");
                let (col_ptr, row_idx, starts) = grid_case(element, nx, ny, symmetric);
                let n = col_ptr.len() - 1;
                let longest = (0..starts.len())
                    .map(|g| starts.get(g + 1).copied().unwrap_or(n) - starts[g])
                    .max()
                    .unwrap();
                run_lengths[longest - 1] = true;
                let upper = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
                let (etree, counts) = elimination_tree(upper, &starts).unwrap();
                let (faer_etree, faer_counts) = faers(upper);
                assert_eq!(etree, faer_etree, "{case}");
                assert_eq!(counts, faer_counts, "{case}");
                // With u32 indices, as the halves of K have them.
                let narrow = |v: &[usize]| v.iter().map(|&i| i as u32).collect::<Vec<_>>();
                let (col_ptr, row_idx) = (narrow(&col_ptr), narrow(&row_idx));
                let upper = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
                let (etree, counts) = elimination_tree(upper, &starts).unwrap();
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

    /// Runs that are not indistinguishable columns are refused (the analysis then takes faer's
    /// own walk), and runs of one column each always pass.
    #[test]
    fn runs_that_are_not_indistinguishable_are_refused() {
        let (col_ptr, row_idx, starts) = grid_case(Element::Q1, 9, 5, false);
        let n = col_ptr.len() - 1;
        let upper = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
        let singles: Vec<usize> = (0..n).collect();
        assert_eq!(elimination_tree(upper, &singles), Some(faers(upper)));
        // Two nodes' dofs in one run.
        let merged: Vec<usize> = starts.iter().copied().filter(|&p| p != starts[5]).collect();
        assert_eq!(elimination_tree(upper, &merged), None);
        // Starts that do not cover the order from 0 in ascending order.
        assert_eq!(elimination_tree(upper, &starts[1..]), None);
        let mut unsorted = starts.clone();
        unsorted.swap(3, 4);
        assert_eq!(elimination_tree(upper, &unsorted), None);
        // A run of two, and a later column that couples with both of its dofs.
        let g = (0..starts.len() - 1)
            .find(|&g| starts[g + 1] - starts[g] == 2)
            .unwrap();
        let first = starts[g];
        let later = (first + 2..n)
            .find(|&c| row_idx[col_ptr[c]..col_ptr[c + 1]].contains(&first))
            .unwrap();
        // Without one of the entries: the run's own coupling, then the later column's with
        // the run's second dof (the pattern stays upper, each column's rows ascending).
        for (column, row) in [(first + 1, first), (later, first + 1)] {
            let mut cut_ptr = col_ptr.clone();
            let mut cut_rows = Vec::new();
            for c in 0..n {
                let rows = row_idx[col_ptr[c]..col_ptr[c + 1]].iter();
                cut_rows.extend(rows.filter(|&&r| (c, r) != (column, row)));
                cut_ptr[c + 1] = cut_rows.len();
            }
            let cut = SymbolicSparseColMatRef::new_checked(n, n, &cut_ptr, None, &cut_rows);
            assert_eq!(elimination_tree(cut, &starts), None, "without ({row}, {column})");
        }
    }
}
