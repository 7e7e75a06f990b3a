//! The couplings against each other and against hand computations (docs/design.md §12): the
//! rows' coefficients sum to 1, and the contact patch test at the coupling level — a uniform
//! multiplier's nodal forces against the consistent load of a uniform pressure.

use super::*;

/// A trace on [0, 2] of `edges` edges of order `order`, the interior vertices shifted by
/// `offset` edge lengths (ends aligned), mid nodes at the middles.
fn trace_nodes(edges: usize, order: usize, offset: f64) -> Vec<f64> {
    let h = 2.0 / edges as f64;
    let v: Vec<f64> = (0..=edges)
        .map(|i| match i {
            0 => 0.0,
            i if i == edges => 2.0,
            i => (i as f64 + offset) * h,
        })
        .collect();
    let mut x = vec![v[0]];
    for e in 0..edges {
        if order == 2 {
            x.push(0.5 * (v[e] + v[e + 1]));
        }
        x.push(v[e + 1]);
    }
    x
}

/// ∫ φ_l over the whole trace, by hand: h/2 per linear edge's end; h/6 per quadratic edge's
/// end and 2h/3 at its middle.
fn consistent_load(x: &[f64], order: usize) -> Vec<f64> {
    let mut f = vec![0.0; x.len()];
    for e in 0..(x.len() - 1) / order {
        let (a, b) = (x[order * e], x[order * e + order]);
        let h = b - a;
        if order == 1 {
            f[e] += h / 2.0;
            f[e + 1] += h / 2.0;
        } else {
            f[2 * e] += h / 6.0;
            f[2 * e + 1] += 2.0 * h / 3.0;
            f[2 * e + 2] += h / 6.0;
        }
    }
    f
}

/// The nodal forces of a uniform multiplier λ = 1: Σ_k weight_k · coefficient_k,i on each
/// side.
fn forces(c: &Coupling, n_slave: usize, n_master: usize) -> (Vec<f64>, Vec<f64>) {
    let (mut fs, mut fm) = (vec![0.0; n_slave], vec![0.0; n_master]);
    for k in 0..c.weight.len() {
        for &(i, v) in &c.slave[k] {
            fs[i] += c.weight[k] * v;
        }
        for &(l, v) in &c.master[k] {
            fm[l] += c.weight[k] * v;
        }
    }
    (fs, fm)
}

/// max_i |f_i − g_i| / max_i |g_i|.
fn relative_error(f: &[f64], g: &[f64]) -> f64 {
    let scale = g.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    f.iter().zip(g).fold(0.0f64, |m, (a, b)| m.max((a - b).abs())) / scale
}

/// The interface pairs of the patch test: (name, slave edges, master edges, master offset).
const PAIRS: [(&str, usize, usize, f64); 5] = [
    ("1:1 offset", 4, 4, 0.3),
    ("2:3", 4, 6, 0.0),
    ("3:2", 6, 4, 0.0),
    ("5:7", 5, 7, 0.0),
    ("7:5", 7, 5, 0.0),
];

/// The patch test's relative errors of the slave's and the master's forces for one method,
/// pair and order.
fn patch_errors(method: InterfaceMethod, ns: usize, nm: usize, offset: f64, order: usize) -> (f64, f64) {
    let (s, m) = (trace_nodes(ns, order, 0.0), trace_nodes(nm, order, offset));
    let c = coupling(method, Side { x: &s, order }, Side { x: &m, order }).unwrap();
    let (fs, fm) = forces(&c, s.len(), m.len());
    (
        relative_error(&fs, &consistent_load(&s, order)),
        relative_error(&fm, &consistent_load(&m, order)),
    )
}

#[test]
fn mortar_passes_the_patch_test() {
    for method in [InterfaceMethod::Mortar, InterfaceMethod::MortarDual] {
        for order in [1, 2] {
            for (name, ns, nm, offset) in PAIRS {
                let (es, em) = patch_errors(method, ns, nm, offset, order);
                assert!(
                    es <= 1e-12 && em <= 1e-12,
                    "{} order {order} {name}: slave {es:e}, master {em:e}",
                    method.name()
                );
            }
        }
    }
}

#[test]
fn one_pass_nts_fails_the_patch_test_on_non_matching_sides() {
    // The slave's forces are its consistent load (a row per node, weight ∫φ_k); the master's
    // are the slave's measures spread by the master's shape functions at the slave's nodes.
    for order in [1, 2] {
        for (name, ns, nm, offset) in PAIRS.into_iter().filter(|p| p.0 != "1:1 offset") {
            let (es, em) = patch_errors(InterfaceMethod::Nts, ns, nm, offset, order);
            assert!(es <= 1e-12, "order {order} {name}: slave {es:e}");
            assert!(em > 1e-3, "order {order} {name}: master {em:e}");
        }
    }
}

#[test]
fn the_failures_repeat_under_refinement() {
    // At a fixed ratio the meshes' pattern repeats, and once a whole period lies inside the
    // interface (twice the edges) so do the nodal forces' relative errors: with twice and
    // four times the edges they are the same; a method's failure does not fall with h.
    for method in InterfaceMethod::ALL {
        for order in [1, 2] {
            for (name, ns, nm, offset) in PAIRS {
                let (cs, cm) = patch_errors(method, 2 * ns, 2 * nm, offset, order);
                let (fs, fm) = patch_errors(method, 4 * ns, 4 * nm, offset, order);
                for (c, f) in [(cs, fs), (cm, fm)] {
                    assert!(
                        (c - f).abs() <= 1e-9 * c.max(f) + 1e-14,
                        "{} order {order} {name}: {c:e} then {f:e}",
                        method.name()
                    );
                }
            }
        }
    }
}

#[test]
fn patch_test_report() {
    // Every method, order and pair: the errors printed (docs/design.md §12 quotes them).
    for method in InterfaceMethod::ALL {
        for order in [1, 2] {
            for times in [1, 2] {
                let errs: Vec<String> = PAIRS
                    .iter()
                    .map(|&(name, ns, nm, offset)| {
                        let (es, em) = patch_errors(method, times * ns, times * nm, offset, order);
                        assert!(es.is_finite() && em.is_finite());
                        format!("{name}: {es:.1e}/{em:.1e}")
                    })
                    .collect();
                println!("{:14} order {order} ×{times}: {}", method.name(), errs.join("  "));
            }
        }
    }
}

#[test]
fn every_row_sums_to_one() {
    // Partial overlaps too: slave [0, 2] against a master on [0.35, 3.05].
    for method in InterfaceMethod::ALL {
        for order in [1, 2] {
            let s = trace_nodes(5, order, 0.0);
            let far_edges = 9 * order;
            let far: Vec<f64> = (0..=far_edges)
                .map(|i| 0.35 + 2.7 * i as f64 / far_edges as f64)
                .collect();
            let pairs = [trace_nodes(7, order, 0.2), far];
            for m in &pairs {
                let c = coupling(method, Side { x: &s, order }, Side { x: m, order }).unwrap();
                assert!(!c.weight.is_empty());
                for k in 0..c.weight.len() {
                    let ss: f64 = c.slave[k].iter().map(|(_, v)| v).sum();
                    let sm: f64 = c.master[k].iter().map(|(_, v)| v).sum();
                    assert!(
                        (ss - 1.0).abs() < 1e-12 && (sm - 1.0).abs() < 1e-12,
                        "{} order {order} row {k}: {ss} {sm}",
                        method.name()
                    );
                    assert!(c.weight[k] > 0.0);
                }
                assert!(c.x.windows(2).all(|w| w[0] <= w[1]), "{}", method.name());
            }
        }
    }
}

#[test]
fn nts_by_hand() {
    // Matching sides: identity rows weighted by the tributary lengths.
    let x = [0.0, 0.5, 1.5, 1.75];
    let side = Side { x: &x, order: 1 };
    for method in [InterfaceMethod::Nts, InterfaceMethod::Nts2] {
        let c = coupling(method, side, side).unwrap();
        assert_eq!(c.x, x.to_vec(), "{}", method.name());
        assert_eq!(c.weight, vec![0.25, 0.75, 0.625, 0.125]);
        for k in 0..4 {
            assert_eq!(c.slave[k], vec![(k, 1.0)]);
            assert_eq!(c.master[k], vec![(k, 1.0)]);
        }
    }
    // One slave edge [0, 1] over two master edges: the slave's ends onto the master's ends.
    let (s, m) = ([0.0, 1.0], [0.0, 0.5, 1.0]);
    let (s, m) = (Side { x: &s, order: 1 }, Side { x: &m, order: 1 });
    let c = coupling(InterfaceMethod::Nts, s, m).unwrap();
    assert_eq!(c.weight, vec![0.5, 0.5]);
    assert_eq!(c.master, vec![vec![(0, 1.0)], vec![(2, 1.0)]]);
    // Two pass: the ends coincide (one row each, weight ½(½ + ¼)), the master's middle node
    // onto the slave's edge at half weight.
    let c = coupling(InterfaceMethod::Nts2, s, m).unwrap();
    assert_eq!(c.x, vec![0.0, 0.5, 1.0]);
    assert_eq!(c.weight, vec![0.375, 0.25, 0.375]);
    assert_eq!(c.slave[1], vec![(0, 0.5), (1, 0.5)]);
    assert_eq!(c.master[1], vec![(1, 1.0)]);
    // A quadratic slave node at 0.25 over a quadratic master edge [0, 1]: φ^m = (3/8, 3/4, −1/8).
    let (s, m) = ([0.0, 0.25, 0.5], [0.0, 0.5, 1.0]);
    let c = coupling(
        InterfaceMethod::Nts,
        Side { x: &s, order: 2 },
        Side { x: &m, order: 2 },
    )
    .unwrap();
    assert_eq!(c.weight, vec![0.5 / 6.0, 0.5 * 2.0 / 3.0, 0.5 / 6.0]);
    assert_eq!(c.master[1], vec![(0, 0.375), (1, 0.75), (2, -0.125)]);
}

#[test]
fn ends_an_ulp_apart_are_the_same_end() {
    // The same width 2 meshed by 3 and by 2 edges, the master ending an ulp short (as i·W/n
    // may): every slave node and trapezoid point still has its row, the forces stay
    // symmetric, and the master's shape functions are taken at its end, not extrapolated.
    let s = [0.0, 2.0 / 3.0, 4.0 / 3.0, 2.0];
    let m = [0.0, 1.0, 2.0 - f64::EPSILON];
    let (ss, sm) = (Side { x: &s, order: 1 }, Side { x: &m, order: 1 });
    for method in [
        InterfaceMethod::Nts,
        InterfaceMethod::Nts2,
        InterfaceMethod::Rip(Rule::Trapezoid),
    ] {
        let c = coupling(method, ss, sm).unwrap();
        assert_eq!(c.x.first(), Some(&0.0), "{}", method.name());
        assert_eq!(c.x.last(), Some(&2.0), "{}", method.name());
        let (fs, fm) = forces(&c, s.len(), m.len());
        assert!((fs[3] - fs[0]).abs() < 1e-12, "{}: {fs:?}", method.name());
        assert!((fm[2] - fm[0]).abs() < 1e-12, "{}: {fm:?}", method.name());
        assert!(c.master.iter().flatten().all(|&(_, v)| (0.0..=1.0).contains(&v)));
    }
}

#[test]
fn rip_rows_are_the_rule_points_and_pbar_follows_17() {
    // Gauss1 on slave edges [0, 1], [1, 3] over a master [0, 2]: the first point (x = 0.5)
    // alone lies over the master — the second (x = 2) too, at the master's end.
    let (s, m) = ([0.0, 1.0, 3.0], [0.0, 2.0]);
    let c = coupling(
        InterfaceMethod::Rip(Rule::Gauss1),
        Side { x: &s, order: 1 },
        Side { x: &m, order: 1 },
    )
    .unwrap();
    assert_eq!(c.x, vec![0.5, 2.0]);
    assert_eq!(c.weight, vec![1.0, 2.0]);
    assert_eq!(c.slave[0], vec![(0, 0.5), (1, 0.5)]);
    assert_eq!(c.master[1], vec![(1, 1.0)]);
    // (17): p̄ = (q₁, (h₁q₁ + h₂q₂)/(h₁ + h₂), q₂).
    let pbar = smoothed_pressure(Rule::Gauss1, Side { x: &s, order: 1 }, &c, &[3.0, 6.0]).unwrap();
    assert_eq!(pbar, vec![3.0, (3.0 + 2.0 * 6.0) / 3.0, 6.0]);
    // Off the master: the trapezoid's point at x = 3 has no row and counts as p = 0.
    let c = coupling(
        InterfaceMethod::Rip(Rule::Trapezoid),
        Side { x: &s, order: 1 },
        Side { x: &m, order: 1 },
    )
    .unwrap();
    assert_eq!(c.x, vec![0.0, 1.0]);
    let pbar = smoothed_pressure(Rule::Trapezoid, Side { x: &s, order: 1 }, &c, &[2.0, 4.0]).unwrap();
    assert_eq!(pbar, vec![2.0, 4.0, 0.0]);
}

#[test]
fn bad_sides_are_named_with_the_allowed_range() {
    let ok = [0.0, 1.0];
    let good = Side { x: &ok, order: 1 };
    let cases: [(&[f64], usize, &str); 6] = [
        (&[0.0, 1.0], 3, "order 3; allowed: 1 (linear edges) or 2"),
        (&[0.0], 1, "has 1 node(s); allowed at order 1"),
        (&[0.0, 1.0], 2, "has 2 node(s); allowed at order 2"),
        (
            &[0.0, f64::NAN],
            1,
            "node 1 is at x = NaN; allowed: a finite number",
        ),
        (&[0.0, 1.0, 1.0], 1, "node 2 at x = 1 is not right of node 1"),
        (
            &[0.0, 0.3, 1.0],
            2,
            "mid-edge node 1 is at x = 0.3, not at its edge's middle 0.5",
        ),
    ];
    for (x, order, want) in cases {
        let err = coupling(InterfaceMethod::Mortar, good, Side { x, order }).unwrap_err();
        let msg = err.to_string();
        assert!(msg.starts_with("the master's") && msg.contains(want), "{msg}");
    }
    let far = [2.0, 3.0];
    let err = coupling(InterfaceMethod::Nts, good, Side { x: &far, order: 1 }).unwrap_err();
    assert!(err.to_string().contains("do not overlap"), "{err}");
    // A master inside one slave edge: no slave node over it.
    let inner = [0.2, 0.8];
    let err = coupling(InterfaceMethod::Nts, good, Side { x: &inner, order: 1 }).unwrap_err();
    assert!(err.to_string().contains("no slave node lies over it"), "{err}");
}
