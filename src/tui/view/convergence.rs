//! The convergence scene: a work–precision chart (relative error of p̄ against solve time,
//! log-log, a marker at each level) over a table of the numbers. It compares either the
//! schemes M1–M4 with the lab's method (M1's raw p dotted) or the contact methods on the
//! lab's scheme (`w` toggles, [`Compare`]); a method that has no answer on the scheme (`exact`
//! on a rule with a kernel) says so in the legend and the table. With the lab's edge grading
//! on (`E`), each scheme or method also has its graded series, its points marked by a letter
//! (no line: the legend keeps to two rows at 80 columns), and the table pairs each uniform row with its graded one
//! ([`super::convergence_graded`]). The study runs on request (see [`App::study_key`]).

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

use crate::study::{Errors, Status, StudyRow};

use super::super::app::{App, Compare, Study};
use super::super::engine::studying::TIMED_RUNS;
use super::super::theme::Theme;
use super::Look;
use super::convergence_graded::{GRADED_METHOD_GLYPHS, GRADED_SCHEME_GLYPHS, paired_table};
use super::fmt::sig;
use super::plot::{Axis, Plot, Scale, Series, Stroke};

/// A curve's name, colour and glyph.
type Legend = (&'static str, Color, char);

/// The schemes in the order of the legend, with their colours and glyphs (as in the
/// inf-sup scene).
const SCHEMES: [Legend; 4] = [
    ("M1", Color::Red, '1'),
    ("M2", Color::Yellow, '2'),
    ("M3", Color::Green, '3'),
    ("M4", Color::Blue, '4'),
];
/// The methods in the order of the legend ([`super::super::app::compared_methods`]), with
/// their colours and glyphs.
const METHODS: [Legend; 4] = [
    ("penalty", Color::Red, 'P'),
    ("alm", Color::Green, 'A'),
    ("nitsche", Color::Magenta, 'N'),
    ("exact", Color::Blue, 'E'),
];
/// The colour of M1's raw pressure (the dotted curve).
const RAW_COLOR: Color = Color::Cyan;
/// The chart keeps at least this many rows (8 data rows); the table gets the rest, without
/// its borders and title when they do not fit (the status line names the reference).
const MIN_CHART_HEIGHT: u16 = super::CHART_NEED;

pub fn render(app: &App, frame: &mut Frame, area: Rect, look: &Look) {
    let key = app.study_key();
    // While the study runs, the levels it has finished (the status line says which comes).
    let partial = app
        .study_partial
        .as_ref()
        .filter(|s| s.key == key && app.study_pending() == Some(&key));
    match (app.studies.get(&key), partial) {
        (Some(Ok(study)), _) | (None, Some(study)) => {
            let levels = shown_levels(study, area.height);
            let rows = table_lines(study, &levels) as u16;
            let graded = study.key.refine_edges.grades();
            let bordered = graded || area.height >= MIN_CHART_HEIGHT + rows + 3;
            let height = if bordered { rows + 3 } else { rows + 1 };
            let [top, bottom] =
                Layout::vertical([Constraint::Fill(1), Constraint::Length(height)]).areas(area);
            chart(frame, top, look, app, study);
            if graded {
                let curves = curves(study);
                let color_of = |name: &str| curves.iter().find(|c| c.name == name).map(|c| c.color);
                let title = table_title(study, &levels);
                paired_table(frame, bottom, look.theme, study, (&levels, title), &color_of);
            } else {
                table(frame, bottom, look.theme, study, &levels, bordered);
            }
        }
        (other, _) => {
            let text = match other {
                Some(Err(e)) => format!("the study failed: {e}"),
                _ if app.study_pending() == Some(&key) => format!(
                    "⟳ computing the reference (q2, level {}), then {} at levels 0 to {}…",
                    key.reference_level(),
                    key.label(),
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

/// The finest level of the study's rows (the key's, when every level gave rows).
fn finest(study: &Study) -> u32 {
    study
        .rows
        .iter()
        .map(|r| r.level)
        .max()
        .unwrap_or(study.key.max_level)
}

/// The lines of the table at `levels`: one per uniform row (a graded row shares its uniform
/// row's line).
fn table_lines(study: &Study, levels: &[u32]) -> usize {
    study
        .rows
        .iter()
        .filter(|r| levels.contains(&r.level) && !r.grading.grades())
        .count()
}

/// The levels the table has room for: all, or the finest that fit (at least one).
fn shown_levels(study: &Study, height: u16) -> Vec<u32> {
    let max = finest(study);
    let per_level = table_lines(study, &[max]).max(1);
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

/// The range of `values` (log10), widened by `pad` either side, `least` wide at least (around
/// its middle; [-1, 1] without values): the axes span the data (the y axis's rows are fitted
/// to it, [`super::yfit`]).
fn bounds(values: impl Iterator<Item = f64>, pad: f64, least: f64) -> [f64; 2] {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if !lo.is_finite() {
        return [-1.0, 1.0];
    }
    if hi - lo + 2.0 * pad < least {
        let mid = (lo + hi) / 2.0;
        return [mid - least / 2.0, mid + least / 2.0];
    }
    [lo - pad, hi + pad]
}

/// The ε of the study's penalty and ALM rows, said as whose it is: the scenario's (the paper's
/// when the scenario's is 0, [`App::defaults`]) for M1–M4, the lab's for the methods.
pub fn study_epsilon(app: &App) -> String {
    let key = app.study_key();
    let whose = match key.compare {
        Compare::Methods => "the lab's",
        Compare::Schemes if app.scenario.epsilon > 0.0 => "the scenario's",
        Compare::Schemes => "the paper's",
    };
    format!("{whose} ε={:e}", key.epsilon)
}

/// What names a row's curve: its scheme or its method.
type NameOf = fn(&StudyRow) -> &str;

/// One curve of the chart: the rows of a scheme (M1–M4) or of a method, uniform or graded
/// (`M1+2e`), its colour, line and glyph.
struct Curve<'a> {
    name: String,
    color: Color,
    stroke: Stroke,
    glyph: char,
    rows: Vec<&'a StudyRow>,
}

/// The curves of `study`: one per scheme or one per method, as the key compares, each
/// followed by its graded series when the study grades.
fn curves(study: &Study) -> Vec<Curve<'_>> {
    let (table, graded_glyphs, of): (&[Legend], &[char; 4], NameOf) = match study.key.compare {
        Compare::Schemes => (&SCHEMES, &GRADED_SCHEME_GLYPHS, |r| r.scheme.as_str()),
        Compare::Methods => (&METHODS, &GRADED_METHOD_GLYPHS, |r| r.method.method),
    };
    let suffix = study.key.graded_suffix();
    let rows_of = |name: &str, graded: bool| -> Vec<&StudyRow> {
        study
            .rows
            .iter()
            .filter(|r| of(r) == name && r.grading.grades() == graded)
            .collect()
    };
    let mut out = Vec::new();
    for (&(name, color, glyph), &graded_glyph) in table.iter().zip(graded_glyphs) {
        out.push(Curve {
            name: name.into(),
            color,
            stroke: Stroke::Solid,
            glyph,
            rows: rows_of(name, false),
        });
        if let Some(suffix) = &suffix {
            out.push(Curve {
                name: format!("{name}{suffix}"),
                color,
                stroke: Stroke::None,
                glyph: graded_glyph,
                rows: rows_of(name, true),
            });
        }
    }
    out.retain(|c| !c.rows.is_empty());
    out
}

/// The legend's name of `curve`: `M1 p̄`, `M1+2e p̄`, or why it has no point (`exact:
/// kernel`; nothing for a graded curve: its uniform one or the table says why, and the legend
/// keeps to its two rows).
fn legend(curve: &Curve) -> String {
    if curve.rows.iter().any(|r| r.status == Status::Ok) {
        return format!("{} p̄", curve.name);
    }
    if curve.stroke == Stroke::None {
        return String::new();
    }
    let word = curve.rows.first().map_or("no rows", |r| r.status.word());
    format!("{}: {word}", curve.name)
}

fn chart(frame: &mut Frame, area: Rect, look: &Look, app: &App, study: &Study) {
    let pbar: fn(&Errors) -> f64 = |e| e.pbar;
    let raw: fn(&Errors) -> f64 = |e| e.p;
    let curves = curves(study);
    let points_of: Vec<Vec<(f64, f64)>> = curves.iter().map(|c| points(&c.rows, pbar)).collect();
    // M1's raw p, dotted, beside the schemes.
    let m1_raw = curves
        .iter()
        .find(|c| study.key.compare == Compare::Schemes && c.name == "M1")
        .map(|c| points(&c.rows, raw));
    let all = || points_of.iter().flatten().chain(m1_raw.iter().flatten());
    // x: a decade at least, for its labels; y: the data's own range.
    let xb = bounds(all().map(|p| p.0), 0.05, 1.0);
    let yb = bounds(all().map(|p| p.1), 0.0, 0.0);
    let mut series = Vec::new();
    if let Some(data) = &m1_raw {
        series.push(Series {
            name: "M1 p (raw)".into(),
            color: RAW_COLOR,
            stroke: Stroke::Dotted,
            glyph: Some('r'),
            data,
        });
    }
    for (curve, pts) in curves.iter().zip(&points_of) {
        series.push(Series {
            name: legend(curve),
            color: curve.color,
            stroke: curve.stroke,
            glyph: Some(curve.glyph),
            data: pts,
        });
    }
    Plot {
        overlays: Vec::new(),
        title: format!(
            " work–precision of {}: relative error of p̄ against solve time (log-log) · {} ",
            study.key.label(),
            study_epsilon(app)
        ),
        x: Axis {
            title: format!("solve ms (median of {TIMED_RUNS})"),
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

/// The work–precision chart's curves in values (solve ms, relative error of p̄; M1's raw p
/// beside the schemes) for the tour's handout ([`crate::plot::LogCurve`]); None until the
/// study of the lab's settings is done.
pub fn svg_curves(app: &App) -> Option<Vec<crate::plot::LogCurve>> {
    let Some(Ok(study)) = app.studies.get(&app.study_key()) else {
        return None;
    };
    let values = |pts: Vec<(f64, f64)>| {
        pts.into_iter()
            .map(|(x, y)| (10f64.powf(x), 10f64.powf(y)))
            .collect()
    };
    let curves = curves(study);
    let mut out: Vec<crate::plot::LogCurve> = curves
        .iter()
        .map(|c| crate::plot::LogCurve {
            name: legend(c),
            points: values(points(&c.rows, |e| e.pbar)),
        })
        .collect();
    if let Some(m1) = curves
        .iter()
        .find(|c| study.key.compare == Compare::Schemes && c.name == "M1")
    {
        out.push(crate::plot::LogCurve {
            name: "M1 p (raw)".into(),
            points: values(points(&m1.rows, |e| e.p)),
        });
    }
    Some(out)
}

fn table(frame: &mut Frame, area: Rect, theme: Theme, study: &Study, levels: &[u32], bordered: bool) {
    let methods = study.key.compare == Compare::Methods;
    // The methods' rows add their Newton steps and the ALM's multiplier updates.
    let head = if methods {
        format!(
            " {:<8} {:>2} {:>7} {:>8} {:>3} {:>3} {:>9} {:>9} {:>9}",
            "method", "L", "dofs", "ms", "it", "upd", "err p", "err p̄", "err u"
        )
    } else {
        format!(
            " {:<6} {:>2} {:>7} {:>8} {:>9} {:>9} {:>9}",
            "scheme", "L", "dofs", "ms", "err p", "err p̄", "err u"
        )
    };
    let mut lines = vec![Line::styled(head, theme.title())];
    let curves = curves(study);
    for r in study.rows.iter().filter(|r| levels.contains(&r.level)) {
        let name = if methods {
            r.method.method
        } else {
            r.scheme.as_str()
        };
        let color = curves
            .iter()
            .find(|c| c.name == name)
            .map_or(Color::Reset, |c| c.color);
        let count = |n: Option<usize>| n.map_or("–".to_string(), |n| n.to_string());
        let iterations = if methods {
            format!(
                " {:>3} {:>3}",
                count(r.newton_iterations),
                count(r.outer_iterations)
            )
        } else {
            String::new()
        };
        let numbers = match (&r.errors, r.solve_ms, r.status) {
            (Some(e), Some(ms), Status::Ok) => format!(
                " {:>2} {:>7} {:>8}{iterations} {:>9} {:>9} {:>9}",
                r.level,
                r.n_dofs,
                sig(ms, 3),
                sig(e.p, 3),
                sig(e.pbar, 3),
                sig(e.u, 3),
            ),
            // Why there is no answer, when the table has room to say it.
            (_, _, status) => match (&r.reason, methods) {
                (Some(reason), true) => {
                    format!(" {:>2} {:>7}  {}: {reason}", r.level, r.n_dofs, status.word())
                }
                _ => format!(" {:>2} {:>7}  {}", r.level, r.n_dofs, status.word()),
            },
        };
        let width = if methods { 8 } else { 6 };
        lines.push(Line::from(vec![
            Span::styled(format!(" {name:<width$}"), Style::new().fg(theme.ink(color))),
            Span::raw(numbers),
        ]));
    }
    let title = table_title(study, levels);
    if !bordered {
        frame.render_widget(Paragraph::new(lines), area);
        return;
    }
    frame.render_widget(
        Paragraph::new(lines).block(
            Block::bordered()
                .title(Span::styled(title, theme.title()))
                .border_style(theme.axis()),
        ),
        area,
    );
}

/// The table's title: the reference, and which levels its rows show when not all.
fn table_title(study: &Study, levels: &[u32]) -> String {
    let max = finest(study);
    let shown = match levels {
        [first, ..] if *first == max && max > 0 => format!(" · rows: level {max} (chart: 0 to {max})"),
        [first, ..] if *first > 0 => format!(" · rows: levels {first} to {max} (chart: 0 to {max})"),
        _ => String::new(),
    };
    format!(
        " relative errors against q2+simpson level {}{shown} ",
        study.key.reference_level()
    )
}
