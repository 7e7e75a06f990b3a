//! The one solve entry (docs/design.md §9): a [`Request`] (the method and its parameters, the
//! friction, the grading, the warm start) solved on a scenario's uniform level by [`solve`],
//! which chooses the solver, accounts for a graded mesh's memory before it is built, and says
//! what is wrong with the answer ([`crate::warning`]). The work that depends only on the mesh
//! (K, its factorisation, the trace compliance) is the [`Discretization`]'s, done once; each
//! solve reuses it and costs only dense work on Γ_C. The entry owns the dispatch: the
//! frictionless methods (`methods`: the trace compliance's, or Nitsche's operator,
//! [`crate::contact::nitsche`]), friction on Γ_C's full trace ([`crate::contact::friction`]),
//! the passes of a graded mesh ([`crate::grading::passes`]); the methods themselves live in
//! [`crate::contact`].

pub mod checks;
mod methods;

use std::ops::ControlFlow;

use crate::contact::ContactParams;
use crate::contact::friction::{self, Friction};
use crate::contact::newton::{Iteration, NewtonOptions};
use crate::contact::solution::{Solution, Timing};
use crate::contact::{ContactPoints, Method, Rule, nitsche};
use crate::discretization::{Discretization, Trace};
use crate::error::{InputFault, SolveError};
use crate::grading::Grading;
use crate::scenario::Scenario;
use crate::warning::{self, Warning};

pub use crate::grading::passes::{Grids, Pass};

/// What one solve asks beyond the mesh: the method and its parameters, the friction, the
/// grading, and where Newton starts.
#[derive(Clone, Debug)]
pub struct Request<'a> {
    /// The rule, the method, ε and the obstacle.
    pub params: ContactParams,
    /// The friction law, its shift and steps ([`Friction::NONE`]: frictionless).
    pub friction: Friction,
    /// The grading of the mesh at the contact edges or over the zone (None: the mesh given).
    pub grading: Option<Graded<'a>>,
    /// Where Newton starts.
    pub warm: Warm<'a>,
}

impl<'a> Request<'a> {
    /// A frictionless solve of `params` on the uniform level, from rest.
    pub fn new(params: ContactParams) -> Self {
        Request {
            params,
            friction: Friction::NONE,
            grading: None,
            warm: Warm::Rest,
        }
    }

    /// The request with `friction`.
    pub fn with_friction(self, friction: Friction) -> Self {
        Request { friction, ..self }
    }

    /// The request on a mesh graded from `scenario`'s uniform `level` (the discretisation
    /// given to [`solve`]) as `grading` asks.
    pub fn with_grading(self, scenario: &'a Scenario, level: u32, grading: Grading) -> Self {
        let grading = Some(Graded {
            scenario,
            level,
            grading,
        });
        Request { grading, ..self }
    }

    /// The request started from `warm`.
    pub fn warm_from(self, warm: Warm<'a>) -> Self {
        Request { warm, ..self }
    }
}

/// Where Newton starts: from rest, or from an earlier solve's contact forces with the same rule
/// (ignored where they do not fit the points).
#[derive(Clone, Copy, Debug, Default)]
pub enum Warm<'a> {
    /// From rest.
    #[default]
    Rest,
    /// From the normal forces y of a frictionless solve.
    Forces(&'a [f64]),
    /// From the normal and tangential forces (y, z) of a solve with friction.
    Frictional(&'a [f64], &'a [f64]),
}

impl<'a> Warm<'a> {
    /// The normal forces (a frictionless start).
    fn forces(self) -> Option<&'a [f64]> {
        match self {
            Warm::Rest => None,
            Warm::Forces(y) | Warm::Frictional(y, _) => Some(y),
        }
    }

    /// The forces (y, z) of a start with friction.
    fn frictional(self) -> Option<(&'a [f64], &'a [f64])> {
        match self {
            Warm::Frictional(y, z) => Some((y, z)),
            _ => None,
        }
    }
}

/// A grading asked of a scenario's uniform level: its size is predicted from the scenario's
/// lines and obstacle ([`Scenario::graded_fits`]), its passes grade the discretisation given to
/// [`solve`] (its material, integration and model).
#[derive(Clone, Copy, Debug)]
pub struct Graded<'a> {
    /// The scenario.
    pub scenario: &'a Scenario,
    /// The uniform level graded.
    pub level: u32,
    /// At the edges or over the zone, and how many passes.
    pub grading: Grading,
}

/// A request's answer: the solution, and the passes of a graded mesh.
pub struct Solved {
    /// The solution (of the last grid, when graded; its timing sums every pass).
    pub sol: Solution,
    /// The passes and the final grid of a graded request (None: the solve on the mesh given).
    pub graded: Option<Grids>,
}

impl Solved {
    /// The discretisation the answer is on: the graded grid's, or `uniform` (the one given).
    pub fn disc<'a>(&'a self, uniform: &'a Discretization) -> &'a Discretization {
        self.graded
            .as_ref()
            .and_then(|g| g.disc.as_ref())
            .unwrap_or(uniform)
    }

    /// How many graded passes were made (0: the uniform level).
    pub fn passes(&self) -> u32 {
        self.graded.as_ref().map_or(0, |g| g.grid.passes)
    }

    /// Charge the uniform level's mesh work (assembly, ordering, factorisation) to the answer,
    /// for a caller that built `uniform` for this solve alone.
    pub fn charge_mesh_work(&mut self, uniform: &Discretization) {
        let work = Timing::mesh_work(uniform);
        self.sol.timing.add(&work);
        if let Some(g) = &mut self.graded {
            g.passes[0].ms += work.total;
        }
    }
}

/// Solve `request` on `disc`, or graded pass after pass from it
/// ([`crate::grading::passes`]); a graded mesh is refused before any pass when its memory estimate does not
/// fit ([`crate::grading::estimate`]), friction on a graded mesh is refused. The answer carries
/// what is wrong with it ([`Solution::warnings`]). `on_iteration` sees each Newton step and may
/// cancel the solve ([`SolveError::Cancelled`]).
///
/// # Errors
///
/// The request is out of range for the mesh or the method ([`SolveError::Input`],
/// [`SolveError::Range`]), does not fit the memory, or the solve was cancelled or failed.
pub fn solve(
    disc: &Discretization,
    request: &Request<'_>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<Solved, SolveError> {
    let Some(g) = request.grading.filter(|g| g.grading.grades()) else {
        let sol = solve_on(
            disc,
            &request.params,
            &request.friction,
            request.warm,
            opts,
            on_iteration,
        )?;
        return Ok(Solved { sol, graded: None });
    };
    if request.friction.is_on() {
        let grading = g.grading.to_string();
        return Err(InputFault::FrictionGraded { grading }.into());
    }
    let (sol, graded) = graded_passes(disc, g, request, opts, on_iteration)?;
    Ok(Solved {
        sol,
        graded: Some(graded),
    })
}

/// The passes of `g` from `disc`, refused before the first when the grading's memory
/// estimate does not fit ([`Scenario::graded_fits`]).
fn graded_passes(
    disc: &Discretization,
    g: Graded<'_>,
    request: &Request<'_>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<(Solution, Grids), SolveError> {
    g.scenario
        .graded_fits(g.level, disc.mesh.element, g.grading, |_| 0)?;
    let params = &request.params;
    crate::grading::passes::solve_graded(
        (g.level, disc),
        g.grading,
        params.rule,
        request.warm.forces(),
        &mut |d, initial| solve_contact(d, params, initial, opts, &mut *on_iteration),
    )
}

/// Solve on `disc` alone: with friction or without, and the answer's warnings.
fn solve_on(
    disc: &Discretization,
    params: &ContactParams,
    friction: &Friction,
    warm: Warm<'_>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<Solution, SolveError> {
    let mut sol = if friction.is_on() {
        Solution::from(friction::solve_frictional(
            disc,
            params,
            friction,
            warm.frictional(),
            opts,
            on_iteration,
        )?)
    } else {
        methods::solve_frictionless(disc, params, warm.forces(), opts, on_iteration)?
    };
    sol.warnings = warnings(disc, params, &sol);
    Ok(sol)
}

/// What is wrong with `sol`: the stiffness's warning first (a locked body makes any penalty
/// soft), then a penalty too soft for the depth (its answer is wrong, not merely poor), the
/// contact zone against the mesh, and a frictionless penalty's round-off.
fn warnings(disc: &Discretization, params: &ContactParams, sol: &Solution) -> Vec<Warning> {
    let penalty = params.method == Method::Penalty;
    let mut warnings: Vec<Warning> = disc.stiffness_warning().into_iter().collect();
    if penalty {
        warnings.extend(crate::contact::warnings::of_soft_penalty(
            &params.obstacle,
            &sol.points,
            params.epsilon,
            &sol.p,
        ));
    }
    warnings.extend(crate::contact::warnings::of_contact(
        &params.obstacle,
        &sol.points,
        &sol.p,
        disc.mesh.h(),
    ));
    if penalty && sol.friction.is_none() {
        warnings.extend(warning::of_round_off(
            params.obstacle.depth(),
            params.epsilon,
            &sol.p,
            disc.mesh.h(),
            disc.material.young,
        ));
    }
    warnings
}

/// Build on `disc` what a solve by `method` with `rule` needs beyond the mesh's own factor, so
/// that the solve costs only its iteration: the coupling G of the penalty, ALM and exact
/// constraint ([`crate::contact::coupling::of`]; milliseconds), or Nitsche's layer, couplings and
/// operator ([`nitsche::prepare`]; seconds at level 7). What fails is the solve's to report.
pub fn prepare(disc: &Discretization, rule: Rule, method: Method) {
    match method {
        Method::Nitsche { theta, gamma0 } => nitsche::prepare(disc, rule, theta, gamma0),
        _ => {
            crate::contact::coupling::of(disc, rule, &ContactPoints::on(disc, rule));
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

/// [`solve`] without friction or grading on `disc` alone, from the contact forces of an
/// earlier solve with the same rule (`initial`, ignored if it does not fit).
///
/// # Errors
///
/// As [`solve`]'s.
#[doc(hidden)]
pub fn solve_contact(
    disc: &Discretization,
    params: &ContactParams,
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<Solution, SolveError> {
    let request = Request::new(params.clone()).warm_from(initial.map_or(Warm::Rest, Warm::Forces));
    Ok(solve(disc, &request, opts, on_iteration)?.sol)
}

/// [`solve`] with `friction` on `disc` alone (built with [`Trace::Full`]), from the forces
/// (y, z) of an earlier solve with the same rule (`initial`, ignored if it does not fit).
///
/// # Errors
///
/// As [`solve`]'s.
#[doc(hidden)]
pub fn solve_friction(
    disc: &Discretization,
    params: &ContactParams,
    friction: &Friction,
    initial: Option<(&[f64], &[f64])>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<Solution, SolveError> {
    let warm = initial.map_or(Warm::Rest, |(y, z)| Warm::Frictional(y, z));
    let request = Request::new(params.clone())
        .with_friction(*friction)
        .warm_from(warm);
    Ok(solve(disc, &request, opts, on_iteration)?.sol)
}

/// A graded solve's answer in one piece: the final grid, its discretisation, the solution and
/// the passes ([`solve_graded`]).
#[doc(hidden)]
pub struct GradedSolve {
    /// The final grid.
    pub grid: crate::grading::GradedGrid,
    /// The final grid's discretisation (None: no pass was made; the uniform level's, given).
    pub graded: Option<Discretization>,
    /// The final pass's solution; its [`Timing`] sums every pass.
    pub sol: Solution,
    /// Every pass, the uniform level first.
    pub passes: Vec<Pass>,
}

impl GradedSolve {
    /// The final grid's discretisation: the graded one, or `uniform` (the one solved on).
    pub fn disc<'a>(&'a self, uniform: &'a Discretization) -> &'a Discretization {
        self.graded.as_ref().unwrap_or(uniform)
    }
}

/// [`solve`] of `params` without friction on `scenario`'s `level` (`uniform`, its
/// discretisation), graded as `grading` asks (0 passes: the uniform level's solve), from rest.
///
/// # Errors
///
/// As [`solve`]'s.
#[doc(hidden)]
pub fn solve_graded(
    scenario: &Scenario,
    (level, uniform): (u32, &Discretization),
    params: &ContactParams,
    grading: impl Into<Grading>,
    opts: &NewtonOptions,
) -> Result<GradedSolve, SolveError> {
    let g = Graded {
        scenario,
        level,
        grading: grading.into(),
    };
    let request = Request::new(params.clone());
    let (sol, g) = graded_passes(uniform, g, &request, opts, &mut |_| ControlFlow::Continue(()))?;
    Ok(GradedSolve {
        grid: g.grid,
        graded: g.disc,
        sol,
        passes: g.passes,
    })
}

/// A fresh solve of `scenario` as given (its level, element, rule, ε, obstacle and friction,
/// on the uniform level). With friction ([`crate::contact::friction`]) the mesh is factorised
/// once with the full trace last ([`Trace::Full`]) and the press and shift are solved on it.
///
/// # Errors
///
/// The scenario's mesh does not fit the memory, or [`solve`]'s.
pub fn solve_scenario(scenario: &Scenario) -> Result<(Discretization, Solution), SolveError> {
    let trace = if scenario.friction.is_on() {
        Trace::Full
    } else {
        Trace::Normal
    };
    let disc = scenario.discretize_traced(scenario.level, scenario.element, trace)?;
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
    let request = Request::new(params).with_friction(scenario.friction);
    let mut sol = solve(&disc, &request, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })?
    .sol;
    sol.timing.include_mesh_work(&disc);
    Ok((disc, sol))
}

/// Solve each of `requests` on `disc` in order. A frictionless request on `disc` itself (no
/// grading) that starts from rest starts from the contact forces of the last such one that
/// solved: a sweep over ε or the depth costs one mesh's work and a few Newton steps a value.
/// The first answer is charged with the mesh's work; a failure is its request's answer, and
/// the rest go on.
pub fn solve_each(disc: &Discretization, requests: &[Request<'_>]) -> Vec<Result<Solved, SolveError>> {
    let mut previous: Option<Vec<f64>> = None;
    let mut out = Vec::with_capacity(requests.len());
    for request in requests {
        let carries = !request.friction.is_on()
            && request.grading.is_none_or(|g| !g.grading.grades())
            && matches!(request.warm, Warm::Rest);
        let warm = match &previous {
            Some(y) if carries => Warm::Forces(y),
            _ => request.warm,
        };
        let warmed = Request {
            warm,
            ..request.clone()
        };
        let solved = solve(disc, &warmed, &NewtonOptions::default(), &mut |_| {
            ControlFlow::Continue(())
        });
        let first = out.is_empty();
        out.push(solved.map(|mut solved| {
            if first {
                solved.charge_mesh_work(disc);
            }
            if carries {
                previous = Some(solved.sol.newton.forces.clone());
            }
            solved
        }));
    }
    out
}

/// [`solve_each`] of frictionless requests of `params` on `disc`: their solutions.
pub fn sweep(disc: &Discretization, params: &[ContactParams]) -> Vec<Result<Solution, SolveError>> {
    let requests: Vec<Request<'_>> = params.iter().cloned().map(Request::new).collect();
    solve_each(disc, &requests)
        .into_iter()
        .map(|r| r.map(|solved| solved.sol))
        .collect()
}

#[cfg(test)]
mod graded_tests;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::SolveError;
    use crate::scenario::Scenario;

    /// Friction asked of a graded mesh is refused by the entry before any pass, naming the
    /// grading; the same request on the uniform level solves.
    #[test]
    fn friction_on_a_graded_mesh_is_refused_before_any_pass() {
        use crate::contact::friction::{Friction, Law};
        use crate::grading::RefineEdges;
        // Kikuchi's example modelled whole (friction needs both sides of Γ_C free).
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-paper-full.toml");
        let scenario = Scenario::load(std::path::Path::new(path)).unwrap();
        let disc = scenario
            .discretize_traced(1, scenario.element, Trace::Full)
            .unwrap();
        let params = ContactParams::by_epsilon(scenario.rule, 1e-6, scenario.obstacle.clone());
        let friction = Friction {
            law: Law::Coulomb { mu: 0.3 },
            ..Friction::NONE
        };
        let request = Request::new(params).with_friction(friction);
        let go_on = &mut |_: &Iteration| ControlFlow::Continue(());
        let opts = NewtonOptions::default();
        let grading = Grading::Edges(RefineEdges::Passes(2));
        let graded = request.clone().with_grading(&scenario, 1, grading);
        match solve(&disc, &graded, &opts, go_on) {
            Err(SolveError::Input(InputFault::FrictionGraded { grading: g })) => {
                assert_eq!(g, grading.to_string())
            }
            Err(e) => panic!("{e}"),
            Ok(_) => panic!("friction on a graded mesh solved"),
        }
        let uniform = solve(&disc, &request, &opts, go_on).unwrap();
        assert!(uniform.graded.is_none() && uniform.sol.friction.is_some());
    }

    /// A sweep on one mesh gives each instance the solution a fresh solve
    /// gives, charges the mesh's work to the first only, and goes on past a failure.
    #[test]
    fn a_sweep_equals_fresh_solves_and_goes_on_past_a_failure() {
        let mut scenario = Scenario::paper();
        scenario.level = 1;
        let disc = scenario.discretize(1, scenario.element).unwrap();
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
