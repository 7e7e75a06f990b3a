//! Smaller behaviours, long builds, warm starts and the engine's cache.

use super::*;

/// The too-small message wraps to fit; units on the axes; kernel spelled out; the
/// convergence scene says whose ε (render's levels and scenes: tests/cli/lab_commands.rs, help.rs).
#[test]
fn smaller_things() {
    let text = frame(&App::new(Scenario::paper()), 40, 12);
    assert!(text.lines().all(|l| l.chars().count() <= 40));
    for part in ["needs a bigger", "40×12", "80×24", "q quits"] {
        assert!(text.contains(part), "{part}:\n{text}");
    }
    let text = render_to_string(&Scenario::paper(), "explore", 80, 24, Some(0), None, None, None)
        .unwrap()
        .text;
    assert!(text.contains("p (units of E) against x (length)"), "{text}");
    assert!(text.contains("load P="), "{text}");
    let text = render_to_string(
        &Scenario::paper(),
        "explore",
        80,
        24,
        Some(1),
        Some(Element::Q1),
        Some(Rule::Gauss2),
        None,
    )
    .unwrap()
    .text;
    assert!(text.contains("kernel"), "M2's β_h is a kernel:\n{text}");
    let text = frame(&convergence_app(), 120, 40);
    assert!(text.contains("the scenario's ε"), "{text}");
}

/// At level 5 the raw p is drawn over p̄ (its cells keep their colour).
#[test]
fn raw_pressure_stays_visible_on_fine_meshes() {
    let app = settled(5, Scene::Explore);
    let buf = buffer(&app, &LOOK, 100, 30);
    let raw = buf
        .content
        .iter()
        .filter(|c| {
            c.fg == Color::Yellow
                && ('\u{2801}'..='\u{28ff}').contains(&c.symbol().chars().next().unwrap_or(' '))
        })
        .count();
    assert!(raw >= 40, "{raw} cells of p:\n{}", riplab::tui::buffer_text(&buf));
}

/// Beyond the defects: styles are locked for a few frames (a lost colour or highlight shows).
#[test]
fn styled_frames() {
    let app = settled(1, Scene::Explore);
    snap!(
        "tui__styles_explore_80x24",
        format!("{:?}", buffer(&app, &LOOK, 80, 24))
    );
    snap!(
        "tui__styles_explore_mono_80x24",
        format!("{:?}", buffer(&app, &MONO, 80, 24))
    );
    snap!(
        "tui__styles_infsup_mono_80x24",
        format!("{:?}", buffer(&infsup_app(), &MONO, 80, 24))
    );
}

/// Beyond the defects: a build expected to take over half a second shows the time left.
#[test]
fn long_builds_show_the_time_left() {
    use riplab::tui::app::Progress;
    let mut app = settled(0, Scene::Explore);
    let Some(Command::Solve(req)) = app.update(key(KeyCode::Right)).commands.first().cloned() else {
        panic!("a new level asks for a solve");
    };
    app.update(Msg::Worker(Response::Progress {
        generation: req.generation,
        progress: Progress::Assembling {
            level: 6,
            unknowns: 263_000,
            started: std::time::Instant::now(),
            estimate_ms: 2600.0,
            method: None,
        },
    }));
    assert!(app.wants_tick());
    let text = frame(&app, 100, 30);
    assert!(
        text.contains("⟳ building level 6 (263000 unknowns) · about 3 s left"),
        "{text}"
    );
    // Nitsche's preparation (its layer's factor, seconds at level 7) says so, whole on an
    // 80-column status line.
    app.update(Msg::Worker(Response::Progress {
        generation: req.generation,
        progress: Progress::Assembling {
            level: 7,
            unknowns: 1_049_088,
            started: std::time::Instant::now(),
            estimate_ms: 6600.0,
            method: Some("nitsche"),
        },
    }));
    let status = status_of(&frame(&app, 80, 24));
    assert!(
        status.contains("⟳ building level 7 for nitsche (1049088 unknowns) · about 7 s left"),
        "{status}"
    );
}

/// The lab's status line says what is known to be poor about the answer.
#[test]
fn the_status_line_shows_warnings() {
    let locking = crate::tui::tests::common::paper_with(&[("poisson", "poisson = 0.4999999")]);
    let mut app = App::new(locking.clone());
    app.show_timing = false;
    settle(&mut app, &mut Engine::new(locking));
    let text = frame(&app, 160, 40);
    let status = status_of(&text);
    assert!(status.contains("⚠") && status.contains("locks"), "{status}");
    // The paper's problem has none.
    let text = frame(&settled(1, Scene::Explore), 160, 40);
    assert!(!text.lines().last().unwrap().contains("⚠"));
}

/// A solve on another mesh or rule starts its Newton
/// iteration from the last solution's pressure carried to its points (shared between the edge
/// points for Nitsche's method), so a level step at a fine level costs one to three Newton
/// steps, not the 12 (penalty, Nitsche) or 21 (exact constraint) of a start from rest at level
/// 5, and gives the same solution: the same final active set solves the same linear system, so
/// the two agree to round-off.
#[test]
fn a_level_or_rule_step_starts_newton_from_the_last_pressure() {
    use riplab::contact::Method;
    use riplab::tui::app::{SolveKey, SolveRequest, Solved};
    let scenario = Scenario::paper();
    let settings = App::new(scenario.clone()).settings;
    let solve = |engine: &mut Engine, key: SolveKey| -> Arc<Solved> {
        match engine.solve(&SolveRequest { generation: 1, key }, &|_| true, &mut |_| {}) {
            Response::Solved { result: Ok(s), .. } => s,
            other => panic!("{other:?}"),
        }
    };
    let same = |a: &Solved, b: &Solved| {
        let (a, b) = (&a.solution, &b.solution);
        assert!(a.newton.converged && b.newton.converged);
        assert!((a.load - b.load).abs() <= 1e-10 * b.load, "{} {}", a.load, b.load);
        let top = b.pbar.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (x, y) in a.pbar.iter().zip(&b.pbar) {
            assert!((x - y).abs() <= 1e-10 * top, "{x} {y}");
        }
    };
    // The exact constraint has unique multipliers only with as many points as nodes: its other
    // rule is the trapezoid.
    for (method, rest, rule) in [
        (Method::Penalty, 12, Rule::Gauss2),
        (Method::Exact, 21, Rule::Trapezoid),
        (Method::Alm { tolerance: 1e-12 }.next(), 12, Rule::Trapezoid),
    ] {
        let at = |level, rule| SolveKey {
            level,
            rule,
            method,
            ..settings
        };
        let (coarse, fine) = (at(4, Rule::Gauss1), at(5, Rule::Gauss1));
        let cold = solve(&mut Engine::new(scenario.clone()), fine);
        assert_eq!(cold.solution.newton.iterations, rest, "{method:?} from rest");
        // Up from level 4, and back down from level 5.
        let mut engine = Engine::new(scenario.clone());
        solve(&mut engine, coarse);
        let up = solve(&mut engine, fine);
        assert!(
            up.solution.newton.iterations <= 3,
            "{method:?} up: {}",
            up.solution.newton.iterations
        );
        same(&up, &cold);
        let down = solve(&mut engine, coarse);
        assert!(down.solution.newton.iterations <= 3, "{method:?} down");
        same(&down, &solve(&mut Engine::new(scenario.clone()), coarse));
        // To another rule on the same mesh.
        let mut engine = Engine::new(scenario.clone());
        solve(&mut engine, fine);
        let other = solve(&mut engine, at(5, rule));
        let rest = solve(&mut Engine::new(scenario.clone()), at(5, rule));
        assert!(
            other.solution.newton.iterations < rest.solution.newton.iterations,
            "{method:?} rule: {} against {}",
            other.solution.newton.iterations,
            rest.solution.newton.iterations
        );
        same(&other, &rest);
    }
}

/// A finished build of `level` with `element` (1 ms, no preparation), for [`Engine::adopt`].
fn finished(scenario: &Scenario, level: u32, element: Element) -> riplab::tui::engine::Built {
    Ok(riplab::tui::engine::Finished {
        disc: Arc::new(scenario.discretize(level, element).unwrap()),
        build_ms: Some(1.0),
        prepare_ms: None,
    })
}

/// Meshes built for inf-sup estimates (the explore scene's table asks for
/// every coarser level) do not push the prefetched neighbours of the mesh in use out of the
/// cache: before, the fifth mesh evicted the least recently used one, a neighbour, and a step
/// to it had to build it again.
#[test]
fn meshes_built_for_estimates_do_not_evict_the_neighbours() {
    let scenario = Scenario::paper();
    let mut engine = Engine::new(scenario.clone());
    let mut app = App::new(scenario.clone());
    app.settings.level = 3;
    settle(&mut app, &mut engine);
    let built = |level| finished(&scenario, level, Element::Q1);
    engine.adopt(4, Element::Q1, built(4), Use::Background);
    engine.adopt(2, Element::Q1, built(2), Use::Background);
    for level in [0, 1] {
        engine.adopt(level, Element::Q1, built(level), Use::Estimate);
    }
    assert!(engine.has(3, Element::Q1), "the mesh in use");
    assert!(
        engine.has(4, Element::Q1) && engine.has(2, Element::Q1),
        "its neighbours"
    );
    assert_eq!(engine.next_prefetch(), None);
}

/// When idle, the engine names the next finer, then the next coarser level
/// of the mesh in use to build in the background, up to the lab's finest level and within its
/// memory budget; an adopted build is used without assembling again.
#[test]
fn the_engine_prefetches_the_neighbouring_levels() {
    use riplab::tui::app::{Progress, SolveRequest};
    let scenario = Scenario::paper();
    let mut engine = Engine::new(scenario.clone());
    assert_eq!(engine.next_prefetch(), None, "nothing in use yet");
    let mut app = App::new(scenario.clone());
    app.settings.level = 2;
    settle(&mut app, &mut engine);
    assert_eq!(engine.next_prefetch(), Some((3, Element::Q1)));
    let built = |level| finished(&scenario, level, Element::Q1);
    engine.adopt(3, Element::Q1, built(3), Use::Background);
    assert!(engine.has(3, Element::Q1));
    assert_eq!(engine.next_prefetch(), Some((1, Element::Q1)));
    engine.adopt(1, Element::Q1, built(1), Use::Background);
    assert_eq!(engine.next_prefetch(), None, "both neighbours built");
    // A build for an element no longer in use is dropped.
    let q2 = finished(&scenario, 1, Element::Q2);
    assert!(engine.adopt(1, Element::Q2, q2, Use::Background).is_some());
    assert!(!engine.has(1, Element::Q2));
    // The step to level 3 assembles nothing.
    let key = riplab::tui::app::SolveKey {
        level: 3,
        ..app.settings
    };
    let mut progress = Vec::new();
    let reply = engine.solve(&SolveRequest { generation: 1, key }, &|_| true, &mut |r| {
        progress.push(r)
    });
    assert!(matches!(reply, Response::Solved { result: Ok(_), .. }));
    assert!(
        !progress.iter().any(|r| matches!(
            r,
            Response::Progress {
                progress: Progress::Assembling { .. },
                ..
            }
        )),
        "{progress:?}"
    );
    // One an estimate waited for is kept within the budget, the mesh in use unchanged; one a
    // solve waited for becomes the mesh in use.
    let q2 = |level| finished(&scenario, level, Element::Q2);
    assert!(engine.adopt(2, Element::Q2, q2(2), Use::Estimate).is_some());
    assert!(engine.has(2, Element::Q2));
    assert_eq!(
        engine.next_prefetch(),
        Some((4, Element::Q1)),
        "still level 3 of Q1 in use"
    );
    assert!(engine.adopt(1, Element::Q2, q2(1), Use::Solve).is_some());
    assert_eq!(engine.next_prefetch(), Some((0, Element::Q2)));
    assert!(
        engine
            .adopt(
                0,
                Element::Q1,
                Err(riplab::error::SolveError::Cancelled),
                Use::Solve
            )
            .is_none()
    );
    // At the lab's finest level only the coarser neighbour; a failed build is not retried.
    // (One level-0 cell, so that level 6 is small.)
    let mut one_cell = scenario.clone();
    one_cell.x_lines = vec![0.0, *scenario.x_lines.last().unwrap()];
    one_cell.y_lines = vec![0.0, *scenario.y_lines.last().unwrap()];
    let mut app = App::new(one_cell.clone());
    (app.settings.level, app.settings.element, app.settings.rule) =
        (MAX_APP_LEVEL, Element::Q2, Rule::Simpson);
    let mut engine = Engine::new(one_cell);
    settle(&mut app, &mut engine);
    assert!(app.current().is_some());
    assert_eq!(engine.next_prefetch(), Some((MAX_APP_LEVEL - 1, Element::Q2)));
    let too_large = riplab::error::SolveError::OutOfMemory {
        step: "test",
        unknowns: 1,
    };
    engine.adopt(MAX_APP_LEVEL - 1, Element::Q2, Err(too_large), Use::Background);
    assert_eq!(engine.next_prefetch(), None, "not retried");
}

/// The lab keeps (and builds in the background) level 7 beside level 6 with
/// Q1 or P1, and Q2's level 6 beside its level 5, but not Q2's level 7 (as many unknowns as
/// Q1's level 8), whose estimate alone exceeds the budget.
#[test]
fn the_cache_budget_holds_level_7_of_q1_not_of_q2() {
    use riplab::tui::engine::CACHE_BYTES;
    let scenario = Scenario::paper();
    let engine = Engine::new(scenario.clone());
    let gib = |l, e| scenario.sizes(l, e).peak_bytes() as f64 / f64::from(1 << 30);
    let sizes = format!(
        "q1 6, 7: {:.2} {:.2} GiB; q2 5, 6, 7: {:.2} {:.2} {:.2} GiB; budget {} GiB",
        gib(6, Element::Q1),
        gib(7, Element::Q1),
        gib(5, Element::Q2),
        gib(6, Element::Q2),
        gib(7, Element::Q2),
        CACHE_BYTES >> 30
    );
    assert!(engine.fits(&[(6, Element::Q1), (7, Element::Q1)]), "{sizes}");
    assert!(engine.fits(&[(6, Element::P1), (7, Element::P1)]), "{sizes}");
    assert!(engine.fits(&[(5, Element::Q2), (6, Element::Q2)]), "{sizes}");
    assert!(!engine.fits(&[(7, Element::Q2)]), "{sizes}");
    assert!(!engine.fits(&[(7, Element::Q1), (7, Element::P1)]), "{sizes}");
}

/// End to end: a worker left idle after a solve builds the next level in
/// the background, and the step to it then assembles nothing (no "assembling" progress).
#[test]
fn an_idle_worker_builds_the_next_level_before_it_is_asked_for() {
    use riplab::tui::app::{Progress, SolveRequest};
    use riplab::tui::worker::Worker;
    use std::time::Duration;
    let (tx, rx) = std::sync::mpsc::channel();
    let worker = Worker::spawn(Scenario::paper(), move |r| tx.send(r).is_ok());
    let solve = |generation, level| {
        let key = riplab::tui::app::SolveKey {
            level,
            ..App::defaults(&Scenario::paper())
        };
        worker.send(&Command::Solve(SolveRequest { generation, key }));
        let mut seen = Vec::new();
        loop {
            let r = rx
                .recv_timeout(Duration::from_secs(120))
                .expect("the worker answers");
            if let Response::Solved { result, .. } = &r {
                assert!(result.is_ok(), "{result:?}");
                return seen;
            }
            seen.push(r);
        }
    };
    let assembling = |seen: &[Response]| {
        seen.iter().any(|r| {
            matches!(
                r,
                Response::Progress {
                    progress: Progress::Assembling { .. },
                    ..
                }
            )
        })
    };
    assert!(assembling(&solve(1, 2)), "level 2 is built on demand");
    // Idle again: levels 3 and 1 built in the background.
    assert!(
        worker.wait_for(Duration::from_secs(120), |a| a.idle()),
        "the worker went idle"
    );
    let seen = solve(2, 3);
    assert!(!assembling(&seen), "level 3 was built while idle: {seen:?}");
}

/// A worker on the paper's problem and the replies it sends: for the tests of the order in
/// which it answers.
pub(super) struct PaperWorker {
    pub(super) worker: riplab::tui::worker::Worker,
    pub(super) replies: std::sync::mpsc::Receiver<Response>,
}

impl PaperWorker {
    pub(super) fn spawn() -> Self {
        let (tx, replies) = std::sync::mpsc::channel();
        let worker = riplab::tui::worker::Worker::spawn(Scenario::paper(), move |r| tx.send(r).is_ok());
        PaperWorker { worker, replies }
    }

    /// Ask for a solve of the lab's default settings at `level`.
    pub(super) fn solve(&self, generation: u64, level: u32) {
        self.solve_by(generation, level, App::defaults(&Scenario::paper()).method);
    }

    /// Ask for a solve of the lab's default settings at `level` by Nitsche's method (θ = 1,
    /// γ₀ auto); its key.
    pub(super) fn solve_by_nitsche(&self, generation: u64, level: u32) -> riplab::tui::app::SolveKey {
        use riplab::contact::{Method, method::Gamma0};
        let nitsche = Method::Nitsche {
            theta: 1,
            gamma0: Gamma0::Auto,
        };
        self.solve_by(generation, level, nitsche)
    }

    pub(super) fn solve_by(
        &self,
        generation: u64,
        level: u32,
        method: riplab::contact::Method,
    ) -> riplab::tui::app::SolveKey {
        let key = riplab::tui::app::SolveKey {
            level,
            method,
            ..App::defaults(&Scenario::paper())
        };
        self.worker.send(&Command::Solve(riplab::tui::app::SolveRequest {
            generation,
            key,
        }));
        key
    }

    /// The next reply (ten minutes at most: a study against Q2's level 5 beside the other
    /// tests of a 2-core host took over two; a reply that never comes still fails).
    pub(super) fn next(&self) -> Response {
        self.replies
            .recv_timeout(std::time::Duration::from_secs(600))
            .expect("the worker answers")
    }
}

/// A level that is not built is built beside the worker, which keeps
/// answering: a step back to a built level during the build is served at once, and the
/// solve left behind is neither run nor reported (before, the worker sat in the build and
/// then reported the old solve cancelled).
#[test]
fn a_step_back_during_a_build_is_served_at_once() {
    use riplab::tui::app::Progress;
    let worker = PaperWorker::spawn();
    let (solve, next) = (|g, l| worker.solve(g, l), || worker.next());
    solve(1, 2);
    while !matches!(next(), Response::Solved { result: Ok(_), .. }) {}
    // Level 5 takes a few hundred ms to build; level 2 is built.
    solve(2, 5);
    loop {
        match next() {
            Response::Progress {
                generation: 2,
                progress: Progress::Assembling { level: 5, .. },
            } => break,
            r => assert!(!matches!(r, Response::Solved { .. }), "{r:?}"),
        }
    }
    solve(3, 2);
    loop {
        match next() {
            Response::Solved {
                generation: 3,
                result,
            } => {
                assert_eq!(result.map(|s| s.key.level).ok(), Some(2));
                break;
            }
            r @ (Response::Solved { generation: 2, .. } | Response::Cancelled { generation: 2 }) => {
                panic!("the step back waited for the build: {r:?}")
            }
            _ => {}
        }
    }
}

/// An inf-sup estimate (seconds at level 7: the H¹ form's factorisation and
/// two eigenproblems) runs beside the worker, which answers a solve meanwhile (before, the
/// solve waited for the estimate).
#[test]
fn a_solve_does_not_wait_for_an_estimate() {
    use riplab::tui::app::{InfSupKey, InfSupRequest};
    use std::time::Duration;
    let paper = PaperWorker::spawn();
    let (worker, solve, next) = (&paper.worker, |g, l| paper.solve(g, l), || paper.next());
    let settings = App::defaults(&Scenario::paper());
    // Level 5 built (its estimate takes ~100 ms: the H¹ factorisation), level 1 built.
    solve(1, 1);
    while !matches!(next(), Response::Solved { generation: 1, .. }) {}
    solve(2, 5);
    while !matches!(next(), Response::Solved { generation: 2, .. }) {}
    worker.send(&Command::InfSup(InfSupRequest {
        generation: 2,
        key: InfSupKey {
            level: 5,
            element: settings.element,
            rule: settings.rule,
        },
    }));
    // Once the worker has started the estimate and waits, a solve of the same generation.
    assert!(
        worker.wait_for(Duration::from_secs(120), |a| a.waits()),
        "the worker waits"
    );
    solve(2, 1);
    loop {
        match next() {
            Response::Solved {
                generation: 2,
                result,
            } => {
                assert_eq!(result.map(|s| s.key.level).ok(), Some(1));
                break;
            }
            r @ Response::InfSup { .. } => panic!("the solve waited for the estimate: {r:?}"),
            _ => {}
        }
    }
    while !matches!(
        next(),
        Response::InfSup {
            result: Some(Ok(_)),
            ..
        }
    ) {}
}
