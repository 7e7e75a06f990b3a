//! The help overlay: the keys of the scene shown, then every key ([`super::super::keys`]).

use ratatui::Frame;
use ratatui::layout::{Constraint, Flex, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph};

use super::super::app::Scene;
use super::super::key_bar;
use super::super::theme::Theme;

/// The lab's help overlay ([`key_bar::scene_help`]: the keys that act in `scene` first, then
/// every key, the Ctrl keys, a note on units and the mouse), centred over `area`, from line
/// `scroll` on (kept within the list); the title says when lines are above or below.
pub fn render(frame: &mut Frame, area: Rect, theme: Theme, scroll: u16, scene: Scene) {
    let all = key_bar::scene_help(scene);
    let rows = usize::from(area.height.saturating_sub(2)).max(1);
    let first = usize::from(scroll).min(all.len().saturating_sub(rows));
    let shown = &all[first..(first + rows).min(all.len())];
    let title = match (first > 0, first + shown.len() < all.len()) {
        (false, false) => " keys ".to_string(),
        (above, below) => format!(
            " keys {}–{} of {} ({}) ",
            first + 1,
            first + shown.len(),
            all.len(),
            match (above, below) {
                (true, true) => "↑ ↓ scroll",
                (true, false) => "↑ scrolls",
                _ => "↓ scrolls",
            }
        ),
    };
    key_popup(frame, area, theme, &title, shown, (62, 16));
}

/// A bordered list of `keys` (key, what it does) centred over `area`, `size` = (popup width,
/// key column width): the lab's help and the tour's.
pub fn key_popup(
    frame: &mut Frame,
    area: Rect,
    theme: Theme,
    title: &str,
    keys: &[(&str, &str)],
    size: (u16, usize),
) {
    let (width, key_width) = size;
    let height = (keys.len() as u16 + 2).min(area.height);
    let [row] = Layout::vertical([Constraint::Length(height)])
        .flex(Flex::Center)
        .areas(area);
    let [popup] = Layout::horizontal([Constraint::Length(width.min(area.width))])
        .flex(Flex::Center)
        .areas(row);
    let lines: Vec<Line> = keys
        .iter()
        .map(|(key, what)| {
            Line::from(vec![
                Span::styled(format!(" {key:<key_width$}"), theme.key()),
                Span::raw(*what),
            ])
        })
        .collect();
    frame.render_widget(Clear, popup);
    frame.render_widget(
        Paragraph::new(lines).block(
            Block::bordered()
                .title(Span::styled(title, theme.title()))
                .border_style(theme.axis()),
        ),
        popup,
    );
}
