//! The terminal lab (ratatui + crossterm): the paper's problem solved live as the user
//! changes level, element, rule, ε and depth, with braille charts of the pressures, the
//! inf-sup estimate and the deformed configuration.
//!
//! The shape is the Elm architecture: [`app::App`] holds the state and its pure
//! [`app::App::update`] turns keys and worker replies into state changes and requests;
//! [`view::view`] draws the state; a [`worker::Worker`] thread owns the discretisation cache
//! and runs solves and estimates, the newest request cancelling older ones.

pub mod app;
pub mod beta;
pub mod export;
mod runtime;
pub mod theme;
pub mod tour;
pub mod view;
pub mod worker;

use ratatui::backend::TestBackend;
use ratatui::buffer::{Buffer, CellWidth};
use ratatui::symbols::Marker;
use ratatui::{Frame, Terminal};

use crate::contact::Rule;
use crate::mesh::Element;
use crate::scenario::Scenario;

use app::{App, MAX_APP_LEVEL, Scene};
use theme::Theme;
use view::Look;
use worker::{Engine, settle};

/// The glyphs of charts and canvases.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum MarkerChoice {
    /// Unicode braille: 2×4 dots per cell (the sharpest).
    #[default]
    Braille,
    /// Half blocks: 1×2 per cell, for fonts without braille.
    #[value(name = "halfblock")]
    HalfBlock,
    /// One dot per cell.
    Dot,
}

impl MarkerChoice {
    pub fn marker(self) -> Marker {
        match self {
            MarkerChoice::Braille => Marker::Braille,
            MarkerChoice::HalfBlock => Marker::HalfBlock,
            MarkerChoice::Dot => Marker::Dot,
        }
    }
}

/// How the interactive app looks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TuiOptions {
    pub marker: MarkerChoice,
    /// Monochrome (the environment's NO_COLOR is honoured as well).
    pub no_color: bool,
}

/// Run the interactive lab on `scenario` until the user quits.
pub fn run(scenario: Scenario, opts: TuiOptions) -> std::io::Result<()> {
    let look = Look {
        theme: Theme::new(opts.no_color),
        marker: opts.marker.marker(),
    };
    runtime::run(scenario, look)
}

/// One frame of `scene` as plain text, solved synchronously with the given overrides of the
/// scenario's settings (timings left out so that the text is deterministic).
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
) -> Result<String, String> {
    let names: Vec<&str> = Scene::ALL.iter().map(|s| s.name()).collect();
    let scene = Scene::from_name(scene)
        .ok_or_else(|| format!("unknown scene `{scene}`; scenes: {}", names.join(", ")))?;
    if width == 0 || height == 0 {
        return Err(format!("size {width}×{height} is empty"));
    }
    let mut app = App::new(scenario.clone());
    app.scene = scene;
    app.show_timing = false;
    if let Some(level) = level {
        if level > MAX_APP_LEVEL {
            return Err(format!(
                "level {level} is out of range; allowed: 0..={MAX_APP_LEVEL}"
            ));
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
        crate::scenario::check::positive(epsilon).map_err(|e| format!("ε: {e}"))?;
        app.settings.epsilon = epsilon;
    }
    settle(&mut app, &mut Engine::new(scenario.clone()));
    let look = Look {
        theme: Theme { color: true },
        marker: Marker::Braille,
    };
    Ok(render_app(&app, &look, width, height))
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
