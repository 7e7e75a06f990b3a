//! With edge grading on, a re-solve after an ε or depth
//! change solves on the graded grid it has first, and keeps it (no new grid, no new factor)
//! while the contact edges found there lie inside its refined band; when they left it, the lab
//! grades again from the level's uniform solve. The status line says which.

use std::ops::ControlFlow;
use std::sync::Arc;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use riplab::contact::ContactParams;
use riplab::contact::newton::NewtonOptions;
use riplab::grading::{GradedGrid, RefineEdges};
use riplab::scenario::Scenario;
use riplab::solve::solve_contact;
use riplab::solve::solve_graded;
use riplab::tui::app::{App, Msg, Scene, Solved};
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

/// The paper's lab at `level` graded twice (`E` `E`), solved, on `engine`.
fn graded_lab(engine: &mut Engine, level: u32) -> App {
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.scene = Scene::Explore;
    app.settings.level = level;
    settle(&mut app, engine);
    press(&mut app, engine, 'E');
    press(&mut app, engine, 'E');
    assert_eq!(app.settings.refine_edges, RefineEdges::Passes(2).into());
    app
}

/// The shown solve's grid as a graded grid after `passes` passes.
fn grid_of(solved: &Solved, passes: u32) -> GradedGrid {
    GradedGrid {
        level: solved.key.level,
        passes,
        xs: solved.disc.mesh.xs.clone(),
        ys: solved.disc.mesh.ys.clone(),
    }
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

/// ε × 10 moves the contact edges a little: the lab solves on the graded grid it has (the
/// same discretisation, shared), keeps it, and says so; the result is a fresh solve on a
/// scenario given those lines (the warm start is only a start) to 1e-12.
#[test]
fn a_small_epsilon_change_keeps_the_graded_grid() {
    let mut engine = Engine::new(Scenario::paper());
    let mut app = graded_lab(&mut engine, 2);
    let before = app.current().expect("the graded solve").clone();
    assert_eq!(before.regrade, Some(Regrade::Graded { passes: 2 }));
    press(&mut app, &mut engine, '+');
    assert_eq!(app.settings.epsilon, 1e-5);
    let after = app.current().expect("the re-solve").clone();
    assert_eq!(after.regrade, Some(Regrade::Kept));
    assert!(Arc::ptr_eq(&before.disc, &after.disc), "the same grid and factor");
    assert!(grid_of(&after, 2).holds_edges(&after.solution.points, &after.solution.p));
    let mut lines = Scenario::paper();
    (lines.x_lines, lines.y_lines, lines.level) = (after.disc.mesh.xs.clone(), after.disc.mesh.ys.clone(), 0);
    let disc = lines.discretize(0, app.settings.element).unwrap();
    let fresh = solve_contact(&disc, &params(&app), None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap();
    let sol = &after.solution;
    assert!(fresh.newton.converged && sol.newton.converged);
    assert!(
        relative(&sol.p, &fresh.p) <= 1e-12,
        "p {}",
        relative(&sol.p, &fresh.p)
    );
    assert!(relative(&sol.pbar, &fresh.pbar) <= 1e-12, "p̄");
    assert!(
        (sol.load - fresh.load).abs() <= 1e-12 * fresh.load,
        "{} {}",
        sol.load,
        fresh.load
    );
    let frame = render_app(&app, &LOOK, 80, 24);
    let status = frame.lines().collect::<Vec<_>>()[frame.lines().count() - 3..]
        .join(" ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    assert!(
        status.contains("edges inside the band: kept the graded grid"),
        "{frame}"
    );
}

/// Depth + 0.1 at level 3 moves the edges out of the band: the lab grades again from the level's uniform
/// solve, says so, and its result is `riplab solve --refine-edges 2`'s (the library's graded
/// solve) at the new depth, whose contact edges lie in its band; back to the old depth
/// re-grades again.
#[test]
fn a_large_depth_change_regrades() {
    let mut engine = Engine::new(Scenario::paper());
    let mut app = graded_lab(&mut engine, 3);
    let before = app.current().unwrap().clone();
    press(&mut app, &mut engine, 'D');
    let after = app.current().expect("the re-solve").clone();
    assert_eq!(after.regrade, Some(Regrade::Regraded { passes: 2 }));
    assert!(!Arc::ptr_eq(&before.disc, &after.disc));
    assert_ne!(before.disc.mesh.xs, after.disc.mesh.xs, "other lines");
    assert!(grid_of(&after, 2).holds_edges(&after.solution.points, &after.solution.p));
    let s = Scenario::paper();
    let uniform = s.discretize(3, app.settings.element).unwrap();
    let g = solve_graded(
        &s,
        (3, &uniform),
        &params(&app),
        RefineEdges::Passes(2),
        &NewtonOptions::default(),
    )
    .unwrap();
    assert_eq!(g.grid.xs, after.disc.mesh.xs);
    assert_eq!(g.grid.ys, after.disc.mesh.ys);
    let sol = &after.solution;
    assert!(
        relative(&sol.pbar, &g.sol.pbar) <= 1e-12,
        "p̄ {}",
        relative(&sol.pbar, &g.sol.pbar)
    );
    assert!((sol.load - g.sol.load).abs() <= 1e-12 * g.sol.load);
    let frame = render_app(&app, &LOOK, 80, 24);
    let status = frame.lines().collect::<Vec<_>>()[frame.lines().count() - 3..]
        .join(" ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    assert!(status.contains("edges moved: re-graded, 2 passes"), "{frame}");
    press(&mut app, &mut engine, 'd');
    let back = app.current().unwrap().clone();
    assert_eq!(back.regrade, Some(Regrade::Regraded { passes: 2 }));
    assert_eq!(
        back.disc.mesh.xs, before.disc.mesh.xs,
        "the first depth's lines again"
    );
}

/// A uniform solve lets the graded grid go (its memory is outside the cache's budget): `E`
/// round to 0 passes and on to 2 again grades afresh instead of keeping the old grid.
#[test]
fn a_uniform_solve_lets_the_graded_grid_go() {
    let mut engine = Engine::new(Scenario::paper());
    let mut app = graded_lab(&mut engine, 2);
    let first = app.current().unwrap().clone();
    let mut seen = Vec::new();
    for _ in 0..8 {
        press(&mut app, &mut engine, 'E');
        seen.push((app.settings.refine_edges, app.current().unwrap().regrade));
    }
    use RefineEdges::{Auto, Passes};
    use riplab::grading::Grading::{Edges, Zone};
    // auto: as many passes as p̄ asks (the library's test `auto_grades_until_pbar_settles`).
    assert!(
        matches!(seen[1].1, Some(Regrade::Graded { passes: 1.. })),
        "{seen:?}"
    );
    assert_eq!(
        seen,
        [
            (Edges(Passes(3)), Some(Regrade::Graded { passes: 3 })),
            (Edges(Auto), seen[1].1),
            (Zone(1), Some(Regrade::Graded { passes: 1 })),
            (Zone(2), Some(Regrade::Graded { passes: 2 })),
            (Zone(3), Some(Regrade::Graded { passes: 3 })),
            (Edges(Passes(0)), None),
            (Edges(Passes(1)), Some(Regrade::Graded { passes: 1 })),
            (Edges(Passes(2)), Some(Regrade::Graded { passes: 2 })),
        ]
    );
    let again = app.current().unwrap();
    assert!(!Arc::ptr_eq(&first.disc, &again.disc));
    assert_eq!(
        first.disc.mesh.xs, again.disc.mesh.xs,
        "the same lines, graded again"
    );
}

/// With a graded grid kept, switching friction on (`F`) does not serve that grid's
/// frictionless answer: the lab refuses graded friction before the settings change, and
/// says so.
#[test]
fn the_kept_graded_grid_does_not_serve_a_friction_solve() {
    let scenario = Scenario::load(std::path::Path::new("scenarios/hertz-paper-full.toml")).unwrap();
    let mut engine = Engine::new(scenario.clone());
    let mut app = App::new(scenario);
    app.show_timing = false;
    app.settings.level = 1;
    settle(&mut app, &mut engine);
    press(&mut app, &mut engine, 'E');
    press(&mut app, &mut engine, 'E');
    press(&mut app, &mut engine, '+');
    assert!(app.error.is_none() && app.solved.is_some());
    press(&mut app, &mut engine, 'F');
    assert!(!app.settings.friction.is_on());
    let notice = app.notice.clone().expect("refused");
    assert!(
        notice.failure && notice.text.contains("friction does not take a graded mesh"),
        "{notice:?}"
    );
    assert!(app.solved.as_ref().is_some_and(|s| !s.key.friction.is_on()));
}
