//! A request checked against what it can answer (docs/design.md §3, §10) before anything is
//! built ([`check_request`]): the scenario's numbers at a level given to the contact
//! parameters' own check ([`check_params`], also run on a discretisation by each method).

use crate::contact::ContactParams;
use crate::contact::params::check_params;
use crate::error::SolveError;
use crate::mesh::Element;
use crate::scenario::Scenario;

/// [`check_params`] before anything is built: from the scenario's numbers at `level` with
/// `element`, so that a request with no answer is refused without assembling a stiffness.
/// # Errors
///
/// As [`check_params`].
pub fn check_request(
    scenario: &Scenario,
    level: u32,
    element: Element,
    params: &ContactParams,
) -> Result<(), SolveError> {
    let n_edges = (scenario.x_lines.len() - 1) << level;
    check_params(
        params,
        scenario.epsilon_range(level),
        scenario.height,
        params.rule.n_points(n_edges),
        element.order() * n_edges + 1,
    )
}
