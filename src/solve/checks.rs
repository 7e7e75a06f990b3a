//! A request checked against what it can answer (docs/design.md §3, §10): the method's own
//! parameters, ε and the depth in their ranges, `exact` only where its multipliers are unique;
//! before anything is built ([`check_request`]) and on a discretisation.

use crate::check;
use crate::contact::{ContactParams, Method};
use crate::discretization::Discretization;
use crate::error::{InputFault, SolveError};
use crate::mesh::Element;
use crate::scenario::Scenario;

/// A contact solve's parameters checked against what it can answer: the method's own
/// parameters ([`Method::check`]), ε within `range` (from [`crate::material::epsilon_range`]) and > 0 for the
/// methods that use it (ε = 0 for `exact`), the depth within the body's `height`, and `exact`
/// only for a rule with no more points (`n_points`) than Γ_C has normal displacements
/// (`normals`).
/// # Errors
///
/// The first parameter out of its range ([`SolveError::Range`], [`SolveError::Input`]), or
/// [`SolveError::Kernel`].
pub fn check_params(
    params: &ContactParams,
    range: (f64, f64),
    height: f64,
    n_points: usize,
    normals: usize,
) -> Result<(), SolveError> {
    params.method.check().map_err(InputFault::from)?;
    check::epsilon_in(params.epsilon, range).map_err(|source| SolveError::Range {
        what: "the penalty parameter ε",
        source,
    })?;
    if params.method.uses_epsilon() && params.epsilon == 0.0 {
        return Err(InputFault::NeedsEpsilon {
            method: params.method.name(),
        }
        .into());
    }
    check::depth(params.obstacle.depth(), height).map_err(|source| SolveError::Range {
        what: "the indentation depth",
        source,
    })?;
    if params.method == Method::Exact && n_points > normals {
        return Err(SolveError::Kernel {
            rule: params.rule.name(),
            points: n_points,
            normals,
        });
    }
    Ok(())
}

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

/// `params` checked against what `disc` can answer with `n_points` contact points.
pub(crate) fn check_on(
    disc: &Discretization,
    params: &ContactParams,
    n_points: usize,
) -> Result<(), SolveError> {
    let (range, normals) = (disc.epsilon_range(), disc.contact_dofs.len());
    check_params(params, range, disc.height(), n_points, normals)
}
