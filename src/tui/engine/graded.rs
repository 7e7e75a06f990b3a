//! The lab's graded solve (`E`), at the contact edges or over the contact zone: the library's
//! entry ([`solve::solve`]) from the uniform level's discretisation, its final grid's discretisation kept with the solution so
//! that every view (the mesh scene's lines, the pressures, the stresses) shows the graded
//! mesh. Each pass builds its own mesh and factor (nothing of the cache's work carries over:
//! the lines changed), so the graded meshes are not in the cache; the last one is kept
//! ([`LastGraded`]): a re-solve of the same level, element, integration and grading after an
//! ε, depth, rule or method change solves on it first, warm-started, and keeps it when the
//! contact edges found there lie inside its refined band ([`GradedGrid::holds_edges`]; a zone
//! grid: the whole contact zone inside its finest band, [`GradedGrid::holds_zone`]): no new
//! grid, no new factor. Otherwise it grades again from the level's uniform solve, as a fresh
//! `riplab solve --refine-edges N` does ([`Regrade`] says which in the status line).

use std::ops::ControlFlow;
use std::sync::{Arc, OnceLock};
use std::time::Instant;

use crate::contact::newton::NewtonOptions;
use crate::contact::solution::Solution;
use crate::contact::{ContactParams, ContactPoints, Method, Rule, carried_forces};
use crate::discretization::Discretization;
use crate::error::SolveError;
use crate::fem::Integration;
use crate::fem::memory::Limits;
use crate::grading::{GradedGrid, Grading};
use crate::mesh::Element;
use crate::solve::{self, Request};

use super::super::protocol::{Response, SolveKey, SolveRequest, Solved};
use super::super::regrade::Regrade;
use super::super::shown::Shown;
use super::Engine;

/// The last graded solve: its grid, the grid's discretisation and where its Newton ended.
pub(super) struct LastGraded {
    /// The settings it serves: a solve with these grades the same level the same way.
    serves: (u32, Element, Integration, Grading),
    /// The graded grid (after at least one pass).
    grid: GradedGrid,
    /// Its discretisation (assembled, ordered and factorised).
    disc: Arc<Discretization>,
    /// The rule and whether the method was Nitsche's: what its forces live on.
    points: (Rule, bool),
    /// The contact forces, the Newton iteration's state.
    forces: Vec<f64>,
    /// The abscissae of the rule's points and p there, to carry to another rule.
    x: Vec<f64>,
    p: Vec<f64>,
}

impl LastGraded {
    /// What `key` leaves of `grid`, `disc` and `sol` for the next graded solve (None for a grid
    /// without a pass: nothing to keep).
    fn of(key: &SolveKey, grid: GradedGrid, disc: Arc<Discretization>, sol: &Solution) -> Option<Self> {
        (grid.passes > 0).then(|| LastGraded {
            serves: serves(key),
            grid,
            disc,
            points: (key.rule, is_nitsche(key.method)),
            forces: sol.newton.forces.clone(),
            x: sol.points.points.iter().map(|q| q.x).collect(),
            p: sol.p.clone(),
        })
    }
}

/// The settings a graded grid serves: the level, element, integration and grading of `key`.
fn serves(key: &SolveKey) -> (u32, Element, Integration, Grading) {
    (key.level, key.element, key.integration, key.refine_edges)
}

fn is_nitsche(method: Method) -> bool {
    matches!(method, Method::Nitsche { .. })
}

impl Engine {
    /// The contact parameters of `key`: `exact` has no ε ([`Method::resolve`]); the others
    /// keep the lab's.
    pub(super) fn contact_params(&self, key: &SolveKey) -> ContactParams {
        ContactParams {
            rule: key.rule,
            method: key.method,
            epsilon: if key.method.uses_epsilon() {
                key.epsilon
            } else {
                0.0
            },
            obstacle: self.scenario.obstacle.with_depth(key.depth),
        }
    }

    /// Solve `req` on the last graded grid if it serves `req`'s settings, warm-started from
    /// its last forces (or its pressure carried to another rule's points, and from rest if that
    /// does not converge); the solve when the contact edges it finds lie inside the grid's
    /// band (a zone grid: its contact zone), the cancellation when `is_current` says so, None otherwise (graded again from the
    /// uniform level: [`Engine::graded`]). A uniform solve lets the last graded grid go (its
    /// discretisation may hold gigabytes at level 7, outside the cache's budget).
    pub(super) fn on_graded_grid(
        &mut self,
        req: &SolveRequest,
        is_current: &dyn Fn(u64) -> bool,
        report: &mut dyn FnMut(Response),
        t: Instant,
    ) -> Option<Response> {
        let key = req.key;
        let generation = req.generation;
        if !key.refine_edges.grades() {
            self.last_graded = None;
            return None;
        }
        // Graded solves take no friction: the friction solve refuses them
        // (LabError::GradedFriction), never this grid's frictionless answer.
        if key.friction.is_on() {
            return None;
        }
        let last = self.last_graded.as_ref().filter(|l| l.serves == serves(&key))?;
        let params = self.contact_params(&key);
        let disc = last.disc.clone();
        let carried = last.points != (key.rule, is_nitsche(key.method));
        let start = match carried {
            false => last.forces.clone(),
            true => carried_forces(&last.x, &last.p, &ContactPoints::on(&disc, key.rule)),
        };
        let mut newton = |start: Option<&[f64]>| {
            let warm = start.map_or(solve::Warm::Rest, solve::Warm::Forces);
            let request = Request::new(params.clone()).warm_from(warm);
            solve::solve(&disc, &request, &NewtonOptions::default(), &mut |it| {
                super::newton_step(generation, is_current, &mut *report, it)
            })
            .map(|solved| solved.sol)
        };
        let mut result = newton(Some(&start));
        if carried && result.as_ref().is_ok_and(|s| !s.newton.converged) {
            result = newton(None);
        }
        let sol = match result {
            Err(SolveError::Cancelled) => return Some(Response::Cancelled { generation }),
            Ok(sol) if sol.newton.converged => sol,
            // No answer on this grid: graded afresh (and said so).
            _ => {
                self.last_graded = None;
                return None;
            }
        };
        let holds = match key.refine_edges {
            Grading::Edges(_) => last.grid.holds_edges(&sol.points, &sol.p),
            Grading::Zone(_) => last.grid.holds_zone(&sol.points, &sol.p),
        };
        if !holds {
            return None;
        }
        let grid = last.grid.clone();
        self.last_graded = LastGraded::of(&key, grid, disc.clone(), &sol);
        Some(self.solved(req, disc, sol, t, Regrade::Kept))
    }

    /// Refuse a graded solve of `key` whose estimate from its lines
    /// ([`crate::grading::estimate`]) exceeds what [`Engine::limits`] leave, before its
    /// uniform level or any pass is assembled, naming the level, the element, the grading
    /// and the memory (the status line shows it). Nothing to check without a grading, nor
    /// with friction (which grading does not take: [`super::super::lab_error::LabError::GradedFriction`]).
    pub(in crate::tui) fn graded_fits(&self, key: &SolveKey) -> Result<(), SolveError> {
        if !key.refine_edges.grades() || key.friction.is_on() {
            return Ok(());
        }
        let mut scenario = self.scenario.clone();
        scenario.obstacle = scenario.obstacle.with_depth(key.depth);
        let limits = self.limits.clone().unwrap_or_else(Limits::of_process);
        scenario.graded_fits_within((key.level, key.element), key.refine_edges, |_| 0, &limits)
    }

    /// Solve `req` on `uniform` graded as its key asks, started at `t`: the library's entry ([`solve::solve`]) from
    /// the level's uniform solve (again, when the last graded grid of these settings no longer
    /// held the contact edges).
    pub(super) fn graded(
        &mut self,
        req: &SolveRequest,
        uniform: &Arc<Discretization>,
        params: &ContactParams,
        t: Instant,
    ) -> Response {
        let key = req.key;
        let again = self
            .last_graded
            .as_ref()
            .is_some_and(|l| l.serves == serves(&key));
        let request = Request::new(params.clone()).with_grading(&self.scenario, key.level, key.refine_edges);
        // Not cancellable between its passes: each pass's mesh is built anew.
        let graded = solve::solve(uniform, &request, &NewtonOptions::default(), &mut |_| {
            ControlFlow::Continue(())
        });
        // A request that grades is answered with its grids.
        let graded = graded.map(|s| (s.sol, s.graded.expect("a graded request's grids")));
        match graded {
            Ok((sol, g)) => {
                let disc = g.disc.map_or_else(|| uniform.clone(), Arc::new);
                let passes = g.grid.passes;
                self.last_graded = LastGraded::of(&key, g.grid, disc.clone(), &sol);
                let regrade = match again {
                    true => Regrade::Regraded { passes },
                    false => Regrade::Graded { passes },
                };
                self.solved(req, disc, sol, t, regrade)
            }
            Err(e) => Response::Solved {
                generation: req.generation,
                result: Err(e.into()),
            },
        }
    }

    /// The reply of a graded solve of `req` on `disc`.
    fn solved(
        &self,
        req: &SolveRequest,
        disc: Arc<Discretization>,
        solution: Solution,
        t: Instant,
        regrade: Regrade,
    ) -> Response {
        Response::Solved {
            generation: req.generation,
            result: Ok(Arc::new(Solved {
                key: req.key,
                disc,
                shown: Shown::new(&self.scenario, &solution),
                solution,
                displacement: OnceLock::new(),
                total_ms: t.elapsed().as_secs_f64() * 1e3,
                stresses: OnceLock::new(),
                regrade: Some(regrade),
            })),
        }
    }
}
