//! `riplab solve` on a two-body scenario (`[upper]`, docs/design.md §12): the interface
//! discretised by `--contact`, the penalty (ε > 0) or the exact multipliers (ε = 0), printed as
//! an [`InterfaceReport`]. What a two-body solve does not take is refused before any work (exit 2);
//! a solve that does not converge exits 1.

use std::process::ExitCode;
use std::time::Instant;

use super::args::{SolveArgs, method_at};
use super::choices::ContactName;
use super::{CliError, print, usage};
use crate::check;
use crate::contact::Method;
use crate::contact::interface::InterfaceMethod;
use crate::contact::interface::solve::{BodiesError, Enforcement};
use crate::output::{InterfaceReport, output};
use crate::scenario::Scenario;
use crate::scenario::upper::TwoBodies;

/// The discretisation `--contact` names, `rip` with the scenario's rule (or --rule's).
pub(super) fn method_of(name: ContactName, scenario: &Scenario) -> InterfaceMethod {
    match name {
        ContactName::Nts => InterfaceMethod::Nts,
        ContactName::Nts2 => InterfaceMethod::Nts2,
        ContactName::Mortar => InterfaceMethod::Mortar,
        ContactName::MortarDual => InterfaceMethod::MortarDual,
        ContactName::Rip => InterfaceMethod::Rip(scenario.rule),
    }
}

/// Refuse the flags a two-body solve does not take.
fn refuse_one_body_flags(args: &SolveArgs, scenario: &Scenario) -> Result<(), CliError> {
    let two = "a two-body scenario ([upper])";
    let given: [(&str, bool, &str); 6] = [
        (
            "--depth",
            !args.depth.is_empty(),
            "the upper body's top is pressed `[upper] displacement`",
        ),
        ("--kappa", !args.kappa.is_empty(), "give --epsilon"),
        ("--plot", args.plot.is_some(), "not available yet"),
        ("--vtu", args.vtu.is_some(), "not available yet"),
        (
            "--refine-edges",
            args.refine_edges.is_some(),
            "grading is not available yet",
        ),
        ("--epsilon", args.epsilon.len() > 1, "one ε at a time (no sweep)"),
    ];
    if let Some((flag, _, why)) = given.iter().find(|g| g.1) {
        return Err(usage(flag, format!("does not apply to {two}: {why}")));
    }
    let frictions = args.friction.resolve(scenario)?;
    if frictions.len() > 1 || frictions[0].is_on() {
        return Err(usage(
            "--friction",
            format!("friction is not available on {two} yet"),
        ));
    }
    Ok(())
}

/// The CLI's error of a two-body solve: bad input exits 2, a failed solve 1.
pub(super) fn cli_error(e: BodiesError, epsilon_flag: &str) -> CliError {
    match e {
        BodiesError::Solve(e) => CliError::Solve(e),
        BodiesError::Epsilon { .. } => usage(epsilon_flag, e),
        BodiesError::NotUnique { .. } | BodiesError::Coupling(_) | BodiesError::OneBody => {
            CliError::Usage(e.to_string())
        }
        BodiesError::Mismatch(_)
        | BodiesError::NotConverged(_)
        | BodiesError::NonFinite(_)
        | BodiesError::Unbalanced { .. } => CliError::Failed(e.to_string()),
    }
}

/// How `method` (None: by ε) at `epsilon` (given by `flag`) enforces the constraint across
/// `scenario`'s interface: penalty, exact or the ALM; any other method, or an ε that either
/// body cannot represent, refused (exit 2).
pub(super) fn enforcement(
    method: Option<Method>,
    epsilon: f64,
    flag: &str,
    scenario: &Scenario,
) -> Result<Enforcement, CliError> {
    let (m, epsilon) = method_at(method, epsilon, flag)?;
    let enforcement = match m {
        Method::Penalty | Method::Exact => Enforcement::from(epsilon),
        Method::Alm { tolerance } => Enforcement::Alm { epsilon, tolerance },
        _ => {
            return Err(usage(
                "--method",
                format!(
                    "{} does not apply to a two-body scenario; allowed: penalty (ε > 0), exact (ε = 0) or alm (ε > 0), the interface's discretisation chosen by --contact",
                    m.name()
                ),
            ));
        }
    };
    if epsilon > 0.0 {
        check::epsilon_in(epsilon, scenario.epsilon_range(scenario.level)).map_err(|e| usage(flag, e))?;
    }
    Ok(enforcement)
}

/// `riplab solve` on the two-body `scenario`.
pub(super) fn solve(args: &SolveArgs, scenario: &Scenario) -> Result<ExitCode, CliError> {
    refuse_one_body_flags(args, scenario)?;
    let method = args.method.resolve(scenario)?;
    let epsilon = args.epsilon.first().copied().unwrap_or(scenario.epsilon);
    let flag = if args.epsilon.is_empty() {
        "the scenario's contact.epsilon"
    } else {
        "--epsilon"
    };
    let enforcement = enforcement(method, epsilon, flag, scenario)?;
    let contact = method_of(args.contact.unwrap_or(ContactName::Mortar), scenario);
    let t = Instant::now();
    let fail = |e| cli_error(e, flag);
    let (lower, upper) = scenario.discretize_bodies(scenario.level).map_err(fail)?;
    let across = Instant::now();
    let interface = scenario
        .solve_discretized(&lower, &upper, contact, enforcement, &|| false)
        .map_err(fail)?;
    let ms = |since: Instant| since.elapsed().as_secs_f64() * 1e3;
    let (interface_ms, total_ms) = (ms(across), ms(t));
    let coupling_ms = interface.coupling_ms;
    let solved = TwoBodies::of(lower, upper, interface);
    let report = InterfaceReport::new(
        scenario,
        scenario.level,
        contact,
        enforcement,
        &solved,
        (coupling_ms, interface_ms, total_ms),
    );
    print(&output(&report, args.format))?;
    Ok(ExitCode::SUCCESS)
}
