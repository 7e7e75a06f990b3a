//! The command line as a user runs it: help and exit codes, bad and hostile input, every
//! README command, the VTU and SVG outputs, and the library's module graph (one test binary).

#[macro_use]
#[path = "../common/mod.rs"]
mod common;

mod accuracy_claims;
mod bad_input;
mod design_map;
mod docs_tables;
mod friction;
mod grading;
mod grading_zone;
mod help;
mod hostile;
mod hostile_again;
mod hostile_cache;
mod infsup_graded;
mod infsup_two_bodies;
mod lab_bodies;
mod lab_commands;
mod modules;
mod plot;
mod pty;
mod readme;
mod record;
mod record_tour;
mod refused_early;
mod render_graded;
mod scenario_words;
mod study_friction;
mod study_notes;
mod study_two_bodies;
mod terminal;
mod tour_files;
mod tours_and_outputs;
mod two_bodies;
mod verify;
mod vtu;
