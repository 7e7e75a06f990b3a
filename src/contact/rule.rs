//! Contact quadrature rules I of (10) on the edges of Γ_C (docs/design.md §2), and the trace of the
//! normal displacement at their points.
//!
//! Points are kept *distinct*: an edge end shared by two edges (trapezoid, Simpson) is one
//! point whose weight is the sum of both edges' weights. The pressure space Q_h is spanned by
//! the Lagrange functions through the points of each edge, one basis function per distinct
//! point, so it is continuous exactly when the rule has points at the edge ends.

use serde::{Deserialize, Serialize};

use crate::fem::basis::lagrange_1d;

/// A quadrature rule for the penalty term.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Rule {
    /// One-point Gauss: piecewise-constant pressure (M1).
    Gauss1,
    /// Two-point Gauss: discontinuous linear pressure (M2).
    Gauss2,
    /// Trapezoid: continuous linear pressure (M3).
    Trapezoid,
    /// Simpson: continuous quadratic pressure (M4 with Q2).
    Simpson,
}

impl Rule {
    /// Every rule, in the order of M1–M4.
    pub const ALL: [Rule; 4] = [Rule::Gauss1, Rule::Gauss2, Rule::Trapezoid, Rule::Simpson];

    /// The rule's name in scenario files, the command line and the outputs, e.g. `gauss1`.
    pub fn name(self) -> &'static str {
        match self {
            Rule::Gauss1 => "gauss1",
            Rule::Gauss2 => "gauss2",
            Rule::Trapezoid => "trapezoid",
            Rule::Simpson => "simpson",
        }
    }

    /// The number of distinct points of the rule on `n_edges` consecutive edges (a point at
    /// an edge's end is shared with the next edge).
    pub fn n_points(self, n_edges: usize) -> usize {
        match self {
            Rule::Gauss1 => n_edges,
            Rule::Gauss2 => 2 * n_edges,
            Rule::Trapezoid => n_edges + 1,
            Rule::Simpson => 2 * n_edges + 1,
        }
    }

    /// Points s ∈ [0, 1] along an edge and weights relative to its length (docs/design.md §2).
    pub fn points(self) -> Vec<(f64, f64)> {
        let d = 0.5 / 3f64.sqrt();
        match self {
            Rule::Gauss1 => vec![(0.5, 1.0)],
            Rule::Gauss2 => vec![(0.5 - d, 0.5), (0.5 + d, 0.5)],
            Rule::Trapezoid => vec![(0.0, 0.5), (1.0, 0.5)],
            Rule::Simpson => vec![(0.0, 1.0 / 6.0), (0.5, 4.0 / 6.0), (1.0, 1.0 / 6.0)],
        }
    }
}

/// One distinct point of the rule on Γ_C.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactPoint {
    /// Its coordinate on Γ_C.
    pub x: f64,
    /// Sum of the weights w_i^e of (10) of every edge that has this point.
    pub weight: f64,
    /// The (first) edge it lies on and its parameter s ∈ [0, 1] there.
    pub edge: usize,
    /// Its parameter s ∈ [0, 1] on `edge`.
    pub s: f64,
    /// Γ_C nodes of that edge (indices into the Γ_C node list) and the trace's shape values:
    /// u_n(x) = Σ `trace[k]` · u_n(`nodes[k]`).
    pub nodes: Vec<usize>,
    /// The trace's shape values at the point, one per entry of `nodes`.
    pub trace: Vec<f64>,
}

/// The rule laid on Γ_C.
#[derive(Clone, Debug)]
pub struct ContactPoints {
    /// The rule laid.
    pub rule: Rule,
    /// Vertex coordinates x₁ < … < x_{E+1} of Γ_C.
    pub vertex_x: Vec<f64>,
    /// Coordinates of every Γ_C node (vertices, and mid-edge nodes for Q2).
    pub node_x: Vec<f64>,
    /// The distinct points of the rule (a point shared by two edges once).
    pub points: Vec<ContactPoint>,
    /// For each edge, the indices of its points in ascending s.
    pub edge_points: Vec<Vec<usize>>,
}

impl ContactPoints {
    /// Lay `rule` on the Γ_C whose nodes are at `node_x` (ascending), the trace being of
    /// degree `order` (1: two nodes per edge, 2: three).
    pub fn new(rule: Rule, node_x: &[f64], order: usize) -> Self {
        let n_edges = (node_x.len() - 1) / order;
        let vertex_x: Vec<f64> = (0..=n_edges).map(|e| node_x[e * order]).collect();
        let mut points: Vec<ContactPoint> = Vec::new();
        let mut edge_points = Vec::with_capacity(n_edges);
        for e in 0..n_edges {
            let (x0, x1) = (vertex_x[e], vertex_x[e + 1]);
            let h = x1 - x0;
            let mut mine = Vec::new();
            for (s, w) in rule.points() {
                if s == 0.0 && e > 0 {
                    // The end shared with the previous edge: already a point.
                    let last = points.len() - 1;
                    points[last].weight += w * h;
                    mine.push(last);
                    continue;
                }
                let (vals, _) = lagrange_1d(order, 2.0 * s - 1.0);
                let x = if s == 1.0 { x1 } else { x0 + s * h };
                points.push(ContactPoint {
                    x,
                    weight: w * h,
                    edge: e,
                    s,
                    nodes: (e * order..=e * order + order).collect(),
                    trace: vals[..=order].to_vec(),
                });
                mine.push(points.len() - 1);
            }
            edge_points.push(mine);
        }
        ContactPoints {
            rule,
            vertex_x,
            node_x: node_x.to_vec(),
            points,
            edge_points,
        }
    }

    /// The number of distinct points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The number of edges E of Γ_C.
    pub fn n_edges(&self) -> usize {
        self.vertex_x.len() - 1
    }

    /// u_n at every point from u_n at the Γ_C nodes.
    pub fn trace_of(&self, un_nodes: &[f64]) -> Vec<f64> {
        self.points
            .iter()
            .map(|q| q.nodes.iter().zip(&q.trace).map(|(&k, t)| t * un_nodes[k]).sum())
            .collect()
    }

    /// The parameter of point k on edge e (a shared end is s = 0 of the later edge).
    pub fn s_on_edge(&self, k: usize, e: usize) -> f64 {
        let q = &self.points[k];
        if q.edge == e { q.s } else { 0.0 }
    }

    /// The edge that holds x (the last one for x past the end).
    pub fn edge_at(&self, x: f64) -> usize {
        self.vertex_x
            .partition_point(|&v| v <= x)
            .clamp(1, self.n_edges())
            - 1
    }

    /// Values at s ∈ [0, 1] of edge e's Lagrange basis through its points (one per point).
    pub fn edge_basis(&self, e: usize, s: f64) -> Vec<f64> {
        let nodes: Vec<f64> = self.edge_points[e]
            .iter()
            .map(|&k| self.s_on_edge(k, e))
            .collect();
        (0..nodes.len())
            .map(|a| {
                (0..nodes.len())
                    .filter(|&b| b != a)
                    .map(|b| (s - nodes[b]) / (nodes[a] - nodes[b]))
                    .product()
            })
            .collect()
    }

    /// The function of Q_h with values `v` at the points, evaluated at x.
    pub fn interpolate(&self, v: &[f64], x: f64) -> f64 {
        let e = self.edge_at(x);
        let s = (x - self.vertex_x[e]) / (self.vertex_x[e + 1] - self.vertex_x[e]);
        self.edge_points[e]
            .iter()
            .zip(self.edge_basis(e, s))
            .map(|(&k, phi)| v[k] * phi)
            .sum()
    }

    /// The continuous piecewise-linear function with values `v` at the vertices, at x.
    pub fn interpolate_vertices(&self, v: &[f64], x: f64) -> f64 {
        let e = self.edge_at(x);
        let s = (x - self.vertex_x[e]) / (self.vertex_x[e + 1] - self.vertex_x[e]);
        (1.0 - s) * v[e] + s * v[e + 1]
    }

    /// The vertex hat functions φ_i of Γ_C that are non-zero at point q, with their values.
    pub fn hats_at(&self, q: &ContactPoint) -> [(usize, f64); 2] {
        [(q.edge, 1.0 - q.s), (q.edge + 1, q.s)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shared_ends_are_merged_and_weights_add_up() {
        let x = [0.0, 1.0, 3.0, 3.5];
        for rule in Rule::ALL {
            let cp = ContactPoints::new(rule, &x, 1);
            let total: f64 = cp.points.iter().map(|q| q.weight).sum();
            assert!((total - 3.5).abs() < 1e-15, "{rule:?}");
            assert!(
                cp.points.windows(2).all(|w| w[0].x < w[1].x),
                "{rule:?} not ascending"
            );
        }
        let trap = ContactPoints::new(Rule::Trapezoid, &x, 1);
        let w: Vec<f64> = trap.points.iter().map(|q| q.weight).collect();
        assert_eq!(w, vec![0.5, 1.5, 1.25, 0.25]);
        assert_eq!(ContactPoints::new(Rule::Simpson, &x, 1).len(), 7);
        assert_eq!(ContactPoints::new(Rule::Gauss2, &x, 1).len(), 6);
    }

    #[test]
    fn quadratic_trace_interpolates() {
        // Q2 edge nodes at 0, 0.5, 1 with u_n = x²: the trace is exact at every point.
        let cp = ContactPoints::new(Rule::Gauss2, &[0.0, 0.5, 1.0], 2);
        let un: Vec<f64> = cp.node_x.iter().map(|x| x * x).collect();
        for (q, v) in cp.points.iter().zip(cp.trace_of(&un)) {
            assert!((v - q.x * q.x).abs() < 1e-15);
        }
    }
}
