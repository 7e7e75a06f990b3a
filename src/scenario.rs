//! Scenarios: the TOML description of a problem (DESIGN §1), its validation, and the paper's
//! problem embedded as the default.
//!
//! Every value is checked against its allowed range; an error names the file, the line and
//! column, the key, the value, and what is allowed.

use std::fmt;
use std::ops::Range;
use std::path::Path;

use serde::Deserialize;
use toml::Spanned;

use crate::contact::{Obstacle, Rule};
use crate::material::{Material, Plane};
use crate::mesh::{Element, Mesh};

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
    /// Cells across the modelled width and the height at level 0.
    pub nx0: usize,
    pub ny0: usize,
    pub level: u32,
    pub rule: Rule,
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

impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if let Some((line, col)) = self.location {
            write!(f, ":{line}:{col}")?;
        }
        write!(f, ": ")?;
        if let Some(key) = &self.key {
            write!(f, "`{key}`: ")?;
        }
        write!(f, "{}", self.message)?;
        if let (Some((line, col)), Some(text)) = (self.location, &self.source_line) {
            write!(f, "\n {line:>4} | {text}\n      | {:>col$}", "^")?;
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

#[derive(Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
enum Shape {
    Cylinder,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawObstacle {
    shape: Shape,
    radius: Spanned<f64>,
    depth: Spanned<f64>,
    #[serde(default)]
    center: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMesh {
    element: Element,
    nx: Spanned<i64>,
    ny: Spanned<i64>,
    #[serde(default)]
    level: Option<Spanned<i64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawContact {
    rule: Rule,
    epsilon: Spanned<f64>,
}

/// Checks of single values, shared by the scenario file and the command-line overrides.
pub mod check {
    /// A finite number in (lo, hi) (open ends).
    pub fn open(value: f64, lo: f64, hi: f64, allowed: &str) -> Result<(), String> {
        if !value.is_finite() {
            return Err(format!("{value} is not a finite number; allowed: {allowed}"));
        }
        if value > lo && value < hi {
            Ok(())
        } else {
            Err(format!("{value} is out of range; allowed: {allowed}"))
        }
    }
    pub fn positive(value: f64) -> Result<(), String> {
        open(value, 0.0, f64::INFINITY, "a finite number > 0")
    }
    /// The penalty parameter: ε > 0, or 0 for the exact constraint.
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
    pub fn finite(value: f64) -> Result<(), String> {
        open(value, f64::NEG_INFINITY, f64::INFINITY, "any finite number")
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
            Err(format!("{value} is out of range; allowed: {lo}..={hi}"))
        }
    }
    pub fn level(value: i64) -> Result<(), String> {
        integer(value, 0, i64::from(super::MAX_LEVEL))
    }
}

/// Locates byte offsets in a source text.
struct Locator<'a> {
    file: &'a str,
    text: &'a str,
}

impl Locator<'_> {
    fn error(&self, span: Option<Range<usize>>, key: Option<String>, message: String) -> ScenarioError {
        let (location, source_line) = match span {
            Some(span) => {
                let start = span.start.min(self.text.len());
                let before = &self.text[..start];
                let line = before.matches('\n').count() + 1;
                let line_start = before.rfind('\n').map_or(0, |i| i + 1);
                let column = self.text[line_start..start].chars().count() + 1;
                let text = self.text[line_start..].lines().next().unwrap_or("").to_string();
                (Some((line, column)), Some(text))
            }
            None => (None, None),
        };
        let key = key.or_else(|| location.and_then(|(l, _)| self.key_at(l)));
        ScenarioError {
            file: self.file.to_string(),
            location,
            key,
            message,
            source_line,
        }
    }

    /// The dotted key assigned on 1-based `line` (`table.key`), found from the text.
    fn key_at(&self, line: usize) -> Option<String> {
        let lines: Vec<&str> = self.text.lines().collect();
        let here = lines.get(line - 1)?.trim();
        let table = lines[..line - 1]
            .iter()
            .rev()
            .map(|l| l.trim())
            .find(|l| l.starts_with('['))
            .map(|l| l.trim_matches(|c| c == '[' || c == ']').trim().to_string());
        if here.starts_with('[') {
            return Some(here.trim_matches(|c| c == '[' || c == ']').trim().to_string());
        }
        let key = here.split('=').next()?.trim();
        if key.is_empty() || here.split('=').count() < 2 {
            return table;
        }
        Some(match table {
            Some(t) => format!("{t}.{key}"),
            None => key.to_string(),
        })
    }

    fn check<T>(
        &self,
        key: &str,
        value: &Spanned<T>,
        test: impl Fn(&T) -> Result<(), String>,
    ) -> Result<(), ScenarioError> {
        test(value.get_ref()).map_err(|msg| self.error(Some(value.span()), Some(key.to_string()), msg))
    }
}

impl Scenario {
    /// The embedded default: the paper's problem.
    pub fn paper() -> Scenario {
        Scenario::parse(DEFAULT_SCENARIO, DEFAULT_SOURCE).expect("the embedded scenario is valid")
    }

    /// Read and validate a scenario file.
    pub fn load(path: &Path) -> Result<Scenario, ScenarioError> {
        let file = path.display().to_string();
        let plain = |message: String| ScenarioError {
            file: file.clone(),
            location: None,
            key: None,
            message,
            source_line: None,
        };
        let meta = std::fs::metadata(path).map_err(|e| plain(format!("cannot read: {e}")))?;
        if meta.len() > 1 << 20 {
            return Err(plain(format!(
                "is {} bytes; a scenario is at most 1 MiB",
                meta.len()
            )));
        }
        let bytes = std::fs::read(path).map_err(|e| plain(format!("cannot read: {e}")))?;
        let text = String::from_utf8(bytes).map_err(|e| {
            let offset = e.utf8_error().valid_up_to();
            let text = String::from_utf8_lossy(e.as_bytes()).into_owned();
            Locator {
                file: &file,
                text: &text,
            }
            .error(Some(offset..offset), None, "is not valid UTF-8".into())
        })?;
        Scenario::parse(&text, &file)
    }

    /// Parse and validate scenario text; `file` names it in errors.
    pub fn parse(text: &str, file: &str) -> Result<Scenario, ScenarioError> {
        let loc = Locator { file, text };
        let raw: RawScenario =
            toml::from_str(text).map_err(|e| loc.error(e.span(), None, e.message().trim().to_string()))?;

        loc.check("body.width", &raw.body.width, |v| check::positive(*v))?;
        loc.check("body.height", &raw.body.height, |v| check::positive(*v))?;
        loc.check("material.young", &raw.material.young, |v| check::positive(*v))?;
        loc.check("material.poisson", &raw.material.poisson, |v| check::poisson(*v))?;
        loc.check("obstacle.radius", &raw.obstacle.radius, |v| check::positive(*v))?;
        loc.check("obstacle.depth", &raw.obstacle.depth, |v| check::finite(*v))?;
        let half_model = raw.body.model == Model::Half;
        let center = match &raw.obstacle.center {
            Some(c) => {
                loc.check("obstacle.center", c, |v| check::finite(*v))?;
                if half_model && *c.get_ref() != 0.0 {
                    return Err(loc.error(
                        Some(c.span()),
                        Some("obstacle.center".into()),
                        format!(
                            "{} is not allowed for a half model; allowed: 0 (the symmetry line)",
                            c.get_ref()
                        ),
                    ));
                }
                *c.get_ref()
            }
            None => 0.0,
        };
        loc.check("mesh.nx", &raw.mesh.nx, |v| check::integer(*v, 1, MAX_CELLS_0))?;
        loc.check("mesh.ny", &raw.mesh.ny, |v| check::integer(*v, 1, MAX_CELLS_0))?;
        let level = match &raw.mesh.level {
            Some(l) => {
                loc.check("mesh.level", l, |v| check::level(*v))?;
                *l.get_ref() as u32
            }
            None => 0,
        };
        loc.check("contact.epsilon", &raw.contact.epsilon, |v| check::epsilon(*v))?;

        let Shape::Cylinder = raw.obstacle.shape;
        let name = raw.name.unwrap_or_else(|| {
            Path::new(file)
                .file_stem()
                .map_or_else(|| "scenario".into(), |s| s.to_string_lossy().into_owned())
        });
        Ok(Scenario {
            name,
            description: raw.description,
            source: file.to_string(),
            width: *raw.body.width.get_ref(),
            height: *raw.body.height.get_ref(),
            half_model,
            material: Material {
                young: *raw.material.young.get_ref(),
                poisson: *raw.material.poisson.get_ref(),
                plane: raw.material.plane,
            },
            obstacle: Obstacle::Cylinder {
                radius: *raw.obstacle.radius.get_ref(),
                depth: *raw.obstacle.depth.get_ref(),
                center,
            },
            element: raw.mesh.element,
            nx0: *raw.mesh.nx.get_ref() as usize,
            ny0: *raw.mesh.ny.get_ref() as usize,
            level,
            rule: raw.contact.rule,
            epsilon: *raw.contact.epsilon.get_ref(),
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

    /// The mesh of `level` with `element`: nx0·2^level × ny0·2^level cells.
    pub fn mesh(&self, level: u32, element: Element) -> Mesh {
        let (x0, x1) = self.x_range();
        let f = 1usize << level;
        Mesh::uniform(
            element,
            (x0, x1, self.nx0 * f),
            (0.0, self.height, self.ny0 * f),
            self.half_model,
        )
    }

    /// The cell width at `level`.
    pub fn h(&self, level: u32) -> f64 {
        let (x0, x1) = self.x_range();
        ((x1 - x0) / self.nx0 as f64).max(self.height / self.ny0 as f64) / f64::from(1u32 << level)
    }
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
            (s.nx0, s.ny0, s.element, s.rule, s.epsilon),
            (8, 4, Element::Q1, Rule::Gauss1, 1e-6)
        );
        assert_eq!(s.mesh(1, Element::Q1).n_elements(), 128);
        assert_eq!(s.h(1), 0.5);
    }
}
