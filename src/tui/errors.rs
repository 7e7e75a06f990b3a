//! The lab's typed errors for what a user gives it: a terminal size and a
//! `riplab render` request. Their messages are the ones users saw as text before.

use crate::check::CheckError;

use super::MAX_SIZE;
use super::app::{LEVEL_LIMIT_WHY, MAX_APP_LEVEL};
use super::view::MIN_SIZE;

/// A terminal size the lab or `render` cannot use.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SizeError {
    /// Outside [`MIN_SIZE`] ..= [`MAX_SIZE`].
    #[error(
        "size {width}x{height} is out of range; allowed: {}x{} to {}x{} (columns x rows)",
        MIN_SIZE.0, MIN_SIZE.1, MAX_SIZE.0, MAX_SIZE.1
    )]
    OutOfRange {
        /// The columns asked for.
        width: u32,
        /// The rows asked for.
        height: u32,
    },
    /// Not `COLUMNSxROWS`.
    #[error(
        "`{text}` is not a size; allowed: COLUMNSxROWS from {}x{} to {}x{}, e.g. 120x40 or 120×40",
        MIN_SIZE.0, MIN_SIZE.1, MAX_SIZE.0, MAX_SIZE.1
    )]
    NotASize {
        /// The text given.
        text: String,
    },
}

/// Why `riplab render` (or [`super::render_with`]) draws no frame: the request is bad input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RenderError {
    /// A scene name that is none of the lab's.
    #[error("unknown scene `{scene}`; scenes: {names}")]
    UnknownScene {
        /// The name given.
        scene: String,
        /// The scenes, comma-separated.
        names: String,
    },
    /// The size.
    #[error(transparent)]
    Size(#[from] SizeError),
    /// A level above the lab's.
    #[error(
        "level {level} is out of range; allowed: 0 to {MAX_APP_LEVEL} (the lab's levels: {LEVEL_LIMIT_WHY})"
    )]
    Level {
        /// The level given.
        level: u32,
    },
    /// An ε that is not a finite number > 0.
    #[error("ε: {0}")]
    Epsilon(#[source] CheckError),
    /// A key of `--keys` that quits the lab (`q`, Ctrl-C): there is no frame after it.
    #[error(
        "--keys: key {at} quits the lab, and render draws the lab running; leave it out (Esc only goes back)"
    )]
    Quits {
        /// The key's place in `--keys`, from 1.
        at: usize,
    },
}
