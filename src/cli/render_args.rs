//! What `riplab render` reads beyond the shared arguments: its level range (the lab's, 0 to
//! [`MAX_APP_LEVEL`], for every level above it alike), `--epsilon 0` as the exact constraint
//! (as `--method`'s help says) and `--keys` ([`crate::tui::render_keys`]).

use crossterm::event::KeyEvent;

use crate::contact::Method;
use crate::tui::app::{LEVEL_LIMIT_WHY, MAX_APP_LEVEL};
use crate::tui::render_keys::parse_keys;

use super::{CliError, RenderArgs, usage};

/// What `render` takes from its arguments before the scenario is read: the keys, and the ε
/// and method `--epsilon` implies (`--epsilon 0` with no method named: `exact`, no ε).
pub(super) struct RenderInput {
    /// The keys to apply before the frame is printed.
    pub keys: Vec<KeyEvent>,
    /// The penalty's ε, if given (and not the exact constraint's 0).
    pub epsilon: Option<f64>,
    /// `exact`, when `--epsilon 0` asked for it.
    pub method: Option<Method>,
}

/// Check `render`'s level against the lab's range and read its keys and ε.
pub(super) fn render_input(args: &RenderArgs) -> Result<RenderInput, CliError> {
    if let Some(level) = args.select.level.filter(|&l| l > i64::from(MAX_APP_LEVEL)) {
        return Err(usage(
            "--level",
            format!(
                "{level} is out of range; allowed: 0 to {MAX_APP_LEVEL} (the lab's levels: {LEVEL_LIMIT_WHY})"
            ),
        ));
    }
    let keys = parse_keys(&args.keys).map_err(|e| CliError::Usage(e.to_string()))?;
    let exact = args.epsilon == Some(0.0) && args.method.method.is_none();
    Ok(RenderInput {
        keys,
        epsilon: args.epsilon.filter(|_| !exact),
        method: exact.then_some(Method::Exact),
    })
}
