//! The two-body scene's inf-sup view (Tab; docs/lab.md, "Two bodies"; docs/design.md §12,
//! "The inf-sup constant across the interface"): β_h/√h against h on log-log axes for each
//! multiplier space of the current rule — mortar `M`, mortar-dual `D`, node-to-segment `N`,
//! the rule's points `R` and their p̄ `P`, each with its glyph so that they read apart in
//! monochrome — at the levels estimated so far ([`super::infsup`]), and a table below: each
//! level's h and β_h per space, and the slope of β_h ∝ h^slope between the finest two. A space
//! whose multipliers are not unique shows its kernel (`kernel` in the table, `β=0, kernel` in
//! the legend), never a 0 on the log axis; a level that was not estimated (too large for the
//! memory) says why under the table.

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph};

use super::super::theme::Theme;
use super::super::view::Look;
use super::super::view::fmt::{sig, table_row};
use super::super::view::infsup_chart::{beta_plot, table_block};
use super::super::view::plot::{Series, Stroke};
use super::BodiesApp;
use super::infsup::{EstimateKey, LevelEstimate, shown_levels};
use crate::contact::interface::solve::BodiesError;
use crate::error::SolveError;
use crate::infsup::interface::Space;
use crate::infsup::interface_table::InterfaceRow;
use crate::infsup::log_slope;

/// The fewest rows the chart keeps above the table.
const CHART_LEAST: u16 = 10;

/// The width of a space's column in the table.
const COLUMN: usize = 11;

/// The significant digits of β_h in the table.
const DIGITS: usize = 4;

/// A space's glyph, colour and column head.
fn look_of(space: Space) -> (char, Color, String) {
    match space {
        Space::Mortar => ('M', Color::Red, "mortar".into()),
        Space::MortarDual => ('D', Color::Yellow, "dual".into()),
        Space::Nts => ('N', Color::Green, "nts".into()),
        Space::Point(rule) => ('R', Color::Blue, rule.name().into()),
        Space::Smoothed(_) => ('P', Color::Cyan, "p̄".into()),
    }
}

/// The glyph of `space` on the chart (and in the table's head).
pub fn glyph(space: Space) -> char {
    look_of(space).0
}

/// The estimates of the view's key at each level it shows, ascending.
fn estimates(app: &BodiesApp, key: EstimateKey) -> Vec<(u32, Option<&LevelEstimate>)> {
    shown_levels(app.settings.level)
        .map(|level| (level, app.infsup.get(key, level)))
        .collect()
}

/// The rows estimated, by ascending level.
fn estimated<'a>(all: &[(u32, Option<&'a LevelEstimate>)]) -> Vec<(u32, &'a [InterfaceRow])> {
    all.iter()
        .filter_map(|&(level, e)| match e {
            Some(Ok(rows)) => Some((level, rows.as_slice())),
            _ => None,
        })
        .collect()
}

/// β_h of space `i` at its finest two levels estimated: its observed slope
/// ([`log_slope`]); None with fewer than two, or a kernel among them.
pub fn slope(rows: &[(u32, &[InterfaceRow])], i: usize) -> Option<f64> {
    match rows {
        [.., (_, a), (_, b)] if a[i].kernel.is_none() && b[i].kernel.is_none() => {
            log_slope((a[i].h, a[i].beta), (b[i].h, b[i].beta))
        }
        _ => None,
    }
}

/// `ratio 2:3 · offset 0 · rule gauss1`.
fn key_text(key: EstimateKey) -> String {
    format!(
        "ratio {}:{} · offset {} · rule {}",
        key.ratio.0,
        key.ratio.1,
        sig(key.offset, 2),
        key.rule.name()
    )
}

/// ` riplab · patch-two-blocks · inf-sup at ratio 2:3 · offset 0 · rule gauss1 · q1 L0–3`.
pub fn header_text(app: &BodiesApp) -> String {
    format!(
        " riplab · {} · inf-sup at {} · {} L0–{}",
        crate::text::sanitize(&app.scenario.name),
        key_text(app.estimate_key()),
        app.scenario.element.name(),
        shown_levels(app.settings.level).end()
    )
}

/// The state of the estimate: the level under way, or the levels done, of which ratio,
/// offset and rule (and why that rule), and the levels not estimated.
pub fn state_text(app: &BodiesApp) -> String {
    let key = app.estimate_key();
    let why = match app.settings.method {
        crate::contact::interface::InterfaceMethod::Rip(_) => format!("{}'s", app.settings.method.name()),
        _ => "contact.rule".into(),
    };
    let all = estimates(app, key);
    let done = all.iter().filter(|e| e.1.is_some()).count();
    let mut text = match app.infsup.waiting(key).first() {
        Some(level) => format!(
            "estimating level {level} ({done} of {} done) · {} ({why})…",
            all.len(),
            key_text(key)
        ),
        None => format!(
            "β_h at {} ({why}) · levels 0–{}",
            key_text(key),
            shown_levels(app.settings.level).end()
        ),
    };
    let failed: Vec<u32> = all
        .iter()
        .filter(|e| matches!(e.1, Some(Err(_))))
        .map(|e| e.0)
        .collect();
    if let (Some(first), Some(last)) = (failed.first(), failed.last()) {
        let levels = if first == last {
            format!("level {first}")
        } else {
            format!("levels {first}–{last}")
        };
        text.push_str(&format!(" · {levels} not estimated (below)"));
    }
    text
}

/// The state line's style: busy while estimating, bad where a level was not estimated.
pub fn state_style(app: &BodiesApp, theme: Theme) -> Style {
    let key = app.estimate_key();
    if app.infsup.busy() {
        theme.busy()
    } else if estimates(app, key).iter().any(|e| matches!(e.1, Some(Err(_)))) {
        theme.bad()
    } else {
        Style::new()
    }
}

/// The chart above, the table below (without its borders when the area is short).
pub fn render(app: &BodiesApp, frame: &mut Frame, area: Rect, look: &Look) {
    let key = app.estimate_key();
    let all = estimates(app, key);
    let n = all.len() as u16;
    let bordered = area.height >= 2 * (n + 5);
    let want = if bordered { n + 5 } else { n + 3 };
    let height = want.min(area.height.saturating_sub(CHART_LEAST));
    let [top, bottom] = Layout::vertical([Constraint::Fill(1), Constraint::Length(height)]).areas(area);
    chart(app, frame, top, look, key, &all);
    table(app, frame, bottom, look.theme, key, &all, bordered);
}

/// β_h/√h against h, each space a series with its glyph; a space whose every level has a
/// kernel named so in the legend, with no point.
fn chart(
    app: &BodiesApp,
    frame: &mut Frame,
    area: Rect,
    look: &Look,
    key: EstimateKey,
    all: &[(u32, Option<&LevelEstimate>)],
) {
    let title = format!(" β_h/√h against h · {} ", key_text(key));
    let rows = estimated(all);
    if rows.is_empty() {
        let block = Block::bordered()
            .title(Span::styled(title, look.theme.title()))
            .border_style(look.theme.axis());
        let waiting = app.infsup.waiting(key).first().copied().unwrap_or(0);
        frame.render_widget(
            Paragraph::new(format!(" ⟳ estimating level {waiting}…")).block(block),
            area,
        );
        return;
    }
    let spaces = key.spaces();
    let data: Vec<Vec<(f64, f64)>> = (0..spaces.len())
        .map(|i| {
            rows.iter()
                .map(|(_, r)| &r[i])
                .filter(|r| r.kernel.is_none() && r.beta_over_sqrt_h > 0.0)
                .map(|r| (r.h.log10(), r.beta_over_sqrt_h.log10()))
                .collect()
        })
        .collect();
    let hs: Vec<f64> = rows.iter().map(|(_, r)| r[0].h.log10()).collect();
    let (h_lo, h_hi) = hs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &h| {
        (a.min(h), b.max(h))
    });
    let xb = if h_hi > h_lo {
        [h_lo, h_hi]
    } else {
        [h_lo - 0.1, h_hi + 0.1]
    };
    let yb = super::super::view::yfit::span(&data);
    let series = spaces
        .iter()
        .zip(&data)
        .enumerate()
        .map(|(i, (&space, points))| {
            let color = look_of(space).1;
            let kernels: Vec<String> = rows
                .iter()
                .filter(|(_, r)| r[i].kernel.is_some())
                .map(|(level, _)| level.to_string())
                .collect();
            let name = if points.is_empty() && !kernels.is_empty() {
                format!("{} β=0, kernel", space.name())
            } else if !kernels.is_empty() {
                format!("{} (kernel L{})", space.name(), kernels.join(","))
            } else {
                space.name().to_string()
            };
            Series {
                name,
                color,
                stroke: Stroke::Solid,
                glyph: Some(glyph(space)),
                data: points,
            }
        })
        .collect();
    beta_plot(title, [xb, yb], series, look).render(frame, area);
}

/// The table: a row per level shown (h, the slave's widest edge on the interface, and β_h of
/// each space), the slope row, and a line saying what was not estimated, the first kernel, or
/// what the numbers are.
fn table(
    app: &BodiesApp,
    frame: &mut Frame,
    area: Rect,
    theme: Theme,
    key: EstimateKey,
    all: &[(u32, Option<&LevelEstimate>)],
    bordered: bool,
) {
    let spaces = key.spaces();
    let mut head = format!(" {:>2} {:>8}", "L", "h");
    for &space in &spaces {
        let (glyph, _, word) = look_of(space);
        head.push_str(&format!(" {:>COLUMN$}", format!("{glyph} {word}")));
    }
    let mut lines = vec![Line::styled(head, theme.title())];
    let levels: Vec<u32> = all.iter().map(|e| e.0).collect();
    let room = usize::from(area.height.saturating_sub(if bordered { 5 } else { 3 }));
    let shown = visible(&levels, app.settings.level, room);
    let waiting = app.infsup.waiting(key);
    let mut failure: Option<(u32, &BodiesError)> = None;
    for &(level, estimate) in all.iter().filter(|e| shown.contains(&e.0)) {
        let mark = if level == app.settings.level { '▸' } else { ' ' };
        let lead = format!("{mark}{level:>2}");
        let text = match estimate {
            Some(Ok(rows)) => {
                let h = sig(rows[0].h, 4);
                let cells: Vec<String> = rows
                    .iter()
                    .map(|r| match r.kernel {
                        Some(_) => "kernel".to_string(),
                        None => sig(r.beta, DIGITS),
                    })
                    .collect();
                let mut all_cells = vec![(h.as_str(), 8)];
                all_cells.extend(cells.iter().map(|c| (c.as_str(), COLUMN)));
                table_row(&lead, &all_cells)
            }
            Some(Err(e)) => {
                failure.get_or_insert((level, e));
                let why = match e {
                    BodiesError::Solve(SolveError::TooLarge { .. }) => "too large for the memory",
                    _ => "failed",
                };
                format!("{lead}   not estimated: {why} (below)")
            }
            None if waiting.first() == Some(&level) => format!("{lead}   ⟳ estimating…"),
            None => format!("{lead}   ·"),
        };
        let style = if level == app.settings.level {
            theme.selected()
        } else {
            Style::new()
        };
        lines.push(Line::styled(text, style));
    }
    let rows = estimated(all);
    let mut slopes = format!("{:>12}", "slope");
    for i in 0..spaces.len() {
        let text = slope(&rows, i).map_or("—".to_string(), |v| format!("{v:.2}"));
        slopes.push_str(&format!(" {text:>COLUMN$}"));
    }
    lines.push(Line::raw(slopes));
    let kernel = rows.iter().find_map(|(level, r)| {
        r.iter().find_map(|row| {
            row.kernel
                .as_ref()
                .map(|k| format!("{} L{level}: {k}", row.space))
        })
    });
    let foot = match (failure, kernel) {
        (Some((level, e)), _) => format!("level {level}: {e}"),
        (None, Some(k)) => format!("kernel {k}"),
        (None, None) => "h: the slave's widest edge · slope: β_h ∝ h^slope, the finest two levels".into(),
    };
    lines.push(Line::styled(format!(" {foot}"), theme.faint()));
    let title = bordered.then(|| format!(" β_h per multiplier space{} ", hidden(&levels, shown)));
    table_block(frame, area, lines, title, theme);
}

/// The levels of `levels` (ascending from 0) that fit in `rows`: all, else the `rows` finest up
/// to the current one (and the one after it).
fn visible(levels: &[u32], current: u32, rows: usize) -> &[u32] {
    let rows = rows.max(1);
    if levels.len() <= rows {
        return levels;
    }
    let at = levels
        .iter()
        .position(|&l| l == current)
        .unwrap_or(levels.len() - 1);
    let end = (at + 2).min(levels.len()).max(rows);
    &levels[end - rows..end]
}

/// ` · L2–5 of 8` when `shown` is not all of `levels`.
fn hidden(levels: &[u32], shown: &[u32]) -> String {
    match (shown.first(), shown.last()) {
        (Some(a), Some(b)) if shown.len() < levels.len() => format!(" · L{a}–{b} of {}", levels.len()),
        _ => String::new(),
    }
}
