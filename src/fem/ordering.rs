//! A fill-reducing elimination order made for the structured grid: geometric nested
//! dissection (George 1973) of the node grid, with the Γ_C normal dofs (the trace) last.
//!
//! A vertex line of the grid (a node column or row that no cell straddles) splits the
//! remaining nodes into two parts that share no cell, so no entry of K couples them. Each part
//! is ordered recursively, then the line itself: the elimination of one part never fills the
//! other, and the factor's fill grows like n log n on an n-unknown grid, the optimum for 2-D
//! meshes. The trace comes after every separator, as the last one, so the trailing block of
//! the factor is the Schur complement on Γ_C that [`super::condense`] reads. The order is read
//! from the grid alone: no graph algorithm runs on K's pattern.

use super::dofs::DofMap;
use crate::mesh::Mesh;

/// Parts with at most this many nodes are not split further (ordered row by row). Smaller
/// leaves cost fewer flops (level 6, Q1: 8.27·10⁹ at 8 nodes, 8.43·10⁹ at 32, 1.03·10¹⁰ at
/// 256); faer merges the small supernodes they leave.
const LEAF_NODES: usize = 8;

/// The free dofs of `mesh` except `trace`, in elimination order: the grid's nested
/// dissection, with every node's free dofs next to each other.
pub fn nested_dissection(mesh: &Mesh, dofs: &DofMap, trace: &[usize]) -> Vec<usize> {
    nested_dissection_of_columns(mesh, dofs, trace, (0, mesh.nnx()))
}

/// The node column that splits the grid into two halves of (nearly) equal width, the first
/// separator of [`nested_dissection`] on a grid wider than high; None when the grid has no
/// node column strictly inside (fewer than three node columns, or Q2 with one cell across).
pub fn middle_column(mesh: &Mesh) -> Option<usize> {
    separator(0, mesh.nnx(), mesh.element.order())
}

/// As [`nested_dissection`] for the nodes of the node columns `columns.0 ≤ i < columns.1`
/// alone: the order of one half of the grid beside a [`middle_column`].
pub fn nested_dissection_of_columns(
    mesh: &Mesh,
    dofs: &DofMap,
    trace: &[usize],
    columns: (usize, usize),
) -> Vec<usize> {
    let mut is_trace = vec![false; dofs.n_free()];
    for &d in trace {
        is_trace[d] = true;
    }
    let mut order = Vec::new();
    let mut emit = |i: usize, j: usize| {
        let node = mesh.node(i, j);
        for comp in 0..2 {
            if let Some(d) = dofs.free_index(2 * node + comp).filter(|&d| !is_trace[d]) {
                order.push(d);
            }
        }
    };
    let part = Part {
        i: columns,
        j: (0, mesh.node_y.len()),
    };
    dissect(part, mesh.element.order(), &mut emit);
    order
}

/// The nodes (i, j) with i0 ≤ i < i1 and j0 ≤ j < j1.
#[derive(Clone, Copy, Debug)]
struct Part {
    i: (usize, usize),
    j: (usize, usize),
}

/// A vertex line strictly inside `lo..hi` (both sides keep a node), nearest the middle:
/// a multiple of the element order `p` (Q2's mid-lines cross cells and separate nothing).
fn separator(lo: usize, hi: usize, p: usize) -> Option<usize> {
    if hi < lo + 3 {
        return None;
    }
    let mid = (lo + hi) / 2;
    let below = mid - mid % p;
    let above = below + p;
    [below, above]
        .into_iter()
        .filter(|&s| s > lo && s + 1 < hi)
        .min_by_key(|&s| s.abs_diff(mid))
}

/// Emit the nodes of `part` in nested dissection order: both halves, then the separator.
fn dissect(part: Part, p: usize, emit: &mut impl FnMut(usize, usize)) {
    let (wide, high) = (part.i.1 - part.i.0, part.j.1 - part.j.0);
    let split = if wide * high <= LEAF_NODES {
        None
    } else if wide >= high {
        separator(part.i.0, part.i.1, p)
            .map(|s| (s, true))
            .or_else(|| separator(part.j.0, part.j.1, p).map(|s| (s, false)))
    } else {
        separator(part.j.0, part.j.1, p)
            .map(|s| (s, false))
            .or_else(|| separator(part.i.0, part.i.1, p).map(|s| (s, true)))
    };
    match split {
        None => {
            for j in part.j.0..part.j.1 {
                for i in part.i.0..part.i.1 {
                    emit(i, j);
                }
            }
        }
        // Across i (`across`: the separator is column s) or across j (row s): the two halves
        // first, the separator last.
        Some((s, across)) => {
            let half = |range: (usize, usize)| {
                if across {
                    Part { i: range, ..part }
                } else {
                    Part { j: range, ..part }
                }
            };
            let (lo, hi) = if across { part.i } else { part.j };
            dissect(half((lo, s)), p, emit);
            dissect(half((s + 1, hi)), p, emit);
            let along = if across { part.j } else { part.i };
            for k in along.0..along.1 {
                if across { emit(s, k) } else { emit(k, s) }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Element;

    /// Every non-trace free dof appears exactly once.
    #[test]
    fn the_order_is_a_permutation_of_the_interior() {
        for element in Element::ALL {
            for (nx, ny, symmetric) in [
                (1, 1, true),
                (3, 2, false),
                (16, 8, true),
                (40, 3, true),
                (2, 30, false),
            ] {
                let mesh = Mesh::uniform(element, (0.0, 2.0, nx), (0.0, 1.0, ny), symmetric);
                let dofs = DofMap::model(&mesh);
                let trace: Vec<usize> = mesh
                    .top_nodes()
                    .iter()
                    .map(|&t| dofs.free_index(2 * t + 1).unwrap())
                    .collect();
                let order = nested_dissection(&mesh, &dofs, &trace);
                let mut seen = vec![0u8; dofs.n_free()];
                for &d in order.iter().chain(&trace) {
                    seen[d] += 1;
                }
                assert!(seen.iter().all(|&s| s == 1), "{element:?} {nx}×{ny}");
            }
        }
    }

    /// A separator is a vertex line (Q2's mid-lines cross cells) with nodes on both sides,
    /// and one is found whenever the part has a vertex line strictly inside.
    #[test]
    fn separators_lie_on_vertex_lines_inside_the_part() {
        for p in [1, 2] {
            for lo in 0usize..6 {
                for hi in lo..lo + 40 {
                    let inside = (lo + 1..hi.saturating_sub(1)).any(|s| s % p == 0);
                    match separator(lo, hi, p) {
                        Some(s) => {
                            assert_eq!(s % p, 0);
                            assert!(lo < s && s + 1 < hi, "{lo} {s} {hi}");
                            // Nearest the middle among the vertex lines inside.
                            let mid = (lo + hi) / 2;
                            assert!(
                                (lo + 1..hi - 1)
                                    .filter(|v| v % p == 0)
                                    .all(|v| v.abs_diff(mid) >= s.abs_diff(mid))
                            );
                        }
                        None => assert!(!inside, "{lo}..{hi} p={p}"),
                    }
                }
            }
        }
    }
}
