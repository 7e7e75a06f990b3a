//! The pressure chart's overlays lie under p̄ (docs/lab.md, "Overlays"): on
//! scenarios/cattaneo-mindlin.toml at 80×24, with each overlay on alone, p̄ stays visible over
//! at least half of its contact cells (overlay marks printed over the braille covered it). And
//! every chart keeps 8 data rows at 80×24, the panels and tables yielding first.

use ratatui::Terminal;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::symbols::Marker;
use riplab::tui::app::{App, Guides, Scene};
use riplab::tui::keys::Guide;
use riplab::tui::view::plot::drawn::{self, Charted};
use riplab::tui::view::plot::{cell_of, dots_per_cell};
use riplab::tui::view::view;

use super::friction::{LOOK, cattaneo, lab};

/// `app` drawn at `w`×`h`: the buffer and the charts drawn.
fn draw(app: &App, w: u16, h: u16) -> (Buffer, Vec<Charted>) {
    drawn::take();
    let mut terminal = Terminal::new(TestBackend::new(w, h)).unwrap();
    terminal.draw(|frame| view(app, frame, &LOOK)).unwrap();
    (terminal.backend().buffer().clone(), drawn::take())
}

/// The cells of p̄'s contact vertices (p̄ > 0, inside the chart's x range) in `chart`, and
/// how many of them show braille dots.
fn pbar_cells(app: &App, buf: &Buffer, chart: &Charted) -> (usize, usize) {
    let per = dots_per_cell(Marker::Braille);
    let graph = chart.graph;
    let mut cells: Vec<(u16, u16)> = app
        .solved
        .as_ref()
        .unwrap()
        .shown
        .pbar
        .iter()
        .filter(|p| p.1 > 0.0)
        .filter_map(|&(x, p)| {
            let cx = cell_of(x, chart.x_bounds, graph.width, per.0)?;
            let cy = cell_of(p, chart.y_bounds, graph.height, per.1)?;
            Some((graph.x + cx, graph.bottom() - 1 - cy))
        })
        .collect();
    cells.sort_unstable();
    cells.dedup();
    let braille = |c: &(u16, u16)| {
        buf[*c]
            .symbol()
            .chars()
            .next()
            .is_some_and(|ch| ('\u{2801}'..='\u{28ff}').contains(&ch))
    };
    (cells.len(), cells.iter().filter(|c| braille(c)).count())
}

/// Seen failing before the overlays were drawn under p̄: Hertz's and the circle's marks took
/// p̄'s top row (`⢀o+o++o+o+o…`).
#[test]
fn pbar_stays_visible_under_each_overlay_at_80x24() {
    let scenario = cattaneo();
    let level = App::new(scenario.clone()).settings.level;
    let (mut app, _engine) = lab(&scenario, level);
    for (guide, glyph) in [
        (Guide::Hertz, '+'),
        (Guide::Circle, 'o'),
        (Guide::Mindlin, '*'),
        (Guide::Gap, '·'),
    ] {
        app.guides = Guides::default();
        app.update(riplab::tui::app::Msg::Key(crossterm::event::KeyEvent::from(
            crossterm::event::KeyCode::Char(match guide {
                Guide::Gap => 'g',
                Guide::Hertz => 'h',
                Guide::Circle => 'o',
                Guide::Mindlin => 'M',
            }),
        )));
        assert!(app.guides.on(guide), "{guide:?}: {:?}", app.notice);
        let (buf, charts) = draw(&app, 80, 24);
        let text = riplab::tui::buffer_text(&buf);
        let chart = charts
            .iter()
            .find(|c| c.title.starts_with("p and t on Γ_C"))
            .unwrap_or_else(|| panic!("no pressure chart\n{text}"));
        // The overlay is drawn (its marks are in the graph), not left out.
        assert_eq!(chart.hidden, 0, "{guide:?}\n{text}");
        let graph = chart.graph;
        let marks = (graph.y..graph.bottom())
            .flat_map(|r| (graph.x..graph.right()).map(move |c| (c, r)))
            .filter(|&c| buf[c].symbol() == glyph.to_string())
            .count();
        assert!(marks > 0, "{guide:?}: no `{glyph}` in\n{text}");
        let (total, visible) = pbar_cells(&app, &buf, chart);
        assert!(total >= 4, "{guide:?}: {total} contact cells\n{text}");
        assert!(
            2 * visible >= total,
            "{guide:?}: p̄ visible in {visible} of its {total} contact cells\n{text}"
        );
    }
}

/// Every chart of every scene has 8 data rows or more at 80×24 (the explore scene's
/// pressure chart had 6 to 7, the inf-sup and the work–precision charts 6): the panels below
/// give their rows first. Seen failing before the panels yielded.
#[test]
fn every_chart_has_eight_data_rows_at_80x24() {
    let scenario = cattaneo();
    let level = App::new(scenario.clone()).settings.level;
    let (friction, _engine) = lab(&scenario, level);
    let mut apps = vec![("cattaneo-mindlin explore", friction)];
    for scene in [Scene::Explore, Scene::InfSup, Scene::Convergence] {
        let mut app = super::settled(1, scene);
        super::steady_times(&mut app);
        apps.push(("hertz-paper", app));
    }
    for (name, app) in &apps {
        let (buf, charts) = draw(app, 80, 24);
        let text = riplab::tui::buffer_text(&buf);
        assert!(!charts.is_empty(), "{name} {:?}: no chart\n{text}", app.scene);
        for chart in charts {
            assert!(
                chart.graph.height >= 8,
                "{name} {:?}: `{}` has {} data rows\n{text}",
                app.scene,
                chart.title,
                chart.graph.height
            );
        }
    }
}
