//! The cursor on the pressure chart and the stress map (`x`, moved with `,` and `.`): a vertical line at a contact
//! point of Γ_C (a vertex, where p̄ is defined) and a readout of x, p (both one-sided values
//! where the raw pressure steps there), p̄, the gap g, with friction t and t̄ as the chart
//! plots them (t/μ and t̄/μ with Coulomb's law, then t; t one-sided like p) and, when
//! overlaid, Hertz's pressure. The stress map reads its own quantity instead
//! ([`super::stress_map`]).

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Modifier;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use super::super::app::App;
use super::super::theme::Theme;
use super::fmt::sig;
use super::plot::{Placed, cell_of, dots_per_cell};
use ratatui::symbols::Marker;

/// Draw the cursor's line at `x` over the graph `placed` (x bounds `bounds`), on every cell
/// of its column that no mark of the chart holds.
pub fn draw_line(frame: &mut Frame, placed: Placed, bounds: [f64; 2], x: f64, marker: Marker, theme: Theme) {
    let graph = placed.graph;
    let Some(col) = cell_of(x, bounds, graph.width, dots_per_cell(marker).0) else {
        return;
    };
    let buf = frame.buffer_mut();
    for row in graph.y..graph.bottom() {
        let cell = &mut buf[(graph.x + col, row)];
        if cell.symbol().trim().is_empty() {
            cell.set_symbol("│")
                .set_style(theme.key().add_modifier(Modifier::DIM));
        }
    }
}

/// The raw pressure's values at `x` on the polyline `raw` (edge by edge): one value inside an
/// edge, the left and the right limits where two edges meet with different values.
pub fn raw_at(raw: &[(f64, f64)], x: f64) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    for w in raw.windows(2) {
        let ((xa, pa), (xb, pb)) = (w[0], w[1]);
        if xa < xb && (xa..=xb).contains(&x) {
            let v = pa + (pb - pa) * (x - xa) / (xb - xa);
            let scale = v.abs().max(1e-300);
            if !out.iter().any(|o| (o - v).abs() <= 1e-9 * scale) {
                out.push(v);
            }
        }
    }
    out
}

/// The readout of the cursor on the solution shown: "x 0.125 · p 61.3 | 70.2 · p̄ 65.8 ·
/// g 0.0012 · Hertz 66.1" (Hertz only while overlaid); None without a cursor.
pub fn readout(app: &App) -> Option<String> {
    let (x, pbar) = app.cursor_point()?;
    let solved = app.solved.as_ref()?;
    let p: Vec<String> = raw_at(&solved.shown.raw, x).iter().map(|&v| sig(v, 4)).collect();
    let obstacle = &solved.solution.params.obstacle;
    let at = if app.scenario.half_model { x.abs() } else { x };
    let gap = obstacle.gap(at);
    let mut text = format!(
        "cursor x {} · p {} · p̄ {} · gap g {}",
        sig(x, 4),
        if p.is_empty() { "–".into() } else { p.join(" | ") },
        sig(pbar, 4),
        if gap.is_finite() {
            sig(gap, 3)
        } else {
            "–".into()
        }
    );
    if let Some(f) = &solved.shown.friction {
        // What the chart plots (t/μ with Coulomb's law), then t itself.
        let per = super::friction::per_mu(f);
        let list = |values: Vec<f64>, by: f64| -> String {
            if values.is_empty() {
                return "–".into();
            }
            let each: Vec<String> = values.iter().map(|&v| sig(v * by, 4)).collect();
            each.join(" | ")
        };
        let t = raw_at(&f.t_edges, x);
        let tbar: Vec<f64> = f.tbar.iter().filter(|v| v.0 == x).map(|v| v.1).take(1).collect();
        if per == 1.0 {
            text.push_str(&format!(" · t {} · t̄ {}", list(t, 1.0), list(tbar, 1.0)));
        } else {
            text.push_str(&format!(
                " · t/μ {} · t̄/μ {} (t {})",
                list(t.clone(), per),
                list(tbar, per),
                list(t, 1.0)
            ));
        }
    }
    if app.guides.hertz
        && let Some(h) = solved.shown.hertz
    {
        text.push_str(&format!(" · Hertz {}", sig(h.pressure(x).max(0.0), 4)));
    }
    Some(text)
}

/// Draw the readout (if the cursor is shown) in the one-row `area`.
pub fn render_readout(app: &App, frame: &mut Frame, area: Rect, theme: Theme) {
    if let Some(text) = readout(app) {
        frame.render_widget(
            Paragraph::new(Line::from(vec![Span::styled(" ", theme.key()), Span::raw(text)])),
            area,
        );
    }
}
