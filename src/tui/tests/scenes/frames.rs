//! Frames as snapshots, the numbers on screen, and the keys.

use super::*;

// ---- snapshots -------------------------------------------------------------------------

#[test]
fn explore_80x24() {
    let text = render_to_string(&Scenario::paper(), "explore", 80, 24, Some(1), None, None, None)
        .unwrap()
        .text;
    snap!("tui__explore_80x24", text);
}

#[test]
fn explore_120x40_with_overlays() {
    let mut app = settled(2, Scene::Explore);
    app.guides = riplab::tui::app::Guides::ALL;
    snap!("tui__explore_120x40", frame(&app, 120, 40));
}

#[test]
fn explore_m3_120x40() {
    let text = render_to_string(
        &Scenario::paper(),
        "explore",
        120,
        40,
        Some(2),
        Some(Element::Q1),
        Some(Rule::Trapezoid),
        None,
    )
    .unwrap()
    .text;
    snap!("tui__explore_m3_120x40", text);
}

pub(super) fn infsup_app() -> App {
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.scene = Scene::InfSup;
    app.settings.level = 2;
    app.all_levels = true;
    settle(&mut app, &mut Engine::new(Scenario::paper()));
    app
}

#[test]
fn infsup_80x24() {
    snap!("tui__infsup_80x24", frame(&infsup_app(), 80, 24));
}

#[test]
fn infsup_120x40() {
    snap!("tui__infsup_120x40", frame(&infsup_app(), 120, 40));
}

#[test]
fn mesh_80x24() {
    let text = render_to_string(&Scenario::paper(), "mesh", 80, 24, Some(0), None, None, None)
        .unwrap()
        .text;
    snap!("tui__mesh_80x24", text);
}

#[test]
fn mesh_120x40() {
    snap!("tui__mesh_120x40", frame(&settled(2, Scene::Mesh), 120, 40));
}

#[test]
fn help_overlay_80x24() {
    let mut app = settled(0, Scene::Explore);
    app.update(ch('?'));
    assert!(app.show_help);
    snap!("tui__help_80x24", frame(&app, 80, 24));
}

#[test]
fn too_small_60x20() {
    let app = App::new(Scenario::paper());
    snap!("tui__too_small_60x20", frame(&app, 60, 20));
}

#[test]
fn error_banner_keeps_the_last_result() {
    let mut app = settled(0, Scene::Explore);
    let effect = app.update(key(KeyCode::Right));
    let Some(Command::Solve(req)) = effect.commands.first() else {
        panic!("a new level asks for a solve: {effect:?}");
    };
    app.update(Msg::Worker(Response::Solved {
        generation: req.generation,
        result: Err(SolveError::Factorization {
            matrix: "stiffness",
            pivot: 12,
        }
        .into()),
    }));
    assert!(app.error.is_some());
    assert!(app.solved.is_some(), "the level-0 result stays on screen");
    snap!("tui__error_banner_80x24", frame(&app, 80, 24));
}

/// A refusal longer than two lines (Nitsche's γ₀ below its threshold, seen on hertz-block)
/// is shown whole at 80×24: the banner grows to hold it, up to five rows.
#[test]
fn a_long_error_is_shown_whole() {
    let mut app = settled(0, Scene::Explore);
    let effect = app.update(key(KeyCode::Right));
    let Some(Command::Solve(req)) = effect.commands.first() else {
        panic!("a new level asks for a solve: {effect:?}");
    };
    let refusal = riplab::error::InputFault::Unstable {
        gamma0: 100.0,
        theta: 1.0,
        threshold: Some(1245.043),
    };
    app.update(Msg::Worker(Response::Solved {
        generation: req.generation,
        result: Err(SolveError::from(refusal).into()),
    }));
    let text = frame(&app, 80, 24);
    let shown: String = text.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(shown.contains("choose a larger γ₀ or θ = −1"), "{text}");
    assert!(shown.contains("(Chouly and Hild's condition)"), "{text}");
    assert_eq!(text.lines().count(), 24);
    // The status line does not go on saying the last solve converged: it says these settings
    // have no result and whose result the charts keep.
    let status = status_of(&text);
    assert!(!status.contains("converged"), "{status}");
    assert!(
        status.contains("✗ no result for these settings · shown: the last solve (level 0"),
        "{status}"
    );
}

// ---- numbers on screen -----------------------------------------------------------------

#[test]
fn status_shows_the_solvers_load() {
    let mut s = Scenario::paper();
    s.level = 1;
    let (_, sol) = riplab::solve::solve_scenario(&s).unwrap();
    let text = render_to_string(&Scenario::paper(), "explore", 80, 24, Some(1), None, None, None)
        .unwrap()
        .text;
    let load = format!("P={}", sig5(sol.load));
    assert!(text.contains(&load), "{load} not in\n{text}");
    assert!(text.contains(&format!("{} Newton steps", sol.newton.iterations)));
}

/// Five significant digits, as the status line prints them.
fn sig5(x: f64) -> String {
    let e = x.abs().log10().floor() as i32;
    let decimals = (4 - e).max(0) as usize;
    let s = format!("{x:.decimals$}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[test]
fn unknown_scene_lists_the_scenes() {
    let err = render_to_string(&Scenario::paper(), "plot", 80, 24, None, None, None, None)
        .unwrap_err()
        .to_string();
    assert!(err.contains("explore, infsup, mesh"), "{err}");
    assert!(render_to_string(&Scenario::paper(), "mesh", 80, 24, Some(9), None, None, None).is_err());
}

// ---- keys ------------------------------------------------------------------------------

#[test]
fn level_keys_stay_in_bounds() {
    let mut app = App::new(Scenario::paper());
    app.update(key(KeyCode::Left));
    app.update(ch('['));
    assert_eq!(app.settings.level, 0);
    for _ in 0..10 {
        app.update(key(KeyCode::Right));
    }
    assert_eq!(app.settings.level, MAX_APP_LEVEL);
    app.update(ch('['));
    assert_eq!(app.settings.level, MAX_APP_LEVEL - 1);
    app.update(ch(']'));
    assert_eq!(app.settings.level, MAX_APP_LEVEL);
}

#[test]
fn rule_cycles_and_presets_set_element_and_rule() {
    let mut app = App::new(Scenario::paper());
    let mut seen = vec![app.settings.rule];
    for _ in 0..4 {
        app.update(ch('r'));
        seen.push(app.settings.rule);
    }
    assert_eq!(
        seen,
        [
            Rule::Gauss1,
            Rule::Gauss2,
            Rule::Trapezoid,
            Rule::Simpson,
            Rule::Gauss1
        ]
    );
    for (c, element, rule) in [
        ('4', Element::Q2, Rule::Simpson),
        ('3', Element::Q1, Rule::Trapezoid),
        ('2', Element::Q1, Rule::Gauss2),
        ('1', Element::Q1, Rule::Gauss1),
    ] {
        app.update(ch(c));
        assert_eq!(
            (app.settings.element, app.settings.rule),
            (element, rule),
            "key {c}"
        );
    }
    app.update(ch('e'));
    assert_eq!(app.settings.element, Element::Q2);
    app.update(ch('e'));
    app.update(ch('e'));
    assert_eq!(app.settings.element, Element::Q1);
}

#[test]
fn epsilon_moves_by_exact_decades_within_bounds() {
    let mut app = App::new(Scenario::paper());
    app.update(ch('+'));
    assert_eq!(app.settings.epsilon, 1e-5);
    app.update(ch('-'));
    app.update(ch('-'));
    assert_eq!(app.settings.epsilon, 1e-7);
    for _ in 0..40 {
        app.update(ch('-'));
    }
    assert_eq!(app.settings.epsilon, 1e-14);
    for _ in 0..40 {
        app.update(ch('+'));
    }
    assert_eq!(app.settings.epsilon, 1e2);
}

#[test]
fn depth_steps_by_a_tenth_within_bounds() {
    let mut app = App::new(Scenario::paper());
    app.update(ch('D'));
    assert_eq!(app.settings.depth, 0.9);
    app.update(ch('d'));
    app.update(ch('d'));
    assert_eq!(app.settings.depth, 0.7);
    for _ in 0..20 {
        app.update(ch('d'));
    }
    assert_eq!(app.settings.depth, 0.0);
    for _ in 0..40 {
        app.update(ch('D'));
    }
    assert_eq!(app.settings.depth, app.max_depth());
}

#[test]
fn tab_cycles_scenes_both_ways() {
    let mut app = App::new(Scenario::paper());
    let mut seen = vec![app.scene];
    for _ in 0..5 {
        app.update(key(KeyCode::Tab));
        seen.push(app.scene);
    }
    assert_eq!(
        seen,
        [
            Scene::Explore,
            Scene::InfSup,
            Scene::Mesh,
            Scene::Convergence,
            Scene::Stress,
            Scene::Explore
        ]
    );
    app.update(key(KeyCode::BackTab));
    assert_eq!(app.scene, Scene::Stress);
}

/// Esc goes back — it closes the help, the log, the projector view — and never quits, so
/// that `l` Esc Esc (a reflex) does not end a lesson; `q` and Ctrl-C quit.
#[test]
fn esc_goes_back_and_only_q_quits() {
    let mut app = App::new(Scenario::paper());
    for open in ['?', 'l', 'f'] {
        app.update(ch(open));
        app.update(key(KeyCode::Esc));
        let o = &app.overlays;
        assert!(
            !app.show_help && !o.show_log && !o.projector && !app.should_quit(),
            "{open} then Esc closes it"
        );
        app.update(key(KeyCode::Esc));
        assert!(!app.should_quit(), "{open} Esc Esc quits");
        let said = app.notice.as_ref().map(|n| n.text.clone()).unwrap_or_default();
        assert!(said.contains("q quits"), "{said}");
    }

    let mut app = App::new(Scenario::paper());
    app.update(ch('q'));
    assert!(app.should_quit());

    let mut app = App::new(Scenario::paper());
    app.update(Msg::Key(KeyEvent::new(KeyCode::Char('c'), KeyModifiers::CONTROL)));
    assert!(app.should_quit());
}

#[test]
fn overlays_toggle() {
    let mut app = App::new(Scenario::paper());
    // Each overlay on its own: g, h, o; M refused without friction (the notice says why).
    for (key, on) in [('g', true), ('h', true), ('o', true), ('M', false)] {
        app.update(ch(key));
        assert_eq!(
            app.notice.as_ref().unwrap().text.contains("no Mindlin"),
            !on,
            "{key}"
        );
    }
    let g = riplab::tui::app::Guides {
        gap: true,
        hertz: true,
        circle: true,
        mindlin: false,
    };
    assert_eq!(app.guides, g);
    app.update(ch('g'));
    assert!(!app.guides.gap && app.guides.hertz && app.guides.circle);
}

#[test]
fn scenes_request_only_what_they_show() {
    let mut app = App::new(Scenario::paper());
    let first = app.update(Msg::Resize).commands;
    assert!(matches!(first[0], Command::Solve(_)));
    assert!(first.iter().any(|c| matches!(c, Command::InfSup(_))));
    // Nothing is asked twice while in flight.
    assert!(app.update(Msg::Resize).commands.is_empty());

    let mut app = App::new(Scenario::paper());
    app.scene = Scene::InfSup;
    let cmds = app.update(Msg::Resize).commands;
    assert_eq!(cmds.len(), 4 * 5, "M1–M4 at levels 0 to 4, no solve: {cmds:?}");
    assert!(cmds.iter().all(|c| matches!(c, Command::InfSup(_))));

    let mut app = App::new(Scenario::paper());
    app.scene = Scene::Mesh;
    let cmds = app.update(Msg::Resize).commands;
    assert_eq!(cmds.len(), 1, "a solve, no inf-sup: {cmds:?}");
}

#[test]
fn newer_settings_supersede_older_solves() {
    let mut app = App::new(Scenario::paper());
    let old = match app.update(Msg::Resize).commands[0] {
        Command::Solve(r) => r,
        ref c => panic!("{c:?}"),
    };
    let new = match app.update(key(KeyCode::Right)).commands[0] {
        Command::Solve(r) => r,
        ref c => panic!("{c:?}"),
    };
    assert!(new.generation > old.generation);
    // The old solve's reply is ignored: it was superseded.
    let mut engine = Engine::new(Scenario::paper());
    let reply = engine.solve(&old, &|_| true, &mut |_| {});
    assert!(!app.update(Msg::Worker(reply)).redraw);
    assert!(app.solved.is_none());
    // A solve that sees a newer generation stops with Cancelled.
    let cancelled = engine.solve(&new, &|_| false, &mut |_| {});
    assert!(matches!(cancelled, Response::Cancelled { .. }));
    // A cancelled solve that is still wanted is asked for again.
    let again = app.update(Msg::Worker(cancelled)).commands;
    assert!(
        matches!(again[..], [Command::Solve(r), ..] if r.key == new.key),
        "{again:?}"
    );
}

#[test]
fn export_needs_a_solution() {
    let mut app = App::new(Scenario::paper());
    assert!(app.update(ch('s')).commands.iter().all(|c| *c != Command::Export));
    assert!(app.notice.is_some());
    let mut app = settled(0, Scene::Explore);
    assert!(app.update(ch('s')).commands.contains(&Command::Export));
}

#[test]
fn export_never_overwrites() {
    let app = settled(0, Scene::Explore);
    let dir = std::env::temp_dir().join(format!("riplab-tui-export-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let solved = app.current().unwrap();
    let a = riplab::tui::export::export_csv(&app.scenario, solved, &dir).unwrap();
    let b = riplab::tui::export::export_csv(&app.scenario, solved, &dir).unwrap();
    assert_ne!(a, b);
    let text = std::fs::read_to_string(&a).unwrap();
    assert!(text.starts_with("kind,x,uy,pbar,p\n"));
    assert_eq!(text, std::fs::read_to_string(&b).unwrap());
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(left.len(), 2, "no temporary file left behind");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn no_key_sequence_panics() {
    // A deterministic stream of every key the app knows and some it does not, with fake
    // worker replies, rendered at a few sizes (no solves run: the replies are failures).
    let keys: Vec<Msg> = "qx?[]rRe1234+-=_dDghasz0"
        .chars()
        .map(ch)
        .chain([
            key(KeyCode::Left),
            key(KeyCode::Right),
            key(KeyCode::Tab),
            key(KeyCode::BackTab),
            key(KeyCode::Up),
            key(KeyCode::Enter),
        ])
        .collect();
    let mut app = App::new(Scenario::paper());
    let mut state = 12345u64;
    for step in 0..2000 {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let msg = keys[(state >> 33) as usize % keys.len()].clone();
        if matches!(&msg, Msg::Key(k) if k.code == KeyCode::Char('q')) {
            continue;
        }
        for command in app.update(msg).commands {
            let reply = match command {
                Command::Solve(r) => Response::Solved {
                    generation: r.generation,
                    result: Err(LabError::EstimateEnded),
                },
                Command::InfSup(r) => Response::InfSup {
                    key: r.key,
                    result: Some(Err(LabError::EstimateEnded)),
                },
                Command::Study(r) => Response::Study {
                    generation: r.generation,
                    key: r.key,
                    result: Some(Err(LabError::EstimateEnded)),
                },
                Command::Stresses(r) => Response::Stresses { key: r.solved.key },
                Command::Displace(r) => Response::Displaced { key: r.solved.key },
                Command::Export | Command::Suspend | Command::Supersede(_) => continue,
            };
            app.update(Msg::Worker(reply));
        }
        if step % 97 == 0 {
            for (w, h) in [(80, 24), (120, 40), (30, 10)] {
                frame(&app, w, h);
            }
        }
    }
    assert!(!app.should_quit());
}
