//! A tour step's friction (docs/design.md §11): `friction = "none" | "coulomb" |
//! "tresca"` with `mu` or `threshold`, and `shift`, validated as the scenario's `[friction]`
//! is (each error names the file, line, key and range), applied over the scenario's own by
//! [`super::Tour::app`], and written by the lab's `T` when the lab's differs from the
//! scenario's ([`super::author`]). A step's friction is checked against its scenario's model,
//! its method and its grading as the lab refuses them ([`check`]), when the tour is read.

use std::ops::Range;

use toml::Spanned;

use crate::contact::Method;
use crate::contact::friction::{Friction, Law};
use crate::input::Locator as Source;
use crate::input::ScenarioError;
use crate::text::num;

use super::super::app::App;
use super::errors::FrictionStepError;

/// What a step sets of the friction; what it leaves out is the scenario's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepFriction {
    /// The law with its parameter, when the step names one.
    pub law: Option<Law>,
    /// The shift ξ, when given.
    pub shift: Option<f64>,
}

impl StepFriction {
    /// `friction` with this step's settings over it.
    pub fn over(&self, mut friction: Friction) -> Friction {
        friction.law = self.law.unwrap_or(friction.law);
        friction.shift = self.shift.unwrap_or(friction.shift);
        friction
    }
}

/// The step's raw friction keys.
pub struct Raw<'a> {
    /// `friction`.
    pub law: Option<&'a Spanned<String>>,
    /// `mu`.
    pub mu: Option<&'a Spanned<f64>>,
    /// `threshold`.
    pub threshold: Option<&'a Spanned<f64>>,
    /// `shift`.
    pub shift: Option<&'a Spanned<f64>>,
}

/// Step `n`'s friction keys validated; None when it gives none.
pub fn parse(src: &Source, n: usize, raw: &Raw) -> Result<Option<StepFriction>, ScenarioError> {
    let key = |k: &str| Some(format!("step[{n}].{k}"));
    let span_of = |k: &str| -> Option<Range<usize>> {
        match k {
            "mu" => raw.mu.map(Spanned::span),
            "threshold" => raw.threshold.map(Spanned::span),
            _ => raw.law.map(Spanned::span),
        }
    };
    let law = match raw.law {
        Some(name) => Some(
            Law::parse(
                name.get_ref(),
                raw.mu.map(|m| *m.get_ref()),
                raw.threshold.map(|t| *t.get_ref()),
            )
            .map_err(|e| {
                // The law's own key is the step's `friction`.
                let k = if e.key() == "law" { "friction" } else { e.key() };
                src.error(span_of(k), key(k), e.to_string())
            })?,
        ),
        None => {
            if let Some((k, span)) = [("mu", raw.mu), ("threshold", raw.threshold)]
                .into_iter()
                .find_map(|(k, v)| v.map(|v| (k, v.span())))
            {
                return Err(src.error(
                    Some(span),
                    key(k),
                    format!("is a parameter of the law: give friction = \"coulomb\" (mu) or \"tresca\" (threshold) with {k}"),
                ));
            }
            None
        }
    };
    let shift = match raw.shift {
        Some(s) if !s.get_ref().is_finite() => {
            return Err(src.error(
                Some(s.span()),
                key("shift"),
                format!("{} is not a number; allowed: a finite shift", num(*s.get_ref())),
            ));
        }
        s => s.map(|s| *s.get_ref()),
    };
    Ok((law.is_some() || shift.is_some()).then_some(StepFriction { law, shift }))
}

/// The lines `T` writes for `friction` where it differs from the scenario's `own`.
pub fn lines(friction: &Friction, own: &Friction, float: fn(f64) -> String) -> Vec<String> {
    if friction == own {
        return Vec::new();
    }
    let mut out = vec![format!("friction = \"{}\"", friction.law.name())];
    if let Some(mu) = friction.law.mu() {
        out.push(format!("mu = {}", float(mu)));
    }
    if let Some(g) = friction.law.threshold() {
        out.push(format!("threshold = {}", float(g)));
    }
    if friction.shift != 0.0 {
        out.push(format!("shift = {}", float(friction.shift)));
    }
    out
}

/// Whether the lab at `app`'s settings can solve its friction, as the lab itself refuses it:
/// a half model holds Γ_C's u_x (`F` says so), Nitsche's method and a graded mesh take no
/// friction (the solve's banner says so), and the shifted obstacle's centre must stay inside
/// the body (the solve's check, docs/design.md §11). Friction off always passes.
pub fn check(app: &App) -> Result<(), FrictionStepError> {
    let s = &app.settings;
    let friction = &s.friction;
    if !friction.is_on() {
        return Ok(());
    }
    if app.scenario.half_model {
        return Err(FrictionStepError::HalfModel);
    }
    if let Method::Nitsche { .. } = s.method {
        return Err(FrictionStepError::Nitsche);
    }
    if s.refine_edges.grades() {
        return Err(FrictionStepError::Graded(s.refine_edges));
    }
    let (x0, x1) = app.scenario.x_range();
    let centre = app.scenario.obstacle.center() + friction.shift;
    if !(centre > x0 && centre < x1) {
        return Err(FrictionStepError::ShiftBeyond {
            shift: friction.shift,
            centre,
            x0,
            x1,
        });
    }
    Ok(())
}
