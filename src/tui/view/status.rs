//! The status line: the state of the solve (or of the estimates, or the study), or a notice,
//! and the main keys. The message wins: the key hints go first when room is short, and a
//! message longer than the line is cut at a word boundary with "…", never mid-word.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use super::super::app::{App, Compare, Progress, Scene};
use super::super::eta::time_left;
use super::super::theme::Theme;
use super::convergence::study_epsilon;
use super::fmt::sig;
use crate::mesh::Element;

pub fn render(app: &App, frame: &mut Frame, area: Rect, theme: Theme) {
    frame.render_widget(
        Paragraph::new(status_line(&state(app, theme), area.width, theme)),
        area,
    );
}

/// `message` followed by the key hints right-aligned when both fit in `width`, else the
/// message alone, cut to fit at a word boundary.
pub fn status_line(message: &[Span<'static>], width: u16, theme: Theme) -> Line<'static> {
    let width = usize::from(width);
    let hints = vec![
        Span::styled("?", theme.key()),
        Span::raw(" help  "),
        Span::styled("q", theme.key()),
        Span::raw(" quit "),
    ];
    let hints_width: usize = hints.iter().map(Span::width).sum();
    let used: usize = message.iter().map(Span::width).sum();
    if used + 2 + hints_width <= width {
        let mut spans = message.to_vec();
        spans.push(Span::raw(" ".repeat(width - used - hints_width)));
        spans.extend(hints);
        return Line::from(spans);
    }
    Line::from(fit_words(message, width))
}

/// The spans cut to `width` columns at the last space that fits, with "…".
fn fit_words(spans: &[Span<'static>], width: usize) -> Vec<Span<'static>> {
    let total: usize = spans.iter().map(Span::width).sum();
    if total <= width {
        return spans.to_vec();
    }
    let room = width.saturating_sub(1);
    let mut out = Vec::new();
    let mut used = 0usize;
    for span in spans {
        let text = span.content.to_string();
        let w = span.width();
        if used + w <= room {
            out.push(span.clone());
            used += w;
            continue;
        }
        // Cut inside this span at its last space within the room.
        let mut kept = String::new();
        let mut cut = String::new();
        for ch in text.chars() {
            if used + kept.chars().count() + 1 > room {
                break;
            }
            kept.push(ch);
            if ch == ' ' {
                cut = kept.clone();
            }
        }
        if !cut.trim().is_empty() {
            out.push(Span::styled(cut.trim_end().to_string(), span.style));
        }
        break;
    }
    // Drop a trailing fragment of spaces, then mark the cut.
    while out.last().is_some_and(|s| s.content.trim().is_empty()) {
        out.pop();
    }
    out.push(Span::raw("…"));
    out
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
    if app.show_timing {
        spans.push(Span::raw(format!(" · {} ms", sig(solved.total_ms, 3))));
    }
    // What is known to be poor about this answer (locking, an unresolved obstacle, a narrow
    // contact zone): the first warning, cut to fit like the rest of the message.
    if let Some(warning) = solved.solution.warnings.first() {
        spans.push(Span::styled(format!(" · ⚠ {warning}"), theme.bad()));
    }
    spans
}
