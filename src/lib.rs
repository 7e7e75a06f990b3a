//! riplab: the reduced-integration penalty (RIP) method for frictionless unilateral contact
//! in plane elasticity, after N. Kikuchi, "A smoothing technique for reduced integration
//! penalty methods in contact problems" (1981). Equation numbers (1)–(26) are the paper's;
//! section numbers §1–§8 are those of `DESIGN.md`.

pub mod cache;
#[cfg(feature = "cli")]
pub mod cli;
pub mod contact;
pub mod error;
pub mod fem;
pub mod infsup;
pub mod material;
pub mod mesh;
pub mod plot;
pub mod report;
pub mod scenario;
pub mod solve;
pub mod stress;
pub mod study;
pub mod text;
#[cfg(feature = "tui")]
pub mod tui;
pub mod vtu;
pub mod warning;
