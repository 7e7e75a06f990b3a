//! The typed errors of the numerics: every way a discretisation or a contact solve can fail,
//! each variant carrying what its message needs, and whether the fault is the input's (a
//! request that has no answer) or the solver's ([`SolveError::is_input`]; the command line
//! turns that into its exit code).

use faer::linalg::evd::EvdError;

pub use crate::check::{Allowed, CheckError};
use crate::fem::error::gib;
use crate::mesh::Element;
use crate::text::num;

mod diagnosis;
mod friction;
mod input;
mod method;
pub use diagnosis::Diagnosis;
pub use friction::FrictionError;
pub use input::InputFault;
pub use method::MethodError;

/// Why a discretisation or a contact solve produced no result.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SolveError {
    /// The caller cancelled the solve (from its progress callback).
    #[error("the solve was cancelled")]
    Cancelled,
    /// A Cholesky factorisation met a zero or negative pivot: with the checks on the input
    /// this means a body not held against rigid motion (or a matrix lost to round-off).
    #[error(
        "the {matrix} is not positive definite (a zero or negative pivot, faer's index {pivot}); is the body held against rigid motion?"
    )]
    Factorization {
        /// The matrix factorised, e.g. "stiffness".
        matrix: &'static str,
        /// faer's index of the pivot ([`crate::fem::FemError::NotPositiveDefinite`]).
        pivot: usize,
    },
    /// ε = 0 asks for more multipliers than there are normal displacements.
    #[error(
        "ε = 0 imposes the constraint exactly at the {points} points of {rule}, more than the {normals} normal displacements on Γ_C: the multipliers are not unique; use a rule without kernel (trapezoid, or simpson with q2)"
    )]
    Kernel {
        /// The contact rule's name ([`crate::contact::Rule::name`]).
        rule: &'static str,
        /// How many points the rule has on Γ_C (one multiplier each).
        points: usize,
        /// How many normal displacements Γ_C has (one per Γ_C node).
        normals: usize,
    },
    /// The problem does not fit the memory this process may use: refused before allocating.
    #[error("{}", too_large(workload, *unknowns, *need, *available))]
    TooLarge {
        /// What was refused.
        workload: Workload,
        /// Its unknowns (free dofs; for Nitsche's method the layer's).
        unknowns: usize,
        /// Its estimated peak, bytes.
        need: u64,
        /// What the process may still allocate, bytes.
        available: u64,
    },
    /// An allocation failed although the estimate allowed it.
    #[error("out of memory in {step} with {unknowns} unknowns: choose a coarser level")]
    OutOfMemory {
        /// The step that ran out, e.g. "the factor".
        step: &'static str,
        /// The unknowns of the problem.
        unknowns: usize,
    },
    /// A parameter of the solve is outside the range where its answer means something (or
    /// where double precision can represent it).
    #[error(transparent)]
    Input(#[from] InputFault),
    /// A value of the solve outside its range ([`CheckError`]).
    #[error("{what}: {source}")]
    Range {
        /// The value, e.g. "the indentation depth".
        what: &'static str,
        /// Why, and what is allowed.
        source: CheckError,
    },
    /// The solver stopped without a result it can certify.
    #[error("{what} did not converge after {iterations} iterations (relative residual {}): {diagnosis}", num(*residual))]
    NotConverged {
        /// What did not converge, e.g. the reference solution.
        what: &'static str,
        /// Iterations taken.
        iterations: usize,
        /// The last relative residual.
        residual: f64,
        /// Why, as far as the solver knows.
        diagnosis: Diagnosis,
    },
    /// A dense eigenvalue solve failed (faer's error).
    #[error("the eigenvalue solve of the inf-sup estimate failed: {0:?}")]
    Eigen(EvdError),
}

impl SolveError {
    /// True when the request itself has no answer (bad input: exit 2), false when the solver
    /// failed on a valid request (exit 1).
    pub fn is_input(&self) -> bool {
        matches!(
            self,
            SolveError::Kernel { .. }
                | SolveError::TooLarge { .. }
                | SolveError::OutOfMemory { .. }
                | SolveError::Input(_)
                | SolveError::Range { .. }
        )
    }
}

/// What a refusal for memory ([`SolveError::TooLarge`]) was about.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Workload {
    /// The discretisation of `level` with `element` ([`crate::discretization::Discretization`]);
    /// `reserved`: less the memory of work under way.
    Level {
        /// The mesh level.
        level: u32,
        /// The element.
        element: Element,
        /// The unknowns on Γ_C.
        trace: usize,
        /// Whether work under way was counted.
        reserved: bool,
    },
    /// The inf-sup estimate at `level` (None: on a mesh already built).
    InfSup {
        /// The level, when asked before building.
        level: Option<u32>,
        /// The element.
        element: Element,
        /// The unknowns on Γ_C.
        trace: usize,
    },
    /// The inf-sup estimate across the interface of two bodies at `level`.
    Interface {
        /// The level.
        level: u32,
        /// The element.
        element: Element,
        /// The two traces' unknowns.
        trace: usize,
    },
    /// Nitsche's dense work on the layer's unknowns along Γ_C.
    Nitsche,
    /// The study's reference (q2 + simpson) at `level` after `refinements` edge refinements.
    Reference {
        /// Its uniform level.
        level: u32,
        /// Its edge refinements.
        refinements: u32,
    },
    /// A solve at `level` with `element` graded as `grading` asks (docs/design.md §6).
    Graded {
        /// Its uniform level.
        level: u32,
        /// The element.
        element: Element,
        /// The grading asked for, in words: where it grades, its passes and its text
        /// (`graded over the contact zone, 8 passes (8z)`).
        grading: String,
    },
    /// A problem of the finite element layer.
    Unknowns,
}

/// [`SolveError::TooLarge`]'s message.
fn too_large(workload: &Workload, unknowns: usize, need: u64, available: u64) -> String {
    let (need, available) = (gib(need), gib(available));
    let limits = crate::fem::memory::limits_in_words();
    match workload {
        Workload::Level {
            level,
            element,
            trace,
            reserved,
        } => format!(
            "level {level} with {} has {unknowns} unknowns ({trace} on Γ_C) and needs about {need}; this process has {available} available ({limits}{}): choose a coarser level",
            element.name(),
            if *reserved {
                ", less the work under way"
            } else {
                ""
            }
        ),
        Workload::InfSup {
            level,
            element,
            trace,
        } => format!(
            "the inf-sup estimate {} with {} ({unknowns} unknowns, {trace} on Γ_C) needs about {need} (the mesh, a second factorisation for the H¹ Gram matrix and the dense matrices on Γ_C); this process has {available} available ({limits}): choose a coarser level",
            level.map_or_else(|| "on this mesh".to_string(), |l| format!("at level {l}")),
            element.name()
        ),
        Workload::Interface {
            level,
            element,
            trace,
        } => format!(
            "the inf-sup estimate across the interface at level {level} with {} ({unknowns} unknowns in the two bodies, {trace} on their traces) needs about {need} (each body's mesh and a factorisation of its H¹ Gram matrix, and the dense matrices on the interface); this process has {available} available ({limits}): choose a coarser level",
            element.name()
        ),
        Workload::Nitsche => format!(
            "Nitsche's method at this level needs about {need} for its dense work on the {unknowns} unknowns along Γ_C, and this process has {available} available: choose a coarser level"
        ),
        Workload::Reference { level, refinements } => format!(
            "the reference (q2 + simpson) at level {level}{}: {unknowns} unknowns need about {need} and {available} is available; choose a coarser --reference-level",
            match refinements {
                0 => String::new(),
                k => format!(" + {k} edge refinements"),
            }
        ),
        Workload::Graded {
            level,
            element,
            grading,
        } => format!(
            "level {level} with {} {}: {unknowns} unknowns on its finest grid, about {need} at the solve's peak (the uniform level's, the previous pass's and the last pass's discretisations); this process has {available} available ({limits}): choose fewer passes or a coarser level",
            element.name(),
            grading
        ),
        Workload::Unknowns => {
            format!(
                "{unknowns} unknowns need about {need} and {available} is available: choose a coarser level"
            )
        }
    }
}
