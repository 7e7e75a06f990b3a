//! The numerical work behind the lab, with no terminal in it: an [`Engine`] owns the
//! discretisation cache (least recently used last out, within a memory budget) and the warm
//! start of the next contact solve (docs/design.md §3), and runs solves, stresses, inf-sup
//! estimates and work–precision studies ([`Studying`]). The worker thread
//! ([`super::worker`]) and the synchronous driver ([`super::settle()`]) drive it.

use std::cell::RefCell;
use std::collections::HashMap;
use std::ops::ControlFlow;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

use crate::contact::newton::{Iteration, NewtonOptions};
use crate::contact::{ContactPoints, Method, Rule, carried_forces};
use crate::discretization::Discretization;
use crate::error::SolveError;
use crate::fem::Integration;
use crate::fem::memory::Limits;
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::solve::{self, Request};

use super::beta::{self, InfSup};
use super::build::Plan;
pub use super::build::{Built, Finished};
use super::eta::Eta;
use super::lab_error::LabError;
use super::protocol::{
    InfSupKey, MAX_APP_LEVEL, Progress, Response, SolveRequest, Solved, StressRequest, Study, StudyKey,
};
use super::shown::Shown;

mod friction;
mod graded;
pub mod studying;
#[cfg(test)]
mod tests;

pub use studying::Studying;

/// How many discretisations (meshes with their factorisations) are kept at most…
const CACHE_SIZE: usize = 4;
/// …and how much memory their estimated peaks ([`crate::fem::memory::Sizes::peak_bytes`], an
/// upper bound on what a kept one holds) may add up to, bytes (the newest is kept whatever
/// its size): in the default scenario, level 7 of Q1 or P1 beside level 6 (1.31 + 0.31 GiB)
/// or level 6 of Q2 beside level 5 (1.41 + 0.33 GiB), but not level 7 of Q2 (6.16 GiB).
pub const CACHE_BYTES: u64 = 2 << 30;

/// What a finished build is for ([`Engine::adopt`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Use {
    /// Built while idle, for a step to a neighbouring level.
    Background,
    /// A solve waits for it.
    Solve,
    /// An inf-sup estimate waits for it.
    Estimate,
}

/// The points a solve's contact forces live on: the mesh, the rule and the kind of method
/// (Nitsche's state lives on its own points, a point two edges share appearing twice; the
/// other methods' on the rule's).
#[derive(Clone, Copy, Debug, PartialEq)]
struct ForcePoints {
    /// The mesh level.
    level: u32,
    /// The element.
    element: Element,
    /// The contact rule.
    rule: Rule,
    /// Whether they are Nitsche's edge points.
    nitsche: bool,
    /// The stiffness's integration (the forces balance its K).
    integration: Integration,
}

/// What the last contact solve leaves for the next to start from.
struct Warm {
    /// The points its forces belong to.
    points: ForcePoints,
    /// The contact forces, the Newton iteration's state (docs/design.md §3).
    forces: Vec<f64>,
    /// The abscissae of the rule's points and the pressure p there: carried to another mesh or
    /// rule ([`carried_forces`]), they start its iteration next to its solution (a level step
    /// at level 7 takes one to three Newton steps instead of 12 to 75, BENCHMARKS.md).
    x: Vec<f64>,
    p: Vec<f64>,
    /// The method (with its parameters): what a background build prepares ([`Plan::method`]).
    method: Method,
    /// The tangential forces of a solve with friction (None without): with `forces`, where
    /// the next friction solve on the same points starts ([`crate::solve::solve_friction`]).
    z: Option<Vec<f64>>,
}

/// Owns the discretisation cache (least recently used last out) and the warm start.
pub struct Engine {
    /// The scenario, its integration that of the last request ([`Engine::follow`]): the
    /// cache keeps meshes of either, and serves those of this one.
    pub(in crate::tui) scenario: Scenario,
    cache: Vec<(u32, Element, Arc<Discretization>)>,
    /// The last contact solve's state: where the next one starts ([`Warm`]).
    warm: Option<Warm>,
    /// The last graded solve's grid and state: where the next graded one of the same level,
    /// element, integration and grading starts ([`graded::LastGraded`]).
    last_graded: Option<graded::LastGraded>,
    /// The last study (a study takes seconds; a second app on the same engine reuses it),
    /// shared with the study's thread ([`Studying`]).
    study: Arc<Mutex<Option<Arc<Study>>>>,
    /// How long builds take here (for the time left)…
    eta: Eta,
    /// …and Nitsche's preparation ([`crate::solve::prepare`]).
    prepare_eta: Eta,
    /// Levels whose background build failed (too large for this machine): not tried again.
    unfit: Vec<(u32, Element)>,
    /// The estimated peak of each mesh asked about (computed once: it lays out the mesh's
    /// lines and contact points, megabytes on a fine grid).
    peaks: RefCell<HashMap<(u32, Element), u64>>,
    /// What a graded solve's estimate is checked against before anything is assembled: None, the
    /// memory this process may use when it is asked ([`Limits::of_process`]); a test sets
    /// limits of its own, derived from the estimate.
    pub limits: Option<Limits>,
}

impl Engine {
    /// An engine for `scenario` with an empty cache.
    pub fn new(scenario: Scenario) -> Self {
        Engine {
            scenario,
            cache: Vec::new(),
            warm: None,
            last_graded: None,
            study: Arc::default(),
            eta: Eta::default(),
            prepare_eta: Eta::preparing(),
            unfit: Vec::new(),
            peaks: RefCell::default(),
            limits: None,
        }
    }

    /// Serve and build meshes integrated as `integration` from now on (the lab's `i`; the
    /// meshes of the other stay cached for a switch back).
    pub fn follow(&mut self, integration: Integration) {
        self.scenario.integration = integration;
    }

    /// Whether the cached `entry` is the mesh of `level` with `element` integrated as the
    /// scenario now is.
    fn is(&self, entry: &(u32, Element, Arc<Discretization>), level: u32, element: Element) -> bool {
        (entry.0, entry.1) == (level, element) && entry.2.integration == self.scenario.integration
    }

    /// The unknowns of the mesh at `level` for `element`, counted without building it.
    fn unknowns(&self, level: u32, element: Element) -> usize {
        self.scenario.n_dofs(level, element)
    }

    /// The memory guard's estimated peak of the mesh of `level` with `element`, bytes.
    fn peak(&self, level: u32, element: Element) -> u64 {
        *self
            .peaks
            .borrow_mut()
            .entry((level, element))
            .or_insert_with(|| self.scenario.sizes(level, element).peak_bytes())
    }

    /// What building `level` with `element` for the rule and method of the last solve is
    /// expected to cost.
    pub(in crate::tui) fn plan(&self, level: u32, element: Element) -> Plan {
        let (rule, method) = self
            .warm
            .as_ref()
            .map_or((self.scenario.rule, self.scenario.method), |w| {
                (w.points.rule, w.method)
            });
        self.plan_for(level, element, rule, method)
    }

    /// What building `level` with `element` for a solve with `rule` and `method` is expected
    /// to cost: the mesh unless it is built, and the method's preparation when it factorises
    /// K again ([`crate::solve::preparing_factorises`]; the rest of it is dense work on Γ_C's
    /// points, not estimated).
    pub(in crate::tui) fn plan_for(&self, level: u32, element: Element, rule: Rule, method: Method) -> Plan {
        let unknowns = self.unknowns(level, element);
        let built = self.peek(level, element);
        let mut plan = Plan {
            level,
            element,
            unknowns,
            rule,
            method,
            peak: self.peak(level, element),
            estimate_ms: if built.is_some() {
                0.0
            } else {
                self.eta.predict_ms(unknowns)
            },
        };
        if plan.prepares() && built.is_none_or(|d| crate::solve::preparing_factorises(&d, method)) {
            plan.estimate_ms += self.prepare_eta.predict_ms(unknowns);
        }
        plan
    }

    /// Whether the discretisations `meshes` (level, element) may be kept together: their
    /// estimated peaks add up to [`CACHE_BYTES`] at most.
    pub fn fits(&self, meshes: &[(u32, Element)]) -> bool {
        let bytes = meshes
            .iter()
            .map(|&(level, element)| self.peak(level, element))
            .fold(0, u64::saturating_add);
        bytes <= CACHE_BYTES
    }

    /// The mesh of `level` with `element` if it is built (its place in the cache unchanged).
    pub(in crate::tui) fn peek(&self, level: u32, element: Element) -> Option<Arc<Discretization>> {
        self.cache
            .iter()
            .find(|entry| self.is(entry, level, element))
            .map(|(_, _, d)| d.clone())
    }

    /// Whether the mesh of `level` with `element` is built and, for `solve` (a rule and
    /// method), prepared ([`crate::solve::needs_preparing`]).
    pub(in crate::tui) fn ready(&self, level: u32, element: Element, solve: Option<(Rule, Method)>) -> bool {
        self.peek(level, element).is_some_and(|disc| {
            solve.is_none_or(|(rule, method)| !crate::solve::needs_preparing(&disc, rule, method))
        })
    }

    pub(in crate::tui) fn cached(&mut self, level: u32, element: Element) -> Option<Arc<Discretization>> {
        let i = self
            .cache
            .iter()
            .position(|entry| self.is(entry, level, element))?;
        let entry = self.cache.remove(i);
        let disc = entry.2.clone();
        self.cache.push(entry);
        Some(disc)
    }

    fn discretization(&mut self, level: u32, element: Element) -> Result<Arc<Discretization>, SolveError> {
        if let Some(disc) = self.cached(level, element) {
            return Ok(disc);
        }
        let t = Instant::now();
        let disc = Arc::new(self.scenario.discretize(level, element)?);
        self.eta
            .record(self.unknowns(level, element), t.elapsed().as_secs_f64() * 1e3);
        self.cache.push((level, element, disc.clone()));
        self.evict();
        Ok(disc)
    }

    /// Drop the least recently used discretisations beyond [`CACHE_SIZE`] and [`CACHE_BYTES`]
    /// (the newest is kept whatever its size), the neighbouring levels of the mesh in use last
    /// (they are what `]` and `[` ask for; the meshes estimates were built on go first).
    fn evict(&mut self) {
        loop {
            let kept: Vec<(u32, Element)> = self.cache.iter().map(|(l, e, _)| (*l, *e)).collect();
            let Some(&(level, element)) = kept.last() else {
                return;
            };
            if kept.len() <= 1 || (kept.len() <= CACHE_SIZE && self.fits(&kept)) {
                return;
            }
            let neighbour = |&(l, e): &(u32, Element)| e == element && l.abs_diff(level) == 1;
            let victim = kept[..kept.len() - 1]
                .iter()
                .position(|m| !neighbour(m))
                .unwrap_or(0);
            self.cache.remove(victim);
        }
    }

    /// The level to build in the background next: the next finer, then the next coarser
    /// level of the mesh last used, up to [`MAX_APP_LEVEL`], when it is not built yet (or,
    /// after a Nitsche solve, not prepared for it), did not fail before, and [`Engine::fits`]
    /// beside the mesh in use.
    pub fn next_prefetch(&self) -> Option<(u32, Element)> {
        let (level, element, _) = self.cache.last()?;
        let last = self.warm.as_ref().map(|w| (w.points.rule, w.method));
        let candidates = [level.checked_add(1), level.checked_sub(1)];
        candidates
            .into_iter()
            .flatten()
            .map(|l| (l, *element))
            .find(|&(l, e)| {
                l <= MAX_APP_LEVEL
                    && !self.ready(l, e, last)
                    && !self.unfit.contains(&(l, e))
                    && self.fits(&[(*level, *element), (l, e)])
            })
    }

    /// Keep a finished build of `level` with `element` as its `use` says, and give it back
    /// (None when it failed: a failed build is not tried in the background again). A solve's
    /// becomes the mesh in use; an estimate's or a background one goes just behind the mesh
    /// in use in the cache's order, kept while the budget allows (an estimate holds its mesh
    /// meanwhile); a background one for another element than the one in use is dropped, and any
    /// one integrated otherwise than the scenario now is ([`Engine::follow`]).
    pub fn adopt(
        &mut self,
        level: u32,
        element: Element,
        built: Built,
        use_: Use,
    ) -> Option<Arc<Discretization>> {
        let Finished {
            disc,
            build_ms,
            prepare_ms,
        } = match built {
            Ok(built) => built,
            Err(_) => {
                self.unfit.push((level, element));
                return None;
            }
        };
        if let Some(ms) = build_ms {
            self.eta.record(disc.n_dofs(), ms);
        }
        if let Some(ms) = prepare_ms {
            self.prepare_eta.record(disc.n_dofs(), ms);
        }
        let in_use = self.cache.last().map(|(_, e, _)| *e);
        // A build started before a switch of the integration (`i`) is not kept: the next
        // request wants the other.
        let stale = disc.integration != self.scenario.integration;
        if stale || (use_ == Use::Background && in_use != Some(element)) || self.has(level, element) {
            return Some(disc);
        }
        let at = match use_ {
            Use::Solve => self.cache.len(),
            Use::Estimate | Use::Background => self.cache.len().saturating_sub(1),
        };
        self.cache.insert(at, (level, element, disc.clone()));
        self.evict();
        Some(disc)
    }

    /// Whether the mesh of `level` with `element` is built.
    pub fn has(&self, level: u32, element: Element) -> bool {
        self.cache.iter().any(|entry| self.is(entry, level, element))
    }

    /// Run `req`; `is_current(generation)` false cancels it; progress goes to `report`.
    pub fn solve(
        &mut self,
        req: &SolveRequest,
        is_current: &dyn Fn(u64) -> bool,
        report: &mut dyn FnMut(Response),
    ) -> Response {
        let t = Instant::now();
        let generation = req.generation;
        let key = req.key;
        self.follow(key.integration);
        // Graded: on the last graded grid first, kept while the contact edges stay in its band.
        if let Some(kept) = self.on_graded_grid(req, is_current, report, t) {
            return kept;
        }
        // A graded solve's memory, estimated from its lines before anything is assembled.
        if let Err(e) = self.graded_fits(&key) {
            return Response::Solved {
                generation,
                result: Err(e.into()),
            };
        }
        if self.cached(key.level, key.element).is_none() {
            let unknowns = self.unknowns(key.level, key.element);
            report(Response::Progress {
                generation,
                progress: Progress::Assembling {
                    level: key.level,
                    unknowns,
                    started: Instant::now(),
                    estimate_ms: self.eta.predict_ms(unknowns),
                    method: None,
                },
            });
        }
        let disc = match self.discretization(key.level, key.element) {
            Ok(d) => d,
            Err(e) => {
                return Response::Solved {
                    generation,
                    result: Err(e.into()),
                };
            }
        };
        let params = self.contact_params(&key);
        let nitsche = matches!(key.method, Method::Nitsche { .. });
        let points = ForcePoints {
            level: key.level,
            element: key.element,
            rule: key.rule,
            nitsche,
            integration: key.integration,
        };
        // The last forces if they live on these points; else the last pressure carried to
        // the rule's points (Nitsche shares them between its edge points).
        let (warm, carried) = match &self.warm {
            Some(w) if w.points == points => (Some(w.forces.clone()), false),
            Some(w) => {
                let to = ContactPoints::on(&disc, key.rule);
                (Some(carried_forces(&w.x, &w.p, &to)), true)
            }
            None => (None, false),
        };
        let mut newton = |start: Option<&[f64]>| {
            let warm = start.map_or(solve::Warm::Rest, solve::Warm::Forces);
            let request = Request::new(params.clone()).warm_from(warm);
            solve::solve(&disc, &request, &NewtonOptions::default(), &mut |it| {
                newton_step(generation, is_current, &mut *report, it)
            })
            .map(|solved| solved.sol)
        };
        if key.friction.is_on() {
            return self.solve_friction(req, disc, &params, points, t, is_current, report);
        }
        // Graded at the contact edges: the passes of crate::grading from the uniform level's
        // solve, the final grid's discretisation shown (not cancellable between its passes).
        if key.refine_edges.grades() {
            return self.graded(req, &disc, &params, t);
        }
        let mut result = newton(warm.as_deref());
        // A carried start is a guess: one that does not lead to convergence is not the
        // method's answer, so the solve starts again from rest.
        if carried && result.as_ref().is_ok_and(|s| !s.newton.converged) {
            result = newton(None);
        }
        self.answer(generation, key, disc, points, t, result)
    }

    /// The reply to the solve `generation` of `key` on `disc` started at `t`: its solution
    /// shown (and its forces, and friction's, kept to warm the next solve on `points`), a
    /// cancellation, or its failure.
    fn answer(
        &mut self,
        generation: u64,
        key: super::protocol::SolveKey,
        disc: Arc<Discretization>,
        points: ForcePoints,
        t: Instant,
        result: Result<crate::contact::solution::Solution, SolveError>,
    ) -> Response {
        match result {
            Ok(solution) => {
                self.warm = Some(Warm {
                    points,
                    forces: solution.newton.forces.clone(),
                    x: solution.points.points.iter().map(|q| q.x).collect(),
                    p: solution.p.clone(),
                    method: key.method,
                    z: solution.friction.as_ref().map(|f| f.z.clone()),
                });
                Response::Solved {
                    generation,
                    result: Ok(Arc::new(Solved {
                        key,
                        disc,
                        shown: Shown::new(&self.scenario, &solution),
                        solution,
                        displacement: OnceLock::new(),
                        total_ms: t.elapsed().as_secs_f64() * 1e3,
                        stresses: OnceLock::new(),
                        regrade: None,
                    })),
                }
            }
            Err(SolveError::Cancelled) => Response::Cancelled { generation },
            Err(e) => Response::Solved {
                generation,
                result: Err(e.into()),
            },
        }
    }

    /// Compute the displacement of `solved` (kept in it, shared with the app).
    pub fn displace(solved: &Solved) -> Response {
        solved.u();
        Response::Displaced { key: solved.key }
    }

    /// Compute the stresses of `req.solved` on `scenario`'s material (kept in the solution,
    /// shared with the app).
    pub fn stresses(scenario: &Scenario, req: &StressRequest) -> Response {
        // Success or failure, the result is kept in the solution for the view to show.
        let _ = req.solved.stress_field(scenario);
        Response::Stresses { key: req.solved.key }
    }

    /// The work–precision study of `key` ([`Studying::run`]), here.
    pub fn study(&self, key: &StudyKey, report: &mut dyn FnMut(Progress)) -> Result<Arc<Study>, LabError> {
        self.studying(key)?.run(report)
    }

    /// The work–precision study of `key`, ready to run on a thread of its own: the scenario, the
    /// estimate of each stage (from this engine's timings) and the engine's place for the
    /// finished study. An error if the engine runs another scenario.
    pub fn studying(&self, key: &StudyKey) -> Result<Studying, LabError> {
        if key.scenario != self.scenario.name {
            return Err(LabError::OtherScenario {
                runs: self.scenario.name.clone(),
                asked: key.scenario.clone(),
            });
        }
        // The reference: a Q2 build and an active-set solve of about the same cost (nothing
        // when the cache holds it).
        let reference = 2.0
            * self
                .eta
                .predict_ms(self.unknowns(key.reference_level(), Element::Q2));
        let mut elements: Vec<Element> = key.schemes.iter().map(|s| s.0).collect();
        elements.dedup();
        // One build per element and method at each level.
        let levels = (0..=key.max_level).map(|level| {
            let unknowns: usize = elements
                .iter()
                .map(|&e| key.methods.len() * self.unknowns(level, e))
                .sum();
            self.eta.predict_ms(unknowns) * studying::cost_factor(key.refine_edges)
        });
        Ok(Studying {
            scenario: Scenario {
                integration: key.integration,
                friction: *key.friction,
                ..self.scenario.clone()
            },
            key: key.clone(),
            estimates_ms: std::iter::once(reference).chain(levels).collect(),
            kept: self.study.clone(),
        })
    }

    /// The inf-sup estimate of `key`, on the mesh of the current integration (β_h does not
    /// depend on it: A is the H¹ Gram matrix of (7), [`crate::infsup`]).
    pub fn inf_sup(&mut self, key: InfSupKey) -> Result<InfSup, LabError> {
        let disc = self.discretization(key.level, key.element)?;
        Ok(beta::estimate(&disc, key.rule)?)
    }
}

/// One Newton iteration of the solve `generation`: reported as progress, or the solve
/// cancelled once `is_current(generation)` is false.
fn newton_step(
    generation: u64,
    is_current: &dyn Fn(u64) -> bool,
    report: &mut dyn FnMut(Response),
    it: &Iteration,
) -> ControlFlow<()> {
    if !is_current(generation) {
        return ControlFlow::Break(());
    }
    report(Response::Progress {
        generation,
        progress: Progress::Newton {
            iteration: it.iteration,
            residual: it.residual,
            active: it.active,
        },
    });
    ControlFlow::Continue(())
}
