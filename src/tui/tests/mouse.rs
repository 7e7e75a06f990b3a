//! The mouse in the lab: a click on a tab shows its scene, a click on the pressure chart
//! places the cursor at the contact point under it, the wheel scrolls the help and the log;
//! clicks on nothing change nothing. Each acts on where the last frame drew.

use crossterm::event::{KeyModifiers, MouseButton, MouseEvent, MouseEventKind};
use ratatui::symbols::Marker;

use riplab::tui::app::{Msg, Scene};
use riplab::tui::render_app;
use riplab::tui::theme::Theme;
use riplab::tui::view::Look;

use super::settled;

const LOOK: Look = Look {
    theme: Theme { color: true },
    marker: Marker::Braille,
};

fn mouse(kind: MouseEventKind, column: u16, row: u16) -> Msg {
    Msg::Mouse(MouseEvent {
        kind,
        column,
        row,
        modifiers: KeyModifiers::NONE,
    })
}

fn click(column: u16, row: u16) -> Msg {
    mouse(MouseEventKind::Down(MouseButton::Left), column, row)
}

#[test]
fn a_click_on_a_tab_shows_its_scene() {
    let mut app = settled(1, Scene::Explore);
    let frame = render_app(&app, &LOOK, 100, 30);
    let header = frame.lines().next().unwrap();
    for scene in [Scene::Mesh, Scene::Stress, Scene::InfSup, Scene::Explore] {
        // The middle of the tab's name, as the header shows it.
        let at = header.rfind(scene.name()).unwrap();
        let column = header[..at].chars().count() + scene.name().len() / 2;
        let redraw = app.update(click(column as u16, 0)).redraw;
        assert!(redraw && app.scene == scene, "{scene:?}: {:?}", app.scene);
        render_app(&app, &LOOK, 100, 30);
    }
    // The title's row left of the tabs, and the settings' row: nothing.
    assert!(!app.update(click(3, 0)).redraw);
    assert!(!app.update(click(60, 1)).redraw);
    assert_eq!(app.scene, Scene::Explore);
}

#[test]
fn a_click_on_the_pressure_chart_places_the_cursor_under_it() {
    let mut app = settled(2, Scene::Explore);
    render_app(&app, &LOOK, 100, 30);
    let (graph, [lo, hi]) = app.overlays.drawn.get().chart.expect("the chart is drawn");
    let pbar = app.solved.as_ref().unwrap().shown.pbar.clone();
    for fraction in [0.1, 0.5, 0.9] {
        let column = graph.x + (f64::from(graph.width) * fraction) as u16;
        app.update(click(column, graph.y + graph.height / 2));
        let i = app.overlays.cursor.expect("the cursor is shown");
        let x = lo + (hi - lo) * (f64::from(column - graph.x) + 0.5) / f64::from(graph.width);
        let best = pbar.iter().map(|p| (p.0 - x).abs()).fold(f64::INFINITY, f64::min);
        assert!(
            (pbar[i].0 - x).abs() <= best,
            "{fraction}: at {} for x = {x}",
            pbar[i].0
        );
    }
    // Below the chart (the inf-sup panel): the cursor stays.
    let before = app.overlays.cursor;
    app.update(click(graph.x + 1, graph.bottom() + 3));
    assert_eq!(app.overlays.cursor, before);
}

#[test]
fn the_wheel_scrolls_the_help_and_the_log() {
    let mut app = settled(0, Scene::Explore);
    app.update(Msg::Key(crossterm::event::KeyEvent::from(
        crossterm::event::KeyCode::Char('?'),
    )));
    render_app(&app, &LOOK, 80, 24);
    app.update(mouse(MouseEventKind::ScrollDown, 40, 10));
    assert_eq!(app.overlays.help_scroll, 3);
    app.update(mouse(MouseEventKind::ScrollUp, 40, 10));
    assert_eq!(app.overlays.help_scroll, 0);
    assert!(app.show_help, "the wheel does not close the help");
    // Without an overlay the wheel does nothing.
    let mut app = settled(0, Scene::Explore);
    assert!(!app.update(mouse(MouseEventKind::ScrollDown, 40, 10)).redraw);
}
