//! A tour step on a scenario of two elastic bodies (docs/design.md §12, docs/lab.md "Two
//! bodies"): the lab's two-body scene ([`BodiesApp`]) at the step's settings — `contact`, the
//! discretisation across the interface by its name in the outputs (`nts` … `rip-simpson`);
//! `ratio` and `offset`, the upper mesh across the interface, checked as the scenario's
//! `[upper]` is; `level`; and `epsilon` (0: the exact multipliers, > 0: the penalty). A key of
//! the one-body lab on such a step, and a two-body key on a one-body step, is refused with its
//! place and the reason, when the tour is read.

use std::ops::Range;

use toml::Spanned;

use crate::contact::interface::InterfaceMethod;
use crate::contact::interface::solve::Enforcement;
use crate::input::Locator as Source;
use crate::input::ScenarioError;
use crate::scenario::Scenario;
use crate::text::sanitize;

use super::super::app::MAX_APP_LEVEL;
use super::super::bodies::BodiesApp;
use super::{RawStep, Tour};

/// The keys a two-body step takes.
pub const TWO_BODY_KEYS: &str = "title, caption, scenario, contact, ratio, offset, level, epsilon";

/// What a two-body step sets of its scene; what it leaves out is its scenario's (the
/// discretisation: mortar).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BodiesStep {
    /// The discretisation across the interface.
    pub contact: Option<InterfaceMethod>,
    /// Upper elements : lower elements across the interface.
    pub ratio: Option<(u32, u32)>,
    /// The upper mesh's interior vertex lines shifted by this fraction of its element.
    pub offset: Option<f64>,
}

impl BodiesStep {
    /// The two-body scene of `scenario` at this step's settings and its `level` and `epsilon`
    /// (None for a one-body scenario); `0` in the scene goes back to them.
    pub fn app(&self, scenario: &Scenario, level: Option<u32>, epsilon: Option<f64>) -> Option<BodiesApp> {
        let mut app = BodiesApp::new(scenario.clone(), self.contact.unwrap_or(InterfaceMethod::Mortar))?;
        let s = &mut app.settings;
        s.level = level.unwrap_or(s.level).min(MAX_APP_LEVEL);
        s.ratio = self.ratio.unwrap_or(s.ratio);
        s.offset = self.offset.unwrap_or(s.offset);
        if let Some(epsilon) = epsilon {
            s.enforcement = match s.enforcement {
                Enforcement::Alm { tolerance, .. } if epsilon > 0.0 => {
                    Enforcement::Alm { epsilon, tolerance }
                }
                _ => Enforcement::from(epsilon),
            };
        }
        app.initial = app.settings;
        Some(app)
    }
}

impl Tour {
    /// The two-body scene of step `index`, when its scenario has two bodies (the step's
    /// lab, [`Tour::app`], then waits on the tour's scenario, unsolved).
    pub fn bodies(&self, index: usize) -> Option<BodiesApp> {
        let step = self.steps.get(index)?;
        step.bodies
            .as_ref()?
            .app(self.scenario_of(index), step.level, step.epsilon)
    }

    /// Whether step `index` shows the two-body scene.
    pub fn is_two_body(&self, index: usize) -> bool {
        self.steps.get(index).is_some_and(|s| s.bodies.is_some())
    }
}

/// Why a key of the one-body lab does not apply to a two-body step.
fn why_not(key: &str) -> &'static str {
    match key {
        "scheme" | "element" | "rule" => {
            "the bodies' element is their scenario's ([mesh] element), and a rip rule is chosen by contact (rip-gauss1, rip-gauss2, rip-trapezoid, rip-simpson)"
        }
        "refine_edges" => "the two bodies' meshes are not graded",
        "integration" => "the two bodies are integrated as their scenario says ([mesh] integration)",
        "method" | "theta" | "gamma0" | "alm_tol" => {
            "the constraint across the interface is enforced by epsilon (0: the exact multipliers, > 0: the penalty), discretised by contact"
        }
        "depth" => "the upper body's top is pressed as its scenario's [upper] says",
        "friction" | "mu" | "threshold" | "shift" => "the two-body solve takes no friction",
        _ => "the step shows the two-body scene",
    }
}

/// The one-body lab's keys step `raw` gives, with their places.
fn one_body_keys(raw: &RawStep) -> Vec<(&'static str, Range<usize>)> {
    let given: [(&str, Option<Range<usize>>); 18] = [
        ("scheme", raw.scheme.as_ref().map(Spanned::span)),
        ("element", raw.element.as_ref().map(Spanned::span)),
        ("rule", raw.rule.as_ref().map(Spanned::span)),
        ("refine_edges", raw.refine_edges.as_ref().map(Spanned::span)),
        ("integration", raw.integration.as_ref().map(Spanned::span)),
        ("method", raw.method.as_ref().map(Spanned::span)),
        ("theta", raw.theta.as_ref().map(Spanned::span)),
        ("gamma0", raw.gamma0.as_ref().map(Spanned::span)),
        ("alm_tol", raw.alm_tol.as_ref().map(Spanned::span)),
        ("depth", raw.depth.as_ref().map(Spanned::span)),
        ("scene", raw.scene.as_ref().map(Spanned::span)),
        ("compare", raw.compare.as_ref().map(Spanned::span)),
        ("overlays", raw.overlays.as_ref().map(Spanned::span)),
        ("quantity", raw.quantity.as_ref().map(Spanned::span)),
        ("friction", raw.friction.as_ref().map(Spanned::span)),
        ("mu", raw.mu.as_ref().map(Spanned::span)),
        ("threshold", raw.threshold.as_ref().map(Spanned::span)),
        ("shift", raw.shift.as_ref().map(Spanned::span)),
    ];
    given.into_iter().filter_map(|(k, s)| s.map(|s| (k, s))).collect()
}

/// Step `n`'s two-body keys validated: Some on a step whose scenario has two bodies
/// (`two_bodies`), None on a one-body step. The first key (in the file's order) that does not
/// apply to the step's scenario is refused.
pub(super) fn parse(
    src: &Source,
    n: usize,
    raw: &RawStep,
    two_bodies: bool,
) -> Result<Option<BodiesStep>, ScenarioError> {
    let key = |k: &str| Some(format!("step[{n}].{k}"));
    if !two_bodies {
        let given = [
            ("contact", raw.contact.as_ref().map(Spanned::span)),
            ("ratio", raw.ratio.as_ref().map(Spanned::span)),
            ("offset", raw.offset.as_ref().map(Spanned::span)),
        ];
        if let Some((k, span)) = given
            .into_iter()
            .filter_map(|(k, s)| s.map(|s| (k, s)))
            .min_by_key(|(_, s)| s.start)
        {
            return Err(src.error(
                Some(span),
                key(k),
                "applies to a step whose scenario has two elastic bodies ([upper], e.g. scenarios/patch-two-blocks.toml); this step's has one body under a rigid obstacle".into(),
            ));
        }
        return Ok(None);
    }
    if let Some((k, span)) = one_body_keys(raw).into_iter().min_by_key(|(_, s)| s.start) {
        return Err(src.error(
            Some(span),
            key(k),
            format!(
                "does not apply to a two-body step (its scenario has an elastic [upper] body): {}; allowed on a two-body step: {TWO_BODY_KEYS}",
                why_not(k)
            ),
        ));
    }
    let contact = match &raw.contact {
        Some(name) => Some(
            InterfaceMethod::ALL
                .into_iter()
                .find(|m| m.name() == name.get_ref())
                .ok_or_else(|| {
                    let names: Vec<&str> = InterfaceMethod::ALL.iter().map(|m| m.name()).collect();
                    src.error(
                        Some(name.span()),
                        key("contact"),
                        format!(
                            "`{}` is not a discretisation across the interface; allowed: {}",
                            sanitize(name.get_ref()),
                            names.join(", ")
                        ),
                    )
                })?,
        ),
        None => None,
    };
    let ratio = match &raw.ratio {
        Some(r) => Some(src.ratio(&format!("step[{n}].ratio"), r)?),
        None => None,
    };
    let offset = match &raw.offset {
        Some(o) => Some(src.offset(&format!("step[{n}].offset"), o)?),
        None => None,
    };
    Ok(Some(BodiesStep {
        contact,
        ratio,
        offset,
    }))
}
