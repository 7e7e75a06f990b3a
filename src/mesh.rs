//! Structured tensor-product meshes of the body (docs/design.md §1): vertex lines `xs`, `ys`, the
//! element kind, and the node grid derived from them (Q2 adds the mid-lines).
//!
//! A *cell* is one rectangle of the grid. Q1 and Q2 have one element per cell; P1 splits each
//! cell into two triangles along a diagonal that is mirrored about x = 0, so that the full
//! model's mesh is the mirror image of itself and its right half is the half model's mesh.

use serde::{Deserialize, Serialize};

/// The finest mesh level riplab accepts: level L bisects every level-0 cell L times.
pub const MAX_LEVEL: u32 = 8;

/// The finite element used for the displacement (docs/design.md §2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Element {
    /// Bilinear 4-node quadrilateral, the paper's element.
    Q1,
    /// Biquadratic 9-node quadrilateral (needed for the paper's M4).
    Q2,
    /// Linear 3-node triangle, two per cell (named in the paper's Theorem 2).
    P1,
}

impl Element {
    /// Polynomial degree of the trace on an edge.
    pub fn order(self) -> usize {
        match self {
            Element::Q2 => 2,
            Element::Q1 | Element::P1 => 1,
        }
    }

    /// The element's name in scenario files, the command line and the outputs, e.g. `q1`.
    pub fn name(self) -> &'static str {
        match self {
            Element::Q1 => "q1",
            Element::Q2 => "q2",
            Element::P1 => "p1",
        }
    }

    /// Every element.
    pub const ALL: [Element; 3] = [Element::Q1, Element::Q2, Element::P1];

    /// The node lines across `cells` cells in one direction: the vertex lines, and for Q2 the
    /// mid-lines too.
    pub fn node_lines(self, cells: usize) -> usize {
        self.order() * cells + 1
    }

    /// The number of elements in `cells` cells (two triangles per cell for P1).
    pub fn elements(self, cells: usize) -> usize {
        match self {
            Element::P1 => 2 * cells,
            Element::Q1 | Element::Q2 => cells,
        }
    }
}

/// Which diagonal splits a P1 cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Diagonal {
    /// From the lower-left to the upper-right corner.
    Rising,
    /// From the upper-left to the lower-right corner.
    Falling,
}

/// A structured mesh of a rectangle.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// The element kind.
    pub element: Element,
    /// Vertex lines x₀ < x₁ < … < x_nx.
    pub xs: Vec<f64>,
    /// Vertex lines y₀ < y₁ < … < y_ny; y₀ is the clamped bottom Γ_D, y_ny the contact side Γ_C.
    pub ys: Vec<f64>,
    /// Node lines (equal to the vertex lines for Q1 and P1, with mid-lines added for Q2).
    pub node_x: Vec<f64>,
    /// Node lines in y, as `node_x`.
    pub node_y: Vec<f64>,
    /// Half model: u_x = 0 on the left side x = x₀ (the symmetry line).
    pub symmetric_left: bool,
    /// u_x = 0 on the right side x = x_nx too (a roller wall; no scenario sets it: the contact
    /// patch test of tests/numerics/methods.rs, whose exact solution is a uniform compression).
    pub roller_right: bool,
}

impl Mesh {
    /// A mesh with the given vertex lines.
    pub fn from_lines(element: Element, xs: Vec<f64>, ys: Vec<f64>, symmetric_left: bool) -> Self {
        assert!(xs.len() >= 2 && ys.len() >= 2, "a mesh needs at least one cell");
        let refine = |v: &[f64]| -> Vec<f64> {
            if element.order() == 1 {
                return v.to_vec();
            }
            let mut out = Vec::with_capacity(2 * v.len() - 1);
            for w in v.windows(2) {
                out.push(w[0]);
                out.push(0.5 * (w[0] + w[1]));
            }
            out.push(v[v.len() - 1]);
            out
        };
        let node_x = refine(&xs);
        let node_y = refine(&ys);
        debug_assert_eq!(node_x.len(), element.node_lines(xs.len() - 1));
        debug_assert_eq!(node_y.len(), element.node_lines(ys.len() - 1));
        Mesh {
            element,
            xs,
            ys,
            node_x,
            node_y,
            symmetric_left,
            roller_right: false,
        }
    }

    /// A uniform grid of `nx` × `ny` cells on [x0, x1] × [y0, y1].
    pub fn uniform(
        element: Element,
        (x0, x1, nx): (f64, f64, usize),
        (y0, y1, ny): (f64, f64, usize),
        symmetric_left: bool,
    ) -> Self {
        let lines = |a: f64, b: f64, n: usize| -> Vec<f64> {
            (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
        };
        Self::from_lines(element, lines(x0, x1, nx), lines(y0, y1, ny), symmetric_left)
    }

    /// The number of cells across.
    pub fn nx(&self) -> usize {
        self.xs.len() - 1
    }
    /// The number of cells up.
    pub fn ny(&self) -> usize {
        self.ys.len() - 1
    }
    /// Nodes per node row.
    pub fn nnx(&self) -> usize {
        self.node_x.len()
    }
    /// The number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.node_x.len() * self.node_y.len()
    }
    /// The number of cells.
    pub fn n_cells(&self) -> usize {
        self.nx() * self.ny()
    }
    /// Number of finite elements (two triangles per cell for P1).
    pub fn n_elements(&self) -> usize {
        self.element.elements(self.n_cells())
    }
    /// Index of the node on node column `i`, node row `j`.
    pub fn node(&self, i: usize, j: usize) -> usize {
        i + j * self.nnx()
    }
    /// The coordinates (x, y) of node `n`.
    pub fn node_coords(&self, n: usize) -> (f64, f64) {
        let nnx = self.nnx();
        (self.node_x[n % nnx], self.node_y[n / nnx])
    }

    /// The nodes of cell (ci, cj) in tensor order (local x index fastest).
    pub fn cell_nodes(&self, ci: usize, cj: usize) -> Vec<usize> {
        self.cell_node_iter(ci, cj).collect()
    }

    /// [`Mesh::cell_nodes`] without allocating, for the assembly's loop over every cell.
    pub fn cell_node_iter(&self, ci: usize, cj: usize) -> impl Iterator<Item = usize> + '_ {
        let p = self.element.order();
        (0..=p).flat_map(move |lj| (0..=p).map(move |li| self.node(ci * p + li, cj * p + lj)))
    }

    /// (x0, x1, y0, y1) of cell (ci, cj).
    pub fn cell_rect(&self, ci: usize, cj: usize) -> (f64, f64, f64, f64) {
        (self.xs[ci], self.xs[ci + 1], self.ys[cj], self.ys[cj + 1])
    }

    /// The diagonal of a P1 cell: rising right of x = 0, falling left of it (mirror symmetry).
    pub fn diagonal(&self, ci: usize) -> Diagonal {
        if self.xs[ci] + self.xs[ci + 1] >= 0.0 {
            Diagonal::Rising
        } else {
            Diagonal::Falling
        }
    }

    /// The nodes on the contact side Γ_C (top), in ascending x.
    pub fn top_nodes(&self) -> Vec<usize> {
        let j = self.node_y.len() - 1;
        (0..self.nnx()).map(|i| self.node(i, j)).collect()
    }

    /// The largest cell side, the h of the paper's estimates.
    pub fn h(&self) -> f64 {
        cell_size(&self.xs, &self.ys, 0)
    }
}

/// The largest cell side (the h of the paper's estimates) of the grid with vertex lines `xs`
/// and `ys` after `level` bisections of every cell, computed from the unbisected lines.
pub fn cell_size(xs: &[f64], ys: &[f64], level: u32) -> f64 {
    let widest = |v: &[f64]| v.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
    widest(xs).max(widest(ys)) / f64::from(1u32 << level)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q2_grid_has_mid_lines_and_nine_nodes_per_cell() {
        let m = Mesh::uniform(Element::Q2, (0.0, 2.0, 2), (0.0, 1.0, 1), true);
        assert_eq!(m.node_x, vec![0.0, 0.5, 1.0, 1.5, 2.0]);
        assert_eq!(m.n_nodes(), 15);
        assert_eq!(m.cell_nodes(1, 0), vec![2, 3, 4, 7, 8, 9, 12, 13, 14]);
        assert_eq!(m.top_nodes(), vec![10, 11, 12, 13, 14]);
    }

    #[test]
    fn p1_diagonals_mirror_about_zero() {
        let m = Mesh::uniform(Element::P1, (-2.0, 2.0, 4), (0.0, 1.0, 1), false);
        let d: Vec<_> = (0..4).map(|i| m.diagonal(i)).collect();
        assert_eq!(
            d,
            [
                Diagonal::Falling,
                Diagonal::Falling,
                Diagonal::Rising,
                Diagonal::Rising
            ]
        );
        assert_eq!(m.n_elements(), 8);
    }
}
