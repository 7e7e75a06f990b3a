//! The worker's scheduling: what a solve waits for and what runs beside it.

use super::*;

/// The displacement of a solution (a quarter of a second
/// at level 7), its stresses (seconds) and a work–precision study (seconds to a minute) run
/// beside the worker, which answers a solve meanwhile: a step back right after a step was
/// served only after the displacement (240–320 ms at level 7, BENCHMARKS.md), a key pressed in
/// the stress scene waited for the stresses, and a step after a Tab through the convergence
/// scene waited for its study (4 s at level 6).
#[test]
fn a_solve_waits_for_no_displacement_stresses_or_study() {
    use riplab::tui::app::StressRequest;
    use std::time::Duration;
    let paper = PaperWorker::spawn();
    let (worker, solve, next) = (&paper.worker, |g, l| paper.solve(g, l), || paper.next());
    let solved = |generation| loop {
        if let Response::Solved {
            generation: g,
            result,
        } = next()
            && g == generation
        {
            break result.expect("solved");
        }
    };
    // Level 1 built, then level 6, whose displacement (~75 ms) the worker starts as soon as it
    // replies; a solve sent while it runs.
    solve(1, 1);
    solved(1);
    solve(2, 6);
    let fine = solved(2);
    // Once the worker has handed the work on level 6 to its thread and waits for the next
    // request, a solve of level 1 is answered before the work, and the work's reply comes —
    // or, for the displacement, the newer level 1's: a job that has not started when a newer
    // one of its lane is submitted never runs (src/tui/job.rs), and on a loaded host the
    // level-1 solve's own displacement can come before level 6's thread starts (the test
    // waited ten minutes for a reply that was never to come).
    let answered_first =
        |generation, work: &str, of_work: &dyn Fn(&Response) -> bool, ends: &dyn Fn(&Response) -> bool| {
            assert!(
                worker.wait_for(Duration::from_secs(120), |a| a.waits()),
                "the worker waits"
            );
            solve(generation, 1);
            loop {
                match next() {
                    Response::Solved { generation: g, .. } if g == generation => break,
                    r if of_work(&r) => panic!("the solve waited for the {work}: {r:?}"),
                    _ => {}
                }
            }
            while !ends(&next()) {}
        };
    let displaced = |r: &Response| matches!(r, Response::Displaced { key } if key.level == 6);
    answered_first(3, "displacement", &displaced, &|r| {
        matches!(r, Response::Displaced { .. })
    });
    // The stresses of level 6, then a solve.
    worker.send(&Command::Stresses(StressRequest { solved: fine.clone() }));
    let stressed = |r: &Response| matches!(r, Response::Stresses { key } if key.level == 6);
    answered_first(4, "stresses", &stressed, &stressed);
    assert!(fine.stresses.get().is_some_and(|s| s.is_ok()));
    // The study of levels 0..=4 (M1–M4 against Q2's level 5), then a solve.
    let mut app = App::new(Scenario::paper());
    app.settings.level = 4;
    let study = app.study_key();
    worker.send(&Command::Study(StudyRequest {
        generation: 5,
        key: study.clone(),
    }));
    let studied = |r: &Response| matches!(r, Response::Study { key, .. } if *key == study);
    answered_first(6, "study", &studied, &studied);
}

/// Its preparation on a built mesh (another
/// factorisation with the layer along Γ_C last, 6–7 s at level 7) runs beside the worker and
/// says so; a solve sent meanwhile is answered at once, and the superseded Nitsche solve is
/// neither run nor reported. Before, the worker sat in the preparation with no progress shown
/// (12–14 s at level 7), and a step back waited for it.
#[test]
fn nitsches_preparation_runs_beside_the_worker() {
    use riplab::tui::app::Progress;
    let paper = PaperWorker::spawn();
    let nitsche = |generation| paper.solve_by_nitsche(generation, 5);
    let solved = |generation| loop {
        match paper.next() {
            Response::Solved {
                generation: g,
                result,
            } if g == generation => break result.expect("solved"),
            Response::Solved { generation: g, .. } | Response::Cancelled { generation: g } => {
                assert!(g > generation, "reply {g} came before {generation}'s");
            }
            _ => {}
        }
    };
    // Level 5 built for the penalty; then Nitsche's method on it.
    paper.solve(1, 5);
    solved(1);
    nitsche(2);
    loop {
        match paper.next() {
            Response::Progress {
                generation: 2,
                progress: Progress::Assembling { level, method, .. },
            } => {
                assert_eq!((level, method), (5, Some("nitsche")));
                break;
            }
            r @ (Response::Solved { .. } | Response::Cancelled { .. }) => {
                panic!("no progress before the reply: {r:?}")
            }
            _ => {}
        }
    }
    // A solve sent during the preparation is answered first; the Nitsche solve it supersedes
    // sends nothing (`solved` fails on a reply for generation 2).
    paper.solve(3, 1);
    solved(3);
    // Asked again, the Nitsche solve uses the prepared layer: the answer of a fresh engine.
    let key = nitsche(4);
    let prepared = solved(4);
    let fresh = match Engine::new(Scenario::paper()).solve(
        &riplab::tui::app::SolveRequest { generation: 1, key },
        &|_| true,
        &mut |_| {},
    ) {
        Response::Solved { result: Ok(s), .. } => s,
        other => panic!("{other:?}"),
    };
    assert!(prepared.solution.newton.converged);
    let (a, b) = (prepared.solution.load, fresh.solution.load);
    assert!((a - b).abs() <= 1e-9 * b.abs(), "{a} against {b}");
}

/// A Nitsche solve that finds its level being built in the background for the penalty waits
/// for that build, then for its own preparation, and is told of each (before, the status line
/// kept the build's "a moment more" through the whole preparation).
#[test]
fn a_nitsche_solve_is_told_of_the_build_then_of_its_preparation() {
    use riplab::tui::app::Progress;
    let paper = PaperWorker::spawn();
    paper.solve(1, 5);
    while !matches!(paper.next(), Response::Solved { generation: 1, .. }) {}
    // Waiting for the next request, the worker has begun building level 6 for the penalty
    // (about a second) in the background.
    let waits = paper
        .worker
        .wait_for(std::time::Duration::from_secs(120), |a| a.waits());
    assert!(waits, "the worker waits");
    paper.solve_by_nitsche(2, 6);
    let mut told = Vec::new();
    loop {
        match paper.next() {
            Response::Progress {
                generation: 2,
                progress: Progress::Assembling { level, method, .. },
            } => told.push((level, method)),
            Response::Solved {
                generation: 2,
                result,
            } => {
                assert!(result.is_ok());
                break;
            }
            _ => {}
        }
    }
    // The preparation is announced last; when the background build had begun (it has, unless
    // the memory could not hold level 6 beside level 5) and not yet ended, the build first.
    assert_eq!(told.last(), Some(&(6, Some("nitsche"))), "{told:?}");
    assert!(
        told.len() == 1 || told == [(6, None), (6, Some("nitsche"))],
        "{told:?}"
    );
}

/// An estimate that waits for its mesh says so with the build's time left
/// (M4 at level 7 builds Q2's level 7, 25–30 s), in the worker's replies and on the inf-sup
/// scene's status line.
#[test]
fn an_estimate_waiting_for_its_mesh_shows_the_build() {
    use riplab::tui::app::{InfSupKey, InfSupRequest, Progress};
    use riplab::tui::worker::Worker;
    use std::time::Duration;
    let (tx, rx) = std::sync::mpsc::channel();
    let worker = Worker::spawn(Scenario::paper(), move |r| tx.send(r).is_ok());
    let asked = InfSupKey {
        level: 3,
        element: Element::Q2,
        rule: Rule::Simpson,
    };
    worker.send(&Command::InfSup(InfSupRequest {
        generation: 0,
        key: asked,
    }));
    let first = rx
        .recv_timeout(Duration::from_secs(120))
        .expect("the worker answers");
    assert!(
        matches!(
            first,
            Response::InfSupProgress {
                key: k,
                progress: Progress::Assembling { level: 3, .. },
            } if k == asked
        ),
        "{first:?}"
    );
    let then = rx
        .recv_timeout(Duration::from_secs(120))
        .expect("the worker answers");
    assert!(
        matches!(then, Response::InfSup { key: k, result: Some(Ok(_)) } if k == asked),
        "{then:?}"
    );
    // The scene's status line.
    let mut app = App::new(Scenario::paper());
    app.settings.level = MAX_APP_LEVEL;
    app.update(key(KeyCode::Tab));
    assert_eq!(app.scene, Scene::InfSup);
    let m4 = InfSupKey {
        level: MAX_APP_LEVEL,
        element: Element::Q2,
        rule: Rule::Simpson,
    };
    assert!(app.is_estimating(&m4), "M4 asked for");
    let progress = Progress::Assembling {
        level: MAX_APP_LEVEL,
        unknowns: 4_195_328,
        started: std::time::Instant::now(),
        estimate_ms: 27_000.0,
        method: None,
    };
    assert!(
        app.update(Msg::Worker(Response::InfSupProgress { key: m4, progress }))
            .redraw
    );
    assert!(app.wants_tick());
    // Whole on an 80-column status line.
    let status = status_of(&frame(&app, 80, 24));
    assert!(
        status.contains("estimate(s) · building q2 level 7 · about 27 s left"),
        "{status}"
    );
    app.update(Msg::Worker(Response::InfSup {
        key: m4,
        result: Some(Err(LabError::EstimateEnded)),
    }));
    assert!(app.infsup_building().is_none() && !app.wants_tick());
}

/// A level whose build the memory guard refuses answers the solve that
/// asked for it with the guard's reason, through the build thread.
#[test]
fn a_refused_build_answers_its_solve_with_why() {
    use riplab::tui::app::{SolveKey, SolveRequest};
    use riplab::tui::worker::Worker;
    use std::time::Duration;
    // 256 × 128 level-0 cells: level 7 has about 10⁹ unknowns.
    let mut huge = Scenario::paper();
    let lines = |a: f64, b: f64, n: usize| (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect();
    let ((x0, x1), (y0, y1)) = (
        (huge.x_lines[0], *huge.x_lines.last().unwrap()),
        (huge.y_lines[0], *huge.y_lines.last().unwrap()),
    );
    (huge.x_lines, huge.y_lines) = (lines(x0, x1, 256), lines(y0, y1, 128));
    let (tx, rx) = std::sync::mpsc::channel();
    let worker = Worker::spawn(huge.clone(), move |r| tx.send(r).is_ok());
    worker.send(&Command::Solve(SolveRequest {
        generation: 1,
        key: SolveKey {
            level: MAX_APP_LEVEL,
            ..App::defaults(&huge)
        },
    }));
    loop {
        let r = rx
            .recv_timeout(Duration::from_secs(60))
            .expect("the worker answers");
        if let Response::Solved { generation, result } = r {
            assert_eq!(generation, 1);
            let Err(e) = result else {
                panic!("level {MAX_APP_LEVEL} of the huge grid was not refused")
            };
            assert!(
                matches!(
                    e,
                    LabError::Solve(SolveError::TooLarge {
                        workload: riplab::error::Workload::Level {
                            level: MAX_APP_LEVEL,
                            ..
                        },
                        ..
                    })
                ),
                "{e}"
            );
            // What the banner says, as before the reply was typed.
            let e = e.to_string();
            assert!(e.contains("needs about") && e.contains("coarser level"), "{e}");
            break;
        }
    }
}

/// Coming back to the solution shown while a solve of other settings is
/// under way (a level being built) shows that solution as settled, not "building", and
/// tells the worker the solve is superseded.
#[test]
fn coming_back_to_the_solution_shown_supersedes_the_solve_under_way() {
    use riplab::tui::app::Progress;
    let mut app = settled(1, Scene::Explore);
    assert!(!app.is_solving());
    let step = app.update(key(KeyCode::Right)).commands;
    let Some(Command::Solve(req)) = step.iter().find(|c| matches!(c, Command::Solve(_))) else {
        panic!("{step:?}")
    };
    app.update(Msg::Worker(Response::Progress {
        generation: req.generation,
        progress: Progress::Assembling {
            level: 2,
            unknowns: 1,
            started: std::time::Instant::now(),
            estimate_ms: 1e4,
            method: None,
        },
    }));
    assert!(app.is_solving() && app.wants_tick());
    let back = app.update(key(KeyCode::Left)).commands;
    assert!(app.current().is_some());
    assert!(!app.is_solving() && !app.wants_tick(), "still building on screen");
    assert!(
        back.iter()
            .any(|c| matches!(c, Command::Supersede(g) if *g > req.generation)),
        "{back:?}"
    );
    assert!(!frame(&app, 80, 24).contains("building"));
    // Its displacement is there (settled): nothing more to ask.
    assert!(
        !back.iter().any(|c| matches!(c, Command::Displace(_))),
        "{back:?}"
    );
}

/// The worker passes over the displacement of a solution whose solve a newer one followed
/// (its lane runs the newest only), so an app that comes back to such a solution asks for it:
/// before, the deformed view said "computing the displacement…" for good.
#[test]
fn coming_back_to_a_solution_without_its_displacement_asks_for_it() {
    let scenario = Scenario::paper();
    let mut engine = Engine::new(scenario.clone());
    let mut app = App::new(scenario);
    let request = app.update(Msg::Resize).commands;
    let Some(Command::Solve(req)) = request.first() else {
        panic!("{request:?}")
    };
    // The solution arrives; its displacement does not (passed over).
    let reply = engine.solve(req, &|_| true, &mut |_| {});
    app.update(Msg::Worker(reply));
    let shown = app.current().expect("shown").clone();
    assert!(shown.displacement.get().is_none());
    app.update(key(KeyCode::Right));
    let back = app.update(key(KeyCode::Left)).commands;
    let Some(Command::Displace(again)) = back.iter().find(|c| matches!(c, Command::Displace(_))) else {
        panic!("{back:?}")
    };
    assert!(Arc::ptr_eq(&again.solved, &shown));
    let mut commands = back.clone();
    commands.retain(|c| matches!(c, Command::Displace(_)));
    riplab::tui::settle::carry_out(&mut app, &mut engine, commands);
    assert!(shown.displacement.get().is_some());
    assert!(!frame(&app, 100, 30).contains("computing the displacement"));
}

/// A solve's reply carries the pressures at once; the displacement (a solve
/// with the whole factor, the larger part of a step to a built level) follows, and the
/// deformed view says so meanwhile.
#[test]
fn the_pressures_are_shown_before_the_displacement_is_computed() {
    let scenario = Scenario::paper();
    let mut engine = Engine::new(scenario.clone());
    let mut app = App::new(scenario);
    app.show_timing = false;
    let request = app.update(Msg::Resize).commands;
    let Some(Command::Solve(req)) = request.first() else {
        panic!("{request:?}")
    };
    let reply = engine.solve(req, &|_| true, &mut |_| {});
    let Response::Solved {
        result: Ok(solved), ..
    } = &reply
    else {
        panic!("{reply:?}")
    };
    let solved = solved.clone();
    assert!(solved.displacement.get().is_none(), "not computed with the solve");
    assert!(app.update(Msg::Worker(reply)).redraw);
    let first = render_app(&app, &LOOK, 100, 30);
    assert!(first.contains("computing the displacement…"), "{first}");
    assert!(first.contains("converged"), "{first}");
    assert!(app.update(Msg::Worker(Engine::displace(&solved))).redraw);
    let then = render_app(&app, &LOOK, 100, 30);
    assert!(!then.contains("computing the displacement"), "{then}");
    assert_eq!(
        solved.displacement.get().map(Vec::len),
        Some(2 * solved.disc.mesh().n_nodes())
    );
}
