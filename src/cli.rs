//! The command line (clap): `riplab [SCENARIO]`, `riplab solve`, and the other commands.

use std::io::Write as _;
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use crate::contact::Rule;
use crate::contact::penalty::{NewtonOptions, SolveError};
use crate::infsup::{TraceCompliance, estimate};
use crate::mesh::Element;
use crate::report::{Format, InfSupRow, SolveReport, infsup_output, study_output, sweep_summary};
use crate::scenario::{MAX_LEVEL, Scenario, ScenarioError, check};
use crate::solve::{ContactParams, Discretization, preset, solve_contact};
use crate::study::{Reference, convergence, epsilon_sweep};
use crate::tui::{MarkerChoice, TuiOptions, render_to_string};

const EXIT_CODES: &str = "Exit codes:
  0  success
  1  the solver failed or did not converge (the output says which)
  2  bad input: a scenario file or a command-line value is invalid";

#[derive(Parser, Debug)]
#[command(name = "riplab", version, about = "A terminal laboratory for reduced-integration penalty contact (Kikuchi 1981)", after_help = EXIT_CODES, args_conflicts_with_subcommands = true)]
pub struct Cli {
    /// Scenario file (TOML) to open in the terminal lab; the paper's problem when omitted.
    pub scenario: Option<PathBuf>,
    /// Chart marker, for fonts without braille (the lab and the tour).
    #[arg(long, value_enum, default_value_t = MarkerChoice::Braille, global = true)]
    pub marker: MarkerChoice,
    /// Monochrome display (also when the NO_COLOR environment variable is set).
    #[arg(long, global = true)]
    pub no_color: bool,
    /// Threads for the factorisation and the dense work on Γ_C (the results do not depend on it).
    #[arg(long, global = true, default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..=256))]
    pub threads: u16,
    #[command(subcommand)]
    pub command: Option<Command>,
}

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
    /// Print one frame of the terminal lab as plain text (for logs, CI and documents).
    #[command(after_help = EXIT_CODES)]
    Render(RenderArgs),
    /// Walk through the paper's argument step by step (Space/→ next, ← back, q quit).
    #[command(after_help = EXIT_CODES)]
    Tour(TourArgs),
    /// Print a shell completion script (e.g. `riplab completions bash > ~/.local/share/bash-completion/completions/riplab`).
    Completions { shell: clap_complete::Shell },
    /// Print the man page (roff), e.g. `riplab man > riplab.1 && man ./riplab.1`.
    Man,
}

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
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub select: Select,
    /// Scene: explore, infsup or mesh.
    #[arg(long, default_value = "explore")]
    pub scene: String,
    /// Frame size, columns x rows.
    #[arg(long, default_value = "120x40")]
    pub size: String,
    /// Penalty parameter ε > 0 (the scenario's when omitted).
    #[arg(long)]
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
    /// One of the paper's schemes M1–M4 (sets element and rule).
    #[arg(long, short, conflicts_with_all = ["element", "rule"])]
    pub scheme: Option<String>,
}

#[derive(Args, Debug)]
pub struct SolveArgs {
    #[command(flatten)]
    pub select: Select,
    /// Penalty parameter ε > 0 (0: the exact constraint); several, comma-separated, sweep on one mesh.
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub epsilon: Vec<f64>,
    /// Scaled penalty: ε = κ·h/E (h the level's cell size, E Young's modulus), so that a value
    /// means the same at every level and for every material; several, comma-separated, sweep.
    #[arg(long, value_delimiter = ',', conflicts_with = "epsilon")]
    pub kappa: Vec<f64>,
    /// Indentation depth; several, comma-separated, sweep on one mesh.
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub depth: Vec<f64>,
    #[arg(long, short, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Also write the pressure chart (p and p̄ along Γ_C) as an SVG file.
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// Let --plot replace an existing file.
    #[arg(long, requires = "plot")]
    pub force: bool,
}

#[derive(Args, Debug)]
pub struct InfsupArgs {
    #[command(flatten)]
    pub select: Select,
    /// Levels, inclusive: `0..6`, `2..=4` or a single level.
    #[arg(long, default_value = "0..4")]
    pub levels: String,
    /// Every element × rule pair (the paper's M1–M4 first).
    #[arg(long, conflicts_with_all = ["element", "rule", "scheme"])]
    pub all: bool,
    #[arg(long, short, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

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
    /// Penalty parameter of the studied solves (the scenario's when omitted).
    #[arg(long)]
    pub epsilon: Option<f64>,
    /// Instead of refining: sweep these ε (comma-separated) at `--level`.
    #[arg(
        long,
        value_delimiter = ',',
        allow_negative_numbers = true,
        requires = "level"
    )]
    pub sweep_epsilon: Vec<f64>,
    /// The level of an ε sweep.
    #[arg(long)]
    pub level: Option<i64>,
    /// Level of the Q2 exact-constraint reference (default: one finer than the finest studied).
    #[arg(long)]
    pub reference_level: Option<i64>,
    #[arg(long, short, value_enum, default_value_t = Format::Table)]
    pub format: Format,
}

/// Parse a scheme: a preset M1–M4 or `element+rule`.
pub fn parse_scheme(text: &str) -> Result<(Element, Rule), String> {
    use clap::ValueEnum;
    if let Some(pair) = preset(text) {
        return Ok(pair);
    }
    let bad = || format!("`{text}`; allowed: M1, M2, M3, M4 or element+rule, e.g. q2+gauss1");
    let (e, r) = text.split_once('+').ok_or_else(bad)?;
    Ok((
        Element::from_str(e.trim(), true).map_err(|_| bad())?,
        Rule::from_str(r.trim(), true).map_err(|_| bad())?,
    ))
}

/// Parse an inclusive level range `a..b`, `a..=b` or `a`.
pub fn parse_levels(text: &str) -> Result<Vec<u32>, String> {
    let bad = || format!("`{text}`; allowed: a level 0..={MAX_LEVEL} or a range like 0..6 (inclusive)");
    let num = |t: &str| -> Result<u32, String> {
        let v: i64 = t.trim().parse().map_err(|_| bad())?;
        check::level(v)?;
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
    #[error("{0}")]
    Scenario(#[from] ScenarioError),
    #[error("{0}")]
    Usage(String),
    #[error("{0}")]
    Solve(String),
}

impl From<SolveError> for CliError {
    fn from(e: SolveError) -> Self {
        match e {
            // A combination that has no solution is a bad request, not a solver failure.
            SolveError::Kernel(_) | SolveError::TooLarge(_) => CliError::Usage(e.to_string()),
            _ => CliError::Solve(e.to_string()),
        }
    }
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
    crate::fem::set_threads(usize::from(cli.threads));
    let result = match cli.command {
        Some(Command::Solve(args)) => solve(&args),
        Some(Command::Infsup(args)) => infsup(&args),
        Some(Command::Study(args)) => study(&args),
        Some(Command::Render(args)) => render(&args),
        Some(Command::Tour(args)) => tour(
            &args,
            TuiOptions {
                marker: cli.marker,
                no_color: cli.no_color,
            },
        ),
        Some(Command::Completions { shell }) => {
            let mut cmd = <Cli as clap::CommandFactory>::command();
            let mut out = Vec::new();
            clap_complete::generate(shell, &mut cmd, "riplab", &mut out);
            print(&String::from_utf8_lossy(&out));
            Ok(ExitCode::SUCCESS)
        }
        Some(Command::Man) => {
            let mut out = Vec::new();
            match clap_mangen::Man::new(<Cli as clap::CommandFactory>::command()).render(&mut out) {
                Ok(()) => {
                    print(&String::from_utf8_lossy(&out));
                    Ok(ExitCode::SUCCESS)
                }
                Err(e) => Err(CliError::Solve(format!("man page: {e}"))),
            }
        }
        None => lab(
            cli.scenario,
            TuiOptions {
                marker: cli.marker,
                no_color: cli.no_color,
            },
        ),
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
        check::epsilon(e).map_err(|m| usage("--epsilon", m))?;
    }
    for &k in &args.kappa {
        check::epsilon(k).map_err(|m| usage("--kappa", m))?;
    }
    for &d in &args.depth {
        check::finite(d).map_err(|m| usage("--depth", m))?;
    }
    if args.epsilon.len().max(args.kappa.len()) > 1 && args.depth.len() > 1 {
        return Err(CliError::Usage(
            "sweep one of --epsilon (or --kappa) and --depth at a time".into(),
        ));
    }
    let scale = scenario.h(scenario.level) / scenario.material.young;
    let epsilons = match (args.epsilon.is_empty(), args.kappa.is_empty()) {
        (false, _) => args.epsilon.clone(),
        (true, false) => args.kappa.iter().map(|k| k * scale).collect(),
        (true, true) => vec![scenario.epsilon],
    };
    let depths = if args.depth.is_empty() {
        vec![scenario.obstacle.depth()]
    } else {
        args.depth.clone()
    };
    let sweep = epsilons.len() > 1 || depths.len() > 1;
    if sweep && args.plot.is_some() {
        return Err(usage("--plot", "plots one solve; a sweep has several".into()));
    }

    let disc = Discretization::of(&scenario, scenario.level, scenario.element).map_err(CliError::from)?;
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
            .map_err(CliError::from)?;
            if reports.is_empty() {
                // The first solve pays for the mesh's work; later ones in a sweep reuse it.
                sol.timing.include_mesh_work(&disc);
            }
            previous = Some(sol.newton.forces.clone());
            reports.push(SolveReport::new(&scenario, scenario.level, &disc, &sol));
            if let Some(path) = &args.plot {
                let title = crate::plot::chart_title(&scenario.name, disc.mesh.element, scenario.level, &sol);
                crate::plot::pressure_svg(path, &title, &sol, scenario.half_model, args.force)
                    .map_err(|e| CliError::Usage(format!("--plot {}: {e}", path.display())))?;
            }
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
        .map(|r| {
            format!(
                "ε = {:e}, depth = {}: {}",
                r.epsilon,
                r.depth,
                r.diagnosis.as_deref().unwrap_or("not converged")
            )
        })
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

/// Element × rule pairs: the paper's schemes first, then the others.
fn all_pairs() -> Vec<(Element, Rule)> {
    let mut pairs: Vec<(Element, Rule)> = ["M1", "M2", "M3", "M4"]
        .iter()
        .filter_map(|m| preset(m))
        .collect();
    for e in Element::ALL {
        for r in Rule::ALL {
            if !pairs.contains(&(e, r)) {
                pairs.push((e, r));
            }
        }
    }
    pairs
}

fn infsup(args: &InfsupArgs) -> Result<ExitCode, CliError> {
    let scenario = args.select.resolve()?;
    let levels = parse_levels(&args.levels).map_err(|m| usage("--levels", m))?;
    let pairs = if args.all {
        all_pairs()
    } else {
        vec![(scenario.element, scenario.rule)]
    };
    let mut rows = Vec::new();
    for element in Element::ALL
        .into_iter()
        .filter(|e| pairs.iter().any(|p| p.0 == *e))
    {
        for &level in &levels {
            let t = std::time::Instant::now();
            let disc = Discretization::of(&scenario, level, element).map_err(CliError::from)?;
            let compliance = TraceCompliance::new(&disc).map_err(CliError::Solve)?;
            let shared_ms = t.elapsed().as_secs_f64() * 1e3;
            for &(_, rule) in pairs.iter().filter(|p| p.0 == element) {
                let t = std::time::Instant::now();
                let est = estimate(&disc, &compliance, rule);
                let rule_ms = t.elapsed().as_secs_f64() * 1e3;
                rows.push(InfSupRow::new(level, element, rule, est, shared_ms, rule_ms));
            }
        }
    }
    let order = |r: &InfSupRow| {
        pairs
            .iter()
            .position(|p| p.0.name() == r.element && p.1.name() == r.rule)
    };
    rows.sort_by_key(|r| (order(r), r.level));
    print(&infsup_output(&rows, args.format));
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
        .map(|s| parse_scheme(s))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|m| usage("--schemes", m))?;
    let epsilon = args.epsilon.unwrap_or(scenario.epsilon);
    check::epsilon(epsilon).map_err(|m| usage("--epsilon", m))?;
    for &e in &args.sweep_epsilon {
        check::epsilon(e).map_err(|m| usage("--sweep-epsilon", m))?;
    }
    let levels = match args.level {
        Some(l) if !args.sweep_epsilon.is_empty() => {
            check::level(l).map_err(|m| usage("--level", m))?;
            vec![l as u32]
        }
        _ => parse_levels(&args.levels).map_err(|m| usage("--levels", m))?,
    };
    let finest = *levels.iter().max().expect("at least one level");
    let reference_level = match args.reference_level {
        Some(l) => {
            check::level(l).map_err(|m| usage("--reference-level", m))?;
            if (l as u32) <= finest {
                return Err(usage(
                    "--reference-level",
                    format!("{l} must be finer than the finest studied level {finest}"),
                ));
            }
            l as u32
        }
        None => (finest + 1).min(MAX_LEVEL),
    };
    if reference_level <= finest {
        return Err(usage(
            "--levels",
            format!(
                "the reference needs a level finer than {finest}; allowed up to {}",
                MAX_LEVEL - 1
            ),
        ));
    }
    eprintln!("computing the reference: q2 + simpson, ε = 0 (exact constraint), level {reference_level} …");
    let reference = Reference::compute(&scenario, reference_level)?;
    eprintln!(
        "reference done in {:.1} s ({} dofs)",
        reference.ms / 1e3,
        reference.n_dofs
    );
    let rows = if args.sweep_epsilon.is_empty() {
        convergence(&scenario, &reference, &schemes, &levels, epsilon)?
    } else {
        epsilon_sweep(&scenario, &reference, &schemes, levels[0], &args.sweep_epsilon)?
    };
    print(&study_output(&scenario.name, &reference, &rows, args.format));
    Ok(ExitCode::SUCCESS)
}

/// The terminal lab.
fn lab(scenario: Option<PathBuf>, opts: TuiOptions) -> Result<ExitCode, CliError> {
    let scenario = Select {
        scenario,
        ..Select::default()
    }
    .resolve()?;
    crate::tui::run(scenario, opts).map_err(|e| CliError::Solve(format!("terminal: {e}")))?;
    Ok(ExitCode::SUCCESS)
}

fn render(args: &RenderArgs) -> Result<ExitCode, CliError> {
    let scenario = args.select.resolve()?;
    let bad_size = || {
        usage(
            "--size",
            format!(
                "`{}`; allowed: COLUMNSxROWS, e.g. 120x40 (at least 80x24)",
                args.size
            ),
        )
    };
    let (w, h) = args.size.split_once('x').ok_or_else(bad_size)?;
    let (width, height): (u16, u16) = (
        w.trim().parse().map_err(|_| bad_size())?,
        h.trim().parse().map_err(|_| bad_size())?,
    );
    if let Some(e) = args.epsilon {
        check::positive(e).map_err(|m| usage("--epsilon", m))?;
    }
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
    print(&frame);
    Ok(ExitCode::SUCCESS)
}

fn tour(args: &TourArgs, opts: TuiOptions) -> Result<ExitCode, CliError> {
    use crate::tui::tour::{Tour, auto_interval, run_tour};
    let scenario = Select {
        scenario: args.scenario.clone(),
        ..Select::default()
    }
    .resolve()?;
    let tour = match &args.tour {
        Some(path) => Tour::load(path)?,
        None => Tour::paper(),
    };
    if let Some(seconds) = args.auto {
        auto_interval(seconds).map_err(|m| usage("--auto", m))?;
    }
    let tour = tour.with_scenario(scenario).map_err(CliError::Usage)?;
    run_tour(tour, opts, args.auto).map_err(|e| CliError::Solve(format!("terminal: {e}")))?;
    Ok(ExitCode::SUCCESS)
}
