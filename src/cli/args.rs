//! The arguments the commands share (docs/design.md §8): the scenario and its overrides, the method
//! and its parameters, and those of `riplab solve`, `riplab infsup` and `riplab study`.

use std::path::PathBuf;

use clap::Args;

use super::choices::{ContactName, ElementName, FormatName, RuleName, choice};
use super::{CliError, usage, values};
use crate::check::{self, CheckError};
use crate::contact::method::Gamma0;
use crate::contact::{Method, Rule};
use crate::error::MethodError;
use crate::mesh::Element;
use crate::mesh::MAX_LEVEL;
use crate::output::Format;
use crate::scenario::Scenario;
use crate::scheme::Scheme;

/// Which problem and discretisation: a scenario and overrides of its values.
#[derive(Args, Debug, Clone, Default)]
pub struct Select {
    /// Scenario file (TOML); the paper's problem when omitted.
    pub scenario: Option<PathBuf>,
    /// Mesh level 0..=8 (h halves with each level).
    #[arg(long, short)]
    pub level: Option<i64>,
    /// Displacement element.
    #[arg(long, short, value_parser = choice::<ElementName, Element>())]
    pub element: Option<Element>,
    /// Quadrature rule of the penalty term.
    #[arg(long, short, value_parser = choice::<RuleName, Rule>())]
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
pub(super) fn method_at(method: Option<Method>, epsilon: f64, flag: &str) -> Result<(Method, f64), CliError> {
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
    /// Friction and the shift after the press.
    #[command(flatten)]
    pub friction: super::FrictionArgs,
    /// Penalty parameter ε > 0 (0: the exact constraint); several, comma-separated, sweep on one mesh.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_parser = values::number)]
    pub epsilon: Vec<f64>,
    /// On a two-body scenario (`[upper]`), the discretisation of the constraint across the
    /// interface (`rip` with the rule of --rule) [default: mortar]
    #[arg(long, value_enum)]
    pub contact: Option<ContactName>,
    /// Scaled penalty: ε = κ·h/E (h the level's cell size, E Young's modulus), so that a value
    /// means the same at every level and for every material; several, comma-separated, sweep.
    #[arg(long, value_delimiter = ',', conflicts_with = "epsilon", allow_hyphen_values = true, value_parser = values::number)]
    pub kappa: Vec<f64>,
    /// Indentation depth; several, comma-separated, sweep on one mesh.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_parser = values::number)]
    pub depth: Vec<f64>,
    /// Output format (docs/design.md §7).
    #[arg(long, short, value_parser = choice::<FormatName, Format>(), default_value = "table")]
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
    /// times (0 to 8), or `auto` until p̄ changes by less than 1e-3; `Nz` (1z to 8z) grades
    /// over the whole contact zone instead: Γ_C uniform across it, halved N times, the cells
    /// growing away from it and from Γ_C [default: the scenario's `[mesh] refine_edges`, else 0]
    #[arg(long, value_name = "N|Nz|auto", allow_hyphen_values = true)]
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
    /// Every element × rule pair (the paper's M1–M4 first); on a two-body scenario every rule's
    /// points and p̄ beside mortar's, mortar-dual's and NTS's spaces.
    #[arg(long, conflicts_with_all = ["element", "rule", "scheme"])]
    pub all: bool,
    /// Estimate on meshes graded at the contact edges: each scheme's own solve graded N times
    /// (or `auto`; `Nz` over the contact zone), as `solve --refine-edges` grades [default: the
    /// scenario's `[mesh] refine_edges`, else 0]
    #[arg(long, value_name = "N|Nz|auto")]
    pub refine_edges: Option<String>,
    /// Output format (docs/design.md §7).
    #[arg(long, short, value_parser = choice::<FormatName, Format>(), default_value = "table")]
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
    /// Schemes: presets M1–M4 or pairs like q2+gauss1, comma-separated [default: M1,M2,M3,M4]
    #[arg(long, value_delimiter = ',')]
    pub schemes: Vec<String>,
    /// On a two-body scenario (`[upper]`), the discretisations of the interface to study,
    /// comma-separated: nts, nts2, mortar, mortar-dual, rip (the reduced-integration penalty
    /// with the scenario's rule), as `solve --contact` [default: all five]
    #[arg(long, value_enum, value_delimiter = ',', hide_possible_values = true)]
    pub contact: Vec<ContactName>,
    /// The contact method and its parameters.
    #[command(flatten)]
    pub method: MethodArgs,
    /// Friction and the shift after the press, of every row and of the reference.
    #[command(flatten)]
    pub friction: super::FrictionArgs,
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
    /// At most this many refinements of the reference at its contact edges (default 4), made
    /// until its estimated error is a tenth of the smallest row error (0: the uniform level
    /// only)
    #[arg(long, allow_negative_numbers = true)]
    pub reference_refinements: Option<i64>,
    /// Compute the reference even if the user's cache directory holds it, and do not store it
    /// (by default it is kept in $XDG_CACHE_HOME/riplab, ~/.cache/riplab).
    #[arg(long)]
    pub no_cache: bool,
    /// Output format (docs/design.md §7).
    #[arg(long, short, value_parser = choice::<FormatName, Format>(), default_value = "table")]
    pub format: Format,
    /// Gradings to study beside the levels, comma-separated (each 0 to 8 or `auto` at the
    /// contact edges, or 1z to 8z over the contact zone, as `solve --refine-edges`): a series
    /// per scheme and value, its rows labelled `4+3e`, `4+3z` [default: the scenario's `[mesh]
    /// refine_edges`, else 0]
    #[arg(
        long,
        value_delimiter = ',',
        conflicts_with = "sweep_epsilon",
        value_name = "N,…"
    )]
    pub refine_edges: Vec<String>,
}

/// A `--levels` that is not a level or a range of levels.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LevelsError {
    /// Not `a..b`, `a..=b` or `a`, or a range that runs down.
    #[error("`{text}`; allowed: a level 0..={MAX_LEVEL} or a range like 0..6 (inclusive)")]
    Malformed {
        /// The text as given.
        text: String,
    },
    /// A level out of range.
    #[error("{0}")]
    Level(#[from] CheckError),
}

/// Parse an inclusive level range `a..b`, `a..=b` or `a`.
///
/// # Errors
///
/// Text that is not a level, a range `a..b` or `a..=b`, or a level out of range.
pub fn parse_levels(text: &str) -> Result<Vec<u32>, LevelsError> {
    let bad = || LevelsError::Malformed {
        text: text.to_string(),
    };
    let num = |t: &str| -> Result<u32, LevelsError> {
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
