//! `[upper]` validated (docs/design.md §12): the upper elastic body in place of the rigid
//! obstacle — E and ν in their ranges, a height, a width up to the lower body's, the shape `block` or `cylinder` (with its radius), the ratio of two whole
//! numbers 1 to [`MAX_RATIO`], an offset |offset| < 1/2, the support among `clamped` and
//! `roller`, the top's displacement within ± the thinner body's height or a pressure on it (the
//! half model's), the slave among
//! `upper` and `lower` (a narrower upper body is the slave). `[obstacle]` beside it is refused, and so is what the two-body solve
//! does not take (friction, a graded mesh, a method other than the penalty or the exact
//! multipliers). Every error: file, line, column, key, value, range.

use toml::Spanned;

use super::locate::{Locator, ScenarioError};
use super::schema::{Model, RawScenario, RawUpper};
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
                // A block as wide as the lower body: a flat beyond both ends; narrower: a flat
                // punch of its width.
                let reach = if upper.width < *raw.body.width.get_ref() {
                    upper.width / 2.0
                } else {
                    (x1 - x0).abs() + x0.abs() + x1.abs() + 1.0
                };
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

    /// The element ratio under `key` (`[upper] ratio`, or a tour step's `ratio`): two whole
    /// numbers [upper, lower], each 1 to [`MAX_RATIO`].
    pub(crate) fn ratio(&self, key: &str, r: &Spanned<Vec<i64>>) -> Result<(u32, u32), ScenarioError> {
        match r.get_ref()[..] {
            [a, b] if (1..=i64::from(MAX_RATIO)).contains(&a) && (1..=i64::from(MAX_RATIO)).contains(&b) => {
                Ok((a as u32, b as u32))
            }
            _ => Err(self.error(
                Some(r.span()),
                Some(key.into()),
                format!(
                    "{:?} is not a ratio; allowed: two whole numbers [upper, lower], each 1 to {MAX_RATIO}: the upper body's elements across the interface for that many of the lower's",
                    r.get_ref()
                ),
            )),
        }
    }

    /// The upper mesh's offset under `key` (`[upper] offset`, or a tour step's `offset`): a
    /// fraction of the upper body's element, |offset| < 1/2.
    pub(crate) fn offset(&self, key: &str, o: &Spanned<f64>) -> Result<f64, ScenarioError> {
        self.check(key, o, |v| {
            check::open(
                *v,
                -0.5,
                0.5,
                check::Allowed::Said("a fraction of the upper body's element strictly between -0.5 and 0.5"),
            )
        })?;
        Ok(*o.get_ref())
    }

    /// The upper body of `[upper]`, and what the rest of `raw` asks that two bodies do not take.
    fn upper(&self, u: &RawUpper, raw: &RawScenario) -> Result<Upper, ScenarioError> {
        self.check("upper.young", &u.young, |v| check::young(*v))?;
        self.check("upper.poisson", &u.poisson, |v| check::poisson(*v))?;
        self.check("upper.height", &u.height, |v| check::length(*v))?;
        let lower_width = *raw.body.width.get_ref();
        let width = match &u.width {
            None => lower_width,
            Some(w) => {
                let lo = check::LENGTH.0.min(lower_width);
                self.check("upper.width", w, |v| {
                    let allowed = check::Allowed::Range {
                        what: "a width",
                        lo,
                        hi: lower_width,
                        note: " (a length, at most the lower body's width)",
                    };
                    check::closed(*v, lo, lower_width, allowed)
                })?;
                *w.get_ref()
            }
        };
        let (displacement, pressure) = self.top_load(u, raw)?;
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
            Some(r) => self.ratio("upper.ratio", r)?,
        };
        let offset = match &u.offset {
            None => 0.0,
            Some(o) => self.offset("upper.offset", o)?,
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
        if width < lower_width && slave == Slave::Lower {
            return Err(self.error(
                u.slave.as_ref().map(Spanned::span),
                Some("upper.slave".into()),
                "\"lower\" does not apply to an upper body narrower than the lower one: the narrower body is the slave, its whole interface over the other's; allowed: \"upper\"".into(),
            ));
        }
        self.two_body_conflicts(raw)?;
        Ok(Upper {
            material: Material {
                young: *u.young.get_ref(),
                poisson: *u.poisson.get_ref(),
                plane: raw.material.plane,
            },
            height: *u.height.get_ref(),
            width,
            shape,
            ratio,
            offset,
            support: match pressure {
                Some(_) => Support::Free,
                None => self.support("upper.support", u.support.as_ref())?,
            },
            displacement,
            pressure,
            slave,
        })
    }

    /// The upper body's load: its top pressed down by `displacement` (within ± the thinner
    /// body's height) or under a uniform `pressure` above 0 and at most the softer body's E
    /// (the half model's, its top then held by a pin alone, no `support`), one of the two
    /// exactly.
    fn top_load(&self, u: &RawUpper, raw: &RawScenario) -> Result<(f64, Option<f64>), ScenarioError> {
        match (&u.displacement, &u.pressure) {
            (Some(d), None) => {
                let thinner = raw.body.height.get_ref().min(*u.height.get_ref());
                self.check("upper.displacement", d, |v| check::depth(*v, thinner))?;
                Ok((*d.get_ref(), None))
            }
            (None, Some(q)) => {
                // At most a strain of 1 in the softer body, as a displacement is at most its height.
                let softer = raw.material.young.get_ref().min(*u.young.get_ref());
                self.check("upper.pressure", q, |v| {
                    let allowed = check::Allowed::Range {
                        what: "a pressure",
                        lo: 0.0,
                        hi: softer,
                        note: " (above 0, compression; at most the softer body's E)",
                    };
                    if *v > 0.0 {
                        check::closed(*v, 0.0, softer, allowed)
                    } else {
                        check::open(*v, 0.0, softer, allowed)
                    }
                })?;
                if raw.body.model != Model::Half {
                    return Err(self.error(
                        Some(q.span()),
                        Some("upper.pressure".into()),
                        "needs the half model (body.model = \"half\"): its symmetry line holds the pressed body's rotation; allowed with model = \"half\", or give displacement".into(),
                    ));
                }
                if let Some(s) = &u.support {
                    return Err(self.error(
                        Some(s.span()),
                        Some("upper.support".into()),
                        "does not apply with pressure: the pressed top is free, held by one pin (docs/design.md §12); give support with displacement only".into(),
                    ));
                }
                Ok((0.0, Some(*q.get_ref())))
            }
            (Some(_), Some(q)) => Err(self.error(
                Some(q.span()),
                Some("upper.pressure".into()),
                "does not apply with displacement: give one of displacement (δ, the top pressed down) and pressure (q on the top)".into(),
            )),
            (None, None) => Err(self.error(
                None,
                Some("upper.displacement".into()),
                "missing: give displacement (δ, the top pressed down) or pressure (q on the top)".into(),
            )),
        }
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
