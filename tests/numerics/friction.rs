//! Friction (issue 34; docs/design.md §11): Tresca and Coulomb under the reduced-integration
//! rules, each check against something independent of the friction solver.

use std::ops::ControlFlow;
use std::path::Path;

use riplab::contact::friction::{Friction, Law, State, solve_friction};
use riplab::contact::newton::NewtonOptions;
use riplab::contact::{ContactParams, Method, Rule};
use riplab::discretization::{Discretization, Trace};
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::solution::Solution;
use riplab::solve::solve_contact;

fn full() -> Scenario {
    Scenario::load(Path::new("scenarios/hertz-paper-full.toml")).unwrap()
}

fn params(s: &Scenario, rule: Rule, method: Method, epsilon: f64) -> ContactParams {
    ContactParams {
        rule,
        method,
        epsilon,
        obstacle: s.obstacle.clone(),
    }
}

fn with(disc: &Discretization, p: &ContactParams, f: &Friction) -> Solution {
    solve_friction(disc, p, f, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap()
}

fn frictionless(disc: &Discretization, p: &ContactParams) -> Solution {
    solve_contact(disc, p, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap()
}

fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

/// μ = 0 (Coulomb) and g = 0 (Tresca), shifted, give today's frictionless solve (another
/// solver, on a Normal discretisation's factor) to 1e-12: load, p and p̄; Q = 0.
#[test]
fn mu_zero_is_frictionless() {
    let s = full();
    for element in [Element::Q1, Element::Q2] {
        let disc = Discretization::of_traced(&s, 1, element, Trace::Full).unwrap();
        let normal = Discretization::of(&s, 1, element).unwrap();
        let cases: &[(Rule, Method, f64)] = match element {
            Element::Q2 => &[
                (Rule::Simpson, Method::Exact, 0.0),
                (Rule::Gauss1, Method::Penalty, 1e-6),
            ],
            _ => &[
                (Rule::Gauss1, Method::Penalty, 1e-6),
                (Rule::Trapezoid, Method::Exact, 0.0),
                (Rule::Trapezoid, Method::Alm { tolerance: 1e-10 }, 1e-3),
            ],
        };
        for &(rule, method, eps) in cases {
            let p = params(&s, rule, method, eps);
            let reference = frictionless(&normal, &p);
            for law in [Law::Coulomb { mu: 0.0 }, Law::Tresca { threshold: 0.0 }] {
                let f = Friction {
                    law,
                    shift: 0.05,
                    steps: 4,
                    epsilon_t: None,
                };
                let sol = with(&disc, &p, &f);
                assert!(
                    sol.newton.converged,
                    "{element:?} {rule:?} {method:?} {law:?}: {:?}",
                    sol.newton.diagnosis
                );
                let what = format!("{element:?} {rule:?} {method:?} {law:?}");
                // The ALM's two solvers stop at the multipliers' relative change 1e-10 by
                // different paths (the frictionless one jumps to the fixed point, friction's
                // is plain Uzawa): equal to the tolerance, not to round-off.
                let tol = if let Method::Alm { .. } = method {
                    1e-9
                } else {
                    1e-12
                };
                assert!(
                    (sol.load - reference.load).abs() <= tol * reference.load,
                    "{what}: {} vs {}",
                    sol.load,
                    reference.load
                );
                assert!(
                    max_rel(&sol.p, &reference.p) <= tol,
                    "{what}: p {}",
                    max_rel(&sol.p, &reference.p)
                );
                assert!(max_rel(&sol.pbar, &reference.pbar) <= tol, "{what}");
                let fr = sol.friction.as_ref().unwrap();
                assert_eq!(fr.tangential_load, 0.0, "{what}");
                assert!(fr.states.iter().all(|&st| st != State::Stick), "{what}");
            }
        }
    }
}
