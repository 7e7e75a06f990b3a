//! The contact discretisation checked by identities and physics independent of the solver:
//! the paper's identity (18), global equilibrium, mirror symmetry, and plane-strain Hertz.

use std::ops::ControlFlow;

use crate::common::{Lcg, bottom_reaction, paper_with, rel};
use riplab::contact::ContactParams;
use riplab::contact::newton::NewtonOptions;
use riplab::contact::pressure::{rule_product, smoothed_pressure, trapezoid_product};
use riplab::contact::solution::Solution;
use riplab::contact::{ContactPoints, Obstacle, Rule};
use riplab::discretization::Discretization;
use riplab::fem::Integration;
use riplab::material::{Material, Plane};
use riplab::mesh::{Element, Mesh};
use riplab::solve::{solve_contact, solve_scenario};

fn solve(disc: &Discretization, rule: Rule, epsilon: f64, obstacle: Obstacle) -> Solution {
    let params = ContactParams::by_epsilon(rule, epsilon, obstacle);
    let sol = solve_contact(disc, &params, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap();
    assert!(
        sol.newton.converged,
        "{rule:?}: Newton did not converge: {:?}",
        sol.newton.history
    );
    sol
}

/// (18): I(q, v_n) = Î(q̄, v_n) for any q at the rule's points and any continuous piecewise
/// linear v_n, on a non-uniform partition. For gauss1, q̄ is exactly (17).
#[test]
fn identity_18_holds_for_every_rule() {
    let mut rng = Lcg(18);
    let mut x = vec![0.0];
    for _ in 0..23 {
        x.push(x.last().unwrap() + 0.05 + rng.next().abs());
    }
    for rule in Rule::ALL {
        let cp = ContactPoints::new(rule, &x, 1);
        for _ in 0..20 {
            let q: Vec<f64> = (0..cp.len()).map(|_| 100.0 * rng.next()).collect();
            let v: Vec<f64> = (0..x.len()).map(|_| rng.next()).collect();
            let v_at_points = cp.trace_of(&v);
            let lhs = rule_product(&cp, &q, &v_at_points);
            let rhs = trapezoid_product(&x, &smoothed_pressure(&cp, &q), &v);
            assert!(
                (lhs - rhs).abs() <= 1e-12 * lhs.abs().max(1.0),
                "{rule:?}: {lhs} vs {rhs}"
            );
        }
    }
}

/// The load P equals the vertical reaction on the clamped bottom: Σ_bottom (K u)_y = I(p, 1).
#[test]
fn load_equals_bottom_reaction() {
    let scenario = paper_with(&[]);
    for element in Element::ALL {
        let disc = scenario.discretize(2, element).unwrap();
        for rule in Rule::ALL {
            let sol = solve(&disc, rule, 1e-6, scenario.obstacle.clone());
            let reaction = bottom_reaction(&scenario, &disc, &sol);
            assert!(sol.load > 100.0);
            assert!(
                rel(reaction, sol.load, 1.0) < 1e-9,
                "{element:?}+{rule:?}: reaction {reaction} vs load {}",
                sol.load
            );
        }
    }
}

/// The half model and the full model give the same pressures, mirrored.
#[test]
fn half_and_full_model_agree() {
    let half = paper_with(&[]);
    let full = paper_with(&[("model", "model = \"full\""), ("nx =", "nx = 16")]);
    for element in Element::ALL {
        let dh = half.discretize(1, element).unwrap();
        let df = full.discretize(1, element).unwrap();
        for rule in Rule::ALL {
            let sh = solve(&dh, rule, 1e-6, half.obstacle.clone());
            let sf = solve(&df, rule, 1e-6, full.obstacle.clone());
            assert!(
                rel(sf.load, 2.0 * sh.load, 1.0) < 1e-8,
                "{element:?}+{rule:?}: load"
            );
            let pmax = sh.p.iter().cloned().fold(0.0, f64::max);
            // Points and vertices of the full model at x ≥ 0 are the half model's, in order,
            // and those at −x mirror them.
            let right: Vec<(f64, f64)> = sf
                .points
                .points
                .iter()
                .zip(&sf.p)
                .filter(|(q, _)| q.x >= 0.0)
                .map(|(q, &p)| (q.x, p))
                .collect();
            assert_eq!(right.len(), sh.p.len());
            for ((x, pf), (qh, ph)) in right.iter().zip(sh.points.points.iter().zip(&sh.p)) {
                assert_eq!(*x, qh.x);
                assert!(
                    (pf - ph).abs() <= 1e-8 * pmax,
                    "{element:?}+{rule:?} p at x = {x}: {pf} vs {ph}"
                );
                let mirror = sf
                    .points
                    .points
                    .iter()
                    .position(|q| (q.x + x).abs() < 1e-12)
                    .unwrap();
                assert!((sf.p[mirror] - pf).abs() <= 1e-8 * pmax);
            }
            let offset = df.mesh().xs.len() / 2;
            for (i, ph) in sh.pbar.iter().enumerate() {
                assert!(
                    (sf.pbar[offset + i] - ph).abs() <= 1e-8 * pmax,
                    "{element:?}+{rule:?} p̄ at node {i}"
                );
                assert!((sf.pbar[offset - i] - ph).abs() <= 1e-8 * pmax);
            }
        }
    }
}

/// Vertex lines: uniform with step `h` on [0, fine], then growing geometrically to `end`.
fn graded(h: f64, fine: f64, end: f64, growth: f64) -> Vec<f64> {
    let mut v: Vec<f64> = (0..=(fine / h).round() as usize).map(|i| i as f64 * h).collect();
    let mut step = h;
    while *v.last().unwrap() < end {
        step *= growth;
        let next = (v.last().unwrap() + step).min(end);
        if end - next < step {
            v.push(end);
        } else {
            v.push(next);
        }
    }
    v
}

/// Plane-strain Hertz on a block much larger than the contact zone: a² = 4PR(1 − ν²)/(πE),
/// p₀ = 2P/(πa) from the computed full-body load P agree with the computed pressure profile,
/// whose fit p̄² = p₀²(1 − x²/a²) gives its own a and p₀.
#[test]
fn plane_strain_hertz() {
    let material = Material {
        young: 1000.0,
        poisson: 0.3,
        plane: Plane::Strain,
    };
    let radius = 10.0;
    let (size, h) = (20.0, 1.0 / 32.0);
    let xs = graded(h, 1.5, size, 1.15);
    let ys: Vec<f64> = graded(h, 1.5, size, 1.15)
        .iter()
        .rev()
        .map(|d| size - d)
        .collect();
    for (element, rule) in [
        (Element::Q1, Rule::Trapezoid),
        (Element::Q1, Rule::Gauss1),
        (Element::Q2, Rule::Simpson),
    ] {
        let disc = Discretization::new(
            Mesh::from_lines(element, xs.clone(), ys.clone(), true),
            material,
            Integration::Full,
        )
        .unwrap();
        let sol = solve(
            &disc,
            rule,
            1e-8,
            Obstacle::Cylinder {
                radius,
                depth: 0.2,
                center: 0.0,
            },
        );
        let load = 2.0 * sol.load;
        let e_star = material.young / (1.0 - material.poisson.powi(2));
        let a = (4.0 * load * radius / (std::f64::consts::PI * e_star)).sqrt();
        let p0 = 2.0 * load / (std::f64::consts::PI * a);
        assert!(
            a > 0.6 && a < 1.4,
            "the contact zone should be resolved by the fine region: a = {a}"
        );
        // Least-squares line through (x², p̄²) over the inner 80% of the zone.
        let pts: Vec<(f64, f64)> = sol
            .points
            .vertex_x
            .iter()
            .zip(&sol.pbar)
            .filter(|(x, _)| **x <= 0.8 * a)
            .map(|(x, p)| (x * x, p * p))
            .collect();
        let n = pts.len() as f64;
        let (mx, my) = (
            pts.iter().map(|p| p.0).sum::<f64>() / n,
            pts.iter().map(|p| p.1).sum::<f64>() / n,
        );
        let slope = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
            / pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
        let intercept = my - slope * mx;
        let (p0_fit, a_fit) = (intercept.sqrt(), (-intercept / slope).sqrt());
        assert!(
            rel(p0_fit, p0, 1e-300) < 0.03,
            "{element:?}+{rule:?}: p₀ fit {p0_fit} vs Hertz {p0}"
        );
        assert!(
            rel(a_fit, a, 1e-300) < 0.03,
            "{element:?}+{rule:?}: a fit {a_fit} vs Hertz {a}"
        );
    }
}

/// The default scenario solves at level 0 with every pair and says it converged.
#[test]
fn default_scenario_converges_for_every_pair() {
    for element in Element::ALL {
        for rule in Rule::ALL {
            let mut s = paper_with(&[]);
            s.element = element;
            s.rule = rule;
            let (_, sol) = solve_scenario(&s).unwrap();
            assert!(sol.newton.converged && sol.load > 0.0);
        }
    }
}

/// ε = 0 solves the exact-constraint problem: its multipliers are non-negative, there is no
/// penetration, the load is the bottom reaction, and the penalty loads approach it linearly
/// in ε (the penalty error is O(ε) once the active set has settled).
#[test]
fn exact_constraint_is_the_limit_of_the_penalty() {
    let scenario = paper_with(&[]);
    let disc = scenario.discretize(3, Element::Q1).unwrap();
    let exact = solve(&disc, Rule::Trapezoid, 0.0, scenario.obstacle.clone());
    let ymax = exact.newton.forces.iter().cloned().fold(0.0, f64::max);
    assert!(
        exact.newton.forces.iter().all(|&y| y >= -1e-10 * ymax),
        "tension in the multipliers"
    );
    assert!(
        exact.newton.violation.iter().all(|&s| s <= 1e-12),
        "penetration with the exact constraint"
    );
    let reaction = bottom_reaction(&scenario, &disc, &exact);
    assert!(rel(reaction, exact.load, 1.0) < 1e-9);
    let gap = |eps: f64| exact.load - solve(&disc, Rule::Trapezoid, eps, scenario.obstacle.clone()).load;
    let (g7, g9) = (gap(1e-7), gap(1e-9));
    assert!(
        g7 > 0.0 && g9 > 0.0,
        "the penalty lets the body penetrate, so it carries less load"
    );
    assert!(
        (g7 / g9 / 100.0 - 1.0).abs() < 0.05,
        "O(ε) convergence: {g7} / {g9}"
    );
}

/// Newton converges over ε from 1e−2 to 1e−14 (round-off in u_n − g is not mistaken for a
/// changing active set), and the load tends to its exact-constraint value as the two error
/// terms predict: the penalty's O(ε) (the body penetrates by ε·p, about 3e−6 relative at
/// ε = 1e−8 here) and round-off O(u·|d|/(ε·p)) with u = 2.2e−16, |d| ≤ 0.8 and p ≈ 280, about
/// 6e−19/ε relative. The bound below is ten times the sum.
#[test]
fn newton_converges_down_to_tiny_epsilon() {
    let scenario = paper_with(&[]);
    let disc = scenario.discretize(3, Element::Q1).unwrap();
    for rule in [Rule::Gauss1, Rule::Trapezoid] {
        let exact = solve(&disc, rule, 0.0, scenario.obstacle.clone()).load;
        for k in 2..=14 {
            let eps = 10f64.powi(-k);
            let sol = solve(&disc, rule, eps, scenario.obstacle.clone());
            let bound = 10.0 * (400.0 * eps + 6e-19 / eps);
            if bound < 1.0 {
                assert!(
                    rel(sol.load, exact, 1.0) < bound,
                    "{rule:?} ε = 1e-{k}: {} vs {exact}",
                    sol.load
                );
            }
        }
    }
}

#[test]
fn exact_constraint_refuses_a_pressure_space_with_a_kernel() {
    let scenario = paper_with(&[]);
    let disc = scenario.discretize(0, Element::Q1).unwrap();
    let params = ContactParams::by_epsilon(Rule::Gauss2, 0.0, scenario.obstacle.clone());
    let err = solve_contact(&disc, &params, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap_err();
    assert!(err.to_string().contains("not unique"), "{err}");
}

/// A library user's own outline ([`riplab::contact::Outline`]) that is the
/// cylinder's, η(x) = R − √(R² − x²), gives the paper's cylinder's solution to round-off.
#[test]
fn a_custom_outline_equal_to_the_cylinder_gives_its_solution() {
    use riplab::contact::{Obstacle, Outline};
    use std::sync::Arc;
    struct Circle(f64);
    impl Outline for Circle {
        fn outline(&self, x: f64) -> f64 {
            if x.abs() >= self.0 {
                f64::INFINITY
            } else {
                x * x / (self.0 + (self.0 * self.0 - x * x).sqrt())
            }
        }
    }
    let mut scenario = riplab::scenario::Scenario::paper();
    scenario.level = 2;
    let Obstacle::Cylinder { radius, depth, .. } = scenario.obstacle else {
        panic!("the paper's obstacle is a cylinder")
    };
    let (_, cylinder) = riplab::solve::solve_scenario(&scenario).unwrap();
    scenario.obstacle = Obstacle::Custom {
        outline: Arc::new(Circle(radius)),
        depth,
    };
    assert_eq!(scenario.obstacle.max_depth(), f64::INFINITY);
    assert_eq!(scenario.obstacle.hertz_radius(), None);
    let (_, custom) = riplab::solve::solve_scenario(&scenario).unwrap();
    assert_eq!(custom.load, cylinder.load);
    assert_eq!(custom.pbar, cylinder.pbar);
    assert_eq!(
        format!("{:?}", scenario.obstacle),
        format!("Custom {{ outline: Outline(a custom outline), depth: {depth:?} }}")
    );
}

/// A custom outline has no text that identifies it, so the study's reference of a scenario
/// with one is computed and never stored in (or read from) the cache.
#[test]
fn a_custom_outline_is_never_cached() {
    use riplab::cache::{Provenance, reference};
    use riplab::contact::{Obstacle, Outline};
    use std::sync::Arc;
    struct Flat;
    impl Outline for Flat {
        fn outline(&self, _: f64) -> f64 {
            0.0
        }
    }
    let mut scenario = riplab::scenario::Scenario::paper();
    scenario.obstacle = Obstacle::Custom {
        outline: Arc::new(Flat),
        depth: 0.1,
    };
    let dir = std::env::temp_dir().join(format!("riplab-custom-cache-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (_, provenance) = reference(&scenario, 1, Some(&dir)).unwrap();
    assert!(matches!(provenance, Provenance::Computed(None)), "{provenance:?}");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0, "nothing stored");
    std::fs::remove_dir_all(&dir).unwrap();
}
