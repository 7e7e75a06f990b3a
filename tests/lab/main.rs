//! The terminal lab and the tour without a terminal: frames, keys, the worker, the stress
//! scene (one test binary).

#[macro_use]
#[path = "../common/mod.rs"]
mod common;

mod authoring;
mod axes;
mod grading_key;
mod hertz_block;
mod locking;
mod record;
mod screens;
mod tour;
mod tour_numbers;
mod tui;
mod tui_stress;
mod typed_errors;
