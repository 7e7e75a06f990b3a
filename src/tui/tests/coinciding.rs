//! A line that lies on an earlier one says so in the legend, and so does a reference line
//! the data cover in every cell. M3's raw p (trapezoid: linear between the vertices, where p̄ = p) is drawn along
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

/// A reference drawn under the data (an overlay: glyphs in the cells the data leave free) on
/// a line through `line_y`, at 80×24 in monochrome: the legend's text.
fn reference_under(line_y: f64) -> String {
    use ratatui::style::Color;
    use riplab::tui::view::plot::{Axis, Plot, Scale, Series, Stroke};
    let xs: Vec<f64> = (0..=40).map(|i| f64::from(i) / 40.0).collect();
    let line: Vec<(f64, f64)> = xs.iter().map(|&x| (x, line_y)).collect();
    let applied: Vec<(f64, f64)> = xs.iter().map(|&x| (x, 1.0)).collect();
    let axis = |title: &str, bounds| Axis {
        title: title.into(),
        bounds,
        scale: Scale::Linear,
    };
    let plot = Plot {
        title: " test ".into(),
        overlays: vec![Series {
            name: "applied 1".into(),
            color: Color::Gray,
            stroke: Stroke::None,
            glyph: Some('─'),
            data: &applied,
        }],
        x: axis("x", [0.0, 1.0]),
        y: axis("p", [0.5, 1.5]),
        series: vec![Series {
            name: "p̄".into(),
            color: Color::Red,
            stroke: Stroke::Solid,
            glyph: None,
            data: &line,
        }],
        marker: Marker::Braille,
        theme: Theme { color: false },
    };
    let mut terminal = ratatui::Terminal::new(ratatui::backend::TestBackend::new(80, 24)).unwrap();
    terminal
        .draw(|f| {
            plot.render(f, f.area()).expect("room for the graph");
        })
        .unwrap();
    let buf = terminal.backend().buffer();
    (0..buf.area.height)
        .map(|y| {
            (0..buf.area.width)
                .map(|x| buf[(x, y)].symbol())
                .collect::<String>()
        })
        .find(|row| row.contains("applied 1"))
        .expect("the legend names the reference")
}

/// Seen failing before: on the two-body patch test, rip-gauss2's p̄ lies within a row of the
/// applied pressure, covers its reference line in every cell, and the legend named a line
/// the chart did not show. A reference every mark of which the data hide says so; one the
/// data leave visible does not.
#[test]
fn a_reference_the_data_cover_is_said_to_be_covered() {
    assert!(reference_under(1.0 + 1e-4).contains("applied 1 (covered)"));
    assert!(!reference_under(1.3).contains("covered"));
}
