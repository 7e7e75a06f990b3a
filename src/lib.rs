//! riplab: the reduced-integration penalty (RIP) method for unilateral contact in plane
//! elasticity, after N. Kikuchi, "A smoothing technique for reduced integration penalty methods
//! in contact problems" (1981), beside the exact constraint, the augmented Lagrangian and
//! Nitsche's method, with Tresca or Coulomb friction. Equation numbers (1)–(26) are the
//! paper's; section numbers §1–§11 are those of `docs/design.md`.
//!
//! The paper's problem in a few lines (M1 at level 1, the paper's 128 elements):
//!
//! ```
//! use riplab::{Scenario, solve_scenario};
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
//! The core is re-exported here: a [`Scenario`] (the paper's, or a TOML file: [`ScenarioError`]
//! says where it is wrong), [`solve_scenario`], or a [`Discretization`] and a [`Request`] (a
//! [`Method`] and a [`Rule`], friction, grading) given to the one solve entry [`solve()`] (or
//! [`sweep`]'s instances), the [`Solution`] (p, p̄, the load, the displacement), the inf-sup
//! estimate [`inf_sup`], the refinement [`study()`], the stresses [`quadrature_stresses`] and the
//! [`vtu`] files; [`SolveError`] is every way a solve fails. The modules hold the rest of each
//! concept's vocabulary; the finite element layer, the outputs, the cache, the plots and the
//! verify pack are public for the binary's tests and benches only (hidden from these docs). The terminal lab and the command line are private: the binary runs
//! them through `run_command_line` (the `cli` feature, on by default), a program with the
//! `tui` feature alone opens the lab with `run_lab`, and without default features (`cargo
//! build --no-default-features`) the library builds without either.

// Every public item is documented, and every public fallible function has an `# Errors`
// section; CI's clippy makes either missing an error.
#![warn(missing_docs)]
#![warn(clippy::missing_errors_doc)]

// The lab's unit tests share helpers with the integration tests, which name the crate.
#[cfg(test)]
extern crate self as riplab;

// The core: what a program needs to pose the paper's problem, solve it and analyse the
// result; each item's home module holds the rest of its vocabulary.
pub use contact::solution::Solution;
pub use contact::{Method, Rule};
pub use discretization::Discretization;
pub use error::SolveError;
pub use infsup::{InfSup, inf_sup};
pub use input::ScenarioError;
pub use mesh::Element;
pub use scenario::Scenario;
pub use solve::{Request, solve, solve_scenario, sweep};
pub use stress::{StressField, quadrature_stresses};
pub use study::{Study, study};

#[doc(hidden)]
pub mod cache;
pub(crate) mod check;
#[cfg(feature = "cli")]
mod cli;
pub mod contact;
pub mod discretization;
pub mod error;
#[doc(hidden)]
pub mod fem;
#[cfg(feature = "fuzzing")]
#[doc(hidden)]
pub mod fuzzing;
pub mod grading;
#[doc(hidden)]
pub mod huge_pages;
pub mod infsup;
pub(crate) mod input;
pub mod material;
pub mod mesh;
#[doc(hidden)]
pub mod output;
#[doc(hidden)]
pub mod plot;
pub mod scenario;
pub mod scheme;
pub mod solve;
pub mod stress;
pub mod study;
pub(crate) mod text;
// Without the command line, the lab's tour, `render` and recording are built but reached by
// nothing: only [`run_lab`] is.
#[cfg(feature = "tui")]
#[cfg_attr(not(feature = "cli"), allow(dead_code, unused_imports))]
mod tui;
#[doc(hidden)]
pub mod verify;
pub mod vtu;
pub mod warning;

/// The terminal lab on `scenario` until the user quits, as `riplab [SCENARIO]` opens it
/// (docs/design.md §9, `tui/`); with the `tui` feature, a program needs no argument parser
/// to embed it.
///
/// # Errors
///
/// The terminal could not be set up, read or written.
#[cfg(feature = "tui")]
pub fn run_lab(scenario: Scenario) -> std::io::Result<()> {
    tui::run(scenario, None, &tui::TuiOptions::default(), None).map_err(|e| match e {
        tui::RunError::Terminal(e) => e,
        // Nothing is recorded here.
        e @ tui::RunError::Recording(_) => std::io::Error::other(e.to_string()),
    })
}

/// The `riplab` binary's command line (`riplab --help`): parse the arguments, run the command,
/// and return its exit code (docs/design.md §8). The terminal lab and the command line are
/// private to the library; this is their one entry.
#[cfg(feature = "cli")]
pub fn run_command_line() -> std::process::ExitCode {
    cli::main()
}
