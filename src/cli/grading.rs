//! `--refine-edges N|Nz|auto` of `riplab solve` and the axis `--refine-edges 0,1,2z,…` of
//! `riplab study` ([`crate::grading`]): parsed and checked here, solved through the library's
//! entry ([`solve_each`]) with the rows' friction.

use super::{CliError, usage};
use crate::contact::ContactParams;
use crate::contact::friction::Friction;
use crate::contact::solution::Solution;
use crate::discretization::Discretization;
use crate::error::SolveError;
use crate::grading::Grading;
use crate::scenario::Scenario;
use crate::solve::{Request, solve_each};

/// The grading of a solve: `--refine-edges` when given, else the scenario's
/// `[mesh] refine_edges`.
pub(super) fn refine_edges(text: Option<&str>, scenario: &Scenario) -> Result<Grading, CliError> {
    match text {
        Some(t) => Grading::parse(t).map_err(|e| usage("--refine-edges", e)),
        None => Ok(scenario.grading()),
    }
}

/// A study's gradings: each value of `--refine-edges` once, in the order given, else the
/// scenario's `[mesh] refine_edges`.
pub(super) fn refine_axis(texts: &[String], scenario: &Scenario) -> Result<Vec<Grading>, CliError> {
    if texts.is_empty() {
        return Ok(vec![scenario.grading()]);
    }
    let mut out: Vec<Grading> = Vec::new();
    for t in texts {
        let r = Grading::parse(t).map_err(|e| usage("--refine-edges", e))?;
        if !out.contains(&r) {
            out.push(r);
        }
    }
    Ok(out)
}

/// One instance's outcome: its solution, the graded mesh it ended on (None: `uniform`'s) and
/// the passes made.
pub(super) type Outcome = (Result<Solution, SolveError>, Option<Discretization>, u32);

/// Solve every instance of `params` on `uniform` (the scenario's level) through the library's
/// entry ([`solve_each`]), each with its friction (the last of `frictions` for the rest; none
/// when empty) and graded as `grading` asks: frictionless instances on the uniform level start
/// from the forces of the last one that solved, with friction each has its own loading
/// history, graded each its own mesh. The first instance is charged with the uniform level's
/// mesh work; a failure is its instance's result.
pub(super) fn solve_all(
    scenario: &Scenario,
    uniform: &Discretization,
    params: &[ContactParams],
    frictions: &[Friction],
    grading: Grading,
) -> Vec<Outcome> {
    let requests: Vec<Request<'_>> = params
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let friction = frictions.get(k.min(frictions.len().saturating_sub(1))).copied();
            Request::new(p.clone())
                .with_friction(friction.unwrap_or(Friction::NONE))
                .with_grading(scenario, scenario.level, grading)
        })
        .collect();
    solve_each(uniform, &requests)
        .into_iter()
        .map(|solved| match solved {
            Ok(solved) => {
                let passes = solved.passes();
                (Ok(solved.sol), solved.graded.and_then(|g| g.disc), passes)
            }
            Err(e) => (Err(e), None, 0),
        })
        .collect()
}
