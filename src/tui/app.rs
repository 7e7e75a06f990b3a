//! The app's state and its pure update function: keys and worker replies come in, the state
//! changes, and the requests the visible scene still needs go out. No terminal, no threads.

use std::collections::{HashMap, HashSet};
use std::sync::Arc;

use crossterm::event::{KeyEvent, KeyEventKind, KeyModifiers};

use crate::contact::{Method, Rule};
use crate::mesh::Element;
use crate::mesh::MAX_LEVEL;
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::stress::Quantity;

use super::beta::InfSup;
pub use super::keys::ExportKind;
use super::keys::{LabAction, lab_action};
pub use super::protocol::{
    Compare, DisplaceRequest, InfSupKey, InfSupRequest, Progress, Response, SolveKey, SolveRequest, Solved,
    StressRequest, Study, StudyKey, StudyRequest,
};

/// The finest level the interactive lab (and `riplab render`) offers. A change at level 7
/// costs about 3–6 s and 1.3 GB with Q1 or P1, and 25–30 s and 5.8 GiB with Q2, whose level 7
/// has the unknowns of Q1's level 8 (BENCHMARKS.md, "Level 7 in the lab"): the lab builds it
/// on a thread of its own with the time left shown, and the memory guard refuses it, saying
/// why, where memory does not allow it. Level 8 is too slow to explore by key; `riplab solve`
/// goes there.
pub const MAX_APP_LEVEL: u32 = if MAX_LEVEL < 7 { MAX_LEVEL } else { 7 };
/// What a change at level 8 costs (Q1, BENCHMARKS.md, "Fresh memory"), as a literal for
/// `concat!`: the one place the lab's messages and `riplab render --help` read it from.
macro_rules! level_8_cost {
    () => {
        "level 8 takes 18–28 s and 5.4 GiB"
    };
}
/// Why the lab stops at [`MAX_APP_LEVEL`], for messages.
pub const LEVEL_LIMIT_WHY: &str = concat!(level_8_cost!(), " a change; `riplab solve --level 8` computes it");
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

/// The finest level the convergence scene studies (the reference is one level finer).
pub const MAX_STUDY_LEVEL: u32 = 4;

/// An input to [`App::update`].
#[derive(Clone, Debug)]
pub enum Msg {
    /// A key pressed.
    Key(KeyEvent),
    /// The terminal was resized (redraw).
    Resize,
    /// A message from the worker.
    Worker(Response),
    /// The result of [`Command::Export`]: the file written, or what went wrong.
    Exported(Result<String, String>),
    /// Time passed while something long runs (the time left changes).
    Tick,
    /// A message for the status line (a tour step saved, a recording that failed).
    Notice(Notice),
}

/// Work for the runtime.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Solve the contact problem of the settings.
    Solve(SolveRequest),
    /// Estimate β_h and β̄_h (docs/design.md §5) for a level, element and rule.
    InfSup(InfSupRequest),
    /// Run the convergence scene's work–precision study.
    Study(StudyRequest),
    /// Compute the stresses of a solution the stress scene shows (kept with it).
    Stresses(StressRequest),
    /// Compute the displacement of the solution shown (kept with it), when the worker passed
    /// it over for a newer solve that the app then left behind.
    Displace(DisplaceRequest),
    /// Write the displayed solution to a new file, or the lab's state as a tour step, as
    /// [`App::export_kind`] says (the kind travels in the app so that the variant stays a
    /// plain `Export`).
    Export,
    /// Ctrl-Z: give the terminal back and stop until resumed.
    Suspend,
    /// Every solve, estimate and study older than this generation is no longer wanted (the
    /// settings came back to the solution shown while a solve of others was under way).
    Supersede(u64),
}

/// What an update asks of the runtime.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Effect {
    /// The screen changed.
    pub redraw: bool,
    /// The work to start, in order.
    pub commands: Vec<Command>,
}

/// A one-off message for the status line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Notice {
    /// The message.
    pub text: String,
    /// Something failed (drawn as bad news).
    pub failure: bool,
}

impl Notice {
    /// A message that is not bad news.
    pub fn info(text: impl Into<String>) -> Self {
        Notice {
            text: text.into(),
            failure: false,
        }
    }
    /// A message that something failed.
    pub fn failure(text: impl Into<String>) -> Self {
        Notice {
            text: text.into(),
            failure: true,
        }
    }
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
    /// Draw −g, scaled, in the pressure chart (`g` toggles).
    pub show_gap: bool,
    /// Draw Hertz's pressure for the computed load in the pressure chart (`h` toggles; a cylinder only).
    pub show_hertz: bool,
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
    pub error: Option<String>,
    /// A one-off message for the status line (the file exported, why a key did nothing).
    pub notice: Option<Notice>,
    /// The kind of the last export asked for.
    pub export_kind: ExportKind,
    /// Inf-sup estimates computed so far.
    pub infsup: HashMap<InfSupKey, Result<InfSup, String>>,
    infsup_pending: HashSet<InfSupKey>,
    /// The estimate in flight whose mesh is being built, and where that build is.
    infsup_progress: Option<(InfSupKey, Progress)>,
    /// Every estimate asked for (a row once shown stays, and is asked again if dropped).
    infsup_wanted: HashSet<InfSupKey>,
    /// Work–precision studies computed so far (failures too: they are not retried).
    pub studies: HashMap<StudyKey, Result<Arc<Study>, String>>,
    /// The study in flight and the generation it was asked for with.
    study_pending: Option<(u64, StudyKey)>,
    /// The stage of the study in flight.
    pub study_progress: Option<Progress>,
    /// The solution whose stresses are being computed.
    stress_pending: Option<SolveKey>,
}

impl App {
    /// The lab on `scenario` at its own settings (level capped at [`MAX_APP_LEVEL`]).
    pub fn new(scenario: Scenario) -> Self {
        let settings = App::defaults(&scenario);
        App {
            scenario,
            settings,
            scene: Scene::Explore,
            show_gap: false,
            show_hertz: false,
            show_help: false,
            zoom: false,
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
            notice: None,
            export_kind: ExportKind::Csv,
            infsup: HashMap::new(),
            infsup_pending: HashSet::new(),
            infsup_progress: None,
            infsup_wanted: HashSet::new(),
            studies: HashMap::new(),
            study_pending: None,
            study_progress: None,
            stress_pending: None,
        }
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
    /// the lab's scheme at the lab's ε (what the penalty's error depends on).
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
            max_level: s.level.min(MAX_STUDY_LEVEL),
            compare: self.compare,
            schemes,
            methods,
            epsilon,
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
        let mut commands = Vec::new();
        let redraw = match msg {
            Msg::Key(key) => self.key(key, &mut commands),
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

    fn key(&mut self, key: KeyEvent, commands: &mut Vec<Command>) -> bool {
        if !matches!(key.kind, KeyEventKind::Press | KeyEventKind::Repeat) {
            return false;
        }
        let control = key.modifiers.contains(KeyModifiers::CONTROL);
        let action = lab_action(key.code, control);
        if control {
            match action {
                Some(LabAction::Quit) => self.quit = true,
                Some(LabAction::Suspend) => commands.push(Command::Suspend),
                _ => return false,
            }
            return true;
        }
        self.notice = None;
        if self.show_help {
            // Any key closes the help and does nothing else.
            self.show_help = false;
            return true;
        }
        let Some(action) = action else {
            return false;
        };
        let before = self.settings;
        match action {
            LabAction::Quit => self.quit = true,
            LabAction::Help => self.show_help = true,
            LabAction::Coarser => {
                if self.settings.level == 0 {
                    self.notice = Some(Notice::info("level 0 is the coarsest mesh"));
                }
                self.settings.level = self.settings.level.saturating_sub(1);
            }
            LabAction::Finer => {
                if self.settings.level >= MAX_APP_LEVEL {
                    self.notice = Some(Notice::info(format!(
                        concat!(
                            "level {} is the lab's finest: ",
                            level_8_cost!(),
                            " (riplab solve)"
                        ),
                        MAX_APP_LEVEL
                    )));
                }
                self.settings.level = (self.settings.level + 1).min(MAX_APP_LEVEL);
            }
            LabAction::Reset => {
                self.settings = App::defaults(&self.scenario);
                self.show_gap = false;
                self.show_hertz = false;
                self.all_levels = false;
                self.zoom = false;
                self.notice = Some(Notice::info("reset to the scenario's settings"));
            }
            LabAction::NextRule => {
                let i = Rule::ALL
                    .iter()
                    .position(|&r| r == self.settings.rule)
                    .unwrap_or(0);
                self.settings.rule = Rule::ALL[(i + 1) % Rule::ALL.len()];
            }
            LabAction::NextElement => {
                let all = Element::ALL;
                let i = all.iter().position(|&e| e == self.settings.element).unwrap_or(0);
                self.settings.element = all[(i + 1) % all.len()];
            }
            LabAction::Scheme(m) => {
                if let Some(s) = Scheme::paper(m) {
                    self.settings.element = s.element;
                    self.settings.rule = s.rule;
                }
            }
            LabAction::NextMethod => self.settings.method = self.settings.method.next(),
            LabAction::Compare => {
                self.compare = match self.compare {
                    Compare::Schemes => Compare::Methods,
                    Compare::Methods => Compare::Schemes,
                };
                if self.scene != Scene::Convergence {
                    self.notice = Some(Notice::info(match self.compare {
                        Compare::Schemes => "the convergence scene compares M1–M4 (Tab to it)",
                        Compare::Methods => "the convergence scene compares the methods (Tab to it)",
                    }));
                }
            }
            LabAction::EpsilonUp => self.shift_epsilon(1),
            LabAction::EpsilonDown => self.shift_epsilon(-1),
            LabAction::Shallower => self.shift_depth(-DEPTH_STEP),
            LabAction::Deeper => self.shift_depth(DEPTH_STEP),
            LabAction::NextScene => self.scene = self.scene.shifted(1),
            LabAction::PreviousScene => self.scene = self.scene.shifted(Scene::ALL.len() - 1),
            LabAction::Gap => self.show_gap = !self.show_gap,
            LabAction::Hertz => {
                if self.scenario.obstacle.hertz_radius().is_some() || self.show_hertz {
                    self.show_hertz = !self.show_hertz;
                } else {
                    self.notice = Some(Notice::info(
                        "no Hertz solution for this obstacle: it needs a cylinder (a radius)",
                    ));
                }
            }
            LabAction::Zoom => self.toggle_zoom(),
            LabAction::AllLevels => self.all_levels = !self.all_levels,
            LabAction::NextQuantity => self.stress_quantity = self.stress_quantity.next(),
            LabAction::Export(ExportKind::TourStep) => {
                // The lab's state, solved or not: written by the runtime (a tour file).
                self.export_kind = ExportKind::TourStep;
                commands.push(Command::Export);
            }
            LabAction::Export(kind) => {
                if self.current().is_some() {
                    self.export_kind = kind;
                    commands.push(Command::Export);
                } else {
                    self.notice = Some(Notice::info("nothing to export yet: the solve is not finished"));
                }
            }
            // Only with Ctrl (above).
            LabAction::Suspend => return false,
        }
        if self.settings != before {
            self.generation += 1;
            self.error = None;
        }
        true
    }

    /// `z`: zoom to the contact zone and back (only where there is one to zoom to).
    fn toggle_zoom(&mut self) {
        if self.zoom {
            self.zoom = false;
            return;
        }
        if !matches!(self.scene, Scene::Explore | Scene::Mesh | Scene::Stress) {
            self.notice = Some(Notice::info(
                "z zooms the pressure chart, the contact zone and the stress map: explore, mesh and stress scenes",
            ));
            return;
        }
        let in_contact = self
            .current()
            .is_some_and(|s| s.solution.pbar.iter().any(|&p| p > 0.0));
        if in_contact {
            self.zoom = true;
        } else {
            self.notice = Some(Notice::info("nothing to zoom to: no contact (p̄ = 0)"));
        }
    }

    /// ε times 10^`decades`, kept to the decimal digits of the scenario's ε.
    fn shift_epsilon(&mut self, decades: i32) {
        let next = shift_decades(self.settings.epsilon, decades);
        if (EPSILON_RANGE.0..=EPSILON_RANGE.1).contains(&next) {
            self.settings.epsilon = next;
        } else {
            self.notice = Some(Notice::info(format!(
                "ε stays within {:e} to {:e}",
                EPSILON_RANGE.0, EPSILON_RANGE.1
            )));
        }
    }

    /// The depth plus `delta`, within 0..=min(R, height)/2, rounded to 1e-9.
    fn shift_depth(&mut self, delta: f64) {
        let max = self.max_depth();
        let next = ((self.settings.depth + delta) * 1e9).round() / 1e9;
        if (0.0..=max + 1e-12).contains(&next) {
            self.settings.depth = next;
        } else {
            self.notice = Some(Notice::info(format!("depth stays within 0 to {max}")));
        }
    }

    /// The deepest indentation offered: the obstacle's own limit, at most half the height.
    pub fn max_depth(&self) -> f64 {
        self.scenario.obstacle.max_depth().min(self.scenario.height / 2.0)
    }

    fn worker(&mut self, response: Response) -> bool {
        match response {
            Response::Progress { generation, progress } => {
                if self.pending_solve != Some(generation) {
                    return false;
                }
                self.progress = Some(progress);
            }
            Response::Solved { generation, result } => {
                if self.pending_solve != Some(generation) {
                    return false;
                }
                self.pending_solve = None;
                self.progress = None;
                match result {
                    // The user came back to the settings on screen meanwhile: keep them.
                    Ok(solved) if solved.key != self.settings && self.current().is_some() => {}
                    Ok(solved) => {
                        self.solved = Some(solved);
                        self.error = None;
                    }
                    Err(e) => {
                        self.failed = Some(self.settings);
                        self.error = Some(e);
                    }
                }
            }
            Response::Displaced { key } => {
                return self.scene.needs_solution() && self.current().is_some_and(|s| s.key == key);
            }
            Response::Stresses { key } => {
                if self.stress_pending == Some(key) {
                    self.stress_pending = None;
                }
                return self.scene == Scene::Stress && self.current().is_some_and(|s| s.key == key);
            }
            Response::StudyProgress { generation, progress } => {
                if self.study_pending.as_ref().map(|(g, _)| *g) != Some(generation) {
                    return false;
                }
                self.study_progress = Some(progress);
                return self.scene == Scene::Convergence;
            }
            Response::Cancelled { generation } => {
                if self.pending_solve != Some(generation) {
                    return false;
                }
                self.pending_solve = None;
                self.progress = None;
            }
            Response::InfSupProgress { key, progress } => {
                if !self.infsup_pending.contains(&key) {
                    return false;
                }
                self.infsup_progress = Some((key, progress));
                return self.scene == Scene::InfSup;
            }
            Response::InfSup { key, result } => {
                self.infsup_pending.remove(&key);
                if self.infsup_progress.is_some_and(|(k, _)| k == key) {
                    self.infsup_progress = None;
                }
                match result {
                    Some(result) => {
                        self.infsup.insert(key, result);
                    }
                    None => return false,
                }
            }
            Response::Study {
                generation,
                key,
                result,
            } => {
                if self.study_pending.as_ref() != Some(&(generation, key.clone())) {
                    // Superseded by a newer study request: dropped.
                    return false;
                }
                self.study_pending = None;
                self.study_progress = None;
                if let Some(result) = result {
                    self.studies.insert(key, result);
                }
            }
        }
        true
    }

    /// The inf-sup estimates the visible scene shows.
    fn infsup_needed(&self) -> Vec<InfSupKey> {
        let levels = if self.all_levels {
            0..=self.settings.level
        } else {
            self.settings.level..=self.settings.level
        };
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
