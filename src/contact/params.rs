//! The parameters of one contact solve beyond the mesh: the rule, the method, ε and the
//! obstacle, and their check against what a solve can answer (docs/design.md §3, §10).

use super::{Method, Obstacle, Rule};
use crate::check;
use crate::discretization::Discretization;
use crate::error::{InputFault, SolveError};

/// What a contact solve depends on beyond the mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactParams {
    /// The contact rule of the penalty term (10) on Γ_C.
    pub rule: Rule,
    /// How the constraint is imposed ([`Method`]).
    pub method: Method,
    /// The penalty parameter ε > 0 of (8) for `penalty` and `alm`; 0 for `exact` (the
    /// limit; [`Method::resolve`]).
    pub epsilon: f64,
    /// The rigid obstacle, whose outline gives the gap g.
    pub obstacle: Obstacle,
}

impl ContactParams {
    /// `penalty` at ε > 0, `exact` at ε = 0 ([`Method::resolve`] with no method named).
    pub fn by_epsilon(rule: Rule, epsilon: f64, obstacle: Obstacle) -> Self {
        let method = if epsilon == 0.0 {
            Method::Exact
        } else {
            Method::Penalty
        };
        ContactParams {
            rule,
            method,
            epsilon,
            obstacle,
        }
    }
}

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

/// `params` checked against what `disc` can answer with `n_points` contact points.
pub(crate) fn check_on(
    disc: &Discretization,
    params: &ContactParams,
    n_points: usize,
) -> Result<(), SolveError> {
    let (range, normals) = (disc.epsilon_range(), disc.contact_dofs.len());
    check_params(params, range, disc.height(), n_points, normals)
}
