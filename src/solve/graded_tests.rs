//! The grading's tests that need no reference, for both gradings (at the edges, over the
//! zone): a graded solve is a solve on its lines; the lines nest and hold the contact edges;
//! the inf-sup estimate runs on graded meshes (M1's p̄ error falling with every pass is
//! tests/numerics/grading.rs).

use std::ops::ControlFlow;

use super::*;
use crate::contact::method::Gamma0;
use crate::contact::newton::NewtonOptions;
use crate::contact::solution::Solution;
use crate::contact::{ContactParams, ContactPoints, Method, Rule};
use crate::discretization::Discretization;
use crate::grading::*;
use crate::mesh::Element;
use crate::solve::solve_contact;

fn params(scenario: &Scenario, rule: Rule, method: Method, epsilon: f64) -> ContactParams {
    ContactParams {
        rule,
        method,
        epsilon,
        obstacle: scenario.obstacle.clone(),
    }
}

fn graded(
    scenario: &Scenario,
    level: u32,
    element: Element,
    p: &ContactParams,
    refine: Grading,
) -> (GradedSolve, Discretization) {
    let uniform = scenario.discretize(level, element).unwrap();
    let g = solve_graded(scenario, (level, &uniform), p, refine, &NewtonOptions::default()).unwrap();
    (g, uniform)
}

/// Two and three passes of each grading.
fn gradings(n: u32) -> [Grading; 2] {
    [RefineEdges::Passes(n).into(), Grading::Zone(n)]
}

fn fresh(disc: &Discretization, p: &ContactParams) -> Solution {
    solve_contact(disc, p, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap()
}

/// The largest difference of `a` and `b` relative to the largest |a|.
fn relative(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let top = a.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / top
}

/// A graded solve equals a fresh solve on a scenario whose level-0 lines are the graded ones
/// (the grading is only a choice of lines, and the warm start only a start), for every
/// method and element, at the edges and over the zone.
#[test]
fn a_graded_solve_is_the_solve_on_its_lines() {
    let s = Scenario::paper();
    let cases = [
        (Element::Q1, Rule::Gauss1, Method::Penalty, 1e-6),
        (Element::Q2, Rule::Simpson, Method::Exact, 0.0),
        (
            Element::P1,
            Rule::Trapezoid,
            Method::Alm { tolerance: 1e-12 },
            1e-7,
        ),
        (
            Element::Q1,
            Rule::Gauss2,
            Method::Nitsche {
                theta: 1,
                gamma0: Gamma0::Given(100.0),
            },
            0.0,
        ),
    ];
    for ((element, rule, method, epsilon), refine) in
        cases.into_iter().flat_map(|c| gradings(2).map(|g| (c, g)))
    {
        let p = params(&s, rule, method, epsilon);
        let (g, _) = graded(&s, 2, element, &p, refine);
        assert_eq!(
            g.grid.passes, 2,
            "{element:?} {method:?}: {:?}",
            g.sol.newton.diagnosis
        );
        let mut lines = s.clone();
        (lines.x_lines, lines.y_lines, lines.level) = (g.grid.xs.clone(), g.grid.ys.clone(), 0);
        let disc = lines.discretize(0, element).unwrap();
        let sol = fresh(&disc, &p);
        assert!(g.sol.newton.converged && sol.newton.converged);
        let what = format!("{element:?} {rule:?} {method:?} {refine}");
        assert!(
            relative(&sol.p, &g.sol.p) <= 1e-12,
            "{what}: p {}",
            relative(&sol.p, &g.sol.p)
        );
        assert!(relative(&sol.pbar, &g.sol.pbar) <= 1e-12, "{what}: p̄");
        assert!((sol.load - g.sol.load).abs() <= 1e-12 * sol.load, "{what}: load");
        assert_eq!(g.sol.points.vertex_x, sol.points.vertex_x, "{what}");
    }
}

/// The graded lines contain the uniform level's (nesting, as the reference's), each pass
/// halves the smallest cell, and the contact edges of the final solve lie in the finest band:
/// the paper's problem (two edges: the symmetry line is not one) and two-bumps (four). Over
/// the zone, every edge of Γ_C with a pressed point, and its neighbours, has the smallest
/// length: (17) sees no change of edge length where p > 0.
#[test]
fn the_lines_nest_and_the_final_edges_lie_in_the_band() {
    let bumps = Scenario::load(std::path::Path::new("scenarios/two-bumps.toml")).unwrap();
    let cases = [(Scenario::paper(), 3, 1), (bumps, 2, 4)];
    for ((s, level, n_edges), refine) in cases
        .into_iter()
        .flat_map(|c| gradings(3).map(|g| (c.clone(), g)))
    {
        let p = params(&s, s.rule, Method::Penalty, s.epsilon);
        let (g, uniform) = graded(&s, level, s.element, &p, refine);
        let lines = s.uniform_grid(level);
        assert!(lines.xs.iter().all(|x| g.grid.xs.contains(x)), "{}", s.name);
        assert!(lines.ys.iter().all(|y| g.grid.ys.contains(y)), "{}", s.name);
        assert_eq!(g.grid.h_min(), lines.h_min() / 8.0, "{}", s.name);
        assert_eq!(g.passes.len(), 4);
        assert_eq!(g.disc(&uniform).n_dofs(), g.passes[3].n_dofs);
        let edges = contact_edges(&g.sol.points, &g.sol.p);
        assert!(edges.len() >= n_edges, "{}: {edges:?}", s.name);
        let x = &g.sol.points.vertex_x;
        for &e in &edges {
            assert!(
                g.grid.in_band(0.5 * (x[e] + x[e + 1])),
                "{} {refine}: edge {e} at {}",
                s.name,
                x[e]
            );
        }
        if let Grading::Zone(_) = refine {
            let zones = crate::grading::zone::contact_zones(&g.sol.points, &g.sol.p);
            assert_eq!(zones.len(), n_edges.div_ceil(2), "{} {zones:?}", s.name);
            for (a, b) in zones {
                let span = &x[a.saturating_sub(1)..=(b + 2).min(x.len() - 1)];
                let h = h_min(&g.grid.xs, &g.grid.xs);
                let uniform = span.windows(2).all(|w| ((w[1] - w[0]) - h).abs() <= 1e-12 * h);
                assert!(uniform, "{} {refine}: {span:?}", s.name);
            }
        }
    }
}

/// The inf-sup estimate runs on a graded mesh (either grading): β_h and β̄_h of M1 on the
/// graded lines are the explicit-lines mesh's, finite and positive, and grading lowers β_h below the uniform
/// level's (its smallest edges are finer: β_h ∝ √h_min where the pressure lives on them).
#[test]
fn the_inf_sup_estimate_runs_on_graded_meshes() {
    let s = Scenario::paper();
    let p = params(&s, Rule::Gauss1, Method::Penalty, 1e-6);
    for refine in gradings(2) {
        let (g, uniform) = graded(&s, 1, Element::Q1, &p, refine);
        let on_graded = crate::infsup::inf_sup(g.disc(&uniform), Rule::Gauss1).unwrap();
        let mut lines = s.clone();
        (lines.x_lines, lines.y_lines, lines.level) = (g.grid.xs.clone(), g.grid.ys.clone(), 0);
        let explicit =
            crate::infsup::inf_sup(&lines.discretize(0, Element::Q1).unwrap(), Rule::Gauss1).unwrap();
        let on_uniform = crate::infsup::inf_sup(&uniform, Rule::Gauss1).unwrap();
        assert!(on_graded.beta.is_finite() && on_graded.beta > 0.0 && on_graded.beta_bar > 0.0);
        assert!((on_graded.beta - explicit.beta).abs() <= 1e-9 * explicit.beta);
        assert!((on_graded.beta_bar - explicit.beta_bar).abs() <= 1e-9 * explicit.beta_bar);
        assert!(
            on_graded.beta < on_uniform.beta,
            "{refine}: {} {}",
            on_graded.beta,
            on_uniform.beta
        );
    }
}

/// `auto` grades until p̄ changes by less than AUTO_TOLERANCE between passes, or the change
/// stops falling (the last two passes above the smallest before them), or MAX_PASSES; each
/// pass's change is measured against the one before; the grid kept is the one whose pass
/// changed p̄ least.
#[test]
fn auto_grades_until_pbar_settles() {
    let s = Scenario::paper();
    let p = params(&s, Rule::Gauss1, Method::Penalty, 1e-6);
    let uniform = s.discretize(2, Element::Q1).unwrap();
    let g = solve_graded(
        &s,
        (2, &uniform),
        &p,
        RefineEdges::Auto,
        &NewtonOptions::default(),
    )
    .unwrap();
    let changes: Vec<f64> = g.passes[1..].iter().map(|q| q.pbar_change.unwrap()).collect();
    assert!(!changes.is_empty() && g.passes[0].pbar_change.is_none());
    let k = changes.len();
    let smallest_before = |n: usize| changes[..n].iter().copied().fold(f64::INFINITY, f64::min);
    let stalled = k >= 3 && changes[k - 2..].iter().all(|&c| c >= smallest_before(k - 2));
    assert!(
        changes[k - 1] < AUTO_TOLERANCE || k == MAX_PASSES as usize || stalled,
        "{changes:?}"
    );
    // No earlier pass met a reason to stop.
    assert!(
        changes[..k - 1].iter().all(|c| *c >= AUTO_TOLERANCE),
        "{changes:?}"
    );
    assert!(
        (3..k).all(|n| changes[n - 2..n].iter().any(|&c| c < smallest_before(n - 2))),
        "{changes:?}"
    );
    let kept = 1 + (0..k).min_by(|&i, &j| changes[i].total_cmp(&changes[j])).unwrap();
    assert_eq!(g.grid.passes as usize, kept, "{changes:?}");
    assert_eq!(
        g.sol.points.vertex_x.len(),
        ContactPoints::on(g.disc(&uniform), p.rule).vertex_x.len()
    );
    assert!(
        g.passes
            .windows(2)
            .all(|w| w[1].h_min == w[0].h_min / 2.0 && w[1].n_dofs > w[0].n_dofs)
    );
}
