//! Contact across the interface of two elastic bodies whose meshes need not match
//! (docs/design.md §12): the discretisations of the constraint between the slave's trace and the
//! master's — node-to-segment (one and two pass), mortar segment-to-segment with standard and
//! dual multipliers, and the reduced-integration penalty's rules on the slave's edges — each
//! given as a [`Coupling`]: weighted gaps, linear in the two traces' normal displacements.

mod condense;
mod dual;
mod error;
mod mortar;
mod multipliers;
mod nts;
#[doc(hidden)]
pub mod pressed;
#[cfg(test)]
mod props;
mod rip;
mod segments;
#[doc(hidden)]
pub mod solve;
#[cfg(test)]
mod tests;
mod trace;

pub use error::InterfaceError;
pub use multipliers::{MultiplierBasis, multiplier_mass};
pub use rip::smoothed_pressure;

use super::Rule;
use trace::Trace;

/// One side of a flat interface: its trace's nodes in ascending x and the order of its edges
/// (1: the Q1 element's linear edges; 2: Q2's quadratic ones, edge e having the nodes
/// `2e, 2e + 1, 2e + 2`).
#[derive(Clone, Copy, Debug)]
pub struct Side<'a> {
    /// The trace's nodes, ascending.
    pub x: &'a [f64],
    /// 1 or 2.
    pub order: usize,
}

/// How the constraint is discretised across the interface (docs/design.md §12).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InterfaceMethod {
    /// Node-to-segment, one pass: each slave node onto the master's segments.
    Nts,
    /// Node-to-segment, two pass: the slave's nodes onto the master and the master's onto the
    /// slave.
    Nts2,
    /// Mortar segment-to-segment, the slave's trace space as multipliers.
    Mortar,
    /// Mortar segment-to-segment, the biorthogonal (dual) basis as multipliers.
    MortarDual,
    /// The reduced-integration penalty: the rule's points on the slave's edges, the gap to the
    /// master measured at each point.
    Rip(Rule),
}

impl InterfaceMethod {
    /// Every discretisation: node-to-segment one and two pass, mortar standard and dual, and
    /// the reduced-integration penalty with each rule.
    pub const ALL: [InterfaceMethod; 8] = [
        InterfaceMethod::Nts,
        InterfaceMethod::Nts2,
        InterfaceMethod::Mortar,
        InterfaceMethod::MortarDual,
        InterfaceMethod::Rip(Rule::Gauss1),
        InterfaceMethod::Rip(Rule::Gauss2),
        InterfaceMethod::Rip(Rule::Trapezoid),
        InterfaceMethod::Rip(Rule::Simpson),
    ];

    /// Its name in the outputs: `nts`, `nts2`, `mortar`, `mortar-dual`, `rip-<rule>` (e.g.
    /// `rip-gauss1`).
    pub fn name(self) -> &'static str {
        match self {
            InterfaceMethod::Nts => "nts",
            InterfaceMethod::Nts2 => "nts2",
            InterfaceMethod::Mortar => "mortar",
            InterfaceMethod::MortarDual => "mortar-dual",
            InterfaceMethod::Rip(Rule::Gauss1) => "rip-gauss1",
            InterfaceMethod::Rip(Rule::Gauss2) => "rip-gauss2",
            InterfaceMethod::Rip(Rule::Trapezoid) => "rip-trapezoid",
            InterfaceMethod::Rip(Rule::Simpson) => "rip-simpson",
        }
    }
}

/// A discretised constraint (docs/design.md §12): at each constraint k, the gap
///
/// `g_k = g0_k + Σ_i slave[k]_i u_s,i − Σ_l master[k]_l u_m,l ≥ 0`,
///
/// u_s and u_m the slave's and the master's displacements at their trace nodes along the
/// interface's normal pointing from the master into the slave (+y when the upper body is the
/// slave), g0 the initial gap along it, and the measure
/// `weight[k]` that the constraint carries: its multiplier λ_k (a pressure, compression
/// positive) exerts the nodal forces `weight[k] λ_k slave[k]_i` and
/// `−weight[k] λ_k master[k]_l`, and the penalty's energy is `(1/2ε) Σ_k weight[k] [g_k]₋²`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Coupling {
    /// Where each constraint sits on the interface (x), for the outputs and the charts.
    pub x: Vec<f64>,
    /// The measure each constraint carries (> 0).
    pub weight: Vec<f64>,
    /// Each constraint's coefficients on the slave's trace nodes: (node, coefficient).
    pub slave: Vec<Vec<(usize, f64)>>,
    /// Each constraint's coefficients on the master's trace nodes: (node, coefficient).
    pub master: Vec<Vec<(usize, f64)>>,
}

/// The constraint across the interface of `slave` and `master` discretised by `method`
/// (docs/design.md §12). Every row's slave and master coefficients sum to 1: a rigid
/// penetration δ of the slave into the master gives the gap −δ at every row.
///
/// # Errors
/// A side whose order is not 1 or 2, whose nodes are fewer than one edge's, not finite, not
/// strictly ascending, or (order 2) whose mid-edge nodes are off their edges' middles; two
/// sides with no overlap; a method that finds no constraint on the overlap.
pub fn coupling(method: InterfaceMethod, slave: Side, master: Side) -> Result<Coupling, InterfaceError> {
    let (slave, master) = (Trace::new(slave, "slave")?, Trace::new(master, "master")?);
    match method {
        InterfaceMethod::Nts => nts::nts(&slave, &master, false),
        InterfaceMethod::Nts2 => nts::nts(&slave, &master, true),
        InterfaceMethod::Mortar => mortar::mortar(&slave, &master, false),
        InterfaceMethod::MortarDual => mortar::mortar(&slave, &master, true),
        InterfaceMethod::Rip(rule) => rip::rip(rule, &slave, &master),
    }
}
