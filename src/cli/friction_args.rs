//! The friction options of `riplab solve` (docs/design.md §8, §11): the law and its
//! parameter, the shift and its steps (a comma list of steps sweeps them, each row its own
//! loading history), ε_t; resolved against the scenario's `[friction]` like the method's
//! options: a parameter without its law, a law on a half model, a shift beyond the body are
//! usage errors naming the flag (exit 2).

use clap::Args;

use super::{CliError, usage, values};
use crate::contact::Method;
use crate::contact::friction::{DEFAULT_STEPS, Friction, Law, MAX_STEPS};
use crate::error::FrictionError;
use crate::scenario::Scenario;

/// Friction on Γ_C and the shift after the press.
#[derive(Args, Debug, Clone, Default)]
pub struct FrictionArgs {
    /// Friction law: none, coulomb (--mu) or tresca (--threshold) [default: the scenario's
    /// `[friction]`, else none]
    #[arg(long, value_name = "none|coulomb|tresca")]
    pub friction: Option<String>,
    /// Coulomb's coefficient μ ≥ 0.
    #[arg(long, allow_negative_numbers = true, value_parser = values::number)]
    pub mu: Option<f64>,
    /// Tresca's slip threshold g ≥ 0 (force per unit length).
    #[arg(long, allow_negative_numbers = true, value_parser = values::number)]
    pub threshold: Option<f64>,
    /// The obstacle's sideways shift after the press (its centre stays inside the body).
    #[arg(long, allow_negative_numbers = true, value_parser = values::number)]
    pub shift: Option<f64>,
    /// Quasi-static steps of the shift (its range and default from the constants).
    #[arg(long, value_delimiter = ',', help = shift_steps_help())]
    pub shift_steps: Vec<usize>,
    /// The tangential penalty ε_t > 0 of penalty and alm [default: ε].
    #[arg(long, allow_negative_numbers = true, value_parser = values::number)]
    pub epsilon_t: Option<f64>,
}

impl FrictionArgs {
    /// Refuse `frictions` with `method` before any work, blaming the flag that asked for the
    /// conflict: friction with Nitsche's method, ε_t with the exact method (the solve's own
    /// check, [`crate::contact::friction::solve::check`], would find them after the assembly).
    /// `method_flag` names what chose the method (`--method`, `--epsilon`, `--kappa`); a
    /// friction the flags did not set is the scenario's.
    pub fn check_method(
        &self,
        method: Method,
        frictions: &[Friction],
        method_flag: &str,
    ) -> Result<(), CliError> {
        let from_flags = self.friction.is_some() || self.mu.is_some() || self.threshold.is_some();
        if let Method::Nitsche { .. } = method {
            return Err(if from_flags {
                usage(
                    "--friction",
                    "friction is imposed by penalty, exact or alm, not by nitsche (the method here)",
                )
            } else {
                usage(
                    method_flag,
                    format!(
                        "nitsche takes no friction, and the scenario's `[friction] law = \"{}\"` asks for it; friction is imposed by penalty, exact or alm",
                        frictions[0].law.name()
                    ),
                )
            });
        }
        if method == Method::Exact && frictions.iter().any(|f| f.epsilon_t.is_some()) {
            return Err(match self.epsilon_t {
                Some(_) => usage(
                    "--epsilon-t",
                    "is the tangential penalty of penalty and alm; the method here is exact, which takes none",
                ),
                None => usage(
                    method_flag,
                    "exact takes no tangential penalty, and the scenario's `[friction] epsilon_t` gives one; choose penalty or alm",
                ),
            });
        }
        Ok(())
    }

    /// The friction of each row: the scenario's `[friction]` with the options applied and
    /// checked (one row unless --shift-steps lists several).
    pub fn resolve(&self, scenario: &Scenario) -> Result<Vec<Friction>, CliError> {
        let flag = |key: &str| match key {
            "law" => "--friction".to_string(),
            "steps" => "--shift-steps".to_string(),
            "epsilon_t" => "--epsilon-t".to_string(),
            key => format!("--{key}"),
        };
        let fail = |e: FrictionError| usage(&flag(e.key()), e.to_string());
        let base = scenario.friction;
        let law = match (&self.friction, self.mu, self.threshold) {
            (Some(name), mu, threshold) => Law::parse(name, mu, threshold).map_err(fail)?,
            (None, None, None) => base.law,
            (None, mu, threshold) => Law::parse(base.law.name(), mu, threshold).map_err(|e| match e {
                FrictionError::NotOf { key, .. } => usage(
                    &flag(key),
                    format!(
                        "needs --friction {} (the scenario's law is {})",
                        if key == "mu" { "coulomb" } else { "tresca" },
                        base.law.name()
                    ),
                ),
                e => fail(e),
            })?,
        };
        if law == Law::None {
            let given = [
                ("--shift", self.shift.is_some()),
                ("--shift-steps", !self.shift_steps.is_empty()),
                ("--epsilon-t", self.epsilon_t.is_some()),
            ];
            if let Some((f, _)) = given.iter().find(|(_, g)| *g) {
                return Err(usage(
                    f,
                    "applies with friction only (--friction coulomb or tresca)",
                ));
            }
            return Ok(vec![Friction::NONE]);
        }
        if scenario.half_model {
            return Err(usage(
                if self.friction.is_some() {
                    "--friction"
                } else {
                    "--mu"
                },
                "friction needs the full model: the scenario has body.model = \"half\", whose symmetry line holds u_x = 0",
            ));
        }
        let steps = if self.shift_steps.is_empty() {
            vec![if base.is_on() { base.steps } else { DEFAULT_STEPS }]
        } else {
            self.shift_steps.clone()
        };
        let (x0, x1) = scenario.x_range();
        steps
            .into_iter()
            .map(|steps| {
                if !(1..=MAX_STEPS).contains(&steps) {
                    return Err(fail(FrictionError::Steps {
                        steps,
                        max: MAX_STEPS,
                    }));
                }
                let f = Friction {
                    law,
                    shift: self.shift.unwrap_or(base.shift),
                    steps,
                    epsilon_t: self.epsilon_t.or(base.epsilon_t),
                    press: base.press,
                };
                f.check().map_err(fail)?;
                let moved = scenario.obstacle.center() + f.shift;
                if !(moved > x0 && moved < x1) {
                    return Err(usage(
                        "--shift",
                        format!(
                            "{} moves the obstacle's centre to x = {}, beyond the body; allowed: the centre strictly inside ({}, {})",
                            crate::text::num(f.shift),
                            crate::text::num(moved),
                            crate::text::num(x0),
                            crate::text::num(x1)
                        ),
                    ));
                }
                Ok(f)
            })
            .collect()
    }
}

/// `--shift-steps`'s help, its range and default from [`MAX_STEPS`] and [`DEFAULT_STEPS`].
fn shift_steps_help() -> String {
    format!(
        "Quasi-static steps of the shift, 1 to {MAX_STEPS} [default: the scenario's, else {DEFAULT_STEPS}]; several, comma-separated, sweep on one mesh"
    )
}
