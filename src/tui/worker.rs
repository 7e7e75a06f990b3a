//! The numerical work behind the app: an [`Engine`] that owns the discretisation cache and runs
//! solves and inf-sup estimates, a [`Worker`] thread that drives it from a channel, and
//! [`settle`], which drives it synchronously (for `render` and tests).

use std::cell::RefCell;
use std::collections::{HashMap, VecDeque};
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};
use std::time::{Duration, Instant};

use crate::contact::penalty::NewtonOptions;

use crate::contact::ContactParams;
use crate::contact::{Method, Rule, carried_forces};
use crate::discretization::Discretization;
use crate::error::SolveError;
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::solve::solve_contact;

use crate::scheme::Scheme;
use crate::study::{StudyRow, convergence};

use super::app::{App, Command, MAX_APP_LEVEL, Msg};
use super::beta::{self, InfSup};
use super::build::{Build, Plan};
pub use super::build::{Built, Finished};
use super::estimating::Estimating;
use super::eta::Eta;
use super::job::{Lane, Sink};
use super::protocol::{
    InfSupKey, InfSupRequest, Progress, Response, SolveRequest, Solved, StressRequest, Study, StudyKey,
    StudyRequest,
};
use super::shown::Shown;

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

/// What the last contact solve leaves for the next to start from.
struct Warm {
    /// The mesh, rule and kind of method its forces belong to: Nitsche's state lives on its
    /// own points (a point two edges share appears twice), the other methods' on the rule's.
    on: (u32, Element, Rule, bool),
    /// The contact forces, the Newton iteration's state (docs/design.md §3).
    forces: Vec<f64>,
    /// The abscissae of the rule's points and the pressure p there: carried to another mesh or
    /// rule ([`carried_forces`]), they start its iteration next to its solution (a level step
    /// at level 7 takes one to three Newton steps instead of 12 to 75, BENCHMARKS.md).
    x: Vec<f64>,
    p: Vec<f64>,
    /// The method (with its parameters): what a background build prepares ([`Plan::method`]).
    method: Method,
}

/// A work–precision study taken from the engine ([`Engine::studying`]), to run anywhere.
pub struct Studying {
    scenario: Scenario,
    key: StudyKey,
    /// The estimated time of each stage, ms: the reference, then each level.
    estimates_ms: Vec<f64>,
    /// The engine's last study: reused if it is this one, replaced by this one when it ends.
    kept: Arc<Mutex<Option<Arc<Study>>>>,
}

impl Studying {
    /// Each of the key's schemes with each of its methods at levels 0..=max against the Q2
    /// reference one level finer, at the key's ε (fresh solves, so the timings are
    /// comparable); each stage (the reference, then each level) is announced to `report` with
    /// its estimate. A method a scheme cannot run (`exact` on a rule with a kernel) gives rows
    /// that say why.
    pub fn run(self, report: &mut dyn FnMut(Progress)) -> Result<Arc<Study>, String> {
        let kept = || self.kept.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(study) = kept().as_ref().filter(|s| s.key == self.key) {
            return Ok(study.clone());
        }
        let key = &self.key;
        report(Progress::Study {
            level: None,
            started: Instant::now(),
            estimate_ms: self.estimates_ms[0],
        });
        let dir = crate::cache::default_dir();
        let (reference, _) = crate::cache::reference(&self.scenario, key.reference_level(), dir.as_deref())
            .map_err(|e| e.to_string())?;
        let mut rows = Vec::new();
        for (level, &estimate_ms) in (0..=key.max_level).zip(&self.estimates_ms[1..]) {
            report(Progress::Study {
                level: Some(level),
                started: Instant::now(),
                estimate_ms,
            });
            for &method in &key.methods {
                rows.extend(convergence(
                    &self.scenario,
                    &reference,
                    &key.schemes,
                    &[level],
                    Some(method),
                    key.epsilon,
                ));
            }
        }
        // The key's order: by scheme, then method, then ascending level.
        let scheme_index = |r: &StudyRow| {
            key.schemes
                .iter()
                .position(|&(e, rule)| Scheme::new(e, rule).label() == r.scheme)
        };
        let method_index = |r: &StudyRow| key.methods.iter().position(|m| m.name() == r.method.method);
        rows.sort_by_key(|r| (scheme_index(r), method_index(r), r.level));
        let study = Arc::new(Study {
            key: self.key.clone(),
            rows,
        });
        *kept() = Some(study.clone());
        Ok(study)
    }
}

/// Owns the discretisation cache (least recently used last out) and the warm start.
pub struct Engine {
    scenario: Scenario,
    cache: Vec<(u32, Element, Arc<Discretization>)>,
    /// The last contact solve's state: where the next one starts ([`Warm`]).
    warm: Option<Warm>,
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
}

impl Engine {
    /// An engine for `scenario` with an empty cache.
    pub fn new(scenario: Scenario) -> Self {
        Engine {
            scenario,
            cache: Vec::new(),
            warm: None,
            study: Arc::default(),
            eta: Eta::default(),
            prepare_eta: Eta::preparing(),
            unfit: Vec::new(),
            peaks: RefCell::default(),
        }
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
            .or_insert_with(|| Discretization::sizes(&self.scenario, level, element).peak_bytes())
    }

    /// What building `level` with `element` for the rule and method of the last solve is
    /// expected to cost.
    fn plan(&self, level: u32, element: Element) -> Plan {
        let (rule, method) = self
            .warm
            .as_ref()
            .map_or((self.scenario.rule, self.scenario.method), |w| (w.on.2, w.method));
        self.plan_for(level, element, rule, method)
    }

    /// What building `level` with `element` for a solve with `rule` and `method` is expected
    /// to cost: the mesh unless it is built, and the method's preparation when it factorises
    /// K again ([`crate::solve::preparing_factorises`]; the rest of it is dense work on Γ_C's
    /// points, not estimated).
    fn plan_for(&self, level: u32, element: Element, rule: Rule, method: Method) -> Plan {
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
    fn peek(&self, level: u32, element: Element) -> Option<Arc<Discretization>> {
        self.cache
            .iter()
            .find(|(l, e, _)| (*l, *e) == (level, element))
            .map(|(_, _, d)| d.clone())
    }

    /// Whether the mesh of `level` with `element` is built and, for `solve` (a rule and
    /// method), prepared ([`crate::solve::needs_preparing`]).
    fn ready(&self, level: u32, element: Element, solve: Option<(Rule, Method)>) -> bool {
        self.peek(level, element).is_some_and(|disc| {
            solve.is_none_or(|(rule, method)| !crate::solve::needs_preparing(&disc, rule, method))
        })
    }

    fn cached(&mut self, level: u32, element: Element) -> Option<Arc<Discretization>> {
        let i = self
            .cache
            .iter()
            .position(|(l, e, _)| (*l, *e) == (level, element))?;
        let entry = self.cache.remove(i);
        let disc = entry.2.clone();
        self.cache.push(entry);
        Some(disc)
    }

    fn discretization(&mut self, level: u32, element: Element) -> Result<Arc<Discretization>, String> {
        if let Some(disc) = self.cached(level, element) {
            return Ok(disc);
        }
        let t = Instant::now();
        let disc = Arc::new(Discretization::of(&self.scenario, level, element).map_err(|e| e.to_string())?);
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
        let last = self.warm.as_ref().map(|w| (w.on.2, w.method));
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
    /// meanwhile); a background one for another element than the one in use is dropped.
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
        if (use_ == Use::Background && in_use != Some(element)) || self.has(level, element) {
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
        self.cache.iter().any(|(l, e, _)| (*l, *e) == (level, element))
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
                    result: Err(e),
                };
            }
        };
        // `exact` has no ε ([`Method::resolve`]); the others keep the lab's.
        let epsilon = if key.method.uses_epsilon() {
            key.epsilon
        } else {
            0.0
        };
        let params = ContactParams {
            rule: key.rule,
            method: key.method,
            epsilon,
            obstacle: self.scenario.obstacle.with_depth(key.depth),
        };
        let nitsche = matches!(key.method, Method::Nitsche { .. });
        let on = (key.level, key.element, key.rule, nitsche);
        // The last forces if they live on these points; else the last pressure carried to
        // the rule's points (Nitsche shares them between its edge points).
        let (warm, carried) = match &self.warm {
            Some(w) if w.on == on => (Some(w.forces.clone()), false),
            Some(w) => {
                let to = disc.contact_points(key.rule);
                (Some(carried_forces(&w.x, &w.p, &to)), true)
            }
            None => (None, false),
        };
        let mut newton = |start: Option<&[f64]>| {
            solve_contact(&disc, &params, start, &NewtonOptions::default(), &mut |it| {
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
            })
        };
        let mut result = newton(warm.as_deref());
        // A carried start is a guess: one that does not lead to convergence is not the
        // method's answer, so the solve starts again from rest.
        if carried && result.as_ref().is_ok_and(|s| !s.newton.converged) {
            result = newton(None);
        }
        match result {
            Ok(solution) => {
                self.warm = Some(Warm {
                    on,
                    forces: solution.newton.forces.clone(),
                    x: solution.points.points.iter().map(|q| q.x).collect(),
                    p: solution.p.clone(),
                    method: key.method,
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
                    })),
                }
            }
            Err(SolveError::Cancelled) => Response::Cancelled { generation },
            Err(e) => Response::Solved {
                generation,
                result: Err(e.to_string()),
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
    pub fn study(&self, key: &StudyKey, report: &mut dyn FnMut(Progress)) -> Result<Arc<Study>, String> {
        self.studying(key)?.run(report)
    }

    /// The work–precision study of `key`, ready to run on a thread of its own: the scenario, the
    /// estimate of each stage (from this engine's timings) and the engine's place for the
    /// finished study. An error if the engine runs another scenario.
    pub fn studying(&self, key: &StudyKey) -> Result<Studying, String> {
        if key.scenario != self.scenario.name {
            return Err(format!(
                "the worker runs {}, not {}",
                self.scenario.name, key.scenario
            ));
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
            self.eta.predict_ms(unknowns)
        });
        Ok(Studying {
            scenario: self.scenario.clone(),
            key: key.clone(),
            estimates_ms: std::iter::once(reference).chain(levels).collect(),
            kept: self.study.clone(),
        })
    }

    /// The inf-sup estimate of `key`.
    pub fn inf_sup(&mut self, key: InfSupKey) -> Result<InfSup, String> {
        let disc = self.discretization(key.level, key.element)?;
        beta::estimate(&disc, key.rule)
    }
}

/// A request to the worker thread.
enum Request {
    Solve(SolveRequest),
    Stresses(StressRequest),
    Displace(Arc<Solved>),
    InfSup(InfSupRequest),
    Study(StudyRequest),
}

/// The worker thread. Dropping it cancels the running solve and lets the thread end.
pub struct Worker {
    tx: Sender<Request>,
    latest: Arc<AtomicU64>,
}

impl Worker {
    /// Start the thread; every response goes to `sink`, which returns false once nobody listens.
    pub fn spawn(scenario: Scenario, sink: impl Fn(Response) -> bool + Send + Sync + 'static) -> Self {
        let (tx, rx) = mpsc::channel();
        let latest = Arc::new(AtomicU64::new(0));
        let shared = latest.clone();
        let sink: Sink = Arc::new(sink);
        std::thread::Builder::new()
            .name("riplab-worker".into())
            .spawn(move || run(Engine::new(scenario), &rx, &shared, &sink))
            .expect("spawn the worker thread");
        Worker { tx, latest }
    }

    /// Send a solve or an inf-sup request, or say which are superseded (anything else is
    /// not the worker's).
    pub fn send(&self, command: &Command) {
        let request = match command {
            Command::Supersede(generation) => {
                self.latest.fetch_max(*generation, Ordering::SeqCst);
                return;
            }
            Command::Solve(r) => Request::Solve(*r),
            Command::Stresses(r) => Request::Stresses(r.clone()),
            Command::Displace(r) => Request::Displace(r.solved.clone()),
            Command::InfSup(r) => Request::InfSup(*r),
            Command::Study(r) => Request::Study(r.clone()),
            Command::Export | Command::Suspend => return,
        };
        let generation = match &request {
            // Not ordered by generation: the stresses of a solution are wanted whenever shown.
            Request::Stresses(_) | Request::Displace(_) => 0,
            Request::Solve(r) => r.generation,
            Request::InfSup(r) => r.generation,
            Request::Study(r) => r.generation,
        };
        self.latest.fetch_max(generation, Ordering::SeqCst);
        // A dead worker shows as requests that never finish; the app keeps running.
        let _ = self.tx.send(request);
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        self.latest.store(u64::MAX, Ordering::SeqCst);
    }
}

/// The requests waiting for the worker: the newest solve, stress field and study, and the
/// inf-sup estimates in order.
#[derive(Default)]
struct Waiting {
    solve: Option<SolveRequest>,
    /// The solution just sent, whose displacement comes next.
    displace: Option<Arc<Solved>>,
    stresses: Option<StressRequest>,
    study: Option<StudyRequest>,
    queue: VecDeque<InfSupRequest>,
}

impl Waiting {
    fn is_empty(&self) -> bool {
        self.solve.is_none()
            && self.displace.is_none()
            && self.stresses.is_none()
            && self.study.is_none()
            && self.queue.is_empty()
    }

    /// File a request: a solve, a stress field or a study replaces any waiting one, an
    /// estimate joins the queue.
    fn take(&mut self, r: Request) {
        match r {
            Request::Solve(r) => self.solve = Some(r),
            Request::Stresses(r) => self.stresses = Some(r),
            Request::Displace(solved) => self.displace = Some(solved),
            Request::Study(r) => self.study = Some(r),
            Request::InfSup(r) => self.queue.push_back(r),
        }
    }

    /// The mesh the next request to run needs: the current solve's (with its generation, rule
    /// and method), or, when nothing else comes first, the next current estimate's.
    fn needs(&self, current: &dyn Fn(u64) -> bool, latest: u64) -> Option<Need> {
        if let Some(r) = self.solve.as_ref().filter(|r| current(r.generation)) {
            return Some(Need {
                level: r.key.level,
                element: r.key.element,
                solve: Some((r.generation, r.key.rule, r.key.method)),
            });
        }
        if self.solve.is_some() || self.displace.is_some() || self.stresses.is_some() || self.study.is_some()
        {
            return None;
        }
        let r = self.queue.front().filter(|r| latest <= r.generation)?;
        Some(Need {
            level: r.key.level,
            element: r.key.element,
            solve: None,
        })
    }

    /// Answer the request [`Waiting::needs`] named with why its mesh could not be built.
    fn fail(&mut self, needed_by: Option<u64>, error: String) -> Option<Response> {
        match needed_by {
            Some(generation) => {
                self.solve.take()?;
                Some(Response::Solved {
                    generation,
                    result: Err(error),
                })
            }
            None => self.queue.pop_front().map(|r| Response::InfSup {
                key: r.key,
                result: Some(Err(error)),
            }),
        }
    }
}

/// The mesh the next request needs ([`Waiting::needs`]).
#[derive(Clone, Copy)]
struct Need {
    level: u32,
    element: Element,
    /// The solve's generation, rule and method; None for an inf-sup estimate.
    solve: Option<(u64, Rule, Method)>,
}

/// How often the worker looks for new requests while it waits for a build.
const POLL: Duration = Duration::from_millis(20);

/// The builds under way on threads of their own ([`super::build`]): those requests wait for,
/// and the one started while idle.
#[derive(Default)]
struct Builds(Vec<Build>);

impl Builds {
    /// The build of `level` with `element`, if one is under way.
    fn of(&self, level: u32, element: Element) -> Option<&Build> {
        self.0.iter().find(|b| b.is_for(level, element))
    }

    /// Start building `plan` (only the method's preparation on `built`, the mesh when it is
    /// built) beside the builds under way, their whole estimates reserved (part of which they
    /// may already hold: the check errs on the safe side) and `extra` bytes more; false when
    /// no thread could be started.
    fn start(
        &mut self,
        scenario: &Scenario,
        plan: Plan,
        extra: u64,
        built: Option<Arc<Discretization>>,
    ) -> bool {
        let reserved = self
            .0
            .iter()
            .map(|b| b.plan.peak)
            .fold(extra, u64::saturating_add);
        match Build::start(scenario, plan, reserved, built) {
            Some(b) => {
                self.0.push(b);
                true
            }
            None => false,
        }
    }

    /// Adopt every finished build into `engine` (see [`Engine::adopt`]), waiting up to `wait`
    /// for the one a request `needs` (with what it is for); that one's mesh, or why it
    /// failed, once it has finished.
    fn collect(
        &mut self,
        engine: &mut Engine,
        needs: Option<(u32, Element, Use)>,
        wait: Duration,
    ) -> Option<Result<Arc<Discretization>, String>> {
        let mut needed = None;
        for b in std::mem::take(&mut self.0) {
            let (level, element) = (b.plan.level, b.plan.element);
            let wanted = needs.filter(|&(l, e, _)| (l, e) == (level, element));
            match b.finished(if wanted.is_some() { wait } else { Duration::ZERO }) {
                Ok(built) => {
                    let failure = built.as_ref().err().map(|e| match e {
                        SolveError::Cancelled => {
                            format!(
                                "the build of level {level} with {} ended without a result",
                                element.name()
                            )
                        }
                        e => e.to_string(),
                    });
                    let use_ = wanted.map_or(Use::Background, |(_, _, u)| u);
                    let disc = engine.adopt(level, element, built, use_);
                    if wanted.is_some() {
                        needed = Some(disc.ok_or_else(|| failure.unwrap_or_default()));
                    }
                }
                Err(b) => self.0.push(b),
            }
        }
        needed
    }
}

/// The worker loop: the newest solve first (older ones are dropped), then the displacement
/// of the solution just sent and the stresses of the solution shown (each on a thread of its
/// own in its [`Lane`], its reply sent from there), then the newest study (likewise), then
/// inf-sup estimates in order; studies and estimates older than the newest generation are
/// skipped. A mesh a solve or an estimate needs that is not built (or, for a Nitsche solve,
/// not prepared: [`crate::solve::needs_preparing`]) is built or prepared on a thread of its
/// own while the worker keeps answering: the solve is told its progress, and
/// a newer request (a step back to a built level) is served at once. Estimates run on a
/// thread of their own too, one at a time on built meshes, and each as soon as the mesh it
/// waited for is built (held by the estimate alone when the cache's budget cannot keep it).
/// When nothing is waiting and no study runs, the neighbouring levels of the mesh in use are
/// built in the background, each only while the memory would hold it twice (what it leaves for the next
/// request).
fn run(mut engine: Engine, rx: &Receiver<Request>, latest: &AtomicU64, sink: &Sink) {
    let mut waiting = Waiting::default();
    let mut builds = Builds::default();
    let mut estimating: Vec<Estimating> = Vec::new();
    let (displacing, stressing) = (Lane::new("riplab-displace"), Lane::new("riplab-stresses"));
    let studies = Lane::new("riplab-study");
    // The solve generation (with the start of the build it waits for: a Nitsche solve may
    // wait for the mesh's build, then for its preparation), and the estimate, told that it
    // waits for a build.
    let mut announced = None;
    let mut announced_estimate = None;
    loop {
        for e in std::mem::take(&mut estimating) {
            match e.finished(Duration::ZERO) {
                Ok(response) => {
                    if !sink(response) {
                        return;
                    }
                }
                Err(e) => estimating.push(e),
            }
        }
        if waiting.is_empty() {
            builds.collect(&mut engine, None, Duration::ZERO);
            // A study under way has the cores (the convergence scene waits for it).
            if builds.0.is_empty()
                && !studies.busy()
                && let Some((level, element)) = engine.next_prefetch()
            {
                let plan = engine.plan(level, element);
                builds.start(&engine.scenario, plan, plan.peak, engine.peek(level, element));
            }
            let next = if builds.0.is_empty() && estimating.is_empty() && !studies.busy() {
                match rx.recv() {
                    Ok(r) => Some(r),
                    Err(_) => return,
                }
            } else {
                match rx.recv_timeout(POLL) {
                    Ok(r) => Some(r),
                    Err(mpsc::RecvTimeoutError::Timeout) => None,
                    Err(mpsc::RecvTimeoutError::Disconnected) => return,
                }
            };
            if let Some(r) = next {
                waiting.take(r);
            }
            continue;
        }
        while let Ok(r) = rx.try_recv() {
            waiting.take(r);
        }
        let current = |g: u64| latest.load(Ordering::SeqCst) == g;
        let needs = waiting
            .needs(&current, latest.load(Ordering::SeqCst))
            .filter(|n| !engine.ready(n.level, n.element, n.solve.map(|(_, r, m)| (r, m))));
        if let Some(Need {
            level,
            element,
            solve,
        }) = needs
        {
            let needed_by = solve.map(|(generation, ..)| generation);
            let plan = match solve {
                Some((_, rule, method)) => engine.plan_for(level, element, rule, method),
                None => engine.plan(level, element),
            };
            let under_way = builds.of(level, element).is_some()
                || builds.start(&engine.scenario, plan, 0, engine.peek(level, element));
            // Without a thread of its own, the request below builds its mesh here.
            if under_way {
                if let Some(b) = builds.of(level, element) {
                    let progress = Progress::Assembling {
                        level,
                        unknowns: b.plan.unknowns,
                        started: b.started,
                        estimate_ms: b.plan.estimate_ms,
                        method: b.plan.prepares().then(|| b.plan.method.name()),
                    };
                    match (needed_by, waiting.queue.front()) {
                        (Some(generation), _) if announced != Some((generation, b.started)) => {
                            announced = Some((generation, b.started));
                            sink(Response::Progress { generation, progress });
                        }
                        (None, Some(req)) if announced_estimate != Some(req.key) => {
                            announced_estimate = Some(req.key);
                            sink(Response::InfSupProgress {
                                key: req.key,
                                progress,
                            });
                        }
                        _ => {}
                    }
                }
                let use_ = if needed_by.is_some() {
                    Use::Solve
                } else {
                    Use::Estimate
                };
                let collected = builds.collect(&mut engine, Some((level, element, use_)), POLL);
                if collected.is_some() {
                    // Built or failed: a later estimate of the same key is told again.
                    announced_estimate = None;
                }
                let response = match collected {
                    Some(Err(error)) => waiting.fail(needed_by, error),
                    // The estimate starts on the mesh just built, kept in the cache or not.
                    Some(Ok(disc)) if use_ == Use::Estimate => waiting.queue.pop_front().and_then(|req| {
                        match Estimating::start(disc.clone(), req.key) {
                            Some(e) => {
                                estimating.push(e);
                                None
                            }
                            None => Some(Response::InfSup {
                                key: req.key,
                                result: Some(beta::estimate(&disc, req.key.rule)),
                            }),
                        }
                    }),
                    _ => None,
                };
                if let Some(response) = response
                    && !sink(response)
                {
                    return;
                }
                continue;
            }
        }
        builds.collect(&mut engine, None, Duration::ZERO);
        let response = if let Some(req) = waiting.solve.take() {
            if !current(req.generation) {
                continue;
            }
            let response = engine.solve(&req, &current, &mut |r| {
                sink(r);
            });
            if let Response::Solved {
                result: Ok(solved), ..
            } = &response
            {
                waiting.displace = Some(solved.clone());
            }
            response
        } else if let Some(solved) = waiting.displace.take() {
            match displacing.submit(sink, move || Engine::displace(&solved)) {
                Some(response) => response,
                None => continue,
            }
        } else if let Some(req) = waiting.stresses.take() {
            let scenario = engine.scenario.clone();
            match stressing.submit(sink, move || Engine::stresses(&scenario, &req)) {
                Some(response) => response,
                None => continue,
            }
        } else if let Some(req) = waiting.study.take() {
            let stale = latest.load(Ordering::SeqCst) > req.generation;
            let (generation, key) = (req.generation, req.key);
            match engine.studying(&key) {
                Ok(studying) if !stale => {
                    let told = sink.clone();
                    let work = move || Response::Study {
                        generation,
                        result: Some(studying.run(&mut |progress| {
                            told(Response::StudyProgress { generation, progress });
                        })),
                        key,
                    };
                    match studies.submit(sink, work) {
                        Some(response) => response,
                        None => continue,
                    }
                }
                Ok(_) => Response::Study {
                    generation,
                    result: None,
                    key,
                },
                Err(error) => Response::Study {
                    generation,
                    result: Some(Err(error)),
                    key,
                },
            }
        } else if !estimating.is_empty() {
            // The next estimate waits for those under way.
            match estimating.remove(0).finished(POLL) {
                Ok(response) => response,
                Err(e) => {
                    estimating.insert(0, e);
                    continue;
                }
            }
        } else if let Some(req) = waiting.queue.pop_front() {
            let stale = latest.load(Ordering::SeqCst) > req.generation;
            let key = req.key;
            match engine.cached(key.level, key.element) {
                Some(disc) if !stale => match Estimating::start(disc, key) {
                    Some(e) => {
                        estimating.push(e);
                        continue;
                    }
                    None => Response::InfSup {
                        key,
                        result: Some(engine.inf_sup(key)),
                    },
                },
                // Without its mesh (no thread for its build), the estimate builds it here.
                _ => Response::InfSup {
                    key,
                    result: (!stale).then(|| engine.inf_sup(key)),
                },
            }
        } else {
            continue;
        };
        if !sink(response) {
            return;
        }
    }
}

/// Run everything `app` needs synchronously on `engine`, until nothing is left.
pub fn settle(app: &mut App, engine: &mut Engine) {
    let commands = app.update(Msg::Resize).commands;
    carry_out(app, engine, commands);
}

/// Run `commands` (which `app` asked for) synchronously on `engine`, and whatever the replies
/// ask for in turn, until nothing is left; exports are skipped.
pub fn carry_out(app: &mut App, engine: &mut Engine, mut commands: Vec<Command>) {
    while let Some(command) = commands.pop() {
        let response = match command {
            Command::Solve(req) => {
                let response = engine.solve(&req, &|_| true, &mut |_| {});
                if let Response::Solved {
                    result: Ok(solved), ..
                } = &response
                {
                    let displaced = Engine::displace(solved);
                    commands.extend(app.update(Msg::Worker(response)).commands);
                    displaced
                } else {
                    response
                }
            }
            Command::InfSup(req) => Response::InfSup {
                key: req.key,
                result: Some(engine.inf_sup(req.key)),
            },
            Command::Study(req) => Response::Study {
                generation: req.generation,
                result: Some(engine.study(&req.key, &mut |_| {})),
                key: req.key,
            },
            Command::Stresses(req) => Engine::stresses(&engine.scenario, &req),
            Command::Displace(req) => Engine::displace(&req.solved),
            Command::Export | Command::Suspend | Command::Supersede(_) => continue,
        };
        commands.extend(app.update(Msg::Worker(response)).commands);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tui::app::{App, SolveKey};

    /// Issue 13 item 4 for Nitsche's method: after a Nitsche solve, the background build of
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
                assert!(e.contains("too small for θ = 1") && e.contains("γ₀* ="), "{e}");
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
            on: (2, key.element, key.rule, false),
            forces: Vec::new(),
            x: vec![-1.0, 1.0],
            p: vec![f64::NAN, f64::NAN],
            method: key.method,
        });
        let again = solve(&mut engine);
        assert!(again.solution.newton.converged);
        assert_eq!(again.solution.newton.iterations, rest.solution.newton.iterations);
        assert_eq!(again.solution.load, rest.solution.load);
    }
}
