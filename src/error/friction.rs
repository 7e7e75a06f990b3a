//! The friction parameters that have no answer (docs/design.md §11): a law not known, a key
//! given to a law that does not take it, a value out of its range.

/// A friction parameter outside its range, or given to a law that does not take it.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FrictionError {
    /// A law not known.
    #[error("unknown friction law `{0}`; allowed: none, coulomb, tresca")]
    UnknownLaw(String),
    /// A press not known.
    #[error("unknown press `{0}`; allowed: with-friction, frictionless")]
    UnknownPress(String),
    /// The law's parameter is missing.
    #[error("`{key}` is required by law {law}")]
    Missing {
        /// The missing key.
        key: &'static str,
        /// The law.
        law: &'static str,
    },
    /// A parameter of another law.
    #[error("`{key}` does not apply to law {law}; coulomb takes mu, tresca takes threshold")]
    NotOf {
        /// The key given.
        key: &'static str,
        /// The law it was given with.
        law: &'static str,
    },
    /// A value out of range.
    #[error("{key} = {} is out of range; allowed: {}", crate::text::num(*value), allowed(key))]
    Range {
        /// The key.
        key: &'static str,
        /// Its value.
        value: f64,
    },
    /// The number of shift steps out of range.
    #[error("steps = {steps} is out of range; allowed: 1 to {max}")]
    Steps {
        /// The number given.
        steps: usize,
        /// The largest number allowed.
        max: usize,
    },
}

/// The range of `key`, as errors state it.
fn allowed(key: &str) -> &'static str {
    match key {
        "mu" => "a finite μ ≥ 0",
        "threshold" => "a finite g ≥ 0",
        "epsilon_t" => "a finite ε_t > 0",
        _ => "a finite number",
    }
}

impl FrictionError {
    /// The key of `[friction]` the error is about.
    pub fn key(&self) -> &'static str {
        match self {
            FrictionError::UnknownLaw(_) => "law",
            FrictionError::UnknownPress(_) => "press",
            FrictionError::Missing { key, .. }
            | FrictionError::NotOf { key, .. }
            | FrictionError::Range { key, .. } => key,
            FrictionError::Steps { .. } => "steps",
        }
    }
}
