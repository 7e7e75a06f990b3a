//! The tour's interactive loop: the lab's loop (input thread, worker, redraw on change inside
//! synchronized-output brackets) with one worker per scenario in use, replies of a replaced
//! worker dropped, and the auto-advance clock.

use std::io;
use std::path::PathBuf;
use std::sync::mpsc::{self, RecvTimeoutError, Sender};
use std::time::{Duration, Instant};

use crossterm::event::Event;
use ratatui::DefaultTerminal;

use crate::scenario::Scenario;

use super::super::TuiOptions;
use super::super::app::{Command, Msg, Response};
use super::super::runtime::{TICK, draw_with, export, forward_terminal, suspend};
use super::super::theme::Theme;
use super::super::view::Look;
use super::super::worker::Worker;
use super::{Tour, TourApp, TourMsg, auto_interval, view};

/// Everything the loop waits for.
enum Input {
    Terminal(Event),
    /// A reply of the worker of the given epoch.
    Worker(u64, Response),
    /// Reading the terminal failed: the loop ends with this error.
    Broken(io::Error),
}

/// Run `tour` in the terminal until the user quits; with `auto` (seconds, 0.5..=3600) each
/// step advances by itself that long after its numbers are on screen, stopping at the last.
/// The terminal is restored in every case.
pub fn run_tour(tour: Tour, opts: &TuiOptions, auto: Option<f64>) -> io::Result<()> {
    let auto = auto
        .map(auto_interval)
        .transpose()
        .map_err(|e| io::Error::new(io::ErrorKind::InvalidInput, format!("--auto: {e}")))?;
    let look = Look {
        theme: Theme::new(opts.no_color),
        marker: opts.marker.marker(),
    };
    let dir = opts.export_dir()?;
    let mut terminal = ratatui::try_init()?;
    let result = event_loop(&mut terminal, tour, auto, &look, dir);
    ratatui::restore();
    result
}

/// The loop's state besides the terminal.
struct Session {
    player: TourApp,
    worker: Worker,
    /// The scenario the worker computes on, and its epoch (bumped with each new worker).
    scenario: Scenario,
    epoch: u64,
    tx: Sender<Input>,
    /// When the current step was shown.
    shown: Instant,
    /// Where exports go (absolute).
    dir: PathBuf,
}

impl Session {
    /// Update the tour and carry out its commands; returns whether to redraw.
    fn apply(&mut self, terminal: &mut DefaultTerminal, msg: TourMsg) -> io::Result<bool> {
        let effect = self.player.update(msg);
        let mut redraw = effect.redraw;
        if effect.step_changed {
            self.shown = Instant::now();
            if self.player.app.scenario != self.scenario {
                self.scenario = self.player.app.scenario.clone();
                self.epoch += 1;
                self.worker = spawn(&self.tx, self.scenario.clone(), self.epoch);
            }
        }
        for command in effect.commands {
            match command {
                Command::Export => {
                    let reply = export(&self.player.app, &self.dir);
                    redraw |= self.apply(terminal, TourMsg::Lab(reply))?;
                }
                Command::Suspend => {
                    suspend(terminal)?;
                    redraw = true;
                }
                other => self.worker.send(&other),
            }
        }
        Ok(redraw)
    }

    /// How long to wait for input: until the auto-advance is due, a tick while a long job
    /// shows its time left, or for ever.
    fn wait(&self) -> Option<Duration> {
        let tick = self.player.app.wants_tick().then_some(TICK);
        let auto = self
            .player
            .auto
            .filter(|_| !self.player.at_end() && !self.player.is_busy() && self.player.fits);
        let due = auto.map(|a| a.saturating_sub(self.shown.elapsed()));
        match (tick, due) {
            (Some(t), Some(d)) => Some(t.min(d)),
            (t, d) => t.or(d),
        }
    }
}

/// A worker on `scenario` whose replies go to `tx` tagged with `epoch`.
fn spawn(tx: &Sender<Input>, scenario: Scenario, epoch: u64) -> Worker {
    let tx = tx.clone();
    Worker::spawn(scenario, move |r| tx.send(Input::Worker(epoch, r)).is_ok())
}

fn event_loop(
    terminal: &mut DefaultTerminal,
    tour: Tour,
    auto: Option<Duration>,
    look: &Look,
    dir: PathBuf,
) -> io::Result<()> {
    let (tx, rx) = mpsc::channel::<Input>();
    forward_terminal(tx.clone(), Input::Terminal, Input::Broken)?;
    let player = TourApp::new(tour, auto);
    let scenario = player.app.scenario.clone();
    let mut session = Session {
        worker: spawn(&tx, scenario.clone(), 0),
        player,
        scenario,
        epoch: 0,
        tx,
        shown: Instant::now(),
        dir,
    };
    let size = terminal.size()?;
    session.player.set_size(size.width, size.height);
    let mut redraw = session.apply(terminal, TourMsg::Lab(Msg::Resize))?;
    while !session.player.should_quit() {
        if redraw {
            draw_with(terminal, |frame| view(&session.player, frame, look))?;
        }
        let first = match session.wait() {
            Some(timeout) => match rx.recv_timeout(timeout) {
                Ok(input) => Some(input),
                Err(RecvTimeoutError::Timeout) => None,
                Err(RecvTimeoutError::Disconnected) => break,
            },
            None => match rx.recv() {
                Ok(input) => Some(input),
                Err(_) => break,
            },
        };
        redraw = false;
        if first.is_none() {
            redraw |= session.apply(terminal, TourMsg::Lab(Msg::Tick))?;
        }
        for input in first.into_iter().chain(std::iter::from_fn(|| rx.try_recv().ok())) {
            let msg = match input {
                Input::Terminal(Event::Key(key)) => Msg::Key(key),
                Input::Terminal(Event::Resize(width, height)) => {
                    let fitted = session.player.fits;
                    session.player.set_size(width, height);
                    if session.player.fits && !fitted {
                        // Paused while too small: the step's time starts again.
                        session.shown = Instant::now();
                    }
                    Msg::Resize
                }
                Input::Terminal(_) => continue,
                Input::Worker(epoch, r) if epoch == session.epoch => Msg::Worker(r),
                Input::Worker(..) => continue,
                Input::Broken(e) => return Err(e),
            };
            redraw |= session.apply(terminal, TourMsg::Lab(msg))?;
            if session.player.should_quit() {
                return Ok(());
            }
        }
        if session.player.auto_due(session.shown.elapsed()) {
            redraw |= session.apply(terminal, TourMsg::Auto)?;
        }
    }
    Ok(())
}
