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
/// 256); [`BLOCK_NODES`] merges the small blocks they leave (faer's relaxed supernodes, in
/// its own analysis of this order).
const LEAF_NODES: usize = 8;

/// Parts with at most this many nodes are one block of [`Dissection`] (one supernode of the
/// halves' factors, [`super::supernodes`]), their separators and leaves merged: fewer, larger
/// dense blocks for a few more flops; the size was chosen by the instruction counts in
/// BENCHMARKS.md, "Supernodes from the grid".
const BLOCK_NODES: usize = 16;

/// The free dofs of `mesh` except `trace`, in elimination order: the grid's nested
/// dissection, with every node's free dofs next to each other.
pub fn nested_dissection(mesh: &Mesh, dofs: &DofMap, trace: &[usize]) -> Vec<usize> {
    nested_dissection_of_columns(mesh, dofs, trace, (0, mesh.nnx())).order
}

/// A nested dissection order and the blocks of consecutive dofs it eliminates together.
pub struct Dissection {
    /// The free dofs in elimination order.
    pub order: Vec<usize>,
    /// Each block of the order (a separator, a part not split further, or a part of at most
    /// 16 nodes, merged) as its end in `order` and the part of the grid it closes: when
    /// the block is eliminated, every node of the part is, and the block's columns of the
    /// Cholesky factor have their rows in it and in the ring of nodes around it
    /// ([`Part::closure`]). Ascending; blocks without dofs are left out.
    pub blocks: Vec<(usize, Part)>,
}

/// The node column that splits the grid into two halves of (nearly) equal width, the first
/// separator of [`nested_dissection`] on a grid wider than high; None when the grid has no
/// node column strictly inside (fewer than three node columns, or Q2 with one cell across).
pub fn middle_column(mesh: &Mesh) -> Option<usize> {
    separator(0, mesh.nnx(), mesh.element.order())
}

/// As [`nested_dissection`] for the nodes of the node columns `columns.0 ≤ i < columns.1`
/// alone (the order of one half of the grid beside a [`middle_column`]), with its blocks.
pub fn nested_dissection_of_columns(
    mesh: &Mesh,
    dofs: &DofMap,
    trace: &[usize],
    columns: (usize, usize),
) -> Dissection {
    let mut is_trace = vec![false; dofs.n_free()];
    for &d in trace {
        is_trace[d] = true;
    }
    let (mut order, mut blocks) = (Vec::new(), Vec::new());
    let mut emit = |step: Step| match step {
        Step::Node(i, j) => {
            let node = mesh.node(i, j);
            for comp in 0..2 {
                if let Some(d) = dofs.free_index(2 * node + comp).filter(|&d| !is_trace[d]) {
                    order.push(d);
                }
            }
        }
        Step::Closes(part) => {
            // A small part is one block: the blocks inside it, the last ones, merge into it.
            if part.nodes() <= BLOCK_NODES {
                while blocks.last().is_some_and(|(_, last)| part.holds(last)) {
                    blocks.pop();
                }
            }
            let start = blocks.last().map_or(0, |&(end, _)| end);
            if order.len() > start {
                blocks.push((order.len(), part));
            }
        }
    };
    let part = Part {
        i: columns,
        j: (0, mesh.node_y.len()),
    };
    dissect(part, mesh.element.order(), &mut emit);
    Dissection { order, blocks }
}

/// The nodes (i, j) with i0 ≤ i < i1 and j0 ≤ j < j1.
#[derive(Clone, Copy, Debug)]
pub struct Part {
    /// Node columns i0..i1.
    pub i: (usize, usize),
    /// Node rows j0..j1.
    pub j: (usize, usize),
}

impl Part {
    /// The number of nodes.
    fn nodes(&self) -> usize {
        (self.i.1 - self.i.0) * (self.j.1 - self.j.0)
    }

    /// Whether `other` lies inside this part.
    fn holds(&self, other: &Part) -> bool {
        self.i.0 <= other.i.0 && other.i.1 <= self.i.1 && self.j.0 <= other.j.0 && other.j.1 <= self.j.1
    }

    /// The part and the ring of nodes around it, within a grid of `nnx` × `nny` nodes: the
    /// nodes (i, j) with i0 − 1 ≤ i ≤ i1 and j0 − 1 ≤ j ≤ j1. The part's sides are vertex
    /// lines or the grid's boundary, so no cell straddles them: every node that shares a
    /// cell with a node of the part lies in its closure, and so does every entry of the
    /// Cholesky factor that eliminating the part creates (George and Liu 1981, the reach of
    /// a node through eliminated ones).
    pub fn closure(&self, nnx: usize, nny: usize) -> Part {
        Part {
            i: (self.i.0.saturating_sub(1), (self.i.1 + 1).min(nnx)),
            j: (self.j.0.saturating_sub(1), (self.j.1 + 1).min(nny)),
        }
    }
}

/// What [`dissect`] emits: a node, in elimination order, or the end of a block of nodes
/// eliminated together, which completes the elimination of the given part.
enum Step {
    Node(usize, usize),
    Closes(Part),
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

/// Emit the nodes of `part` in nested dissection order: both halves, then the separator, each
/// separator and each part not split further a block.
fn dissect(part: Part, p: usize, emit: &mut impl FnMut(Step)) {
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
                    emit(Step::Node(i, j));
                }
            }
            emit(Step::Closes(part));
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
                emit(if across {
                    Step::Node(s, k)
                } else {
                    Step::Node(k, s)
                });
            }
            emit(Step::Closes(part));
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
