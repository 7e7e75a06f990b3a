//! The message log (`l`): every notice, failure and solver warning since the lab started
//! ([`super::super::app::Overlays::log`]), newest last, wrapped whole, scrolled with ↑ ↓.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph};

use super::super::app::App;
use super::super::theme::Theme;
use super::fmt::wrap_words;

/// Draw the log over `area`, its newest line at the bottom unless scrolled up.
pub fn render(app: &App, frame: &mut Frame, area: Rect, theme: Theme) {
    let log = &app.overlays.log;
    let inner_width = usize::from(area.width.saturating_sub(4)).max(1);
    let mut lines: Vec<Line> = Vec::new();
    for (failure, text) in log {
        let style = if *failure {
            theme.bad()
        } else {
            ratatui::style::Style::new()
        };
        let mark = if *failure { "✗ " } else { "· " };
        for (i, row) in wrap_words(text, inner_width.saturating_sub(2))
            .into_iter()
            .enumerate()
        {
            let lead = if i == 0 { mark } else { "  " };
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
