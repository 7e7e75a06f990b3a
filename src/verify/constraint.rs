//! The cases of the constraint's methods on the paper's problem with M3 (q1 + trapezoid):
//! the augmented Lagrangian converges to the exact constraint's solution, and the penalty's
//! load is off by O(ε) — the body penetrates by εp.

use std::ops::ControlFlow;

use super::{Case, Kind, MAX_VERIFY_LEVEL, Measured, converged};
use crate::contact::method::DEFAULT_ALM_TOL;
use crate::contact::newton::NewtonOptions;
use crate::contact::solution::Solution;
use crate::contact::{ContactParams, Method};
use crate::discretization::Discretization;
use crate::error::SolveError;
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::solve::{self, Request};

/// The cases of this family.
pub fn cases() -> [Case; 2] {
    [
        Case {
            name: "alm",
            description: "paper's problem, M3, ALM at ε = 1e-6 (tolerance 1e-10) against the exact constraint",
            source: "the ALM's fixed point satisfies the exact constraint's conditions (Glowinski & Le Tallec, Augmented Lagrangian Methods, 1989; docs/design.md §10)",
            kind: Kind::Consistency,
            default_level: 3,
            max_level: MAX_VERIFY_LEVEL,
            run: alm,
        },
        Case {
            name: "penalty",
            description: "paper's problem, M3: the penalty's load error at κ = εE/h = 1e-3 and 1e-4 against the exact constraint",
            source: "the penalised body penetrates by εp: the load error is O(ε) (Kikuchi & Oden, Contact Problems in Elasticity, 1988, ch. 6)",
            kind: Kind::Consistency,
            default_level: 3,
            max_level: MAX_VERIFY_LEVEL,
            run: penalty,
        },
    ]
}

/// The paper's problem at `level` with M3, and a solver of its contact for a method and ε.
fn setup(level: u32) -> Result<(Scenario, Discretization), SolveError> {
    let scenario = Scenario::paper();
    let m3 = Scheme::PAPER[2];
    let disc = scenario.discretize(level, m3.element)?;
    Ok((scenario, disc))
}

fn solve(
    scenario: &Scenario,
    disc: &Discretization,
    method: Method,
    epsilon: f64,
) -> Result<Solution, SolveError> {
    let params = ContactParams {
        rule: Scheme::PAPER[2].rule,
        method,
        epsilon,
        obstacle: scenario.obstacle.clone(),
    };
    let request = Request::new(params);
    let sol = solve::solve(disc, &request, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })?
    .sol;
    converged(&sol)?;
    Ok(sol)
}

fn alm(level: u32) -> Result<Vec<Measured>, SolveError> {
    let (scenario, disc) = setup(level)?;
    let exact = solve(&scenario, &disc, Method::Exact, 0.0)?;
    let alm = solve(
        &scenario,
        &disc,
        Method::Alm {
            tolerance: DEFAULT_ALM_TOL,
        },
        scenario.epsilon,
    )?;
    let top = exact.p.iter().copied().fold(0.0, f64::max);
    let worst = exact
        .p
        .iter()
        .zip(&alm.p)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    Ok(vec![
        Measured::absolute("max |p_ALM − p_exact|/max p_exact", worst / top, 0.0, 1e-8),
        Measured::relative("load", alm.load, exact.load, 1e-9),
    ])
}

fn penalty(level: u32) -> Result<Vec<Measured>, SolveError> {
    let (scenario, disc) = setup(level)?;
    let exact = solve(&scenario, &disc, Method::Exact, 0.0)?;
    let scale = disc.mesh.h() / scenario.material.young;
    let error = |kappa: f64| -> Result<f64, SolveError> {
        let sol = solve(&scenario, &disc, Method::Penalty, kappa * scale)?;
        Ok((sol.load - exact.load).abs() / exact.load)
    };
    let (coarse, fine) = (error(1e-3)?, error(1e-4)?);
    Ok(vec![Measured::absolute(
        "order of the load error in ε",
        (coarse / fine).log10(),
        1.0,
        0.01,
    )])
}
