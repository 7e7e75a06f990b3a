//! The tests issue 35 lists: a graded solve is a solve on its lines; the lines nest and hold
//! the contact edges; M1's p̄ error falls with every pass against the certified reference.

use std::ops::ControlFlow;

use super::*;
use crate::contact::method::Gamma0;
use crate::contact::penalty::NewtonOptions;
use crate::contact::{ContactParams, Method, Rule};
use crate::solve::{Discretization, Solution, solve_contact};
use crate::study::{Plan, ReferenceFields, study};

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
    n: u32,
) -> (GradedSolve, Discretization) {
    let uniform = Discretization::of(scenario, level, element).unwrap();
    let g = solve_graded(
        scenario,
        (level, &uniform),
        p,
        RefineEdges::Passes(n),
        &NewtonOptions::default(),
    )
    .unwrap();
    (g, uniform)
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
/// method and element.
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
    for (element, rule, method, epsilon) in cases {
        let p = params(&s, rule, method, epsilon);
        let (g, _) = graded(&s, 2, element, &p, 2);
        assert_eq!(
            g.grid.passes, 2,
            "{element:?} {method:?}: {:?}",
            g.sol.newton.diagnosis
        );
        let mut lines = s.clone();
        (lines.x_lines, lines.y_lines, lines.level) = (g.grid.xs.clone(), g.grid.ys.clone(), 0);
        let disc = Discretization::of(&lines, 0, element).unwrap();
        let sol = fresh(&disc, &p);
        assert!(g.sol.newton.converged && sol.newton.converged);
        let what = format!("{element:?} {rule:?} {method:?}");
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
/// the paper's problem (two edges: the symmetry line is not one) and two-bumps (four).
#[test]
fn the_lines_nest_and_the_final_edges_lie_in_the_band() {
    let bumps = Scenario::load(std::path::Path::new("scenarios/two-bumps.toml")).unwrap();
    for (s, level, n_edges) in [(Scenario::paper(), 3, 1), (bumps, 2, 4)] {
        let p = params(&s, s.rule, Method::Penalty, s.epsilon);
        let (g, uniform) = graded(&s, level, s.element, &p, 3);
        let lines = GradedGrid::uniform(&s, level);
        assert!(lines.xs.iter().all(|x| g.grid.xs.contains(x)), "{}", s.name);
        assert!(lines.ys.iter().all(|y| g.grid.ys.contains(y)), "{}", s.name);
        assert_eq!(g.grid.h_min(), lines.h_min() / 8.0, "{}", s.name);
        assert_eq!(g.passes.len(), 4);
        assert_eq!(g.disc(&uniform).n_dofs(), g.passes[3].n_dofs);
        let edges = contact_edges(&g.sol.points, &g.sol.p);
        assert!(edges.len() >= n_edges, "{}: {edges:?}", s.name);
        let x = &g.sol.points.vertex_x;
        for e in edges {
            assert!(
                g.grid.in_band(0.5 * (x[e] + x[e + 1])),
                "{}: edge {e} at {}",
                s.name,
                x[e]
            );
        }
    }
}

/// On the default scenario M1's p̄ error at level 2 falls with every pass N = 0 … 3 (no
/// sawtooth), measured by the study against its reference refined until its estimated error
/// is a tenth of the smallest row error (certified).
#[test]
fn m1_pbar_error_falls_with_every_pass() {
    let s = Scenario::paper();
    let refine = [0, 1, 2, 3].map(RefineEdges::Passes);
    let plan = Plan::Levels {
        levels: &[2],
        epsilon: crate::penalty_error::default_epsilon(&s, 2),
        refine: &refine,
    };
    let mut fetch = |grid: &crate::study::ReferenceMesh| ReferenceFields::solve_on(&s, grid);
    let st = study(&s, &[(Element::Q1, Rule::Gauss1)], None, plan, (3, 4), &mut fetch).unwrap();
    // The reference's estimate of p meets its target (u's is the uniform level's: not asked).
    let (estimate, target) = (
        st.reference.estimate.as_ref().unwrap(),
        st.reference.target.unwrap(),
    );
    assert!(estimate.p <= target.p, "{estimate:?} {target:?}");
    let errors: Vec<f64> = st.rows.iter().map(|r| r.errors.unwrap().pbar).collect();
    assert_eq!(
        st.rows.iter().map(|r| r.refine_edges).collect::<Vec<_>>(),
        [0, 1, 2, 3]
    );
    assert!(errors.windows(2).all(|w| w[1] < w[0]), "{errors:?}");
}
