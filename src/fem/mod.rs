//! The finite element layer: quadrature, cell bases, dofs, assembly, the grid's ordering and
//! the condensation onto Γ_C (docs/design.md §2), with the memory those need.

pub mod assembly;
pub mod basis;
pub mod condense;
pub mod dofs;
pub mod error;
pub mod factor;
mod gather;
pub mod memory;
pub mod ordering;
mod partial;
pub mod quadrature;
pub mod split;
mod supernodes;

use std::num::NonZeroUsize;
use std::sync::atomic::{AtomicUsize, Ordering};

use faer::Par;

pub use assembly::{Form, Integration, SymCsc, apply, assemble, body_load, h1_error};
pub use dofs::{DofMap, Support};
pub use error::FemError;

/// Threads of the assembly, the factorisation and the trace compliance (1: the caller's thread).
static THREADS: AtomicUsize = AtomicUsize::new(1);

/// Run the assembly, the factorisation (both subdomains side by side) and the trace
/// compliance on `threads` threads; everything else (faer's dense eigensolvers among it) stays
/// on the caller's thread. The work and its order of summation are the same for any count, so
/// the results are bit-identical (tests/threads/main.rs).
pub fn set_threads(threads: usize) {
    THREADS.store(threads.max(1), Ordering::Relaxed);
    faer::set_global_parallelism(Par::Seq);
}

/// The cores this process may run on (its CPU affinity and cgroup quota; 1 when unknown):
/// the default of `--threads` and of the benchmarks.
pub fn available_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// The parallelism [`set_threads`] chose.
pub fn parallelism() -> Par {
    match NonZeroUsize::new(THREADS.load(Ordering::Relaxed)) {
        Some(n) if n.get() > 1 => Par::Rayon(n),
        _ => Par::Seq,
    }
}

/// The sparse factorisations and dense matrices below these sizes (unknowns, order) run on
/// the caller's thread whatever [`set_threads`] chose: faer's parallel kernels cost more in
/// tasks than they save there (two threads made level 3's factorisation 2.5× slower,
/// BENCHMARKS.md "Huge pages"). faer sums in the same order either way, so the choice changes
/// no bit.
const PARALLEL_UNKNOWNS: usize = 50_000;
const PARALLEL_ORDER: usize = 512;

/// The parallelism for a sparse factorisation of `unknowns` unknowns: [`parallelism`] from
/// [`PARALLEL_UNKNOWNS`] on, else sequential.
pub(crate) fn sparse_parallelism(unknowns: usize) -> Par {
    if unknowns >= PARALLEL_UNKNOWNS {
        parallelism()
    } else {
        Par::Seq
    }
}

/// The parallelism for dense work on matrices of order `order`: [`parallelism`] from
/// [`PARALLEL_ORDER`] on, else sequential.
pub(crate) fn dense_parallelism(order: usize) -> Par {
    if order >= PARALLEL_ORDER {
        parallelism()
    } else {
        Par::Seq
    }
}

/// Run `a` and `b`, on two threads when [`set_threads`] chose more than one, else one after
/// the other on the caller's (the results are the same: `a` and `b` share nothing mutable).
pub(crate) fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    if THREADS.load(Ordering::Relaxed) < 2 {
        return (a(), b());
    }
    std::thread::scope(|scope| {
        let second = scope.spawn(b);
        let first = a();
        let second = second
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (first, second)
    })
}
