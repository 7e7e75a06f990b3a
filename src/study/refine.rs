//! The reference refined where it is weakest (docs/design.md §6): the uniform reference, then
//! bisections at the contact edges until its estimated error meets the rows' target or the cap.

use super::grid::ReferenceMesh;
use super::reference::{Reference, ReferenceFields, Target, fits_memory};
use crate::error::SolveError;
use crate::scenario::Scenario;

/// Where a study's reference comes from: the fields on a grid, solved or read from a cache
/// ([`crate::cache::fields`]), with whatever the caller reports on the way.
pub type Fetch<'a> = dyn FnMut(&ReferenceMesh) -> Result<ReferenceFields, SolveError> + 'a;

/// The uniform reference at `level` with its estimated error against level − 1 (none at
/// level 0), and its fields.
///
/// # Errors
///
/// As `fetch`'s, or the reference is not meaningful.
pub fn uniform_reference(
    scenario: &Scenario,
    level: u32,
    fetch: &mut Fetch,
) -> Result<(Reference, ReferenceFields), SolveError> {
    let grid = ReferenceMesh::uniform(scenario, level);
    let fields = fetch(&grid)?;
    let mut reference = Reference::from_fields(scenario, &grid, &fields);
    reference.check_meaningful()?;
    if let Some(coarser) = level.checked_sub(1) {
        let coarse = ReferenceMesh::uniform(scenario, coarser);
        reference.estimate = Some(reference.estimate_against(scenario, &coarse, &fetch(&coarse)?));
    }
    Ok((reference, fields))
}

/// Refine `reference` (whose fields are `fields`) at its contact edges until its estimated
/// error meets `target`, to at most `max_refinements` refinements in all. The memory guard or
/// the cap stops it without failing: [`Reference::stopped`] says why. A refinement that does
/// not fit the memory, or whose solve fails, leaves the last good reference in place.
pub fn refine_reference(
    scenario: &Scenario,
    (mut reference, mut fields): (Reference, ReferenceFields),
    target: Option<Target>,
    max_refinements: u32,
    fetch: &mut Fetch,
) -> (Reference, ReferenceFields) {
    reference.target = target;
    reference.stopped = None;
    let Some(target) = target else {
        return (reference, fields);
    };
    loop {
        if reference.estimate.as_ref().is_some_and(|e| target.met_by(e)) {
            return (reference, fields);
        }
        let stop = |mut r: Reference, f: ReferenceFields, why: String| {
            r.stopped = Some(why);
            (r, f)
        };
        if reference.estimate.as_ref().is_some_and(|e| e.p <= target.p) {
            let why = "u's estimated error is the uniform level's, which edge refinements do not lower: a finer --reference-level meets it".to_string();
            return stop(reference, fields, why);
        }
        if reference.grid.refinements >= max_refinements {
            let why = format!("the cap of {max_refinements} edge refinements (--reference-refinements)");
            return stop(reference, fields, why);
        }
        let Some(grid) = reference.grid.refined(&fields.p) else {
            let why = "the reference's pressure has no contact edge to refine".to_string();
            return stop(reference, fields, why);
        };
        let finer = match fits_memory(scenario, &grid).and_then(|()| fetch(&grid)) {
            Ok(f) => f,
            Err(e) => {
                let why = format!("refinement {} failed: {e}", grid.refinements);
                return stop(reference, fields, why);
            }
        };
        let mut next = Reference::from_fields(scenario, &grid, &finer);
        if let Err(e) = next.check_meaningful() {
            let why = format!("refinement {}: {e}", grid.refinements);
            return stop(reference, fields, why);
        }
        let mut estimate = next.estimate_against(scenario, &reference.grid, &fields);
        if let Some(previous) = &reference.estimate {
            estimate.u = previous.u;
        }
        next.estimate = Some(estimate);
        next.target = Some(target);
        (reference, fields) = (next, finer);
    }
}
