//! The tour's typed errors: a step's settings its scenario refuses (its friction
//! among them), a title or caption that does not fit, an `--auto` interval out of range, a
//! step that cannot be drawn and a step `T` could not add. Their messages are the ones users saw as text before.

use std::path::PathBuf;

use crate::check::CheckError;
use crate::grading::Grading;
use crate::input::ScenarioError;
use crate::input::read::MAX_FILE_BYTES;
use crate::plot::PlotError;
use crate::text::num;

use super::super::errors::SizeError;
use super::super::lab_error::LabError;
use super::{MAX_CAPTION_LINES, MAX_CAPTION_WIDTH};

/// A step whose settings its scenario refuses ([`super::Tour::with_scenario`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TourError {
    /// The step's ε is outside the range of its level.
    #[error("{file}: step {step} (`{title}`): ε at level {level}: {source}")]
    Epsilon {
        /// The tour file (sanitised).
        file: String,
        /// The step's number (1-based).
        step: usize,
        /// The step's title.
        title: String,
        /// The step's level.
        level: u32,
        /// Why, and the range allowed (boxed: the check's error is large).
        source: Box<CheckError>,
    },
    /// The step's depth is beyond its scenario's limit.
    #[error(
        "{file}: step {step} (`{title}`): depth {depth} is out of range for its scenario; allowed: 0 to {max}"
    )]
    Depth {
        /// The tour file (sanitised).
        file: String,
        /// The step's number (1-based).
        step: usize,
        /// The step's title.
        title: String,
        /// The depth asked for.
        depth: f64,
        /// The scenario's largest depth.
        max: f64,
    },
    /// The step asks for an overlay its scenario has no curve for.
    #[error("{file}: step {step} (`{title}`): overlays = [\"{overlay}\"]: {why}")]
    Overlay {
        /// The tour file (sanitised).
        file: String,
        /// The step's number (1-based).
        step: usize,
        /// The step's title.
        title: String,
        /// The overlay's name in the tour file.
        overlay: &'static str,
        /// Why the scenario has no such curve.
        why: &'static str,
    },
    /// The scenario of the steps that name none has two bodies: those steps show the one-body
    /// lab (a two-body step names its scenario, [`super::bodies_step`]).
    #[error(
        "{file}: step {step} (`{title}`) names no scenario, and the tour's, {scenario}, has two elastic bodies ([upper]); allowed: a one-body scenario for the steps that name none (a two-body step names its own with `scenario`)"
    )]
    TwoBodies {
        /// The tour file (sanitised).
        file: String,
        /// The first step naming no scenario (1-based).
        step: usize,
        /// The step's title.
        title: String,
        /// The scenario given (sanitised).
        scenario: String,
    },
    /// The step's friction is one the lab refuses to solve on its scenario.
    #[error("{file}: step {step} (`{title}`): {source}")]
    Friction {
        /// The tour file (sanitised).
        file: String,
        /// The step's number (1-based).
        step: usize,
        /// The step's title.
        title: String,
        /// Why.
        source: FrictionStepError,
    },
}

/// Why the lab refuses a screen's friction ([`super::friction_step::check`]): in a tour
/// step (found when the tour is read) or in the lab's `T` (no step written).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FrictionStepError {
    /// Friction on a half model, whose symmetry line holds Γ_C's u_x.
    #[error(
        "friction needs the full model (body.model = \"full\"): the scenario's half model holds u_x = 0 on its symmetry line"
    )]
    HalfModel,
    /// Friction with Nitsche's method.
    #[error("friction is imposed by penalty, exact or alm, not nitsche")]
    Nitsche,
    /// Friction on a graded mesh.
    #[error(
        "grading (refine_edges = \"{0}\") does not take friction yet; give refine_edges = 0 or friction = \"none\""
    )]
    Graded(Grading),
    /// A shift that moves the obstacle's centre out of the body.
    #[error(
        "shift = {} moves the obstacle's centre to x = {}, beyond the body; allowed: the centre strictly inside ({}, {})",
        num(*shift),
        num(*centre),
        num(*x0),
        num(*x1)
    )]
    ShiftBeyond {
        /// The shift.
        shift: f64,
        /// Where it moves the obstacle's centre.
        centre: f64,
        /// The body's left side.
        x0: f64,
        /// The body's right side.
        x1: f64,
    },
}

/// A title or a caption that does not fit the tour's screen.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TextError {
    /// A one-line text (a title) that is blank.
    #[error("is empty; allowed: one line of 1 to {width} characters")]
    EmptyLine {
        /// The characters allowed.
        width: usize,
    },
    /// A one-line text on more lines or longer than allowed.
    #[error("allowed: one line of at most {width} characters")]
    Line {
        /// The characters allowed.
        width: usize,
    },
    /// A blank caption.
    #[error("is empty; allowed: {CAPTION}")]
    EmptyCaption,
    /// A caption of too many lines.
    #[error("has {lines} lines; allowed: {CAPTION}")]
    CaptionLines {
        /// Its lines.
        lines: usize,
    },
    /// A caption with a line too long.
    #[error("line {line} has {chars} characters; allowed: {CAPTION}")]
    CaptionWidth {
        /// The line's number (1-based).
        line: usize,
        /// Its characters.
        chars: usize,
    },
}

/// What a caption may be, for [`TextError`]'s messages.
const CAPTION: Caption = Caption;

/// Writes "1 to [`MAX_CAPTION_LINES`] lines of at most [`MAX_CAPTION_WIDTH`] characters".
struct Caption;

impl std::fmt::Display for Caption {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "1 to {MAX_CAPTION_LINES} lines of at most {MAX_CAPTION_WIDTH} characters"
        )
    }
}

/// An `--auto SECONDS` interval out of range ([`super::auto_interval`]).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("{seconds} is out of range; allowed: 0.5 to 3600 seconds")]
pub struct AutoIntervalError {
    /// The seconds given.
    pub seconds: f64,
}

/// Why a step of a tour could not be drawn as text ([`super::render_step`]) or its pressure
/// chart made (the handout's).
#[derive(Debug, thiserror::Error)]
pub enum StepError {
    /// No step of that number.
    #[error("step {step} does not exist; the tour has {steps} steps")]
    NoSuchStep {
        /// The step asked for (1-based).
        step: usize,
        /// The tour's steps.
        steps: usize,
    },
    /// The size.
    #[error(transparent)]
    Size(#[from] SizeError),
    /// The step's solve failed.
    #[error(transparent)]
    Failed(#[from] LabError),
    /// The step has no solution (and no failure to tell).
    #[error("the step has no solution")]
    NoSolution,
    /// The pressure chart could not be drawn.
    #[error(transparent)]
    Chart(#[from] PlotError),
}

/// Why `T` added no step to the tour file ([`super::author::save_step`]).
#[derive(Debug, thiserror::Error)]
pub enum AuthorError {
    /// The scenario file's path cannot be written into the TOML file.
    #[error("the scenario's path {} is not UTF-8", path.display())]
    NotUtf8 {
        /// The scenario file.
        path: PathBuf,
    },
    /// The tour file is not a valid tour: its first line of error.
    #[error(
        "{} (T adds to a valid tour file only; --tour-out names another)",
        first_line(source)
    )]
    Invalid {
        /// Why the file is not a valid tour.
        source: ScenarioError,
    },
    /// The lab's screen is one a tour step cannot be played as (its friction refused).
    #[error("a step at these settings would not play: {0}")]
    Refused(#[from] FrictionStepError),
    /// The step would make the tour file larger than a tour may be.
    #[error(
        "{path} has {size} bytes and the step {adding} more: beyond the {MAX_FILE_BYTES} bytes (1 MiB) a tour file may have (--tour-out names another)"
    )]
    TooLarge {
        /// The tour file (sanitised).
        path: String,
        /// Its size, bytes.
        size: usize,
        /// The bytes the step would add.
        adding: usize,
    },
    /// The tour file could not be written.
    #[error("{path}: {source}")]
    Write {
        /// The tour file (sanitised).
        path: String,
        /// What the system said.
        source: std::io::Error,
    },
}

/// The first line of `error`'s message.
fn first_line(error: &ScenarioError) -> String {
    error.to_string().lines().next().unwrap_or_default().to_string()
}

/// Why a handout's directory cannot be used ([`super::handout::HandoutError::Directory`]).
#[derive(Debug, thiserror::Error)]
pub enum DirectoryFault {
    /// It holds files already.
    #[error("the directory is not empty")]
    NotEmpty,
    /// It does not exist and cannot be created.
    #[error("cannot create it: {0}")]
    Create(#[source] std::io::Error),
    /// It is a file.
    #[error("not a directory ({0})")]
    NotADirectory(#[source] std::io::Error),
    /// It cannot be read.
    #[error("cannot read it: {0}")]
    Read(#[source] std::io::Error),
}
