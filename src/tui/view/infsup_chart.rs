//! The inf-sup scene: β_h/√h against h for the paper's schemes M1–M4 (and the smoothed
//! β̄_h/√h of M1) on log-log axes, and the numbers in a table below. Levels are estimated as
//! the user visits them (`a`: every level up to the current one).

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

use crate::contact::Rule;
use crate::mesh::Element;
use crate::scheme::Scheme;

use super::super::app::{App, InfSupKey, MAX_APP_LEVEL};
use super::super::beta::InfSup;
use super::super::lab_error::LabError;
use super::super::theme::Theme;
use super::Look;
use super::fmt::{sig, table_row};
use super::infsup_panel::{estimates, hidden_rows, slope, trend, visible};
use super::plot::{self, Axis, Plot, Scale, Stroke};

/// One curve: a scheme and which pressure (raw β or smoothed β̄).
struct Series {
    label: &'static str,
    element: Element,
    rule: Rule,
    pick: fn(&InfSup) -> f64,
    color: Color,
    /// The glyph at each level (the scheme's digit): apart without colour.
    glyph: char,
}

fn series() -> Vec<Series> {
    let raw: fn(&InfSup) -> f64 = |b| b.beta_over_sqrt_h;
    let smooth: fn(&InfSup) -> f64 = |b| b.beta_bar_over_sqrt_h;
    let mut out = Vec::new();
    let looks = [
        (Color::Red, '1'),
        (Color::Yellow, '2'),
        (Color::Green, '3'),
        (Color::Blue, '4'),
    ];
    for (scheme, (color, glyph)) in Scheme::PAPER.into_iter().zip(looks) {
        let Scheme { element, rule } = scheme;
        let label = scheme.name().unwrap_or_default();
        out.push(Series {
            label,
            element,
            rule,
            pick: raw,
            color,
            glyph,
        });
    }
    let Scheme { element, rule } = Scheme::PAPER[0];
    out.push(Series {
        label: "M1 p̄",
        element,
        rule,
        pick: smooth,
        color: Color::Cyan,
        glyph: '*',
    });
    out
}

pub fn render(app: &App, frame: &mut Frame, area: Rect, look: &Look) {
    let all = series();
    let levels: Vec<u32> = (0..=MAX_APP_LEVEL)
        .filter(|&level| {
            all.iter().any(|s| {
                let k = InfSupKey {
                    level,
                    element: s.element,
                    rule: s.rule,
                };
                app.infsup.contains_key(&k) || app.is_estimating(&k)
            })
        })
        .collect();
    // The projector view is the chart alone; else the table takes up to half the height, and
    // in the lab no more than leaves the chart [`super::CHART_NEED`] rows less its legend's
    // (which stands beside the title of a short chart): short of its full height the table
    // drops its borders and title, then its explanation line. (The tour's step keeps the
    // half: its caption quotes the table's numbers.)
    let half = (levels.len() as u16 + 5).min(area.height / 2);
    let table_height = if app.overlays.projector {
        0
    } else if app.overlays.in_tour {
        half
    } else {
        half.min(area.height.saturating_sub(super::CHART_NEED - 2))
    };
    let [top, bottom] = Layout::vertical([Constraint::Fill(1), Constraint::Length(table_height)]).areas(area);
    chart(app, frame, top, look, &all, &levels);
    if table_height > 0 {
        table(app, frame, bottom, look.theme, &all, &levels);
    }
}

/// The chart over the levels estimated: h from the coarsest to the finest of them (a level
/// alone gets a tenth of a decade either side), β/√h over the decades the values span
/// (yfit's doc).
fn chart(app: &App, frame: &mut Frame, area: Rect, look: &Look, all: &[Series], levels: &[u32]) {
    let h_of = |level: u32| app.scenario.h(level).log10();
    let xb = match (levels.first(), levels.last()) {
        (Some(&coarse), Some(&fine)) if fine > coarse => [h_of(fine), h_of(coarse)],
        (Some(&level), _) => [h_of(level) - 0.1, h_of(level) + 0.1],
        _ => [h_of(MAX_APP_LEVEL), h_of(0)],
    };
    let data: Vec<Vec<(f64, f64)>> = all
        .iter()
        .map(|s| {
            estimates(app, s.element, s.rule)
                .into_iter()
                .map(|(_, b)| (b.h.log10(), (s.pick)(b)))
                .filter(|&(_, v)| v > 0.0 && v.is_finite())
                .map(|(x, v)| (x, v.log10()))
                .collect()
        })
        .collect();
    let yb = super::yfit::span(&data);
    let series = all
        .iter()
        .zip(&data)
        .map(|(s, pts)| plot::Series {
            // A kernel's β_h = 0 has no place on a log axis: the legend says so.
            name: if pts.is_empty() && !estimates(app, s.element, s.rule).is_empty() {
                format!("{} β=0, kernel", s.label)
            } else {
                s.label.into()
            },
            color: s.color,
            stroke: Stroke::Solid,
            glyph: Some(s.glyph),
            data: pts,
        })
        .collect();
    beta_plot(" β_h/√h against h ".into(), [xb, yb], series, look).render(frame, area);
}

/// The chart both inf-sup views draw (one body's and two bodies'): `series` of β_h/√h
/// against h on log-log axes over `bounds` (x, then y; log10 values), titled `title`.
pub(in crate::tui) fn beta_plot<'a>(
    title: String,
    [xb, yb]: [[f64; 2]; 2],
    series: Vec<plot::Series<'a>>,
    look: &Look,
) -> Plot<'a> {
    Plot {
        overlays: Vec::new(),
        title,
        x: Axis {
            title: "h".into(),
            bounds: xb,
            scale: Scale::Log10,
        },
        y: Axis {
            title: "β_h/√h".into(),
            bounds: yb,
            scale: Scale::Log10,
        },
        series,
        marker: look.marker,
        theme: look.theme,
    }
}

/// The chart's curves in values (h, β/√h) for the tour's handout ([`crate::plot::LogCurve`]):
/// each scheme's raw β_h/√h and M1's β̄_h/√h, a kernel named so (its β_h = 0 has no place
/// on a log axis).
pub fn svg_curves(app: &App) -> Vec<crate::plot::LogCurve> {
    series()
        .iter()
        .map(|s| {
            let points: Vec<(f64, f64)> = estimates(app, s.element, s.rule)
                .into_iter()
                .map(|(_, b)| (b.h, (s.pick)(b)))
                .collect();
            let kernel = !points.is_empty() && points.iter().all(|p| p.1 <= 0.0);
            crate::plot::LogCurve {
                name: if kernel {
                    format!("{}: β = 0, kernel", s.label)
                } else {
                    s.label.to_string()
                },
                points,
            }
        })
        .collect()
}

fn table(app: &App, frame: &mut Frame, area: Rect, theme: Theme, all: &[Series], levels: &[u32]) {
    let mut head = format!(" {:>2} {:>7}", "L", "h");
    for s in all {
        head.push_str(&format!(" {:>8}", s.label));
    }
    let mut lines = vec![Line::styled(head, theme.title())];
    let mut first_error: Option<&LabError> = None;
    // With room for every level: borders and a title; else the rows alone.
    let bordered = usize::from(area.height) >= levels.len() + 5;
    let rows = area.height.saturating_sub(if bordered { 5 } else { 2 }) as usize;
    let shown = visible(levels, app.settings.level, rows);
    for &level in shown {
        let mark = if level == app.settings.level { '▸' } else { ' ' };
        let h = sig(app.scenario.h(level), 4);
        let mut cells = vec![(h, 7)];
        for s in all {
            let k = InfSupKey {
                level,
                element: s.element,
                rule: s.rule,
            };
            let cell = match app.infsup.get(&k) {
                Some(Ok(b)) if b.kernel.is_some() => "kernel".to_string(),
                Some(Ok(b)) => sig((s.pick)(b), 3),
                Some(Err(e)) => {
                    first_error.get_or_insert(e);
                    "error".to_string()
                }
                None if app.is_estimating(&k) => "⟳".to_string(),
                None => "·".to_string(),
            };
            cells.push((cell, 8));
        }
        let cells: Vec<(&str, usize)> = cells.iter().map(|(t, w)| (t.as_str(), *w)).collect();
        let row = table_row(&format!("{mark}{level:>2}"), &cells);
        let style = if level == app.settings.level {
            theme.selected()
        } else {
            Style::new()
        };
        lines.push(Line::styled(row, style));
    }
    let mut marks = vec![Span::raw(format!("{:>11}", "trend slope"))];
    for s in all {
        let (text, style) = match trend(app, s.element, s.rule, s.pick) {
            Some(true) => ("✓", theme.good()),
            Some(false) => ("✗", theme.bad()),
            None => ("?", Style::new()),
        };
        let slope = slope(app, s.element, s.rule, s.pick).map_or(String::new(), |v| format!(" {v:+.2}"));
        marks.push(Span::raw(" ".repeat(8 - slope.chars().count())));
        marks.push(Span::styled(text, style));
        marks.push(Span::raw(slope));
    }
    lines.push(Line::from(marks));
    lines.push(Line::styled(
        match first_error {
            Some(e) => format!("error: {e}"),
            None => "✓ bounded ✗ decaying or kernel · slope of log β/√h per log h, finest two".into(),
        },
        theme.faint(),
    ));
    let title = bordered.then(|| format!(" β_h/√h (raw) and β̄_h/√h (M1 p̄){} ", hidden_rows(levels, shown)));
    table_block(frame, area, lines, title, theme);
}

/// The table of an inf-sup view (one body's or two bodies'): `lines` in `area`, in a block
/// with `title` when there is one (else bare, where rows are short).
pub(in crate::tui) fn table_block(
    frame: &mut Frame,
    area: Rect,
    lines: Vec<Line<'_>>,
    title: Option<String>,
    theme: Theme,
) {
    let paragraph = Paragraph::new(lines);
    let Some(title) = title else {
        frame.render_widget(paragraph, area);
        return;
    };
    let block = Block::bordered()
        .title(Span::styled(title, theme.title()))
        .border_style(theme.axis());
    frame.render_widget(paragraph.block(block), area);
}
