//! A key that cannot act in the scene shown says so, and only so: `z` in the mesh scene,
//! the cursor's keys where no chart has a cursor, `E` with friction on (refused before the
//! settings change, the header kept); a wrapped message's further rows are indented; the
//! key bar under each scene.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use riplab::scenario::Scenario;
use riplab::tui::app::{App, Msg, Notice, Scene};
use riplab::tui::render_app;

use super::friction::{LOOK, cattaneo, lab, press};
use super::settled;

fn ch(c: char) -> Msg {
    Msg::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE))
}

/// The header's two rows of a frame.
fn header(frame: &str) -> String {
    frame.lines().take(2).collect::<Vec<_>>().join("\n")
}

#[test]
fn z_and_the_cursor_say_where_they_act() {
    let mut app = settled(1, Scene::Mesh);
    let before = render_app(&app, &LOOK, 80, 24);
    app.update(ch('z'));
    assert!(!app.zoom);
    let said = app.notice.clone().expect("z says why").text;
    assert!(said.contains("z does nothing in the mesh scene"), "{said}");
    let after = render_app(&app, &LOOK, 80, 24);
    assert!(after.contains("z does nothing"), "{after}");
    assert_eq!(header(&before), header(&after));
    for (key, name) in [('x', "x"), (',', ","), ('.', ".")] {
        let mut app = settled(1, Scene::InfSup);
        app.update(ch(key));
        assert!(app.overlays.cursor.is_none());
        let said = app.notice.clone().expect("says why").text;
        assert!(
            said.starts_with(&format!("{name} does nothing in the infsup scene")),
            "{said}"
        );
    }
    // In explore `z` acts and says what it did, both ways.
    let mut app = settled(1, Scene::Explore);
    app.update(ch('z'));
    assert!(app.zoom);
    assert!(
        app.notice
            .clone()
            .unwrap()
            .text
            .starts_with("zoomed to the contact zone")
    );
    app.update(ch('z'));
    assert!(!app.zoom);
    assert!(app.notice.clone().unwrap().text.starts_with("zoom off"));
}

/// `E` on cattaneo-mindlin (friction on): the refusal alone — no "edge grading: 1 pass", no
/// banner —, the settings and the header as they were.
#[test]
fn grading_with_friction_is_refused_before_anything_changes() {
    let (mut app, mut engine) = lab(&cattaneo(), 1);
    let before = render_app(&app, &LOOK, 80, 24);
    let settings = app.settings;
    press(&mut app, &mut engine, "E");
    assert_eq!(app.settings, settings);
    assert!(app.error.is_none());
    let frame = render_app(&app, &LOOK, 80, 24);
    assert_eq!(header(&before), header(&frame));
    assert!(frame.contains("does not take friction"), "{frame}");
    assert!(!frame.contains("edge grading"), "{frame}");
    assert!(!frame.contains("no result for these settings"), "{frame}");
}

/// A message wrapped to further rows indents them under its first word, in the status area
/// and in the banner.
#[test]
fn wrapped_rows_are_indented() {
    let mut app = settled(0, Scene::Explore);
    let long = "a failure long enough to wrap ".repeat(5);
    app.update(Msg::Notice(Notice::failure(long.trim_end().to_string())));
    let frame = render_app(&app, &LOOK, 80, 24);
    let lines: Vec<&str> = frame.lines().collect();
    let first = lines
        .iter()
        .position(|l| l.starts_with(" ✗ a failure"))
        .expect(&frame);
    let next = lines[first + 1];
    assert!(next.starts_with("   ") && !next.starts_with("    "), "{frame}");
    assert!(
        next.trim_start().starts_with(|c: char| c.is_alphabetic()),
        "{frame}"
    );
}

/// Under every scene a key bar of its own keys, `? help` and `q quit`; `?` shows the scene's
/// keys first and the mouse.
#[test]
fn each_scene_shows_its_key_bar() {
    for (scene, keys) in [
        (Scene::Explore, ["←→ level", "1-4 scheme", "? help", "q quit"]),
        (Scene::InfSup, ["a levels", "f full", "? help", "q quit"]),
        (Scene::Mesh, ["dD depth", "Tab scene", "? help", "q quit"]),
        (Scene::Convergence, ["w compare", "m method", "? help", "q quit"]),
        (Scene::Stress, ["c quantity", "z zoom", "? help", "q quit"]),
    ] {
        let mut app = App::new(Scenario::paper());
        app.show_timing = false;
        app.scene = scene;
        let frame = render_app(&app, &LOOK, 80, 24);
        let bar = frame.lines().last().unwrap();
        for k in keys {
            assert!(bar.contains(k), "{scene:?}: `{k}` in `{bar}`");
        }
        app.update(ch('?'));
        let help = render_app(&app, &LOOK, 80, 24);
        assert!(help.contains("in the"), "{help}");
    }
}
