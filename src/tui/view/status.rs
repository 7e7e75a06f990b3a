//! The status area: the state of the solve (or of the estimates, or the study), or a notice,
//! then the scene's key bar (in the projector view on the notice's row when both fit). The message wraps at words to further rows (at most
//! [`MAX_ROWS`], indented under its first word) rather than being cut, and every message is
//! kept whole in the log (`l`).

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use super::super::app::{App, Compare, Progress, Scene};
use super::super::eta::time_left;
use super::super::key_bar;
use super::super::theme::Theme;
use super::convergence::study_epsilon;
use super::fmt::sig;
use crate::mesh::Element;

/// The most rows the status area takes (a longer message ends "… l: log", whole in the log).
pub const MAX_ROWS: u16 = 5;

/// What a message's further rows start with, after the row's own space: they line up with
/// the first row's words past its ` ✗ ` mark.
const INDENT: &str = "  ";

/// Draw the status area: the message, wrapped at words to as many rows as it needs (at most
/// [`MAX_ROWS`]), and below it the scene's key bar (not in the guided tour, whose caption
/// panel has its own keys).
pub fn render(app: &App, frame: &mut Frame, area: Rect, theme: Theme) {
    frame.render_widget(Paragraph::new(status_lines(app, area.width, theme)), area);
}

/// The rows the status area of `app` needs at `width` columns.
pub fn rows(app: &App, width: u16, theme: Theme) -> u16 {
    status_lines(app, width, theme).len() as u16
}

/// The status area's lines at `width` columns: the message, then the key bar. In the
/// projector view, whose screen is the chart's, the keys end the message's row when both fit
/// on it.
fn status_lines(app: &App, width: u16, theme: Theme) -> Vec<Line<'static>> {
    let state = state(app, theme);
    if app.overlays.in_tour {
        return wrap_with_hints(&state, &[], width);
    }
    let bar = key_bar(app, theme, width);
    if app.overlays.projector {
        let one = wrap_with_hints(&state, &bar.spans, width);
        if one.len() == 1 {
            return one;
        }
    }
    let mut lines = wrap_with_hints(&state, &[], width);
    lines.push(bar);
    lines
}

/// The scene's key bar ([`key_bar::bar`]): its keys, `? help` and `q quit`; the scene's own
/// keys dropped from the last while the bar is wider than `width`.
fn key_bar(app: &App, theme: Theme, width: u16) -> Line<'static> {
    let mut entries = key_bar::bar(app.scene, app.overlays.projector);
    let width_of = |e: &[(String, &str)]| -> usize {
        e.iter()
            .map(|(k, w)| 1 + k.chars().count() + 1 + w.chars().count() + 1)
            .sum()
    };
    while width_of(&entries) > usize::from(width) && entries.len() > 2 {
        entries.remove(entries.len() - 3);
    }
    let mut spans = Vec::new();
    for (key, what) in entries {
        spans.push(Span::raw(" "));
        spans.push(Span::styled(key, theme.key()));
        spans.push(Span::raw(format!(" {what} ")));
    }
    Line::from(spans)
}

/// `message` wrapped at words into rows of `width` columns, the first row leaving room for
/// `hints` right-aligned; at most [`MAX_ROWS`] rows, the last ending "… l: log" when the
/// message is longer still.
pub fn wrap_with_hints(message: &[Span<'static>], hints: &[Span<'static>], width: u16) -> Vec<Line<'static>> {
    let width = usize::from(width);
    let hints_width: usize = hints.iter().map(Span::width).sum();
    // The words with their styles (a span's leading space kept as the line's indent).
    let mut words: Vec<Span<'static>> = Vec::new();
    for span in message {
        for word in span.content.split(' ').filter(|w| !w.is_empty()) {
            words.push(Span::styled(word.to_string(), span.style));
        }
    }
    // Further rows indented under the message's first word (past ` ✗ `).
    let room = |row: usize| {
        if row == 0 {
            width.saturating_sub(hints_width + 2)
        } else {
            width.saturating_sub(1 + INDENT.len())
        }
    };
    let mut rows: Vec<Vec<Span<'static>>> = vec![Vec::new()];
    let mut used = 0usize;
    for word in words {
        let w = word.width();
        if used > 0 && used + 1 + w > room(rows.len() - 1) {
            rows.push(vec![Span::raw(INDENT)]);
            used = 0;
        }
        let row = rows.last_mut().expect("a row");
        row.push(Span::raw(" "));
        row.push(word);
        used += 1 + w;
    }
    if rows.len() > usize::from(MAX_ROWS) {
        rows.truncate(usize::from(MAX_ROWS));
        let last = rows.last_mut().expect("a row");
        let tail = " … l: log";
        while !last.is_empty() && last.iter().map(Span::width).sum::<usize>() + tail.chars().count() > width {
            last.pop();
        }
        last.push(Span::raw(tail));
    }
    rows.into_iter()
        .enumerate()
        .map(|(i, mut spans)| {
            if i == 0 {
                let used: usize = spans.iter().map(Span::width).sum();
                spans.push(Span::raw(" ".repeat(width.saturating_sub(used + hints_width))));
                spans.extend(hints.iter().cloned());
            }
            Line::from(spans)
        })
        .collect()
}

/// "building level 7 (1049088 unknowns) · about 3 s left", or for a method's preparation
/// "building level 7 for nitsche (1049088 unknowns) · about 9 s left"; with an element (an
/// estimate's build, beside the estimates' count on an 80-column line) the shorter
/// "building q2 level 7 · about 25 s left".
fn building(progress: Progress, element: Option<Element>) -> String {
    let Progress::Assembling {
        level,
        unknowns,
        started,
        estimate_ms,
        method,
    } = progress
    else {
        return "building".into();
    };
    let left = time_left(estimate_ms, started.elapsed().as_secs_f64() * 1e3)
        .map(|t| format!(" · {t}"))
        .unwrap_or_default();
    let method = method.map(|m| format!(" for {m}")).unwrap_or_default();
    match element {
        Some(e) => format!("building {} level {level}{left}", e.name()),
        None => format!("building level {level}{method} ({unknowns} unknowns){left}"),
    }
}

/// What the status line says, as styled spans.
fn state(app: &App, theme: Theme) -> Vec<Span<'static>> {
    if let Some(notice) = &app.notice {
        let style = if notice.failure { theme.bad() } else { Style::new() };
        let mark = if notice.failure { " ✗ " } else { " " };
        return vec![Span::styled(format!("{mark}{}", notice.text), style)];
    }
    let mut spans = vec![Span::raw(" ")];
    if app.is_solving() {
        let what = match app.progress {
            Some(Progress::Newton {
                iteration,
                residual,
                active,
            }) => format!(
                "⟳ Newton {iteration}: residual {}, {active} active",
                sig(residual, 2)
            ),
            Some(progress @ Progress::Assembling { .. }) => format!("⟳ {}", building(progress, None)),
            _ => "⟳ solving".into(),
        };
        spans.push(Span::styled(what, theme.busy()));
        spans.push(Span::raw("  "));
    }
    if app.scene == Scene::InfSup {
        let n = app.infsup_pending();
        if n > 0 {
            let text = match app.infsup_building() {
                Some((key, progress)) => {
                    format!("⟳ {n} estimate(s) · {}", building(progress, Some(key.element)))
                }
                None => format!("⟳ {n} inf-sup estimate(s) running"),
            };
            spans.push(Span::styled(text, theme.busy()));
        } else {
            spans.push(Span::raw(format!("{} inf-sup estimate(s)", app.infsup.len())));
        }
        return spans;
    }
    if app.scene == Scene::Convergence {
        let key = app.study_key();
        let reference = key.reference_level();
        if app.study_pending() == Some(&key) {
            let what = match app.study_progress {
                Some(Progress::Study {
                    level,
                    started,
                    estimate_ms,
                }) => {
                    let stage = match level {
                        None => format!("the reference (q2, level {reference})"),
                        Some(l) => format!("{} at level {l} of {}", key.label(), key.max_level),
                    };
                    let left = time_left(estimate_ms, started.elapsed().as_secs_f64() * 1e3)
                        .map(|t| format!(" · {t}"))
                        .unwrap_or_default();
                    format!("⟳ computing {stage}{left}")
                }
                _ => format!("⟳ computing the reference (q2, level {reference})…"),
            };
            spans.push(Span::styled(what, theme.busy()));
        } else if let Some(Ok(_)) = app.studies.get(&key) {
            let levels = match key.max_level {
                0 => "level 0".to_string(),
                max => format!("levels 0 to {max}"),
            };
            let (other, plus_minus) = match key.compare {
                Compare::Schemes => ("the methods", "do not apply"),
                Compare::Methods => ("M1–M4", "change it"),
            };
            spans.push(Span::raw(format!(
                "{} at {levels} against q2 level {reference} · w compares {other} · {} (+ − {plus_minus})",
                key.label(),
                study_epsilon(app)
            )));
        }
        return spans;
    }
    let Some(solved) = &app.solved else {
        return spans;
    };
    if app.is_solving() {
        // The previous result stays on screen; the progress above says what is coming.
        return spans;
    }
    if app.error.is_some() {
        // The banner says why; the charts keep the last result, which is not these settings'.
        spans.push(Span::styled("✗ no result for these settings", theme.bad()));
        if app.current().is_none() {
            spans.push(Span::raw(format!(
                " · shown: the last solve (level {}, {})",
                solved.key.level,
                solved.key.method.name()
            )));
        }
        return spans;
    }
    let newton = &solved.solution.newton;
    if newton.converged {
        spans.push(Span::styled("✓ converged", theme.good()));
    } else {
        spans.push(Span::styled("✗ NOT converged", theme.bad()));
    }
    let steps = if newton.iterations == 1 { "step" } else { "steps" };
    let updates = solved
        .solution
        .outer_iterations
        .map(|n| format!("{n} update{} × ", if n == 1 { "" } else { "s" }))
        .unwrap_or_default();
    spans.push(Span::raw(format!(
        " in {updates}{} Newton {steps} · load P={}",
        newton.iterations,
        sig(solved.solution.load, 5)
    )));
    if app.scenario.half_model {
        spans.push(Span::raw(format!(" (full {})", sig(solved.shown.full_load, 5))));
    }
    if let Some(f) = &solved.shown.friction {
        spans.push(Span::raw(format!(" · {}", super::friction::status(f))));
    }
    if app.show_timing {
        spans.push(Span::raw(format!(" · {} ms", sig(solved.total_ms, 3))));
    }
    // With edge grading: graded, the graded grid kept, or graded again.
    if let Some(regrade) = solved.regrade {
        spans.push(Span::raw(format!(" · {}", regrade.text())));
    }
    // What is known to be poor about this answer (locking, an unresolved obstacle, a narrow
    // contact zone): the first warning, cut to fit like the rest of the message.
    if let Some(warning) = solved.solution.warnings.first() {
        spans.push(Span::styled(format!(" · ⚠ {warning}"), theme.bad()));
    }
    spans
}
