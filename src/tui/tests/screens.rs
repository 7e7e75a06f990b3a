//! The screens a class meets first. Every series visible at every size, the first
//! look at the inf-sup and convergence scenes showing levels 0 to 4, no message cut, every key
//! saying what it did, the cursor, the projector view, the log and `render --keys/--marker`.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::symbols::Marker;
use riplab::scenario::Scenario;
use riplab::tui::app::{App, Msg, Scene};
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

/// The sizes a class meets: the smallest, a laptop's, a projector's, a big screen's.
const SIZES: [(u16, u16); 4] = [(80, 24), (100, 30), (120, 40), (200, 60)];

/// Press `keys` (characters) in `app`, running what they ask for on `engine`.
fn press(app: &mut App, engine: &mut Engine, keys: &str) {
    for c in keys.chars() {
        let commands = app
            .update(Msg::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE)))
            .commands;
        carry_out(app, engine, commands);
    }
}

/// The cells of the chart box whose title starts with `title` that lie right of its y axis
/// (the graph, without the legend, the ticks' labels or the border): one string per row.
fn graph_rows<'a>(frame: &'a str, title: &str) -> Vec<String> {
    let lines: Vec<&'a str> = frame.lines().collect();
    let top = lines
        .iter()
        .position(|l| l.starts_with(&format!("┌ {title}")))
        .unwrap_or_else(|| panic!("no chart `{title}` in\n{frame}"));
    let mut out = Vec::new();
    for line in &lines[top + 1..] {
        if line.starts_with('└') {
            break;
        }
        let chars: Vec<char> = line.chars().collect();
        // The y axis: the first ┤ or │ after the border and the ticks' labels.
        let Some(axis) = chars[1..]
            .iter()
            .position(|&c| c == '┤' || c == '│')
            .map(|i| i + 1)
        else {
            continue;
        };
        if axis + 1 < chars.len() && !chars[axis + 1..].contains(&'└') {
            out.push(chars[axis + 1..chars.len() - 1].iter().collect());
        }
    }
    out
}

fn count(rows: &[String], glyph: char) -> usize {
    rows.iter()
        .flat_map(|r| r.chars())
        .filter(|&c| c == glyph)
        .count()
}

/// The inf-sup scene at level 0 shows levels 0 to 4 (five rows of
/// its table, a slope for each stable scheme), and every series its legend names has a mark
/// at each of its five values at every size from 80×24 to 200×60 — M3's equal to M1's p̄
/// (the legend says `(= 3)`) and M4's near 0.52 included. M2 has a kernel: its legend says so.
#[test]
fn the_infsup_scene_shows_five_levels_and_every_series_at_every_size() {
    let app = settled(0, Scene::InfSup);
    for (w, h) in SIZES {
        let frame = render_app(&app, &LOOK, w, h);
        let graph = graph_rows(&frame, "β_h/√h against h");
        for glyph in ['1', '3', '4', '*'] {
            assert!(
                count(&graph, glyph) >= 5,
                "{glyph} at {w}×{h}: {}\n{frame}",
                count(&graph, glyph)
            );
        }
        assert!(frame.contains("M2 β=0, kernel"), "{frame}");
        assert!(frame.contains("M1 p̄ (= 3)"), "{frame}");
        for level in 0..=4 {
            let row = format!(" {level}  ");
            assert!(
                frame.lines().any(|l| l.contains(&row)),
                "level {level} at {w}×{h}\n{frame}"
            );
        }
        // The slope of the bounded M3 (about 0) and of the decaying M1 (about +1) are shown.
        assert!(frame.contains("✗ +1.00") && frame.contains("✓ -0.00"), "{frame}");
    }
}

/// Done when, item 1 for the convergence scene: levels 0 to 4 from the first look (level 0),
/// each scheme's mark at each level, at every size.
#[test]
fn the_convergence_scene_shows_five_levels_and_every_scheme_at_every_size() {
    let mut app = settled(0, Scene::Convergence);
    crate::tui::tests::steady_times(&mut app);
    for (w, h) in SIZES {
        let frame = render_app(&app, &LOOK, w, h);
        assert!(frame.contains("levels 0 to 4"), "{frame}");
        let graph = graph_rows(&frame, "work–precision");
        for glyph in ['1', '2', '3', '4'] {
            assert!(count(&graph, glyph) >= 5, "{glyph} at {w}×{h}\n{frame}");
        }
    }
}

/// No status or help line ends cut at 80×24, in any scene, with the
/// longest warnings (a locking material on a shallow indentation) active; the message wraps
/// to a second row, the key bar below.
#[test]
fn no_status_or_help_line_is_cut_at_80x24() {
    let scenario = crate::tui::tests::common::paper_with(&[("poisson", "poisson = 0.4999999")]);
    for scene in Scene::ALL {
        let mut app = App::new(scenario.clone());
        app.scene = scene;
        let mut engine = Engine::new(scenario.clone());
        settle(&mut app, &mut engine);
        let frame = render_app(&app, &LOOK, 80, 24);
        let lines: Vec<&str> = frame.lines().collect();
        let bar = lines
            .iter()
            .position(|l| l.ends_with("? help  q quit"))
            .unwrap_or_else(|| panic!("no key bar in {scene:?}\n{frame}"));
        // The status rows: from below the scene's last border to the key bar.
        let hints = lines[..bar]
            .iter()
            .rposition(|l| l.contains('┘') || l.contains('└'))
            .map_or(0, |i| i + 1);
        for line in &lines[hints..] {
            assert!(!line.contains('…'), "{scene:?}: cut status\n{frame}");
        }
        if scene == Scene::Explore {
            let status = lines[hints..].join(" ");
            assert!(status.contains("locks"), "the warning whole: {status}");
        }
        // The help: every line reachable by scrolling, none cut.
        press(&mut app, &mut engine, "?");
        let mut seen = String::new();
        for _ in 0..30 {
            seen.push_str(&render_app(&app, &LOOK, 80, 24));
            app.update(Msg::Key(KeyEvent::new(KeyCode::Down, KeyModifiers::NONE)));
        }
        for (keys, what) in riplab::tui::keys::lab_help() {
            assert!(
                seen.contains(what) && seen.contains(keys),
                "{what} not in the help"
            );
        }
    }
}

/// The cursor (`x`) shows a line and a readout of x, p, p̄ and the gap, moved with
/// `,` and `.` one contact point (a vertex of Γ_C) at a time; the readout's p̄ is the
/// solution's own value at that vertex.
#[test]
fn the_cursor_reads_out_the_pressures_at_a_contact_point() {
    let mut app = settled(1, Scene::Explore);
    let mut engine = Engine::new(Scenario::paper());
    press(&mut app, &mut engine, ".");
    assert!(app.notice.as_ref().unwrap().text.contains("x shows it first"));
    press(&mut app, &mut engine, "x");
    let (x0, p0) = app.cursor_point().expect("a cursor");
    let solved = app.solved.clone().unwrap();
    let peak = solved.shown.pbar.iter().fold(0.0f64, |m, &(_, p)| m.max(p));
    assert_eq!(p0, peak, "the cursor starts at p̄'s largest value");
    press(&mut app, &mut engine, "..");
    let (x2, _) = app.cursor_point().unwrap();
    // The distinct contact points (a half model's mirror holds x = 0 twice).
    let mut xs: Vec<f64> = solved.shown.pbar.iter().map(|&(x, _)| x).collect();
    xs.dedup();
    let i0 = xs.iter().position(|&x| x == x0).unwrap();
    assert_eq!(x2, xs[i0 + 2], "two contact points on");
    let frame = render_app(&app, &LOOK, 100, 30);
    let readout = frame
        .lines()
        .find(|l| l.contains("cursor x "))
        .unwrap_or_else(|| panic!("{frame}"));
    let pbar = solved.shown.pbar.iter().find(|&&(x, _)| x == x2).unwrap().1;
    assert!(
        readout.contains(&format!("p̄ {}", riplab::tui::view::fmt::sig(pbar, 4))),
        "{readout}"
    );
    assert!(readout.contains("gap g "), "{readout}");
    press(&mut app, &mut engine, "h");
    let frame = render_app(&app, &LOOK, 100, 30);
    assert!(frame.contains("· Hertz "), "{frame}");
    press(&mut app, &mut engine, "x");
    assert!(app.cursor_point().is_none());
}

/// Every key says what it did or why it did nothing (`c` outside the stress
/// scene, `g` in the stress scene, `a` with nothing left, a key with no action), and while
/// the terminal is too small, keys other than `q` are ignored and say so.
#[test]
fn every_key_says_what_it_did() {
    let mut app = settled(0, Scene::Explore);
    let mut engine = Engine::new(Scenario::paper());
    let said = |app: &App| app.notice.as_ref().map(|n| n.text.clone()).unwrap_or_default();
    press(&mut app, &mut engine, "c");
    assert!(said(&app).contains("stress scene will show"), "{}", said(&app));
    app.scene = Scene::Stress;
    press(&mut app, &mut engine, "g");
    assert!(
        said(&app).contains("gap −g on (drawn on explore's"),
        "{}",
        said(&app)
    );
    app.scene = Scene::InfSup;
    settle(&mut app, &mut engine);
    press(&mut app, &mut engine, "a");
    assert!(said(&app).contains("nothing left to compute"), "{}", said(&app));
    press(&mut app, &mut engine, "y");
    assert!(said(&app).contains("y does nothing here"), "{}", said(&app));
    // Too small: `]` ignored, said; the notice is on the too-small screen.
    app.overlays.too_small = true;
    press(&mut app, &mut engine, "]");
    assert_eq!(app.settings.level, 0);
    assert!(said(&app).contains("] ignored"), "{}", said(&app));
    let frame = render_app(&app, &LOOK, 60, 20);
    assert!(frame.contains("] ignored"), "{frame}");
    press(&mut app, &mut engine, "q");
    assert!(app.should_quit());
    // Every message is in the log, whole.
    let log: Vec<&str> = app.overlays.log.iter().map(|e| e.text.as_str()).collect();
    assert!(
        log.iter().any(|t| t.contains("stress scene will show")),
        "{log:?}"
    );
    assert!(log.iter().any(|t| t.contains("] ignored")), "{log:?}");
}

/// Item 4 on the stress map: `x` draws the cursor's line across the map and its readout in
/// place of the peak's caption.
#[test]
fn the_cursor_crosses_the_stress_map() {
    let mut app = settled(1, Scene::Stress);
    let mut engine = Engine::new(Scenario::paper());
    let before = render_app(&app, &LOOK, 100, 30);
    press(&mut app, &mut engine, "x");
    let after = render_app(&app, &LOOK, 100, 30);
    assert!(
        after.contains("cursor x ") && !before.contains("cursor x "),
        "{after}"
    );
    // A whole column of the map's rows holds the line.
    let rows: Vec<Vec<char>> = after
        .lines()
        .skip(3)
        .take(10)
        .map(|l| l.chars().collect())
        .collect();
    let column = (1..rows[0].len() - 1).find(|&c| rows.iter().all(|r| r.get(c) == Some(&'│')));
    assert!(column.is_some(), "{after}");
}

/// The smaller items: the gap overlay's legend says what its curve is (the gap, scaled).
#[test]
fn the_gap_overlay_says_what_it_draws() {
    let mut app = settled(1, Scene::Explore);
    let mut engine = Engine::new(Scenario::paper());
    press(&mut app, &mut engine, "g");
    let frame = render_app(&app, &LOOK, 100, 30);
    assert!(frame.contains("· gap −g, scaled ×"), "{frame}");
}

/// The smaller items: the stress colour bar's end is the marked maximum (it read 110.5 beside
/// a marked max τ₁ of 113.2).
#[test]
fn the_colour_bar_ends_at_the_marked_maximum() {
    let app = settled(1, Scene::Stress);
    let frame = render_app(&app, &LOOK, 100, 30);
    let caption = frame
        .lines()
        .find(|l| l.contains("max τ₁ = "))
        .expect("the caption");
    let max = caption
        .split("max τ₁ = ")
        .nth(1)
        .unwrap()
        .split_whitespace()
        .next()
        .unwrap();
    let bar_top = frame.lines().nth(3).unwrap().trim_end_matches('│').trim_end();
    assert!(bar_top.ends_with(max), "bar `{bar_top}`, max {max}\n{frame}");
}

/// Item 2, progressively: the convergence study hands over each finished level's rows, and
/// the scene draws them (every scheme's mark at each level so far) while the status line says
/// what is being computed; the whole study replaces them.
#[test]
fn the_convergence_points_appear_as_their_levels_finish() {
    use riplab::tui::app::{Command, Response, Study};
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.scene = Scene::Convergence;
    let commands = app.update(Msg::Resize).commands;
    let req = commands
        .iter()
        .find_map(|c| match c {
            Command::Study(r) => Some(r.clone()),
            _ => None,
        })
        .expect("a study");
    let mut partials: Vec<std::sync::Arc<Study>> = Vec::new();
    let whole = Engine::new(Scenario::paper())
        .studying(&req.key)
        .unwrap()
        .run_shown(&mut |_| {}, &mut |s| partials.push(s))
        .unwrap();
    // The chart's x is the measured solve time: steady ones, so that where the points stand
    // (and whether two share a cell) does not depend on the host's load.
    let partials: Vec<std::sync::Arc<Study>> =
        partials.iter().map(|s| crate::tui::tests::steady(s)).collect();
    let whole = crate::tui::tests::steady(&whole);
    let finest = |s: &Study| s.rows.iter().map(|r| r.level).max();
    let levels: Vec<Option<u32>> = partials.iter().map(|s| finest(s)).collect();
    assert_eq!(levels, [Some(0), Some(1), Some(2), Some(3)]);
    // Each partial's rows are the whole study's at those levels (same errors).
    let errors = |s: &Study, level: u32| -> Vec<Option<f64>> {
        s.rows
            .iter()
            .filter(|r| r.level == level)
            .map(|r| r.errors.map(|e| e.pbar))
            .collect()
    };
    assert_eq!(errors(&partials[1], 1), errors(&whole, 1));
    let partial = Response::StudyPartial {
        generation: req.generation,
        study: partials[1].clone(),
    };
    assert!(app.update(Msg::Worker(partial)).redraw);
    let frame = render_app(&app, &LOOK, 100, 30);
    let graph = graph_rows(&frame, "work–precision");
    for glyph in ['1', '2', '3', '4'] {
        assert_eq!(count(&graph, glyph), 2, "{glyph}: levels 0 and 1\n{frame}");
    }
    assert!(frame.contains("⟳ computing"), "{frame}");
    let done = Response::Study {
        generation: req.generation,
        key: req.key.clone(),
        result: Some(Ok(whole)),
    };
    app.update(Msg::Worker(done));
    assert!(app.study_partial.is_none());
    let graph = graph_rows(&render_app(&app, &LOOK, 100, 30), "work–precision");
    assert!(count(&graph, '1') >= 5);
}
