//! The convergence scene: a work–precision chart (relative error of p̄ against solve time,
//! log-log, one curve per scheme M1–M4 with a marker at each level, and M1's raw p dotted)
//! over a table of the numbers. The study runs on request (see [`App::study_key`]).

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

use crate::study::{Errors, Status, StudyRow};

use super::super::app::{App, Study};
use super::super::theme::Theme;
use super::Look;
use super::fmt::sig;
use super::plot::{Axis, Plot, Scale, Series, Stroke};

/// The schemes in the order of the legend, with their colours and glyphs (as in the
/// inf-sup scene).
const SCHEMES: [(&str, Color, char); 4] = [
    ("M1", Color::Red, '1'),
    ("M2", Color::Yellow, '2'),
    ("M3", Color::Green, '3'),
    ("M4", Color::Blue, '4'),
];
/// The colour of M1's raw pressure (the dotted curve).
const RAW_COLOR: Color = Color::Cyan;
/// The chart keeps at least this many rows; the table gets the rest.
const MIN_CHART_HEIGHT: u16 = 12;

pub fn render(app: &App, frame: &mut Frame, area: Rect, look: &Look) {
    let key = app.study_key();
    match app.studies.get(&key) {
        Some(Ok(study)) => {
            let levels = shown_levels(study, area.height);
            let rows = study.rows.iter().filter(|r| levels.contains(&r.level)).count() as u16;
            let [top, bottom] =
                Layout::vertical([Constraint::Fill(1), Constraint::Length(rows + 3)]).areas(area);
            chart(frame, top, look, study);
            table(frame, bottom, look.theme, study, &levels);
        }
        other => {
            let text = match other {
                Some(Err(e)) => format!("the study failed: {e}"),
                _ if app.study_pending() == Some(&key) => format!(
                    "⟳ computing the reference (q2, level {}), then M1–M4 at levels 0 to {}…",
                    key.reference_level(),
                    key.max_level
                ),
                _ => "the study starts when this scene is shown".into(),
            };
            frame.render_widget(
                Paragraph::new(text).wrap(Wrap { trim: true }).block(
                    Block::bordered()
                        .title(Span::styled(
                            " work–precision: error of p̄ against solve time ",
                            look.theme.title(),
                        ))
                        .border_style(look.theme.axis()),
                ),
                area,
            );
        }
    }
}

/// The levels the table has room for: all, or the finest that fit (at least one).
fn shown_levels(study: &Study, height: u16) -> Vec<u32> {
    let max = study.key.max_level;
    let per_level = study.rows.iter().filter(|r| r.level == max).count().max(1);
    let room = height.saturating_sub(MIN_CHART_HEIGHT + 3) as usize / per_level;
    let n = (room.max(1) as u32).min(max + 1);
    (max + 1 - n..=max).collect()
}

/// (log10 ms, log10 error) of `rows`, skipping what a log axis cannot show.
fn points(rows: &[&StudyRow], error: fn(&Errors) -> f64) -> Vec<(f64, f64)> {
    rows.iter()
        .filter(|r| r.status == Status::Ok)
        .filter_map(|r| Some((r.solve_ms?, error(r.errors.as_ref()?))))
        .filter(|&(t, e)| t > 0.0 && e > 0.0 && t.is_finite() && e.is_finite())
        .map(|(t, e)| (t.log10(), e.log10()))
        .collect()
}

/// Bounds on half decades around `values`, at least a decade wide.
fn bounds(values: impl Iterator<Item = f64>) -> [f64; 2] {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if !lo.is_finite() {
        return [-1.0, 1.0];
    }
    let (lo, hi) = ((lo * 2.0).floor() / 2.0, (hi * 2.0).ceil() / 2.0);
    if hi - lo < 1.0 {
        [lo - 0.5, hi + 0.5]
    } else {
        [lo, hi]
    }
}

fn chart(frame: &mut Frame, area: Rect, look: &Look, study: &Study) {
    let of = |name: &str| -> Vec<&StudyRow> { study.rows.iter().filter(|r| r.scheme == name).collect() };
    let pbar: fn(&Errors) -> f64 = |e| e.pbar;
    let raw: fn(&Errors) -> f64 = |e| e.p;
    let curves: Vec<Vec<(f64, f64)>> = SCHEMES.iter().map(|(name, ..)| points(&of(name), pbar)).collect();
    let m1_raw = points(&of("M1"), raw);
    let all = || curves.iter().flatten().chain(&m1_raw);
    let xb = bounds(all().map(|p| p.0));
    let yb = bounds(all().map(|p| p.1));
    let mut series = vec![Series {
        name: "M1 p (raw)".into(),
        color: RAW_COLOR,
        stroke: Stroke::Dotted,
        glyph: Some('r'),
        data: &m1_raw,
    }];
    for ((name, color, glyph), pts) in SCHEMES.iter().zip(&curves) {
        series.push(Series {
            name: format!("{name} p̄"),
            color: *color,
            stroke: Stroke::Solid,
            glyph: Some(*glyph),
            data: pts,
        });
    }
    Plot {
        title: format!(
            " work–precision: relative error of p̄ against solve time (log-log){} ",
            study
                .rows
                .first()
                .map_or(String::new(), |r| format!(" · the scenario's ε={:e}", r.epsilon))
        ),
        x: Axis {
            title: "solve ms".into(),
            bounds: xb,
            scale: Scale::Log10,
        },
        y: Axis {
            title: "error".into(),
            bounds: yb,
            scale: Scale::Log10,
        },
        series,
        marker: look.marker,
        theme: look.theme,
    }
    .render(frame, area);
}

fn table(frame: &mut Frame, area: Rect, theme: Theme, study: &Study, levels: &[u32]) {
    let head = format!(
        " {:<6} {:>2} {:>7} {:>8} {:>9} {:>9} {:>9}",
        "scheme", "L", "dofs", "ms", "err p", "err p̄", "err u"
    );
    let mut lines = vec![Line::styled(head, theme.title())];
    for r in study.rows.iter().filter(|r| levels.contains(&r.level)) {
        let color = SCHEMES
            .iter()
            .find(|(name, ..)| *name == r.scheme)
            .map_or(Color::Reset, |(_, c, _)| *c);
        let numbers = match (&r.errors, r.solve_ms, r.status) {
            (Some(e), Some(ms), Status::Ok) => format!(
                " {:>2} {:>7} {:>8} {:>9} {:>9} {:>9}",
                r.level,
                r.n_dofs,
                sig(ms, 3),
                sig(e.p, 3),
                sig(e.pbar, 3),
                sig(e.u, 3),
            ),
            (_, _, status) => format!(" {:>2} {:>7}  {}", r.level, r.n_dofs, status.word()),
        };
        lines.push(Line::from(vec![
            Span::styled(format!(" {:<6}", r.scheme), Style::new().fg(theme.ink(color))),
            Span::raw(numbers),
        ]));
    }
    let max = study.key.max_level;
    let shown = match levels {
        [first, ..] if *first == max && max > 0 => format!(" · rows: level {max} (chart: 0 to {max})"),
        [first, ..] if *first > 0 => format!(" · rows: levels {first} to {max} (chart: 0 to {max})"),
        _ => String::new(),
    };
    let title = format!(
        " relative errors against q2+simpson level {}{shown} ",
        study.key.reference_level()
    );
    frame.render_widget(
        Paragraph::new(lines).block(
            Block::bordered()
                .title(Span::styled(title, theme.title()))
                .border_style(theme.axis()),
        ),
        area,
    );
}
