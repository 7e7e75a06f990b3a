//! The deformed configuration (like the paper's Figure 3): the mesh lines moved by the
//! displacement (magnified when it is small), mirrored for a half model, with the obstacle.
//! Near the contact in the explore scene; the whole body, with axes, in the mesh scene.

use ratatui::Frame;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::text::Span;
use ratatui::widgets::canvas::{Canvas, Line};
use ratatui::widgets::{Block, Paragraph};

use crate::contact::Obstacle;

use super::super::app::App;
use super::super::protocol::Solved;
use super::Look;
use super::fmt::{sig, title_fit};
use super::mesh_axes;

/// How much of the body to show.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extent {
    /// A window around the contact zone.
    NearContact,
    /// The whole body.
    Full,
}

/// Samples of the obstacle's outline.
const OUTLINE_SAMPLES: usize = 200;

pub fn render(app: &App, frame: &mut Frame, area: Rect, look: &Look, extent: Extent) {
    let title = match extent {
        Extent::NearContact => "deformed near contact",
        Extent::Full => "deformed configuration",
    };
    let Some(solved) = &app.solved else {
        frame.render_widget(
            Paragraph::new("solving…").block(Block::bordered().title(format!(" {title} "))),
            area,
        );
        return;
    };
    let Some(u) = solved.displacement.get() else {
        frame.render_widget(
            Paragraph::new("computing the displacement…")
                .block(Block::bordered().title(format!(" {title} "))),
            area,
        );
        return;
    };
    let block = Block::bordered().border_style(look.theme.axis());
    let inner = block.inner(area);
    // The whole body with its axes (the mesh scene); the contact zone without.
    let axes = (extent == Extent::Full)
        .then(|| mesh_axes::layout(inner, app.scenario.height))
        .flatten();
    let graph = axes.as_ref().map_or(inner, |(g, _)| *g);
    let (cols, rows) = (f64::from(graph.width.max(1)), f64::from(graph.height.max(1)));
    let (xb, yb) = window(app, solved, extent, cols, rows);
    let scale = magnification(u, app.scenario.height);
    let (mesh_lines, thinned) = mesh_lines(
        solved,
        u,
        scale,
        app.scenario.half_model,
        (xb, yb),
        (cols, rows),
        look.theme.mesh(),
    );
    let outline = obstacle_outline(
        &solved.solution.params.obstacle,
        app.scenario.height,
        xb,
        look.theme.obstacle(),
    );
    let thin = if thinned > 1 {
        format!(" · 1/{thinned} grid lines")
    } else {
        String::new()
    };
    let zoom = if app.zoom && extent == Extent::NearContact {
        " · zoom"
    } else {
        ""
    };
    let label = match extent {
        Extent::NearContact => format!(" contact zone{zoom} · ×{}{thin} ", sig(scale, 2)),
        Extent::Full => format!(
            " deformed · {}+{} level {} · u ×{}{thin} ",
            solved.key.element.name(),
            solved.key.rule.name(),
            solved.key.level,
            sig(scale, 2)
        ),
    };
    let block = block.title(Span::styled(
        title_fit(&label, area.width.saturating_sub(2)),
        look.theme.title(),
    ));
    frame.render_widget(block, area);
    if let Some((graph, y_ticks)) = &axes {
        mesh_axes::draw(frame, inner, *graph, (xb, yb), y_ticks, look.marker, look.theme);
    }
    let canvas = Canvas::default()
        .marker(look.marker)
        .x_bounds(xb)
        .y_bounds(yb)
        .paint(|ctx| {
            for line in &mesh_lines {
                ctx.draw(line);
            }
            ctx.layer();
            for line in &outline {
                ctx.draw(line);
            }
        });
    frame.render_widget(canvas, graph);
}

/// x and y bounds with equal scales on screen (a cell is about twice as tall as wide).
fn window(app: &App, solved: &Solved, extent: Extent, cols: f64, rows: f64) -> ([f64; 2], [f64; 2]) {
    let s = &app.scenario;
    let (x0, x1) = s.x_range();
    let (xlo, xhi) = if s.half_model { (-x1, x1) } else { (x0, x1) };
    let top = s.height;
    let aspect = 2.0 * rows / cols; // data height per data width for square pixels
    match extent {
        Extent::Full => {
            // A margin of 1% each side: the body's sides fall inside the canvas, not on its edge.
            let (w, h) = (1.02 * (xhi - xlo), top * 1.3);
            let unit = (w / cols).max(h / (2.0 * rows));
            let (xr, yr) = (unit * cols, unit * 2.0 * rows);
            let xc = 0.5 * (xlo + xhi);
            ([xc - xr / 2.0, xc + xr / 2.0], [-0.05 * top, yr - 0.05 * top])
        }
        Extent::NearContact => {
            let obstacle = &solved.solution.params.obstacle;
            let zoomed = if app.zoom { solved.shown.zone } else { None };
            let (center, half_width) = match zoomed {
                // The contact zone with its margin, as the zoomed pressure chart shows it.
                Some([a, b]) => (0.5 * (a + b), 0.5 * (b - a)),
                None => {
                    let center = obstacle.center();
                    let reach = obstacle
                        .contact_extent(xlo, xhi)
                        .map_or(0.0, |(lo, hi)| (hi - center).max(center - lo));
                    let half_width = (1.6 * reach)
                        .max(4.0 * s.h(solved.key.level))
                        .min(0.5 * (xhi - xlo));
                    (center, half_width)
                }
            };
            let yr = 2.0 * half_width * aspect;
            (
                [center - half_width, center + half_width],
                [top - 0.65 * yr, top + 0.35 * yr],
            )
        }
    }
}

/// Magnify displacements smaller than 2% of the height to about 10% of it (a 1-2-5 factor).
fn magnification(u: &[f64], height: f64) -> f64 {
    let umax = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if umax <= 0.0 || umax >= 0.02 * height {
        return 1.0;
    }
    let want = 0.1 * height / umax;
    let p = 10f64.powf(want.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&v| v <= want)
        .unwrap_or(p)
}

/// The deformed grid lines, every `k`-th vertex line so that a cell spans at least two
/// terminal columns and one row (and on a graded mesh no two lines closer than that), each line through every node (curved for Q2), mirrored for
/// a half model; and `k`.
fn mesh_lines(
    solved: &Solved,
    u: &[f64],
    scale: f64,
    half: bool,
    (xb, yb): ([f64; 2], [f64; 2]),
    (cols, rows): (f64, f64),
    color: Color,
) -> (Vec<Line>, usize) {
    let mesh = &solved.disc.mesh;
    let p = mesh.element.order();
    let h = mesh.h();
    // Cells across the window per two columns, and per row.
    let dense = ((xb[1] - xb[0]) / h / (cols / 2.0)).max((yb[1] - yb[0]) / h / rows);
    let k = (dense.max(1.0).ceil() as usize).next_power_of_two();
    let at = |i: usize, j: usize| -> (f64, f64) {
        let n = mesh.node(i, j);
        let (x, y) = mesh.node_coords(n);
        (x + scale * u[2 * n], y + scale * u[2 * n + 1])
    };
    // Every k-th vertex line, and of those only lines at least `gap` from the last one kept
    // (two columns across, one row up): a graded mesh's dense lines read as denser lines up
    // to the screen's resolution instead of merging into solid blocks. The last line stays.
    let every = |lines: &[f64], gap: f64| -> Vec<usize> {
        let n = lines.len() - 1;
        let mut v: Vec<usize> = Vec::new();
        for i in (0..=n).step_by(k) {
            if v.last().is_none_or(|&j| lines[i] - lines[j] >= gap) {
                v.push(i);
            }
        }
        match v.last() {
            Some(&j) if j == n => {}
            Some(&j) if lines[n] - lines[j] < gap && v.len() > 1 => *v.last_mut().unwrap() = n,
            _ => v.push(n),
        }
        v
    };
    let (gap_x, gap_y) = (2.0 * (xb[1] - xb[0]) / cols, (yb[1] - yb[0]) / rows);
    let mut polylines: Vec<Vec<(f64, f64)>> = Vec::new();
    for jv in every(&mesh.ys, gap_y) {
        polylines.push((0..mesh.nnx()).map(|i| at(i, jv * p)).collect());
    }
    let nny = mesh.node_y.len();
    for iv in every(&mesh.xs, gap_x) {
        polylines.push((0..nny).map(|j| at(iv * p, j)).collect());
    }
    let mut lines = Vec::new();
    for poly in &polylines {
        for w in poly.windows(2) {
            let ((x1, y1), (x2, y2)) = (w[0], w[1]);
            lines.push(Line::new(x1, y1, x2, y2, color));
            if half {
                lines.push(Line::new(-x1, y1, -x2, y2, color));
            }
        }
    }
    (lines, k)
}

/// The obstacle's lower outline over the window, as line segments.
fn obstacle_outline(obstacle: &Obstacle, top: f64, xb: [f64; 2], color: Color) -> Vec<Line> {
    let pts: Vec<(f64, f64)> = (0..OUTLINE_SAMPLES)
        .filter_map(|i| {
            let x = xb[0] + (xb[1] - xb[0]) * i as f64 / (OUTLINE_SAMPLES - 1) as f64;
            let g = obstacle.gap(x);
            g.is_finite().then_some((x, top + g))
        })
        .collect();
    pts.windows(2)
        .map(|w| Line::new(w[0].0, w[0].1, w[1].0, w[1].1, color))
        .collect()
}
