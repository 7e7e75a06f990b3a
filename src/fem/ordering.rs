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

/// Parts with at most this many nodes are not split further (ordered row by row): a band of
/// a few hundred unknowns, one dense enough block for the supernodal factorisation.
const LEAF_NODES: usize = 64;

/// The free dofs of `mesh` except `trace`, in elimination order: the grid's nested
/// dissection, with every node's free dofs next to each other.
pub fn nested_dissection(mesh: &Mesh, dofs: &DofMap, trace: &[usize]) -> Vec<usize> {
    let mut is_trace = vec![false; dofs.n_free()];
    for &d in trace {
        is_trace[d] = true;
    }
    let mut order = Vec::with_capacity(dofs.n_free() - trace.len());
    let mut emit = |i: usize, j: usize| {
        let node = mesh.node(i, j);
        for comp in 0..2 {
            if let Some(d) = dofs.free_index(2 * node + comp).filter(|&d| !is_trace[d]) {
                order.push(d);
            }
        }
    };
    let part = Part {
        i: (0, mesh.nnx()),
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
        Some((s, true)) => {
            dissect(Part { i: (part.i.0, s), ..part }, p, emit);
            dissect(Part { i: (s + 1, part.i.1), ..part }, p, emit);
            for j in part.j.0..part.j.1 {
                emit(s, j);
            }
        }
        Some((s, false)) => {
            dissect(Part { j: (part.j.0, s), ..part }, p, emit);
            dissect(Part { j: (s + 1, part.j.1), ..part }, p, emit);
            for i in part.i.0..part.i.1 {
                emit(i, s);
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
            for (nx, ny, symmetric) in [(1, 1, true), (3, 2, false), (16, 8, true), (40, 3, true), (2, 30, false)] {
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

    /// No cell has nodes on both sides of a separator: the two halves are independent.
    #[test]
    fn separators_lie_on_vertex_lines_and_split_the_cells() {
        for p in [1, 2] {
            for lo in 0..6 {
                for hi in lo..lo + 40 {
                    if let Some(s) = separator(lo, hi, p) {
                        assert_eq!(s % p, 0);
                        assert!(lo < s && s + 1 < hi, "{lo} {s} {hi}");
                        // Cells span node lines p·c ..= p·c + p: none crosses s.
                        assert!((0..hi).all(|c| !(p * c < s && s < p * c + p)));
                    }
                }
            }
        }
    }
}
