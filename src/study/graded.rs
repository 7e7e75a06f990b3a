//! A study's rows on meshes graded at the contact edges or over the contact zone:
//! `--refine-edges 0,1,2,2z,…` is an axis beside the levels; each value is a series per scheme
//! ([`crate::grading`]). A
//! graded row's solve is every pass's (the uniform level's solve, then each graded one), so
//! its time is what the accuracy cost. Its errors are integrated at the reference's points as
//! a uniform row's; its lines need not be the reference's (the reference refines at its own
//! contact edges), so evaluation locates each point in the row's own cell.
//!
//! Rates and fits of a graded series use the unknowns as the abscissa, as an effective cell
//! size n^(−1/2) (a uniform grid's h is proportional to it), so that they compare with a
//! uniform series' rates against h.

use std::ops::ControlFlow;

use super::{Kept, Reference, StudyRow, convergence_kept, row_params};
use crate::contact::newton::NewtonOptions;
use crate::contact::{Method, Rule};
use crate::grading::Grading;
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::solve::{Request, solve};

/// Rows of one scheme and grading, each with what it keeps of its solution.
type Series = Vec<(StudyRow, Option<Kept>)>;

/// Every scheme at every level for every grading of `refine` (a uniform value is
/// [`convergence_kept`]'s shared-mesh rows), grouped per scheme and then per grading in
/// `refine`'s order.
pub(super) fn levels_kept(
    scenario: &Scenario,
    reference: &Reference,
    schemes: &[(Element, Rule)],
    levels: &[u32],
    (method, epsilon): (Option<Method>, f64),
    refine: &[Grading],
) -> Vec<Series> {
    let per_grading: Vec<Vec<Series>> = refine
        .iter()
        .map(|&r| match r.grades() {
            false => convergence_kept(scenario, reference, schemes, levels, method, epsilon),
            true => schemes
                .iter()
                .map(|&scheme| graded_series(scenario, reference, scheme, levels, (method, epsilon), r))
                .collect(),
        })
        .collect();
    let mut columns: Vec<std::vec::IntoIter<Series>> = per_grading.into_iter().map(Vec::into_iter).collect();
    let mut out = Vec::with_capacity(schemes.len() * refine.len());
    for _ in schemes {
        for column in &mut columns {
            out.extend(column.next());
        }
    }
    out
}

/// One scheme at every level, each solve graded as `refine` asks.
fn graded_series(
    scenario: &Scenario,
    reference: &Reference,
    scheme: (Element, Rule),
    levels: &[u32],
    (method, epsilon): (Option<Method>, f64),
    refine: Grading,
) -> Series {
    levels
        .iter()
        .map(|&level| {
            let (resolved, params) = row_params(scenario, scheme.1, method, epsilon);
            let (m, e) = (params.method, params.epsilon);
            let disc = scenario.discretize(level, scheme.0);
            let solved = disc.as_ref().map_err(Clone::clone).and_then(|disc| {
                resolved?;
                let request = Request::new(params.clone()).with_grading(scenario, level, refine);
                let mut g = solve(disc, &request, &NewtonOptions::default(), &mut |_| {
                    ControlFlow::Continue(())
                })?;
                g.charge_mesh_work(disc);
                Ok((disc, g))
            });
            let outcome = solved.as_ref().map(|(d, g)| (g.disc(d), &g.sol));
            let (mut row, kept) = StudyRow::new(reference, scenario, scheme, level, (m, e), outcome);
            row.grading = refine;
            if let Ok((d, g)) = &solved {
                row.n_dofs = g.disc(d).n_dofs();
                if let Some(grids) = &g.graded {
                    row.h_min = grids.grid.h_min();
                }
                row.refine_edges = g.passes();
            }
            (row, kept)
        })
        .collect()
}

impl StudyRow {
    /// The abscissa of its rates and fits: h for a uniform row, n^(−1/2) for a graded one
    /// (module doc).
    pub(super) fn abscissa(&self) -> f64 {
        if self.grading.grades() {
            (self.n_dofs as f64).powf(-0.5)
        } else {
            self.h
        }
    }

    /// Whether `other` is of the same series: scheme, method and grading.
    pub fn same_series(&self, other: &StudyRow) -> bool {
        self.scheme == other.scheme
            && self.method.setting() == other.method.setting()
            && self.grading == other.grading
    }

    /// The level as tables show it: `4`, or `4+3e` after three edge-grading passes (`4+3z`
    /// over the contact zone).
    pub fn level_label(&self) -> String {
        self.grading.level_label(self.level, self.refine_edges)
    }
}
