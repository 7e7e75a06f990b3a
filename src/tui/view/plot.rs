//! A chart that places every tick label at the value it names. ratatui's `Chart` spreads
//! axis labels evenly whatever they say; here the ticks are chosen on a 1-2-5 grid (linear
//! axes) or at decades and their 2 and 5 (log10 axes, data given as log10 values), and each
//! label is drawn at the column (row) where the canvas draws a point of that value. The
//! legend has a row of its own above the graph (never over data) and shows each series with
//! the symbol it is drawn with: a solid or dotted line and an optional glyph at every point,
//! so that the series stay apart in monochrome.

use std::collections::HashMap;

use ratatui::Frame;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::Block;
use ratatui::widgets::canvas::{Canvas, Line as Segment, Painter, Shape};

use super::super::theme::Theme;
pub use super::cells::{cell_of, dots_per_cell};
use super::fmt::title_fit;
use super::path::on_path;
pub use super::ticks::{Scale, linear_ticks, log_ticks, tick_label};
use super::yfit;

/// The graph rows each overlay drawn takes ([`Plot::overlays`]).
pub const OVERLAY_ROWS: u16 = 4;

/// The graph rows under which the legend moves to the title's row (when it fits there).
const ROOMY: u16 = 20;

/// One axis: its title (with units), bounds (in data units) and scale.
#[derive(Clone, Debug)]
pub struct Axis {
    /// The title, with units.
    pub title: String,
    /// Lower and upper bound, in data units (log10 of the values on a [`Scale::Log10`] axis).
    pub bounds: [f64; 2],
    /// How the axis maps values.
    pub scale: Scale,
}

/// How a series joins its points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stroke {
    /// A solid line between the points.
    Solid,
    /// The line in every other cell along its path (the chart's marker).
    Dotted,
    /// Points only (their glyph).
    None,
}

/// One series.
#[derive(Clone, Debug)]
pub struct Series<'a> {
    /// The name in the legend.
    pub name: String,
    /// The colour of its line and glyphs.
    pub color: Color,
    /// How it joins its points.
    pub stroke: Stroke,
    /// A character drawn at every point, over the lines.
    pub glyph: Option<char>,
    /// The points (x, y), in data units.
    pub data: &'a [(f64, f64)],
}

/// A chart: a bordered block titled `title`, the legend row, the graph with its axes.
pub struct Plot<'a> {
    /// The block's title.
    pub title: String,
    /// The horizontal axis.
    pub x: Axis,
    /// The vertical axis.
    pub y: Axis,
    /// The overlays (guides such as Hertz's parabola), drawn under every line and glyph of
    /// `series`: a mark of theirs never covers another's cell, it moves up to three cells along
    /// its row to a free one, else the cell keeps what it shows. The chart draws one for each
    /// [`OVERLAY_ROWS`] rows of its graph, in this order, as many as its legend's two rows
    /// name, and its legend names the others.
    pub overlays: Vec<Series<'a>>,
    /// The series, in the legend's order (after the overlays).
    pub series: Vec<Series<'a>>,
    /// The glyphs of the canvas.
    pub marker: Marker,
    /// The colours (monochrome or not).
    pub theme: Theme,
}

/// The legend's sample of a series: its line drawn with the chart's marker and its glyph.
fn sample(stroke: Stroke, glyph: Option<char>, marker: Marker) -> String {
    let cell = match marker {
        Marker::Braille => "⠒",
        Marker::HalfBlock => "▀",
        _ => "•",
    };
    let line = match stroke {
        Stroke::Solid => cell.repeat(3),
        Stroke::Dotted => format!("{cell} {cell}"),
        Stroke::None => String::new(),
    };
    match glyph {
        Some(g) if stroke == Stroke::None => g.to_string(),
        Some(g) if stroke == Stroke::Dotted => format!("{cell} {g} {cell}"),
        Some(g) => format!("{cell}{g}{cell}"),
        None => line,
    }
}

/// A polyline drawn in every other cell along its path: a dotted line whose dots are the
/// marker's cells, as the legend shows it.
struct DottedLine<'a> {
    data: &'a [(f64, f64)],
    color: Color,
    /// Dots per cell (columns, rows).
    per: (u16, u16),
}

impl Shape for DottedLine<'_> {
    fn draw(&self, painter: &mut Painter) {
        let (px, py) = (usize::from(self.per.0), usize::from(self.per.1));
        let mut cells = 0usize;
        let mut last: Option<(usize, usize)> = None;
        let mut dot = |painter: &mut Painter, x: usize, y: usize| {
            let cell = (x / px, y / py);
            if last.is_some_and(|l| l != cell) {
                cells += 1;
            }
            last = Some(cell);
            if cells.is_multiple_of(2) {
                painter.paint(x, y, self.color);
            }
        };
        for w in self.data.windows(2) {
            let (Some(a), Some(b)) = (
                painter.get_point(w[0].0, w[0].1),
                painter.get_point(w[1].0, w[1].1),
            ) else {
                continue;
            };
            let (dx, dy) = (b.0 as i64 - a.0 as i64, b.1 as i64 - a.1 as i64);
            let n = dx.abs().max(dy.abs()).max(1);
            for i in 0..n {
                let x = a.0 as i64 + dx * i / n;
                let y = a.1 as i64 + dy * i / n;
                dot(painter, x as usize, y as usize);
            }
        }
        if let Some(&(x, y)) = self.data.last()
            && let Some(p) = painter.get_point(x, y)
        {
            dot(painter, p.0, p.1);
        }
    }
}

/// Where a plot put its graph, for tests and overlays.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Placed {
    /// The cells of the data.
    pub graph: Rect,
}

impl Plot<'_> {
    /// Draw into `area`; returns where the graph went (None when there was no room).
    pub fn render(&self, frame: &mut Frame, area: Rect) -> Option<Placed> {
        // The overlays the graph's rows hold: its box less the borders, the x axis with its
        // labels and a legend of two rows; fewer while the legend would not hold their names.
        let rows = area.height.saturating_sub(6);
        let mut keep = usize::from(rows / OVERLAY_ROWS).min(self.overlays.len());
        let fits = |keep| {
            let lines = self.legend_lines(area.width.saturating_sub(2), keep, &[]);
            lines
                .iter()
                .all(|l| l.width() <= usize::from(area.width.saturating_sub(2)))
        };
        while keep > 0 && !fits(keep) {
            keep -= 1;
        }
        let theme = self.theme;
        let block = Block::bordered()
            .title(Span::styled(
                title_fit(&self.title, area.width.saturating_sub(2)),
                theme.title(),
            ))
            .border_style(theme.axis());
        let inner = block.inner(area);
        frame.render_widget(block, area);
        if inner.height < 4 || inner.width < 20 {
            return None;
        }
        // The legend on rows of its own; on the title's row when the graph would have fewer
        // than [`ROOMY`] rows and the legend fits there beside the title.
        let mut legend = self.legend_lines(inner.width, keep, &[]);
        let title_width = Line::raw(title_fit(&self.title, area.width.saturating_sub(2))).width() as u16;
        let one_row = self.legend_lines(u16::MAX, keep, &[]);
        let beside = inner.width.saturating_sub(title_width);
        let short = inner.height.saturating_sub(legend.len() as u16 + 2) < ROOMY;
        let on_title = short && one_row.len() == 1 && one_row[0].width() <= usize::from(beside);
        if on_title {
            let at = area.x + 1 + title_width;
            frame.buffer_mut().set_line(at, area.y, &one_row[0], beside);
            legend.clear();
        }
        let legend_rows = legend.len() as u16;
        // Legend rows, then the graph, then the x axis line and its labels.
        if inner.height < legend_rows + 4 {
            return None;
        }
        let graph_rows = inner.height - legend_rows - 2;
        let per = dots_per_cell(self.marker);
        let max_y_ticks = usize::from(graph_rows / 2 + 1).min(6);
        // The y axis fitted to the data and the rows, each row at its value (yfit's doc).
        let (y_bounds, y_values) = yfit::fit_or(
            self.y.bounds,
            self.ticks(&self.y, max_y_ticks),
            self.y.scale == Scale::Log10,
            graph_rows,
            per.1,
            max_y_ticks,
        );
        let y_ticks: Vec<(f64, String)> = y_values
            .into_iter()
            .map(|v| (v, tick_label(v, self.y.scale)))
            .collect();
        let margin = y_ticks.iter().map(|(_, l)| l.chars().count()).max().unwrap_or(1) as u16;
        let graph = Rect {
            x: inner.x + margin + 1,
            y: inner.y + legend_rows,
            width: inner.width - margin - 1,
            height: graph_rows,
        };
        let buf = frame.buffer_mut();
        for (i, line) in legend.iter().enumerate() {
            buf.set_line(inner.x, inner.y + i as u16, line, inner.width);
        }
        // The y axis: a line with a tick at each label.
        let axis_style = theme.axis();
        let axis_x = graph.x - 1;
        for row in graph.y..graph.bottom() {
            buf[(axis_x, row)].set_symbol("│").set_style(axis_style);
        }
        let mut last_row = None;
        for (v, label) in &y_ticks {
            let Some(off) = cell_of(*v, y_bounds, graph.height, per.1) else {
                continue;
            };
            let row = graph.bottom() - 1 - off;
            if last_row == Some(row) {
                continue;
            }
            last_row = Some(row);
            buf[(axis_x, row)].set_symbol("┤");
            let w = label.chars().count() as u16;
            buf.set_string(inner.x + margin - w, row, label, axis_style);
        }
        // The x axis line and its labels, centred on their columns, none overlapping.
        let axis_row = graph.bottom();
        let label_row = axis_row + 1;
        buf[(axis_x, axis_row)].set_symbol("└").set_style(axis_style);
        for col in graph.x..graph.right() {
            buf[(col, axis_row)].set_symbol("─").set_style(axis_style);
        }
        let max_x_ticks = usize::from(graph.width / 7).max(2);
        let mut free_from = inner.x;
        for v in self.ticks(&self.x, max_x_ticks) {
            let Some(off) = cell_of(v, self.x.bounds, graph.width, per.0) else {
                continue;
            };
            let col = graph.x + off;
            let label = tick_label(v, self.x.scale);
            let w = label.chars().count() as u16;
            let start = col
                .saturating_sub((w - 1) / 2)
                .max(inner.x)
                .min(inner.right() - w);
            buf[(col, axis_row)].set_symbol("┬");
            if start < free_from {
                continue;
            }
            buf.set_string(start, label_row, &label, axis_style);
            free_from = start + w + 1;
        }
        let covered = self.draw_data(frame, graph, y_bounds, keep);
        if !covered.is_empty() {
            // The legend again, saying which overlays the data cover, where it still fits.
            let buf = frame.buffer_mut();
            if on_title {
                let line = self.legend_lines(u16::MAX, keep, &covered);
                if line.len() == 1 && line[0].width() <= usize::from(beside) {
                    let at = area.x + 1 + title_width;
                    buf.set_string(at, area.y, " ".repeat(usize::from(beside)), Style::new());
                    buf.set_line(at, area.y, &line[0], beside);
                }
            } else {
                let lines = self.legend_lines(inner.width, keep, &covered);
                if lines.len() == legend.len() {
                    for (i, line) in lines.iter().enumerate() {
                        let row = inner.y + i as u16;
                        buf.set_string(inner.x, row, " ".repeat(usize::from(inner.width)), Style::new());
                        buf.set_line(inner.x, row, line, inner.width);
                    }
                }
            }
        }
        #[cfg(test)]
        drawn::record(self, keep, graph, y_bounds);
        Some(Placed { graph })
    }

    fn ticks(&self, axis: &Axis, max: usize) -> Vec<f64> {
        match axis.scale {
            Scale::Linear => linear_ticks(axis.bounds, max),
            Scale::Log10 => log_ticks(axis.bounds, max),
        }
    }

    /// The first `keep` overlays, then the series: what the chart draws, bottom layer first.
    fn drawn(&self, keep: usize) -> impl Iterator<Item = &Series<'_>> {
        self.overlays[..keep].iter().chain(&self.series)
    }

    /// The axes' titles ("y against x"), each series' sample and name (the first `keep`
    /// overlays', then the series'; an overlay in `covered` said to be covered), then the
    /// overlays left out for lack of rows, wrapped to `width` (two rows at most; one at
    /// `u16::MAX`).
    fn legend_lines(&self, width: u16, keep: usize, covered: &[usize]) -> Vec<Line<'static>> {
        let width = usize::from(width);
        // The axes' titles, unless the chart's title says them.
        let axes = format!("{} against {}", self.y.title, self.x.title);
        let mut entries: Vec<Vec<Span<'static>>> = Vec::new();
        if !self.title.contains(&axes) {
            entries.push(vec![Span::styled(
                format!("{axes} "),
                self.theme.axis().add_modifier(Modifier::BOLD),
            )]);
        }
        let hidden: Vec<String> = self.overlays[keep..]
            .iter()
            .map(|s| {
                let word = s.name.split_whitespace().next().unwrap_or_default();
                s.glyph
                    .map_or_else(|| word.to_string(), |g| format!("{g} {word}"))
            })
            .collect();
        for (i, s) in self.drawn(keep).enumerate() {
            if s.name.is_empty() {
                continue;
            }
            let style = Style::new().fg(self.theme.ink(s.color));
            // A series equal to an earlier one says so: its glyphs stand beside that one's, a
            // line names the one it lies on (its name's first word).
            let same = self.coincides_with(s, keep).map_or_else(String::new, |earlier| {
                let label = earlier.glyph.map_or_else(
                    || {
                        earlier
                            .name
                            .split_whitespace()
                            .next()
                            .unwrap_or_default()
                            .to_string()
                    },
                    String::from,
                );
                format!(" (= {label})")
            });
            // An overlay whose every mark the data hide: the data lie on it to within a row.
            let same = if i < keep && covered.contains(&i) {
                format!("{same} (covered)")
            } else {
                same
            };
            entries.push(vec![
                Span::styled(format!(" {}", sample(s.stroke, s.glyph, self.marker)), style),
                Span::raw(format!(" {}{same} ", s.name)),
            ]);
        }
        // Last: naming what is left out never pushes a drawn series' entry off the legend.
        if !hidden.is_empty() {
            entries.push(vec![Span::styled(
                format!(" no room: {} ", hidden.join(", ")),
                self.theme.faint(),
            )]);
        }
        let mut lines: Vec<Vec<Span<'static>>> = vec![Vec::new()];
        let mut used = 0usize;
        for entry in entries {
            let w: usize = entry.iter().map(|s| s.width()).sum();
            if used > 0 && used + w > width && lines.len() < 2 {
                lines.push(Vec::new());
                used = 0;
            }
            used += w;
            lines.last_mut().expect("one line at least").extend(entry);
        }
        lines.into_iter().map(Line::from).collect()
    }

    /// The earlier series that `s` repeats, if any: for a series of glyphs, an earlier one
    /// with the same points (the same x and, to a millionth of the y axis's span, the same y);
    /// for a line, an earlier line drawn along the same path (each one's points on the other's
    /// polyline to that tolerance), as M3's raw p, linear between the vertices, lies on p̄.
    fn coincides_with(&self, s: &Series, keep: usize) -> Option<&Series<'_>> {
        let span = |b: [f64; 2]| (b[1] - b[0]).abs();
        let (tx, ty) = (1e-9 * span(self.x.bounds), 1e-6 * span(self.y.bounds));
        let same_points = |a: &Series, b: &Series| {
            !a.data.is_empty()
                && a.data.len() == b.data.len()
                && a.data
                    .iter()
                    .zip(b.data)
                    .all(|(p, q)| (p.0 - q.0).abs() <= tx && (p.1 - q.1).abs() <= ty)
        };
        let same_path = |a: &Series, b: &Series| {
            a.data.len() > 1
                && b.data.len() > 1
                && on_path(a.data, b.data, tx, ty)
                && on_path(b.data, a.data, tx, ty)
        };
        let earlier = self.drawn(keep).take_while(|e| !std::ptr::eq(*e, s));
        match s.glyph {
            Some(_) => earlier.filter(|e| e.glyph.is_some()).find(|e| same_points(e, s)),
            None if s.stroke != Stroke::None => earlier
                .filter(|e| e.glyph.is_none() && e.stroke != Stroke::None)
                .find(|e| same_path(e, s)),
            None => None,
        }
    }

    /// The series on a canvas over `graph` (y over `y_bounds`), lines first, then the glyphs
    /// over them, then the first `keep` overlays' glyphs in the cells left free. Returns the
    /// overlays (their indices) with a point on the graph and no mark drawn: every cell of
    /// theirs held by the data.
    fn draw_data(&self, frame: &mut Frame, graph: Rect, y_bounds: [f64; 2], keep: usize) -> Vec<usize> {
        let theme = self.theme;
        let canvas = Canvas::default()
            .marker(self.marker)
            .x_bounds(self.x.bounds)
            .y_bounds(y_bounds)
            .paint(|ctx| {
                for s in self.drawn(keep) {
                    let color = theme.ink(s.color);
                    match s.stroke {
                        Stroke::Solid => {
                            for w in s.data.windows(2) {
                                ctx.draw(&Segment::new(w[0].0, w[0].1, w[1].0, w[1].1, color));
                            }
                            if let [(x, y)] = s.data {
                                ctx.draw(&Segment::new(*x, *y, *x, *y, color));
                            }
                        }
                        Stroke::Dotted => ctx.draw(&DottedLine {
                            data: s.data,
                            color,
                            per: dots_per_cell(self.marker),
                        }),
                        Stroke::None => {}
                    }
                    // In colour, one layer per series: a cell has one colour, the last drawn
                    // wins. In monochrome the dots of every series merge in one layer, so that
                    // no line loses dots where it meets another.
                    if theme.color {
                        ctx.layer();
                    }
                }
            });
        frame.render_widget(canvas, graph);
        let per = dots_per_cell(self.marker);
        let buf: &mut Buffer = frame.buffer_mut();
        // Which series' glyph holds a cell: a glyph that lands on another series' moves to the
        // next free cell of its row (right, else left, up to three cells away), so that no series
        // hides another. An overlay's glyph takes only a cell that nothing else holds (no line's
        // dots, no other glyph): where none is free it stays under them.
        let mut taken: HashMap<(u16, u16), usize> = HashMap::new();
        let n = self.series.len();
        // Per overlay: whether a point of it lies on the graph, and whether a mark was drawn.
        let mut shown = vec![(false, false); keep];
        let layers = self.series.iter().enumerate().map(|(i, s)| (i, s, false));
        let under = self.overlays[..keep]
            .iter()
            .enumerate()
            .map(|(i, s)| (n + i, s, true));
        for (i, s, beneath) in layers.chain(under) {
            let Some(g) = s.glyph else { continue };
            let style = Style::new().fg(theme.ink(s.color)).add_modifier(Modifier::BOLD);
            for &(x, y) in s.data {
                let (Some(cx), Some(cy)) = (
                    cell_of(x, self.x.bounds, graph.width, per.0),
                    cell_of(y, y_bounds, graph.height, per.1),
                ) else {
                    continue;
                };
                let row = graph.bottom() - 1 - cy;
                if beneath {
                    shown[i - n].0 = true;
                }
                let free = |c: u16| match taken.get(&(c, cy)) {
                    Some(&o) => o == i,
                    None => !beneath || matches!(buf[(graph.x + c, row)].symbol(), " " | "\u{2800}"),
                };
                let near = [0, 1, -1, 2, -2, 3, -3]
                    .into_iter()
                    .filter_map(|d: i32| u16::try_from(i32::from(cx) + d).ok().filter(|&c| c < graph.width))
                    .find(|&c| free(c));
                let cx = match near {
                    Some(c) => c,
                    None if beneath => continue,
                    None => cx,
                };
                taken.insert((cx, cy), i);
                buf[(graph.x + cx, row)].set_char(g).set_style(style);
                if beneath {
                    shown[i - n].1 = true;
                }
            }
        }
        (0..keep).filter(|&k| shown[k] == (true, false)).collect()
    }
}

/// What each chart drew, for the tests that read a frame: the values of its glyphs, to find
/// each one in the frame by the chart's own tick labels.
#[cfg(test)]
pub mod drawn {
    use std::cell::RefCell;

    use ratatui::layout::Rect;

    use super::{Plot, Scale};

    /// One chart: its title, its x bounds, its scales and each glyph series' glyph and points
    /// (values, not log10 values).
    #[derive(Clone, Debug)]
    pub struct Charted {
        /// The chart's title.
        pub title: String,
        /// The x axis's bounds, in values.
        pub x_bounds: [f64; 2],
        /// Whether x and y are on log axes.
        pub log: (bool, bool),
        /// Each glyph series' glyph and points.
        pub series: Vec<(char, Vec<(f64, f64)>)>,
        /// Each overlay drawn (under the series): its glyph and points.
        pub overlays: Vec<(char, Vec<(f64, f64)>)>,
        /// The overlays left out for lack of rows (the legend names them).
        pub hidden: usize,
        /// The graph's cells.
        pub graph: Rect,
        /// The y axis's bounds as fitted to the rows, in values.
        pub y_bounds: [f64; 2],
    }

    thread_local! {
        static CHARTS: RefCell<Vec<Charted>> = const { RefCell::new(Vec::new()) };
    }

    /// Note `plot` as drawn.
    pub(super) fn record(plot: &Plot, keep: usize, graph: Rect, y_bounds: [f64; 2]) {
        let (lx, ly) = (plot.x.scale == Scale::Log10, plot.y.scale == Scale::Log10);
        let value = |v: f64, log: bool| if log { 10f64.powf(v) } else { v };
        let glyphs = |series: &[super::Series]| -> Vec<(char, Vec<(f64, f64)>)> {
            series
                .iter()
                .filter_map(|s| {
                    let points = s.data.iter().map(|&(x, y)| (value(x, lx), value(y, ly)));
                    Some((s.glyph?, points.collect()))
                })
                .collect()
        };
        let charted = Charted {
            title: plot.title.trim().to_string(),
            x_bounds: plot.x.bounds.map(|v| value(v, lx)),
            log: (lx, ly),
            series: glyphs(&plot.series),
            overlays: glyphs(&plot.overlays[..keep]),
            hidden: plot.overlays.len() - keep,
            graph,
            y_bounds: y_bounds.map(|v| value(v, ly)),
        };
        CHARTS.with(|c| c.borrow_mut().push(charted));
    }

    /// The charts drawn on this thread since the last call.
    pub fn take() -> Vec<Charted> {
        CHARTS.with(|c| std::mem::take(&mut *c.borrow_mut()))
    }
}
