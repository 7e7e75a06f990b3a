//! A convergence study's rows graded at the contact edges, on their own: what the lab's
//! convergence scene computes level by level beside [`super::convergence`]'s uniform rows,
//! the same rows `riplab study --refine-edges 0,N` prints in its graded series.

use super::{Reference, StudyRow, graded, strip, with_rates};
use crate::contact::{Method, Rule};
use crate::error::{InputFault, SolveError};
use crate::grading::Grading;
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
    refine: impl Into<Grading>,
) -> Vec<StudyRow> {
    let refine: Grading = refine.into();
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::friction::{Friction, Law, Press};
    use crate::grading::RefineEdges;
    use crate::study::{ReferenceFields, ReferenceMesh, Status, uniform_reference};

    /// With the scenario's friction on, every graded row says that grading does not take it
    /// (the study refuses the same, [`InputFault::GradedFriction`]) instead of solving without
    /// it; the uniform rows are solved with it.
    #[test]
    fn graded_rows_refuse_friction() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-paper-full.toml");
        let mut s = Scenario::load(std::path::Path::new(path)).unwrap();
        s.friction = Friction {
            law: Law::Coulomb { mu: 0.3 },
            shift: 0.05,
            steps: 2,
            epsilon_t: None,
            press: Press::WithFriction,
        };
        let mut fetch = |grid: &ReferenceMesh| ReferenceFields::solve_on(&s, grid);
        let (reference, _) = uniform_reference(&s, 1, &mut fetch).unwrap();
        let m1 = [(Element::Q1, Rule::Gauss1)];
        let graded = convergence_graded(&s, &reference, &m1, &[0], (None, 1e-6), RefineEdges::Passes(1));
        assert_eq!(graded.len(), 1);
        let reason = SolveError::from(InputFault::GradedFriction).to_string();
        assert_eq!(graded[0].status, Status::Failed);
        assert_eq!(graded[0].reason.as_deref(), Some(reason.as_str()));
        assert_eq!(graded[0].grading, Grading::from(RefineEdges::Passes(1)));
        let uniform = convergence_graded(&s, &reference, &m1, &[0], (None, 1e-6), RefineEdges::default());
        assert_eq!(uniform[0].status, Status::Ok, "{:?}", uniform[0].reason);
        assert!(uniform[0].errors.unwrap().tbar.is_some(), "solved with friction");
    }
}
