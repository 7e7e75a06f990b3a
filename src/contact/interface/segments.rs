//! The exact segmentation of the overlap (docs/design.md §12): the two sides' edge ends merged
//! into the pieces on which both traces are polynomials. The interface is flat, so the
//! projection along the slave's normal is the identity in x.

use super::InterfaceError;
use super::trace::{Trace, overlap};

/// A piece [a, b] of the overlap inside one slave edge and one master edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Segment {
    /// Its left end.
    pub a: f64,
    /// Its right end.
    pub b: f64,
    /// The slave's edge holding it.
    pub slave_edge: usize,
    /// The master's edge holding it.
    pub master_edge: usize,
}

/// The segments of the overlap, left to right, by one merge of the two sorted lists of edge
/// ends: O(E_s + E_m) after one binary search per side, and at most E_s + E_m − 1 of them
/// (each segment ends at an edge end of one side, and each overlap end is one of them).
pub(crate) fn segments(slave: &Trace, master: &Trace) -> Result<Vec<Segment>, InterfaceError> {
    let (lo, hi) = overlap(slave, master)?;
    let (mut es, mut em) = (slave.edge_at(lo), master.edge_at(lo));
    let mut out = Vec::with_capacity(slave.n_edges() + master.n_edges());
    let mut a = lo;
    // Invariant: each side's edge holds a, which is left of its right end (x₍e₎ ≤ a < x₍e+1₎).
    while a < hi {
        let (s_end, m_end) = (slave.edge(es).1, master.edge(em).1);
        let b = s_end.min(m_end).min(hi);
        out.push(Segment {
            a,
            b,
            slave_edge: es,
            master_edge: em,
        });
        if s_end == b && es + 1 < slave.n_edges() {
            es += 1;
        }
        if m_end == b && em + 1 < master.n_edges() {
            em += 1;
        }
        a = b;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::super::Side;
    use super::*;

    fn trace(x: &[f64], order: usize) -> Trace<'_> {
        Trace::new(Side { x, order }, "slave").unwrap()
    }

    #[test]
    fn shifted_sides_by_hand() {
        // Slave edges [0, 1], [1, 2]; master [0.5, 1.5], [1.5, 2.5]: overlap [0.5, 2].
        let (s, m) = ([0.0, 1.0, 2.0], [0.5, 1.5, 2.5]);
        let segs = segments(&trace(&s, 1), &trace(&m, 1)).unwrap();
        let got: Vec<(f64, f64, usize, usize)> = segs
            .iter()
            .map(|g| (g.a, g.b, g.slave_edge, g.master_edge))
            .collect();
        assert_eq!(got, vec![(0.5, 1.0, 0, 0), (1.0, 1.5, 1, 0), (1.5, 2.0, 1, 1)]);
    }

    #[test]
    fn count_bounded_and_lengths_sum_to_the_overlap() {
        // Quadratic slave of 5 edges on [0, 2], linear master of 7 on [0.3, 2.9], one vertex
        // shared at 0.8 and the master's last interior vertex past the slave's end.
        let s: Vec<f64> = (0..=10).map(|i| 0.2 * i as f64).collect();
        let mut m: Vec<f64> = (0..=7).map(|i| 0.3 + 2.6 * i as f64 / 7.0).collect();
        m[1] = s[4];
        let (ts, tm) = (trace(&s, 2), trace(&m, 1));
        let segs = segments(&ts, &tm).unwrap();
        assert!(segs.len() <= ts.n_edges() + tm.n_edges(), "{}", segs.len());
        let total: f64 = segs.iter().map(|g| g.b - g.a).sum();
        assert!((total - (2.0 - 0.3)).abs() < 1e-14, "{total}");
        for g in &segs {
            assert!(g.a < g.b, "{g:?}");
            let (sa, sb) = ts.edge(g.slave_edge);
            let (ma, mb) = tm.edge(g.master_edge);
            assert!(sa <= g.a && g.b <= sb && ma <= g.a && g.b <= mb, "{g:?}");
        }
        assert!(segs.windows(2).all(|w| w[0].b == w[1].a));
        // 0.8 is both sides' vertex: one breakpoint, not two.
        let at_08 = segs.iter().filter(|g| g.b == s[4]).count();
        assert_eq!(at_08, 1);
    }

    #[test]
    fn disjoint_sides_are_an_error() {
        let (s, m) = ([0.0, 1.0], [1.0, 2.0]);
        let err = segments(&trace(&s, 1), &trace(&m, 1)).unwrap_err();
        assert!(matches!(err, InterfaceError::NoOverlap { .. }), "{err}");
    }
}
