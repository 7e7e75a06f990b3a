//! The method line of the explore scene: the contact method, what it needs (inf-sup or not,
//! ε or γ₀; [`crate::contact::Method::needs`]) and, once solved, its iteration counts.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use super::super::app::App;
use super::super::theme::Theme;

pub fn render(app: &App, frame: &mut Frame, area: Rect, theme: Theme) {
    frame.render_widget(Paragraph::new(line(app, theme)), area);
}

/// " alm: needs ε > 0, no penalty error; … · 3 updates × 2 Newton".
pub fn line(app: &App, theme: Theme) -> Line<'static> {
    let method = app.settings.method;
    let mut spans = vec![
        Span::styled(format!(" {}", method.name()), theme.title()),
        Span::raw(format!(": {}", method.needs())),
    ];
    if let Some(solved) = app.current() {
        let newton = solved.solution.newton.iterations;
        let counts = match solved.solution.outer_iterations {
            Some(1) => format!(" · 1 update × {newton} Newton"),
            Some(outer) => format!(" · {outer} updates × {newton} Newton"),
            None => format!(" · {newton} Newton"),
        };
        spans.push(Span::raw(counts));
    }
    Line::from(spans)
}
