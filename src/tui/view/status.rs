//! The status line: the state of the solve (or of the estimates) and the main keys.

use ratatui::Frame;
use ratatui::layout::{Alignment, Constraint, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use super::super::app::{App, Progress, Scene};
use super::super::theme::Theme;
use super::fmt::sig;

pub fn render(app: &App, frame: &mut Frame, area: Rect, theme: Theme) {
    let keys = Line::from(vec![
        Span::styled("?", theme.key()),
        Span::raw(" help  "),
        Span::styled("q", theme.key()),
        Span::raw(" quit "),
    ]);
    let [left, right] = Layout::horizontal([Constraint::Fill(1), Constraint::Length(15)]).areas(area);
    frame.render_widget(Paragraph::new(state(app, theme)), left);
    frame.render_widget(Paragraph::new(keys).alignment(Alignment::Right), right);
}

fn state(app: &App, theme: Theme) -> Line<'static> {
    if let Some(notice) = &app.notice {
        return Line::raw(format!(" {notice}"));
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
            Some(Progress::Assembling) => format!("⟳ assembling level {}", app.settings.level),
            None => "⟳ solving".into(),
        };
        spans.push(Span::styled(what, theme.busy()));
        spans.push(Span::raw("  "));
    }
    if app.scene == Scene::InfSup {
        let n = app.infsup_pending();
        if n > 0 {
            spans.push(Span::styled(
                format!("⟳ {n} inf-sup estimate(s) running"),
                theme.busy(),
            ));
        } else {
            spans.push(Span::raw(format!("{} inf-sup estimate(s)", app.infsup.len())));
        }
        return Line::from(spans);
    }
    if app.scene == Scene::Convergence {
        let key = app.study_key();
        let reference = key.reference_level();
        if app.study_pending() == Some(&key) {
            spans.push(Span::styled(
                format!("⟳ computing the reference (q2, level {reference})…"),
                theme.busy(),
            ));
        } else if let Some(Ok(_)) = app.studies.get(&key) {
            spans.push(Span::raw(format!(
                "M1–M4 at levels 0..={} against q2 level {reference}, ε={:e}",
                key.max_level, app.scenario.epsilon
            )));
        }
        return Line::from(spans);
    }
    let Some(solved) = &app.solved else {
        return Line::from(spans);
    };
    if app.is_solving() {
        // The previous result stays on screen; the progress above says what is coming.
        return Line::from(spans);
    }
    let newton = &solved.solution.newton;
    if newton.converged {
        spans.push(Span::styled("✓ converged", theme.good()));
    } else {
        spans.push(Span::styled("✗ NOT converged", theme.bad()));
    }
    let steps = if newton.iterations == 1 { "step" } else { "steps" };
    spans.push(Span::raw(format!(
        " in {} Newton {steps} · P={}",
        newton.iterations,
        sig(solved.solution.load, 5)
    )));
    if app.scenario.half_model {
        spans.push(Span::raw(format!(
            " (full {})",
            sig(2.0 * solved.solution.load, 5)
        )));
    }
    if app.show_timing {
        spans.push(Span::raw(format!(" · {} ms", sig(solved.total_ms, 3))));
    }
    Line::from(spans)
}
