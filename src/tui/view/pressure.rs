//! The main chart (drawn from the solution's [`super::super::shown::Shown`]): raw pressure p (the function of Q_h through the rule's points, so steps
//! for gauss1, a dotted line) against the smoothed p̄ (a solid line through the vertices)
//! along Γ_C, mirrored to the full width for a half model, with the overlays switched on one
//! by one (docs/lab.md, "Overlays"): the gap, the Hertz profile (its parabola, `+`), the exact
//! circular indenter's (`o`) and Mindlin's q (`*`), drawn under p̄ and p. p is drawn last so
//! that its oscillation stays visible on fine meshes. Units are the paper's: x in units of length, p in the units of E.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::widgets::{Block, Paragraph};

use super::super::app::{App, Drawn};
use super::fmt::sig;
use super::plot::{Axis, Plot, Scale, Series, Stroke};
use super::{Look, cursor, friction};

/// Samples of the overlays across the width.
const OVERLAY_SAMPLES: usize = 41;

pub fn render(app: &App, frame: &mut Frame, area: Rect, look: &Look) {
    let theme = look.theme;
    // The cursor's readout takes the chart's last row.
    let (area, readout_row) = match cursor::readout(app) {
        Some(_) if area.height > 8 => {
            let [chart, row] = Layout::vertical([Constraint::Fill(1), Constraint::Length(1)]).areas(area);
            (chart, Some(row))
        }
        _ => (area, None),
    };
    let Some(solved) = &app.solved else {
        frame.render_widget(
            Paragraph::new("solving…").block(Block::bordered().title(" pressure on Γ_C ")),
            area,
        );
        return;
    };
    let sol = &solved.solution;
    let shown = &solved.shown;
    let half = app.scenario.half_model;
    let full = shown.x_range;
    let zoomed = if app.zoom { shown.zone } else { None };
    let xb = zoomed.unwrap_or(full);
    let guides = app.guides;
    let hertz = shown.hertz.filter(|_| guides.hertz);
    let data_max = shown.peak;
    let circle = shown.circle.filter(|_| guides.circle);
    let peak = data_max
        .max(hertz.map_or(0.0, |h| h.p0))
        .max(circle.map_or(0.0, |c| c.p0));
    // With friction: t, t̄, the stick zone and (with `M`) q on the same axis.
    let friction = shown.friction.as_ref();
    let layer = friction.map(|f| friction::Layer::new(f, xb, guides.mindlin));
    let (peak, low) = layer
        .as_ref()
        .map_or((peak, 0.0), |l| (peak.max(l.peak()), l.low()));
    // The data's range: the axis is fitted to it and to the rows ([`super::yfit`]).
    let ymax = if peak > 0.0 { peak } else { 1.0 };
    let ymin = low.min(0.0);

    // Inside the contact zone only: outside it both are 0, on p̄'s own line, and their marks
    // along the whole axis hid it.
    let hertz_pts: Vec<(f64, f64)> = hertz
        .map(|h| sample(xb, 0.0, |x| Some(h.pressure(x)).filter(|&p| p > 0.0)))
        .unwrap_or_default();
    let circle_pts: Vec<(f64, f64)> = circle
        // Between Hertz's samples, so that neither hides the other where they agree.
        .map(|c| sample(xb, 0.5, |x| Some(c.pressure(x)).filter(|&p| p > 0.0)))
        .unwrap_or_default();
    let depth = sol.params.obstacle.depth();
    let gap_scale = if depth > 0.0 {
        data_max.max(ymax / 2.0) / depth
    } else {
        1.0
    };
    let gap_pts: Vec<(f64, f64)> = if guides.gap {
        let obstacle = &sol.params.obstacle;
        sample(xb, 0.0, |x| {
            let g = obstacle.gap(x);
            g.is_finite().then_some(-g * gap_scale)
        })
    } else {
        Vec::new()
    };

    let inks = friction::Inks {
        smooth: theme.ink(ratatui::style::Color::Green),
        raw: theme.ink(ratatui::style::Color::LightRed),
        overlay: theme.hertz_color(),
        stick: theme.ink(ratatui::style::Color::LightGreen),
    };
    // The overlays in the order the chart keeps them when its rows are few.
    let mut overlays = Vec::new();
    if let Some(h) = hertz {
        // Hertz's half-width and peak for the computed load, and p̄'s distance from it.
        let error = shown
            .hertz_error
            .map_or(String::new(), |e| format!(", p̄ off {}%", sig(100.0 * e, 2)));
        overlays.push(Series {
            name: format!("Hertz a={} p₀={}{error}", sig(h.a, 3), sig(h.p0, 3)),
            color: theme.hertz_color(),
            stroke: Stroke::None,
            glyph: Some('+'),
            data: &hertz_pts,
        });
    }
    overlays.extend(layer.as_ref().and_then(|l| l.overlay(&inks)));
    if circle.is_some() {
        overlays.push(Series {
            name: "circle".into(),
            color: theme.hertz_color(),
            stroke: Stroke::None,
            glyph: Some('o'),
            data: &circle_pts,
        });
    }
    if guides.gap {
        overlays.push(Series {
            name: format!("gap −g, scaled ×{}", sig(gap_scale, 2)),
            color: theme.faint_color(),
            stroke: Stroke::None,
            glyph: Some('·'),
            data: &gap_pts,
        });
    }
    let mut series = Vec::new();
    // With friction the legend is long: p's names short (the title names the rule).
    let on = friction.is_some();
    series.push(Series {
        name: if on { "p̄" } else { "p̄ smoothed" }.into(),
        color: theme.smooth_color(),
        stroke: Stroke::Solid,
        glyph: None,
        data: &shown.pbar,
    });
    series.push(Series {
        name: if on {
            "p".into()
        } else {
            format!("p {}", sol.params.rule.name())
        },
        color: theme.raw_color(),
        stroke: Stroke::Dotted,
        glyph: None,
        data: &shown.raw,
    });
    if let Some(l) = &layer {
        series.extend(l.series(&inks));
    }
    // A contact zone under a sixth of the axis is worth zooming into: say so.
    let narrow = shown.zone.is_some_and(|[a, b]| b - a < (full[1] - full[0]) / 6.0);
    let key = solved.key;
    let title = format!(
        " {}{}{} · {}+{} level {} ",
        if friction.is_some() {
            "p and t on Γ_C"
        } else {
            "pressure on Γ_C"
        },
        if half { " (mirrored)" } else { "" },
        match (zoomed.is_some(), narrow) {
            (true, _) => " · zoom (z: back)",
            (false, true) => " · z zooms in",
            _ => "",
        },
        key.element.name(),
        key.rule.name(),
        key.level
    );
    let plot = Plot {
        title,
        x: Axis {
            title: "x (length)".into(),
            bounds: xb,
            scale: Scale::Linear,
        },
        y: Axis {
            title: layer
                .as_ref()
                .map_or("p (units of E)".into(), friction::Layer::y_title),
            bounds: [ymin, ymax],
            scale: Scale::Linear,
        },
        overlays,
        series,
        marker: look.marker,
        theme,
    };
    let placed = plot.render(frame, area);
    if let Some(placed) = placed {
        // Where a click places the cursor.
        let drawn = app.overlays.drawn.get();
        app.overlays.drawn.set(Drawn {
            chart: Some((placed.graph, xb)),
            ..drawn
        });
    }
    if let (Some(placed), Some(ends)) = (placed, layer.as_ref().and_then(|l| l.stick)) {
        friction::draw_stick(frame, placed, xb, ends, look.marker, inks.stick);
    }
    if let (Some(placed), Some((x, _))) = (placed, app.cursor_point()) {
        cursor::draw_line(frame, placed, xb, x, look.marker, theme);
    }
    if let Some(row) = readout_row {
        cursor::render_readout(app, frame, row, theme);
    }
}

/// `f` at evenly spaced x over `[lo, hi]`, where it is defined, shifted by `phase` of a step
/// (the last sample dropped where it would leave the range).
fn sample([lo, hi]: [f64; 2], phase: f64, f: impl Fn(f64) -> Option<f64>) -> Vec<(f64, f64)> {
    (0..OVERLAY_SAMPLES)
        .filter_map(|i| {
            let x = lo + (hi - lo) * (i as f64 + phase) / (OVERLAY_SAMPLES - 1) as f64;
            if x > hi {
                return None;
            }
            f(x).map(|y| (x, y))
        })
        .collect()
}
