//! What makes a side of the interface, or the pair of them, unusable for a coupling
//! (docs/design.md §12).

use crate::text::num;

/// A side of the interface that cannot be discretised, or two sides that cannot be coupled;
/// the message says what and the allowed range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InterfaceError {
    /// An order other than 1 or 2.
    #[error("the {side}'s trace has order {order}; allowed: 1 (linear edges) or 2 (quadratic edges)")]
    Order {
        /// `slave` or `master`.
        side: &'static str,
        /// The order given.
        order: usize,
    },
    /// Too few nodes for one edge, or a count that is not a whole number of edges.
    #[error(
        "the {side}'s trace has {nodes} node(s); allowed at order {order}: {order}·E + 1 nodes \
         for E ≥ 1 edges (neighbouring edges sharing their end)"
    )]
    Nodes {
        /// `slave` or `master`.
        side: &'static str,
        /// The number of nodes given.
        nodes: usize,
        /// The trace's order.
        order: usize,
    },
    /// A node's x that is not a finite number.
    #[error("the {side}'s node {index} is at x = {}; allowed: a finite number", num(*x))]
    NotFinite {
        /// `slave` or `master`.
        side: &'static str,
        /// The node's index in the trace.
        index: usize,
        /// Its x.
        x: f64,
    },
    /// A node that does not lie strictly right of the one before it.
    #[error(
        "the {side}'s node {index} at x = {} is not right of node {} at x = {}; allowed: \
         nodes strictly ascending in x",
        num(*x),
        index - 1,
        num(*previous)
    )]
    NotAscending {
        /// `slave` or `master`.
        side: &'static str,
        /// The node's index in the trace.
        index: usize,
        /// Its x.
        x: f64,
        /// The x of the node before it.
        previous: f64,
    },
    /// A quadratic edge's mid node away from the edge's middle (the edge's basis is the
    /// Lagrange basis on equispaced nodes, as the element's trace).
    #[error(
        "the {side}'s mid-edge node {index} is at x = {}, not at its edge's middle {}; allowed: \
         within 1e-9 of the edge's length from it",
        num(*x),
        num(*middle)
    )]
    MidNode {
        /// `slave` or `master`.
        side: &'static str,
        /// The node's index in the trace.
        index: usize,
        /// Its x.
        x: f64,
        /// The middle of its edge.
        middle: f64,
    },
    /// Sides that share no interval of positive length.
    #[error(
        "the slave [{}, {}] and the master [{}, {}] do not overlap; allowed: sides that share \
         an interval of positive length",
        num(slave.0),
        num(slave.1),
        num(master.0),
        num(master.1)
    )]
    NoOverlap {
        /// The slave's ends.
        slave: (f64, f64),
        /// The master's ends.
        master: (f64, f64),
    },
    /// A discretisation that finds no constraint on the overlap (e.g. node-to-segment with no
    /// slave node over the master).
    #[error(
        "the {method} discretisation has no constraint on the overlap [{}, {}]: no {what} lies \
         over it; allowed: sides whose overlap holds at least one",
        num(overlap.0),
        num(overlap.1)
    )]
    NoConstraint {
        /// The discretisation's name ([`super::InterfaceMethod::name`]).
        method: &'static str,
        /// What it needs on the overlap.
        what: &'static str,
        /// The overlap's ends.
        overlap: (f64, f64),
    },
}
