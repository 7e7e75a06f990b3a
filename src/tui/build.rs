//! Building a discretisation on a thread of its own (issue 13, item 4), so that the worker
//! never waits on a factorisation: a level the user asks for shows its progress and the time
//! left while the worker keeps answering (a step back to a built level is served at once),
//! and a neighbouring level is built while the lab is idle, so that `]` and `[` find it ready.
//!
//! A build hands its result back through a channel; the worker adopts it into its cache
//! ([`super::worker::Engine::adopt`]) or drops it when the user has moved on. A factorisation
//! cannot be interrupted, so "cancelling" a build means dropping its result; the memory it may
//! use is checked before it starts, less what the builds already under way may still take
//! ([`Discretization::of_beside`]).

use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use crate::contact::Rule;
use crate::error::SolveError;
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::solve::Discretization;

/// A build on a thread of its own.
pub struct Build {
    /// What is being built and what it is expected to cost.
    pub plan: Plan,
    /// When the build began.
    pub started: Instant,
    done: Receiver<Built>,
}

/// A finished build and its wall time in ms, or why there is none.
pub type Built = Result<(Discretization, f64), SolveError>;

/// What a build is of and what it is expected to cost.
#[derive(Clone, Copy, Debug)]
pub struct Plan {
    /// The level to build.
    pub level: u32,
    /// The element to build.
    pub element: Element,
    /// Its number of unknowns.
    pub unknowns: usize,
    /// The contact rule of the last solve: its coupling G ([`Discretization::coupling`]) is
    /// computed with the mesh, so that a step to the mesh costs only the contact solve.
    pub rule: Rule,
    /// Its estimated peak memory, bytes ([`crate::fem::memory::Sizes::peak_bytes`]).
    pub peak: u64,
    /// Its expected time, ms ([`super::eta`]).
    pub estimate_ms: f64,
}

impl Build {
    /// Start the build `plan` of `scenario` beside other work that may still take `reserved`
    /// bytes; None if no thread can be started (the caller then builds in its own thread).
    pub fn start(scenario: &Scenario, plan: Plan, reserved: u64) -> Option<Self> {
        let (tx, done) = mpsc::channel();
        let scenario = scenario.clone();
        let Plan {
            level, element, rule, ..
        } = plan;
        std::thread::Builder::new()
            .name("riplab-build".into())
            .spawn(move || {
                let t = Instant::now();
                let built = Discretization::of_beside(&scenario, level, element, reserved).map(|d| {
                    d.coupling(rule, &d.contact_points(rule));
                    (d, t.elapsed().as_secs_f64() * 1e3)
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
