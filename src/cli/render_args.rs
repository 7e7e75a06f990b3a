//! The arguments of `riplab render` ([`RenderArgs`]) and what it reads beyond the shared
//! ones: its level range (the lab's, 0 to [`MAX_APP_LEVEL`], for every level above it
//! alike), `--epsilon 0` as the exact constraint (as `--method`'s help says) and `--keys`
//! ([`crate::tui::render_keys`]).

use clap::Args;
use crossterm::event::KeyEvent;

use crate::contact::Method;
use crate::tui::app::{LEVEL_LIMIT_WHY, MAX_APP_LEVEL};
use crate::tui::render_keys::parse_keys;

use super::args::{MethodArgs, Select};
use super::choices::ContactName;
use super::{CliError, usage, values};

/// The arguments of `riplab render`.
#[derive(Args, Debug)]
#[command(mut_arg("level", |a| a.help("Mesh level 0 to 7, the lab's levels (h halves with each level)")))]
pub struct RenderArgs {
    /// The scenario, level, element and rule.
    #[command(flatten)]
    pub select: Select,
    /// The contact method and its parameters.
    #[command(flatten)]
    pub method: MethodArgs,
    /// Scene: explore, infsup, mesh, convergence (the study takes seconds) or stress.
    #[arg(long, default_value = "explore", value_parser = ["explore", "infsup", "mesh", "convergence", "stress"])]
    pub scene: String,
    /// Frame size, COLUMNSxROWS (or COLUMNS×ROWS), from 80x24 to 1000x500.
    #[arg(long, default_value = "120x40")]
    pub size: String,
    /// Penalty parameter ε > 0 (the scenario's when omitted); 0 with no --method named is the
    /// exact constraint
    #[arg(long, value_parser = values::number)]
    pub epsilon: Option<f64>,
    /// Keys applied to the lab before the frame is printed, e.g. `]]]x..` (each character a
    /// key; `<tab>` `<backtab>` `<esc>` `<enter>` `<space>` `<left>` `<right>` `<up>` `<down>`
    /// `<pageup>` `<pagedown>` `<lt>` name the others; at most 200)
    #[arg(long, default_value = "")]
    pub keys: String,
    /// Grading: the solve graded N times at the contact edges (or `auto`), or `Nz` (1z to 8z)
    /// over the contact zone, as the lab's `E` sets it [default: the scenario's `[mesh]
    /// refine_edges`, else 0]
    #[arg(long, value_name = "N|auto|Nz")]
    pub refine_edges: Option<String>,
    /// On a two-body scenario (`[upper]`), the discretisation of the constraint across the
    /// interface (`rip` with the rule of --rule) [default: mortar]
    #[arg(long, value_enum)]
    pub contact: Option<ContactName>,
}

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
