//! One side's trace checked and laid out: its edges, the edge holding a point, the edge's
//! Lagrange basis there and each node's measure ∫_Γ φ_k (docs/design.md §12).

use super::{InterfaceError, Side};
use crate::fem::basis::lagrange_1d;

/// How far a quadratic edge's mid node may lie from the edge's middle, relative to the
/// edge's length.
const MID_NODE_TOLERANCE: f64 = 1e-9;

/// How far past its end, relative to its length, a point still lies on a trace: the same
/// width meshed with different numbers of cells may end an ulp apart (i·W/n at i = n).
const END_TOLERANCE: f64 = 1e-12;

/// A checked side: nodes finite and strictly ascending, a whole number of edges of order 1
/// or 2, quadratic edges' mid nodes at their middles.
#[derive(Clone, Debug)]
pub(crate) struct Trace<'a> {
    /// The nodes, ascending.
    pub x: &'a [f64],
    /// 1 or 2.
    pub order: usize,
    /// The edges' ends x₀ < x₁ < … < x_E.
    vertices: Vec<f64>,
}

impl<'a> Trace<'a> {
    /// Check `side` (named `role` in the errors: `slave` or `master`).
    pub fn new(side: Side<'a>, role: &'static str) -> Result<Self, InterfaceError> {
        let (x, order) = (side.x, side.order);
        if !(1..=2).contains(&order) {
            return Err(InterfaceError::Order { side: role, order });
        }
        if x.len() < order + 1 || (x.len() - 1) % order != 0 {
            return Err(InterfaceError::Nodes {
                side: role,
                nodes: x.len(),
                order,
            });
        }
        for (index, &xi) in x.iter().enumerate() {
            if !xi.is_finite() {
                return Err(InterfaceError::NotFinite {
                    side: role,
                    index,
                    x: xi,
                });
            }
            if index > 0 && xi <= x[index - 1] {
                return Err(InterfaceError::NotAscending {
                    side: role,
                    index,
                    x: xi,
                    previous: x[index - 1],
                });
            }
        }
        if order == 2 {
            for e in 0..(x.len() - 1) / 2 {
                let (a, m, b) = (x[2 * e], x[2 * e + 1], x[2 * e + 2]);
                let middle = 0.5 * (a + b);
                if (m - middle).abs() > MID_NODE_TOLERANCE * (b - a) {
                    return Err(InterfaceError::MidNode {
                        side: role,
                        index: 2 * e + 1,
                        x: m,
                        middle,
                    });
                }
            }
        }
        let vertices = x.iter().step_by(order).copied().collect();
        Ok(Trace { x, order, vertices })
    }

    /// The number of edges E.
    pub fn n_edges(&self) -> usize {
        self.vertices.len() - 1
    }

    /// Edge e's ends.
    pub fn edge(&self, e: usize) -> (f64, f64) {
        (self.vertices[e], self.vertices[e + 1])
    }

    /// The trace's ends.
    pub fn ends(&self) -> (f64, f64) {
        (self.vertices[0], self.vertices[self.n_edges()])
    }

    /// Whether x lies on the trace, ends included, or past an end by round-off
    /// ([`END_TOLERANCE`] of its length).
    pub fn holds(&self, x: f64) -> bool {
        let (a, b) = self.ends();
        let tol = END_TOLERANCE * (b - a);
        (a - tol..=b + tol).contains(&x)
    }

    /// The edge holding x: x₍e₎ ≤ x < x₍e+1₎, the first edge left of the trace and the last
    /// one from its right end on.
    pub fn edge_at(&self, x: f64) -> usize {
        self.vertices
            .partition_point(|&v| v <= x)
            .clamp(1, self.n_edges())
            - 1
    }

    /// Edge e's first node and its Lagrange basis at x (the first `order + 1` entries).
    pub fn basis(&self, e: usize, x: f64) -> (usize, [f64; 3]) {
        let (a, b) = self.edge(e);
        let (values, _) = lagrange_1d(self.order, 2.0 * (x - a) / (b - a) - 1.0);
        (e * self.order, values)
    }

    /// The trace's shape functions at x on the edge holding it, as (node, value), exact zeros
    /// left out; x past an end (by round-off, [`Trace::holds`]) is taken at that end.
    pub fn shape_at(&self, x: f64) -> Vec<(usize, f64)> {
        let (a, b) = self.ends();
        let x = x.clamp(a, b);
        let (first, values) = self.basis(self.edge_at(x), x);
        (0..=self.order)
            .filter(|&a| values[a] != 0.0)
            .map(|a| (first + a, values[a]))
            .collect()
    }

    /// ∫_Γ φ_k of every node: h/2 from each neighbouring linear edge; h/6 from each
    /// neighbouring quadratic edge at a vertex and 2h/3 at a mid node.
    pub fn measures(&self) -> Vec<f64> {
        let mut m = vec![0.0; self.x.len()];
        for e in 0..self.n_edges() {
            let (a, b) = self.edge(e);
            let h = b - a;
            let first = e * self.order;
            if self.order == 1 {
                m[first] += h / 2.0;
                m[first + 1] += h / 2.0;
            } else {
                m[first] += h / 6.0;
                m[first + 1] += 2.0 * h / 3.0;
                m[first + 2] += h / 6.0;
            }
        }
        m
    }
}

/// The overlap [max of the starts, min of the ends] of two sides, if it has a positive length.
pub(crate) fn overlap(slave: &Trace, master: &Trace) -> Result<(f64, f64), InterfaceError> {
    let (s, m) = (slave.ends(), master.ends());
    let (lo, hi) = (s.0.max(m.0), s.1.min(m.1));
    if lo < hi {
        Ok((lo, hi))
    } else {
        Err(InterfaceError::NoOverlap { slave: s, master: m })
    }
}
