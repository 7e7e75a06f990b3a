//! The parameters of one contact solve beyond the mesh: the rule, the method, ε and the
//! obstacle.

use super::{Method, Obstacle, Rule};

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
