//! `riplab lab` and `riplab render`: the terminal lab, and one frame of it drawn as text.

use std::path::PathBuf;
use std::process::ExitCode;

use super::args::Select;
use super::choices::ContactName;
use super::render_args::{self, RenderArgs, RenderInput};
use super::two_bodies::{cli_error, enforcement, method_of};
use super::{CliError, checks, print, tour, usage};
use crate::check;
use crate::scenario::Scenario;
use crate::tui::bodies::BodiesApp;
use crate::tui::lab_error::LabError;
use crate::tui::{MarkerChoice, RenderExtras, TuiOptions, render_with};

/// The notes under `riplab render --help`.
pub(super) const RENDER_NOTES: &str = concat!(
    "Levels: render draws what the lab shows, levels 0 to 7 (a change at level 8 takes
seconds and gigabytes, BENCHMARKS.md: too slow for the lab; `riplab solve` goes to level 8).

",
    exit_codes!()
);

/// The terminal lab; on a two-body scenario its two-body scene, the interface discretised by
/// `contact` (mortar when None).
pub(super) fn lab(
    file: Option<PathBuf>,
    record: Option<PathBuf>,
    contact: Option<ContactName>,
    opts: TuiOptions,
) -> Result<ExitCode, CliError> {
    let scenario = Select {
        scenario: file.clone(),
        ..Select::default()
    }
    .resolve()?;
    let bodies = bodies_app(scenario.clone(), contact)?;
    let record = tour::with_terminal("the lab", record.as_deref())?;
    match bodies {
        Some(app) => crate::tui::run_bodies(app, &opts, record),
        None => crate::tui::run(scenario, file.as_deref(), &opts, record),
    }
    .map_err(|e| CliError::Failed(e.to_string()))?;
    Ok(ExitCode::SUCCESS)
}

/// The two-body scene of `scenario` with `contact` (mortar when None); None for a one-body
/// scenario, which `--contact` does not apply to.
fn bodies_app(scenario: Scenario, contact: Option<ContactName>) -> Result<Option<BodiesApp>, CliError> {
    if scenario.upper.is_none() {
        return match contact {
            Some(_) => Err(usage(
                "--contact",
                format!(
                    "applies to a two-body scenario ([upper], e.g. scenarios/patch-two-blocks.toml); {} has one body under a rigid obstacle",
                    scenario.source
                ),
            )),
            None => Ok(None),
        };
    }
    let method = method_of(contact.unwrap_or(ContactName::Mortar), &scenario);
    Ok(BodiesApp::new(scenario, method))
}

/// `riplab render` on a two-body scenario: the two-body scene with `--contact`, at the
/// scenario's ε or `--epsilon`'s (penalty or exact alone), after `--keys`, its inf-sup view
/// with `--scene infsup`. What a two-body scene does not take (a one-body scene, grading,
/// another method) is refused before any work
/// (exit 2); a solve the two-body solve refuses as bad input too, with its message; a solve
/// that fails prints the frame showing why, exit 1.
fn render_bodies(
    args: &RenderArgs,
    input: RenderInput,
    scenario: Scenario,
    (width, height): (u16, u16),
    marker: MarkerChoice,
) -> Result<ExitCode, CliError> {
    if !matches!(args.scene.as_str(), "explore" | "infsup") {
        return Err(usage(
            "--scene",
            format!(
                "the {} scene needs one body under a rigid obstacle; a two-body scenario ([upper]) has the two-body scene (--scene explore) and its inf-sup view (--scene infsup)",
                args.scene
            ),
        ));
    }
    if args.refine_edges.is_some() {
        return Err(usage(
            "--refine-edges",
            "grading is not available on a two-body scenario ([upper]) yet",
        ));
    }
    let method = match input.method {
        Some(m) => Some(m),
        None => args.method.resolve(&scenario)?,
    };
    let flag = if args.epsilon.is_some() {
        "--epsilon"
    } else {
        "the scenario's contact.epsilon"
    };
    let enforcement = enforcement(method, input.epsilon.unwrap_or(scenario.epsilon), flag, &scenario)?;
    let Some(mut app) = bodies_app(scenario, Some(args.contact.unwrap_or(ContactName::Mortar)))? else {
        return Err(CliError::Usage("a two-body scenario has an [upper] body".into()));
    };
    app.settings.enforcement = enforcement;
    app.initial.enforcement = enforcement;
    if args.scene == "infsup" {
        app.shown = crate::tui::bodies::BodiesView::InfSup;
    }
    let look = crate::tui::view::Look {
        theme: crate::tui::theme::Theme { color: true },
        marker: marker.marker(),
    };
    let (text, failure) = crate::tui::bodies::render_bodies(app, &input.keys, width, height, &look)
        .map_err(|e| CliError::Usage(e.to_string()))?;
    match failure.map(|e| cli_error(e, flag)) {
        Some(e @ CliError::Failed(_)) => {
            print(&text)?;
            Err(CliError::Failed(format!("the frame shows a failure: {e}")))
        }
        Some(e) => Err(e),
        None => {
            print(&text)?;
            Ok(ExitCode::SUCCESS)
        }
    }
}

pub(super) fn render(args: &RenderArgs, marker: MarkerChoice) -> Result<ExitCode, CliError> {
    // The size first: nothing is loaded or allocated for a frame that cannot be drawn.
    let (width, height) = crate::tui::parse_size(&args.size).map_err(|m| usage("--size", m))?;
    let input = render_args::render_input(args)?;
    let mut scenario = args.select.resolve()?;
    if scenario.upper.is_some() {
        return render_bodies(args, input, scenario, (width, height), marker);
    }
    if args.contact.is_some() {
        return Err(usage(
            "--contact",
            format!(
                "applies to a two-body scenario ([upper], e.g. scenarios/patch-two-blocks.toml); {} has one body under a rigid obstacle",
                scenario.source
            ),
        ));
    }
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
