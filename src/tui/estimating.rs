//! Inf-sup estimates on a thread of their own: at level 7 one takes
//! seconds (the H¹ form's factorisation and two dense eigenproblems), and the worker serves
//! solves meanwhile.

use std::sync::Arc;
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::Duration;

use super::beta::{InfSup, estimate};
use super::lab_error::LabError;
use super::protocol::{InfSupKey, Response};
use crate::discretization::Discretization;

/// An estimate under way on a thread of its own.
pub struct Estimating {
    /// What is estimated.
    pub key: InfSupKey,
    done: Receiver<Result<InfSup, LabError>>,
}

impl Estimating {
    /// Start estimating `key` on `disc` (its mesh); None if no thread can be started.
    pub fn start(disc: Arc<Discretization>, key: InfSupKey) -> Option<Self> {
        let (tx, done) = mpsc::channel();
        std::thread::Builder::new()
            .name("riplab-estimate".into())
            .spawn(move || {
                // Nobody listens any more when the worker has ended: nothing to do then.
                let _ = tx.send(estimate(&disc, key.rule).map_err(LabError::from));
            })
            .ok()?;
        Some(Estimating { key, done })
    }

    /// The reply for the app if the estimate finished within `wait`; `Err(self)` while it runs.
    pub fn finished(self, wait: Duration) -> Result<Response, Self> {
        let result = match self.done.recv_timeout(wait) {
            Ok(result) => result,
            Err(RecvTimeoutError::Timeout) => return Err(self),
            Err(RecvTimeoutError::Disconnected) => Err(LabError::EstimateEnded),
        };
        Ok(Response::InfSup {
            key: self.key,
            result: Some(result),
        })
    }
}
