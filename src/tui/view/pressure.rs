//! The main chart: raw pressure p (the function of Q_h through the rule's points, so steps
//! for gauss1) against the smoothed p̄ (a line through the vertices) along Γ_C, mirrored to
//! the full width for a half model, with optional overlays of the gap and the Hertz profile.

use ratatui::Frame;
use ratatui::layout::{Constraint, Rect};
use ratatui::text::Span;
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Paragraph};

use crate::plot::raw_pressure_edges;

use super::super::app::App;
use super::Look;
use super::fmt::{linear_labels, nice_ceil};
use crate::contact::hertz::Hertz;

/// Samples of the overlays across the width.
const OVERLAY_SAMPLES: usize = 241;

pub fn render(app: &App, frame: &mut Frame, area: Rect, look: &Look) {
    let theme = look.theme;
    let Some(solved) = &app.solved else {
        frame.render_widget(
            Paragraph::new("solving…").block(Block::bordered().title(" pressure on Γ_C ")),
            area,
        );
        return;
    };
    let sol = &solved.solution;
    let half = app.scenario.half_model;
    let mirror = |pts: Vec<(f64, f64)>| -> Vec<(f64, f64)> {
        if !half {
            return pts;
        }
        let mut out: Vec<(f64, f64)> = pts.iter().rev().map(|&(x, y)| (-x, y)).collect();
        out.extend(pts);
        out
    };
    let raw = mirror(raw_pressure_edges(&sol.points, &sol.p).concat());
    let pbar = mirror(
        sol.points
            .vertex_x
            .iter()
            .copied()
            .zip(sol.pbar.iter().copied())
            .collect(),
    );
    let (x0, x1) = app.scenario.x_range();
    let (xlo, xhi) = if half { (-x1, x1) } else { (x0, x1) };
    let full_load = if half { 2.0 * sol.load } else { sol.load };
    let hertz =
        Hertz::for_load(&sol.params.obstacle, &app.scenario.material, full_load).filter(|_| app.show_hertz);
    let data_max = sol.p.iter().chain(&sol.pbar).fold(0.0f64, |m, &v| m.max(v));
    let peak = data_max.max(hertz.map_or(0.0, |h| h.p0));
    let ymax = nice_ceil(peak * 1.05);

    let hertz_pts: Vec<(f64, f64)> = hertz
        .map(|h| sample(xlo, xhi, |x| Some(h.pressure(x))))
        .unwrap_or_default();
    let depth = sol.params.obstacle.depth();
    let gap_scale = if depth > 0.0 {
        data_max.max(ymax / 2.0) / depth
    } else {
        1.0
    };
    let gap_pts: Vec<(f64, f64)> = if app.show_gap {
        let obstacle = &sol.params.obstacle;
        sample(xlo, xhi, |x| {
            let g = obstacle.gap(x);
            g.is_finite().then_some(-g * gap_scale)
        })
    } else {
        Vec::new()
    };

    let mut datasets = Vec::new();
    if app.show_gap {
        datasets.push(
            Dataset::default()
                .name(format!("−g ×{}", super::fmt::sig(gap_scale, 2)))
                .marker(look.marker)
                .graph_type(GraphType::Line)
                .style(theme.faint())
                .data(&gap_pts),
        );
    }
    if hertz.is_some() {
        datasets.push(
            Dataset::default()
                .name("Hertz")
                .marker(look.marker)
                .graph_type(GraphType::Line)
                .style(theme.hertz())
                .data(&hertz_pts),
        );
    }
    datasets.push(
        Dataset::default()
            .name(format!("p {}", sol.params.rule.name()))
            .marker(look.marker)
            .graph_type(GraphType::Line)
            .style(theme.raw())
            .data(&raw),
    );
    datasets.push(
        Dataset::default()
            .name("p̄ smoothed")
            .marker(look.marker)
            .graph_type(GraphType::Line)
            .style(theme.smooth())
            .data(&pbar),
    );

    let inner_h = area.height.saturating_sub(2);
    let x_labels = if area.width >= 100 { 9 } else { 5 };
    let y_labels = if inner_h >= 14 { 5 } else { 3 };
    let key = solved.key;
    let title = format!(
        " pressure on Γ_C{} · {}+{} level {} ",
        if half { " (mirrored)" } else { "" },
        key.element.name(),
        key.rule.name(),
        key.level
    );
    let chart = Chart::new(datasets)
        .block(
            Block::bordered()
                .title(Span::styled(title, theme.title()))
                .border_style(theme.axis()),
        )
        .x_axis(
            Axis::default()
                .title("x")
                .style(theme.axis())
                .bounds([xlo, xhi])
                .labels(linear_labels(xlo, xhi, x_labels)),
        )
        .y_axis(
            Axis::default()
                .title("p")
                .style(theme.axis())
                .bounds([0.0, ymax])
                .labels(linear_labels(0.0, ymax, y_labels)),
        )
        .hidden_legend_constraints((Constraint::Ratio(1, 2), Constraint::Ratio(3, 4)));
    frame.render_widget(chart, area);
}

/// `f` at evenly spaced x over [lo, hi], where it is defined.
fn sample(lo: f64, hi: f64, f: impl Fn(f64) -> Option<f64>) -> Vec<(f64, f64)> {
    (0..OVERLAY_SAMPLES)
        .filter_map(|i| {
            let x = lo + (hi - lo) * i as f64 / (OVERLAY_SAMPLES - 1) as f64;
            f(x).map(|y| (x, y))
        })
        .collect()
}
