//! Every glyph of every chart stands on the row of its value, as a reader reads the row off
//! the chart's own tick labels (within half a row): on every scene, at 80×24, 100×30 and
//! 120×40, in the lab and in the projector view, on every bundled scenario with every
//! overlay on (the work–precision chart on the paper's). So no glyph reads as a value its series does not have (the inf-sup chart drew
//! M4's 0.52 on M3's row of 1.07: `*34` read "M4 = M3 ≈ 1"). And the converse: each value
//! plotted has a glyph of its series on its row (within half a row), or, for an overlay (drawn
//! under the lines), the cells about it are held by what lies above it.

use riplab::scenario::Scenario;
use riplab::tui::app::{App, Scene};
use riplab::tui::engine::Engine;
use riplab::tui::render_app;
use riplab::tui::settle::settle;
use riplab::tui::view::plot::drawn::{self, Charted};

use super::axes::{Chart, chart, place};
use super::friction::LOOK;

const SIZES: [(u16, u16); 3] = [(80, 24), (100, 30), (120, 40)];

/// The bundled scenarios the lab takes, by file name (one body: `riplab lab` refuses a
/// two-body scenario, `[upper]`).
fn scenarios() -> Vec<(String, Scenario)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            (name, Scenario::load(&p).unwrap())
        })
        .filter(|(_, s)| s.upper.is_none())
        .collect()
}

/// The value a reader reads at `line` of the chart: the y ticks' values spread evenly over
/// their rows; and half a row's worth (in the axis's units, log10 on a log axis).
fn read(c: &Chart, line: usize, log: bool) -> (f64, f64) {
    let f = |v: f64| if log { v.log10() } else { v };
    let ((l0, v0), (l1, v1)) = (c.y_ticks[0], c.y_ticks[c.y_ticks.len() - 1]);
    let per_line = (f(v0) - f(v1)) / (l1 as f64 - l0 as f64);
    (f(v0) - (line as f64 - l0 as f64) * per_line, per_line.abs() / 2.0)
}

/// The rows of the graph holding `glyph` within four columns of `x`'s (a glyph landing on
/// another's moves up to three cells along its row).
fn rows_with(c: &Chart, glyph: char, x: f64, log: bool) -> Vec<usize> {
    let col = place(&c.x_ticks, x, log).round() as i64;
    c.graph
        .clone()
        .filter(|&r| {
            (col - 4..=col + 4)
                .any(|k| usize::try_from(k).is_ok_and(|k| k > c.axis && c.lines[r].get(k) == Some(&glyph)))
        })
        .collect()
}

/// Every glyph drawn in the graph of `charted` in `frame` stands where its series has a
/// value: within four columns of the value's x (a glyph landing on another's moves up to
/// three cells along its row) and on a row that reads the value within half a row.
fn check(frame: &str, charted: &Charted, what: &str) {
    let prefix: String = charted.title.chars().take(12).collect();
    let c = chart(frame, &prefix);
    let (log_x, log_y) = charted.log;
    let [x0, x1] = charted.x_bounds;
    for (glyph, points) in charted.series.iter().chain(&charted.overlays) {
        // The points inside the chart's x range (the zoomed one), as (column, value on the y
        // axis, value): a glyph drawn is one of them.
        let drawn: Vec<(f64, f64, f64)> = points
            .iter()
            .filter(|&&(x, _)| x >= x0.min(x1) && x <= x0.max(x1))
            .map(|&(x, y)| (place(&c.x_ticks, x, log_x), if log_y { y.log10() } else { y }, y))
            .collect();
        for r in c.graph.clone() {
            for (k, &ch) in c.lines[r].iter().enumerate() {
                if k <= c.axis || k + 1 >= c.lines[r].len() || ch != *glyph {
                    continue;
                }
                let (read, half) = read(&c, r, log_y);
                let at = drawn.iter().any(|&(col, v, _)| {
                    (col - k as f64).abs() <= 4.5 && (read - v).abs() <= half * (1.0 + 1e-6)
                });
                let near: Vec<f64> = drawn
                    .iter()
                    .filter(|p| (p.0 - k as f64).abs() <= 4.5)
                    .map(|p| p.2)
                    .collect();
                assert!(
                    at,
                    "{what}: `{glyph}` at line {r}, column {k} reads {read} (±{half}); its values there: {near:?}\n{frame}"
                );
            }
        }
    }
}

/// Each value of `charted` inside its ranges has a glyph of its series within four columns
/// of its x on a row that reads it within half a row; an overlay's value may instead have
/// every cell within two columns on that row held by something else (a line's dots or another
/// glyph: the overlay lies under them there).
fn check_converse(frame: &str, charted: &Charted, what: &str) {
    let prefix: String = charted.title.chars().take(12).collect();
    let c = chart(frame, &prefix);
    let (log_x, log_y) = charted.log;
    let [x0, x1] = charted.x_bounds;
    let series = charted.series.iter().map(|s| (s, false));
    for ((glyph, points), beneath) in series.chain(charted.overlays.iter().map(|s| (s, true))) {
        // The values inside the chart's ranges (the y axis of the pressure chart leaves the
        // gap's far depths out).
        let [y0, y1] = charted.y_bounds;
        let inside = |p: &&(f64, f64)| {
            p.0 >= x0.min(x1) && p.0 <= x0.max(x1) && p.1 >= y0.min(y1) && p.1 <= y0.max(y1)
        };
        for &(x, y) in points.iter().filter(inside) {
            let v = if log_y { y.log10() } else { y };
            let col = place(&c.x_ticks, x, log_x).round() as i64;
            let rows: Vec<usize> = c
                .graph
                .clone()
                .filter(|&r| {
                    let (read, half) = read(&c, r, log_y);
                    (read - v).abs() <= half * (1.0 + 1e-6)
                })
                .collect();
            let cell = |r: usize, k: i64| {
                usize::try_from(k)
                    .ok()
                    .filter(|&k| k > c.axis)
                    .and_then(|k| c.lines[r].get(k).copied())
            };
            let found = rows.iter().any(|&r| {
                (col - 4..=col + 4).any(|k| cell(r, k) == Some(*glyph))
                    || (beneath && (col - 2..=col + 2).all(|k| cell(r, k).is_some_and(|ch| ch != ' ')))
            });
            assert!(
                found,
                "{what}: ({x}, {y}) has no `{glyph}` on its rows {rows:?} near column {col}\n{frame}"
            );
        }
    }
}

#[test]
fn every_glyph_stands_on_the_row_of_its_value() {
    for (name, scenario) in scenarios() {
        // One engine per scenario, as the lab keeps one: the scenes share its solves.
        let mut engine = Engine::new(scenario.clone());
        // The work–precision chart on the paper's scenario (its study computes a reference at
        // level 5 for every scheme: minutes on the bigger scenarios).
        let paper = name == "hertz-paper.toml";
        for scene in [
            Scene::Explore,
            Scene::InfSup,
            Scene::Mesh,
            Scene::Convergence,
            Scene::Stress,
        ] {
            if scene == Scene::Convergence && !paper {
                continue;
            }
            let mut app = App::new(scenario.clone());
            app.show_timing = false;
            app.settings.level = 2;
            app.scene = scene;
            app.guides = riplab::tui::app::Guides::ALL;
            settle(&mut app, &mut engine);
            for projector in [false, true] {
                app.overlays.projector = projector;
                for (w, h) in SIZES {
                    drawn::take();
                    let frame = render_app(&app, &LOOK, w, h);
                    for charted in drawn::take() {
                        let what = format!("{name} {scene:?} {w}×{h} projector {projector}");
                        check(&frame, &charted, &what);
                        check_converse(&frame, &charted, &what);
                    }
                }
            }
        }
    }
}

/// The projector view of the inf-sup scene at 80×24 (`riplab render --scene infsup --keys f
/// --size 80x24`): M3's 1.07 and M4's 0.52, 0.31 decades apart, three rows apart or more at
/// every level (the axis from 0.01 to 1 on the rows left beside the one status row, the keys
/// ending the notice's row): never on one row, nor on rows that read alike.
#[test]
fn m3_and_m4_stand_rows_apart_in_the_projector_view() {
    let mut app = super::settled(0, Scene::InfSup);
    // `f`, as `render --keys f` presses it: its notice shares the status row with the keys.
    for key in riplab::tui::render_keys::parse_keys("f").unwrap() {
        app.update(riplab::tui::app::Msg::Key(key));
    }
    assert!(app.overlays.projector);
    drawn::take();
    let frame = render_app(&app, &LOOK, 80, 24);
    let charts = drawn::take();
    let c = chart(&frame, "β_h/√h against h");
    let series = &charts[0].series;
    let points = |g: char| &series.iter().find(|s| s.0 == g).unwrap().1;
    for (&(h, m3), &(_, m4)) in points('3').iter().zip(points('4')) {
        let row = |g: char, v: f64| {
            *rows_with(&c, g, h, true)
                .iter()
                .find(|&&r| {
                    let (read, half) = read(&c, r, true);
                    (read - v.log10()).abs() <= half * (1.0 + 1e-6)
                })
                .unwrap_or_else(|| panic!("`{g}` of {v} at h = {h}\n{frame}"))
        };
        assert!(row('4', m4) >= row('3', m3) + 3, "h = {h}\n{frame}");
    }
}
