//! The lab's solve with friction (docs/design.md §11): the press and the shift solved by the
//! library's entry that `riplab solve` calls ([`crate::solve::solve`]), on the cached mesh (its
//! full trace made once per mesh and kept with it), warm-started from the last friction
//! solve on the same points. Edge grading does not take friction (as `riplab solve` refuses
//! it); Nitsche's method and a half model are refused by the library, and the refusal is the
//! reply.

use std::sync::Arc;
use std::time::Instant;

use crate::contact::ContactParams;
use crate::contact::newton::NewtonOptions;
use crate::discretization::Discretization;
use crate::solve::{self, Request};

use super::super::lab_error::LabError;
use super::super::protocol::{Response, SolveRequest};
use super::{Engine, ForcePoints};

impl Engine {
    /// Solve `req` (its friction on) on `disc` with `params`, on the force points `points`,
    /// started at `t`; `is_current(generation)` false cancels it.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn solve_friction(
        &mut self,
        req: &SolveRequest,
        disc: Arc<Discretization>,
        params: &ContactParams,
        points: ForcePoints,
        t: Instant,
        is_current: &dyn Fn(u64) -> bool,
        report: &mut dyn FnMut(Response),
    ) -> Response {
        let (generation, key) = (req.generation, req.key);
        if key.refine_edges.grades() {
            return Response::Solved {
                generation,
                result: Err(LabError::GradedFriction),
            };
        }
        let mut friction = key.friction;
        // `exact` takes no tangential penalty (as it takes no ε): the scenario's ε_t is
        // penalty's and alm's.
        if !key.method.uses_epsilon() {
            friction.epsilon_t = None;
        }
        // The last friction solve's forces when they live on these points.
        let warm = self
            .warm
            .as_ref()
            .filter(|w| w.points == points)
            .and_then(|w| w.z.as_ref().map(|z| (w.forces.clone(), z.clone())));
        let initial = warm.as_ref().map(|(y, z)| (y.as_slice(), z.as_slice()));
        let warm = initial.map_or(solve::Warm::Rest, |(y, z)| solve::Warm::Frictional(y, z));
        let request = Request::new(params.clone())
            .with_friction(friction)
            .warm_from(warm);
        let result = solve::solve(&disc, &request, &NewtonOptions::default(), &mut |it| {
            super::newton_step(generation, is_current, &mut *report, it)
        })
        .map(|solved| solved.sol);
        self.answer(generation, key, disc, points, t, result)
    }
}
