//! Drawing the tour: the lab on top, the step's caption in a panel below, the tour's help on
//! top of both; and [`render_step`], one step as plain text (for tests and documents).

use ratatui::Frame;
use ratatui::layout::{Alignment, Constraint, Flex, Layout, Rect};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Paragraph, Wrap};

use super::super::render_frame;
use super::super::theme::Theme;
use super::super::view::help::key_popup;
use super::super::view::{Look, MIN_SIZE as LAB_MIN, view_in};
use super::super::worker::{Engine, carry_out};
use super::{Tour, TourApp};

/// The smallest terminal that shows a step with a four-line caption unwrapped.
pub const MIN_TOUR_SIZE: (u16, u16) = (100, 30);

/// The tour's keys and what they do.
const KEYS: [(&str, &str); 8] = [
    ("Space  →  Enter", "next step (PageDown too)"),
    ("←  Backspace", "previous step (PageUp too)"),
    ("Home  End", "first / last step"),
    ("q  Esc  Ctrl-C", "quit the tour (Esc first closes this help)"),
    ("?", "show / hide this help"),
    (
        "r e 1–4 + − d D",
        "the lab's keys work inside a step: rule, element,",
    ),
    ("Tab g h a [ ]", "scheme, ε, depth, scene, overlays, level;"),
    ("s  S", "CSV / SVG export. Coming back restores a step."),
];

/// Draw the tour into the whole frame.
pub fn view(tour: &TourApp, frame: &mut Frame, look: &Look) {
    let area = frame.area();
    let Some(step) = tour.tour.steps.get(tour.index()) else {
        return;
    };
    let inner_width = area.width.saturating_sub(2).max(1);
    let rows = wrapped_rows(&step.caption, usize::from(inner_width)) as u16 + 2;
    if area.width < LAB_MIN.0 || area.height < LAB_MIN.1 + rows {
        too_small(frame, area, LAB_MIN.1 + rows);
        return;
    }
    let [lab, panel] = Layout::vertical([Constraint::Fill(1), Constraint::Length(rows)]).areas(area);
    view_in(&tour.app, frame, lab, look);
    caption_panel(tour, frame, panel, look.theme);
    if tour.show_help {
        help(frame, area, look.theme);
    }
}

/// The caption of the current step in a frame titled with its number and title, the keys in
/// the bottom border.
fn caption_panel(tour: &TourApp, frame: &mut Frame, area: Rect, theme: Theme) {
    let n = tour.tour.steps.len();
    let i = tour.index();
    let Some(step) = tour.tour.steps.get(i) else {
        return;
    };
    let title = Line::from(vec![
        Span::styled(format!(" tour {}/{n} ", i + 1), theme.selected()),
        Span::styled(format!(" {} ", step.title), theme.title()),
    ]);
    let mut keys = Vec::new();
    if let Some(auto) = tour.auto {
        let what = if tour.at_end() {
            "auto: done".to_string()
        } else {
            format!("auto every {} s", auto.as_secs_f64())
        };
        keys.push(Span::styled(format!(" {what} "), theme.busy()));
    }
    if !tour.at_end() {
        keys.push(Span::styled(" Space", theme.key()));
        keys.push(Span::raw(" next "));
    } else {
        keys.push(Span::raw(" end of the tour "));
    }
    if i > 0 {
        keys.push(Span::styled(" ←", theme.key()));
        keys.push(Span::raw(" back "));
    }
    keys.push(Span::styled(" ?", theme.key()));
    keys.push(Span::raw(" keys "));
    keys.push(Span::styled(" q", theme.key()));
    keys.push(Span::raw(" quit "));
    let mut block = Block::bordered()
        .border_style(theme.axis())
        .title(title)
        .title_bottom(Line::from(keys).alignment(Alignment::Right));
    if !tour.is_pristine() {
        block = block.title(
            Line::styled(" changed: leave and come back to restore ", theme.faint())
                .alignment(Alignment::Right),
        );
    }
    let lines: Vec<Line> = step.caption.lines().map(Line::raw).collect();
    frame.render_widget(
        Paragraph::new(lines).wrap(Wrap { trim: false }).block(block),
        area,
    );
}

/// How many rows `text` takes wrapped at word boundaries to `width` columns (a word longer
/// than a row fills whole rows).
fn wrapped_rows(text: &str, width: usize) -> usize {
    let width = width.max(1);
    text.lines()
        .map(|line| {
            let (mut rows, mut used) = (1, 0usize);
            for word in line.split(' ') {
                let w = word.chars().count();
                if used > 0 && used + 1 + w <= width {
                    used += 1 + w;
                } else if used == 0 && w <= width {
                    used = w;
                } else {
                    rows += usize::from(used > 0) + w.saturating_sub(1) / width;
                    used = w - w.saturating_sub(1) / width * width;
                }
            }
            rows
        })
        .sum::<usize>()
        .max(1)
}

/// The tour's keys over the middle of `area`.
fn help(frame: &mut Frame, area: Rect, theme: Theme) {
    key_popup(frame, area, theme, " tour keys ", &KEYS, (74, 17));
}

/// The message shown instead of the tour in a terminal too small for it.
fn too_small(frame: &mut Frame, area: Rect, rows: u16) {
    let lines = vec![
        Line::raw("the tour needs a bigger terminal"),
        Line::raw(format!(
            "this one is {}×{}; this step needs at least {}×{rows}",
            area.width, area.height, LAB_MIN.0
        )),
        Line::raw("enlarge the window or make the font smaller (q quits)"),
    ];
    let height = (lines.len() as u16).min(area.height);
    let [middle] = Layout::vertical([Constraint::Length(height)])
        .flex(Flex::Center)
        .areas(area);
    frame.render_widget(
        Paragraph::new(lines)
            .alignment(Alignment::Center)
            .wrap(Wrap { trim: true }),
        middle,
    );
}

/// Step `index` of `tour` on a `width`×`height` test terminal as plain text, its lab solved
/// synchronously (timings left out so that the text is deterministic).
pub fn render_step(tour: &Tour, index: usize, width: u16, height: u16) -> Result<String, String> {
    if index >= tour.steps.len() {
        return Err(format!(
            "step {} does not exist; the tour has {} steps",
            index + 1,
            tour.steps.len()
        ));
    }
    if width == 0 || height == 0 {
        return Err(format!("size {width}×{height} is empty"));
    }
    let mut player = TourApp::new(tour.clone(), None);
    player.show_timing = false;
    player.app.show_timing = false;
    let commands = player.go_to(index);
    carry_out(
        &mut player.app,
        &mut Engine::new(tour.scenario_of(index).clone()),
        commands,
    );
    let look = Look {
        theme: Theme { color: true },
        marker: Marker::Braille,
    };
    Ok(render_frame(width, height, |frame| view(&player, frame, &look)))
}
