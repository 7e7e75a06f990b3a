//! Grading: everything about a mesh graded at its contact edges or over its contact zone
//! (docs/design.md §6), in one place. It owns the request's words (`N`, `Nz`, `auto`:
//! [`Grading`], [`RefineEdges`], read and written as on the command line); the
//! graded lines (a uniform level's vertex lines with the intervals around each contact edge,
//! and the rows of cells next to Γ_C, bisected once per pass: [`GradedGrid`]); the zone
//! ([`zone`]: the whole contact zone graded instead); the band (whether the contact edges still
//! lie in a graded grid's finest band); the size of a graded request, predicted from its lines
//! before any pass ([`estimate`]); and the passes of a graded solve ([`passes`]). Where the
//! pressure has its square-root profile (the edges of the contact zone), a uniform mesh's
//! error of p and p̄ is set by the two cells that hold an edge; bisecting only there buys the
//! accuracy of a much finer level for a few more unknowns, until (17) meets the band's changes
//! of edge length ([`zone`] says why, and grades the whole zone instead).
//!
//! The same lines serve the study's reference and a graded solve: grading is only a choice of
//! lines, so a graded mesh is the mesh a scenario with those `x_lines`/`y_lines` gives at level
//! 0, and its refined lines contain the uniform level's (nesting). The folder sits above the
//! contact methods and the discretisation, and below the scenario (which stores a grading and
//! hands the estimate its uniform lines and its obstacle) and the solve entry (which hands the
//! passes the uniform level's discretisation and its solve on one mesh); the errors and the
//! warnings name no grading, only carry what they print of one.

use crate::contact::ContactPoints;
use crate::mesh::{Element, Mesh};

mod band;
#[doc(hidden)]
pub mod estimate;
#[doc(hidden)]
pub mod passes;
mod request;
#[doc(hidden)]
pub mod zone;

/// How many vertex intervals on each side of a contact edge one pass bisects (with the edge's
/// own), and how many of Γ_C's neighbouring rows of cells.
pub const EDGE_WIDTH: usize = 2;

pub use request::{AUTO_TOLERANCE, Grading, MAX_PASSES, RefineEdges, RefineEdgesError};

/// A grid graded at the contact edges (or over the contact zone): a uniform level's vertex
/// lines after `passes` passes.
#[derive(Clone, Debug, PartialEq)]
pub struct GradedGrid {
    /// The uniform level it grades.
    pub level: u32,
    /// How many passes it has had (0: the uniform level).
    pub passes: u32,
    /// Vertex lines x₀ < … across.
    pub xs: Vec<f64>,
    /// Vertex lines y₀ < … up the height, Γ_C the last.
    pub ys: Vec<f64>,
}

impl GradedGrid {
    /// The uniform grid of `level`: `mesh`'s vertex lines, no pass yet.
    pub fn uniform(level: u32, mesh: &Mesh) -> Self {
        GradedGrid {
            level,
            passes: 0,
            xs: mesh.xs.clone(),
            ys: mesh.ys.clone(),
        }
    }

    /// The mesh of `element` on these lines.
    pub fn mesh(&self, element: Element, half_model: bool) -> Mesh {
        Mesh::from_lines(element, self.xs.clone(), self.ys.clone(), half_model)
    }

    /// The smallest cell side (the uniform level's h before any pass).
    pub fn h_min(&self) -> f64 {
        h_min(&self.xs, &self.ys)
    }

    /// The next pass at the contact `edges` (vertex intervals of `xs`, [`contact_edges`]);
    /// None when there is no edge to grade.
    pub fn refined(&self, edges: &[usize]) -> Option<Self> {
        let (xs, ys) = refine_lines(&self.xs, &self.ys, edges)?;
        Some(GradedGrid {
            level: self.level,
            passes: self.passes + 1,
            xs,
            ys,
        })
    }

    /// Whether `x` lies in the finest band: in an x-interval as narrow as the last pass made
    /// them (after a pass, where a contact edge must be for the grading to be where it is
    /// needed).
    pub fn in_band(&self, x: f64) -> bool {
        let finest = h_min(&self.xs, &self.xs) * (1.0 + 1e-9);
        self.xs
            .windows(2)
            .any(|w| w[0] <= x && x <= w[1] && w[1] - w[0] <= finest)
    }
}

/// The smallest cell side of the grid with vertex lines `xs` and `ys`.
pub fn h_min(xs: &[f64], ys: &[f64]) -> f64 {
    let narrowest = |v: &[f64]| v.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
    narrowest(xs).min(narrowest(ys))
}

/// The contact edges of the pressure `p` at `points`: every pair of neighbouring points where
/// p goes from > 0 to 0 (or back), as the vertex interval of Γ_C that holds both.
pub fn contact_edges(points: &ContactPoints, p: &[f64]) -> Vec<usize> {
    let top = p.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let pressed = |v: f64| v > 1e-9 * top;
    let mut edges: Vec<usize> = points
        .points
        .windows(2)
        .zip(p.windows(2))
        .filter(|(_, v)| pressed(v[0]) != pressed(v[1]))
        .map(|(q, _)| q[0].edge.max(q[1].edge))
        .collect();
    edges.dedup();
    edges
}

/// `xs` and `ys` after one pass at the contact `edges` (vertex intervals of `xs`): the
/// [`EDGE_WIDTH`] x-intervals on each side of every edge (and the edge's own) bisected, and
/// the [`EDGE_WIDTH`] rows of cells next to Γ_C (the last of `ys`). None without an edge.
pub fn refine_lines(xs: &[f64], ys: &[f64], edges: &[usize]) -> Option<(Vec<f64>, Vec<f64>)> {
    if edges.is_empty() {
        return None;
    }
    let nx = xs.len() - 1;
    let mut split = vec![false; nx];
    for &e in edges {
        split[e.saturating_sub(EDGE_WIDTH)..=(e + EDGE_WIDTH).min(nx - 1)].fill(true);
    }
    let ny = ys.len() - 1;
    let top: Vec<bool> = (0..ny).map(|c| c + EDGE_WIDTH >= ny).collect();
    Some((bisect_marked(xs, &split), bisect_marked(ys, &top)))
}

/// `lines` with the intervals marked in `split` bisected (the old lines are kept: nested).
fn bisect_marked(lines: &[f64], split: &[bool]) -> Vec<f64> {
    let mut out = Vec::with_capacity(2 * lines.len());
    for (w, &s) in lines.windows(2).zip(split) {
        out.push(w[0]);
        if s {
            out.push(0.5 * (w[0] + w[1]));
        }
    }
    out.push(lines[lines.len() - 1]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One pass bisects the edge's interval and EDGE_WIDTH on each side (clipped at the ends),
    /// and the EDGE_WIDTH rows under Γ_C; every old line is kept.
    #[test]
    fn a_pass_bisects_the_band_and_keeps_the_old_lines() {
        let xs: Vec<f64> = (0..=8).map(f64::from).collect();
        let ys: Vec<f64> = (0..=4).map(f64::from).collect();
        let (x2, y2) = refine_lines(&xs, &ys, &[1, 7]).unwrap();
        assert_eq!(
            x2,
            [
                0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 5.0, 5.5, 6.0, 6.5, 7.0, 7.5, 8.0
            ]
        );
        assert_eq!(y2, [0.0, 1.0, 2.0, 2.5, 3.0, 3.5, 4.0]);
        assert!(xs.iter().all(|x| x2.contains(x)) && ys.iter().all(|y| y2.contains(y)));
        assert_eq!(refine_lines(&xs, &ys, &[]), None);
        assert_eq!(h_min(&x2, &y2), 0.5);
    }
}
