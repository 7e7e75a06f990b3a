//! The two-body scene's inf-sup view (docs/lab.md, "Two bodies"; docs/design.md §12, "The
//! inf-sup constant across the interface"): Tab shows β_h/√h of every multiplier space against
//! h and the table of β_h, the numbers `riplab infsup` prints at the same ratio and offset;
//! `k` re-estimates at the new ratio; a kernel is said, never drawn as 0; Tab goes back.

use std::path::Path;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::symbols::Marker;
use riplab::contact::Rule;
use riplab::contact::interface::InterfaceMethod;
use riplab::infsup::interface_table::{InterfaceRow, interface_table};
use riplab::scenario::Scenario;
use riplab::tui::bodies::infsup::EstimateKey;
use riplab::tui::bodies::infsup_view::glyph;
use riplab::tui::bodies::{BodiesApp, BodiesView, settle_bodies, view};
use riplab::tui::theme::Theme;
use riplab::tui::view::Look;
use riplab::tui::view::fmt::sig;

const PATCH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/patch-two-blocks.toml");

const LOOK: Look = Look {
    theme: Theme { color: false },
    marker: Marker::Braille,
};

fn scenario() -> Scenario {
    Scenario::load(Path::new(PATCH)).unwrap()
}

/// The key of `c`: `\t` Tab, `\u{8}` Shift-Tab, `>` →, else the character.
fn key(c: char) -> KeyEvent {
    match c {
        '\t' => KeyEvent::new(KeyCode::Tab, KeyModifiers::NONE),
        '\u{8}' => KeyEvent::new(KeyCode::BackTab, KeyModifiers::SHIFT),
        '>' => KeyEvent::new(KeyCode::Right, KeyModifiers::NONE),
        c => KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE),
    }
}

/// The patch scenario's scene with `method`, settled after `keys`.
fn patch(method: InterfaceMethod, keys: &str) -> BodiesApp {
    let mut app = BodiesApp::new(scenario(), method).expect("two bodies");
    settle_bodies(&mut app, &keys.chars().map(key).collect::<Vec<_>>()).unwrap();
    app
}

fn frame(app: &BodiesApp, width: u16, height: u16) -> String {
    riplab::tui::render_frame(width, height, |f| view::view(app, f, &LOOK))
}

/// `riplab infsup`'s rows at `app`'s ratio, offset and rule, levels 0 to `finest`.
fn printed_rows(app: &BodiesApp, finest: u32) -> Vec<InterfaceRow> {
    let scenario = app.settings.apply(&app.scenario);
    let levels: Vec<u32> = (0..=finest).collect();
    interface_table(&scenario, &app.estimate_key().spaces(), &levels).unwrap()
}

/// The table's row of `level` in `text`: its cells after the level (h, then each space's β_h).
fn table_row(text: &str, level: u32) -> Vec<String> {
    let line = text
        .lines()
        .find(|l| {
            let l = l.trim_start_matches('│');
            let mut words = l.trim_start_matches(['▸', ' ']).split_whitespace();
            l.starts_with([' ', '▸'])
                && words.next() == Some(&level.to_string())
                && words.next().is_some_and(|h| h.parse::<f64>().is_ok())
        })
        .unwrap_or_else(|| panic!("no row of level {level}:\n{text}"));
    line.trim_matches('│')
        .trim_start_matches(['▸', ' '])
        .split_whitespace()
        .skip(1)
        .map(str::to_string)
        .collect()
}

/// Tab shows the inf-sup view: a series per space of the rule (mortar, mortar-dual, nts, the
/// rule's points and p̄), each with its glyph in the legend, and a table row for each level
/// 0–3 with the slope row; the header says the ratio and offset of the estimate.
#[test]
fn tab_shows_every_space_and_the_table() {
    let app = patch(InterfaceMethod::Mortar, "\t");
    assert_eq!(app.shown, BodiesView::InfSup);
    let text = frame(&app, 80, 24);
    let key = app.estimate_key();
    assert_eq!(key.rule, Rule::Gauss1, "the scenario's contact.rule");
    for space in key.spaces() {
        assert!(
            text.contains(&format!("⠒{}⠒ {}", glyph(space), space.name())),
            "{}:\n{text}",
            space.name()
        );
    }
    for level in 0..=3 {
        assert_eq!(table_row(&text, level).len(), 1 + key.spaces().len(), "{text}");
    }
    assert!(text.contains("slope"), "{text}");
    let header = text.lines().next().unwrap();
    assert!(header.contains("inf-sup at ratio 2:3 · offset 0"), "{header}");
}

/// The β_h shown are `riplab infsup`'s at the same settings to the printed digits (level 2,
/// ratio 2:3, every space), h too; the slope printed is the slope of the printed β_h and h of
/// the finest two levels (to the rounding of the printed digits).
#[test]
fn the_numbers_shown_are_riplab_infsup_s() {
    let app = patch(InterfaceMethod::Mortar, "\t>");
    assert_eq!((app.settings.level, app.settings.ratio), (2, (2, 3)));
    let text = frame(&app, 80, 24);
    let rows = printed_rows(&app, 3);
    let spaces = app.estimate_key().spaces();
    let mut printed: Vec<Vec<f64>> = Vec::new();
    for level in 0..=3u32 {
        let cells = table_row(&text, level);
        for (i, space) in spaces.iter().enumerate() {
            let row = rows
                .iter()
                .find(|r| r.space == space.name() && r.level == level)
                .unwrap();
            assert_eq!(cells[0], sig(row.h, 4), "h at level {level}");
            assert_eq!(cells[1 + i], sig(row.beta, 4), "{} at level {level}", row.space);
        }
        printed.push(cells.iter().map(|c| c.parse().unwrap()).collect());
    }
    let slopes: Vec<f64> = text
        .lines()
        .find_map(|l| l.trim_matches('│').trim_start().strip_prefix("slope"))
        .expect("a slope row")
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(slopes.len(), spaces.len());
    let (a, b) = (&printed[2], &printed[3]);
    for (i, &slope) in slopes.iter().enumerate() {
        let again = (b[1 + i] / a[1 + i]).ln() / (b[0] / a[0]).ln();
        assert!(
            (again - slope).abs() <= 0.01,
            "{}: {slope} against {again}",
            spaces[i].name()
        );
    }
}

/// `k` while the view is shown re-estimates at the new ratio (1:1), its numbers
/// `riplab infsup`'s there and not 2:3's, and asks for no solve (the pressure is not shown);
/// Tab back asks for the solve of the new ratio, the estimates kept: Tab again asks for none.
#[test]
fn k_re_estimates_at_the_new_ratio() {
    let mut app = patch(InterfaceMethod::Mortar, "\t");
    let before = table_row(&frame(&app, 80, 24), 2);
    let (_, solve) = app.key(key('k'));
    assert!(solve.is_none(), "the pressure is not shown");
    let job = app.infsup_request().expect("estimates at 1:1");
    assert_eq!((job.key.ratio, job.levels.clone()), ((1, 1), vec![0, 1, 2, 3]));
    let mut app = patch(InterfaceMethod::Mortar, "\tk");
    let text = frame(&app, 80, 24);
    assert!(text.lines().next().unwrap().contains("ratio 1:1"), "{text}");
    let after = table_row(&text, 2);
    assert_ne!(before, after);
    let mortar = printed_rows(&app, 2).iter().find(|r| r.level == 2).unwrap().beta;
    assert_eq!(after[1], sig(mortar, 4));
    let (_, solve) = app.key(key('\t'));
    assert_eq!(solve.expect("the solve at 1:1").1.ratio, (1, 1));
    app.key(key('\u{8}'));
    assert_eq!(app.shown, BodiesView::InfSup);
    assert!(app.infsup_request().is_none(), "kept: nothing to estimate again");
}

/// Tab (and Shift-Tab) back shows the pressure chart and the patch test's verdict; the
/// pressure view asks for no estimate.
#[test]
fn tab_back_shows_the_pressure_chart() {
    for keys in ["\t\t", "\t\u{8}"] {
        let mut app = patch(InterfaceMethod::Mortar, keys);
        assert_eq!(app.shown, BodiesView::Pressure);
        let text = frame(&app, 80, 24);
        assert!(
            text.contains(" interface p · mortar") && text.contains("patch test passed"),
            "{text}"
        );
        assert!(app.infsup_request().is_none());
    }
}

/// A space whose multipliers are not unique (rip-gauss2 on matching meshes, 1:1) shows its
/// kernel: `kernel` in the table, `β=0, kernel` in the legend, never a 0.
#[test]
fn a_kernel_is_said_not_drawn_as_zero() {
    let app = patch(InterfaceMethod::Rip(Rule::Gauss2), "k\t");
    assert_eq!(app.estimate_key().rule, Rule::Gauss2);
    let text = frame(&app, 80, 24);
    assert!(text.contains("rip-gauss2 β=0, kernel"), "{text}");
    let spaces = app.estimate_key().spaces();
    let point = spaces.iter().position(|s| s.name() == "rip-gauss2").unwrap();
    for level in 0..=3 {
        let cells = table_row(&text, level);
        assert_eq!(cells[1 + point], "kernel", "{text}");
        assert!(cells.iter().all(|c| c != "0"), "{text}");
    }
}

/// In monochrome at 80×24 and 120×40 every series keeps a glyph of its own, named in the
/// legend and drawn on the graph (mortar-dual's, equal to mortar's, beside it); the frame's
/// lines fit its width.
#[test]
fn monochrome_frames_keep_every_series_apart() {
    let app = patch(InterfaceMethod::Mortar, "\t");
    let spaces = app.estimate_key().spaces();
    let glyphs: Vec<char> = spaces.iter().map(|&s| glyph(s)).collect();
    let mut distinct = glyphs.clone();
    distinct.sort_unstable();
    distinct.dedup();
    assert_eq!(distinct.len(), glyphs.len());
    for (width, height) in [(80, 24), (120, 40)] {
        let text = frame(&app, width, height);
        assert!(
            // p̄'s macron combines with its p: one cell.
            text.lines()
                .all(|l| l.chars().filter(|&c| c != '\u{304}').count() <= usize::from(width)),
            "{text}"
        );
        let graph = graph(&text);
        for &g in &glyphs {
            assert!(graph.contains(g), "{g} not drawn at {width}×{height}:\n{text}");
        }
    }
}

/// The chart's graph: right of its y axis, above its x axis (the `└` inside the frame).
fn graph(text: &str) -> String {
    let lines: Vec<Vec<char>> = text.lines().map(|l| l.chars().collect()).collect();
    let (axis_row, column) = lines
        .iter()
        .enumerate()
        .find_map(|(i, l)| l.iter().skip(1).position(|&c| c == '└').map(|c| (i, c + 1)))
        .expect("an x axis");
    lines[..axis_row]
        .iter()
        .rev()
        .take_while(|l| matches!(l.get(column), Some('│' | '┤')))
        .map(|l| l[column + 1..].iter().collect::<String>() + "\n")
        .collect()
}

/// A level that was not estimated (here one refused for its memory) is said in its row, on
/// the status line and under the table, not dropped.
#[test]
fn a_level_not_estimated_is_said() {
    let mut app = patch(InterfaceMethod::Mortar, "\t");
    let key: EstimateKey = app.estimate_key();
    let too_large =
        riplab::contact::interface::solve::BodiesError::Solve(riplab::error::SolveError::TooLarge {
            workload: riplab::error::Workload::Interface {
                level: 3,
                element: app.scenario.element,
                trace: 100,
            },
            unknowns: 1000,
            need: 2_000_000,
            available: 1_000_000,
        });
    app.infsup.keep(key, 3, Err(too_large));
    let text = frame(&app, 80, 24);
    assert!(
        text.contains("3   not estimated: too large for the memory")
            && text.contains("level 3 not estimated (below)")
            && text.contains("level 3: "),
        "{text}"
    );
}
