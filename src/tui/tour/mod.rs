//! The guided tour: the lab walked through a list of steps, each a screen of the lab at given
//! settings with a short caption below (`riplab tour`). The steps are data: a TOML tour file
//! (the default, `tours/paper.toml`, is embedded), validated like a scenario, every error
//! naming the file, the line, the key and what is allowed.
//!
//! [`TourApp`] holds the state and its pure update (keys, worker replies, the auto-advance
//! tick); [`view`] draws it; [`run_tour`] runs it in the terminal.

pub mod author;
pub mod bodies_step;
mod bodies_worker;
mod caption;
mod embedded;
pub mod errors;
pub mod friction_step;
pub mod handout;
pub mod listing;
mod player;
mod runtime;
mod scenarios;
mod step_checks;
mod view;

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use serde::Deserialize;
use toml::Spanned;

use crate::check;
use crate::contact::{Method, Rule};
use crate::error::SolveError;
use crate::fem::Integration;
use crate::grading::{Grading, MAX_PASSES};
use crate::input::Locator as Source;
use crate::input::{RawGamma0, RawRefineEdges, ScenarioError, read_toml};
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::stress::Quantity;
use crate::text::{sanitize, sanitize_lines};

use super::app::{App, Compare, Guides, MAX_APP_LEVEL, Scene};
use caption::{caption, one_line};
use scenarios::{StepScenarios, Unloaded};

pub use caption::MIN_TOUR_SIZE;
pub use errors::{AutoIntervalError, TourError};
pub use player::{TourApp, TourMsg};
pub use runtime::run_tour;
pub use view::view;
#[cfg(test)]
pub use view::{render_step, render_step_at};

/// The paper's tour, `tours/paper.toml`.
pub const PAPER_TOUR: &str = include_str!("../../../tours/paper.toml");
/// The name under which the embedded tour is reported.
pub const PAPER_SOURCE: &str = "<embedded tours/paper.toml>";
/// The most lines a caption may have…
pub const MAX_CAPTION_LINES: usize = 4;
/// …and the most characters in each (so that a 100-column terminal shows it unwrapped).
pub const MAX_CAPTION_WIDTH: usize = 96;
/// The most characters in a step's title.
pub const MAX_TITLE_WIDTH: usize = 60;
/// The overlays a step may switch on.
pub const OVERLAYS: [&str; 6] = ["gap", "hertz", "circle", "mindlin", "all-levels", "zoom"];

/// A validated tour.
#[derive(Clone, Debug, PartialEq)]
pub struct Tour {
    /// The tour's title (one line of at most 200 characters).
    pub title: String,
    /// Where it was read from (a path, or [`PAPER_SOURCE`]).
    pub source: String,
    /// The steps, in order.
    pub steps: Vec<Step>,
    /// The scenario of the steps that do not name their own.
    pub scenario: Scenario,
    /// How many scenario files its steps' `scenario` keys made it read: each distinct path
    /// once, however many steps name it.
    pub scenario_reads: usize,
}

/// One screen of a tour.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// The step's title (one line of at most [`MAX_TITLE_WIDTH`] characters).
    pub title: String,
    /// A few lines, shown as written.
    pub caption: String,
    /// The step's own scenario (loaded from its path, shared with the steps that name the
    /// same path), if it names one.
    pub scenario: Option<Arc<Scenario>>,
    /// The displacement element; None keeps the scenario's.
    pub element: Option<Element>,
    /// The contact rule; None keeps the scenario's.
    pub rule: Option<Rule>,
    /// The mesh level (clamped to [`MAX_APP_LEVEL`]); None keeps the scenario's.
    pub level: Option<u32>,
    /// How the solve grades the level's mesh (`refine_edges`, `E` in the lab; docs/design.md
    /// §6); None keeps the scenario's.
    pub grading: Option<Grading>,
    /// The stiffness's volumetric integration (`i` in the lab); None keeps the scenario's.
    pub integration: Option<Integration>,
    /// The penalty parameter ε (0: the `exact` method); None keeps the scenario's.
    pub epsilon: Option<f64>,
    /// The contact method ([`Method::parse`], default parameters); ε = 0 alone is `exact`.
    pub method: Option<Method>,
    /// The obstacle's depth d (clamped to the lab's range); None keeps the scenario's.
    pub depth: Option<f64>,
    /// The scene shown; None: [`Scene::Explore`].
    pub scene: Option<Scene>,
    /// What the convergence scene compares (`w` in the lab; default: the schemes).
    pub compare: Compare,
    /// The pressure chart's overlays (`gap`, `hertz`, `circle`, `mindlin`).
    pub guides: Guides,
    /// Estimate inf-sup at every level up to the step's (overlay `all-levels`).
    pub all_levels: bool,
    /// Zoom to the contact zone (overlay `zoom`, `z` in the lab).
    pub zoom: bool,
    /// What the stress scene shows (`c` in the lab); None: τ₁.
    pub quantity: Option<Quantity>,
    /// The friction law and shift over the scenario's (`F`, `u`/`U`, `<`/`>` in the lab).
    pub friction: Option<friction_step::StepFriction>,
    /// On a step whose scenario has two bodies, its two-body scene's settings
    /// ([`bodies_step`]); None on a one-body step.
    pub bodies: Option<bodies_step::BodiesStep>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTour {
    title: Spanned<String>,
    step: Spanned<Vec<RawStep>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStep {
    title: Spanned<String>,
    caption: Spanned<String>,
    scenario: Option<Spanned<String>>,
    scheme: Option<Spanned<String>>,
    element: Option<Spanned<Element>>,
    rule: Option<Spanned<Rule>>,
    level: Option<Spanned<i64>>,
    refine_edges: Option<Spanned<RawRefineEdges>>,
    integration: Option<Spanned<Integration>>,
    epsilon: Option<Spanned<f64>>,
    method: Option<Spanned<String>>,
    theta: Option<Spanned<f64>>,
    gamma0: Option<Spanned<RawGamma0>>,
    alm_tol: Option<Spanned<f64>>,
    depth: Option<Spanned<f64>>,
    scene: Option<Spanned<String>>,
    compare: Option<Spanned<String>>,
    overlays: Option<Spanned<Vec<Spanned<String>>>>,
    quantity: Option<Spanned<String>>,
    friction: Option<Spanned<String>>,
    mu: Option<Spanned<f64>>,
    threshold: Option<Spanned<f64>>,
    shift: Option<Spanned<f64>>,
    contact: Option<Spanned<String>>,
    ratio: Option<Spanned<Vec<i64>>>,
    offset: Option<Spanned<f64>>,
}

impl Tour {
    /// The embedded tour of the paper's argument, on the paper's problem.
    pub fn paper() -> Tour {
        Tour::parse(PAPER_TOUR, PAPER_SOURCE, None).expect("the embedded tour is valid")
    }

    /// Read and validate a tour file; scenario paths in it are relative to its directory.
    ///
    /// # Errors
    ///
    /// The file cannot be read or is too large, or as [`Tour::parse`]'s.
    pub fn load(path: &Path) -> Result<Tour, ScenarioError> {
        Tour::read(path).map(|(tour, _)| tour)
    }

    /// [`Tour::load`], with the file's size in bytes (what `T` adds to it is bounded by
    /// [`crate::input::read::MAX_FILE_BYTES`] with it).
    ///
    /// # Errors
    ///
    /// As [`Tour::load`]'s.
    pub fn read(path: &Path) -> Result<(Tour, usize), ScenarioError> {
        let (file, text) = read_toml(path, "a tour")?;
        Tour::parse(&text, &file, Some(&directory_of(path))).map(|tour| (tour, text.len()))
    }

    /// Parse and validate tour text; `file` names it in errors, `dir` is where its scenario
    /// paths are relative to (None: the tour may not name scenario files).
    ///
    /// # Errors
    ///
    /// TOML that does not parse, an unknown key, a value of the wrong type or out of its range, a
    /// scenario that cannot be read: [`ScenarioError`] names the file, the line, the column and the
    /// key (and the step).
    pub fn parse(text: &str, file: &str, dir: Option<&Path>) -> Result<Tour, ScenarioError> {
        let src = Source { file, text };
        src.check_nesting()?;
        // Integers beyond 64 bits said in the user's words, with the step they stand in.
        src.check_numbers(|key| {
            let passes = key
                .ends_with(".refine_edges")
                .then_some((0, i64::from(MAX_PASSES)));
            passes.or(key.ends_with(".level").then_some((0, i64::from(MAX_APP_LEVEL))))
        })?;
        let raw: RawTour =
            toml::from_str(text).map_err(|e| src.error(e.span(), None, e.message().trim().to_string()))?;
        src.check("title", &raw.title, |t| one_line(t, 200))?;
        if raw.step.get_ref().is_empty() {
            return Err(src.error(
                Some(raw.step.span()),
                Some("step".into()),
                "is empty; allowed: at least one [[step]]".into(),
            ));
        }
        let mut scenarios = StepScenarios::new(dir);
        let steps = raw
            .step
            .get_ref()
            .iter()
            .enumerate()
            .map(|(i, s)| step(&src, i + 1, s, &mut scenarios))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Tour {
            title: sanitize(raw.title.get_ref()).into_owned(),
            source: file.to_string(),
            steps,
            scenario: Scenario::paper(),
            scenario_reads: scenarios.reads(),
        })
    }

    /// The tour with `scenario` for the steps that do not name their own; every step's depth
    /// is checked against its scenario, its ε against the range of its level, its friction
    /// against its scenario's model, method and grading (as the lab refuses them when the step
    /// is played: [`friction_step::check`]), and its overlays against its obstacle and
    /// friction (as the lab's keys are: [`App::guide_refusal`]).
    ///
    /// # Errors
    ///
    /// The first step whose depth, ε, friction or overlays its scenario cannot take, with the
    /// step's index ([`TourError`]); a two-body `scenario` while a step names none.
    pub fn with_scenario(mut self, scenario: Scenario) -> Result<Tour, TourError> {
        if scenario.upper.is_some()
            && let Some(i) = self.steps.iter().position(|s| s.scenario.is_none())
        {
            return Err(TourError::TwoBodies {
                file: sanitize(&self.source).into_owned(),
                step: i + 1,
                title: self.steps[i].title.clone(),
                scenario: sanitize(&scenario.source).into_owned(),
            });
        }
        self.scenario = scenario;
        for i in 0..self.steps.len() {
            step_checks::check(&self, i)?;
        }
        Ok(self)
    }

    /// Refuse the first graded step whose memory, estimated from its lines, exceeds what this
    /// process may use, as the lab's engine refuses its solve (docs/design.md §6): its number
    /// (1-based) and the refusal, naming the level, the element, the grading and the memory.
    pub fn graded_fits(&self) -> Result<(), (usize, SolveError)> {
        for i in 0..self.steps.len() {
            super::engine::Engine::new(self.scenario_of(i).clone())
                .graded_fits(&self.app(i).settings)
                .map_err(|e| (i + 1, e))?;
        }
        Ok(())
    }

    /// The scenario of step `index` (its own, else the tour's).
    pub fn scenario_of(&self, index: usize) -> &Scenario {
        self.steps
            .get(index)
            .and_then(|s| s.scenario.as_deref())
            .unwrap_or(&self.scenario)
    }

    /// The lab at the settings of step `index` (a setting the step leaves out is the
    /// scenario's; a depth beyond the scenario's limit is clamped to it). A two-body step's is
    /// the lab on the tour's scenario, left unsolved while [`Tour::bodies`] shows the step.
    pub fn app(&self, index: usize) -> App {
        let Some(step) = self.steps.get(index).filter(|s| s.bodies.is_none()) else {
            let mut app = App::new(self.scenario.clone());
            app.overlays.in_tour = true;
            return app;
        };
        let mut app = App::new(self.scenario_of(index).clone());
        let s = &mut app.settings;
        s.element = step.element.unwrap_or(s.element);
        s.rule = step.rule.unwrap_or(s.rule);
        s.level = step.level.unwrap_or(s.level).min(MAX_APP_LEVEL);
        s.refine_edges = step.grading.unwrap_or(s.refine_edges);
        s.integration = step.integration.unwrap_or(s.integration);
        // ε = 0 is the exact method (the lab keeps its ε for penalty and alm).
        match step.epsilon {
            Some(0.0) => s.method = Method::Exact,
            Some(e) => s.epsilon = e,
            None => {}
        }
        s.method = step.method.unwrap_or(s.method);
        let max = app.max_depth();
        let s = &mut app.settings;
        s.depth = step.depth.unwrap_or(s.depth).clamp(0.0, max.max(0.0));
        app.scene = step.scene.unwrap_or(Scene::Explore);
        app.overlays.in_tour = true;
        app.compare = step.compare;
        app.guides = step.guides;
        app.all_levels = step.all_levels;
        app.zoom = step.zoom;
        // A step that zooms chose to: the lab's "opened zoomed in" notice would take the
        // status line, whose numbers the caption quotes.
        if step.zoom {
            app.notice = None;
        }
        app.stress_quantity = step.quantity.unwrap_or(app.stress_quantity);
        if let Some(f) = &step.friction {
            app.settings.friction = f.over(app.settings.friction);
        }
        app
    }
}

/// The directory a tour file's scenario paths are relative to.
fn directory_of(path: &Path) -> PathBuf {
    path.parent()
        .map_or_else(|| Path::new(".").to_path_buf(), Path::to_path_buf)
}

/// Step number `n` (1-based) validated.
fn step(src: &Source, n: usize, raw: &RawStep, scenarios: &mut StepScenarios) -> Result<Step, ScenarioError> {
    let key = |k: &str| format!("step[{n}].{k}");
    src.check(&key("title"), &raw.title, |t| one_line(t, MAX_TITLE_WIDTH))?;
    src.check(&key("caption"), &raw.caption, |t| caption(t))?;
    let scenario = match &raw.scenario {
        None => None,
        Some(path) => Some(scenarios.get(path.get_ref()).map_err(|e| {
            let message = match e {
                Unloaded::Invalid(e) => format!("cannot load the scenario: {e}"),
                Unloaded::NoDirectory => "a scenario path needs a tour file to be relative to; allowed only in a tour read from a file".into(),
            };
            src.error(Some(path.span()), Some(key("scenario")), message)
        })?),
    };
    let two_bodies = scenario.as_ref().is_some_and(|s| s.upper.is_some());
    let bodies = bodies_step::parse(src, n, raw, two_bodies)?;
    let (mut element, mut rule) = (
        raw.element.as_ref().map(|e| *e.get_ref()),
        raw.rule.as_ref().map(|r| *r.get_ref()),
    );
    if let Some(scheme) = &raw.scheme {
        if let Some(other) = raw
            .element
            .as_ref()
            .map(|e| e.span())
            .or(raw.rule.as_ref().map(|r| r.span()))
        {
            return Err(src.error(
                Some(other),
                Some(key("scheme")),
                "give either scheme or element and rule, not both".into(),
            ));
        }
        let s = Scheme::parse(scheme.get_ref())
            .map_err(|m| src.error(Some(scheme.span()), Some(key("scheme")), m.to_string()))?;
        (element, rule) = (Some(s.element), Some(s.rule));
    }
    let level = match &raw.level {
        Some(l) => {
            src.check(&key("level"), l, |v| {
                check::integer(*v, 0, i64::from(MAX_APP_LEVEL))
            })?;
            Some(*l.get_ref() as u32)
        }
        None => None,
    };
    let grading = match &raw.refine_edges {
        Some(r) => {
            src.check(&key("refine_edges"), r, |v| v.parse().map(|_| ()))?;
            r.get_ref().parse().ok()
        }
        None => None,
    };
    if let Some(e) = &raw.epsilon {
        src.check(&key("epsilon"), e, |v| check::epsilon(*v))?;
    }
    if let Some(d) = &raw.depth {
        src.check(&key("depth"), d, |v| check::nonnegative(*v))?;
    }
    let method = method(src, n, raw)?;
    let scene = match &raw.scene {
        Some(name) => Some(Scene::from_name(name.get_ref()).ok_or_else(|| {
            let names: Vec<&str> = Scene::ALL.iter().map(|s| s.name()).collect();
            src.error(
                Some(name.span()),
                Some(key("scene")),
                format!(
                    "`{}` is not a scene; allowed: {}",
                    sanitize(name.get_ref()),
                    names.join(", ")
                ),
            )
        })?),
        None => None,
    };
    let compare = match &raw.compare {
        Some(name) => match name.get_ref().as_str() {
            "schemes" => Compare::Schemes,
            "methods" => Compare::Methods,
            other => {
                return Err(src.error(
                    Some(name.span()),
                    Some(key("compare")),
                    format!(
                        "`{}` is not a comparison; allowed: schemes, methods",
                        sanitize(other)
                    ),
                ));
            }
        },
        None => Compare::Schemes,
    };
    let quantity = match &raw.quantity {
        Some(name) => Some(
            Quantity::ALL
                .into_iter()
                .find(|q| q.name() == name.get_ref())
                .ok_or_else(|| {
                    let names: Vec<&str> = Quantity::ALL.iter().map(|q| q.name()).collect();
                    src.error(
                        Some(name.span()),
                        Some(key("quantity")),
                        format!(
                            "`{}` is not a stress quantity; allowed: {}",
                            name.get_ref(),
                            names.join(", ")
                        ),
                    )
                })?,
        ),
        None => None,
    };
    let mut on = [false; OVERLAYS.len()];
    for overlay in raw.overlays.iter().flat_map(|o| o.get_ref()) {
        let i = OVERLAYS
            .iter()
            .position(|o| o == overlay.get_ref())
            .ok_or_else(|| {
                src.error(
                    Some(overlay.span()),
                    Some(key("overlays")),
                    format!(
                        "`{}` is not an overlay; allowed: {}",
                        sanitize(overlay.get_ref()),
                        OVERLAYS.join(", ")
                    ),
                )
            })?;
        on[i] = true;
    }
    Ok(Step {
        title: sanitize(raw.title.get_ref()).into_owned(),
        // Text from a file: no control character reaches the terminal (the line breaks stay).
        caption: sanitize_lines(raw.caption.get_ref().trim_matches('\n')),
        scenario,
        element,
        rule,
        level,
        grading,
        integration: raw.integration.as_ref().map(|i| *i.get_ref()),
        epsilon: raw.epsilon.as_ref().map(|e| *e.get_ref()),
        method,
        depth: raw.depth.as_ref().map(|d| *d.get_ref()),
        scene,
        compare,
        guides: Guides {
            gap: on[0],
            hertz: on[1],
            circle: on[2],
            mindlin: on[3],
        },
        all_levels: on[4],
        zoom: on[5],
        quantity,
        friction: friction_step::parse(
            src,
            n,
            &friction_step::Raw {
                law: raw.friction.as_ref(),
                mu: raw.mu.as_ref(),
                threshold: raw.threshold.as_ref(),
                shift: raw.shift.as_ref(),
            },
        )?,
        bodies,
    })
}

/// The method of step `n` with its parameters (`theta`, `gamma0`, `alm_tol`, which need
/// `method`), checked as a scenario's are.
fn method(src: &Source, n: usize, raw: &RawStep) -> Result<Option<Method>, ScenarioError> {
    let key = |k: &str| format!("step[{n}].{k}");
    let gamma0 = match &raw.gamma0 {
        Some(g) => Some(
            g.get_ref()
                .parse()
                .map_err(|e| src.error(Some(g.span()), Some(key("gamma0")), e.to_string()))?,
        ),
        None => None,
    };
    let (theta, alm_tol) = (raw.theta.as_ref(), raw.alm_tol.as_ref());
    let Some(name) = &raw.method else {
        let given = [
            ("theta", theta.map(|t| t.span())),
            ("gamma0", raw.gamma0.as_ref().map(|g| g.span())),
            ("alm_tol", alm_tol.map(|t| t.span())),
        ];
        if let Some((k, span)) = given.into_iter().find(|(_, s)| s.is_some()) {
            return Err(src.error(
                span,
                Some(key(k)),
                "needs the step's method (nitsche takes theta and gamma0, alm takes alm_tol)".into(),
            ));
        }
        return Ok(None);
    };
    Method::parse(
        name.get_ref(),
        theta.map(|t| *t.get_ref()),
        gamma0,
        alm_tol.map(|t| *t.get_ref()),
    )
    .map(Some)
    .map_err(|e| {
        let span = match e.key() {
            "theta" => theta.map(|t| t.span()),
            "gamma0" => raw.gamma0.as_ref().map(|g| g.span()),
            "alm_tol" => alm_tol.map(|t| t.span()),
            _ => None,
        }
        .unwrap_or(name.span());
        src.error(Some(span), Some(key(e.key())), e.to_string())
    })
}

/// The interval of `--auto SECONDS`: a finite number of seconds in 0.5..=3600.
pub fn auto_interval(seconds: f64) -> Result<Duration, AutoIntervalError> {
    if seconds.is_finite() && (0.5..=3600.0).contains(&seconds) {
        Ok(Duration::from_secs_f64(seconds))
    } else {
        Err(AutoIntervalError { seconds })
    }
}
