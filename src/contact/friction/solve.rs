//! A contact solve with friction on a discretisation (docs/design.md §11): the checks, the
//! full trace's couplings, the loading path, and the answer ([`Frictional`], with its
//! [`FrictionSolution`]; a [`crate::contact::solution::Solution`] by `From`, since the solution
//! names friction's results), warm-startable from an earlier solve's forces (the warnings are
//! the entry's, [`crate::solve()`]).

use std::ops::ControlFlow;
use std::time::Instant;

use super::trace::{FrictionTrace, apply, nodal};
use crate::contact::friction::law::{Bound, Imposition};
use crate::contact::friction::path::{FrictionSolution, PathProblem};
use crate::contact::friction::{Friction, Law, Press};
use crate::contact::newton::{Iteration, NewtonOptions, NewtonResult};
use crate::contact::{ContactParams, ContactPoints, Method, load, raw_pressure, smoothed_pressure};
use crate::discretization::{Discretization, ms_since};
use crate::error::{Diagnosis, InputFault, SolveError};

/// A solve with friction's answer: the normal contact's (as a frictionless solve gives it)
/// beside friction's own.
#[derive(Clone, Debug)]
pub struct Frictional {
    /// What the solve depended on beyond the mesh.
    pub params: ContactParams,
    /// The rule's points on Γ_C.
    pub points: ContactPoints,
    /// The last step's Newton result (y, u_n − g, its iterations and history).
    pub newton: NewtonResult,
    /// The ALM's multiplier updates (None without).
    pub outer_iterations: Option<usize>,
    /// Raw pressure p at the rule's points (12).
    pub p: Vec<f64>,
    /// Smoothed pressure p̄ at the Γ_C vertices (16)–(17).
    pub pbar: Vec<f64>,
    /// u_y at the Γ_C vertices.
    pub vertex_uy: Vec<f64>,
    /// P = I(p, 1).
    pub load: f64,
    /// The solve's time on Γ_C, in milliseconds.
    pub newton_ms: f64,
    /// The tangential forces, tractions and states.
    pub friction: FrictionSolution,
}

/// The traces of u₀ = K⁻¹f on the rule's points: d = B_n u₀ − g and e = B_t u₀ (a scenario
/// has f = 0: d = −g, e = 0; a patch test loads the body).
pub struct Free<'a> {
    /// d = B_n u₀ − g.
    pub d: &'a [f64],
    /// e = B_t u₀.
    pub e: &'a [f64],
}

/// `friction` checked against `params` and `disc`: its own ranges, a method that it
/// supports, and the obstacle's shifted centre inside the body.
pub fn check(disc: &Discretization, params: &ContactParams, friction: &Friction) -> Result<(), SolveError> {
    friction.check().map_err(InputFault::from)?;
    if let Method::Nitsche { .. } = params.method {
        return Err(InputFault::FrictionOfNitsche.into());
    }
    let nnx = disc.mesh.nnx();
    let (x0, x1) = (disc.mesh.node_x[0], disc.mesh.node_x[nnx - 1]);
    let moved = params.obstacle.center() + friction.shift;
    if !(moved > x0 && moved < x1) {
        return Err(InputFault::ShiftBeyond {
            shift: friction.shift,
            centre: moved,
            x0,
            x1,
        }
        .into());
    }
    Ok(())
}

/// Solve the contact problem with `friction` on `disc` (no body load), from the forces
/// (y, z) of an earlier solve with the same rule (`initial`, ignored if it does not fit).
pub(crate) fn solve_frictional(
    disc: &Discretization,
    params: &ContactParams,
    friction: &Friction,
    initial: Option<(&[f64], &[f64])>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<Frictional, SolveError> {
    let points = ContactPoints::on(disc, params.rule);
    let d: Vec<f64> = points.points.iter().map(|q| -params.obstacle.gap(q.x)).collect();
    let e = vec![0.0; d.len()];
    solve_with(
        disc,
        params,
        friction,
        Free { d: &d, e: &e },
        initial,
        opts,
        on_iteration,
    )
}

/// The solve with friction with the body's load given by its traces `free`.
pub fn solve_with(
    disc: &Discretization,
    params: &ContactParams,
    friction: &Friction,
    free: Free,
    initial: Option<(&[f64], &[f64])>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<Frictional, SolveError> {
    let t = Instant::now();
    let points = ContactPoints::on(disc, params.rule);
    crate::contact::params::check_on(disc, params, points.len())?;
    check(disc, params, friction)?;
    let trace = FrictionTrace::of(disc)?;
    let couplings = trace.couplings(disc, params.rule, &points);
    let weight: Vec<f64> = points.points.iter().map(|q| q.weight).collect();
    let n = weight.len();
    let thresholds = vec![friction.law.threshold().unwrap_or(0.0); n];
    let bound = match friction.law {
        Law::Coulomb { mu } => Bound::Coulomb(mu),
        Law::Tresca { .. } => Bound::Tresca(&thresholds),
        Law::None => Bound::Coulomb(0.0),
    };
    let press_bound = match friction.press {
        Press::WithFriction => bound,
        Press::Frictionless => Bound::Coulomb(0.0),
    };
    let penalised = Imposition::Penalty {
        epsilon: params.epsilon,
        epsilon_t: friction.epsilon_t.unwrap_or(params.epsilon),
    };
    let (imposition, alm) = match params.method {
        Method::Exact => (Imposition::Exact, None),
        Method::Alm { tolerance } => (penalised, Some(tolerance)),
        _ => (penalised, None),
    };
    if imposition == Imposition::Exact && friction.epsilon_t.is_some() {
        return Err(InputFault::TangentialPenaltyOfExact.into());
    }
    let path = PathProblem {
        couplings: &couplings,
        d: free.d,
        e: free.e,
        weight: &weight,
        bound,
        press_bound,
        imposition,
        alm,
        shift: friction.shift,
        steps: friction.steps,
    };
    let result = path.solve(initial, opts, on_iteration)?;
    let last = result.last;
    let p: Vec<f64> = match (params.method, imposition) {
        (Method::Penalty, _) => raw_pressure(&last.s, params.epsilon),
        _ => (0..n).map(|q| last.y[q] / weight[q]).collect(),
    };
    let t_raw: Vec<f64> = (0..n).map(|q| last.z[q] / weight[q]).collect();
    let pbar = smoothed_pressure(&points, &p);
    let tbar = smoothed_pressure(&points, &t_raw);
    let nodes = trace.nodes();
    let (ny, nz) = (nodal(&points, &last.y, nodes), nodal(&points, &last.z, nodes));
    let order = disc.mesh.element.order();
    let at_vertices =
        |a: Vec<f64>, b: Vec<f64>| -> Vec<f64> { (0..nodes).step_by(order).map(|i| b[i] - a[i]).collect() };
    // u_y = −C_nn Tᵀy + C_nt Tᵀz, u_x = −C_tn Tᵀy + C_tt Tᵀz.
    let vertex_uy = at_vertices(apply(trace.block(1, 1), &ny), apply(trace.block(1, 0), &nz));
    let vertex_ux = at_vertices(apply(trace.block(0, 1), &ny), apply(trace.block(0, 0), &nz));
    let load_p = load(&points, &p);
    let tangential_load: f64 = last.z.iter().sum();
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    let mut converged = last.converged();
    let mut diagnosis = last.diagnosis.clone();
    if converged
        && !(load_p.is_finite()
            && tangential_load.is_finite()
            && [&p, &pbar, &t_raw, &tbar, &vertex_uy, &vertex_ux]
                .iter()
                .all(|v| finite(v)))
    {
        converged = false;
        diagnosis = Some(Diagnosis::Overflow);
    }
    let newton_ms = ms_since(t);
    Ok(Frictional {
        params: params.clone(),
        newton: NewtonResult {
            forces: last.y.clone(),
            violation: last.s.clone(),
            iterations: last.iterations,
            converged,
            residual: last.residual,
            history: result.history,
            diagnosis,
        },
        outer_iterations: result.outer,
        p,
        pbar,
        vertex_uy,
        load: load_p,
        newton_ms,
        friction: FrictionSolution {
            friction: *friction,
            z: last.z,
            t: t_raw,
            tbar,
            states: last.states,
            vertex_ux,
            tangential_load,
            steps: result.steps,
        },
        points,
    })
}
