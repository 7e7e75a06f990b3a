//! Why the worker has no result for the lab: a solve, a mesh build, an inf-sup
//! estimate, a study or the stresses that failed, carried from the worker to the app in its
//! replies ([`super::protocol::Response`]) and shown as before (the source's message).

use crate::error::SolveError;
use crate::mesh::Element;
use crate::stress::StressError;

/// Why a piece of the lab's work has no result: cloneable, since a reply is kept by the app
/// (a failed estimate or study is shown until its settings change) and the frame reports it.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LabError {
    /// The discretisation, the solve, the estimate or the study's reference failed.
    #[error(transparent)]
    Solve(#[from] SolveError),
    /// The stresses of a solution could not be computed.
    #[error(transparent)]
    Stress(#[from] StressError),
    /// A study asked of a worker that runs another scenario.
    #[error("the worker runs {runs}, not {asked}")]
    OtherScenario {
        /// The worker's scenario.
        runs: String,
        /// The study's.
        asked: String,
    },
    /// A mesh build was cancelled before it finished (its thread gave no result).
    #[error("the build of level {level} with {} ended without a result", element.name())]
    BuildEnded {
        /// The mesh level.
        level: u32,
        /// The element.
        element: Element,
    },
    /// Friction asked of a graded solve, at the edges or over the zone (`riplab solve`
    /// refuses it too).
    #[error(
        "friction: grading (E, at the edges or over the zone) does not take friction yet; E back to 0 passes, or F to friction none"
    )]
    GradedFriction,
    /// The thread of an inf-sup estimate ended without sending its result.
    #[error("the estimate ended without a result")]
    EstimateEnded,
}
