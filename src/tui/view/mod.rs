//! Drawing the app: `view(&App, &mut Frame)` lays out the header, the scene, the error banner
//! and the status line, and the help overlay on top. One module per scene part.

mod cells;
pub(super) mod convergence;
mod convergence_graded;
mod cursor;
mod deformed;
pub mod fmt;
mod friction;
mod header;
pub mod help;
pub(super) mod infsup_chart;
mod infsup_panel;
mod log;
mod mesh_axes;
mod method;
mod path;
pub mod plot;
mod pressure;
mod status;
mod stress_map;
mod ticks;
pub(in crate::tui) mod yfit;

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::symbols::Marker;
use ratatui::text::Line;
use ratatui::widgets::Paragraph;

use super::app::{App, Drawn, Scene};
use super::protocol::Notice;
use super::theme::Theme;

/// The smallest terminal the layout is made for.
pub const MIN_SIZE: (u16, u16) = (80, 24);

/// How to draw: colours and the marker of charts and canvases.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Look {
    /// The colours (monochrome or not).
    pub theme: Theme,
    /// The glyphs of charts and canvases.
    pub marker: Marker,
}

/// The smallest area the lab is drawn in inside the guided tour: the lab yields the rest of
/// an 80×24 terminal to the step's title and caption, whose words are read before any chart
/// is (every caption of the paper's tour whole at 80×24).
pub const MIN_AREA: (u16, u16) = (80, 17);

/// Draw `app` into the whole frame (at least [`MIN_SIZE`]).
pub fn view(app: &App, frame: &mut Frame, look: &Look) {
    // Nothing to click until this frame draws it.
    app.overlays.drawn.set(Drawn::default());
    let area = frame.area();
    if below_min_size(frame, area, look.theme, app.notice.as_ref()) {
        return;
    }
    view_in(app, frame, area, look);
}

/// The most rows the error banner takes from the scene.
const MAX_BANNER_ROWS: u16 = 5;

/// The banner's rows: ` ✗ ` and the failure wrapped at words to `width` columns, the further
/// rows indented under its first word (at most [`MAX_BANNER_ROWS`], the last ending
/// "… l: log" when it is longer still: the log keeps it whole).
fn banner_rows(error: &str, width: u16) -> Vec<String> {
    const LEAD: &str = " ✗ ";
    let mut rows: Vec<String> = fmt::wrap_words(error, usize::from(width.saturating_sub(3)).max(1))
        .into_iter()
        .enumerate()
        .map(|(i, row)| format!("{}{row}", if i == 0 { LEAD } else { "   " }))
        .collect();
    if rows.len() > usize::from(MAX_BANNER_ROWS) {
        rows.truncate(usize::from(MAX_BANNER_ROWS));
        let last = rows.last_mut().expect("a row");
        let keep = usize::from(width).saturating_sub(10);
        *last = format!(
            "{} … l: log",
            last.chars().take(keep).collect::<String>().trim_end()
        );
    }
    rows
}

/// Draw `app` into `area` of the frame (at least [`MIN_AREA`]; the guided tour puts its
/// caption below).
pub fn view_in(app: &App, frame: &mut Frame, area: Rect, look: &Look) {
    app.overlays.drawn.set(Drawn::default());
    if area.width < MIN_AREA.0 || area.height < MIN_AREA.1 {
        too_small(frame, area, look.theme, "");
        return;
    }
    // The whole message, word-wrapped (at least 2 rows, at most MAX_BANNER_ROWS).
    let message = app
        .error
        .as_ref()
        .map(|error| banner_rows(&error.to_string(), area.width));
    let banner_height = message
        .as_ref()
        .map_or(0, |rows| (rows.len() as u16).clamp(2, MAX_BANNER_ROWS));
    let status_rows = status::rows(app, area.width, look.theme);
    if app.overlays.projector {
        // The scene's main chart on the whole screen, the status (and its keys) below.
        let [body, bottom] =
            Layout::vertical([Constraint::Fill(1), Constraint::Length(status_rows)]).areas(area);
        projector(app, frame, body, look);
        status::render(app, frame, bottom, look.theme);
        overlays(app, frame, body, look);
        return;
    }
    let [top, body, banner, bottom] = Layout::vertical([
        Constraint::Length(2),
        Constraint::Fill(1),
        Constraint::Length(banner_height),
        Constraint::Length(status_rows),
    ])
    .areas(area);
    header::render(app, frame, top, look.theme);
    match app.scene {
        Scene::Explore => explore(app, frame, body, look),
        Scene::InfSup => infsup_chart::render(app, frame, body, look),
        Scene::Mesh => deformed::render(app, frame, body, look, deformed::Extent::Full),
        Scene::Convergence => convergence::render(app, frame, body, look),
        Scene::Stress => stress_map::render(app, frame, body, look),
    }
    if let Some(rows) = message {
        let lines: Vec<Line> = rows.into_iter().map(Line::raw).collect();
        frame.render_widget(Paragraph::new(lines).style(look.theme.banner()), banner);
    }
    status::render(app, frame, bottom, look.theme);
    let [above, _] = Layout::vertical([Constraint::Fill(1), Constraint::Length(status_rows)]).areas(area);
    overlays(app, frame, above, look);
}

/// The help or the message log over `area` (everything above the status area, the header
/// too), scrolled where the user scrolled it.
fn overlays(app: &App, frame: &mut Frame, area: Rect, look: &Look) {
    if app.show_help {
        help::render(frame, area, look.theme, app.overlays.help_scroll, app.scene);
    } else if app.overlays.show_log {
        log::render(app, frame, area, look.theme);
    }
}

/// The projector view (`f`): the scene's main chart alone, with its legend (and in explore
/// the cursor's readout).
fn projector(app: &App, frame: &mut Frame, area: Rect, look: &Look) {
    match app.scene {
        Scene::Explore => pressure::render(app, frame, area, look),
        Scene::InfSup => infsup_chart::render(app, frame, area, look),
        Scene::Mesh => deformed::render(app, frame, area, look, deformed::Extent::Full),
        Scene::Convergence => convergence::render(app, frame, area, look),
        Scene::Stress => stress_map::render(app, frame, area, look),
    }
}

/// The rows a chart's box needs for 8 data rows: its borders, a legend of two rows, the x
/// axis and its labels. At small sizes the panels beside or below a chart give it these rows
/// before it loses any (as btm's basic mode drops its panels).
pub const CHART_NEED: u16 = 14;

/// The least rows of the explore scene's lower panels: the inf-sup panel's borders, header,
/// current row and verdict.
const PANELS_MIN: u16 = 5;

/// The explore scene: pressures on top, the method line, then the inf-sup panel and the
/// contact zone.
fn explore(app: &App, frame: &mut Frame, area: Rect, look: &Look) {
    // The chart takes 57% of the rows, and at least [`CHART_NEED`] while the lower panels keep
    // [`PANELS_MIN`] below the method line. Shorter (the lab at 80×24 with a wrapped message
    // or a banner), the panels drop and the inf-sup panel's numbers take one row. In the
    // tour's shorter area the chart takes the rest above 6 panel rows; shorter still (the
    // tour's caption taking more rows), the method line goes and the panels keep 5 rows.
    let short = area.height < CHART_NEED + 1 + PANELS_MIN;
    let (chart_rows, method_rows) = if !short {
        let share = ((area.height - 1) * 57 + 50) / 100;
        (share.max(CHART_NEED).min(area.height - 1 - PANELS_MIN), 1)
    } else if !app.overlays.in_tour {
        let [chart, method_row, row] = Layout::vertical([
            Constraint::Fill(1),
            Constraint::Length(u16::from(area.height > CHART_NEED + 1)),
            Constraint::Length(1),
        ])
        .areas(area);
        method::render(app, frame, method_row, look.theme);
        pressure::render(app, frame, chart, look);
        infsup_panel::render_row(app, frame, row, look.theme);
        return;
    } else if area.height < 16 {
        (area.height.saturating_sub(5), 0)
    } else {
        (area.height.saturating_sub(7), 1)
    };
    let [chart, method_row, lower] = Layout::vertical([
        Constraint::Length(chart_rows),
        Constraint::Length(method_rows),
        Constraint::Fill(1),
    ])
    .areas(area);
    if method_rows > 0 {
        method::render(app, frame, method_row, look.theme);
    }
    let [panel, contact] = Layout::horizontal([Constraint::Length(42), Constraint::Fill(1)]).areas(lower);
    pressure::render(app, frame, chart, look);
    infsup_panel::render(app, frame, panel, look.theme);
    deformed::render(app, frame, contact, look, deformed::Extent::NearContact);
}

/// Whether `area` is below [`MIN_SIZE`]; if it is, [`too_small`] is drawn there with `notice`
/// (what the last key did) under it.
pub(in crate::tui) fn below_min_size(
    frame: &mut Frame,
    area: Rect,
    theme: Theme,
    notice: Option<&Notice>,
) -> bool {
    let below = area.width < MIN_SIZE.0 || area.height < MIN_SIZE.1;
    if below {
        let said = notice.map(|n| format!("\n{}", n.text)).unwrap_or_default();
        too_small(frame, area, theme, &said);
    }
    below
}

/// The message shown instead of the app in a terminal below [`MIN_SIZE`], wrapped to fit.
/// `said` (a notice: what the last key did) under it.
pub(in crate::tui) fn too_small(frame: &mut Frame, area: Rect, theme: Theme, said: &str) {
    let text = format!(
        "riplab needs a bigger terminal\nthis one is {}×{}; the lab needs at least {}×{}\nenlarge the window or make the font smaller\n(q quits; other keys are ignored){said}",
        area.width, area.height, MIN_SIZE.0, MIN_SIZE.1
    );
    centred_message(frame, area, &text, theme);
}

/// `text` wrapped to `area`'s width and centred in it, its first line as a title.
pub fn centred_message(frame: &mut Frame, area: Rect, text: &str, theme: Theme) {
    let lines: Vec<Line> = fmt::wrap_words(text, usize::from(area.width))
        .into_iter()
        .enumerate()
        .map(|(i, l)| {
            if i == 0 {
                Line::styled(l, theme.title())
            } else {
                Line::raw(l)
            }
        })
        .collect();
    let height = (lines.len() as u16).min(area.height);
    let [middle] = Layout::vertical([Constraint::Length(height)])
        .flex(ratatui::layout::Flex::Center)
        .areas(area);
    frame.render_widget(
        Paragraph::new(lines).alignment(ratatui::layout::Alignment::Center),
        middle,
    );
}
