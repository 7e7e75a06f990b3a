//! `riplab solve` with friction: each row's press and shift on the one full-trace mesh, each
//! with its own loading history (a sweep over --shift-steps, ε or the depth), a failure the
//! row's result.

use std::ops::ControlFlow;

use super::grading::Outcome;
use crate::contact::ContactParams;
use crate::contact::friction::Friction;
use crate::contact::newton::NewtonOptions;
use crate::discretization::Discretization;
use crate::friction::solve_friction;

/// Solve every instance (its params with its friction, the last friction for the rest) on
/// `disc`; the first solution is charged with the mesh's work.
pub(super) fn solve_all(
    disc: &Discretization,
    params: &[ContactParams],
    frictions: &[Friction],
) -> Vec<Outcome> {
    let opts = NewtonOptions::default();
    params
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let friction = frictions[k.min(frictions.len() - 1)];
            let solved = solve_friction(
                disc,
                p,
                &friction,
                None,
                &opts,
                &mut |_| ControlFlow::Continue(()),
            )
            .map(|mut sol| {
                if k == 0 {
                    sol.timing.include_mesh_work(disc);
                }
                sol
            });
            (solved, None, 0)
        })
        .collect()
}
