//! The lab in the one event loop ([`super::event_loop::run_program`]): its app, its worker,
//! how it draws, where its exports go and where `T` writes a tour step.

use std::path::PathBuf;
use std::time::Duration;

use crossterm::event::Event;
use ratatui::Frame;

use super::RunError;
use super::app::{App, Command, ExportKind, Msg, Notice};
use super::event_loop::{Flow, Input, Program, Recording, TICK, run_program};
use super::export::export_shown;
use super::record::Chapter;
use super::tour::author::{LabSource, save_step};
use super::view::{Look, MIN_SIZE, view};
use super::worker::Worker;

/// Run the lab on `scenario` until the user quits, exporting into `dir` (absolute) and adding
/// tour steps as `source` says, recording if asked, with the mouse if `mouse`; the terminal
/// is restored in every case.
pub fn run(
    app: App,
    look: Look,
    dir: PathBuf,
    source: LabSource,
    recording: Recording,
    mouse: bool,
) -> Result<(), RunError> {
    run_program(recording, mouse, |tx, _| {
        let worker = Worker::spawn(app.scenario.clone(), move |r| {
            tx.send(Input::Worker(0, r)).is_ok()
        });
        Ok(Lab {
            app,
            worker,
            look,
            dir,
            source,
        })
    })
}

/// Whether a terminal of `(columns, rows)` is below the lab's [`MIN_SIZE`].
fn too_small((w, h): (u16, u16)) -> bool {
    w < MIN_SIZE.0 || h < MIN_SIZE.1
}

/// The lab in the loop: the app, its worker, how it draws and where exports go.
struct Lab {
    app: App,
    worker: Worker,
    look: Look,
    dir: PathBuf,
    /// Where `T` adds a tour step, and the lab's scenario file.
    source: LabSource,
}

impl Lab {
    /// Update the app and carry out its commands.
    fn apply(&mut self, msg: Msg) -> Flow {
        let effect = self.app.update(msg);
        let mut flow = Flow {
            redraw: effect.redraw,
            suspend: false,
        };
        for command in effect.commands {
            match command {
                Command::Export if self.app.export_kind == ExportKind::TourStep => {
                    let reply = save_step(&self.app, &self.source);
                    flow |= self.apply(Msg::Notice(reply));
                }
                Command::Export => {
                    let reply = export_shown(&self.app, &self.dir);
                    flow |= self.apply(reply);
                }
                Command::Suspend => flow.suspend = true,
                other => self.worker.send(&other),
            }
        }
        flow
    }
}

impl Program for Lab {
    fn start(&mut self) -> Flow {
        if let Ok(size) = crossterm::terminal::size() {
            self.app.overlays.too_small = too_small(size);
        }
        self.apply(Msg::Resize)
    }

    fn input(&mut self, input: Input) -> Flow {
        let msg = match input {
            Input::Terminal(Event::Key(key)) => Msg::Key(key),
            Input::Terminal(Event::Mouse(event)) => Msg::Mouse(event),
            Input::Terminal(Event::Resize(w, h)) => {
                self.app.overlays.too_small = too_small((w, h));
                Msg::Resize
            }
            Input::Terminal(_)
            | Input::Broken(_)
            | Input::RecordingFailed
            | Input::Signal
            | Input::Bodies(..) => {
                return Flow::default();
            }
            Input::Worker(_, r) => Msg::Worker(r),
        };
        self.apply(msg)
    }

    fn tick(&mut self) -> Flow {
        self.apply(Msg::Tick)
    }

    fn wait(&self) -> Option<Duration> {
        self.app.wants_tick().then_some(TICK)
    }

    fn should_quit(&self) -> bool {
        self.app.should_quit()
    }

    fn draw(&self, frame: &mut Frame) {
        view(&self.app, frame, &self.look);
    }

    fn chapter(&self) -> Option<Chapter> {
        Some(Chapter {
            step: None,
            scene: self.app.scene,
        })
    }

    fn notice(&mut self, notice: Notice) -> Flow {
        self.apply(Msg::Notice(notice))
    }
}
