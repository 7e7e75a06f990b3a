//! Validation: a scenario file's schema turned into the model, every value checked against
//! its range ([`crate::check`]) and every error located at its key ([`Locator`]).

use std::ops::Range;
use std::path::Path;

use toml::Spanned;

use super::locate::{Locator, ScenarioError};
use super::schema::{Model, RawContact, RawObstacle, RawScenario, Shape};
use crate::check::{self, CheckError};
use crate::contact::gap::Bump;
use crate::contact::{Method, Obstacle};
use crate::fem::Integration;
use crate::grading::Grading;
use crate::material::Material;
use crate::scenario::Scenario;
use crate::text::{num, sanitize, sanitize_lines};

/// Parse and validate scenario text; `file` names it in errors.
pub(super) fn scenario(text: &str, file: &str) -> Result<Scenario, ScenarioError> {
    let loc = Locator { file, text };
    loc.check_nesting()?;
    loc.check_numbers(integer_range)?;
    let raw: RawScenario =
        toml::from_str(text).map_err(|e| loc.error(e.span(), None, e.message().trim().to_string()))?;

    loc.check("body.width", &raw.body.width, |v| check::length(*v))?;
    loc.check("body.height", &raw.body.height, |v| check::length(*v))?;
    loc.check("material.young", &raw.material.young, |v| check::young(*v))?;
    loc.check("material.poisson", &raw.material.poisson, |v| check::poisson(*v))?;
    let half_model = raw.body.model == Model::Half;
    let (x0, x1) = if half_model {
        (0.0, raw.body.width.get_ref() / 2.0)
    } else {
        (-raw.body.width.get_ref() / 2.0, raw.body.width.get_ref() / 2.0)
    };
    let (obstacle, upper) = loc.obstacle_or_upper(&raw, (x0, x1))?;
    let support = loc.support("body.support", raw.body.support.as_ref())?;
    if let Some(c) = raw
        .obstacle
        .as_ref()
        .and_then(|o| o.center.as_ref())
        .filter(|c| half_model && *c.get_ref() != 0.0)
    {
        return Err(loc.error(
            Some(c.span()),
            Some("obstacle.center".into()),
            format!(
                "{} is not allowed for a half model; allowed: 0 (the symmetry line)",
                c.get_ref()
            ),
        ));
    }
    if let (true, Some(raw_obstacle)) = (half_model, &raw.obstacle) {
        // The half model's symmetry line x = 0 must be the obstacle's too.
        let n = 400;
        for i in 1..=n {
            let x = x1 * i as f64 / n as f64;
            let (a, b) = (obstacle.gap(x), obstacle.gap(-x));
            if a != b && (a - b).abs() > 1e-9 * (1.0 + a.abs().min(b.abs())) {
                return Err(loc.error(
                    Some(raw_obstacle.shape.span()),
                    Some("obstacle".into()),
                    format!("a half model needs an obstacle symmetric about x = 0; here g({x}) = {a} but g({}) = {b}", -x),
                ));
            }
        }
    }
    let x_lines = loc.lines("mesh", "nx", "x_lines", &raw.mesh.nx, &raw.mesh.x_lines, (x0, x1))?;
    let y_lines = loc.lines(
        "mesh",
        "ny",
        "y_lines",
        &raw.mesh.ny,
        &raw.mesh.y_lines,
        (0.0, *raw.body.height.get_ref()),
    )?;
    let level = match &raw.mesh.level {
        Some(l) => {
            loc.check("mesh.level", l, |v| check::level(*v))?;
            *l.get_ref() as u32
        }
        None => 0,
    };
    let grading = match &raw.mesh.refine_edges {
        Some(r) => {
            loc.check("mesh.refine_edges", r, |v| v.parse().map(|_| ()))?;
            r.get_ref().parse().unwrap_or_default()
        }
        None => Grading::default(),
    };
    // The flattest cell of the level-0 grid (every level bisects both sides alike).
    let spacing = |v: &[f64]| {
        v.windows(2)
            .map(|w| w[1] - w[0])
            .fold((f64::INFINITY, 0.0_f64), |(lo, hi), d| (lo.min(d), hi.max(d)))
    };
    let ((dx_min, dx_max), (dy_min, dy_max)) = (spacing(&x_lines), spacing(&y_lines));
    let aspect = (dx_max / dy_min).max(dy_max / dx_min);
    if aspect.is_nan() || aspect > check::ASPECT {
        let (key, span) = match (&raw.mesh.nx, &raw.mesh.x_lines) {
            (Some(n), _) => ("mesh.nx", n.span()),
            (None, Some(l)) => ("mesh.x_lines", l.span()),
            (None, None) => unreachable!("the lines were given"),
        };
        return Err(loc.error(
            Some(span),
            Some(key.into()),
            format!(
                "the level-0 cells are up to {} times longer than they are high (or high than long): allowed at most {}; change body.width, body.height or mesh.nx/mesh.ny (or the lines) so that the cells are closer to square",
                num(aspect),
                num(check::ASPECT)
            ),
        ));
    }
    let h = crate::mesh::cell_size(&x_lines, &y_lines, level);
    let range = crate::material::epsilon_range(*raw.material.young.get_ref(), h);
    loc.check("contact.epsilon", &raw.contact.epsilon, |v| {
        check::epsilon_in(*v, range)
    })?;

    let (method, epsilon) = loc.method(&raw.contact)?;
    let friction = loc.friction(raw.friction.as_ref(), &raw.body, &obstacle, (x0, x1))?;
    loc.friction_conflicts(&raw, method, &friction, grading)?;

    let name = raw.name.unwrap_or_else(|| {
        Path::new(file)
            .file_stem()
            .map_or_else(|| "scenario".into(), |s| s.to_string_lossy().into_owned())
    });
    let mut scenario = Scenario {
        name: sanitize(&name).into_owned(),
        description: sanitize_lines(&raw.description),
        source: file.to_string(),
        width: *raw.body.width.get_ref(),
        height: *raw.body.height.get_ref(),
        half_model,
        material: Material {
            young: *raw.material.young.get_ref(),
            poisson: *raw.material.poisson.get_ref(),
            plane: raw.material.plane,
        },
        obstacle,
        support,
        upper,
        element: raw.mesh.element,
        x_lines,
        y_lines,
        integration: raw.mesh.integration.unwrap_or(Integration::Full),
        level,
        refine_edges: Default::default(),
        refine_zone: 0,
        rule: raw.contact.rule,
        method,
        epsilon,
        friction,
    };
    scenario.set_grading(grading);
    Ok(scenario)
}

/// The range of each integer key of a scenario file, as the validation checks it (for an
/// integer too large to read, [`Locator::check_numbers`]).
fn integer_range(key: &str) -> Option<(i64, i64)> {
    match key {
        "mesh.level" => Some((0, i64::from(crate::mesh::MAX_LEVEL))),
        "mesh.nx" | "mesh.ny" => Some((1, check::MAX_CELLS_0)),
        "mesh.refine_edges" => Some((0, i64::from(crate::grading::MAX_PASSES))),
        "friction.steps" => Some((1, crate::contact::friction::MAX_STEPS as i64)),
        _ => None,
    }
}

impl Locator<'_> {
    /// The method of `[contact]` and the ε it uses, each key's error at its value.
    fn method(&self, raw: &RawContact) -> Result<(Method, f64), ScenarioError> {
        let at = |key: &str| -> Option<Range<usize>> {
            match key {
                "method" => raw.method.as_ref().map(Spanned::span),
                "theta" => raw.theta.as_ref().map(Spanned::span),
                "gamma0" => raw.gamma0.as_ref().map(Spanned::span),
                "alm_tol" => raw.alm_tol.as_ref().map(Spanned::span),
                _ => Some(raw.epsilon.span()),
            }
        };
        let fail = |e: crate::error::MethodError| {
            let key = e.key();
            // A parameter without a method is reported at the parameter.
            let span = at(key).or_else(|| at("method")).or_else(|| at("epsilon"));
            self.error(span, Some(format!("contact.{key}")), e.to_string())
        };
        let get = |v: &Option<Spanned<f64>>| v.as_ref().map(|v| *v.get_ref());
        let gamma0 = raw
            .gamma0
            .as_ref()
            .map(|g| g.get_ref().parse())
            .transpose()
            .map_err(fail)?;
        let (theta, alm_tol) = (get(&raw.theta), get(&raw.alm_tol));
        let method = match &raw.method {
            Some(name) => Some(Method::parse(name.get_ref(), theta, gamma0, alm_tol).map_err(fail)?),
            None => {
                // Parameters without a method name belong to the method ε implies.
                let implied = Method::resolve(None, *raw.epsilon.get_ref()).map_err(fail)?.0;
                if theta.is_some() || gamma0.is_some() || alm_tol.is_some() {
                    implied.with(theta, gamma0, alm_tol).map_err(fail)?;
                }
                None
            }
        };
        Method::resolve(method, *raw.epsilon.get_ref()).map_err(fail)
    }

    /// A required positive/finite value of `[obstacle]`.
    fn required(
        &self,
        key: &str,
        v: &Option<Spanned<f64>>,
        shape: Shape,
        span: Range<usize>,
        test: fn(f64) -> Result<(), CheckError>,
    ) -> Result<f64, ScenarioError> {
        let v = v.as_ref().ok_or_else(|| {
            self.error(
                Some(span),
                Some(format!("obstacle.{key}")),
                format!(
                    "is required for shape {shape:?}; its keys: {}",
                    shape.keys().join(", ")
                ),
            )
        })?;
        self.check(&format!("obstacle.{key}"), v, |x| test(*x))?;
        Ok(*v.get_ref())
    }

    /// The obstacle of `[obstacle]`, every key checked against its shape.
    pub(super) fn obstacle(&self, raw: &RawObstacle, height: f64) -> Result<Obstacle, ScenarioError> {
        let shape = *raw.shape.get_ref();
        self.check("obstacle.depth", &raw.depth, |v| check::depth(*v, height))?;
        let given: [(&str, Option<Range<usize>>); 6] = [
            ("radius", raw.radius.as_ref().map(|v| v.span())),
            ("center", raw.center.as_ref().map(|v| v.span())),
            ("half_width", raw.half_width.as_ref().map(|v| v.span())),
            ("corner_radius", raw.corner_radius.as_ref().map(|v| v.span())),
            ("bumps", raw.bumps.as_ref().map(|v| v.span())),
            ("points", raw.points.as_ref().map(|v| v.span())),
        ];
        for (key, span) in given {
            if let Some(span) = span.filter(|_| !shape.keys().contains(&key)) {
                return Err(self.error(
                    Some(span),
                    Some(format!("obstacle.{key}")),
                    format!(
                        "does not apply to shape {shape:?}; its keys: {}",
                        shape.keys().join(", ")
                    ),
                ));
            }
        }
        let depth = *raw.depth.get_ref();
        let span = raw.shape.span();
        let center = match &raw.center {
            Some(c) => {
                self.check("obstacle.center", c, |v| check::coordinate(*v))?;
                *c.get_ref()
            }
            None => 0.0,
        };
        Ok(match shape {
            Shape::Cylinder => Obstacle::Cylinder {
                radius: self.required("radius", &raw.radius, shape, span, check::length)?,
                depth,
                center,
            },
            Shape::Punch => Obstacle::Punch {
                half_width: self.required(
                    "half_width",
                    &raw.half_width,
                    shape,
                    span.clone(),
                    check::length_or_zero,
                )?,
                corner_radius: self.required(
                    "corner_radius",
                    &raw.corner_radius,
                    shape,
                    span,
                    check::length,
                )?,
                depth,
                center,
            },
            Shape::Bumps => {
                let list = raw.bumps.as_ref().ok_or_else(|| {
                    self.error(
                        Some(span.clone()),
                        Some("obstacle.bumps".into()),
                        "is required for shape Bumps: a list of { center, radius, lift }".into(),
                    )
                })?;
                if list.get_ref().is_empty() {
                    return Err(self.error(
                        Some(list.span()),
                        Some("obstacle.bumps".into()),
                        "is empty; allowed: at least one bump".into(),
                    ));
                }
                let mut bumps = Vec::new();
                for b in list.get_ref() {
                    self.check("obstacle.bumps.center", &b.center, |v| check::coordinate(*v))?;
                    self.check("obstacle.bumps.radius", &b.radius, |v| check::length(*v))?;
                    let lift = match &b.lift {
                        Some(l) => {
                            self.check("obstacle.bumps.lift", l, |v| {
                                check::nonnegative(*v).and(check::coordinate(*v))
                            })?;
                            *l.get_ref()
                        }
                        None => 0.0,
                    };
                    bumps.push(Bump {
                        center: *b.center.get_ref(),
                        radius: *b.radius.get_ref(),
                        lift,
                    });
                }
                Obstacle::Bumps { bumps, depth }
            }
            Shape::Polyline => {
                let list = raw.points.as_ref().ok_or_else(|| {
                    self.error(
                        Some(span.clone()),
                        Some("obstacle.points".into()),
                        "is required for shape Polyline: a list of [x, height]".into(),
                    )
                })?;
                if list.get_ref().len() < 2 {
                    return Err(self.error(
                        Some(list.span()),
                        Some("obstacle.points".into()),
                        "needs at least two points".into(),
                    ));
                }
                let mut points: Vec<(f64, f64)> = Vec::new();
                for p in list.get_ref() {
                    self.check("obstacle.points", p, |v| check::point(v))?;
                    let (x, y) = (p.get_ref()[0], p.get_ref()[1]);
                    if points.last().is_some_and(|q| q.0 >= x) {
                        return Err(self.error(
                            Some(p.span()),
                            Some("obstacle.points".into()),
                            format!("x = {x} does not increase; allowed: strictly increasing x"),
                        ));
                    }
                    points.push((x, y));
                }
                Obstacle::Polyline { points, depth }
            }
        })
    }

    /// Level-0 vertex lines from a cell count `n_key` or explicit lines `lines_key` spanning
    /// `range` (exactly one of them).
    fn lines(
        &self,
        table: &str,
        n_key: &str,
        lines_key: &str,
        n: &Option<Spanned<i64>>,
        lines: &Option<Spanned<Vec<f64>>>,
        range: (f64, f64),
    ) -> Result<Vec<f64>, ScenarioError> {
        let (lo, hi) = range;
        match (n, lines) {
            (Some(n), None) => {
                self.check(&format!("{table}.{n_key}"), n, |v| {
                    check::integer(*v, 1, check::MAX_CELLS_0)
                })?;
                let k = *n.get_ref() as usize;
                Ok((0..=k).map(|i| lo + (hi - lo) * i as f64 / k as f64).collect())
            }
            (None, Some(l)) => {
                let v = l.get_ref();
                let key = format!("{table}.{lines_key}");
                let ok = v.len() >= 2
                    && v.len() as i64 <= check::MAX_CELLS_0 + 1
                    && v.iter().all(|x| x.is_finite())
                    && v.windows(2).all(|w| w[0] < w[1])
                    && (v[0] - lo).abs() <= 1e-12 * (1.0 + lo.abs())
                    && (v[v.len() - 1] - hi).abs() <= 1e-12 * (1.0 + hi.abs());
                if !ok {
                    return Err(self.error(
                        Some(l.span()),
                        Some(key),
                        format!(
                            "allowed: 2 to {} strictly increasing finite numbers from {lo} to {hi}",
                            check::MAX_CELLS_0 + 1
                        ),
                    ));
                }
                Ok(v.clone())
            }
            (Some(n), Some(_)) => Err(self.error(
                Some(n.span()),
                Some(format!("{table}.{n_key}")),
                format!("give either {n_key} or {lines_key}, not both"),
            )),
            (None, None) => Err(self.error(
                None,
                Some(format!("{table}.{n_key}")),
                format!("missing: give {n_key} (uniform cells) or {lines_key} (graded)"),
            )),
        }
    }
}
