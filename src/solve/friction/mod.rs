//! The friction solve on a discretisation (docs/design.md §11): Γ_C's full trace
//! and its couplings ([`trace`]), and the press and shift of [`crate::contact::friction`]'s
//! laws solved on it into a [`crate::solution::Solution`] ([`solve`]). The laws, the
//! systems and the path, which know nothing of the mesh, are [`crate::contact::friction`].

pub mod solve;
pub mod trace;

pub(super) use solve::solve_frictional;
pub use solve::{Free, check, solve_with};
pub use trace::FrictionTrace;
