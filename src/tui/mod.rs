//! The terminal lab (ratatui + crossterm): the paper's problem solved live as the user
//! changes level, element, rule, ε and depth, with braille charts of the pressures, the
//! inf-sup estimate and the deformed configuration.
//!
//! The shape is the Elm architecture: [`app::App`] holds the state and its pure
//! [`app::App::update`] turns keys and worker replies into state changes and requests;
//! [`view::view`] draws the state; a [`worker::Worker`] thread drives an [`engine::Engine`],
//! which owns the discretisation cache and runs solves and estimates, the newest request
//! cancelling older ones; [`settle()`] drives the same engine synchronously. The app and the
//! worker speak through [`protocol`] alone.

pub mod app;
pub mod beta;
pub mod bodies;
pub mod bodies_solve;
mod build;
pub mod engine;
pub mod errors;
mod estimating;
pub mod eta;
mod event_loop;
pub mod export;
mod export_error;
#[cfg(test)]
mod export_tests;
pub mod friction_settings;
mod job;
pub mod key_bar;
pub mod keys;
pub mod lab_error;
pub mod protocol;
pub mod record;
pub mod regrade;
pub mod render_keys;
mod runtime;
pub mod settle;
pub mod shown;
pub mod shown_friction;
mod signals;
mod study_grading;
#[cfg(test)]
mod tests;
pub mod theme;
pub mod tour;
pub mod view;
pub mod worker;

pub use errors::{RenderError, SizeError};

use std::path::{Path, PathBuf};

use ratatui::backend::TestBackend;
use ratatui::buffer::{Buffer, CellWidth};
use ratatui::layout::Rect;
use ratatui::symbols::Marker;
use ratatui::{Frame, Terminal};

use crate::contact::Rule;
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::text;

use app::{App, MAX_APP_LEVEL, Scene};
use engine::Engine;
use lab_error::LabError;
use record::CastFile;
use settle::settle;
use theme::Theme;
use tour::author::{DEFAULT_TOUR_OUT, LabSource};
use view::Look;

/// The glyphs of charts and canvases.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MarkerChoice {
    /// Unicode braille: 2×4 dots per cell (the sharpest).
    #[default]
    Braille,
    /// Half blocks: 1×2 per cell, for fonts without braille.
    HalfBlock,
    /// One dot per cell.
    Dot,
}

impl MarkerChoice {
    /// The ratatui marker of this choice.
    pub fn marker(self) -> Marker {
        match self {
            MarkerChoice::Braille => Marker::Braille,
            MarkerChoice::HalfBlock => Marker::HalfBlock,
            MarkerChoice::Dot => Marker::Dot,
        }
    }
}

/// How the interactive app looks, and where it exports.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TuiOptions {
    /// The glyphs of charts and canvases (`--marker`).
    pub marker: MarkerChoice,
    /// Monochrome (the environment's NO_COLOR is honoured as well).
    pub no_color: bool,
    /// No mouse (`--no-mouse`): the terminal keeps its own selection of text; otherwise a
    /// click on a tab changes the scene, the wheel scrolls the help and the log, and a click
    /// on the pressure chart places the cursor.
    pub no_mouse: bool,
    /// Where `s` and `S` write; the current directory when None.
    pub export_dir: Option<PathBuf>,
    /// Where the lab's `T` adds tour steps; `riplab-tour.toml` in the export directory when
    /// None.
    pub tour_out: Option<PathBuf>,
}

impl TuiOptions {
    /// The export directory, absolute (so that the status line names the file exactly).
    pub fn export_dir(&self) -> std::io::Result<PathBuf> {
        std::path::absolute(self.export_dir.as_deref().unwrap_or(Path::new(".")))
    }

    /// How the lab draws: colour unless `--no-color` (or `NO_COLOR`), and the chosen marker.
    fn look(&self) -> Look {
        Look {
            theme: Theme::new(self.no_color),
            marker: self.marker.marker(),
        }
    }
}

/// Run the interactive lab on `scenario` (read from `scenario_file`, if given) until the user
/// quits, recording into `record` if given (see [`record`]).
pub fn run(
    scenario: Scenario,
    scenario_file: Option<&Path>,
    opts: &TuiOptions,
    record: Option<CastFile>,
) -> Result<(), RunError> {
    let look = opts.look();
    let dir = opts.export_dir()?;
    let source = LabSource {
        tour_out: match &opts.tour_out {
            Some(file) => std::path::absolute(file)?,
            None => dir.join(DEFAULT_TOUR_OUT),
        },
        scenario_file: scenario_file.map(std::path::absolute).transpose()?,
    };
    let title = format!("riplab lab: {}", text::sanitize(&scenario.name));
    let recording = record.map(|r| (r, title));
    // The paper's problem, given by no file, opens on its phenomenon ([`App::opening`]).
    let app = match scenario_file {
        None => App::opening(scenario),
        Some(_) => App::new(scenario),
    };
    runtime::run(app, look, dir, source, recording, !opts.no_mouse)
}

/// Run the lab's two-body scene ([`bodies`]) on `app` until the user quits, recording into
/// `record` if given.
pub fn run_bodies(
    app: bodies::BodiesApp,
    opts: &TuiOptions,
    record: Option<CastFile>,
) -> Result<(), RunError> {
    let look = opts.look();
    let title = format!("riplab lab: {}", text::sanitize(&app.scenario.name));
    bodies::runtime::run(app, look, record.map(|r| (r, title)), !opts.no_mouse)
}

/// Why the lab or the tour ended with an error.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The terminal could not be set up, read or written.
    #[error("terminal: {0}")]
    Terminal(#[from] std::io::Error),
    /// The recording could not be written (the lab or tour itself ran).
    #[error(transparent)]
    Recording(#[from] record::RecordingFailure),
}

/// One frame of `scene` as plain text, solved synchronously with the given overrides of the
/// scenario's settings (timings left out so that the text is deterministic).
#[cfg(test)]
#[allow(clippy::too_many_arguments)]
pub fn render_to_string(
    scenario: &Scenario,
    scene: &str,
    width: u16,
    height: u16,
    level: Option<u32>,
    element: Option<Element>,
    rule: Option<Rule>,
    epsilon: Option<f64>,
) -> Result<Rendered, RenderError> {
    let plain = RenderExtras::default();
    render_with(
        scenario, scene, width, height, level, element, rule, epsilon, &plain,
    )
}

/// What `riplab render` adds to [`render_to_string`]: keys applied before the frame is
/// printed ([`render_keys`]) and the charts' marker.
#[derive(Clone, Debug, Default)]
pub struct RenderExtras {
    /// The keys, in order, applied to the settled lab (each settled in turn).
    pub keys: Vec<crossterm::event::KeyEvent>,
    /// The glyphs of charts and canvases.
    pub marker: MarkerChoice,
    /// Open as the lab opens the paper's problem given by no file ([`App::opening`]).
    pub opening: bool,
}

/// [`render_to_string`] with `extras`: the keys applied one by one to the settled lab (what
/// each asks for computed before the next), then the frame drawn with the marker.
#[allow(clippy::too_many_arguments)]
pub fn render_with(
    scenario: &Scenario,
    scene: &str,
    width: u16,
    height: u16,
    level: Option<u32>,
    element: Option<Element>,
    rule: Option<Rule>,
    epsilon: Option<f64>,
    extras: &RenderExtras,
) -> Result<Rendered, RenderError> {
    let names: Vec<&str> = Scene::ALL.iter().map(|s| s.name()).collect();
    let scene = Scene::from_name(scene).ok_or_else(|| RenderError::UnknownScene {
        scene: scene.to_string(),
        names: names.join(", "),
    })?;
    check_size(width, height)?;
    let mut app = if extras.opening {
        App::opening(scenario.clone())
    } else {
        App::new(scenario.clone())
    };
    app.scene = scene;
    app.show_timing = false;
    if let Some(level) = level {
        if level > MAX_APP_LEVEL {
            return Err(RenderError::Level { level });
        }
        app.settings.level = level;
    }
    if let Some(element) = element {
        app.settings.element = element;
    }
    if let Some(rule) = rule {
        app.settings.rule = rule;
    }
    if let Some(epsilon) = epsilon {
        crate::check::positive(epsilon).map_err(RenderError::Epsilon)?;
        app.settings.epsilon = epsilon;
    }
    let mut engine = Engine::new(scenario.clone());
    settle(&mut app, &mut engine);
    for (i, &key) in extras.keys.iter().enumerate() {
        let commands = app.update(app::Msg::Key(key)).commands;
        if app.should_quit() {
            return Err(RenderError::Quits { at: i + 1 });
        }
        settle::carry_out(&mut app, &mut engine, commands);
    }
    let look = Look {
        theme: Theme { color: true },
        marker: extras.marker.marker(),
    };
    Ok(Rendered {
        text: render_app(&app, &look, width, height),
        failure: shown_failure(&app),
    })
}

/// A frame of [`render_to_string`] and the failure it shows, if any (`riplab render` exits
/// non-zero on one, as `solve` does).
#[derive(Clone, Debug, PartialEq)]
pub struct Rendered {
    /// The frame as plain text.
    pub text: String,
    /// What failed in the frame's scene: the solve, the study or an inf-sup estimate.
    pub failure: Option<LabError>,
}

/// The failure the frame of `app` shows for its scene: the solve's, the study's (the
/// convergence scene) or an inf-sup estimate's (the infsup scene).
fn shown_failure(app: &App) -> Option<LabError> {
    if let Some(e) = &app.error {
        return Some(e.clone());
    }
    match app.scene {
        Scene::Convergence => app.studies.get(&app.study_key())?.as_ref().err().cloned(),
        Scene::InfSup => app.infsup.values().find_map(|r| r.as_ref().err().cloned()),
        _ => None,
    }
}

/// The largest frame `riplab render`, the lab and the tour draw: a sane bound checked before
/// anything is allocated (a 1000×500 buffer of cells is a few tens of MB).
pub const MAX_SIZE: (u16, u16) = (1000, 500);

/// Where the lab and the tour draw in a terminal of `(columns, rows)`: its top-left corner,
/// at most [`MAX_SIZE`], so that the frame's buffers never grow with the terminal (a
/// 30000×20000 terminal's would take 29 GB).
pub fn drawn_area((width, height): (u16, u16)) -> Rect {
    Rect::new(0, 0, width.min(MAX_SIZE.0), height.min(MAX_SIZE.1))
}

/// The one size rule of the lab and `render`: at least [`view::MIN_SIZE`], at most [`MAX_SIZE`].
pub fn check_size(width: impl Into<u32>, height: impl Into<u32>) -> Result<(), SizeError> {
    let (width, height) = (width.into(), height.into());
    let (min, max) = (view::MIN_SIZE, MAX_SIZE);
    let ok = (u32::from(min.0)..=u32::from(max.0)).contains(&width)
        && (u32::from(min.1)..=u32::from(max.1)).contains(&height);
    if ok {
        Ok(())
    } else {
        Err(SizeError::OutOfRange { width, height })
    }
}

/// `COLUMNSxROWS` (`x`, `X` or `×`) parsed and checked by [`check_size`].
pub fn parse_size(text: &str) -> Result<(u16, u16), SizeError> {
    let bad = || SizeError::NotASize {
        text: text.to_string(),
    };
    let (w, h) = text.split_once(['x', 'X', '×']).ok_or_else(bad)?;
    // Parse wide (u32) so that 70000 is "out of range", not "not a size".
    let (w, h): (u32, u32) = (
        w.trim().parse().map_err(|_| bad())?,
        h.trim().parse().map_err(|_| bad())?,
    );
    check_size(w, h)?;
    // In range, hence within u16.
    Ok((w as u16, h as u16))
}

/// `app` drawn on a `width`×`height` test terminal, as plain text.
pub fn render_app(app: &App, look: &Look, width: u16, height: u16) -> String {
    render_frame(width, height, |frame| view::view(app, frame, look))
}

/// What `draw` draws on a `width`×`height` test terminal, as plain text.
pub fn render_frame(width: u16, height: u16, draw: impl FnOnce(&mut Frame)) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).expect("the test backend cannot fail");
    terminal.draw(draw).expect("the test backend cannot fail");
    buffer_text(terminal.backend().buffer())
}

/// The symbols of `buffer`, one line per row, trailing blanks trimmed; the cells hidden
/// behind a wide symbol are skipped.
pub fn buffer_text(buffer: &Buffer) -> String {
    let width = usize::from(buffer.area.width.max(1));
    let mut out = String::new();
    for row in buffer.content.chunks(width) {
        let mut line = String::new();
        let mut skip = 0usize;
        for cell in row {
            if skip == 0 {
                line.push_str(cell.symbol());
            }
            skip = skip.max(usize::from(cell.cell_width())).saturating_sub(1);
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}
