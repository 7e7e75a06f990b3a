//! The command line (clap): `riplab [SCENARIO]`, `riplab solve`, and the other commands.

use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use crate::check;
use crate::contact::method::{Gamma0, MethodError};
use crate::contact::{Method, Rule};
use crate::error::SolveError;
use crate::input::ScenarioError;
use crate::mesh::Element;
use crate::report::{Format, InfSupTable, SolveReport, StudyReport, Sweep, SweepFailure, SweepRow, output};
use crate::scenario::{MAX_LEVEL, Scenario};
use crate::scheme::Scheme;
use crate::solve::{ContactParams, Discretization, check_request};
use crate::study::{Plan, ReferenceLevelError, all_ok};
use crate::tui::{MarkerChoice, TuiOptions, render_to_string};
use crate::vtu;

mod checks;
mod grading;
mod outputs;
mod tour;
pub mod values;
mod verify;

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

/// riplab's command line: the terminal lab on a scenario, or a command.
#[derive(Parser, Debug)]
#[command(name = "riplab", version, about = "A terminal laboratory for reduced-integration penalty contact (Kikuchi 1981)", after_help = EXIT_CODES)]
pub struct Cli {
    /// Scenario file (TOML) to open in the terminal lab; the paper's problem when omitted.
    pub scenario: Option<PathBuf>,
    /// Chart marker, for fonts without braille (the lab and the tour).
    #[arg(long, value_enum, default_value_t = MarkerChoice::Braille, global = true)]
    pub marker: MarkerChoice,
    /// Monochrome display (also when the NO_COLOR environment variable is set).
    #[arg(long, global = true)]
    pub no_color: bool,
    /// Where the lab's and the tour's `s` (CSV) and `S` (SVG) exports go; the current
    /// directory when omitted. Files are never overwritten.
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
    #[command(after_help = RENDER_NOTES)]
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

/// The notes under `riplab render --help`.
const RENDER_NOTES: &str = concat!(
    "Levels: render draws what the lab shows, levels 0 to 7 (",
    crate::tui::app::level_8_cost!(),
    " a change,
too slow for the lab; `riplab solve` goes to level 8).

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
    /// Penalty parameter ε > 0 (the scenario's when omitted).
    #[arg(long, value_parser = values::number)]
    pub epsilon: Option<f64>,
}

/// Which problem and discretisation: a scenario and overrides of its values.
#[derive(Args, Debug, Clone, Default)]
pub struct Select {
    /// Scenario file (TOML); the paper's problem when omitted.
    pub scenario: Option<PathBuf>,
    /// Mesh level 0..=8 (h halves with each level).
    #[arg(long, short)]
    pub level: Option<i64>,
    /// Displacement element.
    #[arg(long, short)]
    pub element: Option<Element>,
    /// Quadrature rule of the penalty term.
    #[arg(long, short)]
    pub rule: Option<Rule>,
    /// One of the paper's schemes M1–M4, or a pair like q2+gauss1 (sets element and rule).
    #[arg(long, short, conflicts_with_all = ["element", "rule"])]
    pub scheme: Option<String>,
}

/// The contact method and its parameters (docs/design.md §10).
#[derive(Args, Debug, Clone, Default)]
pub struct MethodArgs {
    /// Contact method: penalty (ε > 0), exact (multipliers, ε = 0), alm (augmented Lagrangian
    /// at ε > 0) or nitsche [default: the scenario's; with none named, --epsilon 0 is exact]
    #[arg(long, value_name = "METHOD")]
    pub method: Option<String>,
    /// Nitsche's θ: 1 (symmetric), 0 (incomplete) or -1 (skew-symmetric) [default: 1]
    #[arg(long, allow_negative_numbers = true)]
    pub theta: Option<f64>,
    /// Nitsche's γ₀ (γ = γ₀·E/h): `auto` (10·γ₀*, ten times the symmetric variant's stability
    /// threshold on the mesh and rule) or a number from 1e-8 to 1e8 [default: auto]
    #[arg(long, allow_negative_numbers = true, value_name = "auto|GAMMA0")]
    pub gamma0: Option<String>,
    /// The ALM's relative tolerance on the multiplier's change, 0 < tol < 1 [default: 1e-10]
    #[arg(long, allow_negative_numbers = true)]
    pub alm_tol: Option<f64>,
}

impl MethodArgs {
    /// The method named on the command line, else the scenario's (None when the scenario's is
    /// the one its ε implies, so that `--epsilon 0` selects `exact`), with the parameters
    /// given applied and checked.
    pub fn resolve(&self, scenario: &Scenario) -> Result<Option<Method>, CliError> {
        let fail = |e: MethodError| {
            let flag = match e.key() {
                "alm_tol" => "--alm-tol".to_string(),
                key => format!("--{key}"),
            };
            usage(&flag, e.to_string())
        };
        let gamma0 = self
            .gamma0
            .as_deref()
            .map(Gamma0::parse)
            .transpose()
            .map_err(fail)?;
        let (theta, tol) = (self.theta, self.alm_tol);
        match &self.method {
            Some(name) => Method::parse(name, theta, gamma0, tol).map(Some).map_err(fail),
            None => {
                let named = match scenario.method {
                    Method::Penalty | Method::Exact => None,
                    m => Some(m),
                };
                if theta.is_none() && gamma0.is_none() && tol.is_none() {
                    return Ok(named);
                }
                named
                    .unwrap_or(scenario.method)
                    .with(theta, gamma0, tol)
                    .map(Some)
                    .map_err(fail)
            }
        }
    }
}

/// The method and ε of a solve with `method` (from [`MethodArgs::resolve`]) at `epsilon`.
fn method_at(method: Option<Method>, epsilon: f64, flag: &str) -> Result<(Method, f64), CliError> {
    Method::resolve(method, epsilon).map_err(|e| usage(flag, e.to_string()))
}

/// The arguments of `riplab solve`.
#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("output").args(["plot", "vtu"]).multiple(true)))]
pub struct SolveArgs {
    /// The scenario, level, element and rule.
    #[command(flatten)]
    pub select: Select,
    /// The contact method and its parameters.
    #[command(flatten)]
    pub method: MethodArgs,
    /// Penalty parameter ε > 0 (0: the exact constraint); several, comma-separated, sweep on one mesh.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_parser = values::number)]
    pub epsilon: Vec<f64>,
    /// Scaled penalty: ε = κ·h/E (h the level's cell size, E Young's modulus), so that a value
    /// means the same at every level and for every material; several, comma-separated, sweep.
    #[arg(long, value_delimiter = ',', conflicts_with = "epsilon", allow_hyphen_values = true, value_parser = values::number)]
    pub kappa: Vec<f64>,
    /// Indentation depth; several, comma-separated, sweep on one mesh.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_parser = values::number)]
    pub depth: Vec<f64>,
    /// Output format (docs/design.md §7).
    #[arg(long, short, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Also write the pressure chart (p and p̄ along Γ_C) as an SVG file.
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// Also write the body with u and the stresses to FILE (.vtu) and Γ_C with p and p̄ to
    /// FILE.contact.vtu, for ParaView.
    #[arg(long, value_name = "FILE")]
    pub vtu: Option<PathBuf>,
    /// Let --plot and --vtu replace existing regular files.
    #[arg(long, requires = "output")]
    pub force: bool,
    /// Grade the mesh at the contact edges: bisect the lines around them and re-solve, N
    /// times (0 to 8), or `auto` until p̄ changes by less than 1e-3 [default: the scenario's
    /// `[mesh] refine_edges`, else 0]
    #[arg(long, value_name = "N|auto", allow_hyphen_values = true)]
    pub refine_edges: Option<String>,
}

/// The arguments of `riplab infsup`.
#[derive(Args, Debug)]
pub struct InfsupArgs {
    /// The scenario, level, element and rule.
    #[command(flatten)]
    pub select: Select,
    /// Levels, inclusive: `0..6`, `2..=4` or a single level [default: 0..4, or --level's].
    #[arg(long, conflicts_with = "level")]
    pub levels: Option<String>,
    /// Every element × rule pair (the paper's M1–M4 first).
    #[arg(long, conflicts_with_all = ["element", "rule", "scheme"])]
    pub all: bool,
    /// Output format (docs/design.md §7).
    #[arg(long, short, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// The arguments of `riplab study`.
#[derive(Args, Debug)]
pub struct StudyArgs {
    /// Scenario file (TOML); the paper's problem when omitted.
    pub scenario: Option<PathBuf>,
    /// Levels, inclusive: `0..5`, `2..=4` or a single level.
    #[arg(long, default_value = "0..5")]
    pub levels: String,
    /// Schemes: presets M1–M4 or pairs like q2+gauss1, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "M1,M2,M3,M4")]
    pub schemes: Vec<String>,
    /// The contact method and its parameters.
    #[command(flatten)]
    pub method: MethodArgs,
    /// Penalty parameter of the studied solves [default for the penalty: κ = εE/h = 1e-6 at
    /// the finest level, or the scenario's ε when smaller; for the other methods the
    /// scenario's].
    #[arg(long, value_parser = values::number)]
    pub epsilon: Option<f64>,
    /// Instead of refining: sweep these ε (comma-separated) at `--level`.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = values::number,
        requires = "level"
    )]
    pub sweep_epsilon: Vec<f64>,
    /// The level of an ε sweep (with --sweep-epsilon; a refinement study takes --levels).
    #[arg(long, requires = "sweep_epsilon")]
    pub level: Option<i64>,
    /// Level of the Q2 exact-constraint reference (default: one finer than the finest studied).
    #[arg(long)]
    pub reference_level: Option<i64>,
    /// At most this many refinements of the reference at its contact edges, made until its
    /// estimated error is a tenth of the smallest row error (0: the uniform level only).
    #[arg(long, default_value_t = 4, allow_negative_numbers = true)]
    pub reference_refinements: i64,
    /// Compute the reference even if the user's cache directory holds it, and do not store it
    /// (by default it is kept in $XDG_CACHE_HOME/riplab, ~/.cache/riplab).
    #[arg(long)]
    pub no_cache: bool,
    /// Output format (docs/design.md §7).
    #[arg(long, short, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Edge gradings to study beside the levels, comma-separated (each 0 to 8 or `auto`): a
    /// series per scheme and value [default: the scenario's `[mesh] refine_edges`, else 0]
    #[arg(
        long,
        value_delimiter = ',',
        conflicts_with = "sweep_epsilon",
        value_name = "N,…"
    )]
    pub refine_edges: Vec<String>,
}

/// Parse an inclusive level range `a..b`, `a..=b` or `a`.
pub fn parse_levels(text: &str) -> Result<Vec<u32>, String> {
    let bad = || format!("`{text}`; allowed: a level 0..={MAX_LEVEL} or a range like 0..6 (inclusive)");
    let num = |t: &str| -> Result<u32, String> {
        let v: i64 = t.trim().parse().map_err(|_| bad())?;
        check::level(v).map_err(|e| e.to_string())?;
        Ok(v as u32)
    };
    let (a, b) = match text.split_once("..") {
        Some((a, b)) => (num(a)?, num(b.trim_start_matches('='))?),
        None => {
            let v = num(text)?;
            (v, v)
        }
    };
    if a > b {
        return Err(bad());
    }
    Ok((a..=b).collect())
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
    /// The numerics failed (exit code per [`SolveError::exit_code`]).
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
    /// error's own ([`SolveError::exit_code`]).
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Scenario(_) | CliError::Usage(_) => 2,
            CliError::Solve(e) => e.exit_code(),
            CliError::Failed(_) | CliError::Output(_) => 1,
        }
    }
}

fn usage(flag: &str, msg: impl std::fmt::Display) -> CliError {
    CliError::Usage(format!("invalid value for {flag}: {msg}"))
}

impl Select {
    /// The scenario with the overrides applied and validated.
    pub fn resolve(&self) -> Result<Scenario, CliError> {
        let mut s = match &self.scenario {
            Some(path) => Scenario::load(path)?,
            None => Scenario::paper(),
        };
        if let Some(level) = self.level {
            check::level(level).map_err(|m| usage("--level", m))?;
            s.level = level as u32;
        }
        if let Some(name) = &self.scheme {
            let scheme = Scheme::parse(name).map_err(|m| usage("--scheme", m))?;
            s.element = scheme.element;
            s.rule = scheme.rule;
        }
        if let Some(e) = self.element {
            s.element = e;
        }
        if let Some(r) = self.rule {
            s.rule = r;
        }
        Ok(s)
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
    let result = match cli.command {
        Some(Command::Solve(args)) => solve(&args),
        Some(Command::Infsup(args)) => infsup(&args),
        Some(Command::Study(args)) => study(&args),
        Some(Command::Render(args)) => render(&args),
        Some(Command::Verify(args)) => verify::verify(&args),
        Some(Command::Tour(args)) => tour::tour(
            &args,
            TuiOptions {
                marker: cli.marker,
                no_color: cli.no_color,
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
            TuiOptions {
                marker: cli.marker,
                no_color: cli.no_color,
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

fn solve(args: &SolveArgs) -> Result<ExitCode, CliError> {
    let mut scenario = args.select.resolve()?;
    scenario.refine_edges = grading::refine_edges(args.refine_edges.as_deref(), &scenario)?;
    let method = args.method.resolve(&scenario)?;
    let level = scenario.level;
    let range = scenario.epsilon_range(level);
    for &e in &args.epsilon {
        check::epsilon_in(e, range).map_err(|m| usage("--epsilon", m))?;
    }
    // ε = κ·h/E: the κ range is KAPPA_RANGE whatever the level.
    let scale = scenario.h(level) / scenario.material.young;
    for &k in &args.kappa {
        check::epsilon_in(k * scale, range)
            .map_err(|m| usage("--kappa", format!("κ = {}: {m}", crate::text::num(k))))?;
    }
    for &d in &args.depth {
        check::depth(d, scenario.height).map_err(|m| usage("--depth", m))?;
    }
    if args.epsilon.len().max(args.kappa.len()) > 1 && args.depth.len() > 1 {
        return Err(CliError::Usage(
            "sweep one of --epsilon (or --kappa) and --depth at a time".into(),
        ));
    }
    let epsilons = match (args.epsilon.is_empty(), args.kappa.is_empty()) {
        (false, _) => args.epsilon.clone(),
        (true, false) => args.kappa.iter().map(|k| k * scale).collect(),
        // The scenario's ε, or for a method that needs one where the scenario has none
        // (ε = 0), an error that says so.
        (true, true) => vec![scenario.epsilon],
    };
    // Every ε with the method: `penalty` and `alm` refuse ε = 0 (before any work).
    let flag = if args.kappa.is_empty() {
        "--epsilon"
    } else {
        "--kappa"
    };
    for &e in &epsilons {
        method_at(method, e, flag)?;
    }
    let depths = if args.depth.is_empty() {
        vec![scenario.obstacle.depth()]
    } else {
        args.depth.clone()
    };
    let many = epsilons.len() > 1 || depths.len() > 1;
    if let Some(m) = method.filter(|m| !m.uses_epsilon() && epsilons.len() > 1) {
        return Err(usage(
            flag,
            format!(
                "{} does not use ε: every row of a sweep over ε would be the same solve; sweep --depth instead",
                m.name()
            ),
        ));
    }
    let mut targets = Vec::new();
    if let Some(path) = &args.plot {
        targets.push(("--plot", path.clone()));
    }
    if let Some(path) = &args.vtu {
        targets.push(("--vtu", path.clone()));
        targets.push(("--vtu's Γ_C file", vtu::contact_path(path)));
    }
    outputs::distinct(&targets)?;
    if let Some(path) = &args.plot {
        if many {
            return Err(usage("--plot", "plots one solve; a sweep has several"));
        }
        crate::plot::check_target(path, args.force).map_err(|e| plot_error(path, &e))?;
    }
    let params = |epsilon: f64, depth: f64| {
        let (method, epsilon) = Method::resolve(method, epsilon).expect("checked above");
        ContactParams {
            rule: scenario.rule,
            method,
            epsilon,
            obstacle: scenario.obstacle.with_depth(depth),
        }
    };
    // A single solve's request with no answer is refused before any assembly; in a sweep each
    // row says for itself.
    if !many {
        check_request(
            &scenario,
            level,
            scenario.element,
            &params(epsilons[0], depths[0]),
        )?;
    }
    if many && args.vtu.is_some() {
        return Err(usage("--vtu", "exports one solve; a sweep has several"));
    }
    // Before any work: an existing file is refused unless --force, and then only a regular one.
    if let Some(path) = &args.vtu {
        vtu::check_targets(path, args.force).map_err(|e| usage("--vtu", e.to_string()))?;
    }

    let disc = Discretization::of(&scenario, level, scenario.element)?;
    let instances: Vec<ContactParams> = epsilons
        .iter()
        .flat_map(|&e| depths.iter().map(move |&d| (e, d)))
        .map(|(e, d)| params(e, d))
        .collect();
    let mut rows: Vec<SweepRow> = Vec::new();
    let outcomes = grading::solve_all(&scenario, &disc, &instances, scenario.refine_edges);
    for (params, (solved, graded, passes)) in instances.iter().zip(outcomes) {
        let disc = graded.as_ref().unwrap_or(&disc);
        let sol = match solved {
            Ok(sol) => sol,
            Err(e) if many => {
                rows.push(SweepRow::Failed(SweepFailure::new(&scenario, disc, params, &e)));
                continue;
            }
            Err(e) => return Err(e.into()),
        };
        // The setting that tells the sweep's rows apart: ε where the method uses it.
        let setting = if params.method.uses_epsilon() {
            format!("ε = {:e}", params.epsilon)
        } else {
            sol.method_fields().label()
        };
        for w in &sol.warnings {
            note(&format!(
                "warning: {setting}, depth = {}: {w}",
                crate::text::num(params.obstacle.depth())
            ));
        }
        let mut report = SolveReport::new(&scenario, level, disc, &sol);
        report.refine_edges = passes;
        rows.push(SweepRow::Solved(Box::new(report)));
        if let Some(path) = &args.plot {
            let title = crate::plot::chart_title(&scenario.name, disc.mesh.element, level, &sol);
            crate::plot::pressure_svg(path, &title, &sol, scenario.half_model, args.force)
                .map_err(|e| CliError::Failed(format!("--plot {e}")))?;
        }
        if let Some(path) = &args.vtu {
            let field = sol
                .stress_field(&scenario, disc)
                .map_err(|e| CliError::Failed(format!("the stress field: {e}")))?;
            let [body, contact] = vtu::write(path, disc, &sol, &field, args.force)
                .map_err(|e| CliError::Failed(format!("--vtu {e}")))?;
            note(&format!("wrote {} and {}", shown(&body), shown(&contact)));
        }
    }
    let sweep = Sweep { rows };
    let out = match &sweep.rows[..] {
        [SweepRow::Solved(report)] if !many => output(report.as_ref(), args.format),
        _ => output(&sweep, args.format),
    };
    print(&out)?;
    let failed: Vec<String> = sweep
        .rows
        .iter()
        .filter_map(|row| match row {
            SweepRow::Solved(r) if !r.converged => Some(format!(
                "ε = {:e}, depth = {}: {}",
                r.epsilon,
                r.depth,
                r.diagnosis.as_deref().unwrap_or("not converged")
            )),
            SweepRow::Solved(_) => None,
            SweepRow::Failed(f) => Some(format!("ε = {:e}, depth = {}: {}", f.epsilon, f.depth, f.reason)),
        })
        .collect();
    if failed.is_empty() {
        Ok(ExitCode::SUCCESS)
    } else {
        Err(CliError::Failed(format!(
            "no certified result for {}",
            failed.join("; ")
        )))
    }
}

fn plot_error(path: &std::path::Path, e: &std::io::Error) -> CliError {
    let what = match e.kind() {
        std::io::ErrorKind::AlreadyExists => "exists; not overwritten (--force replaces it)".to_string(),
        _ => e.to_string(),
    };
    usage("--plot", format!("{}: {what}", shown(path)))
}

fn infsup(args: &InfsupArgs) -> Result<ExitCode, CliError> {
    let scenario = args.select.resolve()?;
    // `--level L` alone estimates that level; `--levels` a range (they exclude each other).
    let levels = match (&args.levels, args.select.level) {
        (Some(text), _) => parse_levels(text).map_err(|m| usage("--levels", m))?,
        (None, Some(_)) => vec![scenario.level],
        (None, None) => parse_levels("0..4").expect("the default levels parse"),
    };
    let pairs: Vec<(Element, Rule)> = if args.all {
        Scheme::all().into_iter().map(|s| (s.element, s.rule)).collect()
    } else {
        vec![(scenario.element, scenario.rule)]
    };
    let rows = crate::infsup::table(&scenario, &pairs, &levels)?;
    print(&output(&InfSupTable { rows }, args.format))?;
    Ok(ExitCode::SUCCESS)
}

fn study(args: &StudyArgs) -> Result<ExitCode, CliError> {
    let scenario = Select {
        scenario: args.scenario.clone(),
        ..Select::default()
    }
    .resolve()?;
    let schemes = args
        .schemes
        .iter()
        .map(|s| Scheme::parse(s).map(|s| (s.element, s.rule)))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|m| usage("--schemes", m))?;
    let method = args.method.resolve(&scenario)?;
    if let Some(m) = method.filter(|m| !m.uses_epsilon() && !args.sweep_epsilon.is_empty()) {
        return Err(usage(
            "--sweep-epsilon",
            format!(
                "{} does not use ε: its rows would not change and no rate against ε exists",
                m.name()
            ),
        ));
    }
    let levels = match args.level {
        Some(l) => {
            check::level(l).map_err(|m| usage("--level", m))?;
            vec![l as u32]
        }
        None => parse_levels(&args.levels).map_err(|m| usage("--levels", m))?,
    };
    // A penalty refinement study's default ε keeps the penalty's error below the mesh's.
    let penalty = matches!(method, None | Some(Method::Penalty)) && args.sweep_epsilon.is_empty();
    let epsilon = match args.epsilon {
        Some(e) => e,
        None if penalty => crate::penalty_error::default_epsilon(&scenario, levels[levels.len() - 1]),
        None => scenario.epsilon,
    };
    if args.epsilon.is_none() && epsilon != scenario.epsilon {
        note(&format!(
            "note: ε = {epsilon:.3e} (κ = εE/h = {:e} at level {}), not the scenario's {:e}, so that the penalty's error stays well below the mesh's (--epsilon sets it)",
            crate::penalty_error::STUDY_KAPPA,
            levels[levels.len() - 1],
            scenario.epsilon
        ));
    }
    if args.sweep_epsilon.is_empty() {
        method_at(method, epsilon, "--epsilon")?;
    }
    // ε's range depends on h: check it at the coarsest and the finest level studied.
    for &level in [levels[0], levels[levels.len() - 1]].iter() {
        let range = scenario.epsilon_range(level);
        check::epsilon_in(epsilon, range)
            .map_err(|m| usage("--epsilon", format!("at level {level}: {m}")))?;
        for &e in &args.sweep_epsilon {
            check::epsilon_in(e, range).map_err(|m| usage("--sweep-epsilon", m))?;
        }
    }
    let requested = match args.reference_level {
        Some(l) => {
            check::level(l).map_err(|m| usage("--reference-level", m))?;
            Some(l as u32)
        }
        None => None,
    };
    let reference_level = crate::study::reference_level(&levels, requested).map_err(|e| match e {
        ReferenceLevelError::NotFiner { .. } => usage("--reference-level", e),
        ReferenceLevelError::NoFinerLevel { .. } => usage("--levels", e),
    })?;
    check::integer(
        args.reference_refinements,
        0,
        i64::from(crate::study::MAX_REFINEMENTS),
    )
    .map_err(|m| usage("--reference-refinements", m))?;
    note(&format!(
        "the reference: q2 + simpson, ε = 0 (exact constraint), level {reference_level} and, for its estimated error, level {} …",
        reference_level - 1
    ));
    let dir = (!args.no_cache).then(crate::cache::default_dir).flatten();
    let mut fetch = |grid: &crate::study::ReferenceMesh| {
        let (fields, provenance) = crate::cache::fields(&scenario, grid, dir.as_deref())?;
        let what = match grid.refinements {
            0 => format!("reference level {}", grid.level),
            k => format!("reference level {} refinement {k}", grid.level),
        };
        match provenance {
            crate::cache::Provenance::Cached(path) => note(&format!(
                "{what} read from {} (computed in {:.1} s; --no-cache recomputes it)",
                shown(&path),
                fields.ms / 1e3
            )),
            other => {
                note(&format!(
                    "{what} done in {:.1} s ({} dofs)",
                    fields.ms / 1e3,
                    fields.n_dofs
                ));
                if let crate::cache::Provenance::Computed(Some(why)) = other {
                    note(&format!("warning: the reference is {why}"));
                }
            }
        }
        Ok(fields)
    };
    let refine = grading::refine_axis(&args.refine_edges, &scenario)?;
    let plan = if args.sweep_epsilon.is_empty() {
        Plan::Levels {
            levels: &levels,
            epsilon,
            refine: &refine,
        }
    } else {
        Plan::Sweep {
            level: levels[0],
            epsilons: &args.sweep_epsilon,
        }
    };
    let study = crate::study::study(
        &scenario,
        &schemes,
        method,
        plan,
        (reference_level, args.reference_refinements as u32),
        &mut fetch,
    )?;
    // The table says it in its own lines; JSON and CSV carry it in a field.
    if let (Some(why), false) = (&study.reference.stopped, args.format == Format::Table) {
        note(&format!(
            "warning: the reference's estimated error is above a tenth of the smallest row error; its refinement stopped at {}: {why}",
            study.reference.grid.refinements
        ));
    }
    print(&output(
        &StudyReport {
            scenario: &scenario.name,
            study: &study,
        },
        args.format,
    ))?;
    if args.sweep_epsilon.is_empty() {
        for row in crate::penalty_error::dominated_rows(&study.rows, scenario.material.young) {
            note(&format!("note: {row}"));
        }
    }
    let rows = study.rows;
    if all_ok(&rows) {
        Ok(ExitCode::SUCCESS)
    } else {
        let n = rows
            .iter()
            .filter(|r| r.status != crate::study::Status::Ok)
            .count();
        Err(CliError::Failed(format!(
            "{n} of {} rows have no certified result (their status and reason are in the output)",
            rows.len()
        )))
    }
}

/// The error of a lab or tour started without a terminal.
fn needs_terminal(what: &str) -> Result<(), CliError> {
    use std::io::IsTerminal;
    if std::io::stdout().is_terminal() && std::io::stdin().is_terminal() {
        return Ok(());
    }
    Err(CliError::Usage(format!(
        "{what} needs a terminal (stdin and stdout are not both one); for a frame as text use `riplab render` (e.g. `riplab render --scene explore --size 100x30`)"
    )))
}

/// The terminal lab.
fn lab(file: Option<PathBuf>, record: Option<PathBuf>, opts: TuiOptions) -> Result<ExitCode, CliError> {
    let scenario = Select {
        scenario: file.clone(),
        ..Select::default()
    }
    .resolve()?;
    let record = tour::with_terminal("the lab", record.as_deref())?;
    crate::tui::run(scenario, file.as_deref(), &opts, record).map_err(|e| CliError::Failed(e.to_string()))?;
    Ok(ExitCode::SUCCESS)
}

fn render(args: &RenderArgs) -> Result<ExitCode, CliError> {
    // The size first: nothing is loaded or allocated for a frame that cannot be drawn.
    let (width, height) = crate::tui::parse_size(&args.size).map_err(|m| usage("--size", m))?;
    let mut scenario = args.select.resolve()?;
    if let Some(method) = args.method.resolve(&scenario)? {
        scenario.method = method;
    }
    if let Some(e) = args.epsilon {
        check::positive(e)
            .and_then(|()| check::epsilon_in(e, scenario.epsilon_range(scenario.level)))
            .map_err(|m| usage("--epsilon", m))?;
    }
    checks::render_request(&scenario, &args.scene, args.epsilon)?;
    let frame = render_to_string(
        &scenario,
        &args.scene,
        width,
        height,
        Some(scenario.level),
        Some(scenario.element),
        Some(scenario.rule),
        args.epsilon,
    )
    .map_err(CliError::Usage)?;
    print(&frame.text)?;
    match frame.failure {
        Some(why) => Err(CliError::Failed(format!("the frame shows a failure: {why}"))),
        None => Ok(ExitCode::SUCCESS),
    }
}
