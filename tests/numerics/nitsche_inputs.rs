//! What Nitsche's method (`riplab::contact::nitsche`) is given: bad parameters refused as
//! typed input errors, a cancelled or cut-short solve said so, and every bundled scenario
//! solved with a load in equilibrium with its base.

use std::ops::ControlFlow;

use crate::common::{bottom_reaction, rel};
use crate::nitsche::{THETAS, converged, paper_params};
use riplab::contact::newton::NewtonOptions;
use riplab::contact::nitsche::{self, NitscheParams};
use riplab::contact::{ContactParams, Rule};
use riplab::error::{Diagnosis, InputFault, SolveError};
use riplab::mesh::Element;
use riplab::scenario::Scenario;

/// Bad parameters are typed input errors naming the parameter and its range; a cancelled
/// solve says so; an iteration limit gives a non-converged result with a diagnosis.
#[test]
fn bad_nitsche_parameters_are_refused() {
    let scenario = Scenario::paper();
    let disc = scenario.discretize(0, Element::Q1).unwrap();
    let params = paper_params(&scenario, Rule::Trapezoid, 0.0);
    for (theta, gamma0, name) in [
        (2.0, 10.0, "θ"),
        (f64::NAN, 10.0, "θ"),
        (1.0, 0.0, "γ₀"),
        (1.0, -3.0, "γ₀"),
        (1.0, f64::INFINITY, "γ₀"),
    ] {
        match nitsche::solve_once(&disc, &params, NitscheParams { theta, gamma0 }) {
            Err(e @ SolveError::Input(InputFault::Theta { theta: t })) if name == "θ" => {
                assert!(t.to_bits() == theta.to_bits() && e.is_input(), "{e}");
            }
            Err(e @ SolveError::Input(InputFault::Gamma0 { gamma0: g, lo, hi })) if name == "γ₀" => {
                assert!(
                    g.to_bits() == gamma0.to_bits() && lo > 0.0 && hi.is_finite(),
                    "{e}"
                );
                assert!(e.is_input(), "{e}");
            }
            other => panic!("θ = {theta}, γ₀ = {gamma0}: {:?}", other.map(|s| s.load)),
        }
    }
    let too_deep = ContactParams {
        obstacle: scenario.obstacle.with_depth(scenario.height),
        ..params.clone()
    };
    assert!(matches!(
        nitsche::solve_once(
            &disc,
            &too_deep,
            NitscheParams {
                theta: 1.0,
                gamma0: 10.0
            }
        ),
        Err(SolveError::Range {
            what: "the indentation depth",
            ..
        })
    ));
    let stop = NitscheParams {
        theta: 1.0,
        gamma0: 30.0,
    };
    let cancelled = nitsche::solve(&disc, &params, stop, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Break(())
    });
    assert!(matches!(cancelled, Err(SolveError::Cancelled)));
    let short = NewtonOptions {
        max_iterations: 0,
        ..NewtonOptions::default()
    };
    let sol = nitsche::solve(&disc, &params, stop, None, &short, &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap();
    assert!(!sol.newton.converged);
    assert!(matches!(
        sol.newton.diagnosis,
        Some(Diagnosis::Stalled { iterations: 0, .. })
    ));
}

/// Every scenario under `scenarios/` solves by Nitsche's method at level 1 with every element
/// and θ at γ₀ = 10 γ₀* (its own rule, or simpson for q2 and trapezoid otherwise when its rule
/// under-integrates), with a positive load in equilibrium with the clamped base.
#[test]
fn every_scenario_solves_by_nitsche() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    assert!(files.len() >= 5);
    for path in files {
        let scenario = Scenario::load(&path).unwrap();
        for element in Element::ALL {
            let rule = match (element, scenario.rule) {
                (Element::Q2, Rule::Gauss1 | Rule::Trapezoid) => Rule::Simpson,
                (_, rule) => rule,
            };
            let disc = scenario.discretize(1, element).unwrap();
            let params = paper_params(&scenario, rule, 0.0);
            let star = nitsche::stability_threshold(&disc, rule).unwrap();
            // cattaneo-mindlin's ν = 0.499 puts 10·γ₀* (2.9e8) beyond γ₀'s range (1e8).
            if 10.0 * star > 1e8 {
                assert!(scenario.material.poisson > 0.49, "{}", path.display());
                continue;
            }
            for theta in THETAS {
                let sol = converged(&disc, &params, theta, 10.0 * star);
                let what = format!("{} {element:?} {rule:?} θ = {theta}", path.display());
                assert!(sol.load > 0.0, "{what}: P = {}", sol.load);
                let reaction = bottom_reaction(&scenario, &disc, &sol);
                assert!(
                    rel(reaction, sol.load, 1.0) < 1e-8,
                    "{what}: {reaction} against {}",
                    sol.load
                );
            }
        }
    }
}
