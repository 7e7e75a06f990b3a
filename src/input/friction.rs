//! `[friction]` validated (docs/design.md §11): the law among [`Law::NAMES`], μ ≥ 0 or g ≥ 0
//! finite and only with its law, the shift finite with the obstacle's shifted centre inside
//! the body, the steps 1 to [`MAX_STEPS`], ε_t > 0, the press among [`Press::NAMES`];
//! friction on a half model refused at `friction.law`, naming `body.model`; friction with what
//! the rest of the file asks and it cannot take (Nitsche's method, ε_t with the exact method, a
//! grading) refused at the key that asks it. Every error: file, line, column, key, value, range.

use std::ops::Range;

use toml::Spanned;

use super::locate::{Locator, ScenarioError};
use super::schema::{Model, RawBody, RawFriction, RawScenario};
use crate::contact::friction::{DEFAULT_STEPS, Friction, Law, MAX_STEPS, Press};
use crate::contact::{Method, Obstacle};
use crate::error::FrictionError;
use crate::grading::Grading;
use crate::text::num;

impl Locator<'_> {
    /// The friction of `[friction]` (none without the table).
    pub(super) fn friction(
        &self,
        raw: Option<&Spanned<RawFriction>>,
        body: &RawBody,
        obstacle: &Obstacle,
        (x0, x1): (f64, f64),
    ) -> Result<Friction, ScenarioError> {
        let Some(table) = raw else {
            return Ok(Friction::NONE);
        };
        let raw = table.get_ref();
        let at = |key: &str| -> Range<usize> {
            let span = match key {
                "mu" => raw.mu.as_ref().map(Spanned::span),
                "threshold" => raw.threshold.as_ref().map(Spanned::span),
                "shift" => raw.shift.as_ref().map(Spanned::span),
                "steps" => raw.steps.as_ref().map(Spanned::span),
                "epsilon_t" => raw.epsilon_t.as_ref().map(Spanned::span),
                "press" => raw.press.as_ref().map(Spanned::span),
                _ => None,
            };
            span.unwrap_or_else(|| raw.law.span())
        };
        let fail = |e: FrictionError| {
            let key = e.key();
            self.error(Some(at(key)), Some(format!("friction.{key}")), e.to_string())
        };
        let get = |v: &Option<Spanned<f64>>| v.as_ref().map(|v| *v.get_ref());
        let law = Law::parse(raw.law.get_ref(), get(&raw.mu), get(&raw.threshold)).map_err(fail)?;
        if law == Law::None {
            let given = [
                ("shift", raw.shift.is_some()),
                ("steps", raw.steps.is_some()),
                ("epsilon_t", raw.epsilon_t.is_some()),
                ("press", raw.press.is_some()),
            ];
            if let Some((key, _)) = given.iter().find(|(_, g)| *g) {
                return Err(self.error(
                    Some(at(key)),
                    Some(format!("friction.{key}")),
                    "does not apply to law none; its keys: law".into(),
                ));
            }
            return Ok(Friction::NONE);
        }
        if body.model == Model::Half {
            return Err(self.error(
                Some(raw.law.span()),
                Some("friction.law".into()),
                "friction needs body.model = \"full\": the half model's symmetry line holds u_x = 0".into(),
            ));
        }
        let steps = match &raw.steps {
            Some(s) => {
                let v = *s.get_ref();
                if !(1..=MAX_STEPS as i64).contains(&v) {
                    return Err(self.error(
                        Some(s.span()),
                        Some("friction.steps".into()),
                        format!("steps = {v} is out of range; allowed: 1 to {MAX_STEPS}"),
                    ));
                }
                v as usize
            }
            None => DEFAULT_STEPS,
        };
        let press = match &raw.press {
            Some(name) => Press::parse(name.get_ref()).map_err(fail)?,
            None => Press::WithFriction,
        };
        let friction = Friction {
            law,
            shift: get(&raw.shift).unwrap_or(0.0),
            steps,
            epsilon_t: get(&raw.epsilon_t),
            press,
        };
        friction.check().map_err(fail)?;
        let moved = obstacle.center() + friction.shift;
        if !(moved > x0 && moved < x1) {
            return Err(self.error(
                Some(at("shift")),
                Some("friction.shift".into()),
                format!(
                    "shift = {} moves the obstacle's centre to x = {}, beyond the body; allowed: the centre strictly inside ({}, {})",
                    num(friction.shift),
                    num(moved),
                    num(x0),
                    num(x1)
                ),
            ));
        }
        Ok(friction)
    }
}

impl Locator<'_> {
    /// Refuse `friction` (of `raw`'s `[friction]`) with what the rest of the file asks and it
    /// cannot take, at the key that asks it: Nitsche's method (`friction.law`: friction is
    /// imposed by penalty, exact or alm), a tangential penalty ε_t with the exact method
    /// (`friction.epsilon_t`), a grading (`mesh.refine_edges`: graded meshes take no friction).
    pub(super) fn friction_conflicts(
        &self,
        raw: &RawScenario,
        method: Method,
        friction: &Friction,
        grading: Grading,
    ) -> Result<(), ScenarioError> {
        let Some(table) = raw.friction.as_ref().filter(|_| friction.is_on()) else {
            return Ok(());
        };
        let table = table.get_ref();
        if let Method::Nitsche { .. } = method {
            return Err(self.error(
                Some(table.law.span()),
                Some("friction.law".into()),
                format!(
                    "{} friction is imposed by penalty, exact or alm, not by contact.method = \"nitsche\"; choose another method, or law = \"none\"",
                    friction.law.name()
                ),
            ));
        }
        if let (Method::Exact, Some(e)) = (method, &table.epsilon_t) {
            return Err(self.error(
                Some(e.span()),
                Some("friction.epsilon_t".into()),
                "is the tangential penalty of penalty and alm; the method here is exact (contact.method = \"exact\", or epsilon = 0), which takes none".into(),
            ));
        }
        match &raw.mesh.refine_edges {
            Some(r) if grading.grades() => Err(self.error(
                Some(r.span()),
                Some("mesh.refine_edges".into()),
                format!(
                    "{grading} grades the mesh, and grading (at the edges or over the zone) is not available with friction (friction.law = \"{}\") yet; use a finer level",
                    friction.law.name()
                ),
            )),
            _ => Ok(()),
        }
    }
}
