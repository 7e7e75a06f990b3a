//! The failures of the finite element layer: a form that is not positive definite, memory that
//! ran out, and a problem refused before any allocation because it would not fit.

use faer::linalg::cholesky::llt::factor::LltError;
use faer::sparse::FaerError;

/// Bytes as GiB with one decimal, for messages.
pub fn gib(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / (1u64 << 30) as f64)
}

/// A failure of the finite element layer.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FemError {
    /// A zero or negative pivot: the form has a kernel on the free dofs.
    #[error("the matrix is not positive definite (a zero or negative pivot, faer's index {pivot})")]
    NotPositiveDefinite {
        /// faer's index of it, in the factorised matrix's elimination order (its dense kernels
        /// may name the end of the block they were factorising).
        pivot: usize,
    },
    /// An allocation failed although the estimate allowed it (the named step).
    #[error("out of memory in {0}")]
    OutOfMemory(&'static str),
    /// The memory estimate exceeds the memory this process may use: refused before allocating.
    #[error("{unknowns} unknowns need about {} and {} is available", gib(*need), gib(*available))]
    TooLarge {
        /// The number of unknowns (free dofs).
        unknowns: usize,
        /// Estimated peak, bytes.
        need: u64,
        /// What the process may still allocate, bytes.
        available: u64,
    },
}

impl From<LltError> for FemError {
    /// faer's only failure of a numeric Cholesky factorisation, its pivot kept.
    fn from(e: LltError) -> Self {
        let LltError::NonPositivePivot { index } = e;
        FemError::NotPositiveDefinite { pivot: index }
    }
}

impl FemError {
    /// The error of a failed faer call in the step `what`.
    pub(crate) fn from_faer(what: &'static str) -> impl Fn(FaerError) -> FemError {
        // faer's other failure is an index overflow: a size beyond any memory too.
        move |_| FemError::OutOfMemory(what)
    }
}
