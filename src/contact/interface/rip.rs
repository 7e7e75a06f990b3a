//! The reduced-integration penalty across the interface (docs/design.md §12): the rule's
//! distinct points on the slave's edges (docs/design.md §2), the gap at each measured to the
//! master below it, and the smoothed pressure p̄ of (17) on the slave's vertices.

use super::trace::{Trace, overlap};
use super::{Coupling, InterfaceError, InterfaceMethod, Side};
use crate::contact::pressure;
use crate::contact::rule::{ContactPoints, Rule};

/// A row per point x_q of `rule` on the slave that lies over the master:
/// g = Σ_i φ_i(x_q) u_s,i − Σ_l φ^m_l(x_q) u_m,l, weighted by the point's weight (the sum of
/// w_q h_e over the edges that share it), rows ascending in x.
pub(crate) fn rip(rule: Rule, slave: &Trace, master: &Trace) -> Result<Coupling, InterfaceError> {
    let (lo, hi) = overlap(slave, master)?;
    let cp = ContactPoints::new(rule, slave.x, slave.order);
    let mut out = Coupling::default();
    for q in cp.points.iter().filter(|q| master.holds(q.x)) {
        out.x.push(q.x);
        out.weight.push(q.weight);
        out.slave.push(
            q.nodes
                .iter()
                .zip(&q.trace)
                .filter(|&(_, &t)| t != 0.0)
                .map(|(&k, &t)| (k, t))
                .collect(),
        );
        out.master.push(master.shape_at(q.x));
    }
    if out.x.is_empty() {
        return Err(InterfaceError::NoConstraint {
            method: InterfaceMethod::Rip(rule).name(),
            what: "point of the rule on the slave",
            overlap: (lo, hi),
        });
    }
    Ok(out)
}

/// The smoothed pressure p̄ of (17) on the slave's vertices (docs/design.md §4): p̄_i =
/// I(p, φ_i)/I(1, φ_i), φ_i the vertex's hat function, from the pressures `p` of the rows of
/// `coupling` — the one [`super::coupling`] gives for `InterfaceMethod::Rip(rule)` on this
/// slave — a point of the rule off the master (no row) carrying p = 0.
///
/// # Errors
/// The slave's errors of [`super::coupling`].
pub fn smoothed_pressure(
    rule: Rule,
    slave: Side,
    coupling: &Coupling,
    p: &[f64],
) -> Result<Vec<f64>, InterfaceError> {
    let trace = Trace::new(slave, "slave")?;
    let cp = ContactPoints::new(rule, trace.x, trace.order);
    let mut at_points = vec![0.0; cp.len()];
    let mut k = 0;
    for (&x, &pk) in coupling.x.iter().zip(p) {
        while k < cp.len() && cp.points[k].x < x {
            k += 1;
        }
        if k < cp.len() && cp.points[k].x == x {
            at_points[k] = pk;
        }
    }
    Ok(pressure::smoothed_pressure(&cp, &at_points))
}
