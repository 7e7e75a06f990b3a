//! The engine's cache, background builds and warm starts.

use super::*;
use crate::tui::app::{App, SolveKey};
use std::time::Duration;

use crate::tui::build::Build;

/// After a Nitsche solve, the background build of
/// the next level prepares Nitsche's layer with the mesh, and a neighbour built before
/// (for another method) is prepared alone; either way the step finds it ready.
#[test]
fn a_background_build_after_a_nitsche_solve_prepares_its_layer() {
    use crate::contact::method::Gamma0;
    let scenario = Scenario::paper();
    let mut engine = Engine::new(scenario.clone());
    let solve = |engine: &mut Engine, level, method| {
        let key = SolveKey {
            level,
            method,
            ..App::defaults(&scenario)
        };
        let response = engine.solve(&SolveRequest { generation: 1, key }, &|_| true, &mut |_| {});
        assert!(matches!(response, Response::Solved { result: Ok(_), .. }));
        key
    };
    let nitsche = Method::Nitsche {
        theta: 1,
        gamma0: Gamma0::Auto,
    };
    let in_background = |engine: &mut Engine, level| {
        assert_eq!(engine.next_prefetch(), Some((level, Element::Q1)));
        let plan = engine.plan(level, Element::Q1);
        assert!(plan.prepares(), "{plan:?}");
        let built = engine.peek(level, Element::Q1);
        let build = Build::start(&engine.scenario, plan, 0, built).expect("a thread");
        let Ok(Ok(finished)) = build.finished(Duration::from_secs(120)) else {
            panic!("the build finished");
        };
        assert!(finished.prepare_ms.is_some());
        engine.adopt(level, Element::Q1, Ok(finished), Use::Background);
    };
    // The penalty at levels 3 and 2, then Nitsche's method at level 2: level 3 is built,
    // but not for Nitsche's method.
    solve(&mut engine, 3, scenario.method);
    let key = solve(&mut engine, 2, scenario.method);
    assert!(engine.has(3, Element::Q1));
    solve(&mut engine, 2, nitsche);
    assert!(!engine.ready(3, Element::Q1, Some((key.rule, nitsche))));
    in_background(&mut engine, 3);
    // Level 1 is not built: built and prepared.
    in_background(&mut engine, 1);
    for level in [1, 3] {
        assert!(
            engine.ready(level, Element::Q1, Some((key.rule, nitsche))),
            "{level}"
        );
    }
    assert_eq!(engine.next_prefetch(), None, "nothing left to prepare");
}

/// A γ₀ below the stability threshold (θ = 1, γ₀ = 0.1 where auto chooses 10·γ₀* ≈ 16):
/// the preparation ends without its operator and leaves the mesh ready (nothing is
/// prepared again in a loop), and the solve reports the refusal with the threshold.
#[test]
fn a_refused_gamma0_is_the_solves_to_report_after_the_preparation() {
    use crate::contact::method::Gamma0;
    let scenario = Scenario::paper();
    let mut engine = Engine::new(scenario.clone());
    let key = SolveKey {
        level: 2,
        method: Method::Nitsche {
            theta: 1,
            gamma0: Gamma0::Given(0.1),
        },
        ..App::defaults(&scenario)
    };
    let penalty = SolveKey {
        method: scenario.method,
        ..key
    };
    let response = engine.solve(
        &SolveRequest {
            generation: 1,
            key: penalty,
        },
        &|_| true,
        &mut |_| {},
    );
    assert!(matches!(response, Response::Solved { result: Ok(_), .. }));
    let need = Some((key.rule, key.method));
    assert!(!engine.ready(2, Element::Q1, need));
    let plan = engine.plan_for(2, Element::Q1, key.rule, key.method);
    let build = Build::start(&scenario, plan, 0, engine.peek(2, Element::Q1)).expect("a thread");
    let Ok(Ok(finished)) = build.finished(Duration::from_secs(120)) else {
        panic!("the preparation finished");
    };
    engine.adopt(2, Element::Q1, Ok(finished), Use::Solve);
    assert!(engine.ready(2, Element::Q1, need), "prepared, refusal and all");
    match engine.solve(&SolveRequest { generation: 2, key }, &|_| true, &mut |_| {}) {
        Response::Solved { result: Err(e), .. } => {
            let LabError::Solve(SolveError::Input(crate::error::InputFault::Unstable {
                theta,
                threshold: Some(_),
                ..
            })) = e
            else {
                panic!("{e}");
            };
            assert_eq!(theta, 1.0);
        }
        other => panic!("{other:?}"),
    }
}

/// A carried start that does not lead to convergence (here: a pressure that is not a
/// number, as a solve that did not converge may leave) is solved again from rest: the
/// answer and the Newton steps of a start from rest.
#[test]
fn a_carried_start_that_fails_is_solved_again_from_rest() {
    let scenario = Scenario::paper();
    let key = SolveKey {
        level: 3,
        ..App::defaults(&scenario)
    };
    let solve = |engine: &mut Engine| match engine.solve(
        &SolveRequest { generation: 1, key },
        &|_| true,
        &mut |_| {},
    ) {
        Response::Solved { result: Ok(s), .. } => s,
        other => panic!("{other:?}"),
    };
    let rest = solve(&mut Engine::new(scenario.clone()));
    let mut engine = Engine::new(scenario.clone());
    engine.warm = Some(Warm {
        points: ForcePoints {
            level: 2,
            element: key.element,
            rule: key.rule,
            nitsche: false,
            integration: key.integration,
        },
        forces: Vec::new(),
        x: vec![-1.0, 1.0],
        p: vec![f64::NAN, f64::NAN],
        method: key.method,
        z: None,
    });
    let again = solve(&mut engine);
    assert!(again.solution.newton.converged);
    assert_eq!(again.solution.newton.iterations, rest.solution.newton.iterations);
    assert_eq!(again.solution.load, rest.solution.load);
}

/// A background build started before the lab's `i` switched the
/// integration is not kept (it would be served as the mesh of the other integration), and the
/// next prefetch builds the mesh of the new one.
#[test]
fn a_build_of_the_integration_switched_from_is_not_kept() {
    use crate::fem::Integration;
    let scenario = Scenario::paper();
    let mut engine = Engine::new(scenario.clone());
    let key = SolveKey {
        level: 1,
        ..App::defaults(&scenario)
    };
    let response = engine.solve(&SolveRequest { generation: 1, key }, &|_| true, &mut |_| {});
    assert!(matches!(response, Response::Solved { result: Ok(_), .. }));
    assert_eq!(engine.next_prefetch(), Some((2, Element::Q1)));
    let plan = engine.plan(2, Element::Q1);
    let build = Build::start(&engine.scenario, plan, 0, None).expect("a thread");
    let Ok(Ok(finished)) = build.finished(Duration::from_secs(120)) else {
        panic!("the build finished");
    };
    assert_eq!(finished.disc.integration, Integration::Full);
    engine.follow(Integration::Selective);
    engine.adopt(2, Element::Q1, Ok(finished), Use::Background);
    assert!(!engine.has(2, Element::Q1));
    assert!(
        !engine.has(1, Element::Q1),
        "level 1 is built fully integrated only"
    );
    engine.follow(Integration::Full);
    assert!(engine.has(1, Element::Q1));
    assert!(!engine.has(2, Element::Q1), "the stale build was dropped");
    engine.follow(Integration::Selective);
    assert_eq!(engine.next_prefetch(), Some((2, Element::Q1)));
    let plan = engine.plan(2, Element::Q1);
    let build = Build::start(&engine.scenario, plan, 0, None).expect("a thread");
    let Ok(Ok(finished)) = build.finished(Duration::from_secs(120)) else {
        panic!("the build finished");
    };
    assert_eq!(finished.disc.integration, Integration::Selective);
    engine.adopt(2, Element::Q1, Ok(finished), Use::Background);
    assert!(engine.has(2, Element::Q1));
}
