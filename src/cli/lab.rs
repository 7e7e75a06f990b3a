//! `riplab lab` and `riplab render`: the terminal lab, and one frame of it drawn as text.

use std::path::PathBuf;
use std::process::ExitCode;

use super::args::Select;
use super::render_args::{self, RenderArgs};
use super::{CliError, checks, print, tour, usage};
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
    .resolve_one_body("lab")?;
    let record = tour::with_terminal("the lab", record.as_deref())?;
    crate::tui::run(scenario, file.as_deref(), &opts, record).map_err(|e| CliError::Failed(e.to_string()))?;
    Ok(ExitCode::SUCCESS)
}

pub(super) fn render(args: &RenderArgs, marker: MarkerChoice) -> Result<ExitCode, CliError> {
    // The size first: nothing is loaded or allocated for a frame that cannot be drawn.
    let (width, height) = crate::tui::parse_size(&args.size).map_err(|m| usage("--size", m))?;
    let input = render_args::render_input(args)?;
    let mut scenario = args.select.resolve_one_body("render")?;
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
    // The paper's problem with no level given opens as the lab opens it (`App::opening`).
    let opening = args.select.scenario.is_none() && args.select.level.is_none();
    let frame = render_with(
        &scenario,
        &args.scene,
        width,
        height,
        (!opening).then_some(scenario.level),
        Some(scenario.element),
        Some(scenario.rule),
        input.epsilon,
        &RenderExtras {
            keys: input.keys,
            marker,
            opening,
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
