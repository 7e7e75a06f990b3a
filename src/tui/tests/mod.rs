//! The terminal lab and the tour without a terminal: frames, keys, the worker, the stress
//! scene. Unit tests of the crate (the lab is private to the library); what runs the binary
//! is in `tests/cli`.

#[macro_use]
#[path = "../../../tests/common/shared.rs"]
mod common;

mod authoring;
mod axes;
mod coinciding;
mod friction;
mod friction_frames;
mod graded_study;
mod grading_key;
mod hertz_block;
mod lab_errors;
mod locking;
mod record;
mod regrade;
mod scenes;
mod screens;
mod stress_scene;
mod tour;
mod tour_numbers;
mod typed_errors;
mod zone_key;

use riplab::scenario::Scenario;

/// The paper's lab at `level`, solved synchronously, with `scene` shown, timings hidden.
pub fn settled(level: u32, scene: riplab::tui::app::Scene) -> riplab::tui::app::App {
    use riplab::tui::engine::Engine;
    use riplab::tui::settle::settle;
    let mut app = riplab::tui::app::App::new(Scenario::paper());
    app.show_timing = false;
    app.settings.level = level;
    app.scene = scene;
    settle(&mut app, &mut Engine::new(Scenario::paper()));
    app
}
