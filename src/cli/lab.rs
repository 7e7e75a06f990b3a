//! `riplab lab` and `riplab render`: the terminal lab, and one frame of it drawn as text.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use super::args::{MethodArgs, Select};
use super::{CliError, checks, print, render_args, tour, usage, values};
use crate::check;
use crate::tui::lab_error::LabError;
use crate::tui::{MarkerChoice, RenderExtras, TuiOptions, render_with};

/// The notes under `riplab render --help`.
pub(super) const RENDER_NOTES: &str = concat!(
    "Levels: render draws what the lab shows, levels 0 to 7 (a change at level 8 takes
seconds and gigabytes, BENCHMARKS.md: too slow for the lab; `riplab solve` goes to level 8).

",
    exit_codes!()
);

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
}

/// The terminal lab.
pub(super) fn lab(
    file: Option<PathBuf>,
    record: Option<PathBuf>,
    opts: TuiOptions,
) -> Result<ExitCode, CliError> {
    let scenario = Select {
        scenario: file.clone(),
        ..Select::default()
    }
    .resolve()?;
    let record = tour::with_terminal("the lab", record.as_deref())?;
    crate::tui::run(scenario, file.as_deref(), &opts, record).map_err(|e| CliError::Failed(e.to_string()))?;
    Ok(ExitCode::SUCCESS)
}

pub(super) fn render(args: &RenderArgs, marker: MarkerChoice) -> Result<ExitCode, CliError> {
    // The size first: nothing is loaded or allocated for a frame that cannot be drawn.
    let (width, height) = crate::tui::parse_size(&args.size).map_err(|m| usage("--size", m))?;
    let input = render_args::render_input(args)?;
    let mut scenario = args.select.resolve()?;
    let grading = super::grading::refine_edges(args.refine_edges.as_deref(), &scenario)?;
    scenario.set_grading(grading);
    if let Some(method) = input
        .method
        .map_or_else(|| args.method.resolve(&scenario), |m| Ok(Some(m)))?
    {
        scenario.method = method;
    }
    if let Some(e) = input.epsilon {
        check::positive(e)
            .and_then(|()| check::epsilon_in(e, scenario.epsilon_range(scenario.level)))
            .map_err(|m| usage("--epsilon", m))?;
    }
    checks::render_request(&scenario, &args.scene, input.epsilon)?;
    let frame = render_with(
        &scenario,
        &args.scene,
        width,
        height,
        Some(scenario.level),
        Some(scenario.element),
        Some(scenario.rule),
        input.epsilon,
        &RenderExtras {
            keys: input.keys,
            marker,
        },
    )
    .map_err(|e| CliError::Usage(e.to_string()))?;
    match frame.failure {
        // A request the solve refuses as bad input is refused as `solve` refuses it: its
        // message, exit 2, no frame (STABILITY.md).
        Some(LabError::Solve(e)) if e.is_input() => Err(CliError::Solve(e)),
        Some(why) => {
            print(&frame.text)?;
            Err(CliError::Failed(format!("the frame shows a failure: {why}")))
        }
        None => {
            print(&frame.text)?;
            Ok(ExitCode::SUCCESS)
        }
    }
}
