//! The inf-sup estimate of docs/design.md §5 against a brute-force dense computation, a case done by
//! hand, and the paper's claims about M1–M4.

use crate::common::{paper_with, rel};
use nalgebra::{DMatrix, SymmetricEigen};
use riplab::contact::{ContactPoints, Rule};
use riplab::discretization::Discretization;
use riplab::fem::{Form, Integration, assemble};
use riplab::infsup::{InfSupRow, inf_sup, table};
use riplab::material::{Material, Plane};
use riplab::mesh::{Element, Mesh};
use riplab::scheme::Scheme;

/// λ_min(S, N) for N symmetric positive definite, by nalgebra's Cholesky and symmetric eigen.
fn dense_min_eig(s: &DMatrix<f64>, n: &DMatrix<f64>) -> f64 {
    let l = n.clone().cholesky().expect("N is SPD").l();
    let li = l.clone().try_inverse().unwrap();
    let reduced = &li * s * li.transpose();
    let sym = (&reduced + reduced.transpose()) * 0.5;
    SymmetricEigen::new(sym).eigenvalues.min()
}

/// The exact L² Gram matrix of Q_h from each edge's Vandermonde matrix and ∫₀¹ sⁱ⁺ʲ = 1/(i+j+1)
/// (independent of the library's Lagrange-product and Gauss evaluation).
fn brute_mass(cp: &ContactPoints) -> DMatrix<f64> {
    let n = cp.len();
    let mut m = DMatrix::<f64>::zeros(n, n);
    for (e, pts) in cp.edge_points.iter().enumerate() {
        let h = cp.vertex_x[e + 1] - cp.vertex_x[e];
        let s: Vec<f64> = pts
            .iter()
            .map(|&k| (cp.points[k].x - cp.vertex_x[e]) / h)
            .collect();
        let d = s.len();
        let vander = DMatrix::from_fn(d, d, |i, j| s[i].powi(j as i32));
        let coef = vander.try_inverse().unwrap(); // column a: monomial coefficients of L_a
        for a in 0..d {
            for b in 0..d {
                let mut v = 0.0;
                for i in 0..d {
                    for j in 0..d {
                        v += coef[(i, a)] * coef[(j, b)] / (i + j + 1) as f64;
                    }
                }
                m[(pts[a], pts[b])] += h * v;
            }
        }
    }
    m
}

/// β_h² and (for gauss1 and trapezoid) β̄_h² from dense A on every free dof.
fn brute_force(disc: &Discretization, rule: Rule) -> (f64, Option<f64>) {
    let a = assemble(disc.mesh(), disc.dofs(), Form::H1);
    let n = a.n;
    let mut dense = DMatrix::<f64>::zeros(n, n);
    for c in 0..n {
        for k in a.col_ptr[c]..a.col_ptr[c + 1] {
            dense[(a.row_idx[k], c)] = a.values[k];
            dense[(c, a.row_idx[k])] = a.values[k];
        }
    }
    let cp = ContactPoints::on(disc, rule);
    // B[k, j] = I(φ_k, (ψ_j)_n) = w_k (ψ_j)_n(x_k).
    let mut b = DMatrix::<f64>::zeros(cp.len(), n);
    for (k, q) in cp.points.iter().enumerate() {
        for (&node, &t) in q.nodes.iter().zip(&q.trace) {
            b[(k, disc.contact_dofs()[node])] += q.weight * t;
        }
    }
    let s = &b * dense.try_inverse().unwrap() * b.transpose();
    let beta2 = dense_min_eig(&s, &brute_mass(&cp));
    let x = &cp.vertex_x;
    let ne = x.len() - 1;
    let smoothing = match rule {
        // (17) written out.
        Rule::Gauss1 => Some(DMatrix::from_fn(ne + 1, ne, |i, e| {
            let h = |k: usize| x[k + 1] - x[k];
            match i {
                0 => f64::from(e == 0),
                i if i == ne => f64::from(e == ne - 1),
                i if e == i - 1 => h(i - 1) / (h(i - 1) + h(i)),
                i if e == i => h(i) / (h(i - 1) + h(i)),
                _ => 0.0,
            }
        })),
        Rule::Trapezoid => Some(DMatrix::identity(ne + 1, ne + 1)),
        _ => None,
    };
    let beta_bar2 = smoothing.map(|sm| {
        let mut m1 = DMatrix::<f64>::zeros(ne + 1, ne + 1);
        for e in 0..ne {
            let h = x[e + 1] - x[e];
            m1[(e, e)] += h / 3.0;
            m1[(e + 1, e + 1)] += h / 3.0;
            m1[(e, e + 1)] += h / 6.0;
            m1[(e + 1, e)] += h / 6.0;
        }
        dense_min_eig(&s, &(sm.transpose() * m1 * &sm))
    });
    (beta2, beta_bar2)
}

#[test]
fn matches_brute_force_dense_computation() {
    let scenario = paper_with(&[]);
    for (element, rule, level) in [
        (Element::Q1, Rule::Gauss1, 0),
        (Element::Q1, Rule::Gauss1, 1),
        (Element::Q1, Rule::Trapezoid, 1),
        (Element::Q2, Rule::Simpson, 0),
        (Element::Q2, Rule::Gauss2, 0),
        (Element::P1, Rule::Gauss1, 1),
        (Element::P1, Rule::Trapezoid, 0),
    ] {
        let disc = scenario.discretize(level, element).unwrap();
        let est = inf_sup(&disc, rule).unwrap();
        let (beta2, beta_bar2) = brute_force(&disc, rule);
        assert!(
            rel(est.beta, beta2.sqrt(), 1e-300) < 1e-10,
            "{element:?}+{rule:?} L{level}: β {} vs {}",
            est.beta,
            beta2.sqrt()
        );
        if let Some(bb) = beta_bar2 {
            assert!(
                rel(est.beta_bar, bb.sqrt(), 1e-300) < 1e-10,
                "{element:?}+{rule:?}: β̄ {} vs {}",
                est.beta_bar,
                bb.sqrt()
            );
        }
    }
}

/// One Q1 cell [0, h]² clamped at the bottom: the H¹ Gram of the two top u_y dofs is
/// [[α, β], [β, α]], α = 2/3 + h²/9, β = −1/6 + h²/18 (u_x decouples). For one-point Gauss,
/// B = h (½, ½) and M = h, so β_h² = h²/(2(α + β))/h = h/(1 + h²/3). The trapezoid rule gives
/// the same on the symmetric mode (the antisymmetric one gives 9h/(5 + h²/3), larger), and
/// the smoothed gauss1 pressure is constant, so β̄_h² is the same too.
#[test]
fn single_cell_by_hand() {
    let material = Material {
        young: 1.0,
        poisson: 0.3,
        plane: Plane::Strain,
    };
    for h in [1.0, 0.5, 0.2] {
        let disc = Discretization::new(
            Mesh::uniform(Element::Q1, (0.0, h, 1), (0.0, h, 1), false),
            material,
            Integration::Full,
        )
        .unwrap();
        let expect = (h / (1.0 + h * h / 3.0)).sqrt();
        for rule in [Rule::Gauss1, Rule::Trapezoid] {
            let est = inf_sup(&disc, rule).unwrap();
            assert!(
                rel(est.beta, expect, 1.0) < 1e-13,
                "h={h} {rule:?}: β {} vs {expect}",
                est.beta
            );
            assert!(
                rel(est.beta_bar, expect, 1.0) < 1e-13,
                "h={h} {rule:?}: β̄ {} vs {expect}",
                est.beta_bar
            );
        }
        // Three Simpson points against two trace dofs: a kernel, reported as β = 0.
        let simpson = inf_sup(&disc, Rule::Simpson).unwrap();
        assert_eq!(simpson.beta, 0.0);
        assert!(simpson.kernel.unwrap().contains("kernel of dimension 1"));
    }
}

fn levels_of(element: Element, rule: Rule, levels: std::ops::RangeInclusive<u32>) -> Vec<InfSupRow> {
    let levels: Vec<u32> = levels.collect();
    table(&paper_with(&[]), &[(element, rule)], &levels).unwrap()
}

/// The library's table groups the rows per pair in the order asked (not the elements'
/// order), by ascending level, with each pair's first row slopeless and the others' slope
/// log(β₁/β₀)/log(h₁/h₀) of their own pair; a pair with a kernel (β = 0) has none.
#[test]
fn the_table_groups_per_pair_with_slopes_of_the_pair() {
    let pairs = [
        (Element::Q2, Rule::Simpson),
        (Element::Q1, Rule::Simpson),
        (Element::Q1, Rule::Gauss1),
    ];
    let rows = table(&paper_with(&[]), &pairs, &[1, 0]).unwrap();
    let got: Vec<(&str, &str, u32)> = rows.iter().map(|r| (r.element, r.rule, r.level)).collect();
    assert_eq!(
        got,
        [
            ("q2", "simpson", 0),
            ("q2", "simpson", 1),
            ("q1", "simpson", 0),
            ("q1", "simpson", 1),
            ("q1", "gauss1", 0),
            ("q1", "gauss1", 1),
        ]
    );
    for pair in rows.chunks(2) {
        assert_eq!(pair[0].slope, None);
        let by_hand = (pair[0].beta > 0.0).then(|| (pair[1].beta / pair[0].beta).ln() / 0.5f64.ln());
        assert_eq!(pair[1].slope, by_hand, "{pair:?}");
    }
    assert_eq!(rows[3].slope, None, "q1 + simpson has a kernel: no slope");
    assert!(rows[5].slope.is_some());
}

/// The paper's claims, levels 0..5 of its problem: M1 fails (13) — β_h/√h decreases strictly,
/// with a clearly positive log-log slope against h — while its smoothed pressure (21) and M3
/// keep β/√h bounded below; Q1 + Simpson has a kernel.
#[test]
fn paper_claims_over_levels_0_to_5() {
    let m1 = levels_of(Element::Q1, Rule::Gauss1, 0..=5);
    assert!(
        m1.windows(2)
            .all(|w| w[1].beta_over_sqrt_h < w[0].beta_over_sqrt_h),
        "M1 β/√h must decrease strictly"
    );
    // Least-squares slope of log(β/√h) against log h.
    let pts: Vec<(f64, f64)> = m1.iter().map(|r| (r.h.ln(), r.beta_over_sqrt_h.ln())).collect();
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let fit = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
        / pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
    assert!(fit > 0.5, "M1: β/√h ∝ h^{fit}: not clearly vanishing");
    let m3 = levels_of(Element::Q1, Rule::Trapezoid, 0..=5);
    for rows in [&m1, &m3] {
        let first = rows[0].beta_bar_over_sqrt_h;
        assert!(
            rows.iter().all(|r| r.beta_bar_over_sqrt_h > 0.8 * first),
            "smoothed β̄/√h collapsed: {rows:?}"
        );
    }
    assert!(
        m3.iter()
            .all(|r| r.beta_over_sqrt_h > 0.8 * m3[0].beta_over_sqrt_h)
    );
    let simpson = levels_of(Element::Q1, Rule::Simpson, 0..=1);
    assert!(simpson.iter().all(|r| r.beta == 0.0 && r.kernel.is_some()));
}

/// The table for M1–M4 at levels 0..4, rounded to 5 significant digits.
#[test]
fn snapshot_table_m1_to_m4() {
    let mut text = String::from(
        "scheme  level  h         beta        beta/sqrt(h)  beta_bar    beta_bar/sqrt(h)  slope\n",
    );
    for m in ["M1", "M2", "M3", "M4"] {
        let Scheme { element, rule } = Scheme::parse(m).unwrap();
        let rows = levels_of(element, rule, 0..=4);
        for r in &rows {
            let sl = r.slope.map_or("-".into(), |v| format!("{v:.3}"));
            text += &format!(
                "{m:<7} {:<6} {:<9} {:<11.5e} {:<13.5e} {:<11.5e} {:<17.5e} {sl}\n",
                r.level, r.h, r.beta, r.beta_over_sqrt_h, r.beta_bar, r.beta_bar_over_sqrt_h
            );
        }
    }
    snap!("infsup_m1_m4_levels_0_4", text);
}
