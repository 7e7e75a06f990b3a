//! Work on a thread of its own whose reply goes straight to the app (issue 13, item 4): the
//! displacement of a solution (a quarter of a second at level 7: the factor's solves on every
//! unknown) and its stress field (seconds at level 7), so that the worker answers a key
//! pressed meanwhile (a step back right after a step used to wait for the displacement).

use std::sync::{Arc, Mutex, PoisonError};

use super::protocol::Response;

/// Where replies go: the app's channel; false once nobody listens.
pub type Sink = Arc<dyn Fn(Response) -> bool + Send + Sync>;

/// Run `work` on a thread called `name` and send its reply to `sink`; when no thread can be
/// started, run it here and return the reply for the caller to send.
pub fn detach(name: &str, sink: &Sink, work: impl FnOnce() -> Response + Send + 'static) -> Option<Response> {
    // The work goes through a slot so that it is still at hand if the thread does not start.
    let slot = Arc::new(Mutex::new(Some(work)));
    let (theirs, sink) = (slot.clone(), sink.clone());
    let started = std::thread::Builder::new().name(name.into()).spawn(move || {
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
