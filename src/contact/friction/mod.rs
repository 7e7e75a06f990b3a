//! Friction on Γ_C (docs/design.md §11): Tresca's and Coulomb's laws imposed at the
//! contact rule's points with the same rule as the normal constraint (the penalty (11), the
//! exact multipliers, the augmented Lagrangian), solved by a semismooth Newton (the
//! primal–dual active-set form) on the normal and tangential forces together, condensed onto
//! Γ_C's full trace [u_x, u_y] ([`trace`]). The obstacle is pressed to its depth, then moved
//! sideways by a shift ξ in quasi-static steps ([`path`]); the tangential traction t at the
//! points is smoothed to t̄ at the vertices with p̄'s weights, the paper's (16)–(17). The laws,
//! the systems and the path know nothing of the mesh; [`trace`] and [`solve`] solve them on a
//! discretisation into a [`crate::contact::solution::Solution`].

#[doc(hidden)]
pub mod law;
#[doc(hidden)]
pub mod newton;
#[doc(hidden)]
pub mod path;
#[doc(hidden)]
pub mod solve;
#[doc(hidden)]
pub mod system;
#[doc(hidden)]
pub mod trace;

use serde::Serialize;

use crate::error::FrictionError;

pub use path::{FrictionSolution, StepReport};
pub(crate) use solve::solve_frictional;
#[doc(hidden)]
pub use solve::{Free, Frictional, check, solve_with};
#[doc(hidden)]
pub use trace::FrictionTrace;

/// The default number of shift steps: one. On monotone shifts (docs/design.md §11, "Steps")
/// 1 to 64 steps gave the same Q, P, stick half-width and t̄ to 1e-12 (`hertz-paper-full` at
/// levels 3 and 5, M1 and M3, μ = 0.3 and 0.6; `cattaneo-mindlin`), and a step that does not
/// converge is bisected ([`path::MAX_BISECTIONS`]).
pub const DEFAULT_STEPS: usize = 1;
/// The most shift steps a solve takes.
pub const MAX_STEPS: usize = 1000;

/// The friction law on Γ_C.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Law {
    /// Frictionless: today's contact.
    None,
    /// Tresca: slip where |t| reaches the threshold g ≥ 0 (force per unit length), at the
    /// points in contact.
    Tresca {
        /// The slip threshold g.
        threshold: f64,
    },
    /// Coulomb: slip where |t| reaches μ p.
    Coulomb {
        /// The friction coefficient μ ≥ 0.
        mu: f64,
    },
}

impl Law {
    /// The laws' names, as `--friction` and `[friction] law` take them.
    pub const NAMES: [&'static str; 3] = ["none", "coulomb", "tresca"];

    /// The law's name.
    pub fn name(&self) -> &'static str {
        match self {
            Law::None => "none",
            Law::Tresca { .. } => "tresca",
            Law::Coulomb { .. } => "coulomb",
        }
    }

    /// μ for Coulomb.
    pub fn mu(&self) -> Option<f64> {
        match *self {
            Law::Coulomb { mu } => Some(mu),
            _ => None,
        }
    }

    /// g for Tresca.
    pub fn threshold(&self) -> Option<f64> {
        match *self {
            Law::Tresca { threshold } => Some(threshold),
            _ => None,
        }
    }

    /// The law `name` with its parameter: μ for coulomb, g for tresca, neither for none; a
    /// parameter of another law is refused, naming its key.
    ///
    /// # Errors
    ///
    /// An unknown law, or a parameter given to a law that does not take it.
    pub fn parse(name: &str, mu: Option<f64>, threshold: Option<f64>) -> Result<Self, FrictionError> {
        let law = match name {
            "none" => Law::None,
            "coulomb" => Law::Coulomb {
                mu: mu.ok_or(FrictionError::Missing {
                    key: "mu",
                    law: "coulomb",
                })?,
            },
            "tresca" => Law::Tresca {
                threshold: threshold.ok_or(FrictionError::Missing {
                    key: "threshold",
                    law: "tresca",
                })?,
            },
            other => {
                return Err(FrictionError::UnknownLaw(
                    crate::text::sanitize(other).into_owned(),
                ));
            }
        };
        if mu.is_some() && law.mu().is_none() {
            return Err(FrictionError::NotOf {
                key: "mu",
                law: law.name(),
            });
        }
        if threshold.is_some() && law.threshold().is_none() {
            return Err(FrictionError::NotOf {
                key: "threshold",
                law: law.name(),
            });
        }
        law.check()?;
        Ok(law)
    }

    /// μ ≥ 0 and g ≥ 0, finite.
    ///
    /// # Errors
    ///
    /// μ or g negative or not finite ([`FrictionError::Range`]).
    pub fn check(&self) -> Result<(), FrictionError> {
        let (key, v) = match *self {
            Law::None => return Ok(()),
            Law::Coulomb { mu } => ("mu", mu),
            Law::Tresca { threshold } => ("threshold", threshold),
        };
        if v.is_finite() && v >= 0.0 {
            Ok(())
        } else {
            Err(FrictionError::Range { key, value: v })
        }
    }
}

/// How the obstacle is pressed to its depth before the shift (docs/design.md §11, "The press").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Press {
    /// With the law on: a point that touches sticks where it touched, so that the press
    /// itself may lock in a tangential traction (Dundurs' β ≠ 0, a finite body).
    WithFriction,
    /// Without friction: the points slide freely while the obstacle goes down and stick from
    /// the shift on where the press left them (the anchors r̂ = r after the press) —
    /// Cattaneo and Mindlin's loading, the normal load first with no tangential traction.
    Frictionless,
}

impl Press {
    /// The presses' names, as `[friction] press` takes them.
    pub const NAMES: [&'static str; 2] = ["with-friction", "frictionless"];

    /// The press's name.
    pub fn name(self) -> &'static str {
        match self {
            Press::WithFriction => "with-friction",
            Press::Frictionless => "frictionless",
        }
    }

    /// The press named `name`.
    ///
    /// # Errors
    ///
    /// A name that is not a press, with the allowed names.
    pub fn parse(name: &str) -> Result<Self, FrictionError> {
        match name {
            "with-friction" => Ok(Press::WithFriction),
            "frictionless" => Ok(Press::Frictionless),
            other => Err(FrictionError::UnknownPress(
                crate::text::sanitize(other).into_owned(),
            )),
        }
    }
}

/// What a solve with friction depends on beyond [`crate::contact::ContactParams`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    /// The law.
    pub law: Law,
    /// The obstacle's sideways shift ξ after the press (displacement control).
    pub shift: f64,
    /// The quasi-static steps of the shift, 1 ..= [`MAX_STEPS`].
    pub steps: usize,
    /// The tangential penalty ε_t (penalty and alm); None: ε.
    pub epsilon_t: Option<f64>,
    /// How the obstacle is pressed before the shift.
    pub press: Press,
}

impl Friction {
    /// No friction.
    pub const NONE: Friction = Friction {
        law: Law::None,
        shift: 0.0,
        steps: DEFAULT_STEPS,
        epsilon_t: None,
        press: Press::WithFriction,
    };

    /// Whether a law other than `none` is on.
    pub fn is_on(&self) -> bool {
        self.law != Law::None
    }

    /// The law's parameter, the steps and ε_t in their ranges (the shift is checked against
    /// the body by [`crate::discretization`]'s caller).
    ///
    /// # Errors
    ///
    /// The first setting out of its range, named ([`FrictionError`]).
    pub fn check(&self) -> Result<(), FrictionError> {
        self.law.check()?;
        if !self.shift.is_finite() {
            return Err(FrictionError::Range {
                key: "shift",
                value: self.shift,
            });
        }
        if !(1..=MAX_STEPS).contains(&self.steps) {
            return Err(FrictionError::Steps {
                steps: self.steps,
                max: MAX_STEPS,
            });
        }
        if let Some(e) = self.epsilon_t
            && !(e.is_finite() && e > 0.0)
        {
            return Err(FrictionError::Range {
                key: "epsilon_t",
                value: e,
            });
        }
        Ok(())
    }
}

/// The state of a contact point after a friction solve.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum State {
    /// Not in contact: no force.
    Open,
    /// In contact, |t| below its bound: no relative slip.
    Stick,
    /// In contact, |t| at its bound, slipping against the traction.
    Slip,
}

impl State {
    /// The state's name in outputs.
    pub fn name(&self) -> &'static str {
        match self {
            State::Open => "open",
            State::Stick => "stick",
            State::Slip => "slip",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each law takes its own parameter only, in range; errors name the key.
    #[test]
    fn laws_parse_and_refuse_by_key() {
        assert_eq!(
            Law::parse("coulomb", Some(0.3), None),
            Ok(Law::Coulomb { mu: 0.3 })
        );
        assert_eq!(
            Law::parse("tresca", None, Some(2.0)),
            Ok(Law::Tresca { threshold: 2.0 })
        );
        assert_eq!(Law::parse("none", None, None), Ok(Law::None));
        let e = Law::parse("tresca", Some(0.3), Some(1.0)).unwrap_err();
        assert_eq!(e.key(), "mu");
        let e = Law::parse("coulomb", Some(-1.0), None).unwrap_err();
        assert_eq!(e.key(), "mu");
        assert!(e.to_string().contains("μ ≥ 0"), "{e}");
        assert_eq!(
            Law::parse("coulomb", Some(f64::NAN), None).unwrap_err().key(),
            "mu"
        );
        assert_eq!(Law::parse("coulomb", None, None).unwrap_err().key(), "mu");
        assert_eq!(Law::parse("stiction", None, None).unwrap_err().key(), "law");
        let steps = Friction {
            steps: 0,
            ..Friction::NONE
        };
        assert_eq!(steps.check().unwrap_err().key(), "steps");
    }
}
