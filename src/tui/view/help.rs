//! The help overlay listing every key.

use ratatui::Frame;
use ratatui::layout::{Constraint, Flex, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph};

use super::super::theme::Theme;

/// Every key and what it does.
pub const KEYS: [(&str, &str); 20] = [
    ("q  Esc  Ctrl-C", "quit"),
    ("?", "this help (any key closes it)"),
    ("←  →   [  ]", "coarser / finer mesh level (0 to 6)"),
    ("1 2 3 4", "the paper's schemes M1–M4"),
    ("r  e", "next contact rule / element (q1, q2, p1)"),
    ("+  -", "ε × 10 / ε ÷ 10 (1e-14 to 1e2)"),
    ("m", "next method: penalty, exact, alm, nitsche"),
    ("d  D", "depth − 0.1 / + 0.1"),
    ("Tab  Shift-Tab", "next / previous scene"),
    ("g  h", "gap / Hertz overlay on the pressure chart"),
    ("z", "zoom to the contact zone (p̄ > 0) and back"),
    ("a", "inf-sup at every level up to this one"),
    ("s  S  v", "export CSV / SVG / VTU (new files, ε and"),
    ("", "d in the name; --export-dir sets where)"),
    ("c", "stress scene: τ₁ / von Mises / σ_yy"),
    ("0", "reset to the scenario's settings"),
    ("Ctrl-Z", "suspend (fg resumes)"),
    ("", "p, p̄ and E share a unit; x is in units of"),
    ("", "length; load P = ∫p over Γ_C (per unit"),
    ("", "thickness; full: both halves)"),
];

pub fn render(frame: &mut Frame, area: Rect, theme: Theme) {
    key_popup(frame, area, theme, " keys ", &KEYS, (62, 16));
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
