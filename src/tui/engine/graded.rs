//! The lab's solve graded at the contact edges (`E`; issue 35): [`solve_graded`] from the
//! uniform level's discretisation, its final grid's discretisation kept with the solution so
//! that every view (the mesh scene's lines, the pressures, the stresses) shows the graded
//! mesh. Each pass builds its own mesh and factor (nothing of the cache's work carries over:
//! the lines changed), so the graded meshes are not cached.

use std::sync::{Arc, OnceLock};
use std::time::Instant;

use crate::contact::ContactParams;
use crate::contact::newton::NewtonOptions;
use crate::discretization::Discretization;
use crate::grading::solve_graded;

use super::super::protocol::{Response, SolveRequest, Solved};
use super::super::shown::Shown;
use super::Engine;

impl Engine {
    /// Solve `req` on `uniform` graded as its key asks, started at `t`.
    pub(super) fn graded(
        &mut self,
        req: &SolveRequest,
        uniform: &Arc<Discretization>,
        params: &ContactParams,
        t: Instant,
    ) -> Response {
        let key = req.key;
        let graded = solve_graded(
            &self.scenario,
            (key.level, uniform),
            params,
            key.refine_edges,
            &NewtonOptions::default(),
        );
        let result = graded.map(|g| {
            let disc = g.graded.map_or_else(|| uniform.clone(), Arc::new);
            Arc::new(Solved {
                key,
                disc,
                shown: Shown::new(&self.scenario, &g.sol),
                solution: g.sol,
                displacement: OnceLock::new(),
                total_ms: t.elapsed().as_secs_f64() * 1e3,
                stresses: OnceLock::new(),
            })
        });
        Response::Solved {
            generation: req.generation,
            result: result.map_err(Into::into),
        }
    }
}
