//! The tour in the lab's event loop ([`super::super::event_loop::run_program`]): one worker per
//! scenario in use, replies of a replaced worker dropped, a two-body solver for the two-body
//! steps ([`super::bodies_worker`]), and the auto-advance clock.

use std::io;
use std::path::PathBuf;
use std::sync::mpsc::Sender;
use std::time::{Duration, Instant};

use crossterm::event::Event;
use ratatui::Frame;

use crate::scenario::Scenario;

use super::super::app::{Command, Msg, Notice};
use super::super::bodies::Request;
use super::super::event_loop::{Flow, Input, Program, TICK, run_program};
use super::super::export::export_shown;
use super::super::record::{CastFile, Chapter};
use super::super::theme::Theme;
use super::super::view::Look;
use super::super::worker::Worker;
use super::super::{RunError, TuiOptions};
use super::bodies_worker::BodiesWorker;
use super::{Tour, TourApp, TourMsg, auto_interval, view};

/// Run `tour` in the terminal until the user quits; with `auto` (seconds, 0.5..=3600) each
/// step advances by itself that long after its computations have finished (its numbers on
/// screen), stopping at the last. The terminal is restored in every case. With `record`, the
/// tour is recorded (see [`super::super::record`]), a marker at each step once it is
/// computed.
pub fn run_tour(
    tour: Tour,
    opts: &TuiOptions,
    auto: Option<f64>,
    record: Option<CastFile>,
) -> Result<(), RunError> {
    let auto = auto
        .map(auto_interval)
        .transpose()
        .map_err(|e| io::Error::new(io::ErrorKind::InvalidInput, format!("--auto: {e}")))?;
    let look = Look {
        theme: Theme::new(opts.no_color),
        marker: opts.marker.marker(),
    };
    let dir = opts.export_dir()?;
    let title = format!("riplab tour: {}", tour.title);
    run_program(record.map(|r| (r, title)), !opts.no_mouse, |tx, size| {
        let mut player = TourApp::new(tour, auto);
        player.set_size(size.width, size.height);
        let scenario = player.app.scenario.clone();
        Ok(Session {
            worker: spawn(&tx, scenario.clone(), 0),
            bodies: None,
            player,
            scenario,
            epoch: 0,
            tx,
            ready: None,
            dir,
            look,
            recording_failed: None,
        })
    })
}

/// The tour in the loop: the player, its worker and what the loop needs besides.
struct Session {
    player: TourApp,
    worker: Worker,
    /// The solver of the two-body steps' scenario, once one is shown.
    bodies: Option<BodiesWorker>,
    /// The scenario the worker computes on, and its epoch (bumped with each new worker).
    scenario: Scenario,
    epoch: u64,
    tx: Sender<Input>,
    /// When the current step's finished frame was shown (None while its computations run,
    /// or while the terminal is too small for the tour): the auto-advance counts from then,
    /// so that a step stays on screen, and in a recording after its marker, the whole
    /// interval however long the frame took to come.
    ready: Option<Instant>,
    /// Where exports go (absolute).
    dir: PathBuf,
    look: Look,
    /// The recording's failure: shown again on each step the tour advances to by itself, until
    /// a key is pressed (a step's lab starts without the notice of the step before).
    recording_failed: Option<Notice>,
}

impl Session {
    /// Update the tour and carry out its commands.
    fn apply(&mut self, msg: TourMsg) -> Flow {
        let effect = self.player.update(msg);
        let mut flow = Flow {
            redraw: effect.redraw,
            suspend: false,
        };
        if effect.step_changed {
            self.ready = None;
            if let Some(failure) = &self.recording_failed {
                self.player.show_notice(failure.clone());
            }
            if self.player.app.scenario != self.scenario {
                self.scenario = self.player.app.scenario.clone();
                self.epoch += 1;
                self.worker = spawn(&self.tx, self.scenario.clone(), self.epoch);
            }
        }
        for command in effect.commands {
            match command {
                Command::Export => {
                    let reply = export_shown(&self.player.app, &self.dir);
                    flow |= self.apply(TourMsg::Lab(reply));
                }
                Command::Suspend => flow.suspend = true,
                other => self.worker.send(&other),
            }
        }
        if let Some(request) = effect.bodies {
            self.ask_bodies(request);
        }
        self.finish(flow)
    }

    /// Ask the two-body solver of the shown scene's scenario (started, or replaced, when the
    /// scene's scenario is another) for `request`; a solver that cannot start or has stopped
    /// is said on the status line.
    fn ask_bodies(&mut self, request: Request) {
        let Some(scene) = &mut self.player.bodies else {
            return;
        };
        if self.bodies.as_ref().is_none_or(|w| w.scenario != scene.scenario) {
            // The solver of another scenario is dropped first: what it solves is given up.
            self.bodies = None;
            match BodiesWorker::spawn(scene.scenario.clone(), self.tx.clone()) {
                Ok(worker) => self.bodies = Some(worker),
                Err(e) => {
                    scene.notice = Some(Notice::failure(format!(
                        "the two-body solver could not start: {e}"
                    )));
                    return;
                }
            }
        }
        if !self.bodies.as_ref().is_some_and(|w| w.send(request)) {
            scene.notice = Some(Notice::failure("the two-body solver has stopped"));
        }
    }

    /// `flow`, redrawn when the step's frame is finished (the auto-advance's clock starts once
    /// it is shown).
    fn finish(&mut self, mut flow: Flow) -> Flow {
        if !self.player.fits {
            self.ready = None;
        } else if self.ready.is_none() && !self.player.is_busy() {
            // The finished frame is drawn, and the clock starts when it is shown.
            flow.redraw = true;
        }
        flow
    }
}

impl Program for Session {
    fn start(&mut self) -> Flow {
        let flow = self.apply(TourMsg::Lab(Msg::Resize));
        if let Some(request) = self.player.bodies_request() {
            self.ask_bodies(request);
        }
        flow
    }

    fn input(&mut self, input: Input) -> Flow {
        if let Input::Terminal(Event::Key(_)) = input {
            // Seen: the failure is not shown again.
            self.recording_failed = None;
        }
        let msg = match input {
            Input::Terminal(Event::Key(key)) => Msg::Key(key),
            Input::Terminal(Event::Mouse(event)) => Msg::Mouse(event),
            Input::Terminal(Event::Resize(width, height)) => {
                // Paused while too small: the step's time starts again once it fits ([`Session::apply`]).
                self.player.set_size(width, height);
                Msg::Resize
            }
            Input::Worker(epoch, r) if epoch == self.epoch => Msg::Worker(r),
            Input::Bodies(generation, result) => {
                let shown = self.player.bodies_reply(generation, *result);
                return self.finish(Flow {
                    redraw: shown,
                    suspend: false,
                });
            }
            // Other terminal events, replies of a replaced worker.
            Input::Terminal(_)
            | Input::Worker(..)
            | Input::Broken(_)
            | Input::RecordingFailed
            | Input::Signal => {
                return Flow::default();
            }
        };
        self.apply(TourMsg::Lab(msg))
    }

    fn tick(&mut self) -> Flow {
        self.apply(TourMsg::Lab(Msg::Tick))
    }

    fn after_inputs(&mut self) -> Flow {
        if self.ready.is_some_and(|t| self.player.auto_due(t.elapsed())) {
            self.apply(TourMsg::Auto)
        } else {
            Flow::default()
        }
    }

    /// Until the auto-advance is due (counted from the step's finished frame), a tick
    /// while a long job shows its time left, or for ever.
    fn wait(&self) -> Option<Duration> {
        let tick = self.player.app.wants_tick().then_some(TICK);
        let auto = self
            .player
            .auto
            .filter(|_| !self.player.at_end() && !self.player.is_busy() && self.player.fits);
        let due = auto
            .zip(self.ready)
            .map(|(a, ready)| a.saturating_sub(ready.elapsed()));
        match (tick, due) {
            (Some(t), Some(d)) => Some(t.min(d)),
            (t, d) => t.or(d),
        }
    }

    fn should_quit(&self) -> bool {
        self.player.should_quit()
    }

    fn shown(&mut self) {
        if self.ready.is_none() && !self.player.is_busy() && self.player.fits {
            self.ready = Some(Instant::now());
        }
    }

    fn draw(&self, frame: &mut Frame) {
        view(&self.player, frame, &self.look);
    }

    /// The step once its computations have finished (so that a marker's frame is the
    /// step's finished frame); None while they run.
    fn chapter(&self) -> Option<Chapter> {
        if self.player.is_busy() {
            return None;
        }
        let i = self.player.index();
        Some(Chapter {
            step: Some((i, self.player.tour.steps[i].title.clone())),
            scene: self.player.app.scene,
        })
    }

    fn notice(&mut self, notice: Notice) -> Flow {
        self.recording_failed = notice.failure.then(|| notice.clone());
        self.apply(TourMsg::Lab(Msg::Notice(notice)))
    }
}

/// A worker on `scenario` whose replies go to `tx` tagged with `epoch`.
fn spawn(tx: &Sender<Input>, scenario: Scenario, epoch: u64) -> Worker {
    let tx = tx.clone();
    Worker::spawn(scenario, move |r| tx.send(Input::Worker(epoch, r)).is_ok())
}
