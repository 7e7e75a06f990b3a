//! The lab opens the paper's problem on its phenomenon (level 1, where M1's raw p zigzags,
//! the inf-sup panel's trend shown); the log (`l`) holds every change of state with its time,
//! repeats folded.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use riplab::scenario::Scenario;
use riplab::tui::app::{App, Msg, OPENING_LEVEL};
use riplab::tui::engine::Engine;
use riplab::tui::render_app;
use riplab::tui::settle::{carry_out, settle};

use super::friction::LOOK;

#[test]
fn the_lab_opens_where_p_zigzags() {
    let mut app = App::opening(Scenario::paper());
    app.show_timing = false;
    settle(&mut app, &mut Engine::new(Scenario::paper()));
    assert_eq!(app.settings.level, OPENING_LEVEL);
    // The raw p alternates over the contact zone: the differences of neighbours change sign.
    let p = &app.current().unwrap().solution.p;
    let inside: Vec<f64> = p.iter().copied().filter(|&v| v > 0.0).collect();
    let turns = inside
        .windows(3)
        .filter(|w| (w[1] - w[0]) * (w[2] - w[1]) < 0.0)
        .count();
    assert!(turns >= 3, "p {inside:?}");
    let frame = render_app(&app, &LOOK, 80, 24);
    assert!(frame.contains("level 1"), "{frame}");
    assert!(!frame.contains("trend: p ?"), "{frame}");
    assert!(frame.contains("trend: p ✗"), "{frame}");
}

#[test]
fn the_log_has_every_change_with_its_time_and_folds_repeats() {
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    let mut engine = Engine::new(Scenario::paper());
    settle(&mut app, &mut engine);
    for c in "]2dddddd\t".chars() {
        let key = if c == '\t' { KeyCode::Tab } else { KeyCode::Char(c) };
        let commands = app
            .update(Msg::Key(KeyEvent::new(key, KeyModifiers::NONE)))
            .commands;
        carry_out(&mut app, &mut engine, commands);
    }
    let log: Vec<(String, u32)> = app
        .overlays
        .log
        .iter()
        .map(|e| (e.text.clone(), e.count))
        .collect();
    let has = |text: &str, count: u32| log.iter().any(|(t, n)| t == text && *n == count);
    assert!(has("level 0 → 1", 1), "{log:?}");
    assert!(
        has("rule gauss1 → gauss2", 1) || log.iter().any(|(t, _)| t.starts_with("rule M1")),
        "{log:?}"
    );
    assert!(has("depth 0.8 → 0.2", 6), "{log:?}");
    assert!(has("scene explore → infsup", 1), "{log:?}");
    app.update(Msg::Key(KeyEvent::new(KeyCode::Char('l'), KeyModifiers::NONE)));
    let frame = render_app(&app, &LOOK, 80, 24);
    assert!(frame.contains("0:0"), "the time of each line:\n{frame}");
    assert!(frame.contains("depth 0.8 → 0.2 × 6"), "{frame}");
}
