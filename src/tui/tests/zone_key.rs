//! `E` goes on from the edge gradings to 1z, 2z, 3z (passes
//! over the contact zone), says so, the header shows `level 2+3z`, and the solve shown is the
//! library's zone-graded solve of the same settings (the engine calls the same
//! `riplab::solve::solve_graded`); an ε change keeps the zone grid while the contact zone
//! stays in its finest band; friction with zone grading is refused as with edge grading; a
//! scenario's `refine_edges = "3z"` opens the lab graded so.

use std::ops::ControlFlow;
use std::sync::Arc;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use riplab::contact::ContactParams;
use riplab::contact::newton::NewtonOptions;
use riplab::grading::{GradedGrid, Grading};
use riplab::scenario::Scenario;
use riplab::solve::solve_contact;
use riplab::solve::solve_graded;
use riplab::tui::app::{App, Msg};
use riplab::tui::engine::Engine;
use riplab::tui::regrade::Regrade;
use riplab::tui::render_app;
use riplab::tui::settle::{carry_out, settle};

const LOOK: riplab::tui::view::Look = riplab::tui::view::Look {
    theme: riplab::tui::theme::Theme { color: false },
    marker: ratatui::symbols::Marker::Braille,
};

fn press(app: &mut App, engine: &mut Engine, c: char) {
    let commands = app
        .update(Msg::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE)))
        .commands;
    carry_out(app, engine, commands);
    settle(app, engine);
}

/// The paper's contact parameters at the lab's settings of `app`.
fn params(app: &App) -> ContactParams {
    let s = &app.settings;
    ContactParams {
        rule: s.rule,
        method: s.method,
        epsilon: s.epsilon,
        obstacle: app.scenario.obstacle.with_depth(s.depth),
    }
}

/// The largest difference of `a` and `b` relative to the largest |b|.
fn relative(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let top = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max) / top
}

/// Seven presses of `E` from the uniform level reach `3z`; the notice, the header and the
/// solve are the zone grading's: the library's `solve_graded` with `Grading::Zone(3)` at
/// level 2 has the same lines, p, p̄ and load (to 1e-12).
#[test]
fn e_reaches_the_zone_grading_and_the_lab_shows_its_solve() {
    let mut engine = Engine::new(Scenario::paper());
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.settings.level = 2;
    settle(&mut app, &mut engine);
    for _ in 0..7 {
        press(&mut app, &mut engine, 'E');
    }
    assert_eq!(app.settings.refine_edges, Grading::Zone(3));
    let notice = &app.notice.as_ref().unwrap().text;
    assert!(notice.contains("zone grading: 3 passes"), "{notice}");
    let shown = app.current().expect("the zone-graded solve").clone();
    assert_eq!(shown.regrade, Some(Regrade::Graded { passes: 3 }));
    let frame = render_app(&app, &LOOK, 80, 24);
    assert!(frame.contains("level 2+3z"), "{frame}");
    let s = Scenario::paper();
    let uniform = s.discretize(2, app.settings.element).unwrap();
    let g = solve_graded(
        &s,
        (2, &uniform),
        &params(&app),
        Grading::Zone(3),
        &NewtonOptions::default(),
    )
    .unwrap();
    assert_eq!(
        (g.grid.passes, &g.grid.xs, &g.grid.ys),
        (3, &shown.disc.mesh.xs, &shown.disc.mesh.ys)
    );
    let sol = &shown.solution;
    assert!(
        relative(&sol.p, &g.sol.p) <= 1e-12,
        "p {}",
        relative(&sol.p, &g.sol.p)
    );
    assert!(relative(&sol.pbar, &g.sol.pbar) <= 1e-12, "p̄");
    assert!((sol.load - g.sol.load).abs() <= 1e-12 * g.sol.load);
    assert!(
        frame.contains(&format!(" el {} dofs", g.graded.unwrap().n_dofs())),
        "{frame}"
    );
}

/// ε × 10 on a `3z` grid: the contact zone found there lies in the grid's finest band, so the
/// lab keeps the grid (the same discretisation) and says so; the result is a fresh solve on
/// those lines to 1e-12.
#[test]
fn an_epsilon_change_keeps_the_zone_grid() {
    let mut scenario = Scenario::paper();
    scenario.set_grading(Grading::Zone(3));
    let mut engine = Engine::new(scenario.clone());
    let mut app = App::new(scenario);
    app.show_timing = false;
    app.settings.level = 2;
    assert_eq!(
        app.settings.refine_edges,
        Grading::Zone(3),
        "the scenario's grading"
    );
    settle(&mut app, &mut engine);
    let before = app.current().expect("the zone-graded solve").clone();
    press(&mut app, &mut engine, '+');
    let after = app.current().expect("the re-solve").clone();
    assert_eq!(after.regrade, Some(Regrade::Kept));
    assert!(Arc::ptr_eq(&before.disc, &after.disc), "the same grid and factor");
    let grid = GradedGrid {
        level: 2,
        passes: 3,
        xs: after.disc.mesh.xs.clone(),
        ys: after.disc.mesh.ys.clone(),
    };
    assert!(grid.holds_zone(&after.solution.points, &after.solution.p));
    let fresh = solve_contact(
        &after.disc,
        &params(&app),
        None,
        &NewtonOptions::default(),
        &mut |_| ControlFlow::Continue(()),
    )
    .unwrap();
    let sol = &after.solution;
    assert!(fresh.newton.converged && sol.newton.converged);
    assert!(
        relative(&sol.p, &fresh.p) <= 1e-12,
        "p {}",
        relative(&sol.p, &fresh.p)
    );
    assert!(relative(&sol.pbar, &fresh.pbar) <= 1e-12, "p̄");
    let frame = render_app(&app, &LOOK, 80, 24);
    assert!(frame.contains("kept the graded grid"), "{frame}");
}

/// Friction with zone grading is refused as with edge grading, before the settings change.
#[test]
fn friction_with_zone_grading_is_refused() {
    let mut scenario = Scenario::load(std::path::Path::new("scenarios/hertz-paper-full.toml")).unwrap();
    scenario.set_grading(Grading::Zone(1));
    let mut engine = Engine::new(scenario.clone());
    let mut app = App::new(scenario);
    app.show_timing = false;
    app.settings.level = 1;
    settle(&mut app, &mut engine);
    assert!(app.error.is_none() && app.solved.is_some());
    press(&mut app, &mut engine, 'F');
    assert!(!app.settings.friction.is_on());
    assert!(app.error.is_none());
    let said = app.notice.clone().expect("refused");
    assert!(
        said.failure && said.text.contains("does not take a graded mesh"),
        "{said:?}"
    );
    assert!(app.solved.as_ref().is_some_and(|s| !s.key.friction.is_on()));
}

/// `E` from 1z onto 2z when 2z's estimate from its lines exceeds the memory the engine may
/// use (one byte short of it, derived from the estimate) is refused before its passes are
/// assembled, naming the level, the element, the zone grading and the memory.
#[test]
fn e_onto_a_zone_grading_beyond_the_memory_is_refused_before_its_assembly() {
    use riplab::fem::memory::Limits;
    let mut scenario = Scenario::paper();
    scenario.set_grading(Grading::Zone(1));
    let mut engine = Engine::new(scenario.clone());
    let mut app = App::new(scenario.clone());
    app.show_timing = false;
    app.settings.level = 2;
    settle(&mut app, &mut engine);
    assert_eq!(
        app.current().and_then(|c| c.regrade),
        Some(Regrade::Graded { passes: 1 })
    );
    let (_, need) = scenario.graded_estimate(2, app.settings.element, Grading::Zone(2), |_| 0);
    engine.limits = Some(Limits {
        machine: Some(need - 1),
        ..Limits::default()
    });
    press(&mut app, &mut engine, 'E');
    assert_eq!(app.settings.refine_edges, Grading::Zone(2));
    let said = app.error.as_ref().expect("refused").to_string();
    for words in [
        "level 2 with q1 graded over the contact zone, 2 passes (2z): ",
        "GiB",
        "available",
    ] {
        assert!(said.contains(words), "lacks {words:?}: {said}");
    }
    let frame = render_app(&app, &LOOK, 120, 30);
    assert!(
        frame.contains("graded over the contact zone, 2 passes"),
        "{frame}"
    );
}
