//! The convergence scene with the lab's edge grading on: each scheme's (or
//! method's) graded series beside its uniform one, its points marked by a letter, and a table that pairs each uniform row with its graded row at the same level
//! (`4` beside `4+2e`: the graded row's unknowns, time and error of p̄).

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

use crate::study::{Status, StudyRow};

use super::super::app::{Compare, Study};
use super::super::theme::Theme;
use super::fmt::sig;

/// The glyphs of M1–M4's graded series (their uniform series are `1`–`4`).
pub(super) const GRADED_SCHEME_GLYPHS: [char; 4] = ['a', 'b', 'c', 'd'];
/// The glyphs of the graded series of penalty, alm, nitsche and exact (their uniform series
/// are `P`, `A`, `N`, `E`).
pub(super) const GRADED_METHOD_GLYPHS: [char; 4] = ['p', 'a', 'n', 'e'];

/// The table of a graded study at `levels`, headed `title`: a line per uniform row, its graded row beside it
/// (`L+e` the level as graded, `4+2e`); a row without a result says why in a word.
pub(super) fn paired_table(
    frame: &mut Frame,
    area: Rect,
    theme: Theme,
    study: &Study,
    (levels, title): (&[u32], String),
    color_of: &dyn Fn(&str) -> Option<Color>,
) {
    let methods = study.key.compare == Compare::Methods;
    let width = if methods { 8 } else { 6 };
    let first = if methods { "method" } else { "scheme" };
    let head = format!(
        // `p̄` is two chars (p and a combining macron) in one column: a column wider.
        " {first:<width$} {:>2} {:>7} {:>8} {:>10} │ {:>4} {:>7} {:>8} {:>10}",
        "L", "dofs", "ms", "err p̄", "L+e", "dofs", "ms", "err p̄"
    );
    let mut lines = vec![Line::styled(head, theme.title())];
    let name_of = |r: &StudyRow| -> String {
        if methods {
            r.method.method.into()
        } else {
            r.scheme.clone()
        }
    };
    for r in study
        .rows
        .iter()
        .filter(|r| levels.contains(&r.level) && !r.grading.grades())
    {
        let name = name_of(r);
        let graded = study.rows.iter().find(|g| {
            g.grading.grades()
                && g.level == r.level
                && g.scheme == r.scheme
                && g.method.method == r.method.method
        });
        let color = color_of(&name).unwrap_or(Color::Reset);
        let right = graded.map_or_else(|| format!("{:>4}  –", r.level), |g| numbers(g, 4));
        lines.push(Line::from(vec![
            Span::styled(format!(" {name:<width$}"), Style::new().fg(theme.ink(color))),
            Span::raw(format!("{} │{}", numbers(r, 2), right)),
        ]));
    }
    frame.render_widget(
        Paragraph::new(lines).block(
            Block::bordered()
                .title(Span::styled(title, theme.title()))
                .border_style(theme.axis()),
        ),
        area,
    );
}

/// A row's level (`level_width` wide), unknowns, time and error of p̄; or its level, its
/// unknowns and why it has no result.
fn numbers(r: &StudyRow, level_width: usize) -> String {
    let level = r.level_label();
    match (&r.errors, r.solve_ms, r.status) {
        (Some(e), Some(ms), Status::Ok) => format!(
            " {level:>level_width$} {:>7} {:>8} {:>9}",
            r.n_dofs,
            sig(ms, 3),
            sig(e.pbar, 3)
        ),
        (_, _, status) => format!(" {level:>level_width$} {:>7}  {:<17}", r.n_dofs, status.word()),
    }
}
