//! A convergence study's rows graded at the contact edges, on their own: what the lab's
//! convergence scene computes level by level beside [`super::convergence`]'s uniform rows
//! (issue 35), the same rows `riplab study --refine-edges 0,N` prints in its graded series.

use super::{Reference, StudyRow, graded, strip, with_rates};
use crate::contact::{Method, Rule};
use crate::error::{InputFault, SolveError};
use crate::grading::RefineEdges;
use crate::mesh::Element;
use crate::scenario::Scenario;

/// Every scheme at every level, each solve graded as `refine` asks (fresh solves with
/// `method` at ε, against `reference`), grouped per scheme: the rows of [`super::study`]'s
/// series for `refine` (a uniform `refine` gives [`super::convergence`]'s rows). Graded rows
/// do not take friction: with the scenario's on, each says so
/// ([`InputFault::GradedFriction`]).
pub fn convergence_graded(
    scenario: &Scenario,
    reference: &Reference,
    schemes: &[(Element, Rule)],
    levels: &[u32],
    (method, epsilon): (Option<Method>, f64),
    refine: RefineEdges,
) -> Vec<StudyRow> {
    if !refine.grades() {
        return super::convergence(scenario, reference, schemes, levels, method, epsilon);
    }
    if scenario.friction.is_on() {
        let refused = SolveError::from(InputFault::GradedFriction);
        let groups = schemes
            .iter()
            .map(|&scheme| {
                let (_, params) = super::row_params(scenario, scheme.1, method, epsilon);
                levels
                    .iter()
                    .map(|&level| {
                        let (m, e) = (params.method, params.epsilon);
                        let (mut row, _) =
                            StudyRow::new(reference, scenario, scheme, level, (m, e), Err(&refused));
                        row.grading = refine;
                        row
                    })
                    .collect()
            })
            .collect();
        return with_rates(groups, false);
    }
    let groups = graded::levels_kept(scenario, reference, schemes, levels, (method, epsilon), &[refine]);
    with_rates(strip(groups), false)
}
