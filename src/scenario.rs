//! Scenarios: the TOML description of a problem (docs/design.md §1), its validation, and the paper's
//! problem embedded as the default.
//!
//! Every value is checked against its allowed range; an error names the file, the line and
//! column, the key, the value, and what is allowed.

use std::fmt;
use std::ops::Range;
use std::path::Path;

use serde::Deserialize;
use toml::Spanned;

use crate::contact::gap::Bump;
use crate::contact::{Method, Obstacle, Rule};
use crate::fem::Integration;
use crate::material::{Material, Plane};
use crate::mesh::{Element, Mesh};
use crate::text::{num, sanitize, sanitize_lines};

/// The paper's problem, half model: `scenarios/hertz-paper.toml`.
pub const DEFAULT_SCENARIO: &str = include_str!("../scenarios/hertz-paper.toml");
/// The name under which the embedded default is reported.
pub const DEFAULT_SOURCE: &str = "<embedded hertz-paper.toml>";

/// The finest mesh level riplab accepts.
pub const MAX_LEVEL: u32 = 8;
/// The largest level-0 grid in either direction.
pub const MAX_CELLS_0: i64 = 4096;

/// A validated problem.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    pub name: String,
    pub description: String,
    /// Where it was read from (a path, or [`DEFAULT_SOURCE`]).
    pub source: String,
    /// Full width and height of the body.
    pub width: f64,
    pub height: f64,
    pub half_model: bool,
    pub material: Material,
    pub obstacle: Obstacle,
    pub element: Element,
    /// Vertex lines of the level-0 grid across the modelled width and the height (uniform,
    /// or graded); each level bisects every cell.
    pub x_lines: Vec<f64>,
    pub y_lines: Vec<f64>,
    /// Integration of the stiffness: full, or selective (reduced for the volumetric part).
    pub integration: Integration,
    pub level: u32,
    pub rule: Rule,
    /// How the constraint is imposed: `[contact] method` (with its parameters), or by ε:
    /// `penalty` for ε > 0, `exact` for ε = 0 ([`Method::resolve`]).
    pub method: Method,
    /// The penalty parameter (0 for `exact`).
    pub epsilon: f64,
}

/// What went wrong in a scenario, and where.
#[derive(Clone, Debug, PartialEq)]
pub struct ScenarioError {
    pub file: String,
    /// 1-based (line, column), when known.
    pub location: Option<(usize, usize)>,
    /// Dotted key, e.g. `material.poisson`, when known.
    pub key: Option<String>,
    pub message: String,
    /// The offending source line, for display.
    pub source_line: Option<String>,
}

impl std::error::Error for ScenarioError {}

/// Every piece of text that came from the file (its name, keys, the message that may quote
/// the file, the source line) is sanitised: an error must not replay escape sequences.
impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", sanitize(&self.file))?;
        if let Some((line, col)) = self.location {
            write!(f, ":{line}:{col}")?;
        }
        write!(f, ": ")?;
        if let Some(key) = &self.key {
            write!(f, "`{}`: ", sanitize(key))?;
        }
        write!(f, "{}", sanitize_lines(&self.message))?;
        if let (Some((line, col)), Some(text)) = (self.location, &self.source_line) {
            write!(f, "\n {line:>4} | {}\n      | {:>col$}", sanitize(text), "^")?;
        }
        Ok(())
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScenario {
    name: Option<String>,
    #[serde(default)]
    description: String,
    body: RawBody,
    material: RawMaterial,
    obstacle: RawObstacle,
    mesh: RawMesh,
    contact: RawContact,
}

#[derive(Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
enum Model {
    Half,
    Full,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    width: Spanned<f64>,
    height: Spanned<f64>,
    model: Model,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    young: Spanned<f64>,
    poisson: Spanned<f64>,
    plane: Plane,
}

#[derive(Deserialize, Clone, Copy, PartialEq, Eq, Debug)]
#[serde(rename_all = "lowercase")]
enum Shape {
    Cylinder,
    Punch,
    Bumps,
    Polyline,
}

impl Shape {
    /// The keys of `[obstacle]` that each shape takes (besides `shape` and `depth`).
    fn keys(self) -> &'static [&'static str] {
        match self {
            Shape::Cylinder => &["radius", "center"],
            Shape::Punch => &["half_width", "corner_radius", "center"],
            Shape::Bumps => &["bumps"],
            Shape::Polyline => &["points"],
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawObstacle {
    shape: Spanned<Shape>,
    depth: Spanned<f64>,
    radius: Option<Spanned<f64>>,
    center: Option<Spanned<f64>>,
    half_width: Option<Spanned<f64>>,
    corner_radius: Option<Spanned<f64>>,
    bumps: Option<Spanned<Vec<RawBump>>>,
    points: Option<Spanned<Vec<Spanned<Vec<f64>>>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBump {
    center: Spanned<f64>,
    radius: Spanned<f64>,
    #[serde(default)]
    lift: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMesh {
    element: Element,
    nx: Option<Spanned<i64>>,
    ny: Option<Spanned<i64>>,
    x_lines: Option<Spanned<Vec<f64>>>,
    y_lines: Option<Spanned<Vec<f64>>>,
    #[serde(default)]
    level: Option<Spanned<i64>>,
    #[serde(default)]
    integration: Option<Integration>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawContact {
    rule: Rule,
    epsilon: Spanned<f64>,
    /// `penalty`, `exact`, `alm` or `nitsche` ([`Method::parse`]).
    method: Option<Spanned<String>>,
    theta: Option<Spanned<f64>>,
    gamma0: Option<Spanned<f64>>,
    alm_tol: Option<Spanned<f64>>,
}

/// Checks of single values, shared by the scenario file and the command-line overrides.
pub mod check {
    use crate::text::num;

    /// The largest and smallest magnitude of a length (body sizes, radii, coordinates): a
    /// scenario's units must put its lengths within 1e-6 to 1e6, so that the stiffness, the
    /// gaps and the forces stay far from the limits of double precision.
    pub const LENGTH: (f64, f64) = (1e-6, 1e6);
    /// The range of Young's modulus E (any units).
    pub const YOUNG: (f64, f64) = (1e-6, 1e12);
    /// The largest aspect ratio of a level-0 cell: beyond it the stiffness of a cell is lost
    /// to round-off (Q1's entries scale with hx/hy and hy/hx).
    pub const ASPECT: f64 = 1e4;

    /// A finite number in (lo, hi) (open ends).
    pub fn open(value: f64, lo: f64, hi: f64, allowed: &str) -> Result<(), String> {
        if !value.is_finite() {
            return Err(format!(
                "{} is not a finite number; allowed: {allowed}",
                num(value)
            ));
        }
        if value > lo && value < hi {
            Ok(())
        } else {
            Err(format!("{} is out of range; allowed: {allowed}", num(value)))
        }
    }
    /// A finite number in [lo, hi] (closed ends).
    pub fn closed(value: f64, lo: f64, hi: f64, allowed: &str) -> Result<(), String> {
        if value.is_finite() && value >= lo && value <= hi {
            Ok(())
        } else {
            open(value, f64::NAN, f64::NAN, allowed)
        }
    }
    pub fn positive(value: f64) -> Result<(), String> {
        open(value, 0.0, f64::INFINITY, "a finite number > 0")
    }
    pub fn nonnegative(value: f64) -> Result<(), String> {
        if value == 0.0 {
            Ok(())
        } else {
            open(value, 0.0, f64::INFINITY, "a finite number ≥ 0")
        }
    }
    /// A length: within [`LENGTH`].
    pub fn length(value: f64) -> Result<(), String> {
        let (lo, hi) = LENGTH;
        closed(
            value,
            lo,
            hi,
            &format!("a length from {} to {}", num(lo), num(hi)),
        )
    }
    /// A length that may be 0 (a punch's flat half-width).
    pub fn length_or_zero(value: f64) -> Result<(), String> {
        if value == 0.0 { Ok(()) } else { length(value) }
    }
    /// A coordinate or a signed offset: |value| at most [`LENGTH`]'s upper end.
    pub fn coordinate(value: f64) -> Result<(), String> {
        let hi = LENGTH.1;
        closed(
            value,
            -hi,
            hi,
            &format!("a finite number from {} to {}", num(-hi), num(hi)),
        )
    }
    /// Young's modulus: within [`YOUNG`].
    pub fn young(value: f64) -> Result<(), String> {
        let (lo, hi) = YOUNG;
        closed(
            value,
            lo,
            hi,
            &format!("a modulus from {} to {}", num(lo), num(hi)),
        )
    }
    /// The penalty parameter: ε > 0, or 0 for the exact constraint (its range depends on the
    /// mesh and the material: see [`crate::solve::epsilon_range`]).
    pub fn epsilon(value: f64) -> Result<(), String> {
        if value == 0.0 {
            Ok(())
        } else {
            open(
                value,
                0.0,
                f64::INFINITY,
                "a finite number > 0, or 0 for the exact constraint",
            )
        }
    }
    /// ε within `range` (from [`crate::solve::epsilon_range`]), or 0.
    pub fn epsilon_in(value: f64, (lo, hi): (f64, f64)) -> Result<(), String> {
        epsilon(value)?;
        if value == 0.0 || (lo..=hi).contains(&value) {
            Ok(())
        } else {
            Err(format!(
                "ε = {} is out of range; allowed: 0 (the exact constraint) or {} to {} here (ε·E/h from {} to {}, so that the penalty's products stay finite)",
                num(value),
                num(lo),
                num(hi),
                num(crate::solve::KAPPA_RANGE.0),
                num(crate::solve::KAPPA_RANGE.1)
            ))
        }
    }
    /// The indentation depth: beyond the body's height it is meaningless (the obstacle would
    /// pass through the clamped base).
    pub fn depth(value: f64, height: f64) -> Result<(), String> {
        open(
            value,
            -height,
            height,
            &format!(
                "a depth between {} and {} (the body is {} high)",
                num(-height),
                num(height),
                num(height)
            ),
        )
    }
    pub fn poisson(value: f64) -> Result<(), String> {
        open(
            value,
            -1.0,
            0.5,
            "−1 < ν < 0.5 (ν = 0.5 is incompressible, which the displacement formulation cannot represent)",
        )
    }
    pub fn integer(value: i64, lo: i64, hi: i64) -> Result<(), String> {
        if (lo..=hi).contains(&value) {
            Ok(())
        } else {
            Err(format!("{value} is out of range; allowed: {lo} to {hi}"))
        }
    }
    pub fn level(value: i64) -> Result<(), String> {
        integer(value, 0, i64::from(super::MAX_LEVEL))
    }
}

/// Turns byte spans of a TOML text into located errors (used for scenarios and tours).
pub struct Locator<'a> {
    pub file: &'a str,
    pub text: &'a str,
}

impl Locator<'_> {
    /// An error at `span` about `key` (inferred from the line's `key = value` when None).
    pub fn error(&self, span: Option<Range<usize>>, key: Option<String>, message: String) -> ScenarioError {
        let (location, source_line) = match span {
            Some(span) => {
                let start = span.start.min(self.text.len());
                let start = (0..=start)
                    .rev()
                    .find(|&i| self.text.is_char_boundary(i))
                    .unwrap_or(0);
                let before = &self.text[..start];
                let line = before.matches('\n').count() + 1;
                let line_start = before.rfind('\n').map_or(0, |i| i + 1);
                let column = self.text[line_start..start].chars().count() + 1;
                let text = self.text[line_start..].lines().next().unwrap_or("").to_string();
                (Some((line, column)), Some(text))
            }
            None => (None, None),
        };
        // A missing field is reported at the table that lacks it: name the field.
        let missing = message
            .strip_prefix("missing field `")
            .and_then(|rest| rest.split('`').next())
            .map(str::to_string);
        let key = key.or_else(|| {
            let at = location.and_then(|(l, _)| self.key_at(l));
            match (missing, at) {
                (Some(field), Some(at)) if location.is_some_and(|(l, c)| l > 1 || c > 1) => {
                    Some(format!("{at}.{field}"))
                }
                (Some(field), _) => Some(field),
                (None, at) => at,
            }
        });
        ScenarioError {
            file: self.file.to_string(),
            location,
            key,
            message,
            source_line,
        }
    }

    /// The dotted key assigned on 1-based `line` (`table.key`), found from the text; inside
    /// an array of inline tables (`bumps = [ { … }, … ]`), the array's key.
    fn key_at(&self, line: usize) -> Option<String> {
        let lines: Vec<&str> = self.text.lines().collect();
        let here = lines.get(line - 1)?.trim();
        let header = |l: &str| l.trim_matches(|c| c == '[' || c == ']').trim().to_string();
        if here.starts_with('[') {
            return Some(header(here));
        }
        let above = &lines[..line - 1];
        let start = above
            .iter()
            .rposition(|l| l.trim().starts_with('['))
            .map_or(0, |i| i + 1);
        let table = start.checked_sub(1).map(|i| header(above[i].trim()));
        let join = |key: &str| match &table {
            Some(t) => format!("{t}.{key}"),
            None => key.to_string(),
        };
        let bare = |k: &str| !k.is_empty() && k.chars().all(|c| c.is_alphanumeric() || "_-.".contains(c));
        let key = here
            .split('=')
            .next()
            .map(str::trim)
            .filter(|k| bare(k) && here.contains('='));
        if let Some(key) = key {
            return Some(join(key));
        }
        // Inside a multi-line array: the key of the line that opened it.
        let opened = above[start..]
            .iter()
            .rev()
            .find_map(|l| l.split_once('=').filter(|(_, v)| v.trim_start().starts_with('[')));
        match opened {
            Some((key, _)) if bare(key.trim()) => Some(join(key.trim())),
            _ => table,
        }
    }

    /// `test` of a spanned value, failing with an error at the value about `key`.
    pub fn check<T>(
        &self,
        key: &str,
        value: &Spanned<T>,
        test: impl Fn(&T) -> Result<(), String>,
    ) -> Result<(), ScenarioError> {
        test(value.get_ref()).map_err(|msg| self.error(Some(value.span()), Some(key.to_string()), msg))
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
        let fail = |e: crate::contact::method::MethodError| {
            let key = e.key();
            // A parameter without a method is reported at the parameter.
            let span = at(key).or_else(|| at("method")).or_else(|| at("epsilon"));
            self.error(span, Some(format!("contact.{key}")), e.to_string())
        };
        let get = |v: &Option<Spanned<f64>>| v.as_ref().map(|v| *v.get_ref());
        let (theta, gamma0, alm_tol) = (get(&raw.theta), get(&raw.gamma0), get(&raw.alm_tol));
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
        test: fn(f64) -> Result<(), String>,
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
    fn obstacle(&self, raw: &RawObstacle, height: f64) -> Result<Obstacle, ScenarioError> {
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
                    self.check("obstacle.points", p, |v| match v[..] {
                        [x, y] => check::coordinate(x).and(check::coordinate(y)),
                        _ => Err(format!(
                            "a point has {} coordinates; allowed: [x, height]",
                            v.len()
                        )),
                    })?;
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
                    check::integer(*v, 1, MAX_CELLS_0)
                })?;
                let k = *n.get_ref() as usize;
                Ok((0..=k).map(|i| lo + (hi - lo) * i as f64 / k as f64).collect())
            }
            (None, Some(l)) => {
                let v = l.get_ref();
                let key = format!("{table}.{lines_key}");
                let ok = v.len() >= 2
                    && v.len() as i64 <= MAX_CELLS_0 + 1
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
                            MAX_CELLS_0 + 1
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

/// The largest scenario or tour file riplab reads.
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// Read a TOML file of at most [`MAX_FILE_BYTES`] as UTF-8 text: (its name for errors, its
/// text). `what` names the kind of file in the errors ("a scenario", "a tour").
///
/// Only regular files are read (a FIFO would block, a device such as `/dev/zero` never
/// ends), and never more than the cap plus one byte, whatever size the file claims: a file
/// that grows while it is read is refused like one that was too large from the start.
pub fn read_toml(path: &Path, what: &str) -> Result<(String, String), ScenarioError> {
    use std::io::Read as _;
    let file = path.display().to_string();
    let plain = |message: String| ScenarioError {
        file: file.clone(),
        location: None,
        key: None,
        message,
        source_line: None,
    };
    let not_regular = |meta: &std::fs::Metadata| {
        plain(format!(
            "is not a regular file ({}); {what} is read from a regular file of at most 1 MiB",
            file_kind(meta)
        ))
    };
    // Ask before opening: opening a FIFO for reading blocks until a writer comes.
    let meta = std::fs::metadata(path).map_err(|e| plain(format!("cannot read: {e}")))?;
    if !meta.is_file() {
        return Err(not_regular(&meta));
    }
    let handle = std::fs::File::open(path).map_err(|e| plain(format!("cannot read: {e}")))?;
    // The file opened may not be the one asked about (a rename in between): ask again.
    let meta = handle
        .metadata()
        .map_err(|e| plain(format!("cannot read: {e}")))?;
    if !meta.is_file() {
        return Err(not_regular(&meta));
    }
    let mut bytes = Vec::with_capacity(meta.len().min(MAX_FILE_BYTES) as usize + 1);
    handle
        .take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| plain(format!("cannot read: {e}")))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(plain(format!(
            "is larger than 1 MiB ({} bytes or more); {what} is at most 1 MiB",
            bytes.len()
        )));
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        let offset = e.utf8_error().valid_up_to();
        let text = String::from_utf8_lossy(e.as_bytes()).into_owned();
        Locator {
            file: &file,
            text: &text,
        }
        .error(Some(offset..offset), None, "is not valid UTF-8".into())
    })?;
    Ok((file, text))
}

/// What kind of file system object `meta` describes, for an error message.
fn file_kind(meta: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt as _;
        let t = meta.file_type();
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if meta.is_dir() {
        "a directory"
    } else {
        "not a regular file"
    }
}

impl Scenario {
    /// The embedded default: the paper's problem.
    pub fn paper() -> Scenario {
        Scenario::parse(DEFAULT_SCENARIO, DEFAULT_SOURCE).expect("the embedded scenario is valid")
    }

    /// Read and validate a scenario file.
    pub fn load(path: &Path) -> Result<Scenario, ScenarioError> {
        let (file, text) = read_toml(path, "a scenario")?;
        Scenario::parse(&text, &file)
    }

    /// Parse and validate scenario text; `file` names it in errors.
    pub fn parse(text: &str, file: &str) -> Result<Scenario, ScenarioError> {
        let loc = Locator { file, text };
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
        let obstacle = loc.obstacle(&raw.obstacle, *raw.body.height.get_ref())?;
        if let Some(c) = raw
            .obstacle
            .center
            .as_ref()
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
        if half_model {
            // The half model's symmetry line x = 0 must be the obstacle's too.
            let n = 400;
            for i in 1..=n {
                let x = x1 * i as f64 / n as f64;
                let (a, b) = (obstacle.gap(x), obstacle.gap(-x));
                if a != b && (a - b).abs() > 1e-9 * (1.0 + a.abs().min(b.abs())) {
                    return Err(loc.error(
                        Some(raw.obstacle.shape.span()),
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
                    "the level-0 cells are up to {} times longer than they are high (or high than long): allowed at most {}; change mesh.nx/mesh.ny (or the lines) so that the cells are closer to square",
                    num(aspect),
                    num(check::ASPECT)
                ),
            ));
        }
        let h = dx_max.max(dy_max) / f64::from(1u32 << level);
        let range = crate::solve::epsilon_range(*raw.material.young.get_ref(), h);
        loc.check("contact.epsilon", &raw.contact.epsilon, |v| {
            check::epsilon_in(*v, range)
        })?;

        let (method, epsilon) = loc.method(&raw.contact)?;

        let name = raw.name.unwrap_or_else(|| {
            Path::new(file)
                .file_stem()
                .map_or_else(|| "scenario".into(), |s| s.to_string_lossy().into_owned())
        });
        Ok(Scenario {
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
            element: raw.mesh.element,
            x_lines,
            y_lines,
            integration: raw.mesh.integration.unwrap_or(Integration::Full),
            level,
            rule: raw.contact.rule,
            method,
            epsilon,
        })
    }

    /// The x-range of the modelled body.
    pub fn x_range(&self) -> (f64, f64) {
        if self.half_model {
            (0.0, self.width / 2.0)
        } else {
            (-self.width / 2.0, self.width / 2.0)
        }
    }

    /// The mesh of `level` with `element`: the level-0 grid with every cell bisected `level`
    /// times in each direction.
    pub fn mesh(&self, level: u32, element: Element) -> Mesh {
        Mesh::from_lines(
            element,
            bisect(&self.x_lines, level),
            bisect(&self.y_lines, level),
            self.half_model,
        )
    }

    /// The number of free dofs at `level` with `element`, counted without building the mesh
    /// (bottom clamped; u_x fixed on the symmetry line of a half model).
    pub fn n_dofs(&self, level: u32, element: Element) -> usize {
        let f = 1usize << level;
        let p = element.order();
        let (nnx, nny) = (
            p * (self.x_lines.len() - 1) * f + 1,
            p * (self.y_lines.len() - 1) * f + 1,
        );
        let symmetric = if self.half_model { nny - 1 } else { 0 };
        2 * nnx * (nny - 1) - symmetric
    }

    /// The number of elements at `level` with `element`, counted without building the mesh
    /// (two triangles per cell for P1, as [`crate::mesh::Mesh::n_elements`]).
    pub fn n_elements(&self, level: u32, element: Element) -> usize {
        let cells = ((self.x_lines.len() - 1) * (self.y_lines.len() - 1)) << (2 * level);
        match element {
            Element::P1 => 2 * cells,
            _ => cells,
        }
    }

    /// The penalty parameters accepted at `level` ([`crate::solve::epsilon_range`]).
    pub fn epsilon_range(&self, level: u32) -> (f64, f64) {
        crate::solve::epsilon_range(self.material.young, self.h(level))
    }

    /// The largest cell side at `level`.
    pub fn h(&self, level: u32) -> f64 {
        let widest = |v: &[f64]| v.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
        widest(&self.x_lines).max(widest(&self.y_lines)) / f64::from(1u32 << level)
    }
}

/// Vertex lines with every interval bisected `level` times.
fn bisect(lines: &[f64], level: u32) -> Vec<f64> {
    let f = 1usize << level;
    let mut out = Vec::with_capacity((lines.len() - 1) * f + 1);
    for w in lines.windows(2) {
        out.extend((0..f).map(|i| w[0] + (w[1] - w[0]) * i as f64 / f as f64));
    }
    out.push(lines[lines.len() - 1]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_the_paper() {
        let s = Scenario::paper();
        assert_eq!(s.name, "hertz-paper");
        assert_eq!((s.width, s.height, s.half_model), (16.0, 4.0, true));
        assert_eq!(
            s.obstacle,
            Obstacle::Cylinder {
                radius: 8.0,
                depth: 0.8,
                center: 0.0
            }
        );
        assert_eq!(
            (s.x_lines.len(), s.y_lines.len(), s.element, s.rule, s.epsilon),
            (9, 5, Element::Q1, Rule::Gauss1, 1e-6)
        );
        assert_eq!(s.mesh(1, Element::Q1).n_elements(), 128);
        assert_eq!(s.h(1), 0.5);
    }
}
