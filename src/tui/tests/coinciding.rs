//! A line that lies on an earlier one says so in
//! the legend. M3's raw p (trapezoid: linear between the vertices, where p̄ = p) is drawn along
//! p̄'s own path, so its dotted line cannot be seen apart; M1's (gauss1: a step per edge) can.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::symbols::Marker;
use riplab::scenario::Scenario;
use riplab::tui::app::{Msg, Scene};
use riplab::tui::engine::Engine;
use riplab::tui::render_app;
use riplab::tui::settle::{carry_out, settle};
use riplab::tui::theme::Theme;
use riplab::tui::view::Look;

use crate::tui::tests::settled;

const LOOK: Look = Look {
    theme: Theme { color: false },
    marker: Marker::Braille,
};

/// The pressure chart's legend on the paper's scenario at level 2, for scheme key `scheme`, at
/// every size from 80×24 to 200×60.
fn legends(scheme: char) -> Vec<String> {
    let mut app = settled(2, Scene::Explore);
    let mut engine = Engine::new(Scenario::paper());
    let key = KeyEvent::new(KeyCode::Char(scheme), KeyModifiers::NONE);
    let commands = app.update(Msg::Key(key)).commands;
    carry_out(&mut app, &mut engine, commands);
    settle(&mut app, &mut engine);
    [(80, 24), (100, 30), (120, 40), (200, 60)]
        .into_iter()
        .map(|(w, h)| {
            let frame = render_app(&app, &LOOK, w, h);
            let legend = frame
                .lines()
                .find(|l| l.contains("p̄ smoothed"))
                .unwrap_or_else(|| panic!("no legend at {w}×{h}\n{frame}"));
            legend.to_string()
        })
        .collect()
}

#[test]
fn m3s_raw_pressure_is_said_to_lie_on_pbar() {
    for legend in legends('3') {
        assert!(legend.contains("p trapezoid (= p̄)"), "{legend}");
    }
}

#[test]
fn m1s_raw_pressure_is_not_said_to_lie_on_pbar() {
    for legend in legends('1') {
        assert!(legend.contains("p gauss1") && !legend.contains("(= "), "{legend}");
    }
}
