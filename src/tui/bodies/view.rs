//! Drawing the two-body scene: a header naming the scenario, the level, the element and the
//! multipliers; the interface pressure of the chosen discretisation along the interface —
//! p at the slave's contact points (a dotted line, `•` at each point while they are few),
//! p̄ by (17) for the reduced-integration rules (a solid line) and, on the contact patch test,
//! the applied pressure as a dashed reference line (`─`); under it both meshes near the
//! interface ([`super::meshes`]); the state of the solve with the patch error or the load; the
//! key's answer; and the key bar. Lines differ by stroke and
//! glyph, not by colour alone (NO_COLOR). In the inf-sup view (Tab) the panels and the state
//! are [`super::infsup_view`]'s.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use super::super::bodies_solve::Solved;
use super::super::key_bar;
use super::super::theme::Theme;
use super::super::view::fmt::{sig, wrap_items, wrap_words};
use super::super::view::help::key_popup;
use super::super::view::plot::{Axis, Plot, Scale, Series, Stroke};
use super::super::view::{Look, below_min_size};
use super::{BodiesApp, BodiesView, infsup_view};
use crate::contact::interface::InterfaceMethod;
use crate::contact::interface::solve::Enforcement;

/// A patch error at most this says the method passes the patch test (the mortar methods'
/// round-off, docs/design.md §12).
pub const PASSES: f64 = 1e-10;

/// A patch error above this says the method fails it.
pub const FAILS: f64 = 1e-3;

/// Below this a patch error is shown as `< 1e-12` (round-off, whose digits vary by platform).
const ROUND_OFF: f64 = 1e-12;

/// The patch test's pressure axis: the applied pressure ± this fraction of it at most …
const PATCH_WINDOW: f64 = 0.25;
/// … and at least: the window is 2.5 times the largest departure from the applied pressure
/// between the two, so that a departure of a row's height or more (rip-gauss1's 0.87 %, under
/// a row at ±25 %, hid the applied line under p̄) stands rows apart from it.
const PATCH_WINDOW_LEAST: f64 = 0.01;

/// The fewest rows of the meshes' panel (its border's two and six of meshes).
const MESH_ROWS: u16 = 8;

/// The fewest rows the pressure chart keeps beside the meshes: its border's two, the legend's,
/// the x axis' two and seven of graph, where the applied pressure's reference line has room
/// (an overlay for every four rows of graph, [`super::super::view::plot`]).
const CHART_LEAST: u16 = 12;

/// Samples of the applied pressure's reference line across the chart.
const REFERENCE_SAMPLES: usize = 41;

/// A contact zone (widened) under this fraction of the interface is drawn alone.
const ZOOM_BELOW: f64 = 2.0 / 3.0;

/// The most contact points marked `•` (more would fill every cell).
const MAX_MARKED: usize = 40;

/// Draw the two-body scene into the whole frame (at least [`super::super::view::MIN_SIZE`]).
pub fn view(app: &BodiesApp, frame: &mut Frame, look: &Look) {
    let area = frame.area();
    if below_min_size(frame, area, look.theme, app.notice.as_ref()) {
        return;
    }
    view_in(app, frame, area, look, true);
}

/// Draw the two-body scene into `area` (at least [`super::super::view::MIN_SIZE`]), its key
/// bar at the bottom when `keys` (the guided tour puts its caption and its own keys there).
pub fn view_in(app: &BodiesApp, frame: &mut Frame, area: Rect, look: &Look, keys: bool) {
    let theme = look.theme;
    let infsup = app.shown == BodiesView::InfSup;
    let state = if infsup {
        infsup_view::state_text(app)
    } else {
        state_text(app)
    };
    let state = wrap_items(&state, usize::from(area.width.saturating_sub(1)));
    let notice = app
        .notice
        .as_ref()
        .map(|n| wrap_words(&n.text, usize::from(area.width.saturating_sub(1))))
        .unwrap_or_default();
    let status_rows = (state.len() + notice.len()).min(6) as u16;
    let [header, panels, status, bar] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Fill(1),
        Constraint::Length(status_rows),
        Constraint::Length(u16::from(keys)),
    ])
    .areas(area);
    let header_line = if infsup {
        infsup_view::header_text(app)
    } else {
        header_text(app)
    };
    frame.render_widget(Paragraph::new(Line::styled(header_line, theme.title())), header);
    if infsup {
        infsup_view::render(app, frame, panels, look);
    } else {
        // The chart first: the meshes take two fifths of the rows when the chart keeps
        // CHART_LEAST beside MESH_ROWS of them, and are left out otherwise (a tour step's
        // caption takes the rows they would need).
        let meshes_rows = if panels.height >= CHART_LEAST + MESH_ROWS {
            (panels.height * 2 / 5).clamp(MESH_ROWS, panels.height - CHART_LEAST)
        } else {
            0
        };
        let [chart, meshes] =
            Layout::vertical([Constraint::Fill(1), Constraint::Length(meshes_rows)]).areas(panels);
        pressure_chart(app, frame, chart, look);
        if meshes_rows > 0 {
            super::meshes::render(app.solved.as_ref(), app.scenario.height, frame, meshes, look);
        }
    }
    let state_style = if infsup {
        infsup_view::state_style(app, theme)
    } else if app.error.is_some() {
        theme.bad()
    } else if app.settled() {
        Style::new()
    } else {
        theme.busy()
    };
    let mut lines: Vec<Line> = state
        .into_iter()
        .map(|l| Line::styled(format!(" {l}"), state_style))
        .collect();
    let notice_style = match &app.notice {
        Some(n) if n.failure => theme.bad(),
        _ => theme.faint(),
    };
    lines.extend(
        notice
            .into_iter()
            .map(|l| Line::styled(format!(" {l}"), notice_style)),
    );
    frame.render_widget(Paragraph::new(lines), status);
    if keys {
        frame.render_widget(Paragraph::new(key_bar_line(theme)), bar);
    }
    if app.show_help {
        help(app, frame, area, theme);
    }
}

/// `riplab · patch-two-blocks · two bodies · q1 level 1 · exact · slave upper`.
fn header_text(app: &BodiesApp) -> String {
    let s = &app.settings;
    let multipliers = match s.enforcement {
        Enforcement::Exact => "exact".to_string(),
        Enforcement::Penalty(epsilon) => format!("ε = {}", sig(epsilon, 2)),
        Enforcement::Alm { epsilon, .. } => format!("ALM ε = {}", sig(epsilon, 2)),
    };
    let slave = app.scenario.upper.as_ref().map_or("upper", |u| u.slave.name());
    format!(
        " riplab · {} · two bodies · {} level {} · {multipliers} · slave {slave}",
        crate::text::sanitize(&app.scenario.name),
        app.scenario.element.name(),
        s.level
    )
}

/// The state of the solve: its failure, that it runs, or the numbers of the one shown — the
/// patch error and its verdict on the patch test, or the load.
pub fn state_text(app: &BodiesApp) -> String {
    if let Some(e) = &app.error {
        return format!("✗ {e}");
    }
    let Some(solved) = &app.solved else {
        return format!("solving {}…", settings_text(app));
    };
    let running = if app.settled() {
        String::new()
    } else {
        format!("solving {}… · shown: ", settings_text(app))
    };
    let name = solved.settings.method.name();
    let numbers = match solved.patch {
        Some((exact, error)) => {
            let shown = if error < ROUND_OFF {
                format!("< {ROUND_OFF:e}")
            } else {
                sig(error, 2)
            };
            let verdict = if error <= PASSES {
                format!("passed: error {shown} (≤ {PASSES:e})")
            } else if error > FAILS {
                format!("failed: error {shown} (> {FAILS:e})")
            } else {
                format!(": error {shown}")
            };
            format!(
                "patch test {verdict} · applied {} · P = {}",
                sig(exact, 5),
                sig(solved.load, 4)
            )
        }
        None => format!(
            "{name}: load P = {} · p max {} · contact {} · {} iteration{}",
            sig(solved.load, 4),
            sig(solved.p.iter().fold(0.0_f64, |m, p| m.max(p.1)), 4),
            solved.zone().map_or("nowhere".to_string(), |[a, b]| format!(
                "{} to {}",
                sig(a, 3),
                sig(b, 3)
            )),
            solved.iterations,
            if solved.iterations == 1 { "" } else { "s" }
        ),
    };
    format!("{running}{numbers}")
}

/// `level 2 · nts · ratio 2:3 · offset 0.1`.
fn settings_text(app: &BodiesApp) -> String {
    let s = &app.settings;
    format!(
        "level {} · {} · ratio {} · offset {}",
        s.level,
        s.method.name(),
        s.ratio_text(),
        sig(s.offset, 2)
    )
}

/// The chart of the shown solve (or "solving…").
fn pressure_chart(app: &BodiesApp, frame: &mut Frame, area: Rect, look: &Look) {
    let theme = look.theme;
    let Some(solved) = &app.solved else {
        let block = ratatui::widgets::Block::bordered().title(" interface pressure ");
        frame.render_widget(Paragraph::new(" solving…").block(block), area);
        return;
    };
    let reference: Vec<(f64, f64)> = solved
        .patch
        .map(|(exact, _)| {
            let [a, b] = solved.x_range;
            (0..REFERENCE_SAMPLES)
                .map(|i| (a + (b - a) * i as f64 / (REFERENCE_SAMPLES - 1) as f64, exact))
                .collect()
        })
        .unwrap_or_default();
    let xb = x_bounds(solved);
    let inside = |data: &[(f64, f64)]| -> Vec<(f64, f64)> {
        data.iter()
            .copied()
            .filter(|q| (xb[0]..=xb[1]).contains(&q.0))
            .collect()
    };
    let (p, pbar) = (inside(&solved.p), inside(&solved.pbar));
    let plot = Plot {
        title: chart_title(solved),
        x: Axis {
            title: "x (length)".into(),
            bounds: xb,
            scale: Scale::Linear,
        },
        y: Axis {
            title: "p (units of E)".into(),
            bounds: y_bounds(solved),
            scale: Scale::Linear,
        },
        overlays: reference_series(solved, &reference, theme),
        series: pressure_series(solved, &p, &pbar, theme),
        marker: look.marker,
        theme,
    };
    plot.render(frame, area);
}

/// The x range drawn: the whole interface on the patch test; elsewhere the contact zone
/// (p > 0) widened by half its width each way, when that is under [`ZOOM_BELOW`] of the
/// interface (a Hertz contact's zone is a few per cent of it).
pub fn x_bounds(solved: &Solved) -> [f64; 2] {
    let whole = solved.x_range;
    match (solved.patch, solved.zone()) {
        (None, Some([a, b])) => {
            let margin = 0.5 * (b - a).max((whole[1] - whole[0]) / 100.0);
            let zoomed = [(a - margin).max(whole[0]), (b + margin).min(whole[1])];
            if zoomed[1] - zoomed[0] < ZOOM_BELOW * (whole[1] - whole[0]) {
                zoomed
            } else {
                whole
            }
        }
        _ => whole,
    }
}

/// ` interface p · nts · ratio 2:3 · offset 0 · 8:12 edges `.
fn chart_title(solved: &Solved) -> String {
    let s = &solved.settings;
    format!(
        " interface p · {} · ratio {} · offset {} · {}:{} edges ",
        s.method.name(),
        s.ratio_text(),
        sig(s.offset, 2),
        solved.edges.0,
        solved.edges.1
    )
}

/// The pressure axis: from 0 to the largest of p and p̄ (1 if none); on the patch test a
/// window of ±[`PATCH_WINDOW`] about the applied pressure, widened to the data, so that a
/// departure from the uniform pressure shows.
fn y_bounds(solved: &Solved) -> [f64; 2] {
    let values = solved.p.iter().chain(&solved.pbar).map(|q| q.1);
    let (lo, hi) = values.fold((f64::INFINITY, 0.0_f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    match solved.patch {
        Some((exact, _)) => {
            let departure = (hi - exact).max(exact - lo) / exact;
            let window = (2.5 * departure).clamp(PATCH_WINDOW_LEAST, PATCH_WINDOW);
            [
                lo.min(exact * (1.0 - window)).max(0.0),
                hi.max(exact * (1.0 + window)),
            ]
        }
        None => [0.0, if hi > 0.0 { hi } else { 1.0 }],
    }
}

/// The patch test's applied pressure, a dashed reference line (`─`).
fn reference_series<'a>(solved: &Solved, data: &'a [(f64, f64)], theme: Theme) -> Vec<Series<'a>> {
    match solved.patch {
        Some((exact, _)) => vec![Series {
            name: format!("applied {}", sig(exact, 4)),
            color: theme.hertz_color(),
            stroke: Stroke::None,
            glyph: Some('─'),
            data,
        }],
        None => Vec::new(),
    }
}

/// p̄ (for the reduced-integration rules: a solid line) and p (dotted, `•` at each point
/// while they are few), the points drawn.
fn pressure_series<'a>(
    solved: &Solved,
    p: &'a [(f64, f64)],
    pbar: &'a [(f64, f64)],
    theme: Theme,
) -> Vec<Series<'a>> {
    let mut series = Vec::new();
    if matches!(solved.settings.method, InterfaceMethod::Rip(_)) {
        series.push(Series {
            name: "p̄ smoothed (17)".into(),
            color: theme.smooth_color(),
            stroke: Stroke::Solid,
            glyph: None,
            data: pbar,
        });
    }
    series.push(Series {
        name: format!("p {}", solved.settings.method.name()),
        color: theme.raw_color(),
        stroke: Stroke::Dotted,
        glyph: (p.len() <= MAX_MARKED).then_some('•'),
        data: p,
    });
    series
}

/// The key bar: the scene's keys ([`key_bar::bodies_bar`]), `? help`, `q quit`.
fn key_bar_line(theme: Theme) -> Line<'static> {
    let mut spans = Vec::new();
    for (key, what) in key_bar::bodies_bar() {
        spans.push(Span::raw(" "));
        spans.push(Span::styled(key, theme.key()));
        spans.push(Span::raw(format!(" {what} ")));
    }
    Line::from(spans)
}

/// The help overlay ([`key_bar::bodies_help`]), from the app's scroll on.
fn help(app: &BodiesApp, frame: &mut Frame, area: Rect, theme: Theme) {
    let all = key_bar::bodies_help();
    let rows = usize::from(area.height.saturating_sub(2)).max(1);
    let first = usize::from(app.help_scroll).min(all.len().saturating_sub(rows));
    let shown = &all[first..(first + rows).min(all.len())];
    let title = if shown.len() < all.len() {
        format!(
            " keys {}–{} of {} (↑ ↓ scroll) ",
            first + 1,
            first + shown.len(),
            all.len()
        )
    } else {
        " keys ".to_string()
    };
    key_popup(frame, area, theme, &title, shown, (62, 16));
}
