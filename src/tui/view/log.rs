//! The message log (`l`): every notice, failure, solver warning and change of state since
//! the lab started ([`super::super::app::Overlays::log`]), each with its time, repeats
//! folded (`× 6`), newest last, wrapped whole, scrolled with ↑ ↓.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph};

use super::super::app::App;
use super::super::app::log::clock;
use super::super::theme::Theme;
use super::fmt::wrap_words;

/// Draw the log over `area`, its newest line at the bottom unless scrolled up.
pub fn render(app: &App, frame: &mut Frame, area: Rect, theme: Theme) {
    let log = &app.overlays.log;
    let inner_width = usize::from(area.width.saturating_sub(4)).max(1);
    let mut lines: Vec<Line> = Vec::new();
    for entry in log.iter() {
        let style = if entry.failure {
            theme.bad()
        } else {
            ratatui::style::Style::new()
        };
        // `m:ss ✗ text × n`, the further rows indented under the text.
        let time = format!("{:>5} ", clock(entry.at));
        let mark = if entry.failure { "✗ " } else { "· " };
        let times = if entry.count > 1 {
            format!(" × {}", entry.count)
        } else {
            String::new()
        };
        let lead_width = time.chars().count() + 2;
        let text = format!("{}{times}", entry.text);
        for (i, row) in wrap_words(&text, inner_width.saturating_sub(lead_width))
            .into_iter()
            .enumerate()
        {
            let lead = if i == 0 {
                format!("{time}{mark}")
            } else {
                " ".repeat(lead_width)
            };
            lines.push(Line::from(vec![Span::raw(lead), Span::styled(row, style)]));
        }
    }
    let empty = lines.is_empty();
    if empty {
        lines.push(Line::raw(
            "no notice, failure or solver warning yet (the status line shows the last solve)",
        ));
    }
    let rows = usize::from(area.height.saturating_sub(2)).max(1);
    let last_first = lines.len().saturating_sub(rows);
    let first = last_first.saturating_sub(usize::from(app.overlays.log_scroll));
    let total = lines.len();
    let shown: Vec<Line> = lines.into_iter().skip(first).take(rows).collect();
    let title = if empty {
        " messages: none yet (any key closes) ".to_string()
    } else if total <= rows {
        let plural = if total == 1 { "" } else { "s" };
        format!(" messages: {total} line{plural} (any key closes) ")
    } else {
        format!(
            " messages: lines {}–{} of {total} (↑ ↓ scroll, other keys close) ",
            first + 1,
            first + shown.len()
        )
    };
    frame.render_widget(Clear, area);
    frame.render_widget(
        Paragraph::new(shown).block(
            Block::bordered()
                .title(Span::styled(title, theme.title()))
                .border_style(theme.axis()),
        ),
        area,
    );
}
