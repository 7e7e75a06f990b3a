//! Work on a thread of its own whose reply goes straight to the app: the
//! displacement of a solution (a quarter of a second at level 7: the factor's solves on every
//! unknown) and its stress field (seconds at level 7), so that the worker answers a key
//! pressed meanwhile (a step back right after a step used to wait for the displacement).
//!
//! The work–precision study runs in a lane too (seconds to a minute): a key pressed on the way
//! through the convergence scene is answered at once.
//!
//! Each kind of job has its [`Lane`]: one job at a time, and only the newest of those waiting,
//! so that a burst of solves (a held `+`) does not start a displacement per solve on two cores.

use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

use super::protocol::Response;

/// Where replies go: the app's channel; false once nobody listens.
pub type Sink = Arc<dyn Fn(Response) -> bool + Send + Sync>;

/// Jobs of one kind: each runs on a thread of its own after the one before it has finished,
/// and not at all if a newer job was submitted meanwhile (its reply is for a solution the app
/// no longer shows).
pub struct Lane {
    /// The threads' names.
    name: &'static str,
    /// Held by the job that runs.
    turn: Arc<Mutex<()>>,
    /// The number of the newest job submitted.
    newest: Arc<AtomicU64>,
    /// The jobs submitted whose threads have not ended.
    open: Arc<AtomicUsize>,
}

impl Lane {
    /// An empty lane whose threads are called `name`.
    pub fn new(name: &'static str) -> Self {
        Lane {
            name,
            turn: Arc::default(),
            newest: Arc::default(),
            open: Arc::default(),
        }
    }

    /// Whether a job of this lane runs or waits to.
    pub fn busy(&self) -> bool {
        self.open.load(Ordering::SeqCst) > 0
    }

    /// Run `work` in this lane and send its reply to `sink`; when no thread can be started,
    /// run it here and return the reply for the caller to send.
    pub fn submit(&self, sink: &Sink, work: impl FnOnce() -> Response + Send + 'static) -> Option<Response> {
        let ticket = self.newest.fetch_add(1, Ordering::SeqCst) + 1;
        // The work goes through a slot so that it is still at hand if the thread does not start.
        let slot = Arc::new(Mutex::new(Some(work)));
        let (theirs, sink) = (slot.clone(), sink.clone());
        let (turn, newest) = (self.turn.clone(), self.newest.clone());
        self.open.fetch_add(1, Ordering::SeqCst);
        let ended = Ended(self.open.clone());
        let started = std::thread::Builder::new().name(self.name.into()).spawn(move || {
            let _ended = ended;
            let _turn = turn.lock().unwrap_or_else(PoisonError::into_inner);
            if newest.load(Ordering::SeqCst) != ticket {
                return;
            }
            let work = theirs.lock().unwrap_or_else(PoisonError::into_inner).take();
            if let Some(work) = work {
                // Nobody listens any more when the app has ended: nothing to do then.
                sink(work());
            }
        });
        match started {
            Ok(_) => None,
            Err(_) => {
                let work = slot.lock().unwrap_or_else(PoisonError::into_inner).take();
                work.map(|work| work())
            }
        }
    }
}

/// Counts a job's end when dropped: when its thread ends, or with the thread that did not start
/// (a panic in the job counts too).
struct Ended(Arc<AtomicUsize>);

impl Drop for Ended {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Scenario;
    use crate::tui::app::App;
    use std::sync::mpsc;
    use std::time::Duration;

    /// One job at a time, and of those that waited only the newest runs: with the first job
    /// running, the second and third are submitted; the second never runs. The lane is busy
    /// from the first submission until the last job's thread has ended.
    #[test]
    fn a_lane_runs_one_job_at_a_time_and_skips_the_superseded() {
        let (tx, rx) = mpsc::channel();
        let sink: Sink = Arc::new(move |r| tx.send(r).is_ok());
        let key = App::defaults(&Scenario::paper());
        let reply = move |level| Response::Displaced {
            key: crate::tui::app::SolveKey { level, ..key },
        };
        let lane = Lane::new("riplab-test");
        let (started_tx, started) = mpsc::channel();
        let (release, released) = mpsc::channel::<()>();
        let first = lane.submit(&sink, move || {
            started_tx.send(()).unwrap();
            released.recv().unwrap();
            reply(1)
        });
        assert!(first.is_none(), "on a thread of its own");
        started.recv_timeout(Duration::from_secs(60)).unwrap();
        assert!(lane.busy());
        let ran = Arc::new(AtomicU64::new(0));
        let counted = ran.clone();
        lane.submit(&sink, move || {
            counted.fetch_add(1, Ordering::SeqCst);
            reply(2)
        });
        lane.submit(&sink, move || reply(3));
        release.send(()).unwrap();
        let level = |r: Response| match r {
            Response::Displaced { key } => key.level,
            other => panic!("{other:?}"),
        };
        let wait = Duration::from_secs(60);
        assert_eq!(level(rx.recv_timeout(wait).unwrap()), 1);
        assert_eq!(level(rx.recv_timeout(wait).unwrap()), 3);
        assert!(
            rx.recv_timeout(Duration::from_millis(200)).is_err(),
            "the second sent nothing"
        );
        assert_eq!(ran.load(Ordering::SeqCst), 0, "the second never ran");
        // Its thread ends just after the last reply.
        let since = std::time::Instant::now();
        while lane.busy() {
            assert!(since.elapsed() < wait, "the lane stays busy");
            std::thread::sleep(Duration::from_millis(1));
        }
    }
}
