//! `riplab tour`: the guided tour in the terminal (recorded with `--record`), its handout
//! (`--handout DIR`) and the check of a tour file (`--check FILE`), the last two without a
//! terminal.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;

use crate::tui::TuiOptions;
use crate::tui::record::{CastFile, RecordError};
use crate::tui::tour::handout::{HandoutError, write_handout};
use crate::tui::tour::listing::listing;
use crate::tui::tour::{Tour, auto_interval, run_tour};

use super::{CliError, Select, needs_terminal, note, print, usage};

/// The arguments of `riplab tour`.
#[derive(Args, Debug)]
pub struct TourArgs {
    /// Scenario for the steps that name none; the paper's problem when omitted.
    pub scenario: Option<PathBuf>,
    /// A tour file (TOML; see tours/paper.toml); the embedded paper tour when omitted.
    #[arg(long)]
    pub tour: Option<PathBuf>,
    /// Advance by itself every SECONDS (for a projector); stops at the last step.
    #[arg(long, value_name = "SECONDS")]
    pub auto: Option<f64>,
    /// Record the tour as an asciicast v2 file (asciinema's format; a new file, never
    /// replacing one), with a marker at each step (its title) and each change of scene.
    #[arg(long, value_name = "FILE.cast", conflicts_with_all = ["handout", "check"])]
    pub record: Option<PathBuf>,
    /// Write a handout instead of running the tour: each step's screen as text
    /// (step-01.txt…), its scene's chart as SVG (step-01.svg…; none for a two-body step, whose
    /// screen draws its interface pressure) and an index.md, into DIR (created if missing; it
    /// must be empty). No terminal needed.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["auto", "check"])]
    pub handout: Option<PathBuf>,
    /// The handout's frame size, COLUMNSxROWS, from 80x24 to 1000x500.
    #[arg(long, default_value = "100x30", requires = "handout")]
    pub size: String,
    /// Validate the tour file FILE and list its steps (scene, level, scheme, method, title),
    /// without a terminal; exit 2 with the file, line and key of an error.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["tour", "auto"])]
    pub check: Option<PathBuf>,
}

/// `riplab tour`.
pub(super) fn tour(args: &TourArgs, opts: TuiOptions) -> Result<ExitCode, CliError> {
    // The size first: nothing is loaded or solved for frames that cannot be drawn.
    let size = match &args.handout {
        Some(_) => Some(crate::tui::parse_size(&args.size).map_err(|m| usage("--size", m))?),
        None => None,
    };
    let scenario = Select {
        scenario: args.scenario.clone(),
        ..Select::default()
    }
    .resolve()?;
    let tour = match args.check.as_ref().or(args.tour.as_ref()) {
        Some(path) => Tour::load(path)?,
        None => Tour::paper(),
    };
    if let Some(seconds) = args.auto {
        auto_interval(seconds).map_err(|m| usage("--auto", m))?;
    }
    let tour = tour
        .with_scenario(scenario)
        .map_err(|e| CliError::Usage(e.to_string()))?;
    if args.check.is_some() {
        // A graded step the lab would refuse for its memory is refused here too.
        tour.graded_fits().map_err(|(step, e)| {
            CliError::Usage(format!(
                "{}: step {step}: {e}",
                crate::text::sanitize(&tour.source)
            ))
        })?;
        print(&listing(&tour))?;
        return Ok(ExitCode::SUCCESS);
    }
    if let (Some(dir), Some((width, height))) = (&args.handout, size) {
        return handout(&tour, dir, width, height);
    }
    let record = with_terminal("the tour", args.record.as_deref())?;
    run_tour(tour, &opts, args.auto, record).map_err(|e| CliError::Failed(e.to_string()))?;
    Ok(ExitCode::SUCCESS)
}

/// `--handout DIR`: the files, then a line saying where they are.
fn handout(tour: &Tour, dir: &Path, width: u16, height: u16) -> Result<ExitCode, CliError> {
    let files = write_handout(tour, dir, width, height, |done, all| {
        note(&format!("step {done}/{all} written"));
    })
    .map_err(|e| match e {
        e @ (HandoutError::Directory { .. } | HandoutError::TooLarge { .. }) => usage("--handout", e),
        e @ HandoutError::Memory { .. } => CliError::Usage(format!("handout: {e}")),
        other => CliError::Failed(format!("handout: {other}")),
    })?;
    let index = files.last().map(|p| p.display().to_string()).unwrap_or_default();
    print(&format!(
        "wrote {} (the index) and {} step files\n",
        crate::text::sanitize(&index),
        files.len().saturating_sub(1)
    ))?;
    Ok(ExitCode::SUCCESS)
}

/// The recording's file (`--record`), created before anything else is checked, so that an
/// existing file or a bad path is said first (bad input, exit 2); then the check that `what`
/// has a terminal, which removes the file again (still empty) if not.
pub(super) fn with_terminal(what: &str, record: Option<&Path>) -> Result<Option<CastFile>, CliError> {
    let cast = record
        .map(CastFile::create)
        .transpose()
        .map_err(|e: RecordError| usage("--record", e))?;
    if let Err(e) = needs_terminal(what) {
        if let Some(cast) = cast {
            let path = cast.path().to_path_buf();
            drop(cast);
            let _ = std::fs::remove_file(path);
        }
        return Err(e);
    }
    Ok(cast)
}
