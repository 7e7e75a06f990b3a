//! The two-body scene's meshes panel (docs/lab.md "Two bodies"): both bodies' meshes near the
//! interface, deformed — the lower body's below, the upper body's above, each vertex line
//! through its nodes — over [`MESH_WINDOW`](super::super::bodies_solve::MESH_WINDOW) of the
//! coarser body's elements about the middle of the contact zone, so that the two element
//! sizes (the ratio) and the offset are seen where they meet. Equal scales across and up.
//!
//! Displacements smaller than a tenth of the window's height are magnified (a 1-2-5 factor,
//! said in the title), and the upper body's initial gap g₀ with them: the gap drawn is the
//! factor times the gap g = g₀ + u_y(upper) − u_y(lower) (docs/design.md §12), so that the
//! bodies touch on screen where they touch, and never overlap where they do not.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::text::Span;
use ratatui::widgets::canvas::{Canvas, Line};
use ratatui::widgets::{Block, Paragraph};

use super::super::bodies_solve::{Solved, Strip, StripNode};
use super::super::view::Look;
use super::super::view::fmt::{sig, title_fit};

/// The panel's title when there is nothing to draw yet.
const TITLE: &str = " meshes at the interface ";

/// Draw the meshes of `solved` (None: a solve under way) into `area`; `lower_top` is the
/// lower body's height (where the interface lies, the bodies unpressed).
pub fn render(solved: Option<&Solved>, lower_top: f64, frame: &mut Frame, area: Rect, look: &Look) {
    let Some(solved) = solved else {
        frame.render_widget(
            Paragraph::new(" solving…").block(Block::bordered().title(TITLE)),
            area,
        );
        return;
    };
    let block = Block::bordered().border_style(look.theme.axis());
    let inner = block.inner(area);
    let (cols, rows) = (f64::from(inner.width.max(1)), f64::from(inner.height.max(1)));
    let [a, b] = solved.window;
    // A cell is about twice as tall as it is wide: equal scales across and up.
    let height = (b - a) * 2.0 * rows / cols;
    let scale = magnification(solved, height);
    let [lower, upper] = &solved.strips;
    // The interface (the lower body's top at the window's middle, deformed) 55 % up.
    let middle = lower.rows.first().and_then(|row| nearest(row, 0.5 * (a + b)));
    let level = lower_top + middle.map_or(0.0, |n| scale * n.uy);
    let (y0, y1) = (level - 0.55 * height, level + 0.45 * height);
    let lines: Vec<Line> = strip_lines(lower, scale, look.theme.mesh())
        .into_iter()
        .chain(strip_lines(upper, scale, look.theme.obstacle()))
        .collect();
    let magnified = if scale > 1.0 {
        format!(" · u, g₀ ×{}", sig(scale, 2))
    } else {
        String::new()
    };
    let label = format!(
        " meshes, x {} to {}: upper above, lower below{magnified} ",
        sig(a, 3),
        sig(b, 3)
    );
    let block = block.title(Span::styled(
        title_fit(&label, area.width.saturating_sub(2)),
        look.theme.title(),
    ));
    frame.render_widget(block, area);
    // A margin of 1 % each side: the window's edges fall inside the canvas, not on its edge.
    let margin = 0.01 * (b - a);
    let canvas = Canvas::default()
        .marker(look.marker)
        .x_bounds([a - margin, b + margin])
        .y_bounds([y0, y1])
        .paint(|ctx| {
            for line in &lines {
                ctx.draw(line);
            }
        });
    frame.render_widget(canvas, inner);
}

/// The node of `row` nearest `x`.
fn nearest(row: &[StripNode], x: f64) -> Option<&StripNode> {
    row.iter()
        .min_by(|p, q| (p.x - x).abs().total_cmp(&(q.x - x).abs()))
}

/// Magnify displacements (and the upper body's initial gap) smaller than a tenth of the
/// window's `height` to about a tenth of it, by a 1-2-5 factor; 1 otherwise.
fn magnification(solved: &Solved, height: f64) -> f64 {
    let [a, b] = solved.window;
    let largest = solved
        .strips
        .iter()
        .flat_map(|s| s.rows.iter().flatten())
        .filter(|n| n.x >= a && n.x <= b)
        .fold(0.0_f64, |m, n| m.max(n.ux.abs()).max(n.uy.abs()).max(n.lift));
    let want = 0.1 * height / largest;
    if want.is_nan() || want <= 1.0 || want.is_infinite() {
        return 1.0;
    }
    let decade = 10f64.powf(want.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&v| v <= want)
        .unwrap_or(decade)
}

/// The vertex lines of `strip` deformed by `scale` × its displacements (its initial gap
/// magnified with them): each vertex row across, each vertex column through every row.
fn strip_lines(strip: &Strip, scale: f64, color: Color) -> Vec<Line> {
    let at = |n: &StripNode| (n.x + scale * n.ux, n.y + scale * (n.lift + n.uy));
    let p = strip.order;
    let mut polylines: Vec<Vec<(f64, f64)>> = strip
        .rows
        .iter()
        .step_by(p)
        .map(|row| row.iter().map(at).collect())
        .collect();
    let across = strip.rows.first().map_or(0, Vec::len);
    for i in (0..across).filter(|i| (strip.first_column + i).is_multiple_of(p)) {
        polylines.push(strip.rows.iter().map(|row| at(&row[i])).collect());
    }
    polylines
        .iter()
        .flat_map(|poly| {
            poly.windows(2)
                .map(|w| Line::new(w[0].0, w[0].1, w[1].0, w[1].1, color))
        })
        .collect()
}
