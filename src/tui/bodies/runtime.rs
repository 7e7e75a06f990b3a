//! The two-body scene in the lab's one event loop ([`crate::tui::event_loop`]): its state,
//! and a worker thread that solves the newest settings (older requests still queued are
//! skipped, a solve under way is given up when a newer request is made) on the bodies it
//! keeps ([`super::cache`]), and estimates the inf-sup view's levels one by one (given up
//! between levels once the view wants another key or is left), so that the screen's thread
//! never solves. The solves come back through the loop's channel; the estimates through one of
//! their own, taken after each batch of inputs and every [`POLL`] while a job is out. The
//! terminal is restored on every path by the loop.

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
use super::infsup::{EstimateJob, EstimateKey, LevelEstimate, estimate_level};
use super::{BodiesApp, Request};
use crate::scenario::Scenario;

/// Run the two-body scene until the user quits, recording if asked, the terminal restored in
/// every case.
pub fn run(app: BodiesApp, look: Look, recording: Recording, mouse: bool) -> Result<(), RunError> {
    run_program(recording, mouse, |tx, size| {
        let (estimates_tx, estimates) = mpsc::channel();
        let jobs = spawn_worker(app.scenario.clone(), tx, estimates_tx)?;
        let mut lab = BodiesLab {
            app,
            jobs,
            estimates,
            look,
        };
        lab.app.too_small = size.width < MIN_SIZE.0 || size.height < MIN_SIZE.1;
        Ok(lab)
    })
}

/// What the worker is asked: a solve, or the inf-sup view's levels.
enum Job {
    Solve(Request),
    Estimate(EstimateJob),
}

/// One level estimated: its key, its level and the estimate.
type Estimated = (EstimateKey, u32, LevelEstimate);

/// The way to the worker: its jobs, and the newest solve's and estimate's generations, which
/// the worker compares with the ones it is answering to give up a stale job.
struct Jobs {
    requests: mpsc::Sender<Job>,
    newest: Arc<AtomicU64>,
    newest_estimate: Arc<AtomicU64>,
}

impl Jobs {
    /// Ask for `request`: from now on every older request is stale.
    fn send(&self, request: Request) -> Result<(), mpsc::SendError<Job>> {
        self.newest.store(request.0, Ordering::Release);
        self.requests.send(Job::Solve(request))
    }

    /// Ask for `job`: from now on every older estimate is stale.
    fn estimate(&self, job: EstimateJob) -> Result<(), mpsc::SendError<Job>> {
        self.newest_estimate.store(job.generation, Ordering::Release);
        self.requests.send(Job::Estimate(job))
    }
}

/// How long the scene must be quiet before the worker builds a level finer (four times the
/// work of the current one, and a factorisation cannot be interrupted: not while keys come in
/// a burst).
const QUIET: Duration = Duration::from_millis(300);

/// How often the loop looks for estimates while a job is out.
const POLL: Duration = Duration::from_millis(50);

/// The worker: it takes the newest solve and the newest estimate queued. The solve first, on
/// the bodies it keeps ([`BodiesCache`]), given up as soon as a newer request is made (a stale
/// result is never sent), its result sent to the loop; then, idle, it builds what the next
/// keys are likely to ask for until a job comes: the upper bodies of the next ratios at once,
/// both bodies a level finer after [`QUIET`]. An estimate level by level, each sent as it is
/// done, given up between levels as soon as a newer one is asked for (the view left or its key
/// changed); a level it estimated once is not estimated again (the scene keeps it). It ends
/// when either channel closes.
fn spawn_worker(
    scenario: Scenario,
    tx: mpsc::Sender<Input>,
    estimates: mpsc::Sender<Estimated>,
) -> std::io::Result<Jobs> {
    let (requests, rx) = mpsc::channel::<Job>();
    let newest = Arc::new(AtomicU64::new(0));
    let newest_estimate = Arc::new(AtomicU64::new(0));
    let (seen, seen_estimate) = (newest.clone(), newest_estimate.clone());
    std::thread::Builder::new()
        .name("riplab-bodies".into())
        .spawn(move || {
            let mut cache = BodiesCache::new(scenario.clone());
            let mut done: Vec<(EstimateKey, u32)> = Vec::new();
            let mut pending = Pending::default();
            let Ok(first) = rx.recv() else { return };
            pending.put(first);
            loop {
                // Only the newest of each kind matters: the others are already stale.
                while let Ok(newer) = rx.try_recv() {
                    pending.put(newer);
                }
                if let Some((generation, settings)) = pending.solve.take() {
                    let stale = || seen.load(Ordering::Acquire) != generation;
                    let result = cache.solve(&settings, &stale);
                    // A newer request is on its way: its answer replaces this one.
                    if !stale() {
                        if tx.send(Input::Bodies(generation, Box::new(result))).is_err() {
                            return;
                        }
                        cache.prefetch_ratios(&settings, &stale);
                        match rx.recv_timeout(QUIET) {
                            Ok(job) => pending.put(job),
                            Err(mpsc::RecvTimeoutError::Timeout) => cache.prefetch_finer(&settings, &stale),
                            Err(mpsc::RecvTimeoutError::Disconnected) => return,
                        }
                    }
                    continue;
                }
                if let Some(job) = pending.estimate.take() {
                    for &level in &job.levels {
                        if seen_estimate.load(Ordering::Acquire) != job.generation {
                            break;
                        }
                        if done.contains(&(job.key, level)) {
                            continue;
                        }
                        let result = estimate_level(&scenario, job.key, level);
                        done.push((job.key, level));
                        if estimates.send((job.key, level, result)).is_err() {
                            return;
                        }
                    }
                    continue;
                }
                match rx.recv() {
                    Ok(job) => pending.put(job),
                    Err(_) => return,
                }
            }
        })?;
    Ok(Jobs {
        requests,
        newest,
        newest_estimate,
    })
}

/// The newest solve and estimate the worker has taken and not started.
#[derive(Default)]
struct Pending {
    solve: Option<Request>,
    estimate: Option<EstimateJob>,
}

impl Pending {
    /// `job`, replacing the older of its kind.
    fn put(&mut self, job: Job) {
        match job {
            Job::Solve(r) => self.solve = Some(r),
            Job::Estimate(e) => self.estimate = Some(e),
        }
    }
}

/// The scene in the loop.
struct BodiesLab {
    app: BodiesApp,
    jobs: Jobs,
    estimates: mpsc::Receiver<Estimated>,
    look: Look,
}

impl BodiesLab {
    /// Ask for `request`, and for the estimates the view now wants (a job it no longer wants
    /// given up: its generation moves on).
    fn ask(&mut self, request: Option<Request>) {
        // A solve of older settings is given up, even when the view asks for none now.
        self.jobs.newest.store(self.app.generation, Ordering::Release);
        let estimate = self.app.infsup_request();
        self.jobs
            .newest_estimate
            .store(self.app.infsup.generation(), Ordering::Release);
        let sent = request.map_or(Ok(()), |r| self.jobs.send(r)).is_ok()
            && estimate.map_or(Ok(()), |e| self.jobs.estimate(e)).is_ok();
        if !sent {
            self.app.notice = Some(Notice::failure("the solver's thread has stopped: q quits"));
        }
    }

    /// Keep the estimates the worker has sent; whether there were any.
    fn take_estimates(&mut self) -> bool {
        let mut any = false;
        while let Ok((key, level, estimate)) = self.estimates.try_recv() {
            self.app.infsup.keep(key, level, estimate);
            any = true;
        }
        any
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
        Flow {
            redraw: self.take_estimates(),
            suspend: false,
        }
    }

    fn after_inputs(&mut self) -> Flow {
        self.tick()
    }

    /// [`POLL`] while estimates are out (they come on a channel of their own), else for ever.
    fn wait(&self) -> Option<Duration> {
        self.app.infsup.busy().then_some(POLL)
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

    /// A worker on `scenario`, its settings with `method`, and the channels the worker answers
    /// on: solves, then estimates.
    fn worker(
        scenario: &Scenario,
        method: InterfaceMethod,
    ) -> (Jobs, Settings, mpsc::Receiver<Input>, mpsc::Receiver<Estimated>) {
        let settings = Settings::of(scenario, method).unwrap();
        let (tx, rx) = mpsc::channel();
        let (estimates, got) = mpsc::channel();
        (
            spawn_worker(scenario.clone(), tx, estimates).unwrap(),
            settings,
            rx,
            got,
        )
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
        let (jobs, settings, rx, _got) = worker(&patch(), InterfaceMethod::Nts);
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
        let (jobs, settings, rx, _got) = worker(&patch(), InterfaceMethod::Nts);
        // Generation 3 is the newest before the worker sees any request.
        jobs.newest.store(3, Ordering::Release);
        for generation in 1..=3 {
            let ratio = RATIOS[generation as usize];
            jobs.requests
                .send(Job::Solve((generation, Settings { ratio, ..settings })))
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

    /// The inf-sup view's levels are estimated on the worker, each sent as it is done; a job
    /// made stale by a newer one (another ratio) is given up before its next level, and a
    /// level estimated once is not estimated again: asked twice, it is sent once.
    #[test]
    fn the_worker_estimates_level_by_level_and_gives_up_a_stale_key() {
        let scenario = patch();
        let (jobs, settings, _rx, got) = worker(&scenario, InterfaceMethod::Mortar);
        let key = |ratio| EstimateKey {
            ratio,
            ..EstimateKey::of(&settings, &scenario)
        };
        let job = |generation, ratio, levels: &[u32]| EstimateJob {
            generation,
            key: key(ratio),
            levels: levels.to_vec(),
        };
        // Job 1 (2:3) is stale before the worker takes it: job 2 (1:1) is the newest.
        jobs.newest_estimate.store(2, Ordering::Release);
        jobs.requests
            .send(Job::Estimate(job(1, (2, 3), &[0, 1])))
            .unwrap();
        jobs.requests
            .send(Job::Estimate(job(2, (1, 1), &[0, 1])))
            .unwrap();
        jobs.estimate(job(3, (1, 1), &[1, 0])).unwrap();
        let next = || got.recv_timeout(Duration::from_secs(120)).expect("an estimate");
        let mut seen = Vec::new();
        while seen.len() < 2 {
            let (k, level, estimate) = next();
            assert_eq!(k, key((1, 1)), "a stale key's level was sent");
            assert_eq!(estimate.expect("estimated").len(), k.spaces().len());
            seen.push(level);
        }
        seen.sort_unstable();
        assert_eq!(seen, [0, 1]);
        // Nothing more: each level of 1:1 once (job 3 asked again for both).
        jobs.estimate(job(4, (2, 3), &[0])).unwrap();
        assert_eq!(next().0, key((2, 3)));
    }
}
