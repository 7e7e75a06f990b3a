//! The stress scene: a heat map of τ₁, von Mises or σ_yy (key `c` cycles) over the body near
//! the contact, mirrored for a half model, with a colour bar and its range in numbers and a
//! marker at the maximum with its value and depth. Each level is a shading glyph (· ░ ▒ ▓ █)
//! as well as a colour, so that the map reads the same under NO_COLOR.
//!
//! The stresses ([`crate::stress::StressField`]) are computed by the worker the first time
//! the scene shows a solution, and kept with it; this view only draws them.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

use crate::stress::{Peak, Quantity, StressField};

use super::super::app::App;
use super::super::protocol::Solved;
use super::super::theme::Theme;
use super::Look;
use super::fmt::sig;

/// The shading of the levels, lowest first, and their colours.
const GLYPHS: [&str; 5] = ["·", "░", "▒", "▓", "█"];
const COLOURS: [Color; 5] = [Color::Blue, Color::Cyan, Color::Green, Color::Yellow, Color::Red];
/// The marker at the maximum.
const MARKER: &str = "✕";
/// Width of the colour bar with its labels.
const BAR_WIDTH: u16 = 12;

pub fn render(app: &App, frame: &mut Frame, area: Rect, look: &Look) {
    let q = app.stress_quantity;
    let zoom = if app.zoom { " · zoom (z: back)" } else { "" };
    let title = format!(" {} near the contact (c: next quantity){zoom} ", q.symbol());
    let block = Block::bordered().title(title).border_style(look.theme.axis());
    let Some(solved) = &app.solved else {
        frame.render_widget(Paragraph::new("solving…").block(block), area);
        return;
    };
    let field = match solved.stresses.get() {
        Some(Ok(f)) => f.clone(),
        None => {
            frame.render_widget(Paragraph::new("computing the stresses…").block(block), area);
            return;
        }
        Some(Err(e)) => {
            frame.render_widget(Paragraph::new(format!("stresses: {e}")).block(block), area);
            return;
        }
    };
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let [body, caption] = Layout::vertical([Constraint::Fill(1), Constraint::Length(1)]).areas(inner);
    let [map_area, bar_area] =
        Layout::horizontal([Constraint::Fill(1), Constraint::Length(BAR_WIDTH)]).areas(body);
    let mut map = HeatMap::sample(app, solved, &field, q, map_area);
    let peak = field.peak(&solved.disc.mesh, q);
    // The bar's ends hold the marked peak (a quadrature point's value, beyond the cells'
    // centres the map samples) when it lies in the window.
    if peak.value.is_finite() && (map.x.0..=map.x.1).contains(&peak.x) && peak.depth <= map.z_max {
        map.range = (map.range.0.min(peak.value), map.range.1.max(peak.value));
    }
    frame.render_widget(Paragraph::new(map.lines(&peak, look.theme)), map_area);
    frame.render_widget(
        Paragraph::new(colour_bar(map.range, bar_area.height, look.theme)),
        bar_area,
    );
    // The cursor (`x`): a vertical line at its contact point, the stress under it for the
    // caption.
    match app.cursor_point() {
        Some((x, _)) => {
            let (a, b) = map.x;
            let col = ((x - a) / (b - a) * f64::from(map_area.width)).floor();
            if (0.0..f64::from(map_area.width)).contains(&col) {
                let buf = frame.buffer_mut();
                for row in map_area.y..map_area.bottom() {
                    buf[(map_area.x + col as u16, row)]
                        .set_symbol("│")
                        .set_style(look.theme.key().add_modifier(Modifier::BOLD));
                }
            }
            frame.render_widget(Paragraph::new(format!(" {}", map.readout(x, q))), caption);
        }
        None => frame.render_widget(Paragraph::new(caption_line(&peak, &map, look.theme)), caption),
    }
}

/// The quantity sampled at the centre of every character cell of the map.
struct HeatMap {
    values: Vec<Vec<f64>>,
    /// The window: x from −x_max (0 for a full model's left edge) to x_max, depth 0..z_max.
    x: (f64, f64),
    z_max: f64,
    range: (f64, f64),
}

impl HeatMap {
    fn sample(app: &App, solved: &Solved, field: &StressField, q: Quantity, area: Rect) -> HeatMap {
        let s = &app.scenario;
        let mesh = &solved.disc.mesh;
        let (cols, rows) = (usize::from(area.width.max(1)), usize::from(area.height.max(1)));
        let (x_lo, x_hi) = (mesh.xs[0], mesh.xs[mesh.xs.len() - 1]);
        let top = mesh.ys[mesh.ys.len() - 1];
        let full = if s.half_model { (-x_hi, x_hi) } else { (x_lo, x_hi) };
        // Zoomed: the window of the zoomed pressure chart. Otherwise 2.5 times the contact
        // zone's half-width (the farthest Γ_C vertex from the centre where p̄ > 0).
        let zoomed = if app.zoom { solved.shown.zone } else { None };
        let (a, b) = match zoomed {
            Some([a, b]) => (a, b),
            None => {
                let centre = solved.solution.params.obstacle.center();
                let zone = solved
                    .solution
                    .points
                    .vertex_x
                    .iter()
                    .zip(&solved.solution.pbar)
                    .filter(|&(_, &p)| p > 0.0)
                    .map(|(&x, _)| (x - centre).abs())
                    .fold(0.0, f64::max);
                let half = if zone > 0.0 {
                    2.5 * zone
                } else {
                    (x_hi - x_lo) / 4.0
                };
                let (a, b) = if s.half_model {
                    (-half.min(x_hi), half.min(x_hi))
                } else {
                    ((centre - half).max(x_lo), (centre + half).min(x_hi))
                };
                if b <= a { full } else { (a, b) }
            }
        };
        // A character is about twice as tall as wide: keep the body's proportions.
        let z_max = ((b - a) / cols as f64 * 2.0 * rows as f64).min(top - mesh.ys[0]);
        let values: Vec<Vec<f64>> = (0..rows)
            .map(|r| {
                let y = top - z_max * (r as f64 + 0.5) / rows as f64;
                (0..cols)
                    .map(|c| {
                        let x = a + (b - a) * (c as f64 + 0.5) / cols as f64;
                        // The mirror image of the half model: τ₁, von Mises and σ_yy are even.
                        let x = if s.half_model { x.abs() } else { x };
                        field.at(mesh, x, y).get(q)
                    })
                    .collect()
            })
            .collect();
        let finite = || values.iter().flatten().copied().filter(|v| v.is_finite());
        let range = (
            finite().fold(f64::INFINITY, f64::min),
            finite().fold(f64::NEG_INFINITY, f64::max),
        );
        HeatMap {
            values,
            x: (a, b),
            z_max,
            range,
        }
    }

    /// The cursor's readout at `x`: the quantity in the map's column under it, at Γ_C (its top
    /// row) and its largest with the depth: "cursor x 0.125 · τ₁ under it 12.3 at Γ_C, largest
    /// 45.6 at depth 0.21".
    fn readout(&self, x: f64, q: Quantity) -> String {
        let (a, b) = self.x;
        let cols = self.values.first().map_or(0, Vec::len);
        let rows = self.values.len();
        let col = ((x - a) / (b - a) * cols as f64).floor();
        let head = format!("cursor x {} · {}", sig(x, 4), q.symbol());
        if !(0.0..cols as f64).contains(&col) {
            return format!("{head}: the cursor is outside the map");
        }
        let column: Vec<f64> = self.values.iter().map(|row| row[col as usize]).collect();
        let largest = column
            .iter()
            .enumerate()
            .filter(|(_, v)| v.is_finite())
            .max_by(|p, q| p.1.total_cmp(q.1));
        match (column.first().filter(|v| v.is_finite()), largest) {
            (Some(top), Some((r, v))) => format!(
                "{head} under it {} at Γ_C, largest {} at depth {}",
                sig(*top, 3),
                sig(*v, 3),
                sig(self.z_max * (r as f64 + 0.5) / rows as f64, 2)
            ),
            _ => format!("{head}: no value under the cursor"),
        }
    }

    /// The map's rows, with the marker on the cell nearest the peak (and its mirror image).
    fn lines(&self, peak: &Peak, theme: Theme) -> Vec<Line<'static>> {
        let rows = self.values.len();
        let cols = self.values.first().map_or(0, Vec::len);
        let cell = |x: f64, depth: f64| -> Option<(usize, usize)> {
            let c = ((x - self.x.0) / (self.x.1 - self.x.0) * cols as f64).floor();
            let r = (depth / self.z_max * rows as f64).floor();
            (c >= 0.0 && r >= 0.0 && (c as usize) < cols && (r as usize) < rows)
                .then_some((r as usize, c as usize))
        };
        let marks: Vec<(usize, usize)> = [peak.x, -peak.x]
            .iter()
            .filter_map(|&x| cell(x, peak.depth))
            .collect();
        self.values
            .iter()
            .enumerate()
            .map(|(r, row)| {
                Line::from(
                    row.iter()
                        .enumerate()
                        .map(|(c, &v)| {
                            if marks.contains(&(r, c)) {
                                let style = Style::new().add_modifier(Modifier::BOLD | Modifier::REVERSED);
                                return Span::styled(MARKER, style);
                            }
                            let k = level(v, self.range);
                            Span::styled(GLYPHS[k], Style::new().fg(theme.ink(COLOURS[k])))
                        })
                        .collect::<Vec<_>>(),
                )
            })
            .collect()
    }
}

/// The level 0..5 of `v` within `range`.
fn level(v: f64, (lo, hi): (f64, f64)) -> usize {
    if !(v.is_finite() && hi > lo) {
        return 0;
    }
    (((v - lo) / (hi - lo) * GLYPHS.len() as f64) as usize).min(GLYPHS.len() - 1)
}

/// The colour bar: each level's glyph and colour from the highest (top) to the lowest, with
/// the range's top, middle and bottom values.
fn colour_bar((lo, hi): (f64, f64), height: u16, theme: Theme) -> Vec<Line<'static>> {
    if !(lo.is_finite() && hi.is_finite()) {
        return Vec::new();
    }
    let rows = usize::from(height);
    (0..rows)
        .map(|r| {
            let f = 1.0 - (r as f64 + 0.5) / rows as f64;
            let k = level(lo + f * (hi - lo), (lo, hi));
            let label = if r == 0 {
                sig(hi, 4)
            } else if r + 1 == rows {
                sig(lo, 4)
            } else if r == rows / 2 {
                sig((lo + hi) / 2.0, 4)
            } else {
                String::new()
            };
            Line::from(vec![
                Span::styled(
                    format!(" {}{} ", GLYPHS[k], GLYPHS[k]),
                    Style::new().fg(theme.ink(COLOURS[k])),
                ),
                Span::raw(label),
            ])
        })
        .collect()
}

/// "✕ max τ₁ = 109.5 at depth 1.66 (x = 0) · x -6.88…6.88, depth 0…4": the peak and the window.
fn caption_line(peak: &Peak, map: &HeatMap, theme: Theme) -> Line<'static> {
    let what = if peak.quantity == Quantity::SigmaYy {
        "most compressive"
    } else {
        "max"
    };
    // A peak on the axis of symmetry found at round-off off it (x = −2.6e-14 on a full
    // model) reads as the axis.
    let x = if peak.x.abs() <= 1e-9 * (map.x.1 - map.x.0).abs() {
        0.0
    } else {
        peak.x
    };
    Line::from(vec![
        Span::styled(format!(" {MARKER} "), theme.title()),
        Span::raw(format!(
            "{what} {} = {} at depth {} (x = {})",
            peak.quantity.symbol(),
            sig(peak.value, 4),
            sig(peak.depth, 3),
            sig(x, 3)
        )),
        Span::styled(
            format!(
                " · x {}…{}, depth 0…{}",
                sig(map.x.0, 3),
                sig(map.x.1, 3),
                sig(map.z_max, 3)
            ),
            theme.faint(),
        ),
    ])
}
