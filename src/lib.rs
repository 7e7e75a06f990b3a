//! riplab: the reduced-integration penalty (RIP) method for frictionless unilateral contact
//! in plane elasticity, after N. Kikuchi, "A smoothing technique for reduced integration
//! penalty methods in contact problems" (1981). Equation numbers (1)–(26) are the paper's;
//! section numbers §1–§9 are those of `docs/design.md`.
//!
//! The paper's problem in a few lines (M1 at level 1, the paper's 128 elements):
//!
//! ```
//! use riplab::scenario::Scenario;
//! use riplab::solve::solve_scenario;
//!
//! let mut scenario = Scenario::paper();
//! scenario.level = 1;
//! let (_disc, sol) = solve_scenario(&scenario).expect("the paper's problem solves");
//! assert!(sol.newton.converged && sol.warnings.is_empty());
//! // Identity (18) with v = 1: the trapezoid rule on the smoothed p̄ carries the load I(p, 1).
//! let x = &sol.points.vertex_x;
//! let trapezoid: f64 = (0..x.len() - 1)
//!     .map(|e| (x[e + 1] - x[e]) * (sol.pbar[e] + sol.pbar[e + 1]) / 2.0)
//!     .sum();
//! assert!((trapezoid - sol.load).abs() < 1e-9 * sol.load);
//! ```
//!
//! Without default features (`cargo build --no-default-features`) the library builds without
//! the terminal lab (`tui`) and the command line (`cli`).

// Every public item is documented; CI's clippy makes a missing doc an error.
#![warn(missing_docs)]

pub mod cache;
pub mod check;
#[cfg(feature = "cli")]
pub mod cli;
pub mod contact;
pub mod discretization;
pub mod error;
pub mod fem;
pub mod friction;
pub mod grading;
pub mod huge_pages;
pub mod infsup;
pub mod input;
pub mod material;
pub mod mesh;
pub mod nitsche;
pub mod output;
pub mod penalty_error;
pub mod plot;
pub mod refine_edges;
pub mod scenario;
pub mod scheme;
pub mod solution;
pub mod solve;
pub mod stress;
pub mod study;
pub mod text;
#[cfg(feature = "tui")]
pub mod tui;
pub mod verify;
pub mod vtu;
pub mod warning;
