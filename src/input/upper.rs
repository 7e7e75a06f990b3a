//! `[upper]` validated (docs/design.md §12): the upper elastic body in place of the rigid
//! obstacle — E and ν in their ranges, a height, the shape `block` or `cylinder` (with its radius), the ratio of two whole
//! numbers 1 to [`MAX_RATIO`], an offset |offset| < 1/2, the support among `clamped` and
//! `roller`, the top's displacement within ± the thinner body's height, the slave among
//! `upper` and `lower`. `[obstacle]` beside it is refused, and so is what the two-body solve
//! does not take (friction, a graded mesh, a method other than the penalty or the exact
//! multipliers). Every error: file, line, column, key, value, range.

use toml::Spanned;

use super::locate::{Locator, ScenarioError};
use super::schema::{RawScenario, RawUpper};
use crate::check;
use crate::contact::interface::solve::Slave;
use crate::contact::{Method, Obstacle};
use crate::fem::Support;
use crate::material::Material;
use crate::scenario::upper::MAX_RATIO;
use crate::scenario::{Upper, UpperShape};

impl Locator<'_> {
    /// The support named by `key` (`clamped` when absent).
    pub(super) fn support(&self, key: &str, raw: Option<&Spanned<String>>) -> Result<Support, ScenarioError> {
        match raw {
            None => Ok(Support::Clamped),
            Some(s) => match s.get_ref().as_str() {
                "clamped" => Ok(Support::Clamped),
                "roller" => Ok(Support::Roller),
                other => Err(self.error(
                    Some(s.span()),
                    Some(key.into()),
                    format!("\"{other}\" is not a support; allowed: \"clamped\", \"roller\""),
                )),
            },
        }
    }

    /// The obstacle of `[obstacle]`, or with `[upper]` its rigid limit (a flat or the cylinder
    /// pressed the top's displacement), and the upper body; one of the two tables exactly.
    pub(super) fn obstacle_or_upper(
        &self,
        raw: &RawScenario,
        (x0, x1): (f64, f64),
    ) -> Result<(Obstacle, Option<Upper>), ScenarioError> {
        let height = *raw.body.height.get_ref();
        match (&raw.obstacle, &raw.upper) {
            (Some(o), None) => Ok((self.obstacle(o, height)?, None)),
            (None, Some(u)) => {
                let upper = self.upper(u.get_ref(), raw)?;
                let reach = (x1 - x0).abs() + x0.abs() + x1.abs() + 1.0;
                let rigid = match upper.shape {
                    UpperShape::Block => Obstacle::Polyline {
                        points: vec![(-reach, 0.0), (reach, 0.0)],
                        depth: upper.displacement,
                    },
                    UpperShape::Cylinder { radius } => Obstacle::Cylinder {
                        radius,
                        depth: upper.displacement,
                        center: 0.0,
                    },
                };
                Ok((rigid, Some(upper)))
            }
            (Some(o), Some(_)) => Err(self.error(
                Some(o.shape.span()),
                Some("obstacle".into()),
                "does not apply with [upper]: the upper elastic body is the obstacle; give one of [obstacle] and [upper]".into(),
            )),
            (None, None) => Err(self.error(
                None,
                Some("obstacle".into()),
                "missing: give [obstacle] (a rigid obstacle) or [upper] (an elastic body)".into(),
            )),
        }
    }

    /// The upper body of `[upper]`, and what the rest of `raw` asks that two bodies do not take.
    fn upper(&self, u: &RawUpper, raw: &RawScenario) -> Result<Upper, ScenarioError> {
        self.check("upper.young", &u.young, |v| check::young(*v))?;
        self.check("upper.poisson", &u.poisson, |v| check::poisson(*v))?;
        self.check("upper.height", &u.height, |v| check::length(*v))?;
        let thinner = raw.body.height.get_ref().min(*u.height.get_ref());
        self.check("upper.displacement", &u.displacement, |v| {
            check::depth(*v, thinner)
        })?;
        let shape = match (u.shape.as_ref().map(|s| s.get_ref().as_str()), &u.radius) {
            (None | Some("block"), None) => UpperShape::Block,
            (Some("cylinder"), Some(r)) => {
                self.check("upper.radius", r, |v| check::length(*v))?;
                UpperShape::Cylinder { radius: *r.get_ref() }
            }
            (Some("cylinder"), None) => {
                return Err(self.error(
                    u.shape.as_ref().map(Spanned::span),
                    Some("upper.radius".into()),
                    "is required for shape \"cylinder\": the radius of its bottom's arc".into(),
                ));
            }
            (None | Some("block"), Some(r)) => {
                return Err(self.error(
                    Some(r.span()),
                    Some("upper.radius".into()),
                    "applies to shape \"cylinder\" only; the block's bottom is flat".into(),
                ));
            }
            (Some(other), _) => {
                return Err(self.error(
                    u.shape.as_ref().map(Spanned::span),
                    Some("upper.shape".into()),
                    format!("\"{other}\" is not a shape of the upper body; allowed: \"block\", \"cylinder\" (with radius)"),
                ));
            }
        };
        let ratio = match &u.ratio {
            None => (1, 1),
            Some(r) => match r.get_ref()[..] {
                [a, b]
                    if (1..=i64::from(MAX_RATIO)).contains(&a) && (1..=i64::from(MAX_RATIO)).contains(&b) =>
                {
                    (a as u32, b as u32)
                }
                _ => {
                    return Err(self.error(
                        Some(r.span()),
                        Some("upper.ratio".into()),
                        format!(
                            "{:?} is not a ratio; allowed: two whole numbers [upper, lower], each 1 to {MAX_RATIO}: the upper body's elements across the interface for that many of the lower's",
                            r.get_ref()
                        ),
                    ));
                }
            },
        };
        let offset = match &u.offset {
            None => 0.0,
            Some(o) => {
                self.check("upper.offset", o, |v| {
                    check::open(
                        *v,
                        -0.5,
                        0.5,
                        check::Allowed::Said(
                            "a fraction of the upper body's element strictly between -0.5 and 0.5",
                        ),
                    )
                })?;
                *o.get_ref()
            }
        };
        let slave = match &u.slave {
            None => Slave::Upper,
            Some(s) => match s.get_ref().as_str() {
                "upper" => Slave::Upper,
                "lower" => Slave::Lower,
                other => {
                    return Err(self.error(
                        Some(s.span()),
                        Some("upper.slave".into()),
                        format!("\"{other}\" is not a side; allowed: \"upper\", \"lower\""),
                    ));
                }
            },
        };
        self.two_body_conflicts(raw)?;
        Ok(Upper {
            material: Material {
                young: *u.young.get_ref(),
                poisson: *u.poisson.get_ref(),
                plane: raw.material.plane,
            },
            height: *u.height.get_ref(),
            shape,
            ratio,
            offset,
            support: self.support("upper.support", u.support.as_ref())?,
            displacement: *u.displacement.get_ref(),
            slave,
        })
    }

    /// What two bodies do not take: friction, a graded mesh, a method other than `penalty`
    /// and `exact`.
    fn two_body_conflicts(&self, raw: &RawScenario) -> Result<(), ScenarioError> {
        if let Some(f) = raw
            .friction
            .as_ref()
            .filter(|f| f.get_ref().law.get_ref() != "none")
        {
            return Err(self.error(
                Some(f.get_ref().law.span()),
                Some("friction.law".into()),
                "friction is not available between two elastic bodies ([upper]) yet; allowed: \"none\""
                    .into(),
            ));
        }
        if let Some(r) = &raw.mesh.refine_edges {
            return Err(self.error(
                Some(r.span()),
                Some("mesh.refine_edges".into()),
                "grading is not available with two elastic bodies ([upper]) yet; give a finer level".into(),
            ));
        }
        if let Some(m) = &raw.contact.method {
            let method = Method::parse(m.get_ref(), None, None, None).ok();
            if !matches!(method, Some(Method::Penalty | Method::Exact | Method::Alm { .. })) {
                return Err(self.error(
                    Some(m.span()),
                    Some("contact.method".into()),
                    format!(
                        "\"{}\" does not apply with [upper]; allowed: \"penalty\" (ε > 0), \"exact\" (ε = 0) or \"alm\" (ε > 0), the interface's discretisation chosen by `riplab solve --contact`",
                        m.get_ref()
                    ),
                ));
            }
        }
        Ok(())
    }
}
