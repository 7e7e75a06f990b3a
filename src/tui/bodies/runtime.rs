//! The two-body scene in the lab's one event loop ([`crate::tui::event_loop`]): its state,
//! and a worker thread that solves the newest settings (older requests still queued are
//! skipped, a solve under way is given up when a newer request is made) on the bodies it
//! keeps ([`super::cache`]), so that the screen's thread never solves. The terminal is restored on every path
//! by the loop.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, mpsc};
use std::time::Duration;

use crossterm::event::{Event, KeyCode, KeyEventKind, KeyModifiers};
use ratatui::Frame;

use super::super::RunError;
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

/// The way to the worker: its requests, and the newest request's generation, which the
/// worker compares with the one it is answering to give up a stale solve.
struct Jobs {
    requests: mpsc::Sender<Request>,
    newest: Arc<AtomicU64>,
}

impl Jobs {
    /// Ask for `request`: from now on every older request is stale.
    fn send(&self, request: Request) -> Result<(), mpsc::SendError<Request>> {
        self.newest.store(request.0, Ordering::Release);
        self.requests.send(request)
    }
}

/// How long the scene must be quiet before the worker builds a level finer (four times the
/// work of the current one, and a factorisation cannot be interrupted: not while keys come in
/// a burst).
const QUIET: Duration = Duration::from_millis(300);

/// The worker: it takes the newest request queued and solves it on the bodies it keeps
/// ([`BodiesCache`]), giving the solve up as soon as a newer request is made (a stale
/// result is never sent), and sends the result to the loop; then, idle, it builds what the
/// next keys are likely to ask for until a request comes: the upper bodies of the next
/// ratios at once, both bodies a level finer after [`QUIET`]. It ends when either channel
/// closes.
fn spawn_worker(scenario: Scenario, tx: mpsc::Sender<Input>) -> std::io::Result<Jobs> {
    let (requests, rx) = mpsc::channel::<Request>();
    let newest = Arc::new(AtomicU64::new(0));
    let seen = newest.clone();
    std::thread::Builder::new()
        .name("riplab-bodies".into())
        .spawn(move || {
            let mut cache = BodiesCache::new(scenario);
            let mut next = rx.recv().ok();
            while let Some(mut job) = next.take() {
                // Only the newest request matters: the others are already stale.
                while let Ok(newer) = rx.try_recv() {
                    job = newer;
                }
                let (generation, settings) = job;
                let stale = || seen.load(Ordering::Acquire) != generation;
                let result = cache.solve(&settings, &stale);
                // A newer request is on its way: its answer replaces this one.
                if !stale() {
                    if tx.send(Input::Bodies(generation, Box::new(result))).is_err() {
                        return;
                    }
                    cache.prefetch_ratios(&settings, &stale);
                    next = match rx.recv_timeout(QUIET) {
                        Ok(request) => Some(request),
                        Err(mpsc::RecvTimeoutError::Timeout) => {
                            cache.prefetch_finer(&settings, &stale);
                            None
                        }
                        Err(mpsc::RecvTimeoutError::Disconnected) => return,
                    };
                }
                if next.is_none() {
                    next = rx.recv().ok();
                }
            }
        })?;
    Ok(Jobs { requests, newest })
}

/// The scene in the loop.
struct BodiesLab {
    app: BodiesApp,
    jobs: Jobs,
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
    use crate::tui::bodies_solve::{RATIOS, Settings};

    fn patch() -> Scenario {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/patch-two-blocks.toml");
        Scenario::load(Path::new(path)).unwrap()
    }

    /// The next answer of the worker: (its generation, its ratio).
    fn answer(rx: &mpsc::Receiver<Input>) -> (u64, (u32, u32)) {
        // A generous deadline, not a timing: the worker answers in well under a second.
        match rx.recv_timeout(Duration::from_secs(120)).expect("an answer") {
            Input::Bodies(generation, result) => (generation, result.expect("solved").settings.ratio),
            _ => panic!("only the worker sends"),
        }
    }

    /// The worker answers each request it takes with its generation, off the caller's
    /// thread; of requests queued while it works, it solves the newest.
    #[test]
    fn the_worker_answers_the_newest_request() {
        let scenario = patch();
        let settings = Settings::of(&scenario, InterfaceMethod::Nts).unwrap();
        let (tx, rx) = mpsc::channel();
        let jobs = spawn_worker(scenario, tx).unwrap();
        for generation in 1..=3 {
            let ratio = RATIOS[generation as usize];
            jobs.send((generation, Settings { ratio, ..settings })).unwrap();
        }
        loop {
            let (generation, ratio) = answer(&rx);
            assert_eq!(ratio, RATIOS[generation as usize]);
            if generation == 3 {
                break;
            }
        }
    }

    /// Requests older than the newest are given up, whether still queued or taken: the
    /// worker's first answer is the newest request's, and a later request is answered after it.
    #[test]
    fn the_worker_never_answers_a_stale_request() {
        let scenario = patch();
        let settings = Settings::of(&scenario, InterfaceMethod::Nts).unwrap();
        let (tx, rx) = mpsc::channel();
        let jobs = spawn_worker(scenario, tx).unwrap();
        // Generation 3 is the newest before the worker sees any request.
        jobs.newest.store(3, Ordering::Release);
        for generation in 1..=3 {
            let ratio = RATIOS[generation as usize];
            jobs.requests
                .send((generation, Settings { ratio, ..settings }))
                .unwrap();
        }
        assert_eq!(answer(&rx), (3, RATIOS[3]));
        jobs.send((
            4,
            Settings {
                ratio: RATIOS[0],
                ..settings
            },
        ))
        .unwrap();
        assert_eq!(answer(&rx), (4, RATIOS[0]));
    }
}
