//! The door of the fuzz targets (`fuzz/fuzz_targets/`, STABILITY.md "Random input"), open
//! only with the `fuzzing` feature and hidden from the documentation: the parsers of what a
//! user types that are private to the library — a tour file's, and the command line's level
//! ranges and numbers — and the ranges a parsed scenario is checked against. (A scenario
//! file's parser, [`crate::Scenario::parse`], and a scheme's, [`crate::scheme::Scheme::parse`],
//! are public.)

pub use crate::check::{LENGTH, YOUNG};
pub use crate::cli::{number, parse_levels};
pub use crate::tui::tour::Tour;
