//! The app's state and its pure update function: keys and worker replies come in, the state
//! changes, and the requests the visible scene still needs go out. No terminal, no threads.

use std::collections::{HashMap, HashSet};
use std::sync::Arc;

use crate::contact::Method;
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::stress::Quantity;

use super::beta::InfSup;
pub use super::keys::ExportKind;
use super::lab_error::LabError;

mod dispatch;
pub(in crate::tui) use dispatch::key_name;
mod friction;
pub mod guides;
mod integration;
pub mod log;
mod mouse;
mod overlays;
mod replies;

pub use super::protocol::{
    Command, Compare, DisplaceRequest, InfSupKey, InfSupRequest, MAX_APP_LEVEL, Msg, Notice, Progress,
    Response, SolveKey, SolveRequest, Solved, StressRequest, Study, StudyKey, StudyRequest,
};
pub use guides::Guides;
pub use overlays::{Drawn, Overlays};

/// Why the lab stops at [`MAX_APP_LEVEL`], for messages (the figures are BENCHMARKS.md's,
/// "Fresh memory", not the code's).
pub const LEVEL_LIMIT_WHY: &str =
    "a change at level 8 takes seconds and gigabytes (BENCHMARKS.md); `riplab solve --level 8` computes it";
/// The range of ε reachable with `+`/`-`.
pub const EPSILON_RANGE: (f64, f64) = (1e-14, 1e2);
/// The ε that `penalty` and `alm` use in a scenario whose own is 0 (`exact`): the paper's.
pub const DEFAULT_EPSILON: f64 = 1e-6;
/// The depth step of `d`/`D`.
pub const DEPTH_STEP: f64 = 0.1;

/// A screen of the app.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scene {
    /// Pressures, inf-sup panel and deformed configuration near the contact.
    Explore,
    /// β/√h against h for the paper's schemes.
    InfSup,
    /// The deformed configuration, full size.
    Mesh,
    /// Error against solve time (work–precision) for M1–M4 against a finer Q2 reference.
    Convergence,
    /// A heat map of a stress quantity under the contact.
    Stress,
}

impl Scene {
    /// Every scene, in the order Tab cycles through them.
    pub const ALL: [Scene; 5] = [
        Scene::Explore,
        Scene::InfSup,
        Scene::Mesh,
        Scene::Convergence,
        Scene::Stress,
    ];

    /// The scene's name, as `riplab render --scene` takes it.
    pub fn name(self) -> &'static str {
        match self {
            Scene::Explore => "explore",
            Scene::InfSup => "infsup",
            Scene::Mesh => "mesh",
            Scene::Convergence => "convergence",
            Scene::Stress => "stress",
        }
    }

    /// The scene called `name`, if any.
    pub fn from_name(name: &str) -> Option<Scene> {
        Scene::ALL.into_iter().find(|s| s.name() == name)
    }

    fn shifted(self, by: usize) -> Scene {
        let i = Scene::ALL.iter().position(|&s| s == self).unwrap_or(0);
        Scene::ALL[(i + by) % Scene::ALL.len()]
    }

    /// Whether the scene shows a contact solution.
    pub fn needs_solution(self) -> bool {
        matches!(self, Scene::Explore | Scene::Mesh | Scene::Stress)
    }
}

/// The level [`App::opening`] opens the paper's problem at: 128 elements (h = 0.5), the first
/// level where M1's raw p alternates from edge to edge (at level 0's 32 elements it does not
/// yet), solved in milliseconds.
pub const OPENING_LEVEL: u32 = 1;

/// The finest level the convergence scene studies (the reference is one level finer).
pub const MAX_STUDY_LEVEL: u32 = 4;
/// The levels the inf-sup scene computes on first show (0 to this, progressively).
pub const FIRST_LEVELS: u32 = 4;

/// What an update asks of the runtime.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Effect {
    /// The screen changed.
    pub redraw: bool,
    /// The work to start, in order.
    pub commands: Vec<Command>,
}

/// The state of the lab.
#[derive(Clone, Debug)]
pub struct App {
    /// The scenario the lab explores (its settings the starting values).
    pub scenario: Scenario,
    /// The settings the user chose (what the screen should show).
    pub settings: SolveKey,
    /// The scene on screen.
    pub scene: Scene,
    /// The pressure chart's overlays on: −g, Hertz, the circle, Mindlin (`g`, `h`, `o`, `M`).
    pub guides: Guides,
    /// The help overlay is open (`?`).
    pub show_help: bool,
    /// Zoom the pressure chart and the contact-zone view to the contact zone.
    pub zoom: bool,
    /// Show solve times (off for deterministic frames).
    pub show_timing: bool,
    /// Compute the inf-sup estimate at every level up to the current one, not just the current.
    pub all_levels: bool,
    /// What the stress scene shows (`c` cycles).
    pub stress_quantity: Quantity,
    /// What the convergence scene compares (`w` toggles).
    pub compare: Compare,
    quit: bool,
    /// Bumped on every change of the settings.
    pub generation: u64,
    /// The last finished solve (kept on screen while a newer one runs).
    pub solved: Option<Arc<Solved>>,
    /// The generation of the solve in flight.
    pending_solve: Option<u64>,
    /// The settings whose solve failed (not retried until they change).
    failed: Option<SolveKey>,
    /// Where the solve in flight is; None when none runs.
    pub progress: Option<Progress>,
    /// A failure to show in a banner.
    pub error: Option<LabError>,
    /// A one-off message for the status line (the file exported, why a key did nothing).
    pub notice: Option<Notice>,
    /// The kind of the last export asked for.
    pub export_kind: ExportKind,
    /// Inf-sup estimates computed so far.
    pub infsup: HashMap<InfSupKey, Result<InfSup, LabError>>,
    infsup_pending: HashSet<InfSupKey>,
    /// The estimate in flight whose mesh is being built, and where that build is.
    infsup_progress: Option<(InfSupKey, Progress)>,
    /// Every estimate asked for (a row once shown stays, and is asked again if dropped).
    infsup_wanted: HashSet<InfSupKey>,
    /// Work–precision studies computed so far (failures too: they are not retried).
    pub studies: HashMap<StudyKey, Result<Arc<Study>, LabError>>,
    /// The study in flight and the generation it was asked for with.
    study_pending: Option<(u64, StudyKey)>,
    /// The stage of the study in flight.
    pub study_progress: Option<Progress>,
    /// The levels of the study in flight finished so far (drawn until it ends).
    pub study_partial: Option<Arc<Study>>,
    /// The solution whose stresses are being computed.
    stress_pending: Option<SolveKey>,
    /// The overlays, the cursor, the projector view and the message log ([`Overlays`]).
    pub overlays: Overlays,
}

impl App {
    /// The lab on `scenario` at its own settings (level capped at [`MAX_APP_LEVEL`]).
    pub fn new(scenario: Scenario) -> Self {
        let settings = App::defaults(&scenario);
        // A contact zone too narrow to see on the whole of Γ_C opens zoomed in, and says so.
        let narrow = crate::tui::shown::narrow_contact(&scenario);
        let notice = opening_notice(narrow);
        App {
            scenario,
            settings,
            scene: Scene::Explore,
            guides: Guides::default(),
            show_help: false,
            zoom: narrow.is_some(),
            show_timing: true,
            all_levels: false,
            stress_quantity: Quantity::PrincipalShear,
            compare: Compare::Schemes,
            quit: false,
            generation: 0,
            solved: None,
            pending_solve: None,
            failed: None,
            progress: None,
            error: None,
            notice,
            export_kind: ExportKind::Csv,
            infsup: HashMap::new(),
            infsup_pending: HashSet::new(),
            infsup_progress: None,
            infsup_wanted: HashSet::new(),
            studies: HashMap::new(),
            study_pending: None,
            study_progress: None,
            study_partial: None,
            stress_pending: None,
            overlays: Overlays::default(),
        }
    }

    /// The lab as it opens on a scenario given by no file (the paper's problem): at
    /// [`OPENING_LEVEL`] when the scenario's level is coarser, with the inf-sup panel at every
    /// level up to it, so that the first screen shows p's zigzag and the panel's trend.
    pub fn opening(scenario: Scenario) -> Self {
        let mut app = App::new(scenario);
        app.settings.level = app.settings.level.max(OPENING_LEVEL);
        app.all_levels = true;
        app
    }

    /// The scenario's own settings (what `0` returns to).
    pub fn defaults(scenario: &Scenario) -> SolveKey {
        SolveKey {
            level: scenario.level.min(MAX_APP_LEVEL),
            element: scenario.element,
            rule: scenario.rule,
            method: scenario.method,
            // An exact scenario (ε = 0) lends `penalty` and `alm` the paper's ε.
            epsilon: if scenario.epsilon > 0.0 {
                scenario.epsilon
            } else {
                DEFAULT_EPSILON
            },
            depth: scenario.obstacle.depth(),
            refine_edges: scenario.grading(),
            integration: scenario.integration,
            friction: scenario.friction,
        }
    }

    /// Whether something long runs whose time left is shown (the runtime ticks meanwhile).
    pub fn wants_tick(&self) -> bool {
        matches!(self.progress, Some(Progress::Assembling { .. }))
            || (self.scene == Scene::Convergence && self.study_progress.is_some())
            || (self.scene == Scene::InfSup && self.infsup_building().is_some())
    }

    /// Whether the user asked to quit.
    pub fn should_quit(&self) -> bool {
        self.quit
    }

    /// Whether a solve is in flight.
    pub fn is_solving(&self) -> bool {
        self.pending_solve.is_some()
    }

    /// Whether the scene on screen still waits for work it asked for: a solve, an inf-sup
    /// estimate, the study (and its reference) of the convergence scene, the stresses of the
    /// stress scene, the displacement of the deformed body. The tour's auto-advance counts a step's time from the moment this turns
    /// false, and a recording marks the step then.
    pub fn is_computing(&self) -> bool {
        let scene_work = match self.scene {
            Scene::Convergence => self.study_pending.is_some(),
            Scene::Stress => self.current().is_some_and(|s| s.stresses.get().is_none()),
            // The deformed body (explore's contact zone, the mesh scene).
            Scene::Explore | Scene::Mesh => self.current().is_some_and(|s| s.displacement.get().is_none()),
            Scene::InfSup => false,
        };
        self.is_solving() || !self.infsup_pending.is_empty() || scene_work
    }

    /// The estimate in flight whose mesh is being built, and where that build is.
    pub fn infsup_building(&self) -> Option<(InfSupKey, Progress)> {
        self.infsup_progress
            .filter(|(key, _)| self.infsup_pending.contains(key))
    }

    /// The inf-sup estimates in flight.
    pub fn infsup_pending(&self) -> usize {
        self.infsup_pending.len()
    }

    /// Whether the estimate of `key` is in flight.
    pub fn is_estimating(&self, key: &InfSupKey) -> bool {
        self.infsup_pending.contains(key)
    }

    /// The study the convergence scene shows at the current settings: M1–M4 with the lab's
    /// method at the scenario's ε ([`App::defaults`]), or the methods ([`compared_methods`]) on
    /// the lab's scheme at the lab's ε (what the penalty's error depends on); with the lab's
    /// edge grading on, each also graded so, beside the uniform levels.
    pub fn study_key(&self) -> StudyKey {
        let s = &self.settings;
        let (schemes, methods, epsilon) = match self.compare {
            Compare::Schemes => (
                Scheme::PAPER.iter().map(|m| (m.element, m.rule)).collect(),
                vec![s.method],
                App::defaults(&self.scenario).epsilon,
            ),
            Compare::Methods => (
                vec![(s.element, s.rule)],
                compared_methods(s.method).to_vec(),
                s.epsilon,
            ),
        };
        StudyKey {
            scenario: self.scenario.name.clone(),
            // Levels 0 to 4 from the first look, so that the slopes show.
            max_level: MAX_STUDY_LEVEL,
            compare: self.compare,
            schemes,
            methods,
            epsilon,
            integration: s.integration,
            refine_edges: s.refine_edges,
            friction: Box::new(s.friction),
        }
    }

    /// The study in flight, if any.
    pub fn study_pending(&self) -> Option<&StudyKey> {
        self.study_pending.as_ref().map(|(_, k)| k)
    }

    /// The displayed solution if it is of the current settings.
    pub fn current(&self) -> Option<&Arc<Solved>> {
        self.solved.as_ref().filter(|s| s.key == self.settings)
    }

    /// The inf-sup key of the current settings.
    pub fn infsup_key(&self) -> InfSupKey {
        InfSupKey {
            level: self.settings.level,
            element: self.settings.element,
            rule: self.settings.rule,
        }
    }

    /// Handle one input; returns whether to redraw and the work still needed.
    pub fn update(&mut self, msg: Msg) -> Effect {
        let before = (self.notice.clone(), self.error.clone());
        let (settings, scene) = (self.settings, self.scene);
        let solved_before = self.solved.clone();
        let cursor_x = self.cursor_point().map(|(x, _)| x);
        let effect = self.update_inner(msg);
        let same = self.shows(solved_before.as_ref());
        if !same {
            self.follow_cursor(cursor_x);
        }
        // The change first, then what the key said of it.
        self.overlays
            .log
            .changes((&settings, scene), (&self.settings, self.scene));
        self.log_new_messages(before, same);
        effect
    }

    fn update_inner(&mut self, msg: Msg) -> Effect {
        let mut commands = Vec::new();
        let redraw = match msg {
            Msg::Key(key) => self.key(key, &mut commands),
            Msg::Mouse(event) => self.mouse(event),
            Msg::Resize => true,
            Msg::Worker(response) => self.worker(response),
            Msg::Exported(result) => {
                self.notice = Some(match result {
                    Ok(path) => Notice::info(format!("wrote {path}")),
                    Err(e) => Notice::failure(format!("export failed: {e}")),
                });
                true
            }
            Msg::Tick => self.wants_tick(),
            Msg::Notice(notice) => {
                self.notice = Some(notice);
                true
            }
        };
        commands.extend(self.requests());
        Effect { redraw, commands }
    }

    /// The deepest indentation offered: the obstacle's own limit, at most half the height.
    pub fn max_depth(&self) -> f64 {
        self.scenario.obstacle.max_depth().min(self.scenario.height / 2.0)
    }

    /// The levels whose inf-sup estimates the scene shows: in the inf-sup scene levels 0 to
    /// [`FIRST_LEVELS`] (or to the lab's level when finer), so that a trend and its slope show
    /// from the first look; in explore the lab's level, or with `a` every level up to it.
    pub fn infsup_levels(&self) -> std::ops::RangeInclusive<u32> {
        let level = self.settings.level;
        match self.scene {
            Scene::InfSup => 0..=level.max(FIRST_LEVELS),
            _ if self.all_levels => 0..=level,
            _ => level..=level,
        }
    }

    /// The inf-sup estimates the visible scene shows.
    pub(super) fn infsup_needed(&self) -> Vec<InfSupKey> {
        let levels = self.infsup_levels();
        let mut keys = Vec::new();
        for level in levels {
            match self.scene {
                Scene::Explore => keys.push(InfSupKey {
                    level,
                    ..self.infsup_key()
                }),
                Scene::InfSup => keys.extend(Scheme::PAPER.iter().map(|s| InfSupKey {
                    level,
                    element: s.element,
                    rule: s.rule,
                })),
                Scene::Mesh | Scene::Convergence | Scene::Stress => {}
            }
        }
        if self.scene == Scene::Explore {
            // Rows once asked for stay: asked again if the worker dropped them as stale.
            let current = self.infsup_key();
            let mut again: Vec<InfSupKey> = self
                .infsup_wanted
                .iter()
                .filter(|k| (k.element, k.rule) == (current.element, current.rule))
                .copied()
                .collect();
            again.sort_by_key(|k| std::cmp::Reverse(k.level));
            keys.extend(again);
        }
        keys
    }

    /// The requests the visible scene needs that are neither done nor in flight.
    fn requests(&mut self) -> Vec<Command> {
        let mut out = Vec::new();
        if self.current().is_some() && self.pending_solve.is_some_and(|g| g != self.generation) {
            // Back at the solution shown: the solve under way is for settings left behind.
            self.pending_solve = None;
            self.progress = None;
            out.push(Command::Supersede(self.generation));
            // Its displacement was passed over if the solve left behind was answered first.
            if let Some(solved) = self.current()
                && solved.displacement.get().is_none()
            {
                out.push(Command::Displace(DisplaceRequest {
                    solved: solved.clone(),
                }));
            }
        }
        let wants_solve = self.scene.needs_solution()
            && self.current().is_none()
            && self.failed != Some(self.settings)
            && self.pending_solve != Some(self.generation);
        if wants_solve {
            self.pending_solve = Some(self.generation);
            out.push(Command::Solve(SolveRequest {
                generation: self.generation,
                key: self.settings,
            }));
        }
        if self.scene == Scene::Stress
            && let Some(solved) = self.current()
            && solved.stresses.get().is_none()
            && self.stress_pending != Some(solved.key)
        {
            let solved = solved.clone();
            self.stress_pending = Some(solved.key);
            out.push(Command::Stresses(StressRequest { solved }));
        }
        if self.scene == Scene::Convergence {
            let key = self.study_key();
            let in_flight = self.study_pending.as_ref().is_some_and(|(_, k)| *k == key);
            if !self.studies.contains_key(&key) && !in_flight {
                self.study_pending = Some((self.generation, key.clone()));
                out.push(Command::Study(StudyRequest {
                    generation: self.generation,
                    key,
                }));
            }
        }
        for key in self.infsup_needed() {
            if self.scene == Scene::Explore {
                self.infsup_wanted.insert(key);
            }
            if !self.infsup.contains_key(&key) && self.infsup_pending.insert(key) {
                out.push(Command::InfSup(InfSupRequest {
                    generation: self.generation,
                    key,
                }));
            }
        }
        out
    }
}

/// The methods the convergence scene compares, in the legend's order: penalty, alm, nitsche
/// and exact, each with the lab's parameters when it is the lab's method (else its defaults).
pub fn compared_methods(current: Method) -> [Method; 4] {
    let like = |name: &str| {
        if current.name() == name {
            current
        } else {
            Method::parse(name, None, None, None).expect("the names parse")
        }
    };
    [like("penalty"), like("alm"), like("nitsche"), like("exact")]
}

/// `value` × 10^`decades`, computed in decimal so that 1e-6 becomes 1e-5 exactly.
pub fn shift_decades(value: f64, decades: i32) -> f64 {
    let text = format!("{value:e}");
    match text.split_once('e') {
        Some((mantissa, exponent)) => match exponent.parse::<i32>() {
            Ok(e) => format!("{mantissa}e{}", e + decades).parse().unwrap_or(value),
            Err(_) => value,
        },
        None => value,
    }
}

/// What the lab says as it opens: that a contact zone too narrow to see on the whole of Γ_C
/// is shown zoomed in.
fn opening_notice(narrow: Option<f64>) -> Option<Notice> {
    narrow.map(|share| {
        Notice::info(format!(
            "the contact zone spans {:.1}% of Γ_C: opened zoomed in on it (z shows all of Γ_C)",
            100.0 * share
        ))
    })
}
