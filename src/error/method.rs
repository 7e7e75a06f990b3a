//! A contact method or one of its parameters that is not allowed
//! ([`crate::contact::method::Method::parse`], [`crate::contact::method::Method::check`]).

use crate::check::CheckError;
use crate::text::{num, sanitize};

/// A method or one of its parameters that is not allowed; the message names what is.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MethodError {
    /// Not one of the methods.
    #[error("`{}` is not a method; allowed: {}", sanitize(given), allowed.join(", "))]
    Name {
        /// The name given.
        given: String,
        /// The methods' names ([`crate::contact::method::NAMES`]).
        allowed: &'static [&'static str],
    },
    /// A θ not in [`crate::contact::method::THETAS`].
    #[error(
        "θ = {} is not allowed; allowed: 1 (symmetric), 0 (incomplete), -1 (skew-symmetric)",
        num(*theta)
    )]
    Theta {
        /// The θ given.
        theta: f64,
    },
    /// A given γ₀ outside [`crate::contact::method::GAMMA0_RANGE`].
    #[error("{0}")]
    Gamma0(CheckError),
    /// A γ₀ that is neither `auto` nor a number.
    #[error("`{}` is neither `auto` nor a number", sanitize(given))]
    Gamma0Text {
        /// The text given.
        given: String,
    },
    /// An ALM tolerance outside (0, 1).
    #[error("{0}")]
    Tolerance(CheckError),
    /// A parameter given to a method that does not take it.
    #[error("`{key}` is a parameter of {takes}, not of {method}")]
    NotTaken {
        /// The parameter's key, e.g. `alm_tol`.
        key: &'static str,
        /// The method it was given to.
        method: &'static str,
        /// The method that takes it.
        takes: &'static str,
    },
    /// `penalty` or `alm` (the named one) at ε = 0.
    #[error("{0} needs a penalty parameter ε > 0; ε = 0 is the exact method (`exact`)")]
    NeedsEpsilon(&'static str),
}

impl MethodError {
    /// The key of the scenario file (and, with `--` and `_` as `-`, the flag) at fault.
    pub fn key(&self) -> &'static str {
        match self {
            MethodError::Name { .. } => "method",
            MethodError::Theta { .. } => "theta",
            MethodError::Gamma0(_) | MethodError::Gamma0Text { .. } => "gamma0",
            MethodError::Tolerance(_) => "alm_tol",
            MethodError::NotTaken { key, .. } => key,
            MethodError::NeedsEpsilon(_) => "epsilon",
        }
    }
}
