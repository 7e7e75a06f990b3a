//! The guided tour: every tour file is valid and every step solves; each step of the embedded
//! tour as an insta snapshot (plain text, 100×30); the keys that move between steps (the
//! validation errors of bad tour files: [`super::tour_validation`]).

use std::path::{Path, PathBuf};
use std::time::Duration;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

use riplab::tui::app::{Command, Compare, Msg, Scene};
use riplab::tui::engine::Engine;
use riplab::tui::settle::{carry_out, settle};
use riplab::tui::tour::{Tour, TourApp, TourMsg, auto_interval};

fn key(code: KeyCode) -> TourMsg {
    TourMsg::Lab(Msg::Key(KeyEvent::new(code, KeyModifiers::NONE)))
}

fn ch(c: char) -> TourMsg {
    key(KeyCode::Char(c))
}

/// The notice the tour shows now: the two-body scene's on a two-body step, the lab's else.
fn said(p: &TourApp) -> String {
    let notice = p
        .bodies
        .as_ref()
        .map_or(p.app.notice.as_ref(), |b| b.notice.as_ref());
    notice.map(|n| n.text.clone()).unwrap_or_default()
}

const LOOK: riplab::tui::view::Look = riplab::tui::view::Look {
    theme: riplab::tui::theme::Theme { color: true },
    marker: ratatui::symbols::Marker::Braille,
};

/// Every tour file under `tours/`.
fn tour_files() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tours");
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files
}

// ---- every step is valid and solves ------------------------------------------------------

#[test]
fn every_tour_loads_and_every_step_solves() {
    let mut tours = vec![Tour::paper()];
    for file in tour_files() {
        tours.push(Tour::load(&file).unwrap_or_else(|e| panic!("{e}")));
    }
    assert!(tours.len() >= 2, "tours/paper.toml is there");
    // A step's scenario file is embedded too (tour/embedded.rs): the same scenario, read
    // from another source.
    let unsourced = |tour: &Tour| {
        let mut steps = tour.steps.clone();
        for s in steps.iter_mut().filter_map(|s| s.scenario.as_mut()) {
            std::sync::Arc::make_mut(s).source.clear();
        }
        steps
    };
    assert_eq!(
        unsourced(&tours[1]),
        unsourced(&tours[0]),
        "the embedded tour is tours/paper.toml"
    );
    // A tour whose steps are one already solved (tours/paper.toml's, the embedded tour's) is
    // not solved again.
    let mut solved = Vec::new();
    for tour in &tours {
        if solved.contains(&unsourced(tour)) {
            continue;
        }
        solved.push(unsourced(tour));
        for (i, step) in tour.steps.iter().enumerate() {
            let what = format!("{}: step {} `{}`", tour.source, i + 1, step.title);
            if let Some(mut bodies) = tour.bodies(i) {
                riplab::tui::bodies::settle_bodies(&mut bodies, &[]).unwrap();
                assert!(bodies.error.is_none(), "{what}: {:?}", bodies.error);
                assert!(bodies.settled(), "{what}: not solved");
                continue;
            }
            let mut app = tour.app(i);
            app.show_timing = false;
            settle(&mut app, &mut Engine::new(tour.scenario_of(i).clone()));
            assert!(app.error.is_none(), "{what}: {:?}", app.error);
            if app.scene.needs_solution() {
                let solved = app.current().unwrap_or_else(|| panic!("{what}: not solved"));
                assert!(solved.solution.newton.converged, "{what}: not converged");
            }
            assert!(
                app.infsup.values().all(|r| r.is_ok()),
                "{what}: an inf-sup estimate failed"
            );
            assert_eq!(app.infsup_pending(), 0);
        }
    }
}

#[test]
fn the_paper_tour_tells_the_story_in_order() {
    let tour = Tour::paper();
    let settings: Vec<(Option<u32>, Option<f64>, Option<Scene>)> =
        tour.steps.iter().map(|s| (s.level, s.epsilon, s.scene)).collect();
    // M1 at 32 and 128 elements, refinement, ε → 0, the inf-sup scene, then M3 and M4.
    let levels: Vec<u32> = tour.steps.iter().filter_map(|s| s.level).collect();
    assert!(levels.starts_with(&[0, 0, 1]), "{settings:?}");
    assert!(
        tour.steps
            .iter()
            .any(|s| s.epsilon == Some(0.0) && s.level == Some(4))
    );
    assert!(
        tour.steps
            .iter()
            .any(|s| s.scene == Some(Scene::InfSup) && s.all_levels)
    );
    let schemes: Vec<String> = (0..tour.steps.len())
        .map(|i| {
            let app = tour.app(i);
            riplab::scheme::Scheme::new(app.settings.element, app.settings.rule)
                .name()
                .unwrap_or("-")
                .to_string()
        })
        .collect();
    let m3 = schemes.iter().position(|s| s == "M3").unwrap();
    let m4 = schemes.iter().position(|s| s == "M4").unwrap();
    assert!(m3 < m4 && schemes[..m3].iter().all(|s| s == "M1"), "{schemes:?}");
}

// ---- snapshots -----------------------------------------------------------------------------

#[test]
fn every_step_of_the_paper_tour_100x30() {
    let tour = Tour::paper();
    for i in 0..tour.steps.len() {
        let text = &super::paper_frames()[i][1];
        assert!(text.contains(&format!("tour {}/{}", i + 1, tour.steps.len())));
        let first = tour.steps[i].caption.lines().next().unwrap();
        assert!(
            text.contains(first.trim_end()),
            "step {} caption missing:\n{text}",
            i + 1
        );
        if let Some(bodies) = tour.bodies(i) {
            // The two-body scene's chart is not snapshotted: its header and its status line.
            let header = format!(" riplab · {} · two bodies · ", bodies.scenario.name);
            assert!(
                text.lines().any(|l| l.starts_with(&header)),
                "step {}:\n{text}",
                i + 1
            );
            assert!(text.contains("patch test "), "step {}:\n{text}", i + 1);
            continue;
        }
        if tour.steps[i].scene == Some(Scene::Convergence) {
            // Measured run times place the curves: no snapshot, but every method is drawn.
            for entry in ["P⠒ penalty p̄", "A⠒ alm p̄", "N⠒ nitsche p̄", "E⠒ exact p̄"] {
                assert!(text.contains(entry), "step {}: `{entry}` in\n{text}", i + 1);
            }
            continue;
        }
        snap!(format!("tour__paper_step{:02}_100x30", i + 1), text);
    }
}

/// The tour compares the methods on one chart, each method's error of p̄ against
/// its run time, on the same scheme and levels; the ALM's errors are the exact method's and
/// the penalty's (at ε = 1e-3) stay at its ε term, as the caption says.
#[test]
fn the_tour_compares_the_methods() {
    let tour = Tour::paper();
    let i = tour
        .steps
        .iter()
        .position(|s| s.scene == Some(Scene::Convergence) && s.compare == Compare::Methods)
        .expect("a step compares the methods");
    let mut app = tour.app(i);
    settle(&mut app, &mut Engine::new(tour.scenario_of(i).clone()));
    let key = app.study_key();
    let Some(Ok(study)) = app.studies.get(&key) else {
        panic!("the study of the methods: {:?}", app.studies.get(&key));
    };
    let pbar = |name: &str| -> Vec<f64> {
        study
            .rows
            .iter()
            .filter(|r| r.method.method == name)
            .map(|r| r.errors.expect("a result").pbar)
            .collect()
    };
    let (penalty, alm, exact) = (pbar("penalty"), pbar("alm"), pbar("exact"));
    assert_eq!(exact.len(), key.max_level as usize + 1);
    for (a, e) in alm.iter().zip(&exact) {
        assert!((a - e).abs() <= 1e-6 * e, "alm {alm:?} exact {exact:?}");
    }
    // The penalty's error does not fall with h: it is ε's, several times the exact one's.
    assert!(
        penalty.iter().zip(&exact).all(|(p, e)| *p > 3.0 * e),
        "{penalty:?} {exact:?}"
    );
    // The numbers the caption quotes (the finest level's, which the table shows at 80×24), to
    // three significant digits.
    let caption = &tour.steps[i].caption;
    for values in [&penalty, &exact] {
        if let Some(v) = values.last() {
            let decimals = (2 - v.log10().floor() as i32).max(0) as usize;
            let quoted = format!("{v:.decimals$}");
            assert!(
                caption.contains(&quoted),
                "{quoted} in\n{caption}\n{penalty:?} {exact:?}"
            );
        }
    }
}

#[test]
fn too_small_and_help() {
    let tour = Tour::paper();
    let small = riplab::tui::render_frame(60, 20, |frame| {
        riplab::tui::tour::view(
            &TourApp::new(tour.clone(), Some(Duration::from_secs(8))),
            frame,
            &LOOK,
        )
    });
    assert!(small.contains("the tour needs a bigger terminal"), "{small}");
    assert!(small.contains("at least 80×24"), "{small}");
    assert!(small.contains("auto-advance paused"), "{small}");
    assert!(small.lines().all(|l| l.chars().count() <= 60));
    let mut player = TourApp::new(tour, None);
    player.show_timing = false;
    player.app.show_timing = false;
    player.update(ch('?'));
    assert!(player.show_help);
    let text = riplab::tui::render_frame(100, 30, |frame| {
        riplab::tui::tour::view(
            &player,
            frame,
            &riplab::tui::view::Look {
                theme: riplab::tui::theme::Theme { color: true },
                marker: ratatui::symbols::Marker::Braille,
            },
        )
    });
    snap!("tour__help_100x30", text);
    // Esc closes the help without quitting; q then quits.
    player.update(key(KeyCode::Esc));
    assert!(!player.show_help && !player.should_quit());
    // The key that closes the help does nothing else (Space does not advance).
    player.update(ch('?'));
    player.update(ch(' '));
    assert!(!player.show_help);
    assert_eq!(player.index(), 0);
    player.update(ch('q'));
    player.update(ch('q'));
    assert!(player.should_quit());
}

// ---- keys ----------------------------------------------------------------------------------

#[test]
fn keys_advance_go_back_and_stay_in_bounds() {
    let tour = Tour::paper();
    let n = tour.steps.len();
    let mut player = TourApp::new(tour, None);
    assert_eq!(player.index(), 0);
    let back = player.update(key(KeyCode::Left));
    assert!(!back.step_changed, "no step before the first");
    assert_eq!(player.index(), 0);
    // And says so.
    assert!(said(&player).contains("is the first"), "{}", said(&player));
    let next = player.update(ch(' '));
    assert!(next.step_changed);
    assert_eq!(player.index(), 1);
    assert!(
        next.commands.iter().any(|c| matches!(c, Command::Solve(_))),
        "the new step asks for its solve"
    );
    player.update(key(KeyCode::Right));
    assert_eq!(player.index(), 2);
    player.update(key(KeyCode::Backspace));
    assert_eq!(player.index(), 1);
    player.update(key(KeyCode::End));
    assert_eq!(player.index(), n - 1);
    assert!(player.at_end());
    assert!(!player.update(ch(' ')).step_changed, "no step after the last");
    assert_eq!(player.index(), n - 1);
    assert!(
        said(&player).contains("is the last: q ends the tour"),
        "{}",
        said(&player)
    );
    player.update(key(KeyCode::Home));
    assert_eq!(player.index(), 0);
    assert!(!player.should_quit());
}

/// Esc never ends the tour (it goes back: closes the help, the lab's log or projector view);
/// `q` before the last step asks once — a second `q` quits, any other key goes on — and at
/// the last step quits at once.
#[test]
fn esc_never_quits_the_tour_and_q_asks_once_before_the_end() {
    let tour = Tour::paper();
    let mut player = TourApp::new(tour, None);
    player.update(ch('l'));
    assert!(player.app.overlays.show_log);
    player.update(key(KeyCode::Esc));
    assert!(!player.app.overlays.show_log && !player.should_quit());
    player.update(key(KeyCode::Esc));
    assert!(!player.should_quit(), "Esc Esc ends the tour");
    player.update(ch('q'));
    assert!(!player.should_quit(), "q at step 1 ends the tour at once");
    assert!(
        said(&player).contains("q again ends the tour"),
        "{}",
        said(&player)
    );
    player.update(ch(' '));
    assert_eq!(player.index(), 1, "the key after the question acts");
    player.update(ch('q'));
    player.update(ch('q'));
    assert!(player.should_quit());
    let mut player = TourApp::new(Tour::paper(), None);
    player.update(key(KeyCode::End));
    player.update(ch('q'));
    assert!(player.should_quit(), "q at the last step quits at once");
}

#[test]
fn each_step_sets_the_lab_and_coming_back_restores_it() {
    let tour = Tour::paper();
    let mut player = TourApp::new(tour.clone(), None);
    for i in 0..tour.steps.len() {
        let expected = tour.app(i);
        assert_eq!(player.app.settings, expected.settings, "step {}", i + 1);
        assert_eq!(player.app.scene, expected.scene);
        assert!(player.is_pristine());
        player.update(ch(' '));
    }
    // The lab's keys work inside a step; leaving and coming back restores the step.
    player.update(key(KeyCode::Home));
    player.update(ch(' '));
    let step = player.app.settings;
    player.update(ch('3'));
    player.update(ch(']'));
    assert_ne!(player.app.settings, step);
    assert!(!player.is_pristine());
    player.update(key(KeyCode::Left));
    player.update(key(KeyCode::Right));
    assert_eq!(player.app.settings, step);
}

#[test]
fn replies_to_a_left_step_are_ignored_and_results_are_kept() {
    let tour = Tour::paper();
    let mut player = TourApp::new(tour.clone(), None);
    player.show_timing = false;
    let first = player.update(TourMsg::Lab(Msg::Resize)).commands;
    let Some(Command::Solve(old)) = first.first().cloned() else {
        panic!("step 1 asks for a solve: {first:?}");
    };
    // Step 1 is solved, then step 2 is shown; the late reply of step 1 must not show there.
    let mut engine = Engine::new(tour.scenario_of(0).clone());
    let reply = engine.solve(&old, &|_| true, &mut |_| {});
    player.update(ch(' '));
    player.update(TourMsg::Lab(Msg::Worker(reply.clone())));
    assert!(
        player.app.current().is_none(),
        "a stale reply is not the new step's result"
    );
    // Back on step 1 a reply for it is shown, and kept for the next visit.
    let again = match player.update(key(KeyCode::Left)).commands.first() {
        Some(Command::Solve(r)) => *r,
        other => panic!("{other:?}"),
    };
    let reply = engine.solve(&again, &|_| true, &mut |_| {});
    player.update(TourMsg::Lab(Msg::Worker(reply)));
    assert!(player.app.current().is_some());
    player.update(ch(' '));
    player.update(key(KeyCode::Left));
    assert!(player.app.current().is_some(), "the kept solve is shown at once");
}

#[test]
fn auto_advances_when_due_and_stops_at_the_end() {
    let tour = Tour::paper();
    let n = tour.steps.len();
    let every = Duration::from_secs(5);
    let mut player = TourApp::new(tour.clone(), Some(every));
    settle(&mut player.app, &mut Engine::new(tour.scenario_of(0).clone()));
    assert!(!player.auto_due(Duration::from_secs(4)));
    assert!(player.auto_due(every));
    let effect = player.update(TourMsg::Auto);
    assert!(effect.step_changed);
    assert_eq!(player.index(), 1);
    // Not due while the step's numbers are being computed.
    assert!(player.is_busy());
    assert!(!player.auto_due(Duration::from_secs(60)));
    carry_out(
        &mut player.app,
        &mut Engine::new(tour.scenario_of(1).clone()),
        effect.commands,
    );
    assert!(player.auto_due(every));
    for _ in 0..2 * n {
        player.update(TourMsg::Auto);
    }
    assert_eq!(player.index(), n - 1);
    assert!(!player.auto_due(Duration::from_secs(3600)), "it stops at the end");
    assert!(!TourApp::new(tour, None).auto_due(Duration::from_secs(3600)));
    assert!(auto_interval(8.0).is_ok());
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e9] {
        assert!(auto_interval(bad).is_err(), "{bad}");
    }
}

/// Every step runs at 80×24: the lab above, below it the step's title wrapped (never cut)
/// and its whole caption — the lab yields the rows, nothing is a `↓` away.
#[test]
fn every_step_runs_at_80x24() {
    let tour = Tour::paper();
    let words = |text: &str| text.split_whitespace().collect::<Vec<_>>().join(" ");
    for i in 0..tour.steps.len() {
        let text = &super::paper_frames()[i][0];
        assert!(!text.contains("bigger terminal"), "step {}:\n{text}", i + 1);
        assert!(text.contains(&format!("tour {}/{}", i + 1, tour.steps.len())));
        // Columns: combining marks (the bar of p̄) take none.
        let columns = |l: &str| l.chars().filter(|c| !('\u{300}'..='\u{36f}').contains(c)).count();
        assert!(text.lines().all(|l| columns(l) <= 80), "{text}");
        assert!(
            !text.contains("↓ more"),
            "step {}: the caption scrolls:\n{text}",
            i + 1
        );
        // The whole caption, its words in order, at the bottom of the frame.
        let caption = words(&tour.steps[i].caption);
        assert!(
            words(text).ends_with(&caption),
            "step {} caption `{caption}`:\n{text}",
            i + 1
        );
        // The title: every word on screen, none cut.
        let head = text.lines().find(|l| l.contains(" tour ")).unwrap();
        assert!(!head.contains('…'), "step {}: {head}", i + 1);
        for word in tour.steps[i].title.split_whitespace() {
            assert!(text.contains(word), "step {} title word `{word}`:\n{text}", i + 1);
        }
        assert!(text.contains("riplab"), "{text}");
        if i == 2 {
            snap!("tour__paper_step03_80x24", text);
        }
    }
}

/// A caption longer than the rows left scrolls with ↓ and ↑, and the panel says there is
/// more (at 80×24: four lines of at most 96 characters whose long words wrap to 8 rows).
#[test]
fn long_captions_scroll() {
    let long = "abcdefghij".repeat(4);
    let line = |n: usize| format!("{n} {long} {long}");
    let caption = [line(1), line(2), line(3), line(4)].join("\n");
    let text = format!(
        "title = \"Long\"\n[[step]]\ntitle = \"A long title that wraps beside the keys of the panel\"\nlevel = 0\ncaption = \"\"\"\n{caption} the end\"\"\"\n[[step]]\ntitle = \"Two\"\nlevel = 0\ncaption = \"Short.\"\n"
    );
    let tour = Tour::parse(&text, "long.toml", None).unwrap();
    let mut player = TourApp::new(tour.clone(), None);
    player.show_timing = false;
    let commands = player.go_to(0);
    carry_out(
        &mut player.app,
        &mut Engine::new(tour.scenario_of(0).clone()),
        commands,
    );
    let draw =
        |player: &TourApp| riplab::tui::render_frame(80, 24, |f| riplab::tui::tour::view(player, f, &LOOK));
    let text = draw(&player);
    assert!(text.contains("↓ more"), "{text}");
    assert!(!text.contains("the end"), "`the end` not yet shown:\n{text}");
    for _ in 0..10 {
        player.update(key(KeyCode::Down));
    }
    let text = draw(&player);
    assert!(text.contains("the end"), "`the end` shown after ↓:\n{text}");
    assert!(text.contains("↑ more"), "{text}");
    // Leaving the step starts the next caption at its top.
    player.update(ch(' '));
    assert_eq!(player.caption_scroll, 0);
}

/// `--auto` pauses while the window is too small.
#[test]
fn auto_pauses_while_the_window_is_too_small() {
    let tour = Tour::paper();
    let every = Duration::from_secs(5);
    let mut player = TourApp::new(tour.clone(), Some(every));
    settle(&mut player.app, &mut Engine::new(tour.scenario_of(0).clone()));
    player.set_size(80, 24);
    assert!(player.auto_due(every));
    player.set_size(79, 40);
    assert!(!player.auto_due(Duration::from_secs(3600)));
    player.set_size(120, 23);
    assert!(!player.auto_due(Duration::from_secs(3600)));
    player.set_size(160, 50);
    assert!(player.auto_due(every));
}

/// The tour compares the penalty and the ALM at the same large ε on the same mesh,
/// and its ε = 0 step is the exact method.
#[test]
fn the_tour_compares_the_penalty_and_the_alm() {
    use riplab::contact::Method;
    let tour = Tour::paper();
    let apps: Vec<_> = (0..tour.steps.len()).map(|i| tour.app(i)).collect();
    let i = apps
        .iter()
        .position(|a| a.settings.method == Method::Penalty && a.settings.epsilon == 1e-3)
        .expect("a penalty step at ε = 1e-3");
    let (p, a) = (&apps[i].settings, &apps[i + 1].settings);
    assert!(matches!(a.method, Method::Alm { .. }), "{a:?}");
    assert_eq!(
        (p.level, p.element, p.rule, p.epsilon),
        (a.level, a.element, a.rule, a.epsilon)
    );
    assert!(
        tour.steps
            .iter()
            .zip(&apps)
            .any(|(s, a)| s.epsilon == Some(0.0) && a.settings.method == Method::Exact)
    );
}
