//! The tour's state and its pure update: the step shown, the lab at that step's settings (or,
//! on a two-body step, the lab's two-body scene, [`super::bodies_step`]), and the keys that
//! move between steps. Every other key goes to the lab (or the two-body scene), so that a step
//! can be explored; leaving a step and coming back restores its settings.

use std::collections::HashMap;
use std::sync::Arc;
use std::time::Duration;

use crossterm::event::{KeyCode, KeyEventKind, KeyModifiers};

use crate::scenario::Scenario;

use super::super::app::{App, Command, InfSupKey, Msg, Notice};
use super::super::beta::InfSup;
use super::super::bodies::{BodiesApp, Request};
use super::super::bodies_solve::Solved as BodiesSolved;
use super::super::keys::{LabAction, TourAction, lab_action, tour_action};
use super::super::lab_error::LabError;
use super::super::protocol::Solved;
use super::Tour;
use super::caption::caption_rows;

/// Inf-sup estimates by key, as the lab holds them.
type Estimates = HashMap<InfSupKey, Result<InfSup, LabError>>;

/// How many finished solves are kept for going back.
const KEPT_SOLVES: usize = 16;

/// An input to [`TourApp::update`].
#[derive(Clone, Debug)]
pub enum TourMsg {
    /// A key, a resize, a worker reply or an export result, as for the lab.
    Lab(Msg),
    /// The auto-advance interval has passed (see [`TourApp::auto_due`]).
    Auto,
}

/// What an update asks of the runtime.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TourEffect {
    /// The screen changed.
    pub redraw: bool,
    /// Work for the worker of the current step's scenario (or exports).
    pub commands: Vec<Command>,
    /// Another step is shown (the auto-advance clock starts again).
    pub step_changed: bool,
    /// The solve the two-body scene of the current step asks for.
    pub bodies: Option<Request>,
}

/// The state of a running tour.
#[derive(Debug)]
pub struct TourApp {
    /// The tour being walked through.
    pub tour: Tour,
    index: usize,
    /// The lab at the current step (on a two-body step, the lab on the tour's scenario,
    /// unsolved: [`TourApp::bodies`] is shown).
    pub app: App,
    /// The two-body scene of the current step, when its scenario has two bodies.
    pub bodies: Option<BodiesApp>,
    /// The newest generation of the two-body scenes' requests: a step's scene starts past it,
    /// so that a late reply to a step left is never taken for another's.
    bodies_generation: u64,
    /// Recent two-body solves, with their scenarios, for going back without solving again.
    bodies_solves: Vec<(Scenario, BodiesSolved)>,
    /// Advance by itself after this long on a step (once its numbers are on screen).
    pub auto: Option<Duration>,
    /// The help overlay is open (`?`).
    pub show_help: bool,
    /// Show solve times (off for deterministic frames).
    pub show_timing: bool,
    /// The first caption row shown (long captions scroll with ↑ and ↓).
    pub caption_scroll: u16,
    /// Whether the terminal is large enough for the tour (auto-advance pauses otherwise).
    pub fits: bool,
    quit: bool,
    /// `q` was pressed before the last step: the next key quits if it is `q` again.
    quit_asked: bool,
    /// Recent solves, with their scenarios, for going back without solving again.
    solves: Vec<(Scenario, Arc<Solved>)>,
    /// Inf-sup estimates per scenario.
    estimates: Vec<(Scenario, Estimates)>,
}

impl TourApp {
    /// The tour at its first step.
    pub fn new(tour: Tour, auto: Option<Duration>) -> Self {
        let app = tour.app(0);
        let bodies = tour.bodies(0);
        TourApp {
            tour,
            index: 0,
            app,
            bodies,
            bodies_generation: 0,
            bodies_solves: Vec::new(),
            auto,
            show_help: false,
            show_timing: true,
            caption_scroll: 0,
            fits: true,
            quit: false,
            quit_asked: false,
            solves: Vec::new(),
            estimates: Vec::new(),
        }
    }

    /// The index of the step shown.
    pub fn index(&self) -> usize {
        self.index
    }

    /// Whether the last step is shown.
    pub fn at_end(&self) -> bool {
        self.index + 1 >= self.tour.steps.len()
    }

    /// Whether the user asked to quit.
    pub fn should_quit(&self) -> bool {
        self.quit
    }

    /// Whether the lab still computes what the step shows ([`App::is_computing`]: the solve,
    /// the inf-sup rows, the study and its reference, the stresses); on a two-body step,
    /// whether its scene's solve is still to come.
    pub fn is_busy(&self) -> bool {
        match &self.bodies {
            Some(bodies) => !bodies.settled(),
            None => self.app.is_computing(),
        }
    }

    /// The solve the current step's two-body scene still needs (None on a one-body step, or
    /// once it is solved).
    pub fn bodies_request(&self) -> Option<Request> {
        self.bodies
            .as_ref()
            .filter(|b| !b.settled())
            .map(BodiesApp::start)
    }

    /// The two-body solver's answer for `generation`: shown if it is the current scene's
    /// newest request's; whether it was.
    pub fn bodies_reply(
        &mut self,
        generation: u64,
        result: Result<BodiesSolved, crate::contact::interface::solve::BodiesError>,
    ) -> bool {
        self.bodies.as_mut().is_some_and(|b| b.reply(generation, result))
    }

    /// Show `notice` on the status line of the scene shown (the lab's, or the two-body
    /// scene's).
    pub fn show_notice(&mut self, notice: Notice) {
        match &mut self.bodies {
            Some(bodies) => bodies.notice = Some(notice),
            None => self.app.notice = Some(notice),
        }
    }

    /// Say `text` on the status line of the scene shown.
    fn say(&mut self, text: String) {
        self.show_notice(Notice::info(text));
    }

    /// Whether to advance by itself, the step's computations having finished `elapsed` ago
    /// (the runtime counts from that moment): in auto mode, once the interval has passed and
    /// nothing is computing, except at the end and while the terminal is too small to show
    /// the step.
    pub fn auto_due(&self, elapsed: Duration) -> bool {
        self.auto.is_some_and(|a| elapsed >= a) && !self.at_end() && !self.is_busy() && self.fits
    }

    /// The terminal is `width`×`height`: does the tour fit (see [`super::MIN_TOUR_SIZE`])?
    pub fn set_size(&mut self, width: u16, height: u16) {
        self.fits = width >= super::MIN_TOUR_SIZE.0 && height >= super::MIN_TOUR_SIZE.1;
    }

    /// Whether the lab's settings still are the step's (false once the user changed them).
    pub fn is_pristine(&self) -> bool {
        if let Some(bodies) = &self.bodies {
            return self
                .tour
                .bodies(self.index)
                .is_some_and(|step| step.settings == bodies.settings);
        }
        let step = self.tour.app(self.index);
        (step.settings, step.scene, step.guides, step.all_levels)
            == (
                self.app.settings,
                self.app.scene,
                self.app.guides,
                self.app.all_levels,
            )
    }

    /// Handle one input.
    pub fn update(&mut self, msg: TourMsg) -> TourEffect {
        let target = match msg {
            TourMsg::Auto => (!self.at_end()).then_some(self.index + 1),
            TourMsg::Lab(Msg::Key(key)) => {
                if !matches!(key.kind, KeyEventKind::Press | KeyEventKind::Repeat) {
                    return TourEffect::default();
                }
                // Asked by the key before: any key but `q` goes on.
                let asked = std::mem::take(&mut self.quit_asked);
                if key.modifiers.contains(KeyModifiers::CONTROL) {
                    if matches!(key.code, KeyCode::Char('c' | 'C')) {
                        self.quit = true;
                        return TourEffect {
                            redraw: true,
                            ..TourEffect::default()
                        };
                    }
                    // Ctrl-Z and the like are the lab's.
                    return self.lab(Msg::Key(key));
                }
                if self.show_help {
                    // Any key closes the help and does nothing else.
                    self.show_help = false;
                    return TourEffect {
                        redraw: true,
                        ..TourEffect::default()
                    };
                }
                let last = self.tour.steps.len().saturating_sub(1);
                let Some(action) = tour_action(key.code) else {
                    return self.lab(Msg::Key(key));
                };
                match action {
                    TourAction::Quit if asked || self.at_end() => {
                        self.quit = true;
                        return TourEffect {
                            redraw: true,
                            ..TourEffect::default()
                        };
                    }
                    TourAction::Quit => {
                        // A lesson is not ended by a stray key: asked once.
                        self.quit_asked = true;
                        let (n, last) = (self.index + 1, self.tour.steps.len());
                        self.say(format!(
                            "step {n} of {last}: q again ends the tour, any other key goes on"
                        ));
                        return TourEffect {
                            redraw: true,
                            ..TourEffect::default()
                        };
                    }
                    TourAction::Help => {
                        self.show_help = true;
                        return TourEffect {
                            redraw: true,
                            ..TourEffect::default()
                        };
                    }
                    TourAction::Next => Some((self.index + 1).min(last)),
                    TourAction::Previous => Some(self.index.saturating_sub(1)),
                    TourAction::ScrollUp => {
                        self.caption_scroll = self.caption_scroll.saturating_sub(1);
                        return TourEffect {
                            redraw: true,
                            ..TourEffect::default()
                        };
                    }
                    TourAction::ScrollDown => {
                        // At most to the last row of the caption at the narrowest width.
                        let caption = &self.tour.steps[self.index].caption;
                        let rows = caption_rows(caption, super::MIN_TOUR_SIZE.0 - 2).len();
                        self.caption_scroll = (self.caption_scroll + 1).min(rows.saturating_sub(1) as u16);
                        return TourEffect {
                            redraw: true,
                            ..TourEffect::default()
                        };
                    }
                    TourAction::First => Some(0),
                    TourAction::Last => Some(last),
                }
            }
            // The tour's help is over the lab: a click there is not the lab's.
            TourMsg::Lab(Msg::Mouse(_)) if self.show_help => return TourEffect::default(),
            TourMsg::Lab(other) => return self.lab(other),
        };
        match target {
            Some(i) if i != self.index => TourEffect {
                redraw: true,
                commands: self.enter(i),
                step_changed: true,
                bodies: self.bodies_request(),
            },
            // At either end: nothing moves, and the status line says why (a help overlay
            // closed above needs a redraw too).
            Some(_) => {
                let (n, last) = (self.index + 1, self.tour.steps.len());
                self.say(if n == last {
                    format!("step {n} of {last} is the last: q ends the tour, Home goes back to the first")
                } else {
                    format!("step {n} of {last} is the first: Space goes on")
                });
                TourEffect {
                    redraw: true,
                    ..TourEffect::default()
                }
            }
            None => TourEffect {
                redraw: true,
                ..TourEffect::default()
            },
        }
    }

    /// Pass `msg` to the lab, or on a two-body step to its scene.
    fn lab(&mut self, msg: Msg) -> TourEffect {
        if let Some(bodies) = &mut self.bodies {
            return bodies_msg(bodies, msg);
        }
        let effect = self.app.update(msg);
        TourEffect {
            redraw: effect.redraw,
            commands: effect.commands,
            ..TourEffect::default()
        }
    }

    /// Show step `index` (clamped to the last step); returns the requests its lab needs.
    pub fn go_to(&mut self, index: usize) -> Vec<Command> {
        let index = index.min(self.tour.steps.len().saturating_sub(1));
        if index == self.index {
            return self.lab(Msg::Resize).commands;
        }
        self.enter(index)
    }

    /// Show step `index`: keep what the lab computed, set up the step's lab from what is
    /// known, and return the requests it still needs (a two-body step's solve is
    /// [`TourApp::bodies_request`]).
    fn enter(&mut self, index: usize) -> Vec<Command> {
        self.keep();
        let generation = self.app.generation + 1;
        self.index = index;
        self.caption_scroll = 0;
        let mut app = self.tour.app(index);
        app.show_timing = self.show_timing;
        // Replies to the previous step's requests carry older generations: ignored.
        app.generation = generation;
        if let Some((_, estimates)) = self.estimates.iter().find(|(s, _)| *s == app.scenario) {
            app.infsup = estimates.clone();
        }
        app.solved = self
            .solves
            .iter()
            .rev()
            .find(|(s, solved)| *s == app.scenario && solved.key == app.settings)
            .map(|(_, solved)| solved.clone());
        self.app = app;
        self.bodies = self.tour.bodies(index).map(|mut bodies| {
            self.bodies_generation += 1;
            bodies.generation = self.bodies_generation;
            bodies.solved = self
                .bodies_solves
                .iter()
                .rev()
                .find(|(s, solved)| *s == bodies.scenario && solved.settings == bodies.settings)
                .map(|(_, solved)| solved.clone());
            bodies
        });
        if self.bodies.is_some() {
            // The lab waits unsolved while the two-body scene is shown.
            return Vec::new();
        }
        self.app.update(Msg::Resize).commands
    }

    /// File the lab's (or the two-body scene's) finished work under its scenario.
    fn keep(&mut self) {
        if let Some(bodies) = &self.bodies {
            self.bodies_generation = self.bodies_generation.max(bodies.generation);
            if let Some(solved) = bodies.solved.as_ref().filter(|_| bodies.error.is_none()) {
                let known = self
                    .bodies_solves
                    .iter()
                    .any(|(s, k)| k == solved && *s == bodies.scenario);
                if !known {
                    self.bodies_solves.push((bodies.scenario.clone(), solved.clone()));
                    if self.bodies_solves.len() > KEPT_SOLVES {
                        self.bodies_solves.remove(0);
                    }
                }
            }
            return;
        }
        let scenario = &self.app.scenario;
        if let Some(solved) = &self.app.solved {
            let known = self
                .solves
                .iter()
                .any(|(s, k)| Arc::ptr_eq(k, solved) && s == scenario);
            if !known {
                self.solves.push((scenario.clone(), solved.clone()));
                if self.solves.len() > KEPT_SOLVES {
                    self.solves.remove(0);
                }
            }
        }
        let done = self.app.infsup.clone();
        match self.estimates.iter_mut().find(|(s, _)| s == scenario) {
            Some((_, estimates)) => estimates.extend(done),
            None => self.estimates.push((scenario.clone(), done)),
        }
    }
}

/// `msg` for the two-body scene of a step: a key to the scene (its solve asked for when its
/// settings changed; Ctrl-Z suspends, as in the lab), a resize redrawn, a notice shown; the
/// lab's other messages (its worker's replies, its clock) concern the lab, which waits.
fn bodies_msg(bodies: &mut BodiesApp, msg: Msg) -> TourEffect {
    match msg {
        Msg::Key(key) if key.modifiers.contains(KeyModifiers::CONTROL) => {
            let suspend = lab_action(key.code, true) == Some(LabAction::Suspend)
                && matches!(key.kind, KeyEventKind::Press | KeyEventKind::Repeat);
            TourEffect {
                redraw: suspend,
                commands: if suspend {
                    vec![Command::Suspend]
                } else {
                    Vec::new()
                },
                ..TourEffect::default()
            }
        }
        Msg::Key(key)
            if matches!(
                lab_action(key.code, false),
                Some(LabAction::NextScene | LabAction::PreviousScene)
            ) =>
        {
            // The tour's worker solves a step; the inf-sup view's estimates are the lab's.
            bodies.notice = Some(Notice::info(
                "Tab: a tour step shows its interface pressure; the lab (riplab FILE) has the two-body inf-sup view",
            ));
            TourEffect {
                redraw: true,
                ..TourEffect::default()
            }
        }
        Msg::Key(key) => {
            let (redraw, request) = bodies.key(key);
            TourEffect {
                redraw,
                bodies: request,
                ..TourEffect::default()
            }
        }
        Msg::Resize => TourEffect {
            redraw: true,
            ..TourEffect::default()
        },
        Msg::Notice(notice) => {
            bodies.notice = Some(notice);
            TourEffect {
                redraw: true,
                ..TourEffect::default()
            }
        }
        Msg::Mouse(_) | Msg::Worker(_) | Msg::Exported(_) | Msg::Tick => TourEffect::default(),
    }
}
