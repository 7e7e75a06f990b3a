//! The typed errors of the numerics: every way a discretisation or a contact solve can fail,
//! each variant carrying what its message needs, and whether the fault is the input's (a
//! request that has no answer) or the solver's ([`SolveError::is_input`]; the command line
//! turns that into its exit code).

use faer::linalg::evd::EvdError;

use crate::text::num;

/// Why a discretisation or a contact solve produced no result.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
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
    /// The problem does not fit the memory this process may use.
    #[error("{0}")]
    TooLarge(String),
    /// A parameter of the solve is outside the range where its answer means something (or
    /// where double precision can represent it).
    #[error("{what}: {message}")]
    Input {
        /// The parameter, e.g. "the indentation depth".
        what: &'static str,
        /// What is wrong with it, and what is allowed.
        message: String,
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
        diagnosis: String,
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
            SolveError::Kernel { .. } | SolveError::TooLarge(_) | SolveError::Input { .. }
        )
    }
}
