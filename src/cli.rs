//! The command line (clap): `riplab [SCENARIO]`, `riplab solve`, and the other commands.

use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use crate::error::SolveError;
use crate::input::ScenarioError;
use crate::tui::{MarkerChoice, TuiOptions};
use choices::{ContactName, MarkerName, choice};

mod checks;
mod choices;
mod friction_args;
mod grading;
#[cfg(test)]
mod lab_help;
mod outputs;
mod render_args;
mod tour;
pub mod values;
mod verify;

pub use friction_args::FrictionArgs;
pub use tour::TourArgs;

/// The exit codes, as every `--help` shows them (a macro, so that other notes can extend it).
macro_rules! exit_codes {
    () => {
        "Exit codes:
  0  success
  1  the solver failed or did not converge, or a row of a study or sweep has no result
     (the output says which), or the output could not be written
  2  bad input: a scenario file or a command-line value is invalid"
    };
}
const EXIT_CODES: &str = exit_codes!();

mod args;
mod infsup;
mod lab;
mod solve;
mod study;
mod two_bodies;
pub use args::{InfsupArgs, Select, SolveArgs, StudyArgs};
use infsup::infsup;
use lab::{RENDER_NOTES, lab, render};
pub use render_args::RenderArgs;
use solve::solve;
use study::study;
#[cfg(feature = "fuzzing")]
pub use {args::parse_levels, values::number};

/// riplab's command line: the terminal lab on a scenario, or a command.
#[derive(Parser, Debug)]
#[command(name = "riplab", version, about = "A terminal laboratory for reduced-integration penalty contact (Kikuchi 1981)", after_help = EXIT_CODES)]
pub struct Cli {
    /// Scenario file (TOML) to open in the terminal lab; the paper's problem when omitted.
    pub scenario: Option<PathBuf>,
    /// Chart marker, for fonts without braille (the lab and the tour).
    #[arg(long, value_parser = choice::<MarkerName, MarkerChoice>(), default_value = "braille", global = true)]
    pub marker: MarkerChoice,
    /// Monochrome display (also when the NO_COLOR environment variable is set).
    #[arg(long, global = true)]
    pub no_color: bool,
    /// No mouse in the lab and the tour (the terminal keeps its own selection of text); with
    /// it, a click on a tab changes the scene, the wheel scrolls the help and the log, and a
    /// click on the pressure chart places the cursor.
    #[arg(long, global = true)]
    pub no_mouse: bool,
    /// Where the lab's and the tour's `s` (CSV), `S` (SVG) and `v` (VTU) exports go; the
    /// current directory when omitted. Files are never overwritten.
    #[arg(long, global = true, value_name = "DIR")]
    pub export_dir: Option<PathBuf>,
    /// Threads for the assembly, the factorisation and the dense work on Γ_C [default: the
    /// cores available]. Meshes of 50,000 unknowns or more are factorised as two halves, side
    /// by side from 2 threads; every result has the same bits for any thread count.
    #[arg(long, global = true, value_parser = clap::value_parser!(u16).range(1..=256))]
    pub threads: Option<u16>,
    /// Record the lab as an asciicast v2 file (asciinema's format; a new file, never
    /// replacing one), with a marker at each change of scene.
    #[arg(long, value_name = "FILE.cast")]
    pub record: Option<PathBuf>,
    /// The tour file to which the lab's `T` adds the screen as a step (created if missing,
    /// added to only if it is a valid tour) [default: riplab-tour.toml in the export directory]
    #[arg(long, value_name = "FILE")]
    pub tour_out: Option<PathBuf>,
    /// On a two-body scenario (`[upper]`), the lab's discretisation across the interface to
    /// start with (`n` cycles them; `rip` with the scenario's rule) [default: mortar]
    #[arg(long, value_enum)]
    pub contact: Option<ContactName>,
    /// The command; None opens the terminal lab.
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// riplab's commands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Solve the penalised contact problem and print the pressures.
    #[command(after_help = EXIT_CODES)]
    Solve(SolveArgs),
    /// Estimate the inf-sup constants β_h of (13) and β̄_h of (21) over mesh levels.
    #[command(after_help = EXIT_CODES)]
    Infsup(InfsupArgs),
    /// Errors and rates of every scheme against an exact-constraint reference, with run times.
    #[command(after_help = EXIT_CODES)]
    Study(StudyArgs),
    /// Grade a pack of verification cases against closed-form and published answers (exit 1
    /// when a check is NOOK).
    #[command(after_help = EXIT_CODES)]
    Verify(verify::VerifyArgs),
    /// Print one frame of the terminal lab as plain text (for logs, CI and documents).
    #[command(after_help = crate::tui::keys::with_lab_keys(RENDER_NOTES))]
    Render(RenderArgs),
    /// Walk through the paper's argument step by step (Space/→ next, ← back, q quit).
    #[command(after_help = EXIT_CODES)]
    Tour(TourArgs),
    /// Print a shell completion script (e.g. `riplab completions bash > ~/.local/share/bash-completion/completions/riplab`).
    Completions {
        /// The shell to complete for.
        shell: clap_complete::Shell,
    },
    /// Print the man page (roff), e.g. `riplab man > riplab.1 && man ./riplab.1`.
    Man,
}

/// A failure of a command, with its exit code.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// A scenario file that cannot be read or is invalid (exit 2).
    #[error("{0}")]
    Scenario(#[from] ScenarioError),
    /// A command-line value out of range or inconsistent (exit 2).
    #[error("{0}")]
    Usage(String),
    /// The numerics failed (exit 2 when [`SolveError::is_input`], else 1).
    #[error("{0}")]
    Solve(#[from] SolveError),
    /// The command ran but some of what it was asked for has no result (rows of a study or a
    /// sweep, a terminal that failed).
    #[error("{0}")]
    Failed(String),
    /// The output could not be written (exit 1).
    #[error("cannot write the output: {0}")]
    Output(std::io::Error),
}

impl CliError {
    /// The process's exit code (docs/design.md §8): 2 for bad input, 1 for a failure; a solve
    /// error's by whether the input was at fault ([`SolveError::is_input`]).
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Scenario(_) | CliError::Usage(_) => 2,
            CliError::Solve(e) if e.is_input() => 2,
            CliError::Solve(_) => 1,
            CliError::Failed(_) | CliError::Output(_) => 1,
        }
    }
}

fn usage(flag: &str, msg: impl std::fmt::Display) -> CliError {
    CliError::Usage(format!("invalid value for {flag}: {msg}"))
}

/// Parse the command line and run it; a parse error is printed plain and sanitised (clap echoes
/// the values it refuses, which may hold escape sequences), with clap's exit code (2).
pub fn main() -> ExitCode {
    match Cli::try_parse() {
        Ok(cli) => run(cli),
        Err(e) if e.use_stderr() => {
            let text = crate::text::sanitize_lines(&e.render().to_string());
            // A closed stderr cannot be told about itself: the exit code stands.
            let _ = write!(std::io::stderr().lock(), "{text}");
            ExitCode::from(e.exit_code().clamp(0, 255) as u8)
        }
        Err(e) => e.exit(),
    }
}

/// Run the command line; returns the process exit code.
pub fn run(cli: Cli) -> ExitCode {
    // The cores available by default, at most 256 as `--threads`.
    let threads = cli
        .threads
        .map_or_else(|| crate::fem::available_threads().min(256), usize::from);
    crate::fem::set_threads(threads);
    if let (Some(path), Some(_)) = (&cli.scenario, &cli.command) {
        note(&format!(
            "error: {} before the command is the lab's scenario; a command takes its scenario after its name (e.g. `riplab solve FILE`)",
            shown(path)
        ));
        return ExitCode::from(2);
    }
    if let (Some(_), Some(_)) = (&cli.contact, &cli.command) {
        note(
            "error: --contact before the command is the lab's; a command takes its own after its name (e.g. `riplab solve FILE --contact nts`)",
        );
        return ExitCode::from(2);
    }
    let result = match cli.command {
        Some(Command::Solve(args)) => solve(&args),
        Some(Command::Infsup(args)) => infsup(&args),
        Some(Command::Study(args)) => study(&args),
        Some(Command::Render(args)) => render(&args, cli.marker),
        Some(Command::Verify(args)) => verify::verify(&args),
        Some(Command::Tour(args)) => tour::tour(
            &args,
            TuiOptions {
                marker: cli.marker,
                no_color: cli.no_color,
                no_mouse: cli.no_mouse,
                export_dir: cli.export_dir.clone(),
                tour_out: None,
            },
        ),
        Some(Command::Completions { shell }) => {
            let mut cmd = <Cli as clap::CommandFactory>::command();
            let mut out = Vec::new();
            clap_complete::generate(shell, &mut cmd, "riplab", &mut out);
            print(&String::from_utf8_lossy(&out)).map(|()| ExitCode::SUCCESS)
        }
        Some(Command::Man) => {
            let mut out = Vec::new();
            match clap_mangen::Man::new(<Cli as clap::CommandFactory>::command()).render(&mut out) {
                Ok(()) => print(&String::from_utf8_lossy(&out)).map(|()| ExitCode::SUCCESS),
                Err(e) => Err(CliError::Failed(format!("man page: {e}"))),
            }
        }
        None => lab(
            cli.scenario,
            cli.record,
            cli.contact,
            TuiOptions {
                marker: cli.marker,
                no_color: cli.no_color,
                no_mouse: cli.no_mouse,
                export_dir: cli.export_dir.clone(),
                tour_out: cli.tour_out,
            },
        ),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            note(&format!("error: {e}"));
            ExitCode::from(e.exit_code())
        }
    }
}

/// Write `out` to standard output. A reader that closed the pipe (`| head`) has taken what it
/// wanted: that is not an error. Any other failure (a full disk, `> /dev/full`) is.
fn print(out: &str) -> Result<(), CliError> {
    let mut stdout = std::io::stdout().lock();
    match stdout.write_all(out.as_bytes()).and_then(|()| stdout.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(CliError::Output(e)),
        _ => Ok(()),
    }
}

/// A line on standard error (progress, warnings, the final error). A closed or full stderr
/// cannot be told about itself, and is no reason to stop: the line is dropped.
fn note(line: &str) {
    let line = crate::text::sanitize_lines(line);
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// A path as a message shows it: sanitised (a name may hold escapes, bidi controls or a
/// line break, from the command line or the environment).
fn shown(path: &std::path::Path) -> String {
    crate::text::sanitize(&path.display().to_string()).into_owned()
}

/// The error of a lab or tour started without a terminal, or on one that cannot show its
/// escape sequences (TERM=dumb).
fn needs_terminal(what: &str) -> Result<(), CliError> {
    use std::io::IsTerminal;
    if !(std::io::stdout().is_terminal() && std::io::stdin().is_terminal()) {
        return Err(CliError::Usage(format!(
            "{what} needs a terminal (stdin and stdout are not both one); for a frame as text use `riplab render` (e.g. `riplab render --scene explore --size 100x30`)"
        )));
    }
    // A terminal that cannot move its cursor (Emacs' shell, a plain serial console) would
    // show the escape sequences as text.
    if std::env::var_os("TERM").is_some_and(|t| t == "dumb") {
        return Err(CliError::Usage(format!(
            "{what} draws with escape sequences, and TERM=dumb says this terminal cannot show them; run it in a terminal emulator (TERM=xterm-256color or the like), or print a frame as text with `riplab render` (e.g. `riplab render --scene explore --size 100x30`)"
        )));
    }
    Ok(())
}
