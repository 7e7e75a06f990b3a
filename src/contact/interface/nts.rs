//! Node-to-segment coupling (docs/design.md §12): each slave node's gap to the master's
//! segment below it (one pass), and in the two-pass variant also each master node's gap to
//! the slave, written in the same slave/master columns.

use super::trace::{Trace, overlap};
use super::{Coupling, InterfaceError};

/// Two nodes whose x differ by at most this fraction of the overlap's length coincide: the
/// two passes' rows there are the same constraint, kept once.
const COINCIDENT: f64 = 1e-12;

/// One constraint before the rows are ordered.
struct Row {
    x: f64,
    weight: f64,
    slave: Vec<(usize, f64)>,
    master: Vec<(usize, f64)>,
}

/// The one-pass rows: a row per slave node k over the master, g = u_s,k − Σ_l φ^m_l(x_k) u_m,l,
/// weighted by ∫_Γs φ_k, times `share`.
fn slave_pass(slave: &Trace, master: &Trace, share: f64) -> Vec<Row> {
    let measure = slave.measures();
    slave
        .x
        .iter()
        .enumerate()
        .filter(|&(_, &x)| master.holds(x))
        .map(|(k, &x)| Row {
            x,
            weight: share * measure[k],
            slave: vec![(k, 1.0)],
            master: master.shape_at(x),
        })
        .collect()
}

/// The node-to-segment coupling. One pass: [`slave_pass`] with its full weights. Two pass:
/// both passes at half weight — the second a row per master node l over the slave,
/// g = Σ_k φ_k(x_l) u_s,k − u_m,l, weighted by ½ ∫_Γm φ^m_l — so that each body carries
/// the load of the overlap once (Σ weight = ½(|Γs| + |Γm|) when each covers the other), and
/// where a master node coincides with a slave node the two rows, the same constraint, are
/// one row of the summed weight (matching meshes give one-pass NTS back). Rows ascend in x.
pub(crate) fn nts(slave: &Trace, master: &Trace, two_pass: bool) -> Result<Coupling, InterfaceError> {
    let (lo, hi) = overlap(slave, master)?;
    let share = if two_pass { 0.5 } else { 1.0 };
    let mut rows = slave_pass(slave, master, share);
    if two_pass {
        let tol = COINCIDENT * (hi - lo);
        let measure = master.measures();
        let first_pass = rows.len();
        for (l, &x) in master.x.iter().enumerate().filter(|&(_, &x)| slave.holds(x)) {
            let weight = share * measure[l];
            let near = rows[..first_pass].partition_point(|r| r.x < x - tol);
            match rows[..first_pass].get_mut(near).filter(|r| r.x <= x + tol) {
                Some(row) => row.weight += weight,
                None => rows.push(Row {
                    x,
                    weight,
                    slave: slave.shape_at(x),
                    master: vec![(l, 1.0)],
                }),
            }
        }
        rows.sort_by(|a, b| a.x.total_cmp(&b.x));
    }
    if rows.is_empty() {
        return Err(InterfaceError::NoConstraint {
            method: if two_pass { "nts2" } else { "nts" },
            what: if two_pass {
                "node of either side"
            } else {
                "slave node"
            },
            overlap: (lo, hi),
        });
    }
    let mut out = Coupling::default();
    for r in rows {
        out.x.push(r.x);
        out.weight.push(r.weight);
        out.slave.push(r.slave);
        out.master.push(r.master);
    }
    Ok(out)
}
