//! The terminal lab: rendered frames (insta snapshots of the plain text, in `snapshots/`) and
//! the key handling of `App::update`, without a terminal.

mod convergence;
mod details;
mod exactness;
mod frames;
mod keys_and_lines;
mod look;
mod worker;

use convergence::convergence_app;
use details::PaperWorker;
use exactness::{MONO, buffer, row_text};
use frames::infsup_app;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::Color;
use ratatui::symbols::Marker;

use riplab::contact::Rule;
use riplab::contact::hertz::Hertz;
use riplab::error::SolveError;
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::tui::lab_error::LabError;
use std::sync::Arc;

use crate::tui::tests::settled;
use riplab::study::{Errors, Status, StudyRow};
use riplab::tui::app::{
    App, Command, Compare, MAX_APP_LEVEL, MAX_STUDY_LEVEL, Msg, Response, Scene, Study, StudyRequest,
};
use riplab::tui::engine::{Engine, Use};
use riplab::tui::settle::settle;
use riplab::tui::theme::Theme;
use riplab::tui::view::Look;
use riplab::tui::view::plot::{Axis as PlotAxis, Plot, Scale, Series as PlotSeries, Stroke};
use riplab::tui::{render_app, render_to_string};

const LOOK: Look = Look {
    theme: Theme { color: true },
    marker: Marker::Braille,
};

fn key(code: KeyCode) -> Msg {
    Msg::Key(KeyEvent::new(code, KeyModifiers::NONE))
}

fn ch(c: char) -> Msg {
    key(KeyCode::Char(c))
}

fn frame(app: &App, w: u16, h: u16) -> String {
    render_app(app, &LOOK, w, h)
}

/// The status area of a frame (wrapped, never cut): its rows between the scene's last
/// border and the key bar (the last row, ending `? help  q quit`), joined with single spaces.
pub(super) fn status_of(text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let bar = lines
        .iter()
        .rposition(|l| l.trim_end().ends_with("? help  q quit"))
        .expect("the key bar");
    let first = lines[..bar]
        .iter()
        .rposition(|l| l.contains('┘') || l.contains('└'))
        .map_or(0, |i| i + 1);
    // The explore scene's panels collapsed to one row (a short lab) end the scene.
    let first = lines[first..bar]
        .iter()
        .position(|l| l.starts_with("inf-sup "))
        .map_or(first, |i| first + i + 1);
    let rows = lines[first..bar].iter().copied();
    rows.flat_map(str::split_whitespace).collect::<Vec<_>>().join(" ")
}
