//! `--refine-edges N|Nz|auto` of `riplab solve` and the axis `--refine-edges 0,1,2z,…` of
//! `riplab study` ([`crate::grading`]): parsed and checked here, solved through
//! [`solve_graded`].

use super::{CliError, usage};
use crate::contact::ContactParams;
use crate::contact::newton::NewtonOptions;
use crate::discretization::Discretization;
use crate::error::SolveError;
use crate::grading::{Grading, solve_graded};
use crate::scenario::Scenario;
use crate::solution::Solution;
use crate::solve::sweep;

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

/// Solve every instance of `params` on `uniform` (the scenario's level), graded as `refine`
/// asks: without grading [`sweep`]'s warm-started solves on one mesh; with it each instance
/// grades its own mesh ([`solve_graded`]). The first instance is charged with the uniform
/// level's mesh work.
pub(super) fn solve_all(
    scenario: &Scenario,
    uniform: &Discretization,
    params: &[ContactParams],
    refine: Grading,
) -> Vec<Outcome> {
    if !refine.grades() {
        return sweep(uniform, params).into_iter().map(|r| (r, None, 0)).collect();
    }
    let level = scenario.level;
    params
        .iter()
        .enumerate()
        .map(
            |(i, p)| match solve_graded(scenario, (level, uniform), p, refine, &NewtonOptions::default()) {
                Ok(mut g) => {
                    if i == 0 {
                        g.charge_uniform(uniform);
                    }
                    (Ok(g.sol), g.graded, g.grid.passes)
                }
                Err(e) => (Err(e), None, 0),
            },
        )
        .collect()
}
