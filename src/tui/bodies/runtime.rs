//! The two-body scene in the lab's one event loop ([`crate::tui::event_loop`]): its state,
//! and a worker thread that solves the newest settings (older requests still queued are
//! skipped) on the bodies it keeps ([`super::cache`]), so that the screen's thread never
//! solves. The terminal is restored on every path
//! by the loop.

use std::sync::mpsc;
use std::time::Duration;

use crossterm::event::{Event, KeyCode, KeyEventKind, KeyModifiers};
use ratatui::Frame;

use super::super::RunError;
use super::super::bodies_solve::Settings;
use super::super::event_loop::{Flow, Input, Program, Recording, run_program};
use super::super::protocol::Notice;
use super::super::record::Chapter;
use super::super::view::{Look, MIN_SIZE};
use super::cache::BodiesCache;
use super::{BodiesApp, Request};
use crate::scenario::Scenario;

/// Run the two-body scene until the user quits, recording if asked, the terminal restored in
/// every case.
pub fn run(app: BodiesApp, look: Look, recording: Recording, mouse: bool) -> Result<(), RunError> {
    run_program(recording, mouse, |tx, size| {
        let jobs = spawn_worker(app.scenario.clone(), tx)?;
        let mut lab = BodiesLab { app, jobs, look };
        lab.app.too_small = size.width < MIN_SIZE.0 || size.height < MIN_SIZE.1;
        Ok(lab)
    })
}

/// The worker: it takes the newest request queued, solves it and sends the result to the
/// loop; it ends when either channel closes.
fn spawn_worker(scenario: Scenario, tx: mpsc::Sender<Input>) -> std::io::Result<mpsc::Sender<Request>> {
    let (jobs, rx) = mpsc::channel::<(u64, Settings)>();
    std::thread::Builder::new()
        .name("riplab-bodies".into())
        .spawn(move || {
            let mut cache = BodiesCache::new(scenario);
            while let Ok(mut job) = rx.recv() {
                // Only the newest request matters: the others are already stale.
                while let Ok(newer) = rx.try_recv() {
                    job = newer;
                }
                let result = cache.solve(&job.1);
                if tx.send(Input::Bodies(job.0, Box::new(result))).is_err() {
                    return;
                }
            }
        })?;
    Ok(jobs)
}

/// The scene in the loop.
struct BodiesLab {
    app: BodiesApp,
    jobs: mpsc::Sender<Request>,
    look: Look,
}

impl BodiesLab {
    fn ask(&mut self, request: Option<Request>) {
        if let Some(request) = request
            && self.jobs.send(request).is_err()
        {
            self.app.notice = Some(Notice::failure("the solver's thread has stopped: q quits"));
        }
    }
}

impl Program for BodiesLab {
    fn start(&mut self) -> Flow {
        let first = self.app.start();
        self.ask(Some(first));
        Flow {
            redraw: true,
            suspend: false,
        }
    }

    fn input(&mut self, input: Input) -> Flow {
        let redraw = match input {
            Input::Terminal(Event::Key(key))
                if key.modifiers.contains(KeyModifiers::CONTROL)
                    && matches!(key.code, KeyCode::Char('z' | 'Z'))
                    && key.kind != KeyEventKind::Release =>
            {
                return Flow {
                    redraw: true,
                    suspend: true,
                };
            }
            Input::Terminal(Event::Key(key)) => {
                let (redraw, request) = self.app.key(key);
                self.ask(request);
                redraw
            }
            Input::Terminal(Event::Resize(w, h)) => {
                self.app.too_small = w < MIN_SIZE.0 || h < MIN_SIZE.1;
                true
            }
            Input::Bodies(generation, result) => self.app.reply(generation, *result),
            _ => false,
        };
        Flow {
            redraw,
            suspend: false,
        }
    }

    fn tick(&mut self) -> Flow {
        Flow::default()
    }

    fn wait(&self) -> Option<Duration> {
        None
    }

    fn should_quit(&self) -> bool {
        self.app.quit
    }

    fn draw(&self, frame: &mut Frame) {
        super::view::view(&self.app, frame, &self.look);
    }

    fn chapter(&self) -> Option<Chapter> {
        None
    }

    fn notice(&mut self, notice: Notice) -> Flow {
        self.app.notice = Some(notice);
        Flow {
            redraw: true,
            suspend: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;
    use std::time::Duration;

    use super::*;
    use crate::contact::interface::InterfaceMethod;

    /// The worker answers each request it takes with its generation, off the caller's
    /// thread; of requests queued while it works, it solves the newest.
    #[test]
    fn the_worker_answers_the_newest_request() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/patch-two-blocks.toml");
        let scenario = Scenario::load(Path::new(path)).unwrap();
        let settings = Settings::of(&scenario, InterfaceMethod::Nts).unwrap();
        let (tx, rx) = mpsc::channel();
        let jobs = spawn_worker(scenario, tx).unwrap();
        for generation in 1..=3 {
            let ratio = super::super::super::bodies_solve::RATIOS[generation as usize];
            jobs.send((generation, Settings { ratio, ..settings })).unwrap();
        }
        // A generous deadline, not a timing: the loop waits for the newest answer.
        let deadline = Duration::from_secs(120);
        loop {
            match rx.recv_timeout(deadline).expect("an answer") {
                Input::Bodies(generation, result) => {
                    let solved = result.expect("solved");
                    assert_eq!(
                        solved.settings.ratio,
                        super::super::super::bodies_solve::RATIOS[generation as usize]
                    );
                    if generation == 3 {
                        break;
                    }
                }
                _ => panic!("only the worker sends"),
            }
        }
    }
}
