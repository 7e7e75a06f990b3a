//! The mesh scene's axes: the body's height on the left (ticks from 0 to its top) and x along
//! the bottom, each tick label at the row or column where the canvas draws its value
//! ([`cell_of`]), so that the block's size and the grid's lines can be read off the picture.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::symbols::Marker;

use super::super::theme::Theme;
use super::plot::{Scale, cell_of, dots_per_cell, linear_ticks, tick_label};

/// The axes' layout in a block's `inner` area: the graph (right of the y labels and their
/// axis, above the x axis and its labels) and the y ticks' values (0 to `top`, the body's
/// height). None when the area is too small for axes (the graph is then the whole area).
pub fn layout(inner: Rect, top: f64) -> Option<(Rect, Vec<f64>)> {
    let ticks = linear_ticks([0.0, top], usize::from(inner.height / 3).clamp(2, 5));
    let margin = ticks
        .iter()
        .map(|&v| tick_label(v, Scale::Linear).chars().count())
        .max()
        .unwrap_or(1) as u16;
    if inner.height < 6 || inner.width < margin + 20 {
        return None;
    }
    let graph = Rect {
        x: inner.x + margin + 1,
        y: inner.y,
        width: inner.width - margin - 1,
        height: inner.height - 2,
    };
    Some((graph, ticks))
}

/// Draw the axes around `graph` (from [`layout`], in `inner`) for the canvas bounds `xb` and
/// `yb`: a y axis with `y_ticks`, an x axis with ticks on a 1-2-5 grid, their labels.
pub fn draw(
    frame: &mut Frame,
    inner: Rect,
    graph: Rect,
    (xb, yb): ([f64; 2], [f64; 2]),
    y_ticks: &[f64],
    marker: Marker,
    theme: Theme,
) {
    let per = dots_per_cell(marker);
    let style = theme.axis();
    let buf = frame.buffer_mut();
    let axis_x = graph.x - 1;
    for row in graph.y..graph.bottom() {
        buf[(axis_x, row)].set_symbol("│").set_style(style);
    }
    for &v in y_ticks {
        let Some(off) = cell_of(v, yb, graph.height, per.1) else {
            continue;
        };
        let row = graph.bottom() - 1 - off;
        buf[(axis_x, row)].set_symbol("┤");
        let label = tick_label(v, Scale::Linear);
        let w = label.chars().count() as u16;
        buf.set_string(axis_x - w, row, &label, style);
    }
    let axis_row = graph.bottom();
    buf[(axis_x, axis_row)].set_symbol("└").set_style(style);
    for col in graph.x..graph.right() {
        buf[(col, axis_row)].set_symbol("─").set_style(style);
    }
    let mut free_from = inner.x;
    for v in linear_ticks(xb, usize::from(graph.width / 7).max(2)) {
        let Some(off) = cell_of(v, xb, graph.width, per.0) else {
            continue;
        };
        let col = graph.x + off;
        buf[(col, axis_row)].set_symbol("┬");
        let label = tick_label(v, Scale::Linear);
        let w = label.chars().count() as u16;
        let start = col
            .saturating_sub((w - 1) / 2)
            .max(inner.x)
            .min(inner.right() - w);
        if start >= free_from {
            buf.set_string(start, axis_row + 1, &label, style);
            free_from = start + w + 1;
        }
    }
}
