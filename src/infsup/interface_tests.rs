//! The inf-sup constant across the interface (docs/design.md §12) against what is known
//! without its code: small cases by hand, the one-body estimate on two identical bodies, and
//! the relation of mortar's and NTS's constants on matching meshes.

use faer::Mat;

use super::interface::{Space, Traces, estimate};
use super::interface_table::{InterfaceRow, interface_table};
use crate::contact::Rule;
use crate::contact::interface::{InterfaceMethod, Side, coupling};
use crate::mesh::Element;
use crate::scenario::Scenario;

const PATCH: &str = include_str!("../../scenarios/patch-two-blocks.toml");

/// β_h of `space` on the traces `s`, `m` (linear edges) with the compliances c_s I and c_m I.
fn beta(space: Space, s: &[f64], m: &[f64], c_s: f64, c_m: f64) -> f64 {
    let diagonal = |n: usize, c: f64| Mat::<f64>::from_fn(n, n, |i, j| if i == j { c } else { 0.0 });
    let (cs, cm) = (diagonal(s.len(), c_s), diagonal(m.len(), c_m));
    let traces = Traces {
        slave: Side { x: s, order: 1 },
        master: Side { x: m, order: 1 },
        slave_compliance: &cs,
        master_compliance: &cm,
    };
    let est = estimate(space, &traces).unwrap();
    assert!(est.kernel.is_none(), "{space:?}: {:?}", est.kernel);
    est.beta
}

fn close(a: f64, b: f64, what: &str) {
    assert!(
        (a - b).abs() <= 1e-13 * b.abs().max(1.0),
        "{what}: {a} against {b}"
    );
}

/// One linear edge [0, 1] on each side, C_s = 2I, C_m = I (J = C_s + C_m = 3 on the matching
/// nodes), by hand. Mortar: B = D[I, −I], D = [[1/3, 1/6], [1/6, 1/3]], so β² = 3 λ_min(D) =
/// 1/2; gauss2 integrates λ[v] (degree 2) exactly over the same linear functions: mortar's 1/2;
/// the dual: B = ½[I, −I], ∫ψψ = [[1, −½], [−½, 1]] (largest eigenvalue 3/2): (3/4)/(3/2) =
/// 1/2 (on one edge ψ spans φ's space). NTS and the trapezoid: B = ½[I, −I] against D (largest
/// eigenvalue 1/2): (3/4)/(1/2) = 3/2. gauss1: one row at ½, S = M = (½, ½), w = 1:
/// 2·½ + ½ = 3/2 against ∫1 = 1; its p̄ is p at both vertices, Sᵀ M₁ S = ∫1 = 1: 3/2.
#[test]
fn one_edge_by_hand() {
    let x = [0.0, 1.0];
    for (space, want) in [
        (Space::Mortar, 0.5),
        (Space::MortarDual, 0.5),
        (Space::Point(Rule::Gauss2), 0.5),
        (Space::Nts, 1.5),
        (Space::Point(Rule::Trapezoid), 1.5),
        (Space::Point(Rule::Gauss1), 1.5),
        (Space::Smoothed(Rule::Gauss1), 1.5),
    ] {
        close(beta(space, &x, &x, 2.0, 1.0), f64::sqrt(want), space.name());
    }
}

/// The slave's edge [0, 1] over the master's [0, ½], [½, 1], C_s = C_m = I, by hand. Mortar:
/// D as above, M = [[5, 6, 1], [1, 6, 5]]/24; D² + M Mᵀ and D share the eigenvectors (1, 1)
/// and (1, −1): (1/4 + 3/16)/(1/2) = 7/8 and (1/36 + 1/36)/(1/6) = 1/3, so β² = 1/3 (the dual's
/// too: one slave edge). NTS: rows at 0 and 1 over the master's ends, ¼(I + I) against D:
/// (1/2)/(1/2) = 1. gauss1: the row at ½ is the master's middle node: 1·(½ + 1) = 3/2.
#[test]
fn two_master_edges_by_hand() {
    let (s, m) = ([0.0, 1.0], [0.0, 0.5, 1.0]);
    for (space, want) in [
        (Space::Mortar, 1.0 / 3.0),
        (Space::MortarDual, 1.0 / 3.0),
        (Space::Nts, 1.0),
        (Space::Point(Rule::Gauss1), 1.5),
    ] {
        close(beta(space, &s, &m, 1.0, 1.0), f64::sqrt(want), space.name());
    }
}

/// More multipliers than the two traces have nodes: β_h = 0 and the reason. Matching linear
/// edges with gauss2: each row is (T_q, −T_q), so the 2E rows constrain only the E + 1 nodal
/// differences — found by the eigenvalues, a kernel of dimension E − 1.
#[test]
fn kernels_are_reported() {
    let (cs, cm) = (Mat::<f64>::identity(2, 2), Mat::<f64>::identity(2, 2));
    let x = [0.0, 1.0];
    let traces = Traces {
        slave: Side { x: &x, order: 1 },
        master: Side { x: &x, order: 1 },
        slave_compliance: &cs,
        master_compliance: &cm,
    };
    // Simpson on one linear edge: three points, two nodes a side: not a kernel by count, but
    // its three rows span only the two nodal differences.
    let est = estimate(Space::Point(Rule::Simpson), &traces).unwrap();
    assert_eq!((est.beta, est.multipliers), (0.0, 3));
    assert!(est.kernel.unwrap().contains("dimension 1"));
    let x: Vec<f64> = (0..=4).map(f64::from).collect();
    let c = Mat::<f64>::identity(5, 5);
    let traces = Traces {
        slave: Side { x: &x, order: 1 },
        master: Side { x: &x, order: 1 },
        slave_compliance: &c,
        master_compliance: &c,
    };
    let est = estimate(Space::Point(Rule::Gauss2), &traces).unwrap();
    assert_eq!((est.beta, est.multipliers), (0.0, 8));
    assert!(est.kernel.unwrap().contains("dimension 3"));
    // One slave edge over a master of eight: gauss2's two rows are independent.
    let m: Vec<f64> = (0..=8).map(|i| f64::from(i) / 8.0).collect();
    let cm = Mat::<f64>::identity(9, 9);
    let s = [0.0, 1.0];
    let traces = Traces {
        slave: Side { x: &s, order: 1 },
        master: Side { x: &m, order: 1 },
        slave_compliance: &cs,
        master_compliance: &cm,
    };
    assert!(
        estimate(Space::Point(Rule::Gauss2), &traces)
            .unwrap()
            .kernel
            .is_none()
    );
}

/// The patch scenario with `ratio` and `offset` (and `element`).
fn patch(ratio: &str, offset: &str, element: Element) -> Scenario {
    let text = PATCH
        .replace("ratio = [2, 3]", &format!("ratio = {ratio}"))
        .replace("offset = 0.0", &format!("offset = {offset}"));
    let mut s = Scenario::parse(&text, "patch-two-blocks.toml").unwrap();
    s.element = element;
    s
}

fn rows_of(rows: &[InterfaceRow], space: Space) -> Vec<&InterfaceRow> {
    rows.iter().filter(|r| r.space == space.name()).collect()
}

/// Two identical bodies (the upper's mirrored mesh is the lower's: the same lines, support
/// and half model) at 1:1: C_s = C_m = C, and a rule's rows are (T_q, −T_q), so
/// B A⁻¹ Bᵀ = W T (C + C) Tᵀ W, twice the one-body Schur complement of §5, against the same
/// Gram matrices: β_h across the interface is √2 times the one-body estimate of the lower
/// body (`crate::infsup::table`, its own coupling, compliance and mass code) for every rule,
/// NTS being the trapezoid's and p̄ β̄_h's; gauss2 has a kernel in both.
#[test]
fn identical_bodies_are_the_one_body_estimate_twice() {
    let text = PATCH
        .replace("ratio = [2, 3]", "ratio = [1, 1]")
        .replace("width = 3.0", "width = 2.0")
        .replace("nx = 6\nny = 4", "nx = 4\nny = 4")
        .replace("height = 0.5", "height = 1.0");
    let s = Scenario::parse(&text, "identical.toml").unwrap();
    let lower = s.mesh(1, Element::Q1);
    let upper = s.upper_mesh(1, Element::Q1).unwrap();
    assert_eq!(
        (lower.node_x.clone(), lower.node_y.clone()),
        (upper.node_x, upper.node_y)
    );
    let rules = [Rule::Gauss1, Rule::Trapezoid, Rule::Gauss2];
    let two = interface_table(&s, &Space::with_rules(&rules), &[0, 1]).unwrap();
    let pairs: Vec<(Element, Rule)> = rules.iter().map(|&r| (Element::Q1, r)).collect();
    let one = crate::infsup::table(&s, &pairs, &[0, 1]).unwrap();
    for (level, r1) in one.iter().map(|r| (r.level, r)) {
        let at = |space: Space| rows_of(&two, space)[level as usize].clone();
        let rule = Rule::ALL.into_iter().find(|r| r.name() == r1.rule).unwrap();
        let (point, smooth) = (at(Space::Point(rule)), at(Space::Smoothed(rule)));
        assert_eq!(point.h, r1.h);
        let sqrt2 = std::f64::consts::SQRT_2;
        if rule == Rule::Gauss2 {
            assert!(r1.kernel.is_some() && point.kernel.is_some(), "{point:?}");
        } else {
            close(point.beta, sqrt2 * r1.beta, point.space);
        }
        close(smooth.beta, sqrt2 * r1.beta_bar, smooth.space);
        if rule == Rule::Trapezoid {
            close(at(Space::Nts).beta, sqrt2 * r1.beta, "nts");
        }
    }
}

/// Matching meshes (1:1, no offset), Q1 and Q2. NTS's rows are then mortar-dual's (S = M =
/// e_j, w_j = ∫φ_j) and the trapezoid's (Q1) or Simpson's (Q2) — the same rows over the same
/// nodal space, so the same β_h (each computed by its own code). Standard mortar's rows are
/// D[I, −I] (D the slave's mass matrix) against NTS's W[I, −I] (W its lumped masses), over
/// the same space: with σ the eigenvalues of W^(−1/2) D W^(−1/2), in [σ₀, 1] (σ₀ = 1/3 on
/// linear edges, 2/5 on quadratic ones, element by element), β_mortar ≤ β_nts ≤ β_mortar/σ₀:
/// they are equal only where D = W, which a consistent mass never is.
#[test]
fn matching_meshes_relate_mortar_and_nts() {
    for (element, rule, sigma0) in [
        (Element::Q1, Rule::Trapezoid, 1.0 / 3.0),
        (Element::Q2, Rule::Simpson, 0.4),
    ] {
        let s = patch("[1, 1]", "0.0", element);
        let x = s.mesh(1, element).node_x;
        let side = Side {
            x: &x,
            order: element.order(),
        };
        let nts = coupling(InterfaceMethod::Nts, side, side).unwrap();
        let dual = coupling(InterfaceMethod::MortarDual, side, side).unwrap();
        assert_eq!(nts.x, dual.x);
        let n = x.len();
        let dense = |row: &[(usize, f64)]| {
            let mut v = vec![0.0; n];
            for &(i, c) in row {
                v[i] += c;
            }
            v
        };
        for k in 0..nts.x.len() {
            close(nts.weight[k], dual.weight[k], "weight");
            for (a, b) in [(&nts.slave[k], &dual.slave[k]), (&nts.master[k], &dual.master[k])] {
                let (a, b) = (dense(a), dense(b));
                assert!(
                    a.iter().zip(&b).all(|(a, b)| (a - b).abs() < 1e-12),
                    "{k}: {a:?} {b:?}"
                );
            }
            assert_eq!(nts.slave[k], vec![(k, 1.0)]);
        }
        let spaces = [Space::Mortar, Space::Nts, Space::Point(rule)];
        let rows = interface_table(&s, &spaces, &[0, 1]).unwrap();
        for level in 0..2 {
            let at = |space: Space| rows_of(&rows, space)[level].beta;
            let (mortar, nts) = (at(Space::Mortar), at(Space::Nts));
            close(nts, at(Space::Point(rule)), rule.name());
            assert!(
                mortar <= nts && nts <= mortar / sigma0,
                "{element:?} level {level}: mortar {mortar}, nts {nts}"
            );
            assert!(nts > 1.01 * mortar, "{nts} {mortar}");
        }
    }
}

/// gauss1's alternating pressure on the slave's edges is the one-body M1's near-kernel where
/// the meshes match (each master node between two slave edges' points gets ½ − ½): β_h ∝
/// h^1.5 at 1:1; at 2:3 the master's nodes sit elsewhere, its forces do not cancel and β_h ∝
/// √h (docs/design.md §12).
#[test]
fn gauss1_needs_the_meshes_not_to_match() {
    for (ratio, slope) in [("[1, 1]", 1.5), ("[2, 3]", 0.5)] {
        let s = patch(ratio, "0.0", Element::Q1);
        let rows = interface_table(&s, &[Space::Point(Rule::Gauss1)], &[0, 1, 2, 3]).unwrap();
        let last = rows[3].slope.unwrap();
        assert!((last - slope).abs() < 0.05, "{ratio}: {rows:?}");
    }
}
