//! What the lab and its worker thread say to each other: the keys that name a solve, an
//! inf-sup estimate or a study, the requests, the progress reports and the replies, and the
//! finished solve ([`Solved`]) they share. The app ([`super::app`]) and the worker
//! ([`super::worker`]) both depend on this module and not on each other's insides.

use std::sync::{Arc, OnceLock};
use std::time::Instant;

use crate::contact::{Method, Rule};
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::solve::{Discretization, Solution};
use crate::stress::StressField;
use crate::study::StudyRow;

use super::beta::InfSup;

/// Everything a contact solve depends on (the scenario aside).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveKey {
    pub level: u32,
    pub element: Element,
    pub rule: Rule,
    /// The contact method (`m` cycles it).
    pub method: Method,
    /// The penalty parameter of `penalty` and `alm` (kept while another method is shown).
    pub epsilon: f64,
    pub depth: f64,
}

/// Everything an inf-sup estimate depends on (the scenario aside).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct InfSupKey {
    pub level: u32,
    pub element: Element,
    pub rule: Rule,
}

/// What a work–precision study depends on: the scenario (by name) and the finest level
/// studied; M1–M4 run at levels 0..=`max_level` against the Q2 reference at `max_level + 1`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct StudyKey {
    pub scenario: String,
    pub max_level: u32,
}

impl StudyKey {
    /// The level of the reference solution.
    pub fn reference_level(&self) -> u32 {
        self.max_level + 1
    }
}

/// A finished study: one row per scheme and level, M1–M4 in order.
#[derive(Clone, Debug)]
pub struct Study {
    pub key: StudyKey,
    pub rows: Vec<StudyRow>,
}

/// A study to run; dropped unstarted if a newer generation exists (a running one cannot be
/// stopped, and its reply is dropped by the app if a newer study was asked for meanwhile).
#[derive(Clone, Debug, PartialEq)]
pub struct StudyRequest {
    pub generation: u64,
    pub key: StudyKey,
}

/// A solve to run; `generation` orders requests (a newer one cancels an older one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveRequest {
    pub generation: u64,
    pub key: SolveKey,
}

/// The stresses of `solved` to compute (into its `stresses`, shared with the app).
#[derive(Clone, Debug)]
pub struct StressRequest {
    pub solved: Arc<Solved>,
}

/// Two requests are the same when they are for the same solution.
impl PartialEq for StressRequest {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.solved, &other.solved)
    }
}

/// An inf-sup estimate to run; dropped unstarted if a newer generation exists.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InfSupRequest {
    pub generation: u64,
    pub key: InfSupKey,
}

/// Where a running solve or study is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Progress {
    /// Assembling and factorising K for a new mesh of `unknowns` unknowns at `level`, begun
    /// at `started` and expected to take `estimate_ms` (see [`super::eta`]).
    Assembling {
        level: u32,
        unknowns: usize,
        started: Instant,
        estimate_ms: f64,
    },
    /// A study's stage: the reference (`level` None) or the schemes at `level`.
    Study {
        level: Option<u32>,
        started: Instant,
        estimate_ms: f64,
    },
    /// Newton iteration `iteration` reached relative residual `residual`.
    Newton {
        iteration: usize,
        residual: f64,
        active: usize,
    },
}

/// A message from the worker.
#[derive(Clone, Debug)]
pub enum Response {
    Progress {
        generation: u64,
        progress: Progress,
    },
    Solved {
        generation: u64,
        result: Result<Arc<Solved>, String>,
    },
    /// A stage of the study asked for with `generation` began.
    StudyProgress {
        generation: u64,
        progress: Progress,
    },
    /// The solve of `generation` was superseded and stopped.
    Cancelled {
        generation: u64,
    },
    /// `result` is None when the request was dropped as stale before it started.
    InfSup {
        key: InfSupKey,
        result: Option<Result<InfSup, String>>,
    },
    /// The displacement of the solution with `key` is computed.
    Displaced {
        key: SolveKey,
    },
    /// The stresses of the solution with `key` are computed (or failed; see
    /// [`Solved::stresses`]).
    Stresses {
        key: SolveKey,
    },
    /// `result` is None when the request was dropped as stale before it started.
    Study {
        generation: u64,
        key: StudyKey,
        result: Option<Result<Arc<Study>, String>>,
    },
}

/// A finished solve with the discretisation it was computed on.
#[derive(Clone)]
pub struct Solved {
    pub key: SolveKey,
    pub disc: Arc<Discretization>,
    pub solution: Solution,
    /// Displacement on every dof, node-major (u_x = [2n], u_y = [2n + 1]): one solve with
    /// the whole factor, computed by the worker just after the solution is shown
    /// ([`Engine::displace`]), so that a level step shows its pressures without waiting for it.
    pub displacement: OnceLock<Vec<f64>>,
    /// Wall time of the request, mesh work included, in ms.
    pub total_ms: f64,
    /// The stresses, computed by the worker when the stress scene first shows this solution
    /// ([`Engine::stresses`]).
    pub stresses: OnceLock<Result<Arc<StressField>, String>>,
}

impl Solved {
    /// The displacement ([`Solved::displacement`]), computed on first use and kept.
    pub fn u(&self) -> &[f64] {
        self.displacement
            .get_or_init(|| self.solution.displacement(&self.disc))
    }

    /// The stresses of this solution (on `scenario`'s material), computed on first use and
    /// kept.
    pub fn stress_field(&self, scenario: &Scenario) -> Result<Arc<StressField>, String> {
        self.stresses
            .get_or_init(|| {
                StressField::new(
                    &self.disc.mesh,
                    &scenario.material,
                    scenario.integration,
                    self.u(),
                )
                .map(Arc::new)
                .map_err(|e| e.to_string())
            })
            .clone()
    }
}

impl std::fmt::Debug for Solved {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Solved")
            .field("key", &self.key)
            .field("load", &self.solution.load)
            .finish_non_exhaustive()
    }
}
