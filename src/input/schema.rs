//! The TOML schema of a scenario file: the tables and keys serde reads (unknown keys are
//! refused), every value still raw and spanned for the error locator.

use serde::Deserialize;
use toml::Spanned;

use crate::contact::Rule;
use crate::contact::method::Gamma0;
use crate::error::MethodError;
use crate::fem::Integration;
use crate::grading::{Grading, RefineEdges, RefineEdgesError};
use crate::material::Plane;
use crate::mesh::Element;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScenario {
    pub(super) name: Option<String>,
    #[serde(default)]
    pub(super) description: String,
    pub(super) body: RawBody,
    pub(super) material: RawMaterial,
    /// `[obstacle]`: required without `[upper]`, refused with it ([`super::upper`]).
    #[serde(default)]
    pub(super) obstacle: Option<RawObstacle>,
    /// `[upper]`, optional: an elastic body in place of the obstacle ([`super::upper`]).
    #[serde(default)]
    pub(super) upper: Option<Spanned<RawUpper>>,
    pub(super) mesh: RawMesh,
    pub(super) contact: RawContact,
    /// `[friction]`, optional ([`super::friction`]).
    #[serde(default)]
    pub(super) friction: Option<Spanned<RawFriction>>,
}

/// `[friction]` as written: the law and its parameters, the shift and its steps, the press.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFriction {
    pub(super) law: Spanned<String>,
    pub(super) mu: Option<Spanned<f64>>,
    pub(super) threshold: Option<Spanned<f64>>,
    pub(super) shift: Option<Spanned<f64>>,
    pub(super) steps: Option<Spanned<i64>>,
    pub(super) epsilon_t: Option<Spanned<f64>>,
    pub(super) press: Option<Spanned<String>>,
}

#[derive(Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub(super) enum Model {
    Half,
    Full,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBody {
    pub(super) width: Spanned<f64>,
    pub(super) height: Spanned<f64>,
    pub(super) model: Model,
    /// `clamped` (the default) or `roller` ([`crate::fem::Support`]).
    #[serde(default)]
    pub(super) support: Option<Spanned<String>>,
}

/// `[upper]` as written: the upper body's material, height, width and shape, its mesh across the
/// interface (ratio and offset), its support, its top's displacement or pressure and the slave
/// side.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawUpper {
    pub(super) young: Spanned<f64>,
    pub(super) poisson: Spanned<f64>,
    pub(super) height: Spanned<f64>,
    pub(super) width: Option<Spanned<f64>>,
    pub(super) displacement: Option<Spanned<f64>>,
    pub(super) pressure: Option<Spanned<f64>>,
    pub(super) shape: Option<Spanned<String>>,
    pub(super) radius: Option<Spanned<f64>>,
    pub(super) ratio: Option<Spanned<Vec<i64>>>,
    pub(super) offset: Option<Spanned<f64>>,
    pub(super) support: Option<Spanned<String>>,
    pub(super) slave: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMaterial {
    pub(super) young: Spanned<f64>,
    pub(super) poisson: Spanned<f64>,
    pub(super) plane: Plane,
}

#[derive(Deserialize, Clone, Copy, PartialEq, Eq, Debug)]
#[serde(rename_all = "lowercase")]
pub(super) enum Shape {
    Cylinder,
    Punch,
    Bumps,
    Polyline,
}

impl Shape {
    /// The keys of `[obstacle]` that each shape takes (besides `shape` and `depth`).
    pub(super) fn keys(self) -> &'static [&'static str] {
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
pub(super) struct RawObstacle {
    pub(super) shape: Spanned<Shape>,
    pub(super) depth: Spanned<f64>,
    pub(super) radius: Option<Spanned<f64>>,
    pub(super) center: Option<Spanned<f64>>,
    pub(super) half_width: Option<Spanned<f64>>,
    pub(super) corner_radius: Option<Spanned<f64>>,
    pub(super) bumps: Option<Spanned<Vec<RawBump>>>,
    pub(super) points: Option<Spanned<Vec<Spanned<Vec<f64>>>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBump {
    pub(super) center: Spanned<f64>,
    pub(super) radius: Spanned<f64>,
    #[serde(default)]
    pub(super) lift: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMesh {
    pub(super) element: Element,
    pub(super) nx: Option<Spanned<i64>>,
    pub(super) ny: Option<Spanned<i64>>,
    pub(super) x_lines: Option<Spanned<Vec<f64>>>,
    pub(super) y_lines: Option<Spanned<Vec<f64>>>,
    #[serde(default)]
    pub(super) level: Option<Spanned<i64>>,
    #[serde(default)]
    pub(super) integration: Option<Integration>,
    /// Edge-grading passes: a count, `"auto"` or `"Nz"` ([`RawRefineEdges`]).
    #[serde(default)]
    pub(super) refine_edges: Option<Spanned<RawRefineEdges>>,
}

/// `[mesh] refine_edges` as written: a whole number of passes, or text (`"auto"`, `"3z"`);
/// both checked by [`Grading::parse`], any other TOML value refused naming what is allowed.
pub(crate) enum RawRefineEdges {
    Count(i64),
    Text(String),
}

impl RawRefineEdges {
    /// The grading written (0 to [`crate::grading::MAX_PASSES`], `auto`, or `Nz`).
    pub(crate) fn parse(&self) -> Result<Grading, RefineEdgesError> {
        match self {
            RawRefineEdges::Count(n) => RefineEdges::of_count(*n).map(Grading::Edges),
            RawRefineEdges::Text(t) => Grading::parse(t),
        }
    }
}

impl<'de> Deserialize<'de> for RawRefineEdges {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl serde::de::Visitor<'_> for Visitor {
            type Value = RawRefineEdges;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                write!(
                    f,
                    "a number of passes 0 to {} or `\"auto\"` or `\"1z\"` to `\"{0}z\"`",
                    crate::grading::MAX_PASSES
                )
            }
            fn visit_i64<E>(self, v: i64) -> Result<RawRefineEdges, E> {
                Ok(RawRefineEdges::Count(v))
            }
            fn visit_u64<E>(self, v: u64) -> Result<RawRefineEdges, E> {
                Ok(RawRefineEdges::Count(i64::try_from(v).unwrap_or(i64::MAX)))
            }
            fn visit_str<E>(self, v: &str) -> Result<RawRefineEdges, E> {
                Ok(RawRefineEdges::Text(v.to_string()))
            }
        }
        d.deserialize_any(Visitor)
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawContact {
    pub(super) rule: Rule,
    pub(super) epsilon: Spanned<f64>,
    /// `penalty`, `exact`, `alm` or `nitsche` ([`Method::parse`]).
    pub(super) method: Option<Spanned<String>>,
    pub(super) theta: Option<Spanned<f64>>,
    pub(super) gamma0: Option<Spanned<RawGamma0>>,
    pub(super) alm_tol: Option<Spanned<f64>>,
}

/// Nitsche's γ₀ as written: a number, or text (`"auto"`, checked by
/// [`crate::contact::method::Gamma0::parse`]). Any other TOML value is refused naming what is
/// allowed (serde's untagged enums would name this type instead). Tour steps read it too.
pub(crate) enum RawGamma0 {
    Number(f64),
    Text(String),
}

impl RawGamma0 {
    /// The γ₀ written (its range is [`crate::contact::Method::check`]'s).
    pub(crate) fn parse(&self) -> Result<Gamma0, MethodError> {
        match self {
            RawGamma0::Number(v) => Ok(Gamma0::Given(*v)),
            RawGamma0::Text(t) => Gamma0::parse(t),
        }
    }
}

impl<'de> Deserialize<'de> for RawGamma0 {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl serde::de::Visitor<'_> for Visitor {
            type Value = RawGamma0;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("`\"auto\"` or a number γ₀ from 1e-8 to 1e8")
            }
            fn visit_f64<E>(self, v: f64) -> Result<RawGamma0, E> {
                Ok(RawGamma0::Number(v))
            }
            fn visit_i64<E>(self, v: i64) -> Result<RawGamma0, E> {
                Ok(RawGamma0::Number(v as f64))
            }
            fn visit_u64<E>(self, v: u64) -> Result<RawGamma0, E> {
                Ok(RawGamma0::Number(v as f64))
            }
            fn visit_str<E>(self, v: &str) -> Result<RawGamma0, E> {
                Ok(RawGamma0::Text(v.to_string()))
            }
        }
        d.deserialize_any(Visitor)
    }
}
