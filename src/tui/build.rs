//! Building a discretisation on a thread of its own, so that the worker
//! never waits on a factorisation: a level the user asks for shows its progress and the time
//! left while the worker keeps answering (a step back to a built level is served at once),
//! and a neighbouring level is built while the lab is idle, so that `]` and `[` find it ready.
//! A build also does what the solve's method needs beyond the mesh's factor (Nitsche's layer,
//! seconds at level 7), alone when the mesh is already built.
//!
//! A build hands its result back through a channel; the worker adopts it into its cache
//! ([`super::engine::Engine::adopt`]) or drops it when the user has moved on. A factorisation
//! cannot be interrupted, so "cancelling" a build means dropping its result; the memory it may
//! use is checked before it starts, less what the builds already under way may still take
//! ([`crate::scenario::Scenario::discretize_beside`]).

use std::sync::Arc;
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use crate::contact::{Method, Rule};
use crate::discretization::Discretization;
use crate::discretization::ms_since;
use crate::error::SolveError;
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::solve;

/// A build on a thread of its own.
pub struct Build {
    /// What is being built and what it is expected to cost.
    pub plan: Plan,
    /// When the build began.
    pub started: Instant,
    done: Receiver<Built>,
}

/// A finished build, or why there is none.
pub type Built = Result<Finished, SolveError>;

/// What a build hands back: the mesh, and the wall time of each part it did, ms.
pub struct Finished {
    /// The mesh, built by this build or given to it.
    pub disc: Arc<Discretization>,
    /// Assembly and factorisation; None when the mesh was given.
    pub build_ms: Option<f64>,
    /// The method's preparation ([`solve::prepare`]) when it factorised K again
    /// ([`solve::preparing_factorises`]: what the plan's estimate counts).
    pub prepare_ms: Option<f64>,
}

/// What a build is of and what it is expected to cost.
#[derive(Clone, Copy, Debug)]
pub struct Plan {
    /// The level to build.
    pub level: u32,
    /// The element to build.
    pub element: Element,
    /// Its number of unknowns.
    pub unknowns: usize,
    /// The contact rule and method of the solve the mesh is for (or of the last solve): what
    /// the solve needs beyond the mesh's factor is built with it ([`solve::prepare`]: G, or
    /// Nitsche's layer), so that a step to the mesh costs only the contact solve.
    pub rule: Rule,
    /// The method, with its parameters (see `rule`).
    pub method: Method,
    /// Its estimated peak memory, bytes ([`crate::fem::memory::Sizes::peak_bytes`]).
    pub peak: u64,
    /// Its expected time, ms ([`super::eta`]).
    pub estimate_ms: f64,
}

impl Plan {
    /// Whether the method's preparation is long work ([`solve::needs_preparing`] on a mesh
    /// without it): Nitsche's.
    pub fn prepares(&self) -> bool {
        matches!(self.method, Method::Nitsche { .. })
    }
}

impl Build {
    /// Start the build `plan` of `scenario` beside other work that may still take `reserved`
    /// bytes, or, given the mesh `built`, only the method's preparation on it; None if no
    /// thread can be started (the caller then builds in its own thread).
    pub fn start(
        scenario: &Scenario,
        plan: Plan,
        reserved: u64,
        built: Option<Arc<Discretization>>,
    ) -> Option<Self> {
        let (tx, done) = mpsc::channel();
        let scenario = scenario.clone();
        let Plan {
            level,
            element,
            rule,
            method,
            ..
        } = plan;
        std::thread::Builder::new()
            .name("riplab-build".into())
            .spawn(move || {
                let (t, fresh) = (Instant::now(), built.is_none());
                let disc = match built {
                    Some(disc) => Ok(disc),
                    None => scenario.discretize_beside(level, element, reserved).map(Arc::new),
                };
                let build_ms = fresh.then(|| ms_since(t));
                let built = disc.and_then(|disc| {
                    // Nitsche's layer is another factorisation of the mesh's size, beside the
                    // mesh when it was built here. Without the memory for it, a fresh mesh is
                    // handed back unprepared (a solve then meets the refusal).
                    let factorises = solve::preparing_factorises(&disc, method);
                    let beside = reserved.saturating_add(if fresh { plan.peak } else { 0 });
                    if factorises && let Err(e) = scenario.fits_beside(level, element, beside) {
                        return if fresh {
                            Ok(Finished {
                                disc,
                                build_ms,
                                prepare_ms: None,
                            })
                        } else {
                            Err(e)
                        };
                    }
                    let t = Instant::now();
                    solve::prepare(&disc, rule, method);
                    Ok(Finished {
                        disc,
                        build_ms,
                        prepare_ms: factorises.then(|| ms_since(t)),
                    })
                });
                // Nobody listens any more when the worker has ended: nothing to do then.
                let _ = tx.send(built);
            })
            .ok()?;
        Some(Build {
            plan,
            started: Instant::now(),
            done,
        })
    }

    /// The build's result if it finished within `wait` (a thread that ended without one
    /// counts as cancelled: the level is then built again when asked for); `Err(self)` while
    /// it runs.
    pub fn finished(self, wait: Duration) -> Result<Built, Self> {
        let got = if wait.is_zero() {
            self.done.try_recv().map_err(|e| match e {
                mpsc::TryRecvError::Empty => RecvTimeoutError::Timeout,
                mpsc::TryRecvError::Disconnected => RecvTimeoutError::Disconnected,
            })
        } else {
            self.done.recv_timeout(wait)
        };
        match got {
            Ok(built) => Ok(built),
            Err(RecvTimeoutError::Timeout) => Err(self),
            Err(RecvTimeoutError::Disconnected) => Ok(Err(SolveError::Cancelled)),
        }
    }

    /// Whether this build is of `level` with `element`.
    pub fn is_for(&self, level: u32, element: Element) -> bool {
        (self.plan.level, self.plan.element) == (level, element)
    }
}
