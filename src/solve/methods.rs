//! The frictionless methods on a discretisation (docs/design.md §2–§4, §10): the penalty, the
//! exact constraint and the augmented Lagrangian on the trace compliance's coupling G, Nitsche's
//! method on its own operator ([`crate::contact::nitsche`]); p, p̄ (17), the load and the contact
//! displacement of the answer. The warnings are the entry's ([`super::solve`]).

use std::ops::ControlFlow;
use std::time::Instant;

use crate::contact::ContactParams;
use crate::contact::newton::{Iteration, NewtonOptions};
use crate::contact::nitsche::{self, NitscheParams};
use crate::contact::penalty::{self, Penalty};
use crate::contact::signorini::solve_exact;
use crate::contact::solution::{Solution, Timing};
use crate::contact::{ContactPoints, Method, alm, load, raw_pressure, smoothed_pressure};
use crate::discretization::{Discretization, ms_since};
use crate::error::{Diagnosis, SolveError};

/// Solve the frictionless contact problem on `disc`, from the contact forces of an earlier
/// solution with the same rule (`initial`, ignored if it does not fit); no warnings yet.
pub(super) fn solve_frictionless(
    disc: &Discretization,
    params: &ContactParams,
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<Solution, SolveError> {
    let t = Instant::now();
    let points = ContactPoints::on(disc, params.rule);
    crate::contact::params::check_on(disc, params, points.len())?;
    if let Method::Nitsche { theta, gamma0 } = params.method {
        // `auto`'s γ₀* is computed once per rule on this mesh; its time is the preparation's.
        let nitsche = NitscheParams {
            theta: f64::from(theta),
            gamma0: nitsche::gamma0(disc, params.rule, gamma0)?,
        };
        let chosen_ms = ms_since(t);
        let mut sol = nitsche::solve(disc, params, nitsche, initial, opts, on_iteration)?;
        sol.timing.factorization += chosen_ms;
        sol.timing.total += chosen_ms;
        return Ok(sol);
    }
    let coupling = crate::contact::coupling::of(disc, params.rule, &points);
    let weight: Vec<f64> = points.points.iter().map(|q| q.weight).collect();
    // No body force or traction (docs/design.md §1): u₀ = 0 and d = −g.
    let free_violation: Vec<f64> = points.points.iter().map(|q| -params.obstacle.gap(q.x)).collect();
    let problem = Penalty {
        coupling: &coupling,
        free_violation: &free_violation,
        weight: &weight,
        epsilon: params.epsilon,
    };
    // The multiplier per unit tributary length.
    let per_length =
        |forces: &[f64]| -> Vec<f64> { forces.iter().zip(&weight).map(|(y, w)| y / w).collect() };
    let (mut newton, p, outer_iterations) = match params.method {
        Method::Exact => {
            let newton = solve_exact(&problem, initial, opts, on_iteration)?;
            let p = per_length(&newton.forces);
            (newton, p, None)
        }
        // The penalty (Nitsche's solve returned above, on its own operator).
        Method::Penalty | Method::Nitsche { .. } => {
            let newton = penalty::solve(&problem, initial, opts, on_iteration)?;
            let p = raw_pressure(&newton.violation, params.epsilon);
            (newton, p, None)
        }
        Method::Alm { tolerance } => {
            // Unique multipliers (no kernel) allow the ALM's Newton step on them.
            let unique = points.len() <= disc.contact_dofs.len();
            let result = alm::solve(&problem, unique, tolerance, initial, opts, on_iteration)?;
            let p = per_length(&result.newton.forces);
            (result.newton, p, Some(result.outer))
        }
    };
    let pbar = smoothed_pressure(&points, &p);
    let nodal = points.nodal_forces(&newton.forces, disc.contact_dofs.len());
    let loaded: Vec<usize> = (0..nodal.len()).filter(|&k| nodal[k] != 0.0).collect();
    let order = disc.mesh.element.order();
    let vertex_uy: Vec<f64> = (0..nodal.len())
        .step_by(order)
        .map(|i| {
            -loaded
                .iter()
                .map(|&k| disc.compliance[(i, k)] * nodal[k])
                .sum::<f64>()
        })
        .collect();
    let load = load(&points, &p);
    // A number that is not finite is never a result (the input checks should make this
    // unreachable; this is the last line of defence).
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    if newton.converged
        && !(load.is_finite()
            && newton.residual.is_finite()
            && finite(&newton.forces)
            && finite(&p)
            && finite(&pbar)
            && finite(&vertex_uy))
    {
        newton.converged = false;
        newton.diagnosis = Some(Diagnosis::Overflow);
    }
    let newton_ms = ms_since(t);
    let timing = Timing {
        newton: newton_ms,
        total: newton_ms,
        ..Timing::default()
    };
    Ok(Solution {
        params: params.clone(),
        points,
        newton,
        outer_iterations,
        p,
        pbar,
        vertex_uy,
        load,
        timing,
        warnings: Vec::new(),
        nodal_forces: None,
        gamma0: None,
        friction: None,
    })
}
