//! The command line (clap): `riplab [SCENARIO]`, `riplab solve`, and the other commands.

use std::io::Write as _;
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use crate::contact::Rule;
use crate::contact::penalty::NewtonOptions;
use crate::mesh::Element;
use crate::report::{Format, SolveReport, sweep_summary};
use crate::scenario::{Scenario, ScenarioError, check};
use crate::solve::{ContactParams, Discretization, preset, solve_contact};

const EXIT_CODES: &str = "Exit codes:
  0  success
  1  the solver failed or did not converge (the output says which)
  2  bad input: a scenario file or a command-line value is invalid";

#[derive(Parser, Debug)]
#[command(name = "riplab", version, about = "A terminal laboratory for reduced-integration penalty contact (Kikuchi 1981)", after_help = EXIT_CODES, args_conflicts_with_subcommands = true)]
pub struct Cli {
    /// Scenario file (TOML); the paper's problem when omitted.
    pub scenario: Option<PathBuf>,
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Solve the penalised contact problem and print the pressures.
    #[command(after_help = EXIT_CODES)]
    Solve(SolveArgs),
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
    /// One of the paper's schemes M1–M4 (sets element and rule).
    #[arg(long, short, conflicts_with_all = ["element", "rule"])]
    pub scheme: Option<String>,
}

#[derive(Args, Debug)]
pub struct SolveArgs {
    #[command(flatten)]
    pub select: Select,
    /// Penalty parameter ε > 0; several, comma-separated, sweep on one mesh.
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub epsilon: Vec<f64>,
    /// Indentation depth; several, comma-separated, sweep on one mesh.
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub depth: Vec<f64>,
    #[arg(long, short, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// A failure of a command, with its exit code.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    #[error("{0}")]
    Scenario(#[from] ScenarioError),
    #[error("{0}")]
    Usage(String),
    #[error("{0}")]
    Solve(String),
}

impl CliError {
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Scenario(_) | CliError::Usage(_) => 2,
            CliError::Solve(_) => 1,
        }
    }
}

fn usage(flag: &str, msg: String) -> CliError {
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
            let (e, r) = preset(name)
                .ok_or_else(|| usage("--scheme", format!("`{name}`; allowed: M1, M2, M3, M4")))?;
            s.element = e;
            s.rule = r;
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
    let result = match cli.command {
        Some(Command::Solve(args)) => solve(&args),
        None => {
            let args = SolveArgs {
                select: Select {
                    scenario: cli.scenario,
                    ..Select::default()
                },
                epsilon: vec![],
                depth: vec![],
                format: Format::Table,
            };
            solve(&args)
        }
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}

fn print(out: &str) {
    let mut stdout = std::io::stdout().lock();
    // A closed pipe (e.g. `| head`) is not an error worth a panic.
    let _ = stdout.write_all(out.as_bytes());
}

fn solve(args: &SolveArgs) -> Result<ExitCode, CliError> {
    let scenario = args.select.resolve()?;
    for &e in &args.epsilon {
        check::positive(e).map_err(|m| usage("--epsilon", m))?;
    }
    for &d in &args.depth {
        check::finite(d).map_err(|m| usage("--depth", m))?;
    }
    if args.epsilon.len() > 1 && args.depth.len() > 1 {
        return Err(CliError::Usage(
            "sweep one of --epsilon and --depth at a time".into(),
        ));
    }
    let epsilons = if args.epsilon.is_empty() {
        vec![scenario.epsilon]
    } else {
        args.epsilon.clone()
    };
    let depths = if args.depth.is_empty() {
        vec![scenario.obstacle.depth()]
    } else {
        args.depth.clone()
    };
    let sweep = epsilons.len() > 1 || depths.len() > 1;

    let disc = Discretization::of(&scenario, scenario.level, scenario.element)
        .map_err(|e| CliError::Solve(e.to_string()))?;
    let mut reports = Vec::new();
    let mut previous: Option<Vec<f64>> = None;
    for &epsilon in &epsilons {
        for &depth in &depths {
            let params = ContactParams {
                rule: scenario.rule,
                epsilon,
                obstacle: scenario.obstacle.with_depth(depth),
            };
            let mut sol = solve_contact(
                &disc,
                &params,
                previous.as_deref(),
                &NewtonOptions::default(),
                &mut |_| ControlFlow::Continue(()),
            )
            .map_err(|e| CliError::Solve(e.to_string()))?;
            if reports.is_empty() {
                // The first solve pays for the mesh's work; later ones in a sweep reuse it.
                sol.timing.assembly = disc.assembly_ms;
                sol.timing.symbolic = disc.symbolic_ms;
                sol.timing.total += disc.assembly_ms + disc.symbolic_ms;
            }
            previous = Some(sol.newton.u.clone());
            reports.push(SolveReport::new(&scenario, scenario.level, &disc, &sol));
        }
    }
    let out = match (args.format, sweep) {
        (Format::Json, false) => serde_json::to_string_pretty(&reports[0]).expect("serialisable") + "\n",
        (Format::Json, true) => serde_json::to_string_pretty(&reports).expect("serialisable") + "\n",
        (Format::Csv, false) => reports[0].csv(),
        (Format::Table, false) => reports[0].table(),
        (format, true) => sweep_summary(&reports, format),
    };
    print(&out);
    let failed: Vec<String> = reports
        .iter()
        .filter(|r| !r.converged)
        .map(|r| format!("ε = {:e}, depth = {}", r.epsilon, r.depth))
        .collect();
    if failed.is_empty() {
        Ok(ExitCode::SUCCESS)
    } else {
        Err(CliError::Solve(format!(
            "Newton did not converge for {}",
            failed.join("; ")
        )))
    }
}
