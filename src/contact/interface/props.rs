//! The couplings on random non-matching sides (docs/design.md §12): mortar's integrals against
//! a brute-force pairing of every slave edge with every master edge (no segmentation), the dual
//! basis's diagonal D and consistent forces, and every method's rows, on sides laid on a grid
//! of 1/64 (coincident vertices often, no slivers thinner than 1/64).

use proptest::prelude::*;

use super::dual::DualBasis;
use super::trace::Trace;
use super::*;
use crate::fem::quadrature::gauss_legendre;

/// A side: its order, its first vertex and its edges' lengths, all in 64ths.
fn side() -> impl Strategy<Value = (usize, i32, Vec<u32>)> {
    (1usize..=2, -64i32..=64, prop::collection::vec(1u32..=40, 1..=10))
}

/// The nodes of a side (mid nodes at the middles).
fn nodes((order, start, lengths): &(usize, i32, Vec<u32>)) -> Vec<f64> {
    let mut x = vec![*start as f64 / 64.0];
    let mut v = *start as f64;
    for &h in lengths {
        if *order == 2 {
            x.push((v + h as f64 / 2.0) / 64.0);
        }
        v += h as f64;
        x.push(v / 64.0);
    }
    x
}

/// D_jk = ∫ φ_j φ_k and M_jl = ∫ μ_j φ^m_l over the overlap, dense, μ = φ or (`dual`) ψ
/// built on each slave edge's covered part, by pairing every slave edge with every master
/// edge and integrating over their intersection.
fn brute_force(slave: &Trace, master: &Trace, dual: bool) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let (lo, hi) = trace::overlap(slave, master).unwrap();
    let (ns, nm) = (slave.x.len(), master.x.len());
    let (mut d, mut m) = (vec![vec![0.0; ns]; ns], vec![vec![0.0; nm]; ns]);
    for es in 0..slave.n_edges() {
        for em in 0..master.n_edges() {
            let (a, b) = (
                slave.edge(es).0.max(master.edge(em).0),
                slave.edge(es).1.min(master.edge(em).1),
            );
            if a >= b {
                continue;
            }
            for (xi, w) in gauss_legendre(4) {
                let x = 0.5 * (a + b) + 0.5 * (b - a) * xi;
                let w = 0.5 * (b - a) * w;
                let (s0, phi) = slave.basis(es, x);
                let (m0, phi_m) = master.basis(em, x);
                let (ea, eb) = slave.edge(es);
                let mu = if dual {
                    DualBasis::on(slave, es, ea.max(lo), eb.min(hi)).at(x)
                } else {
                    phi
                };
                for i in 0..=slave.order {
                    for k in 0..=slave.order {
                        d[s0 + i][s0 + k] += w * phi[i] * phi[k];
                    }
                    for l in 0..=master.order {
                        m[s0 + i][m0 + l] += w * mu[i] * phi_m[l];
                    }
                }
            }
        }
    }
    (d, m)
}

/// The smallest covered part of a slave edge, over its length (1 when the overlap ends at
/// slave vertices).
fn least_covered(slave: &Trace, (lo, hi): (f64, f64)) -> f64 {
    (0..slave.n_edges())
        .map(|e| slave.edge(e))
        .filter(|&(a, b)| a < hi && b > lo)
        .map(|(a, b)| (b.min(hi) - a.max(lo)) / (b - a))
        .fold(1.0, f64::min)
}

/// How far from 1 a row may sum: the dual basis on a part r of an edge solves with
/// T (cond ~ r^−p) and divides by D̂_j ~ r^p, so its rows lose r^−2p of the machine precision
/// (docs/design.md §12); every other method's rows are sums of positive weights.
fn row_tolerance(method: InterfaceMethod, order: usize, r: f64) -> f64 {
    match method {
        InterfaceMethod::MortarDual => 1e-13_f64.max(64.0 * f64::EPSILON / r.powi(2 * order as i32)),
        _ => 1e-13,
    }
}

/// A row of `method` summing to 1 within [`row_tolerance`].
fn rows_sum_to_one(s: &(usize, i32, Vec<u32>), m: &(usize, i32, Vec<u32>)) -> Result<(), TestCaseError> {
    let (xs, xm) = (nodes(s), nodes(m));
    let (ss, sm) = (Side { x: &xs, order: s.0 }, Side { x: &xm, order: m.0 });
    let (ts, tm) = (
        Trace::new(ss, "slave").unwrap(),
        Trace::new(sm, "master").unwrap(),
    );
    let r = trace::overlap(&ts, &tm).map_or(1.0, |o| least_covered(&ts, o));
    for method in InterfaceMethod::ALL {
        match coupling(method, ss, sm) {
            Ok(c) => {
                prop_assert!(!c.x.is_empty());
                prop_assert!(c.x.windows(2).all(|w| w[0] <= w[1]));
                let tol = row_tolerance(method, s.0, r);
                for k in 0..c.x.len() {
                    let a: f64 = c.slave[k].iter().map(|(_, v)| v).sum();
                    let b: f64 = c.master[k].iter().map(|(_, v)| v).sum();
                    prop_assert!(
                        (a - 1.0).abs() <= tol && (b - 1.0).abs() <= tol,
                        "{} row {}: {} {} (tolerance {:e}, least covered part {})",
                        method.name(),
                        k,
                        a - 1.0,
                        b - 1.0,
                        tol,
                        r
                    );
                    prop_assert!(c.weight[k] > 0.0 && c.weight[k].is_finite());
                }
            }
            Err(e) => prop_assert!(
                matches!(
                    e,
                    InterfaceError::NoOverlap { .. } | InterfaceError::NoConstraint { .. }
                ),
                "{}: {}",
                method.name(),
                e
            ),
        }
    }
    Ok(())
}

/// A quadratic slave whose last edge the master covers by 1/37: its mortar-dual row summed
/// to 1 − 1.0e−10, outside the 1e−10 asked of every row before the tolerance followed r^−2p.
#[test]
fn a_sliver_of_a_quadratic_edge_keeps_its_rows_within_the_dual_basis_precision() {
    let s = (2, 50, vec![36, 25, 3, 32, 25, 37]);
    let m = (1, -61, vec![13, 26, 28, 34, 34, 19, 27, 13, 39]);
    rows_sum_to_one(&s, &m).unwrap();
}

fn dense(row: &[(usize, f64)], n: usize) -> Vec<f64> {
    let mut v = vec![0.0; n];
    for &(k, c) in row {
        v[k] += c;
    }
    v
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn mortar_integrals_are_the_brute_force_ones(s in side(), m in side()) {
        let (xs, xm) = (nodes(&s), nodes(&m));
        let (ss, sm) = (Side { x: &xs, order: s.0 }, Side { x: &xm, order: m.0 });
        let (ts, tm) = (Trace::new(ss, "slave").unwrap(), Trace::new(sm, "master").unwrap());
        prop_assume!(trace::overlap(&ts, &tm).is_ok());
        let (d, mm) = brute_force(&ts, &tm, false);
        let c = coupling(InterfaceMethod::Mortar, ss, sm).unwrap();
        let measure = ts.measures();
        let kept: Vec<usize> = (0..xs.len())
            .filter(|&j| d[j].iter().sum::<f64>() > 1e-9 * measure[j])
            .collect();
        let rows: Vec<usize> = c.x.iter().map(|x| xs.iter().position(|v| v == x).unwrap()).collect();
        prop_assert_eq!(&rows, &kept);
        for (k, &j) in rows.iter().enumerate() {
            let got_d: Vec<f64> = dense(&c.slave[k], xs.len()).iter().map(|v| v * c.weight[k]).collect();
            let got_m: Vec<f64> = dense(&c.master[k], xm.len()).iter().map(|v| v * c.weight[k]).collect();
            for (a, b) in got_d.iter().zip(&d[j]).chain(got_m.iter().zip(&mm[j])) {
                prop_assert!((a - b).abs() < 1e-13, "row {} (node {}): {} vs {}", k, j, a, b);
            }
        }
    }

    #[test]
    fn the_dual_d_is_diagonal_and_its_forces_consistent(s in side(), m in side()) {
        let (xs, xm) = (nodes(&s), nodes(&m));
        let (ss, sm) = (Side { x: &xs, order: s.0 }, Side { x: &xm, order: m.0 });
        let (ts, tm) = (Trace::new(ss, "slave").unwrap(), Trace::new(sm, "master").unwrap());
        let (lo, hi) = match trace::overlap(&ts, &tm) {
            Ok(o) => o,
            Err(_) => return Ok(()),
        };
        let (d, mm) = brute_force(&ts, &tm, false);
        let (_, mdual) = brute_force(&ts, &tm, true);
        let c = coupling(InterfaceMethod::MortarDual, ss, sm).unwrap();
        let mut force = vec![0.0; xm.len()];
        for k in 0..c.x.len() {
            let j = xs.iter().position(|v| *v == c.x[k]).unwrap();
            prop_assert_eq!(&c.slave[k], &vec![(j, 1.0)]);
            // D̂_j = ∫_overlap ψ_j = ∫_overlap φ_j (biorthogonality on the covered part).
            let dhat: f64 = d[j].iter().sum();
            prop_assert!((c.weight[k] - dhat).abs() < 1e-13, "{} vs {}", c.weight[k], dhat);
            let got: Vec<f64> = dense(&c.master[k], xm.len()).iter().map(|v| v * c.weight[k]).collect();
            for (a, b) in got.iter().zip(&mdual[j]) {
                prop_assert!((a - b).abs() < 1e-11, "row {} (node {}): {} vs {}", k, j, a, b);
            }
            for (f, g) in force.iter_mut().zip(&got) {
                *f += g;
            }
        }
        // Σ_j w_j M_jl = ∫_overlap φ^m_l when no row is left out: always on linear slave
        // edges (∫φ_j ≥ 0), on quadratic ones when the overlap ends at slave vertices.
        let vertex = |x: f64| xs.iter().step_by(ts.order).any(|&v| v == x);
        let whole = ts.order == 1 || (vertex(lo) && vertex(hi));
        if whole {
            for (l, f) in force.iter().enumerate() {
                let want: f64 = (0..xs.len()).map(|j| mm[j][l]).sum();
                prop_assert!((f - want).abs() < 1e-12, "master node {}: {} vs {}", l, f, want);
            }
        }
    }

    #[test]
    fn every_method_gives_rows_that_sum_to_one(s in side(), m in side()) {
        rows_sum_to_one(&s, &m)?;
    }
}
