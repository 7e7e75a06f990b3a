//! Read off the frame as a user reads it: the y ticks of a chart sit
//! on evenly spaced rows at their values (the data's top lies in the row its value names), and
//! every series' mark appears near each of its values, placed by the chart's own tick labels
//! (not by the code that drew it), at every size a class meets.

use riplab::mesh::Element;
use riplab::scheme::Scheme;
use riplab::tui::app::{App, Scene};
use riplab::tui::engine::Engine;
use riplab::tui::render_app;
use riplab::tui::settle::settle;

use crate::tui::tests::settled;

const LOOK: riplab::tui::view::Look = riplab::tui::view::Look {
    theme: riplab::tui::theme::Theme { color: false },
    marker: ratatui::symbols::Marker::Braille,
};

const SIZES: [(u16, u16); 4] = [(80, 24), (100, 30), (120, 40), (200, 60)];

/// A chart as drawn: its cells, the y ticks (line, value) and the x ticks (column, value).
pub(super) struct Chart {
    pub(super) lines: Vec<Vec<char>>,
    /// The lines of the graph (between the legend and the x axis).
    pub(super) graph: std::ops::Range<usize>,
    /// The column of the y axis; the graph starts right of it.
    pub(super) axis: usize,
    pub(super) y_ticks: Vec<(usize, f64)>,
    pub(super) x_ticks: Vec<(usize, f64)>,
}

fn number(text: &str) -> Option<f64> {
    text.trim().replace('−', "-").parse().ok()
}

/// The chart whose box title starts with `title` in `frame`.
pub(super) fn chart(frame: &str, title: &str) -> Chart {
    let lines: Vec<Vec<char>> = frame.lines().map(|l| l.chars().collect()).collect();
    let top = lines
        .iter()
        .position(|l| l.iter().collect::<String>().starts_with(&format!("┌ {title}")))
        .unwrap_or_else(|| panic!("no chart `{title}` in\n{frame}"));
    let bottom = top + lines[top..].iter().position(|l| l[0] == '└').unwrap();
    let axis = (top + 1..bottom)
        .find_map(|i| lines[i].iter().position(|&c| c == '┤'))
        .unwrap_or_else(|| panic!("no y tick in\n{frame}"));
    let x_axis = (top + 1..bottom)
        .find(|&i| lines[i].get(axis) == Some(&'└'))
        .unwrap();
    let first = (top + 1..x_axis)
        .find(|&i| {
            lines[i][1..axis]
                .iter()
                .all(|c| *c == ' ' || c.is_ascii_digit() || ".-−e".contains(*c))
                && matches!(lines[i][axis], '┤' | '│')
        })
        .unwrap();
    let y_ticks = (first..x_axis)
        .filter(|&i| lines[i][axis] == '┤')
        .map(|i| (i, number(&lines[i][1..axis].iter().collect::<String>()).unwrap()))
        .collect();
    // Each x label is centred on its ┬ (╤ in a stick zone; or pushed inside the box at the
    // ends).
    let label_line = &lines[x_axis + 1];
    let mut x_ticks = Vec::new();
    let mut col = 1;
    while col < label_line.len() - 1 {
        if label_line[col] == ' ' {
            col += 1;
            continue;
        }
        let start = col;
        while col < label_line.len() - 1 && label_line[col] != ' ' {
            col += 1;
        }
        let value = number(&label_line[start..col].iter().collect::<String>()).unwrap();
        let tick = (start..col)
            .filter(|&c| matches!(lines[x_axis][c], '┬' | '╤'))
            .min_by_key(|&c| c.abs_diff((start + col - 1) / 2))
            .unwrap_or_else(|| panic!("label at {start} without a tick in\n{frame}"));
        x_ticks.push((tick, value));
    }
    Chart {
        lines,
        graph: first..x_axis,
        axis,
        y_ticks,
        x_ticks,
    }
}

/// Where `v` falls between the first and the last tick (a fractional line or column).
pub(super) fn place(ticks: &[(usize, f64)], v: f64, log: bool) -> f64 {
    assert!(ticks.len() >= 2, "two ticks at least: {ticks:?}");
    let f = |x: f64| if log { x.log10() } else { x };
    let ((p0, v0), (p1, v1)) = (ticks[0], ticks[ticks.len() - 1]);
    p0 as f64 + (f(v) - f(v0)) * (p1 as f64 - p0 as f64) / (f(v1) - f(v0))
}

impl Chart {
    /// The rows between the y ticks, top to bottom.
    fn tick_gaps(&self) -> Vec<usize> {
        self.y_ticks.windows(2).map(|w| w[1].0 - w[0].0).collect()
    }

    /// Whether `glyph` is drawn within a row and four columns of (x, y) (a glyph landing on
    /// another moves up to three cells along its row).
    fn has_near(&self, glyph: char, x: f64, y: f64, log: bool) -> bool {
        let row = place(&self.y_ticks, y, log).round() as i64;
        let col = place(&self.x_ticks, x, log).round() as i64;
        (row - 1..=row + 1).any(|r| {
            let Ok(r) = usize::try_from(r) else { return false };
            self.graph.contains(&r)
                && (col - 4..=col + 4).any(|c| {
                    usize::try_from(c).is_ok_and(|c| c > self.axis && self.lines[r].get(c) == Some(&glyph))
                })
        })
    }

    /// The highest line of the graph holding any mark.
    fn top_mark(&self) -> usize {
        self.graph
            .clone()
            .find(|&i| {
                self.lines[i][self.axis + 1..self.lines[i].len() - 1]
                    .iter()
                    .any(|&c| c != ' ')
            })
            .unwrap()
    }
}

/// At 80×24 (and larger) the pressure chart's y ticks sit on evenly spaced rows, and
/// the largest pressure is drawn in the row its value names by the ticks — on the paper's
/// levels and on the soft penalty of the tour's step 10 (its ticks were 200, 100, 0 on rows
/// 1, 2 and 4).
#[test]
fn y_ticks_sit_on_evenly_spaced_rows_at_their_values() {
    let mut cases: Vec<App> = (0..=2).map(|level| settled(level, Scene::Explore)).collect();
    let mut soft = App::new(riplab::scenario::Scenario::paper());
    soft.show_timing = false;
    soft.settings.level = 2;
    soft.settings.epsilon = 1e-3;
    let m3 = Scheme::PAPER[2];
    (soft.settings.element, soft.settings.rule) = (m3.element, m3.rule);
    settle(&mut soft, &mut Engine::new(riplab::scenario::Scenario::paper()));
    cases.push(soft);
    for app in &cases {
        let shown = &app.solved.as_ref().unwrap().shown;
        let peak = shown
            .raw
            .iter()
            .chain(&shown.pbar)
            .fold(0.0f64, |m, &(_, p)| m.max(p));
        for (w, h) in SIZES {
            let frame = render_app(app, &LOOK, w, h);
            let c = chart(&frame, "pressure on Γ_C");
            let gaps = c.tick_gaps();
            assert!(
                !gaps.is_empty() && gaps.iter().all(|&g| g == gaps[0]),
                "uneven ticks {:?} at {w}×{h}\n{frame}",
                c.y_ticks
            );
            let row = place(&c.y_ticks, peak, false);
            assert!(
                (c.top_mark() as f64 - row).abs() <= 1.0,
                "peak {peak} drawn on line {}, its ticks say {row:.1}, at {w}×{h}\n{frame}",
                c.top_mark()
            );
        }
    }
}

/// Item 3 on the inf-sup scene: every series' glyph near each of its values (M3's under M1's
/// p̄ and M4's near 0.52 included), at every size.
#[test]
fn every_infsup_series_is_marked_near_each_of_its_values() {
    let app = settled(0, Scene::InfSup);
    let glyph_of = |element: Element, rule| {
        let at = Scheme::PAPER
            .iter()
            .position(|s| s.element == element && s.rule == rule)
            .unwrap();
        char::from(b'1' + at as u8)
    };
    let mut values = Vec::new();
    for (key, estimate) in &app.infsup {
        let b = estimate.as_ref().unwrap();
        if b.beta_over_sqrt_h > 0.0 {
            values.push((glyph_of(key.element, key.rule), b.h, b.beta_over_sqrt_h));
        }
        if glyph_of(key.element, key.rule) == '1' {
            values.push(('*', b.h, b.beta_bar_over_sqrt_h));
        }
    }
    assert_eq!(values.len(), 5 * 4, "M1, M3, M4 and M1's p̄ at five levels");
    for (w, h) in SIZES {
        let frame = render_app(&app, &LOOK, w, h);
        let c = chart(&frame, "β_h/√h against h");
        let gaps = c.tick_gaps();
        assert!(
            gaps.iter().all(|&g| g == gaps[0]),
            "uneven ticks at {w}×{h}\n{frame}"
        );
        for &(glyph, x, y) in &values {
            assert!(
                c.has_near(glyph, x, y, true),
                "`{glyph}` not near h = {x}, {y} at {w}×{h}\n{frame}"
            );
        }
    }
}

/// Item 3 on the convergence scene: each scheme's glyph near each level's (time, error of
/// p̄), and M1's raw p (`r`) near its own errors, at every size.
#[test]
fn every_convergence_series_is_marked_near_each_of_its_values() {
    let app = settled(0, Scene::Convergence);
    let Some(Ok(study)) = app.studies.get(&app.study_key()) else {
        panic!("no study")
    };
    let mut values = Vec::new();
    for r in &study.rows {
        let (Some(ms), Some(e)) = (r.solve_ms, r.errors.as_ref()) else {
            continue;
        };
        let glyph = r.scheme.chars().last().unwrap();
        values.push((glyph, ms, e.pbar));
        if r.scheme == "M1" {
            values.push(('r', ms, e.p));
        }
    }
    assert!(values.len() >= 5 * 5, "{values:?}");
    for (w, h) in SIZES {
        let frame = render_app(&app, &LOOK, w, h);
        let c = chart(&frame, "work–precision");
        let gaps = c.tick_gaps();
        assert!(
            gaps.iter().all(|&g| g == gaps[0]),
            "uneven ticks at {w}×{h}\n{frame}"
        );
        for &(glyph, x, y) in &values {
            assert!(
                c.has_near(glyph, x, y, true),
                "`{glyph}` not near {x} ms, {y} at {w}×{h}\n{frame}"
            );
        }
    }
}

/// The mesh scene has axes: y from 0 to the block's height, x across its width, each
/// label where the body's own lines are drawn (the bottom on the 0 row, the top at the far
/// edge on the height's row, the left side in the column of its x), at 80×24 and 120×40.
#[test]
fn the_mesh_scene_has_axes_at_the_bodys_lines() {
    let app = settled(1, Scene::Mesh);
    let (x0, x1) = app.scenario.x_range();
    let left = if app.scenario.half_model { -x1 } else { x0 };
    let top = app.scenario.height;
    for (w, h) in [(80, 24), (120, 40)] {
        let frame = render_app(&app, &LOOK, w, h);
        let c = chart(&frame, "deformed");
        let values: Vec<f64> = c.y_ticks.iter().map(|t| t.1).collect();
        assert!(
            values.contains(&0.0) && values.contains(&top),
            "{values:?}\n{frame}"
        );
        let braille = |c: char| ('\u{2801}'..='\u{28ff}').contains(&c);
        let line_of = |v: f64| c.y_ticks.iter().find(|t| t.1 == v).unwrap().0;
        // The bottom line across, the top's far left end on their ticks' rows.
        let bottom = &c.lines[line_of(0.0)][c.axis + 1..];
        assert!(
            bottom.iter().filter(|&&ch| braille(ch)).count() > bottom.len() / 2,
            "{frame}"
        );
        assert!(braille(c.lines[line_of(top)][c.axis + 2]), "{frame}");
        // The left side in the column its x names, on every row of the body.
        let col = place(&c.x_ticks, left, false).round() as usize;
        for line in line_of(top)..=line_of(0.0) {
            assert!(
                (col.saturating_sub(1)..=col + 1).any(|k| braille(c.lines[line][k])),
                "x = {left} at column {col}, line {line}\n{frame}"
            );
        }
    }
}
