//! The numerical work behind the app: an [`Engine`] that owns the discretisation cache and runs
//! solves and inf-sup estimates, a [`Worker`] thread that drives it from a channel, and
//! [`settle`], which drives it synchronously (for `render` and tests).

use std::collections::VecDeque;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, OnceLock};
use std::time::Instant;

use crate::contact::Rule;
use crate::contact::penalty::{NewtonOptions, SolveError};
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::solve::{ContactParams, Discretization, Solution, solve_contact};
use crate::stress::StressField;

use crate::solve::preset;
use crate::study::{StudyRow, convergence};

use super::app::{
    App, Command, InfSupKey, InfSupRequest, Msg, Progress, Response, SolveKey, SolveRequest, Study, StudyKey,
    StudyRequest,
};
use super::beta::{self, InfSup};
use super::eta::Eta;

/// How many discretisations (meshes with their factorisations) are kept at most…
const CACHE_SIZE: usize = 4;
/// …and how many unknowns they may hold together (the newest is kept whatever its size).
const CACHE_DOFS: usize = 600_000;

/// A finished solve with the discretisation it was computed on.
#[derive(Clone)]
pub struct Solved {
    pub key: SolveKey,
    pub disc: Arc<Discretization>,
    pub solution: Solution,
    /// Displacement on every dof, node-major (u_x = [2n], u_y = [2n + 1]).
    pub displacement: Vec<f64>,
    /// Wall time of the request, mesh work included, in ms.
    pub total_ms: f64,
    /// The stresses, computed when first shown (see `view::stress_map`).
    pub stresses: OnceLock<Result<Arc<StressField>, String>>,
}

impl std::fmt::Debug for Solved {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Solved")
            .field("key", &self.key)
            .field("load", &self.solution.load)
            .finish_non_exhaustive()
    }
}

/// Owns the discretisation cache (least recently used last out) and the warm start.
pub struct Engine {
    scenario: Scenario,
    cache: Vec<(u32, Element, Arc<Discretization>)>,
    /// The last contact forces and the mesh and rule they belong to (the warm start).
    warm: Option<(u32, Element, Rule, Vec<f64>)>,
    /// The last study (a study takes seconds; a second app on the same engine reuses it).
    study: Option<Arc<Study>>,
    /// How long builds take here (for the time left).
    eta: Eta,
}

impl Engine {
    pub fn new(scenario: Scenario) -> Self {
        Engine {
            scenario,
            cache: Vec::new(),
            warm: None,
            study: None,
            eta: Eta::default(),
        }
    }

    /// The unknowns of the mesh at `level` for `element` (two per node, before the supports).
    fn unknowns(&self, level: u32, element: Element) -> usize {
        2 * self.scenario.mesh(level, element).n_nodes()
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
        let dofs = |cache: &[(u32, Element, Arc<Discretization>)]| -> usize {
            cache.iter().map(|(_, _, d)| d.n_dofs()).sum()
        };
        while self.cache.len() > 1 && (self.cache.len() > CACHE_SIZE || dofs(&self.cache) > CACHE_DOFS) {
            self.cache.remove(0);
        }
        Ok(disc)
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
        let warm = self
            .warm
            .as_ref()
            .filter(|(l, e, r, _)| (*l, *e, *r) == (key.level, key.element, key.rule))
            .map(|(_, _, _, y)| y.as_slice());
        let result = solve_contact(&disc, &params, warm, &NewtonOptions::default(), &mut |it| {
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
        });
        match result {
            Ok(solution) => {
                self.warm = Some((key.level, key.element, key.rule, solution.newton.forces.clone()));
                // Every scene that shows a solution draws the deformed configuration.
                let displacement = solution.displacement(&disc);
                Response::Solved {
                    generation,
                    result: Ok(Arc::new(Solved {
                        key,
                        disc,
                        solution,
                        displacement,
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

    /// The work–precision study of `key`: M1–M4 at levels 0..=max against the Q2 reference
    /// one level finer, at the scenario's ε (fresh solves: the timings are comparable); each
    /// stage (the reference, then each level) is announced to `report` with its estimate.
    pub fn study(&mut self, key: &StudyKey, report: &mut dyn FnMut(Progress)) -> Result<Arc<Study>, String> {
        if let Some(study) = self.study.as_ref().filter(|s| s.key == *key) {
            return Ok(study.clone());
        }
        if key.scenario != self.scenario.name {
            return Err(format!(
                "the worker runs {}, not {}",
                self.scenario.name, key.scenario
            ));
        }
        // The reference: a Q2 build and an active-set solve of about the same cost (nothing
        // when the cache holds it).
        let unknowns = self.unknowns(key.reference_level(), Element::Q2);
        report(Progress::Study {
            level: None,
            started: Instant::now(),
            estimate_ms: 2.0 * self.eta.predict_ms(unknowns),
        });
        let dir = crate::cache::default_dir();
        let (reference, _) = crate::cache::reference(&self.scenario, key.reference_level(), dir.as_deref())
            .map_err(|e| e.to_string())?;
        let schemes: Vec<(Element, Rule)> = (1..=4).filter_map(|m| preset(&format!("M{m}"))).collect();
        let mut rows = Vec::new();
        for level in 0..=key.max_level {
            // One Q1 and one Q2 build per level.
            let unknowns = self.unknowns(level, Element::Q1) + self.unknowns(level, Element::Q2);
            report(Progress::Study {
                level: Some(level),
                started: Instant::now(),
                estimate_ms: self.eta.predict_ms(unknowns),
            });
            rows.extend(convergence(
                &self.scenario,
                &reference,
                &schemes,
                &[level],
                None,
                self.scenario.epsilon,
            ));
        }
        // M1–M4 in order, each by ascending level.
        let order = |r: &StudyRow| schemes_index(&r.scheme);
        rows.sort_by_key(|r| (order(r), r.level));
        let study = Arc::new(Study {
            key: key.clone(),
            rows,
        });
        self.study = Some(study.clone());
        Ok(study)
    }

    /// The inf-sup estimate of `key`.
    pub fn inf_sup(&mut self, key: InfSupKey) -> Result<InfSup, String> {
        let disc = self.discretization(key.level, key.element)?;
        beta::estimate(&disc, key.rule)
    }
}

/// The position of scheme `name` among M1–M4 (others last).
fn schemes_index(name: &str) -> usize {
    ["M1", "M2", "M3", "M4"]
        .iter()
        .position(|m| *m == name)
        .unwrap_or(4)
}

/// A request to the worker thread.
enum Request {
    Solve(SolveRequest),
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
    pub fn spawn(scenario: Scenario, sink: impl Fn(Response) -> bool + Send + 'static) -> Self {
        let (tx, rx) = mpsc::channel();
        let latest = Arc::new(AtomicU64::new(0));
        let shared = latest.clone();
        std::thread::Builder::new()
            .name("riplab-worker".into())
            .spawn(move || run(Engine::new(scenario), &rx, &shared, &sink))
            .expect("spawn the worker thread");
        Worker { tx, latest }
    }

    /// Send a solve or an inf-sup request (anything else is not the worker's).
    pub fn send(&self, command: &Command) {
        let request = match command {
            Command::Solve(r) => Request::Solve(*r),
            Command::InfSup(r) => Request::InfSup(*r),
            Command::Study(r) => Request::Study(r.clone()),
            Command::Export | Command::Suspend => return,
        };
        let generation = match &request {
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

/// The worker loop: the newest solve first (older ones are dropped), then the newest study
/// (likewise), then inf-sup estimates in order; studies and estimates older than the newest
/// generation are skipped.
fn run(mut engine: Engine, rx: &Receiver<Request>, latest: &AtomicU64, sink: &dyn Fn(Response) -> bool) {
    let mut solve: Option<SolveRequest> = None;
    let mut study: Option<StudyRequest> = None;
    let mut queue: VecDeque<InfSupRequest> = VecDeque::new();
    loop {
        if solve.is_none() && study.is_none() && queue.is_empty() {
            match rx.recv() {
                Ok(r) => take(r, &mut solve, &mut study, &mut queue),
                Err(_) => return,
            }
        }
        while let Ok(r) = rx.try_recv() {
            take(r, &mut solve, &mut study, &mut queue);
        }
        let current = |g: u64| latest.load(Ordering::SeqCst) == g;
        let response = if let Some(req) = solve.take() {
            if !current(req.generation) {
                continue;
            }
            engine.solve(&req, &current, &mut |r| {
                sink(r);
            })
        } else if let Some(req) = study.take() {
            let stale = latest.load(Ordering::SeqCst) > req.generation;
            let generation = req.generation;
            Response::Study {
                generation,
                result: (!stale).then(|| {
                    engine.study(&req.key, &mut |progress| {
                        sink(Response::StudyProgress { generation, progress });
                    })
                }),
                key: req.key,
            }
        } else if let Some(req) = queue.pop_front() {
            let stale = latest.load(Ordering::SeqCst) > req.generation;
            Response::InfSup {
                key: req.key,
                result: (!stale).then(|| engine.inf_sup(req.key)),
            }
        } else {
            continue;
        };
        if !sink(response) {
            return;
        }
    }
}

/// File a request: a solve or a study replaces any waiting one, an estimate joins the queue.
fn take(
    r: Request,
    solve: &mut Option<SolveRequest>,
    study: &mut Option<StudyRequest>,
    queue: &mut VecDeque<InfSupRequest>,
) {
    match r {
        Request::Solve(r) => *solve = Some(r),
        Request::Study(r) => *study = Some(r),
        Request::InfSup(r) => queue.push_back(r),
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
            Command::Solve(req) => engine.solve(&req, &|_| true, &mut |_| {}),
            Command::InfSup(req) => Response::InfSup {
                key: req.key,
                result: Some(engine.inf_sup(req.key)),
            },
            Command::Study(req) => Response::Study {
                generation: req.generation,
                result: Some(engine.study(&req.key, &mut |_| {})),
                key: req.key,
            },
            Command::Export | Command::Suspend => continue,
        };
        commands.extend(app.update(Msg::Worker(response)).commands);
    }
}
