//! The terminal lab: rendered frames (insta snapshots of the plain text, in `snapshots/`) and
//! the key handling of `App::update`, without a terminal.

mod common;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::symbols::Marker;

use riplab::contact::Rule;
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use std::sync::Arc;

use riplab::study::{Errors, StudyRow};
use riplab::tui::app::{
    App, Command, MAX_APP_LEVEL, MAX_STUDY_LEVEL, Msg, Response, Scene, Study, StudyRequest,
};
use riplab::tui::theme::Theme;
use riplab::tui::view::Look;
use riplab::tui::worker::{Engine, settle};
use riplab::tui::{render_app, render_to_string};

const LOOK: Look = Look {
    theme: Theme { color: true },
    marker: Marker::Braille,
};

fn key(code: KeyCode) -> Msg {
    Msg::Key(KeyEvent::new(code, KeyModifiers::NONE))
}

fn ch(c: char) -> Msg {
    key(KeyCode::Char(c))
}

/// The paper's app, solved synchronously, at `level` with `scene` shown.
fn settled(level: u32, scene: Scene) -> App {
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.settings.level = level;
    app.scene = scene;
    settle(&mut app, &mut Engine::new(Scenario::paper()));
    app
}

fn frame(app: &App, w: u16, h: u16) -> String {
    render_app(app, &LOOK, w, h)
}

// ---- snapshots -------------------------------------------------------------------------

#[test]
fn explore_80x24() {
    let text = render_to_string(&Scenario::paper(), "explore", 80, 24, Some(1), None, None, None).unwrap();
    snap!("tui__explore_80x24", text);
}

#[test]
fn explore_120x40_with_overlays() {
    let mut app = settled(2, Scene::Explore);
    app.show_gap = true;
    app.show_hertz = true;
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
    .unwrap();
    snap!("tui__explore_m3_120x40", text);
}

fn infsup_app() -> App {
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
    let text = render_to_string(&Scenario::paper(), "mesh", 80, 24, Some(0), None, None, None).unwrap();
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
        result: Err(
            "the Jacobian is not positive definite (Numeric); is the body held against rigid motion?".into(),
        ),
    }));
    assert!(app.error.is_some());
    assert!(app.solved.is_some(), "the level-0 result stays on screen");
    snap!("tui__error_banner_80x24", frame(&app, 80, 24));
}

// ---- numbers on screen -----------------------------------------------------------------

#[test]
fn status_shows_the_solvers_load() {
    let mut s = Scenario::paper();
    s.level = 1;
    let (_, sol) = riplab::solve::solve_scenario(&s).unwrap();
    let text = render_to_string(&Scenario::paper(), "explore", 80, 24, Some(1), None, None, None).unwrap();
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
    let err = render_to_string(&Scenario::paper(), "plot", 80, 24, None, None, None, None).unwrap_err();
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

#[test]
fn quit_keys() {
    let mut app = App::new(Scenario::paper());
    app.update(ch('?'));
    app.update(key(KeyCode::Esc));
    assert!(!app.show_help && !app.should_quit(), "Esc first closes the help");
    app.update(key(KeyCode::Esc));
    assert!(app.should_quit());

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
    app.update(ch('g'));
    app.update(ch('h'));
    assert!(app.show_gap && app.show_hertz);
    app.update(ch('g'));
    assert!(!app.show_gap);
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
    assert_eq!(cmds.len(), 4, "M1–M4 at the current level, no solve: {cmds:?}");
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
                    result: Err("test failure".into()),
                },
                Command::InfSup(r) => Response::InfSup {
                    key: r.key,
                    result: Some(Err("test failure".into())),
                },
                Command::Study(r) => Response::Study {
                    generation: r.generation,
                    key: r.key,
                    result: Some(Err("test failure".into())),
                },
                Command::Export => continue,
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

// ---- look ------------------------------------------------------------------------------

#[test]
fn monochrome_keeps_the_selection_visible() {
    use ratatui::style::{Color, Modifier};
    let app = settled(0, Scene::Explore);
    let look = Look {
        theme: Theme { color: false },
        marker: Marker::Braille,
    };
    let mut terminal = ratatui::Terminal::new(ratatui::backend::TestBackend::new(80, 24)).unwrap();
    terminal
        .draw(|f| riplab::tui::view::view(&app, f, &look))
        .unwrap();
    let buf = terminal.backend().buffer();
    assert!(
        buf.content
            .iter()
            .all(|c| c.fg == Color::Reset && c.bg == Color::Reset),
        "no colour at all"
    );
    let row: String = (0..80).map(|x| buf[(x, 0)].symbol()).collect();
    let x = row.find("explore").expect("the scene tabs") as u16;
    assert!(buf[(x, 0)].modifier.contains(Modifier::REVERSED));
    let y = row.find("infsup").expect("the scene tabs") as u16;
    assert!(!buf[(y, 0)].modifier.contains(Modifier::REVERSED));
}

#[test]
fn fallback_markers_render() {
    let app = settled(0, Scene::Explore);
    for marker in [Marker::HalfBlock, Marker::Dot] {
        let look = Look {
            theme: Theme { color: true },
            marker,
        };
        let text = render_app(&app, &look, 80, 24);
        assert!(!text.contains('⣀'), "no braille with {marker:?}");
        assert!(text.contains("pressure on Γ_C"));
    }
}

#[test]
fn progress_shows_while_the_last_result_stays() {
    use riplab::tui::app::Progress;
    let mut app = settled(0, Scene::Explore);
    let Some(Command::Solve(req)) = app.update(key(KeyCode::Right)).commands.first().cloned() else {
        panic!("a new level asks for a solve");
    };
    let effect = app.update(Msg::Worker(Response::Progress {
        generation: req.generation,
        progress: Progress::Newton {
            iteration: 3,
            residual: 1.5e-3,
            active: 12,
        },
    }));
    assert!(effect.redraw);
    let text = frame(&app, 80, 24);
    assert!(text.contains("⟳ Newton 3: residual 0.0015, 12 active"), "{text}");
    assert!(
        text.contains("q1+gauss1 level 0"),
        "the level-0 chart stays:\n{text}"
    );
    // Progress of a superseded solve is not shown.
    assert!(
        !app.update(Msg::Worker(Response::Progress {
            generation: req.generation - 1,
            progress: Progress::Assembling,
        }))
        .redraw
    );
}

#[test]
fn every_element_and_rule_renders_every_scene() {
    let mut engine = Engine::new(Scenario::paper());
    for element in Element::ALL {
        for rule in Rule::ALL {
            for scene in Scene::ALL {
                let mut app = App::new(Scenario::paper());
                app.show_timing = false;
                app.settings.element = element;
                app.settings.rule = rule;
                app.scene = scene;
                settle(&mut app, &mut engine);
                assert!(app.error.is_none(), "{element:?} {rule:?}: {:?}", app.error);
                for (w, h) in [(80, 24), (120, 40)] {
                    let text = frame(&app, w, h);
                    assert!(text.contains(scene.name()), "{element:?} {rule:?} {scene:?}");
                }
            }
        }
    }
}

#[test]
fn a_asks_for_every_level_up_to_the_current_one() {
    let mut app = App::new(Scenario::paper());
    app.scene = Scene::InfSup;
    app.settings.level = 2;
    assert_eq!(app.update(Msg::Resize).commands.len(), 4, "M1–M4 at level 2");
    let more = app.update(ch('a')).commands;
    assert!(app.all_levels);
    assert_eq!(more.len(), 8, "M1–M4 at levels 0 and 1: {more:?}");
    assert!(
        more.iter()
            .all(|c| matches!(c, Command::InfSup(r) if r.key.level < 2))
    );
}

#[test]
fn no_contact_renders() {
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.settings.depth = 0.0;
    app.show_gap = true;
    app.show_hertz = true;
    for scene in Scene::ALL {
        app.scene = scene;
        settle(&mut app, &mut Engine::new(Scenario::paper()));
        let text = frame(&app, 80, 24);
        if scene.needs_solution() {
            assert!(text.contains(" P=0 (full 0)"), "{text}");
        }
    }
}

// ---- convergence scene -----------------------------------------------------------------

/// A row of a made-up study (fixed timings, so that frames are deterministic).
#[allow(clippy::too_many_arguments)]
fn row(scheme: &str, level: u32, n_dofs: usize, ms: f64, p: f64, pbar: f64, u: f64) -> StudyRow {
    StudyRow {
        scheme: scheme.into(),
        element: "q1",
        rule: "gauss1",
        level,
        h: 1.0 / f64::from(1 << level),
        epsilon: 1e-6,
        n_dofs,
        newton_iterations: 3,
        converged: true,
        solve_ms: ms,
        load: 1.0,
        errors: Errors {
            p,
            pbar,
            u,
            load: pbar,
        },
        rates: None,
    }
}

/// The paper's app on the convergence scene at level 2 with a made-up study of levels 0..=2.
fn convergence_app() -> App {
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.scene = Scene::Convergence;
    app.settings.level = 2;
    let key = app.study_key();
    assert_eq!(key.max_level, 2);
    let rows = vec![
        row("M1", 0, 90, 2.0, 0.42, 0.12, 0.05),
        row("M1", 1, 306, 6.5, 0.31, 0.045, 0.025),
        row("M1", 2, 1122, 24.0, 0.22, 0.016, 0.0123),
        row("M2", 0, 90, 2.4, 0.9, 0.2, 0.05),
        row("M2", 1, 306, 7.1, 1.3, 0.15, 0.026),
        row("M2", 2, 1122, 27.0, 1.8, 0.11, 0.0125),
        row("M3", 0, 90, 1.8, 0.15, 0.1, 0.048),
        row("M3", 1, 306, 6.0, 0.07, 0.04, 0.024),
        row("M3", 2, 1122, 22.0, 0.0345, 0.0149, 0.012),
        row("M4", 0, 306, 5.2, 0.05, 0.03, 0.01),
        row("M4", 1, 1122, 19.0, 0.018, 0.01, 0.0025),
        row("M4", 2, 4290, 80.0, 0.0065, 0.0035, 0.000612),
    ];
    app.studies.insert(key.clone(), Ok(Arc::new(Study { key, rows })));
    app
}

#[test]
fn convergence_80x24() {
    let app = convergence_app();
    assert!(
        app.clone().update(Msg::Resize).commands.is_empty(),
        "a cached study asks for nothing more"
    );
    snap!("tui__convergence_80x24", frame(&app, 80, 24));
}

#[test]
fn convergence_120x40() {
    snap!("tui__convergence_120x40", frame(&convergence_app(), 120, 40));
}

fn studies(commands: &[Command]) -> Vec<StudyRequest> {
    commands
        .iter()
        .filter_map(|c| match c {
            Command::Study(r) => Some(r.clone()),
            _ => None,
        })
        .collect()
}

#[test]
fn convergence_asks_for_one_study_and_caches_it() {
    let mut app = App::new(Scenario::paper());
    app.update(Msg::Resize);
    app.update(key(KeyCode::Tab));
    app.update(key(KeyCode::Tab));
    let cmds = app.update(key(KeyCode::Tab)).commands;
    assert_eq!(app.scene, Scene::Convergence);
    let asked = studies(&cmds);
    assert_eq!(cmds.len(), 1, "only the study: {cmds:?}");
    assert_eq!(asked.len(), 1);
    let req = asked[0].clone();
    assert_eq!(req.key.scenario, app.scenario.name);
    assert_eq!(req.key.max_level, 0);
    assert_eq!(req.key.reference_level(), 1);
    let text = frame(&app, 80, 24);
    assert!(text.contains("computing the reference (q2, level 1)…"), "{text}");
    // Away and back while it runs: not asked again.
    app.update(key(KeyCode::Tab));
    assert!(studies(&app.update(key(KeyCode::BackTab)).commands).is_empty());
    // The study finishes (on the real engine: level 0 against the q2 reference at level 1).
    let mut engine = Engine::new(Scenario::paper());
    let reply = Response::Study {
        generation: req.generation,
        result: Some(engine.study(&req.key)),
        key: req.key.clone(),
    };
    assert!(app.update(Msg::Worker(reply)).redraw);
    let Some(Ok(study)) = app.studies.get(&req.key) else {
        panic!("the study is cached: {:?}", app.studies);
    };
    let schemes: Vec<&str> = study.rows.iter().map(|r| r.scheme.as_str()).collect();
    assert_eq!(schemes, ["M1", "M2", "M3", "M4"]);
    assert!(
        study
            .rows
            .iter()
            .all(|r| r.errors.pbar > 0.0 && r.errors.pbar.is_finite())
    );
    assert!(!frame(&app, 80, 24).contains("computing"));
    // Cached: coming back asks for nothing.
    app.update(key(KeyCode::Tab));
    let back = app.update(key(KeyCode::BackTab)).commands;
    assert_eq!(app.scene, Scene::Convergence);
    assert!(back.is_empty(), "{back:?}");
}

#[test]
fn newer_studies_supersede_older_ones() {
    let mut app = App::new(Scenario::paper());
    app.scene = Scene::Convergence;
    let old = studies(&app.update(Msg::Resize).commands).remove(0);
    let new = studies(&app.update(key(KeyCode::Right)).commands).remove(0);
    assert!(new.generation > old.generation);
    assert_eq!((old.key.max_level, new.key.max_level), (0, 1));
    // The old study's reply is dropped: a newer one was asked for.
    let reply = Response::Study {
        generation: old.generation,
        key: old.key.clone(),
        result: Some(Err("stale".into())),
    };
    assert!(!app.update(Msg::Worker(reply)).redraw);
    assert!(app.studies.is_empty());
    // A study dropped unstarted by the worker is asked for again while still wanted.
    let dropped = Response::Study {
        generation: new.generation,
        key: new.key.clone(),
        result: None,
    };
    let again = studies(&app.update(Msg::Worker(dropped)).commands);
    assert_eq!(again.len(), 1);
    assert_eq!(again[0].key, new.key);
    // Levels above the study's cap share the capped study.
    app.settings.level = MAX_APP_LEVEL;
    assert_eq!(app.study_key().max_level, MAX_APP_LEVEL.min(MAX_STUDY_LEVEL));
}
