//! The contact patch test: a flat rigid plane pressed into the paper's block with ν = 0. The
//! uniform compression u = (0, −δy/H) then satisfies every boundary condition exactly (the
//! clamped base, the free side, the symmetry line, frictionless contact over all of Γ_C), so
//! the pressure is uniform, p = E δ/H, and every element reproduces it (a linear field); with
//! the penalty the body penetrates by εp, p = E d/(H + εE) at the depth d. A rule whose
//! pressure oscillates on a uniform state fails the test.

use std::ops::ControlFlow;

use super::{Case, Kind, MAX_VERIFY_LEVEL, Measured, converged};
use crate::contact::newton::NewtonOptions;
use crate::contact::{ContactParams, Obstacle};
use crate::error::SolveError;
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::solve::{self, Request};

/// The case.
pub const CASE: Case = Case {
    name: "patch",
    description: "flat rigid plane on the paper's block, ν = 0, penalty ε = 1e-6: uniform p and p̄ for M1–M4",
    source: "the uniform compression u = (0, −δy/H) is exact for ν = 0 and reproduced by every element (patch test, Taylor & Papadopoulos 1991): p = E d/(H + εE)",
    kind: Kind::ClosedForm,
    default_level: 3,
    max_level: MAX_VERIFY_LEVEL,
    run,
};

/// The plane's depth (the paper's block is 4 high).
const DEPTH: f64 = 0.01;

fn run(level: u32) -> Result<Vec<Measured>, SolveError> {
    let mut scenario = Scenario::paper();
    scenario.material.poisson = 0.0;
    let (lo, hi) = scenario.x_range();
    let plane = Obstacle::Polyline {
        points: vec![(lo - 1.0, 0.0), (hi + 1.0, 0.0)],
        depth: DEPTH,
    };
    let young = scenario.material.young;
    let epsilon = scenario.epsilon;
    let exact = young * DEPTH / (scenario.height + epsilon * young);
    let mut out = Vec::new();
    for scheme in Scheme::PAPER {
        let disc = scenario.discretize(level, scheme.element)?;
        let params = ContactParams::by_epsilon(scheme.rule, epsilon, plane.clone());
        let request = Request::new(params);
        let sol = solve::solve(&disc, &request, &NewtonOptions::default(), &mut |_| {
            ControlFlow::Continue(())
        })?
        .sol;
        converged(&sol)?;
        let worst = |v: &[f64]| v.iter().map(|p| (p - exact).abs()).fold(0.0, f64::max) / exact;
        let name = scheme.name().unwrap_or("-");
        out.push(Measured::absolute(
            format!("{name}: max |p − p_exact|/p_exact"),
            worst(&sol.p),
            0.0,
            1e-9,
        ));
        out.push(Measured::absolute(
            format!("{name}: max |p̄ − p_exact|/p_exact"),
            worst(&sol.pbar),
            0.0,
            1e-9,
        ));
    }
    Ok(out)
}
