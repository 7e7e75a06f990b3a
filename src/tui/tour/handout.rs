//! `riplab tour --handout DIR`: a printable lesson from the same data as the live tour. For
//! every step, its screen as text (`step-01.txt`, equal to [`super::render_step`], the caption
//! panel included) and its pressure chart as SVG (`step-01.svg`: p and p̄ along Γ_C at the
//! step's settings, as the lab's `S` writes it, whatever scene the step shows); and `index.md`,
//! which lists the steps with their captions, settings and files.
//!
//! The rule for the directory: it is created if it does not exist, and used only if it is
//! empty, so that a handout never mixes with the files of another run (and no file is ever
//! replaced: each is created new).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::plot::{chart_title, pressure_svg_string, write_file};
use crate::scheme::Scheme;
use crate::text::num;

use super::super::app::{App, Msg, Scene};
use super::super::engine::Engine;
use super::super::settle::carry_out;
use super::Tour;
use super::errors::{DirectoryFault, StepError};
use super::view::step_frame;

/// Why a handout was not written.
#[derive(Debug, thiserror::Error)]
pub enum HandoutError {
    /// The directory holds files already, or is not a directory (bad input).
    #[error(
        "{dir}: {fault}; a handout is written only into a new or empty directory (no file is ever replaced)"
    )]
    Directory {
        /// The directory (sanitised).
        dir: String,
        /// What is wrong with it.
        fault: DirectoryFault,
    },
    /// A step could not be drawn or its chart made (the size out of range, a failed solve).
    #[error("step {step}: {source}")]
    Step {
        /// The step's number (1-based).
        step: usize,
        /// What went wrong.
        source: StepError,
    },
    /// A file could not be written.
    #[error("{path}: {source}")]
    Write {
        /// The file.
        path: String,
        /// What the system said.
        source: std::io::Error,
    },
}

/// Write the handout of `tour` at `width`×`height` into `dir` (created if missing, used only
/// if empty); `progress` is told each step as it is done. Returns the files written, the index
/// last.
pub fn write_handout(
    tour: &Tour,
    dir: &Path,
    width: u16,
    height: u16,
    mut progress: impl FnMut(usize, usize),
) -> Result<Vec<PathBuf>, HandoutError> {
    prepare(dir)?;
    let mut files = Vec::new();
    let mut index = intro(tour, width, height);
    for (i, step) in tour.steps.iter().enumerate() {
        let fail = |source: StepError| HandoutError::Step { step: i + 1, source };
        // A fresh engine per step, as `render_step`'s: a warm start from the step before
        // would change the Newton steps the status line counts.
        let mut engine = Engine::new(tour.scenario_of(i).clone());
        let (text, app) = step_frame(tour, i, width, height, &mut engine).map_err(fail)?;
        let svg = chart(app, &mut engine).map_err(fail)?;
        let stem = format!("step-{:02}", i + 1);
        for (ext, bytes) in [("txt", text.as_bytes()), ("svg", svg.as_bytes())] {
            let path = dir.join(format!("{stem}.{ext}"));
            save(&path, bytes)?;
            files.push(path);
        }
        let _ = write!(index, "## {}. {}\n\n", i + 1, step.title);
        for line in step.caption.lines() {
            let _ = writeln!(index, "> {line}");
        }
        let settings = settings(&tour.app(i));
        let _ = write!(
            index,
            "\n{settings}\n\n- screen: [{stem}.txt]({stem}.txt)\n- pressure chart: [{stem}.svg]({stem}.svg)\n\n"
        );
        progress(i + 1, tour.steps.len());
    }
    let path = dir.join("index.md");
    save(&path, index.as_bytes())?;
    files.push(path);
    Ok(files)
}

/// The directory, created if missing; refused unless it is an empty directory.
fn prepare(dir: &Path) -> Result<(), HandoutError> {
    let shown = crate::text::sanitize(&dir.display().to_string()).into_owned();
    let refuse = |fault: DirectoryFault| HandoutError::Directory {
        dir: shown.clone(),
        fault,
    };
    match std::fs::read_dir(dir) {
        Ok(mut entries) => {
            if entries.next().is_some() {
                return Err(refuse(DirectoryFault::NotEmpty));
            }
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            std::fs::create_dir_all(dir).map_err(|e| refuse(DirectoryFault::Create(e)))
        }
        Err(e) if dir.exists() && !dir.is_dir() => Err(refuse(DirectoryFault::NotADirectory(e))),
        Err(e) => Err(refuse(DirectoryFault::Read(e))),
    }
}

fn save(path: &Path, bytes: &[u8]) -> Result<(), HandoutError> {
    write_file(path, bytes, false).map_err(|source| HandoutError::Write {
        path: crate::text::sanitize(&path.display().to_string()).into_owned(),
        source,
    })
}

/// The pressure chart of the step's settings (solved here if the step's scene shows no
/// solution).
fn chart(mut app: App, engine: &mut Engine) -> Result<String, StepError> {
    if app.current().is_none() {
        // The mesh scene needs the solve alone (no inf-sup estimate, no study).
        app.scene = Scene::Mesh;
        let commands = app.update(Msg::Resize).commands;
        carry_out(&mut app, engine, commands);
    }
    let solved = app
        .current()
        .ok_or_else(|| app.error.clone().map_or(StepError::NoSolution, StepError::Failed))?;
    let title = chart_title(
        &app.scenario.name,
        solved.key.element,
        solved.key.level,
        &solved.solution,
    );
    Ok(pressure_svg_string(
        &title,
        &solved.solution,
        app.scenario.half_model,
    )?)
}

/// The index's first lines.
fn intro(tour: &Tour, width: u16, height: u16) -> String {
    format!(
        "# {}\n\nA handout of riplab's tour `{}`: {} steps, each step's screen as text ({width}×{height}, \
         as `riplab tour` shows it, without timings) and its pressure chart (p and p̄ along Γ_C) as SVG.\n\n",
        tour.title,
        tour.source,
        tour.steps.len()
    )
}

/// The step's settings in a line: scene, scenario, scheme, level, method and ε, depth.
fn settings(app: &App) -> String {
    let s = &app.settings;
    let epsilon = if s.method.uses_epsilon() {
        format!(", ε = {}", num(s.epsilon))
    } else {
        String::new()
    };
    format!(
        "Scene {} · {} · {} at level {} · {}{epsilon} · depth {}",
        app.scene.name(),
        app.scenario.name,
        Scheme::new(s.element, s.rule).label(),
        s.level,
        s.method.label(),
        num(s.depth)
    )
}
