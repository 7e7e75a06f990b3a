//! `riplab tour --handout DIR`: a printable lesson from the same data as the live tour. For
//! every step, its screen as text (`step-01.txt`, equal to [`super::render_step`], the caption
//! panel included) and its scene's chart as SVG (`step-01.svg`: the inf-sup chart on an inf-sup
//! step, the work–precision chart on a convergence step, else p and p̄ along Γ_C at the step's
//! settings, as the lab's `S` writes it; none on a two-body step, whose screen draws its
//! interface pressure); and `index.md`,
//! which lists the steps with their captions, settings and files.
//!
//! The rule for the directory: it is created if it does not exist, and used only if it is
//! empty, so that a handout never mixes with the files of another run (and no file is ever
//! replaced: each is created new).
//!
//! The rule for the size: before anything is written, the handout's bytes are estimated from
//! its steps and frame size ([`estimate`]) and a handout beyond [`MAX_HANDOUT_BYTES`] is
//! refused; while it is written, the bytes are counted against the same limit (a graded step's
//! chart has more points than its level's, which the estimate counts). A graded step whose
//! memory, estimated from its lines, exceeds what the process may use is refused before
//! anything is written, as the lab's engine refuses it ([`Tour::graded_fits`]).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::error::SolveError;
use crate::plot::{chart_title, loglog_svg_string, pressure_svg_string, write_file};
use crate::scheme::Scheme;
use crate::text::num;

use super::super::app::{App, Msg, Scene};
use super::super::bodies::BodiesApp;
use super::super::engine::Engine;
use super::super::settle::carry_out;
use super::super::view::{convergence, infsup_chart};
use super::Tour;
use super::errors::{DirectoryFault, StepError};
use super::view::step_frame;
use crate::contact::interface::solve::Enforcement;

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
    /// The handout would write more than [`MAX_HANDOUT_BYTES`] (bad input).
    #[error(
        "{steps} steps at {width}×{height} would write up to {} (each step's screen at up to 4 bytes a cell, its chart and its lines of the index), beyond the {} a handout may write; choose a smaller --size or a tour of fewer steps",
        mib(*estimate),
        mib(MAX_HANDOUT_BYTES)
    )]
    TooLarge {
        /// The tour's steps.
        steps: usize,
        /// The frame's columns.
        width: u16,
        /// The frame's rows.
        height: u16,
        /// The estimate, bytes.
        estimate: u64,
    },
    /// A step's files would take the handout past the bytes it may write,
    /// [`MAX_HANDOUT_BYTES`] (its chart larger than estimated): nothing more is written.
    #[error(
        "step {step}: its files would take the handout past the {} it may write ({} written so far); stopped",
        mib(*limit),
        mib(*written)
    )]
    Limit {
        /// The step's number (1-based).
        step: usize,
        /// The bytes written before it.
        written: u64,
        /// The bytes the handout may write.
        limit: u64,
    },
    /// A graded step whose estimate from its lines exceeds the memory this process may use
    /// (bad input): refused before anything is written.
    #[error("step {step}: {source}")]
    Memory {
        /// The step's number (1-based).
        step: usize,
        /// The refusal, naming the level, the element, the grading and the memory.
        source: SolveError,
    },
    /// A file or link appeared at a file's name while the handout was written.
    #[error(
        "{path}: a file or link appeared there while the handout was written; a handout never replaces a file"
    )]
    Taken {
        /// The file (sanitised).
        path: String,
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
    progress: impl FnMut(usize, usize),
) -> Result<Vec<PathBuf>, HandoutError> {
    let estimate = estimate(tour, width, height);
    if estimate > MAX_HANDOUT_BYTES {
        return Err(HandoutError::TooLarge {
            steps: tour.steps.len(),
            width,
            height,
            estimate,
        });
    }
    tour.graded_fits()
        .map_err(|(step, source)| HandoutError::Memory { step, source })?;
    write_within(tour, dir, (width, height), MAX_HANDOUT_BYTES, progress)
}

/// Write the handout of `tour` at `width`×`height` into `dir` as [`write_handout`] does once
/// its estimate passed, the bytes counted against `limit` while they are written: the step
/// whose files (with the index, written last) would pass it is refused, and nothing more is
/// written.
fn write_within(
    tour: &Tour,
    dir: &Path,
    (width, height): (u16, u16),
    limit: u64,
    mut progress: impl FnMut(usize, usize),
) -> Result<Vec<PathBuf>, HandoutError> {
    prepare(dir)?;
    let mut files = Vec::new();
    let mut index = intro(tour, width, height);
    let mut written = 0;
    for (i, step) in tour.steps.iter().enumerate() {
        let fail = |source: StepError| HandoutError::Step { step: i + 1, source };
        // A fresh engine per step, as `render_step`'s: a warm start from the step before
        // would change the Newton steps the status line counts.
        let mut engine = Engine::new(tour.scenario_of(i).clone());
        let (text, app) = step_frame(tour, i, width, height, &mut engine).map_err(fail)?;
        // A two-body step's chart is on its screen (no SVG of two bodies yet).
        let bodies = tour.bodies(i);
        let svg = match &bodies {
            Some(_) => String::new(),
            None => chart(app, &mut engine).map_err(fail)?,
        };
        written += (text.len() + svg.len()) as u64;
        // The index, written last, is counted in as it will be.
        if written + (index.len() as u64) + INDEX_STEP_BYTES > limit {
            return Err(HandoutError::Limit {
                step: i + 1,
                written: written - (text.len() + svg.len()) as u64,
                limit,
            });
        }
        let stem = format!("step-{:02}", i + 1);
        for (ext, bytes) in [("txt", text.as_bytes()), ("svg", svg.as_bytes())] {
            if bytes.is_empty() {
                continue;
            }
            let path = dir.join(format!("{stem}.{ext}"));
            save(&path, bytes)?;
            files.push(path);
        }
        let _ = write!(index, "## {}. {}\n\n", i + 1, step.title);
        for line in step.caption.lines() {
            let _ = writeln!(index, "> {line}");
        }
        let (settings, chart) = match &bodies {
            Some(bodies) => (
                bodies_settings(bodies),
                "none: the two-body scene's interface pressure is on its screen".to_string(),
            ),
            None => (settings(&tour.app(i)), format!("[{stem}.svg]({stem}.svg)")),
        };
        let _ = write!(
            index,
            "\n{settings}\n\n- screen: [{stem}.txt]({stem}.txt)\n- chart: {chart}\n\n"
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

/// Write `bytes` to the new file `path`; a name taken meanwhile (a file or a link planted
/// there) is refused, never replaced or removed.
fn save(path: &Path, bytes: &[u8]) -> Result<(), HandoutError> {
    let shown = || crate::text::sanitize(&path.display().to_string()).into_owned();
    write_file(path, bytes, false).map_err(|source| match source.kind() {
        std::io::ErrorKind::AlreadyExists | std::io::ErrorKind::InvalidInput => {
            HandoutError::Taken { path: shown() }
        }
        _ => HandoutError::Write {
            path: shown(),
            source,
        },
    })
}

/// The most bytes a handout writes: its steps' screens, charts and index together.
pub const MAX_HANDOUT_BYTES: u64 = 256 << 20;
/// An SVG pressure chart's bytes besides its points (axes, labels, legend), at most.
const CHART_BYTES: u64 = 64 << 10;
/// An SVG pressure chart's bytes per contact point at most (its mark, and its vertices in the
/// lines of p and p̄), each drawn twice on a half model (mirrored).
const CHART_POINT_BYTES: u64 = 512;
/// The index's bytes per step at most: its title, caption, settings and links.
const INDEX_STEP_BYTES: u64 = 4 << 10;

/// `bytes` in MiB, for messages.
fn mib(bytes: u64) -> String {
    format!("{:.1} MiB", bytes as f64 / f64::from(1u32 << 20))
}

/// The bytes the handout of `tour` at `width`×`height` writes at most, before any step is
/// solved: each step's screen at 4 bytes a cell (UTF-8's longest) with a line break a row, its
/// chart by the contact points of its level and rule on the uniform mesh, and its lines of the
/// index.
pub fn estimate(tour: &Tour, width: u16, height: u16) -> u64 {
    let screen = u64::from(height) * (4 * u64::from(width) + 1);
    let steps = (0..tour.steps.len()).map(|i| {
        if tour.is_two_body(i) {
            // Its screen and its lines of the index: no chart.
            return screen + INDEX_STEP_BYTES;
        }
        let app = tour.app(i);
        let s = &app.settings;
        let cells = (app.scenario.x_lines.len() as u64 - 1) << s.level;
        let points = s.rule.n_points(cells as usize) as u64;
        let mirrored = if app.scenario.half_model { 2 } else { 1 };
        screen + CHART_BYTES + CHART_POINT_BYTES * points * mirrored + INDEX_STEP_BYTES
    });
    intro(tour, width, height).len() as u64 + steps.sum::<u64>()
}

/// The chart of the step's scene: the inf-sup chart, the work–precision chart (its study
/// done), else the pressure chart of the step's settings (solved here if the step's scene
/// shows no solution).
fn chart(mut app: App, engine: &mut Engine) -> Result<String, StepError> {
    let name = &app.scenario.name;
    match app.scene {
        Scene::InfSup => {
            let title = format!("{name}: β_h/√h against h");
            return Ok(loglog_svg_string(
                &title,
                "h (length)",
                "β_h/√h",
                &infsup_chart::svg_curves(&app),
            )?);
        }
        Scene::Convergence => {
            if let Some(curves) = convergence::svg_curves(&app) {
                let title = format!("{name}: work–precision, {}", app.study_key().label());
                return Ok(loglog_svg_string(
                    &title,
                    "solve ms",
                    "relative error of p̄",
                    &curves,
                )?);
            }
        }
        _ => {}
    }
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
         as `riplab tour` shows it, without timings) and its scene's chart as SVG.\n\n",
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

/// A two-body step's settings in a line: scenario, element and level, the discretisation
/// across the interface, the ratio and offset, the enforcement.
fn bodies_settings(app: &BodiesApp) -> String {
    let s = &app.settings;
    let enforcement = match s.enforcement {
        Enforcement::Exact => "exact multipliers".to_string(),
        Enforcement::Penalty(epsilon) => format!("penalty, ε = {}", num(epsilon)),
        Enforcement::Alm { epsilon, .. } => format!("alm, ε = {}", num(epsilon)),
    };
    format!(
        "Scene two bodies · {} · {} at level {} · {} · ratio {} · offset {} · {enforcement}",
        app.scenario.name,
        app.scenario.element.name(),
        s.level,
        s.method.name(),
        s.ratio_text(),
        num(s.offset)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The count while writing (the backstop behind the estimate, for a chart larger than
    /// estimated) stops a handout at the step whose files would pass its limit: under a
    /// limit that admits step 1 with its index lines and no more, step 1's files are written,
    /// step 2 is refused in its own words, and neither its files nor the index are.
    #[test]
    fn the_count_while_writing_stops_at_the_step_past_the_limit() {
        let dir = std::env::temp_dir().join(format!("riplab-handout-count-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let step = |t: &str| format!("\n[[step]]\ntitle = \"{t}\"\ncaption = \"c\"\nlevel = 0\n");
        let text = format!("title = \"two\"\n{}{}", step("a"), step("b"));
        let tour = Tour::parse(&text, "t.toml", None).unwrap();
        let size = (80, 24);
        let whole = write_within(&tour, &dir.join("whole"), size, MAX_HANDOUT_BYTES, |_, _| {}).unwrap();
        let bytes = |name: &str| std::fs::metadata(dir.join("whole").join(name)).unwrap().len();
        assert_eq!(whole.len(), 5, "{whole:?}");
        let first = bytes("step-01.txt") + bytes("step-01.svg");
        let limit = first + intro(&tour, size.0, size.1).len() as u64 + INDEX_STEP_BYTES;
        let out = dir.join("limited");
        let mut done = Vec::new();
        let e = write_within(&tour, &out, size, limit, |d, _| done.push(d)).unwrap_err();
        assert!(
            matches!(e, HandoutError::Limit { step: 2, written, limit: l } if written == first && l == limit),
            "{e:?}"
        );
        assert!(
            e.to_string()
                .starts_with("step 2: its files would take the handout past"),
            "{e}"
        );
        assert_eq!(done, [1]);
        for (name, kept) in [
            ("step-01.txt", true),
            ("step-01.svg", true),
            ("step-02.txt", false),
            ("step-02.svg", false),
            ("index.md", false),
        ] {
            assert_eq!(out.join(name).exists(), kept, "{name}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
