//! The finite element layer: quadrature, cell bases, dofs, assembly, the grid's ordering and
//! the condensation onto Γ_C (DESIGN §2), with the memory those need.

pub mod assembly;
pub mod basis;
pub mod condense;
pub mod dofs;
pub mod error;
pub mod memory;
pub mod ordering;
pub mod quadrature;

pub use assembly::{Form, Integration, SymCsc, apply, assemble, body_load, h1_error};
pub use dofs::DofMap;
pub use error::FemError;

/// Run the numeric factorisation and the dense work on Γ_C on `threads` threads (1: on the
/// caller's thread). Every result is bit-identical for any count (tests/threads.rs).
pub fn set_threads(threads: usize) {
    faer::set_global_parallelism(match std::num::NonZeroUsize::new(threads) {
        Some(n) if threads > 1 => faer::Par::Rayon(n),
        _ => faer::Par::Seq,
    });
}
