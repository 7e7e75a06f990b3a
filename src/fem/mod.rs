//! The finite element layer: quadrature, cell bases, dofs and assembly (DESIGN §2).

pub mod assembly;
pub mod basis;
pub mod condense;
pub mod dofs;
pub mod quadrature;

pub use assembly::{Form, Integration, SymCsc, apply, assemble, body_load, h1_error};
pub use dofs::DofMap;
