//! From a scenario to a solution: the work that depends only on the mesh (assembly of K, its
//! factorisation, the trace compliance) is held in a [`Discretization`] and done once; each
//! contact solve (rule, method, ε, obstacle) reuses it and costs only dense work on Γ_C. This
//! module chooses the method's solver ([`crate::contact::Method`]): the penalty, the exact
//! constraint and the augmented Lagrangian on the trace compliance, Nitsche's method on its
//! own operator ([`crate::nitsche`]).

use std::ops::ControlFlow;
use std::time::Instant;

use crate::contact::ContactParams;
use crate::contact::newton::{Iteration, NewtonOptions};
use crate::contact::penalty::{self, Penalty};
use crate::contact::signorini::solve_exact;
use crate::contact::{Method, Rule, alm, load, raw_pressure, smoothed_pressure};
use crate::discretization::ms_since;
use crate::discretization::{Discretization, Trace};
use crate::error::{Diagnosis, SolveError};
use crate::friction::solve_friction;
use crate::nitsche::{self, NitscheParams};
use crate::scenario::Scenario;
use crate::solution::{Solution, Timing};
use crate::warning::{self, Warning};

/// Build on `disc` what a solve by `method` with `rule` needs beyond the mesh's own factor, so
/// that the solve costs only its iteration: the coupling G of the penalty, ALM and exact
/// constraint ([`Discretization::coupling`]; milliseconds), or Nitsche's layer, couplings and
/// operator ([`nitsche::prepare`]; seconds at level 7). What fails is the solve's to report.
pub fn prepare(disc: &Discretization, rule: Rule, method: Method) {
    match method {
        Method::Nitsche { theta, gamma0 } => nitsche::prepare(disc, rule, theta, gamma0),
        _ => {
            disc.coupling(rule, &disc.contact_points(rule));
        }
    }
}

/// Whether a solve by `method` with `rule` on `disc` would first do long work that
/// [`prepare`] does: Nitsche's, when not [`nitsche::prepared`].
pub fn needs_preparing(disc: &Discretization, rule: Rule, method: Method) -> bool {
    match method {
        Method::Nitsche { gamma0, .. } => !nitsche::prepared(disc, rule, gamma0),
        _ => false,
    }
}

/// Whether [`prepare`] for `method` on `disc` factorises K again, needing as much memory as
/// the mesh's own build: Nitsche's, before its layer is built.
pub fn preparing_factorises(disc: &Discretization, method: Method) -> bool {
    matches!(method, Method::Nitsche { .. }) && nitsche::factorises(disc)
}

/// Solve the contact problem on `disc`, from the contact forces of an earlier solution with
/// the same rule (`initial`, ignored if it does not fit).
pub fn solve_contact(
    disc: &Discretization,
    params: &ContactParams,
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<Solution, SolveError> {
    let t = Instant::now();
    let points = disc.contact_points(params.rule);
    disc.check(params, points.len())?;
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
    let coupling = disc.coupling(params.rule, &points);
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
    let nodal = Discretization::nodal_forces(&points, &newton.forces, disc.contact_dofs.len());
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
    // The stiffness's warning first (a locked body makes any penalty soft), then a penalty
    // too soft for the depth: its answer is wrong, not merely poor.
    let mut warnings: Vec<Warning> = disc.stiffness_warning().into_iter().collect();
    if params.method == Method::Penalty {
        warnings.extend(warning::of_soft_penalty(
            &params.obstacle,
            &points,
            params.epsilon,
            &p,
        ));
    }
    warnings.extend(warning::of_contact(&params.obstacle, &points, &p, disc.mesh.h()));
    if params.method == Method::Penalty {
        warnings.extend(warning::of_round_off(
            params.obstacle.depth(),
            params.epsilon,
            &p,
            disc.mesh.h(),
            disc.material.young,
        ));
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
        warnings,
        nodal_forces: None,
        gamma0: None,
        friction: None,
    })
}

/// A fresh solve of `scenario` as given (its level, element, rule, ε and obstacle).
/// With friction ([`crate::contact::friction`]) the mesh is factorised once with the full
/// trace last ([`Trace::Full`]) and the press and shift are solved on it.
pub fn solve_scenario(scenario: &Scenario) -> Result<(Discretization, Solution), SolveError> {
    let trace = if scenario.friction.is_on() {
        Trace::Full
    } else {
        Trace::Normal
    };
    let disc = Discretization::of_traced(scenario, scenario.level, scenario.element, trace)?;
    // A scenario whose ε was set to 0 after parsing asks for the exact constraint.
    let method = match scenario.method {
        Method::Penalty if scenario.epsilon == 0.0 => Method::Exact,
        m => m,
    };
    let params = ContactParams {
        rule: scenario.rule,
        method,
        epsilon: scenario.epsilon,
        obstacle: scenario.obstacle.clone(),
    };
    let opts = NewtonOptions::default();
    let mut sol = if scenario.friction.is_on() {
        solve_friction(&disc, &params, &scenario.friction, None, &opts, &mut |_| {
            ControlFlow::Continue(())
        })?
    } else {
        solve_contact(&disc, &params, None, &opts, &mut |_| ControlFlow::Continue(()))?
    };
    sol.timing.include_mesh_work(&disc);
    Ok((disc, sol))
}

/// Solve every instance of `params` on `disc` in order, each warm-started from the contact
/// forces of the last one that solved (a sweep over ε or the depth costs one mesh's work and
/// a few Newton steps per value). The first solution is charged with the mesh's work; a
/// failure is its instance's result, and the sweep goes on.
pub fn sweep(disc: &Discretization, params: &[ContactParams]) -> Vec<Result<Solution, SolveError>> {
    let mut previous: Option<Vec<f64>> = None;
    let mut results = Vec::with_capacity(params.len());
    for p in params {
        let solved = solve_contact(
            disc,
            p,
            previous.as_deref(),
            &NewtonOptions::default(),
            &mut |_| ControlFlow::Continue(()),
        );
        let solved = solved.map(|mut sol| {
            if results.is_empty() {
                sol.timing.include_mesh_work(disc);
            }
            previous = Some(sol.newton.forces.clone());
            sol
        });
        results.push(solved);
    }
    results
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::SolveError;
    use crate::scenario::Scenario;

    /// A sweep on one mesh gives each instance the solution a fresh solve
    /// gives, charges the mesh's work to the first only, and goes on past a failure.
    #[test]
    fn a_sweep_equals_fresh_solves_and_goes_on_past_a_failure() {
        let mut scenario = Scenario::paper();
        scenario.level = 1;
        let disc = Discretization::of(&scenario, 1, scenario.element).unwrap();
        let at = |epsilon: f64, depth: f64| {
            ContactParams::by_epsilon(scenario.rule, epsilon, scenario.obstacle.with_depth(depth))
        };
        // The middle instance's depth is beyond the body: refused, the sweep goes on.
        let params = [at(1e-6, 0.8), at(1e-6, 1e9), at(1e-7, 0.6)];
        let results = sweep(&disc, &params);
        assert!(matches!(
            results[1],
            Err(SolveError::Range {
                what: "the indentation depth",
                ..
            })
        ));
        for k in [0, 2] {
            let swept = results[k].as_ref().unwrap();
            let fresh = solve_contact(&disc, &params[k], None, &NewtonOptions::default(), &mut |_| {
                ControlFlow::Continue(())
            })
            .unwrap();
            assert!((swept.load - fresh.load).abs() < 1e-9 * fresh.load, "{k}");
        }
        let first = &results[0].as_ref().unwrap().timing;
        let last = &results[2].as_ref().unwrap().timing;
        assert!(first.assembly > 0.0 && last.assembly == 0.0);
    }
}
