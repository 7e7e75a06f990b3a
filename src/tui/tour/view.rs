//! Drawing the tour: the lab (or, on a two-body step, the lab's two-body scene) on top, the
//! step's caption in a panel below, the tour's help on top of both; and [`render_step`], one
//! step as plain text (for tests and documents).

use ratatui::Frame;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;

use super::super::app::App;
use super::super::bodies::cache::BodiesCache;
use super::super::engine::Engine;
use super::super::keys;
use super::super::settle::carry_out;
use super::super::theme::Theme;
use super::super::view::fmt::wrap_words;
use super::super::view::help::key_popup;
use super::super::view::{Look, view_in};
use super::super::view::{MIN_AREA as LAB_MIN, centred_message};
use super::super::{check_size, render_frame};
use super::caption::{MIN_TOUR_SIZE, caption_rows};
use super::errors::StepError;
use super::{Tour, TourApp};

/// Draw the tour into the whole frame.
pub fn view(tour: &TourApp, frame: &mut Frame, look: &Look) {
    let area = frame.area();
    let Some(step) = tour.tour.steps.get(tour.index()) else {
        return;
    };
    if area.width < MIN_TOUR_SIZE.0 || area.height < MIN_TOUR_SIZE.1 {
        too_small(frame, area, tour, look.theme);
        return;
    }
    // The title's and the caption's rows: all of them while the lab keeps its minimum (the
    // lab's charts yield their rows first), else what is left, the caption scrolling.
    let text = caption_rows(&step.caption, area.width - 2);
    let room = usize::from(area.height - LAB_MIN.1);
    let title_beside = |more| {
        let keys = key_spans(tour, look.theme, more);
        title_rows(tour, area.width, Line::from(keys).width() as u16)
    };
    let mut title = title_beside(None);
    if title.len() + text.len() > room {
        // The caption scrolls: the title wraps beside the keys with `↑↓ more`.
        title = title_beside(Some("↑↓"));
    }
    let rows = (title.len() + text.len()).min(room).max(title.len() + 1) as u16;
    let [lab, panel] = Layout::vertical([Constraint::Fill(1), Constraint::Length(rows)]).areas(area);
    match &tour.bodies {
        Some(bodies) => super::super::bodies::view::view_in(bodies, frame, lab, look, false),
        None => view_in(&tour.app, frame, lab, look),
    }
    caption_panel(tour, frame, panel, look.theme, &title, &text);
    if tour.show_help {
        help(frame, area, look.theme);
    }
}

/// The keys of the caption panel's first row: `↑↓ more` when the caption scrolls (`more`),
/// the auto-advance's state, `Space next` (or `end`) and `? keys`.
fn key_spans(tour: &TourApp, theme: Theme, more: Option<&str>) -> Vec<Span<'static>> {
    let mut keys: Vec<Span> = Vec::new();
    if let Some(arrows) = more {
        keys.push(Span::styled(format!(" {arrows}"), theme.key()));
        keys.push(Span::raw(" more "));
    }
    if let Some(auto) = tour.auto {
        let what = if tour.at_end() {
            "auto: done".to_string()
        } else {
            format!("auto {} s", auto.as_secs_f64())
        };
        keys.push(Span::styled(format!(" {what} "), theme.busy()));
    }
    if tour.at_end() {
        keys.push(Span::raw(" end "));
    } else {
        keys.push(Span::styled(" Space", theme.key()));
        keys.push(Span::raw(" next "));
    }
    keys.push(Span::styled(" ?", theme.key()));
    keys.push(Span::raw(" keys "));
    keys
}

/// The caption panel's head: ` tour 3/15 ` (with ` (changed)` once the user changed the
/// step's settings) and the step's title wrapped at words, never cut, beside keys
/// `keys_width` columns wide.
struct TitleRows {
    head: String,
    rows: Vec<String>,
}

impl TitleRows {
    fn len(&self) -> usize {
        self.rows.len().max(1)
    }
}

fn title_rows(tour: &TourApp, width: u16, keys_width: u16) -> TitleRows {
    let (i, n) = (tour.index(), tour.tour.steps.len());
    let changed = if tour.is_pristine() { "" } else { " (changed)" };
    let head = format!(" tour {}/{n}{changed} ", i + 1);
    let title = tour.tour.steps.get(i).map_or("", |s| s.title.as_str());
    let room = usize::from(width.saturating_sub(keys_width + 2)).saturating_sub(head.chars().count());
    TitleRows {
        head,
        rows: wrap_words(title, room.max(8)),
    }
}

/// The step's number and title (wrapped, `title` from [`title_rows`]), the keys, then the
/// caption (↑ ↓ scroll it when it is longer than the rows it has).
fn caption_panel(
    tour: &TourApp,
    frame: &mut Frame,
    area: Rect,
    theme: Theme,
    title: &TitleRows,
    text: &[String],
) {
    let head_rows = title.len().min(usize::from(area.height));
    let rows = usize::from(area.height).saturating_sub(head_rows);
    let scroll = usize::from(tour.caption_scroll).min(text.len().saturating_sub(rows));
    let more = match (scroll > 0, scroll + rows < text.len()) {
        (true, true) => Some("↑↓"),
        (true, false) => Some("↑"),
        (false, true) => Some("↓"),
        (false, false) => None,
    };
    let keys = key_spans(tour, theme, more);
    let keys_width = Line::from(keys.clone()).width() as u16;
    let [top, body] =
        Layout::vertical([Constraint::Length(head_rows as u16), Constraint::Fill(1)]).areas(area);
    let [left, right] = Layout::horizontal([Constraint::Fill(1), Constraint::Length(keys_width)]).areas(top);
    let indent = " ".repeat(title.head.chars().count());
    let lines: Vec<Line> = (0..head_rows)
        .map(|k| {
            let row = title.rows.get(k).map_or("", String::as_str);
            let lead = if k == 0 {
                Span::styled(title.head.clone(), theme.selected())
            } else {
                Span::raw(indent.clone())
            };
            Line::from(vec![lead, Span::styled(format!(" {row}"), theme.title())])
        })
        .collect();
    frame.render_widget(Paragraph::new(lines), left);
    frame.render_widget(Paragraph::new(Line::from(keys)), right);
    let lines: Vec<Line> = text
        .iter()
        .skip(scroll)
        .take(rows)
        .map(|l| Line::raw(format!(" {l}")))
        .collect();
    frame.render_widget(Paragraph::new(lines), body);
}

/// The tour's keys over the middle of `area`.
/// The tour's help: its own keys ([`keys::TOUR`]), then the lab's keys that work inside a
/// step, wrapped to the popup.
fn help(frame: &mut Frame, area: Rect, theme: Theme) {
    const WIDTH: u16 = 74;
    const KEY_WIDTH: usize = 17;
    let mut lines: Vec<(String, String)> = keys::help_lines(keys::TOUR)
        .into_iter()
        .map(|(k, w)| (k.to_string(), w.to_string()))
        .collect();
    let room = usize::from(WIDTH) - 3 - KEY_WIDTH;
    let mut row = String::new();
    let mut rows = Vec::new();
    for group in keys::lab_keys_in_tour() {
        if !row.is_empty() && row.chars().count() + 2 + group.chars().count() > room {
            rows.push(std::mem::take(&mut row));
        }
        if !row.is_empty() {
            row.push_str("  ");
        }
        row.push_str(&group);
    }
    rows.push(row);
    rows.push("work inside a step (? outside the tour explains them);".into());
    rows.push("leaving a step and coming back restores its settings.".into());
    for (i, r) in rows.into_iter().enumerate() {
        lines.push((
            if i == 0 {
                "the lab's keys".into()
            } else {
                String::new()
            },
            r,
        ));
    }
    let lines: Vec<(&str, &str)> = lines.iter().map(|(k, w)| (k.as_str(), w.as_str())).collect();
    key_popup(frame, area, theme, " tour keys ", &lines, (WIDTH, KEY_WIDTH));
}

/// The message shown instead of the tour in a terminal too small for it, wrapped to fit.
fn too_small(frame: &mut Frame, area: Rect, tour: &TourApp, theme: Theme) {
    let paused = if tour.auto.is_some() {
        "\nauto-advance paused until it fits"
    } else {
        ""
    };
    let text = format!(
        "the tour needs a bigger terminal\nthis one is {}×{}; the tour needs at least {}×{}{paused}\nenlarge the window or make the font smaller (q quits)",
        area.width, area.height, MIN_TOUR_SIZE.0, MIN_TOUR_SIZE.1
    );
    centred_message(frame, area, &text, theme);
}

/// Step `index` of `tour` on a `width`×`height` test terminal as plain text, its lab (or its
/// two-body scene) solved synchronously (timings left out so that the text is deterministic).
#[cfg(test)]
pub fn render_step(tour: &Tour, index: usize, width: u16, height: u16) -> Result<String, StepError> {
    render_step_at(tour, index, &[(width, height)]).map(|mut frames| frames.remove(0))
}

/// [`render_step`] at each of `sizes`: the step solved once and drawn at each size.
#[cfg(test)]
pub fn render_step_at(tour: &Tour, index: usize, sizes: &[(u16, u16)]) -> Result<Vec<String>, StepError> {
    for &(width, height) in sizes {
        check_size(width, height)?;
    }
    let player = settled_step(tour, index, &mut Engine::new(tour.scenario_of(index).clone()))?;
    Ok(sizes
        .iter()
        .map(|&(width, height)| step_text(&player, width, height))
        .collect())
}

/// [`render_step`] computed with `engine` (on the step's scenario, so that steps share its
/// work; a two-body step's scene is solved here on its own bodies): the text and the step's lab as drawn
/// (a two-body step's waits unsolved).
pub(crate) fn step_frame(
    tour: &Tour,
    index: usize,
    width: u16,
    height: u16,
    engine: &mut Engine,
) -> Result<(String, App), StepError> {
    check_size(width, height)?;
    let player = settled_step(tour, index, engine)?;
    Ok((step_text(&player, width, height), player.app))
}

/// The tour on step `index`, its lab's commands carried out with `engine` and a two-body
/// step's scene solved, timings hidden.
fn settled_step(tour: &Tour, index: usize, engine: &mut Engine) -> Result<TourApp, StepError> {
    if index >= tour.steps.len() {
        return Err(StepError::NoSuchStep {
            step: index + 1,
            steps: tour.steps.len(),
        });
    }
    let mut player = TourApp::new(tour.clone(), None);
    player.show_timing = false;
    player.app.show_timing = false;
    let commands = player.go_to(index);
    carry_out(&mut player.app, engine, commands);
    if let Some(bodies) = &mut player.bodies {
        let (generation, settings) = bodies.start();
        let result = BodiesCache::new(bodies.scenario.clone()).solve(&settings, &|| false);
        bodies.reply(generation, result);
    }
    Ok(player)
}

/// `player` drawn on a `width`×`height` test terminal as plain text.
fn step_text(player: &TourApp, width: u16, height: u16) -> String {
    let look = Look {
        theme: Theme { color: true },
        marker: Marker::Braille,
    };
    render_frame(width, height, |frame| view(player, frame, &look))
}
