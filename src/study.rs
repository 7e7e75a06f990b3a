//! Accuracy against work (docs/design.md §6, Theorem 2 (26)): errors of every scheme against a
//! reference solution of the continuous problem, observed rates, and the time each solve took.
//!
//! The reference is independent of the penalty: the exact-constraint problem (ε = 0, see
//! [`crate::contact::signorini`]) with Q2 and nodal multipliers (Simpson's points), on a level
//! finer than any studied one. Coarse solutions live on nested meshes and are evaluated
//! exactly at the reference's quadrature points: the pressures on every reference edge of
//! Γ_C, the displacement in every reference cell.
//!
//! The reference carries its own estimated error (its difference from the next coarser
//! reference) and is refined where it is weakest, at the contact edges where p has a
//! square-root profile, until that estimate is at most a tenth of the smallest error any row
//! reports ([`study`], docs/design.md §6).

use crate::contact::ContactParams;
use crate::contact::friction::Friction;
use crate::contact::{Method, Rule};
use crate::error::{InputFault, SolveError};
use crate::grading::Grading;
use crate::mesh::Element;
use crate::scenario::Scenario;

mod convergence_graded;
mod errors;
mod graded;
mod grid;
#[doc(hidden)]
pub mod interface;
mod meaning;
pub mod penalty_error;
mod rates;
mod reference;
mod refine;
mod row;
mod source;
pub use convergence_graded::convergence_graded;
use errors::Kept;
pub use errors::{Errors, errors};
pub use grid::{MAX_REFINEMENTS, REFERENCE_SCHEME, ReferenceLevelError, ReferenceMesh, reference_level};
pub use meaning::check_contact;
use rates::with_rates;
pub use rates::{Fit, fits, least_squares_slope};
pub use reference::{Estimate, Reference, ReferenceFields, TARGET_SHARE, Target, reference_friction};
use reference::{solve_row, solve_warm};
pub use refine::{Fetch, refine_reference, uniform_reference};
pub use row::{Status, StudyRow, all_ok};
pub use source::ReferenceSource;

/// The elements of `schemes`, each once, in order of first appearance.
fn elements(schemes: &[(Element, Rule)]) -> Vec<Element> {
    let mut out: Vec<Element> = Vec::new();
    for &(e, _) in schemes {
        if !out.contains(&e) {
            out.push(e);
        }
    }
    out
}

/// The method a study's row at `epsilon` uses ([`Method::resolve`]: None and ε = 0 is
/// `exact`), or why it has none.
fn row_method(method: Option<Method>, epsilon: f64) -> Result<(Method, f64), SolveError> {
    Method::resolve(method, epsilon).map_err(|e| InputFault::from(e).into())
}

/// A row's contact parameters with `rule` at `epsilon`, and whether its method resolves (a row
/// whose method does not still gets parameters, the penalty's, to name it in the table).
fn row_params(
    scenario: &Scenario,
    rule: Rule,
    method: Option<Method>,
    epsilon: f64,
) -> (Result<(), SolveError>, ContactParams) {
    let resolved = row_method(method, epsilon);
    let (method, epsilon) = resolved.clone().unwrap_or((Method::Penalty, epsilon));
    let params = ContactParams {
        rule,
        method,
        epsilon,
        obstacle: scenario.obstacle.clone(),
    };
    (resolved.map(|_| ()), params)
}

/// Every scheme at every level (fresh solves with `method` at ε; None: penalty, or exact for
/// ε = 0), against `reference`.
/// Each mesh is assembled and factorised once and shared by the schemes of its element; each
/// row's `solve_ms` is still a fresh solve's cost (that mesh's work plus the scheme's Newton).
/// A row that cannot be computed says why ([`StudyRow::status`]) and the others go on.
pub fn convergence(
    scenario: &Scenario,
    reference: &Reference,
    schemes: &[(Element, Rule)],
    levels: &[u32],
    method: Option<Method>,
    epsilon: f64,
) -> Vec<StudyRow> {
    let groups = convergence_kept(scenario, reference, schemes, levels, method, epsilon);
    with_rates(strip(groups), false)
}

/// The rows of [`convergence`] per scheme, each with what it keeps of its solution.
fn convergence_kept(
    scenario: &Scenario,
    reference: &Reference,
    schemes: &[(Element, Rule)],
    levels: &[u32],
    method: Option<Method>,
    epsilon: f64,
) -> Vec<Vec<(StudyRow, Option<Kept>)>> {
    let mut groups: Vec<Vec<(StudyRow, Option<Kept>)>> = (0..schemes.len()).map(|_| Vec::new()).collect();
    for element in elements(schemes) {
        for &level in levels {
            let disc = scenario.discretize(level, element);
            for (i, &scheme) in schemes.iter().enumerate().filter(|(_, s)| s.0 == element) {
                let (resolved, params) = row_params(scenario, scheme.1, method, epsilon);
                let (m, e) = (params.method, params.epsilon);
                let solved = disc.as_ref().map_err(Clone::clone).and_then(|disc| {
                    resolved?;
                    let mut sol = solve_row(disc, &params, &scenario.friction)?;
                    sol.timing.include_mesh_work(disc);
                    Ok((disc, sol))
                });
                let outcome = solved.as_ref().map(|(d, s)| (*d, s));
                groups[i].push(StudyRow::new(reference, scenario, scheme, level, (m, e), outcome));
            }
        }
    }
    groups
}

/// Every scheme at one level over several ε (re-solves on one mesh, warm-started from the
/// previous ε), against `reference`; one mesh per element. Rows that cannot be computed say
/// why, as in [`convergence`].
pub fn epsilon_sweep(
    scenario: &Scenario,
    reference: &Reference,
    schemes: &[(Element, Rule)],
    level: u32,
    method: Option<Method>,
    epsilons: &[f64],
) -> Vec<StudyRow> {
    let groups = epsilon_sweep_kept(scenario, reference, schemes, level, method, epsilons);
    with_rates(strip(groups), true)
}

/// The rows of [`epsilon_sweep`] per scheme, each with what it keeps of its solution.
fn epsilon_sweep_kept(
    scenario: &Scenario,
    reference: &Reference,
    schemes: &[(Element, Rule)],
    level: u32,
    method: Option<Method>,
    epsilons: &[f64],
) -> Vec<Vec<(StudyRow, Option<Kept>)>> {
    let mut groups: Vec<Vec<(StudyRow, Option<Kept>)>> = (0..schemes.len()).map(|_| Vec::new()).collect();
    for element in elements(schemes) {
        let disc = scenario.discretize(level, element);
        for (i, &scheme) in schemes.iter().enumerate().filter(|(_, s)| s.0 == element) {
            let mut previous: Option<Vec<f64>> = None;
            for &epsilon in epsilons {
                let (resolved, params) = row_params(scenario, scheme.1, method, epsilon);
                let (m, e) = (params.method, params.epsilon);
                let solved = disc.as_ref().map_err(Clone::clone).and_then(|disc| {
                    resolved?;
                    let sol = solve_warm(disc, &params, &scenario.friction, previous.as_deref())?;
                    Ok((disc, sol))
                });
                if let Ok((_, sol)) = &solved {
                    previous = Some(sol.newton.forces.clone());
                }
                let outcome = solved.as_ref().map(|(d, s)| (*d, s));
                groups[i].push(StudyRow::new(reference, scenario, scheme, level, (m, e), outcome));
            }
        }
    }
    groups
}

/// The rows of every group, without what they keep.
fn strip(groups: Vec<Vec<(StudyRow, Option<Kept>)>>) -> Vec<Vec<StudyRow>> {
    groups
        .into_iter()
        .map(|g| g.into_iter().map(|(row, _)| row).collect())
        .collect()
}

/// What a study measures: a refinement over levels at one ε, or a sweep of ε at one level.
#[derive(Clone, Copy, Debug)]
pub enum Plan<'a> {
    /// Every scheme at each of `levels`, at `epsilon` ([`convergence`]), for each grading of
    /// `refine` (`--refine-edges`; `[Grading::default()]`: uniform levels only).
    Levels {
        /// The levels studied.
        levels: &'a [u32],
        /// The penalty parameter ε of every row.
        epsilon: f64,
        /// The gradings (at the edges or over the zone), each a series per scheme
        /// ([`crate::grading`]).
        refine: &'a [Grading],
    },
    /// Every scheme at `level`, at each of `epsilons` ([`epsilon_sweep`]).
    Sweep {
        /// The level of every row.
        level: u32,
        /// The ε swept.
        epsilons: &'a [f64],
    },
}

/// A study's result: its reference (with its estimated error and refinements), its rows with
/// their row-to-row rates, and the least-squares rate of every scheme.
pub struct Study {
    /// The reference, as refined, with its estimated error.
    pub reference: Reference,
    /// The rows, grouped per scheme in the order asked, each group in the plan's order of
    /// levels (or ε).
    pub rows: Vec<StudyRow>,
    /// One least-squares fit per scheme (and method), in the rows' order.
    pub fits: Vec<Fit>,
    /// The friction of every row and of the reference (the scenario's; [`Friction::NONE`]:
    /// frictionless).
    pub friction: Friction,
}

/// Every scheme of `plan` against a reference at `reference_level` (≥ 1) that is refined at
/// its contact edges, at most `max_refinements` times, until its estimated error is at most a
/// tenth of the smallest error any row reports ([`Target`]). The rows are solved once: after a
/// refinement their errors are measured again against the refined reference from what they
/// kept. `fetch` provides the reference's fields on a grid (solved, or from the cache).
/// With the scenario's friction on, every row and the reference are solved with it
/// (docs/design.md §11) and the rows report t̄'s and Q's errors too; edge-graded rows do not
/// take friction ([`InputFault::GradedFriction`]).
///
/// # Errors
///
/// The scenario has no contact, the reference does not fit the memory or does not solve, or its
/// norms are not finite ([`SolveError`]); a row's own failure is its row's status.
pub fn study(
    scenario: &Scenario,
    schemes: &[(Element, Rule)],
    method: Option<Method>,
    plan: Plan,
    (reference_level, max_refinements): (u32, u32),
    fetch: &mut Fetch,
) -> Result<Study, SolveError> {
    check_contact(scenario)?;
    if let Plan::Levels { refine, .. } = plan
        && scenario.friction.is_on()
        && refine.iter().any(|r| r.grades())
    {
        return Err(InputFault::GradedFriction.into());
    }
    let (mut reference, mut fields) = uniform_reference(scenario, reference_level, fetch)?;
    let (mut groups, by_epsilon) = match plan {
        Plan::Levels {
            levels,
            epsilon,
            refine,
        } => (
            graded::levels_kept(scenario, &reference, schemes, levels, (method, epsilon), refine),
            false,
        ),
        Plan::Sweep { level, epsilons } => (
            epsilon_sweep_kept(scenario, &reference, schemes, level, method, epsilons),
            true,
        ),
    };
    let rows = |groups: &Vec<Vec<(StudyRow, Option<Kept>)>>| -> Vec<StudyRow> {
        groups.iter().flatten().map(|(r, _)| r.clone()).collect()
    };
    let mut target = Target::of(&rows(&groups));
    // Refine, measure the rows again, and refine on if their new errors ask for more.
    loop {
        let refinements = reference.grid.refinements;
        (reference, fields) = refine_reference(scenario, (reference, fields), target, max_refinements, fetch);
        if reference.grid.refinements == refinements {
            break;
        }
        for (row, kept) in groups.iter_mut().flatten() {
            if let Some(kept) = kept {
                row.errors = Some(kept.errors(&reference));
                row.certify();
            }
        }
        target = Target::of(&rows(&groups));
        reference.target = target;
        let met = match (&target, &reference.estimate) {
            (Some(t), Some(e)) => t.met_by(e),
            _ => true,
        };
        if met {
            reference.stopped = None;
        }
        if met || reference.stopped.is_some() {
            break;
        }
    }
    let rows = with_rates(strip(groups), by_epsilon);
    let fits = fits(&rows, by_epsilon);
    Ok(Study {
        reference,
        rows,
        fits,
        friction: scenario.friction,
    })
}

#[cfg(test)]
mod friction_tests;
