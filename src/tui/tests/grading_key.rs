//! `E` cycles the edge grading (0, 1, 2, 3 passes, auto),
//! says what it set, the header shows it (`level 1+2e`) and the solve shown is the graded one:
//! the same as the library's graded solve of the same settings, on its graded mesh.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use riplab::contact::newton::NewtonOptions;
use riplab::contact::{ContactParams, Method};
use riplab::grading::{Grading, RefineEdges};
use riplab::scenario::Scenario;
use riplab::solve::solve_graded;
use riplab::tui::app::{App, Msg, Scene};
use riplab::tui::engine::Engine;
use riplab::tui::regrade::Regrade;
use riplab::tui::render_app;
use riplab::tui::settle::{carry_out, settle};

use crate::tui::tests::settled;

const LOOK: riplab::tui::view::Look = riplab::tui::view::Look {
    theme: riplab::tui::theme::Theme { color: false },
    marker: ratatui::symbols::Marker::Braille,
};

fn press(app: &mut App, engine: &mut Engine, c: char) {
    let commands = app
        .update(Msg::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE)))
        .commands;
    carry_out(app, engine, commands);
}

#[test]
fn e_cycles_the_grading_and_the_lab_shows_the_graded_solve() {
    let mut app = settled(1, Scene::Explore);
    let mut engine = Engine::new(Scenario::paper());
    let uniform_dofs = app.current().unwrap().disc.n_dofs();
    let mut seen = Vec::new();
    for _ in 0..8 {
        press(&mut app, &mut engine, 'E');
        seen.push(app.settings.refine_edges);
    }
    use Grading::{Edges, Zone};
    use RefineEdges::{Auto, Passes};
    assert_eq!(
        seen,
        [
            Edges(Passes(1)),
            Edges(Passes(2)),
            Edges(Passes(3)),
            Edges(Auto),
            Zone(1),
            Zone(2),
            Zone(3),
            Edges(Passes(0))
        ]
    );
    press(&mut app, &mut engine, 'E');
    press(&mut app, &mut engine, 'E');
    settle(&mut app, &mut engine);
    assert!(
        app.notice
            .as_ref()
            .unwrap()
            .text
            .contains("edge grading: 2 passes")
    );
    let shown = app.current().expect("the graded solve").clone();
    let frame = render_app(&app, &LOOK, 80, 24);
    assert!(frame.contains("level 1+2e"), "{frame}");
    // The library's graded solve of the same settings: same mesh, same load.
    let scenario = Scenario::paper();
    let uniform = scenario.discretize(1, scenario.element).unwrap();
    let params = ContactParams {
        rule: scenario.rule,
        method: Method::Penalty,
        epsilon: app.settings.epsilon,
        obstacle: scenario.obstacle.clone(),
    };
    let g = solve_graded(
        &scenario,
        (1, &uniform),
        &params,
        Passes(2),
        &NewtonOptions::default(),
    )
    .unwrap();
    let graded = g.graded.expect("two passes made");
    assert_eq!(shown.disc.n_dofs(), graded.n_dofs());
    assert!(graded.n_dofs() > uniform_dofs);
    let (a, b) = (shown.solution.load, g.sol.load);
    assert!((a - b).abs() <= 1e-9 * b, "{a} against {b}");
    assert!(
        frame.contains(&format!(" el {} dofs", graded.n_dofs())),
        "{frame}"
    );
}

/// Item 4 with item 6: the mesh scene draws a graded mesh's dense lines no closer than two
/// columns (one row) apart, so that the grading reads as denser lines, not solid blocks (it
/// drew full braille cells ⣿ at the contact edges at 80×24).
#[test]
fn a_graded_mesh_reads_as_lines_not_blocks() {
    let mut app = settled(2, Scene::Mesh);
    let mut engine = Engine::new(Scenario::paper());
    press(&mut app, &mut engine, 'E');
    press(&mut app, &mut engine, 'E');
    settle(&mut app, &mut engine);
    for (w, h) in [(80, 24), (120, 40)] {
        let frame = render_app(&app, &LOOK, w, h);
        assert!(frame.contains("level 2+2e"), "{frame}");
        assert!(!frame.contains('⣿'), "a solid block at {w}×{h}\n{frame}");
    }
}

/// `E` onto a grading whose estimate from its lines exceeds the memory the engine may use
/// (here one byte short of the estimate of 2 passes at level 1: the limit derived from it) is
/// refused before any pass is assembled, in the status line's words: the level, the element,
/// the grading, the unknowns and the memory; the pass before, which fits, is solved.
#[test]
fn e_onto_a_grading_beyond_the_memory_is_refused_before_its_assembly() {
    use riplab::fem::memory::Limits;
    let mut app = settled(1, Scene::Explore);
    let mut engine = Engine::new(Scenario::paper());
    let (element, s) = (app.settings.element, Scenario::paper());
    let (_, one) = s.graded_estimate(1, element, RefineEdges::Passes(1).into(), |_| 0);
    let (last, two) = s.graded_estimate(1, element, RefineEdges::Passes(2).into(), |_| 0);
    assert!(one < two, "{one} {two}");
    engine.limits = Some(Limits {
        machine: Some(two - 1),
        ..Limits::default()
    });
    press(&mut app, &mut engine, 'E');
    settle(&mut app, &mut engine);
    assert!(app.error.is_none(), "{:?}", app.error);
    assert_eq!(
        app.current().and_then(|c| c.regrade),
        Some(Regrade::Graded { passes: 1 })
    );
    press(&mut app, &mut engine, 'E');
    settle(&mut app, &mut engine);
    let said = app.error.as_ref().expect("refused").to_string();
    for words in [
        "level 1 with q1 graded at the contact edges, 2 passes (2): ",
        &format!("{} unknowns", last.unknowns),
        "GiB",
        "available",
    ] {
        assert!(said.contains(words), "lacks {words:?}: {said}");
    }
    let frame = render_app(&app, &LOOK, 120, 30);
    assert!(frame.contains("graded at the contact edges, 2 passes"), "{frame}");
}
