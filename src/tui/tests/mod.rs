//! The terminal lab and the tour without a terminal: frames, keys, the worker, the stress
//! scene. Unit tests of the crate (the lab is private to the library); what runs the binary
//! is in `tests/cli`.

#[macro_use]
#[path = "../../../tests/common/shared.rs"]
mod common;

mod at_value;
mod authoring;
mod axes;
mod bodies;
mod bodies_cache;
mod bodies_infsup;
mod bodies_meshes;
mod coinciding;
mod friction;
mod friction_frames;
mod graded_study;
mod grading_key;
mod handout_charts;
mod hertz_block;
mod lab_errors;
mod locking;
mod mouse;
mod opening_and_log;
mod overlay_layers;
mod record;
mod refusals;
mod regrade;
mod scenes;
mod screens;
mod stress_scene;
mod tour;
mod tour_bodies;
mod tour_checks;
mod tour_numbers;
mod tour_validation;
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

/// The sizes the embedded tour's walks read: the smallest terminal the lab takes and the
/// projector's.
pub const PAPER_SIZES: [(u16, u16); 2] = [(80, 24), (100, 30)];

/// The embedded tour's frames at [`PAPER_SIZES`], step by step: each step solved once for
/// both sizes (`render_step_at`) and the frames kept for every walk that reads them
/// (`tour::every_step_runs_at_80x24`, `tour::every_step_of_the_paper_tour_100x30`,
/// `tour_numbers`), which solved every step anew each.
pub fn paper_frames() -> &'static [Vec<String>] {
    static FRAMES: std::sync::OnceLock<Vec<Vec<String>>> = std::sync::OnceLock::new();
    FRAMES.get_or_init(|| {
        let tour = riplab::tui::tour::Tour::paper();
        (0..tour.steps.len())
            .map(|i| riplab::tui::tour::render_step_at(&tour, i, &PAPER_SIZES).unwrap())
            .collect()
    })
}

/// Every study row's solve time replaced by a steady one (proportional to its unknowns and
/// passes, M1–M4 a few per cent apart, as measured), so that a work–precision frame is the
/// same on every machine: the tests that use it claim something of the drawing (every mark
/// visible), which measured times made depend on the machine's load.
pub fn steady_times(app: &mut riplab::tui::app::App) {
    for study in app.studies.values_mut().flatten() {
        *study = steady(study);
    }
}

/// `study` with [`steady_times`]' solve times.
pub fn steady(study: &riplab::tui::app::Study) -> std::sync::Arc<riplab::tui::app::Study> {
    let mut steady = study.clone();
    for row in &mut steady.rows {
        let scheme = row
            .scheme
            .chars()
            .last()
            .and_then(|c| c.to_digit(10))
            .unwrap_or(1);
        let passes = 1.0 + f64::from(row.refine_edges);
        row.solve_ms = row
            .solve_ms
            .map(|_| 2.5e-4 * row.n_dofs as f64 * passes * (1.0 + 0.04 * f64::from(scheme)));
    }
    std::sync::Arc::new(steady)
}
