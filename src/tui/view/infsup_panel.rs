//! The inf-sup panel of the explore scene: β_h, β_h/√h and β̄_h/√h for the current element
//! and rule at every level computed so far, the current level highlighted, and a verdict.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

use crate::contact::Rule;
use crate::mesh::Element;
use crate::scheme::Scheme;

use super::super::app::{App, InfSupKey};
use super::super::beta::InfSup;
use super::super::theme::Theme;
use super::fmt::{sig, table_row};

/// Below this ratio of β/√h between two successive levels, the estimate is decaying.
const DECAY: f64 = 0.8;

pub fn render(app: &App, frame: &mut Frame, area: Rect, theme: Theme) {
    let key = app.infsup_key();
    let scheme = Scheme::new(key.element, key.rule)
        .name()
        .map(|m| format!("{m} "))
        .unwrap_or_default();
    let levels = computed_levels(app, key.element, key.rule);
    let rows = area.height.saturating_sub(4) as usize; // borders, header, verdict
    let shown = visible(&levels, key.level, rows);
    let title = format!(
        " inf-sup · {scheme}{}+{}{} ",
        key.element.name(),
        key.rule.name(),
        hidden_rows(&levels, shown)
    );
    let mut lines = vec![Line::styled(
        format!(
            " {:>2} {:>6} {:>9} {:>9} {:>9}",
            "L", "h", "β_h", "β_h/√h", "β̄_h/√h"
        ),
        theme.title(),
    )];
    for &level in shown {
        let k = InfSupKey { level, ..key };
        let mark = if level == key.level { '▸' } else { ' ' };
        let text = match app.infsup.get(&k) {
            Some(Ok(b)) => {
                let (beta, over) = match b.kernel {
                    Some(_) => ("kernel".to_string(), "kernel".to_string()),
                    None => (sig(b.beta, 3), sig(b.beta_over_sqrt_h, 3)),
                };
                table_row(
                    &format!("{mark}{level:>2}"),
                    &[
                        (&sig(b.h, 3), 6),
                        (&beta, 9),
                        (&over, 9),
                        (&sig(b.beta_bar_over_sqrt_h, 3), 9),
                    ],
                )
            }
            Some(Err(e)) => format!("{mark}{level:>2} {e}"),
            None => format!(
                "{mark}{level:>2} {:>6} ⟳ estimating…",
                sig(app.scenario.h(level), 3)
            ),
        };
        let style = if level == key.level {
            theme.selected()
        } else {
            ratatui::style::Style::new()
        };
        lines.push(Line::styled(text, style));
    }
    lines.push(verdict(app, key.element, key.rule, theme));
    frame.render_widget(
        Paragraph::new(lines).wrap(Wrap { trim: false }).block(
            Block::bordered()
                .title(Span::styled(title, theme.title()))
                .border_style(theme.axis()),
        ),
        area,
    );
}

/// The panel in one row without borders, where the explore scene is too short for it (the
/// chart keeps its rows): the current level's β_h/√h and β̄_h/√h, and the verdict.
pub fn render_row(app: &App, frame: &mut Frame, area: Rect, theme: Theme) {
    let key = app.infsup_key();
    let scheme = Scheme::new(key.element, key.rule)
        .name()
        .map(|m| format!("{m} "))
        .unwrap_or_default();
    let numbers = match app.infsup.get(&key) {
        Some(Ok(b)) if b.kernel.is_some() => "β_h = 0, kernel".to_string(),
        Some(Ok(b)) => format!(
            "β_h/√h {} β̄_h/√h {}",
            sig(b.beta_over_sqrt_h, 3),
            sig(b.beta_bar_over_sqrt_h, 3)
        ),
        Some(Err(_)) => "failed (l: log)".to_string(),
        None => "⟳ estimating…".to_string(),
    };
    let mut spans = vec![
        Span::styled(format!("inf-sup {scheme}L{}: ", key.level), theme.title()),
        Span::raw(format!("{numbers} · ")),
    ];
    spans.extend(verdict(app, key.element, key.rule, theme).spans);
    frame.render_widget(Paragraph::new(Line::from(spans)), area);
}

/// The rows of `levels` that fit in `rows`: all, else a window that holds `current` (the
/// finest rows when `current` is not among them), as far down as it can go.
pub fn visible(levels: &[u32], current: u32, rows: usize) -> &[u32] {
    let rows = rows.max(1);
    if levels.len() <= rows {
        return levels;
    }
    let end = match levels.iter().position(|&l| l == current) {
        // Keep the current row, with the row after it when there is one.
        // (One row: the current one.)
        Some(i) => (i + 2).min(levels.len()).max(rows).min(i + rows),
        None => levels.len(),
    };
    &levels[end - rows..end]
}

/// " · rows 2–5 of 7" when `shown` is not all of `levels`, else nothing.
pub fn hidden_rows(levels: &[u32], shown: &[u32]) -> String {
    match (shown.first(), shown.last()) {
        (Some(a), Some(b)) if shown.len() < levels.len() => {
            format!(" · L{a}–{b} of {}", levels.len())
        }
        _ => String::new(),
    }
}

/// Levels with an estimate (done, failed or running) for this element and rule, ascending.
pub fn computed_levels(app: &App, element: Element, rule: Rule) -> Vec<u32> {
    (0..=super::super::app::MAX_APP_LEVEL)
        .filter(|&level| {
            let k = InfSupKey { level, element, rule };
            app.infsup.contains_key(&k) || app.is_estimating(&k)
        })
        .collect()
}

/// The successful estimates for this element and rule, by ascending level.
pub fn estimates(app: &App, element: Element, rule: Rule) -> Vec<(u32, &InfSup)> {
    (0..=super::super::app::MAX_APP_LEVEL)
        .filter_map(|level| {
            let k = InfSupKey { level, element, rule };
            match app.infsup.get(&k) {
                Some(Ok(b)) => Some((level, b)),
                _ => None,
            }
        })
        .collect()
}

/// Stability as observed: a kernel, β/√h decaying between the two finest levels, or bounded.
/// `pick` selects β/√h (raw) or β̄/√h (smoothed).
pub fn trend(app: &App, element: Element, rule: Rule, pick: fn(&InfSup) -> f64) -> Option<bool> {
    let est = estimates(app, element, rule);
    if est.iter().any(|(_, b)| pick(b) == 0.0) {
        return Some(false);
    }
    match est.as_slice() {
        [.., (_, a), (_, b)] => Some(pick(b) >= DECAY * pick(a)),
        _ => None,
    }
}

/// The observed slope of log(β/√h) against log h between the two finest levels estimated
/// (0 where β/√h is bounded, positive where it decays as h → 0); None with fewer than two
/// levels or a zero estimate.
pub fn slope(app: &App, element: Element, rule: Rule, pick: fn(&InfSup) -> f64) -> Option<f64> {
    match estimates(app, element, rule).as_slice() {
        [.., (_, a), (_, b)] if pick(a) > 0.0 && pick(b) > 0.0 && a.h != b.h => {
            Some((pick(b) / pick(a)).ln() / (b.h / a.h).ln())
        }
        _ => None,
    }
}

fn mark(stable: Option<bool>, theme: Theme) -> Span<'static> {
    match stable {
        Some(true) => Span::styled("✓", theme.good()),
        Some(false) => Span::styled("✗", theme.bad()),
        None => Span::raw("?"),
    }
}

/// "trend: p ✗  p̄ ✓ · paper: unstable": observed (✓ bounded, ✗ decaying or a kernel, ? fewer
/// than two levels), and the paper's verdict for M1–M4.
fn verdict(app: &App, element: Element, rule: Rule, theme: Theme) -> Line<'static> {
    let raw = trend(app, element, rule, |b| b.beta_over_sqrt_h);
    let smooth = trend(app, element, rule, |b| b.beta_bar_over_sqrt_h);
    let mut spans = vec![
        Span::raw("trend: p "),
        mark(raw, theme),
        Span::raw("  p̄ "),
        mark(smooth, theme),
    ];
    if let Some(m) = Scheme::new(element, rule).name() {
        let stable = matches!(m, "M3" | "M4");
        spans.push(Span::raw(format!(
            " · paper: {}",
            if stable { "stable" } else { "unstable" }
        )));
    }
    Line::from(spans)
}
