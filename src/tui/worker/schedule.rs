//! The worker thread's scheduler ([`run`]): which request runs next, the builds it waits for
//! on threads of their own, and the estimates and studies beside them.

use std::collections::VecDeque;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver};
use std::time::Duration;

use crate::contact::{Method, Rule};
use crate::discretization::Discretization;
use crate::error::SolveError;
use crate::mesh::Element;
use crate::scenario::Scenario;

use super::super::beta;
use super::super::build::{Build, Plan};
use super::super::engine::{Engine, Use};
use super::super::estimating::Estimating;
use super::super::job::{Lane, Sink};
use super::super::lab_error::LabError;
use super::super::protocol::{
    InfSupRequest, Progress, Response, SolveRequest, Solved, StressRequest, StudyRequest,
};
use super::{Request, Watch};

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
    /// The requests taken so far.
    taken: u64,
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
        self.taken += 1;
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
    fn fail(&mut self, needed_by: Option<u64>, error: LabError) -> Option<Response> {
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
    ) -> Option<Result<Arc<Discretization>, LabError>> {
        let mut needed = None;
        for b in std::mem::take(&mut self.0) {
            let (level, element) = (b.plan.level, b.plan.element);
            let wanted = needs.filter(|&(l, e, _)| (l, e) == (level, element));
            match b.finished(if wanted.is_some() { wait } else { Duration::ZERO }) {
                Ok(built) => {
                    let failure = built.as_ref().err().map(|e| match e {
                        SolveError::Cancelled => LabError::BuildEnded { level, element },
                        e => LabError::from(e.clone()),
                    });
                    let use_ = wanted.map_or(Use::Background, |(_, _, u)| u);
                    let disc = engine.adopt(level, element, built, use_);
                    if wanted.is_some() {
                        needed = Some(match failure {
                            Some(e) => Err(e),
                            None => disc.ok_or(LabError::BuildEnded { level, element }),
                        });
                    }
                }
                Err(b) => self.0.push(b),
            }
        }
        needed
    }
}

/// A solve's integration is the engine's from its arrival on: the meshes built for it (and
/// in the background next) are integrated so ([`Engine::follow`]).
fn follow(engine: &mut Engine, r: &Request) {
    if let Request::Solve(req) = r {
        engine.follow(req.key.integration);
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
/// Each time it waits for a request, the worker says so to `watch`.
pub(super) fn run(
    mut engine: Engine,
    rx: &Receiver<Request>,
    latest: &AtomicU64,
    sink: &Sink,
    watch: &Watch,
) {
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
            let background = !builds.0.is_empty() || !estimating.is_empty() || studies.busy();
            watch.waits(waiting.taken, background);
            let next = if !background {
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
                follow(&mut engine, &r);
                waiting.take(r);
            }
            continue;
        }
        while let Ok(r) = rx.try_recv() {
            follow(&mut engine, &r);
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
                                result: Some(beta::estimate(&disc, req.key.rule).map_err(LabError::from)),
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
                    let (told, shown) = (sink.clone(), sink.clone());
                    let work = move || Response::Study {
                        generation,
                        result: Some(studying.run_shown(
                            &mut |progress| {
                                told(Response::StudyProgress { generation, progress });
                            },
                            &mut |study| {
                                shown(Response::StudyPartial { generation, study });
                            },
                        )),
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
