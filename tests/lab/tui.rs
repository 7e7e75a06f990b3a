//! The terminal lab: rendered frames (insta snapshots of the plain text, in `snapshots/`) and
//! the key handling of `App::update`, without a terminal.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::symbols::Marker;

use riplab::contact::Rule;
use riplab::contact::hertz::Hertz;
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use std::sync::Arc;

use crate::common::settled;
use riplab::study::{Errors, Status, StudyRow};
use riplab::tui::app::{
    App, Command, Compare, MAX_APP_LEVEL, MAX_STUDY_LEVEL, Msg, Response, Scene, Study, StudyRequest,
};
use riplab::tui::theme::Theme;
use riplab::tui::view::Look;
use riplab::tui::worker::{Engine, Use, settle};
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

fn frame(app: &App, w: u16, h: u16) -> String {
    render_app(app, &LOOK, w, h)
}

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
    .unwrap()
    .text;
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
        result: Err(
            "the Jacobian is not positive definite (Numeric); is the body held against rigid motion?".into(),
        ),
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
    let refusal = "the method: Nitsche's γ₀: 100 is too small for θ = 1: the method is stable for γ₀ > ((1 + θ)²/4)·γ₀* (here γ₀* = 1245.043), where K − ((1 + θ)²/4)(1/γ)∫σ_n σ_n stays positive definite (Chouly and Hild's condition); choose a larger γ₀ or θ = −1";
    app.update(Msg::Worker(Response::Solved {
        generation: req.generation,
        result: Err(refusal.into()),
    }));
    let text = frame(&app, 80, 24);
    let shown: String = text.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(shown.contains("choose a larger γ₀ or θ = −1"), "{text}");
    assert!(shown.contains("(Chouly and Hild's condition)"), "{text}");
    assert_eq!(text.lines().count(), 24);
    // The status line does not go on saying the last solve converged: it says these settings
    // have no result and whose result the charts keep.
    let status = text.lines().last().unwrap();
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
            progress: Progress::Assembling {
                level: 1,
                unknowns: 100,
                started: std::time::Instant::now(),
                estimate_ms: 1.0,
                method: None,
            },
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
        method: riplab::contact::Method::Penalty.into(),
        n_dofs,
        refine_edges: 0,
        h_min: 1.0 / f64::from(1 << level),
        grading: Default::default(),
        status: Status::Ok,
        reason: None,
        newton_iterations: Some(3),
        outer_iterations: None,
        converged: true,
        solve_ms: Some(ms),
        load: Some(1.0),
        errors: Some(Errors {
            p,
            pbar,
            u,
            load: pbar,
        }),
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
    let engine = Engine::new(Scenario::paper());
    let reply = Response::Study {
        generation: req.generation,
        result: Some(engine.study(&req.key, &mut |_| {})),
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
            .all(|r| r.errors.is_some_and(|e| e.pbar > 0.0 && e.pbar.is_finite()))
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

// ---- issue 14: the convergence scene compares the methods -------------------------------

/// The methods' names in the rows of `study`, in order.
fn methods_of(study: &Study) -> Vec<&'static str> {
    study.rows.iter().map(|r| r.method.method).collect()
}

/// `w` turns the study of M1–M4 with the lab's method into a study of the methods on the
/// lab's scheme; its rows carry each method (checked on the real engine: the ALM gives the
/// exact load where the penalty misses it by its ε term), and the chart has one series per
/// method, each with its own glyph (legible without colour).
#[test]
fn w_makes_a_study_of_the_methods() {
    let mut app = App::new(Scenario::paper());
    app.scene = Scene::Convergence;
    let schemes = studies(&app.update(Msg::Resize).commands).remove(0);
    assert_eq!(schemes.key.compare, Compare::Schemes);
    assert_eq!(schemes.key.methods, [app.settings.method]);
    assert_eq!(schemes.key.schemes.len(), 4, "M1–M4");
    let asked = studies(&app.update(ch('w')).commands);
    assert_eq!(asked.len(), 1, "one study: {asked:?}");
    let req = asked[0].clone();
    assert_eq!(req.key.compare, Compare::Methods);
    let names: Vec<&str> = req.key.methods.iter().map(|m| m.name()).collect();
    assert_eq!(names, ["penalty", "alm", "nitsche", "exact"]);
    assert_eq!(req.key.schemes, [(app.settings.element, app.settings.rule)]);
    let text = frame(&app, 120, 40);
    assert!(text.contains("then the methods on M1 at levels 0 to 0"), "{text}");
    // The study runs on the real engine: level 0 against the q2 reference at level 1.
    let engine = Engine::new(Scenario::paper());
    let reply = Response::Study {
        generation: req.generation,
        result: Some(engine.study(&req.key, &mut |_| {})),
        key: req.key.clone(),
    };
    assert!(app.update(Msg::Worker(reply)).redraw);
    let Some(Ok(study)) = app.studies.get(&req.key) else {
        panic!("the study is cached: {:?}", app.studies);
    };
    assert_eq!(methods_of(study), ["penalty", "alm", "nitsche", "exact"]);
    assert!(
        study
            .rows
            .iter()
            .all(|r| r.scheme == "M1" && r.status == Status::Ok)
    );
    let load = |name: &str| {
        study
            .rows
            .iter()
            .find(|r| r.method.method == name)
            .unwrap()
            .load
            .unwrap()
    };
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    // The ALM has no penalty error: its load is the exact one; the penalty's is not.
    assert!(
        rel(load("alm"), load("exact")) < 1e-9,
        "{} {}",
        load("alm"),
        load("exact")
    );
    assert!(
        rel(load("penalty"), load("exact")) > 1e-6,
        "{} {}",
        load("penalty"),
        load("exact")
    );
    // Only the ALM updates a multiplier.
    let updates: Vec<bool> = study.rows.iter().map(|r| r.outer_iterations.is_some()).collect();
    assert_eq!(updates, [false, true, false, false]);
    // One series per method, each with its glyph in the legend; no raw-p curve here.
    let text = render_app(&app, &MONO, 120, 40);
    for entry in ["⠒P⠒ penalty p̄", "⠒A⠒ alm p̄", "⠒N⠒ nitsche p̄", "⠒E⠒ exact p̄"] {
        assert!(text.contains(entry), "legend entry `{entry}` in\n{text}");
    }
    assert!(!text.contains("M1 p (raw)"), "{text}");
    assert!(text.contains("work–precision of the methods on M1"), "{text}");
    assert!(text.contains("w compares M1–M4"), "{text}");
    // Back to the schemes: that study is asked for again (the first was never answered).
    let back = studies(&app.update(ch('w')).commands);
    assert_eq!(back.len(), 1);
    assert_eq!(back[0].key, schemes.key);
}

/// `m` changes the method of the schemes' study, which is a study of its own.
#[test]
fn the_schemes_study_runs_the_labs_method() {
    let mut app = App::new(Scenario::paper());
    app.scene = Scene::Convergence;
    let penalty = studies(&app.update(Msg::Resize).commands).remove(0);
    let alm = studies(&app.update(ch('m')).commands);
    assert_eq!(alm.len(), 1);
    assert_ne!(alm[0].key, penalty.key);
    assert_eq!(alm[0].key.methods, [app.settings.method]);
    assert_eq!(alm[0].key.label(), "M1–M4 (exact)");
    // ε: the methods' study runs at the lab's (the penalty's error depends on it), the
    // schemes' at the scenario's.
    app.update(ch('w'));
    assert_eq!(app.study_key().epsilon, 1e-6);
    app.update(ch('+'));
    assert_eq!(app.study_key().epsilon, 1e-5);
    app.update(ch('w'));
    assert_eq!(app.study_key().epsilon, 1e-6);
}

/// A made-up study of the methods on M2 at levels 0..=2 (fixed timings): `exact` has no
/// answer on a rule with a kernel, and says so.
fn methods_app() -> App {
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.scene = Scene::Convergence;
    app.compare = Compare::Methods;
    app.settings.level = 2;
    app.settings.rule = Rule::Gauss2;
    let key = app.study_key();
    let mut rows = Vec::new();
    for (i, &method) in key.methods.iter().enumerate() {
        for level in 0..=2u32 {
            let f = f64::from(1 << level);
            let mut r = row(
                "M2",
                level,
                [90, 306, 1122][level as usize],
                2.0 * f * f * (1.0 + i as f64),
                0.5 / f,
                0.2 / f,
                0.05 / f,
            );
            r.rule = "gauss2";
            r.method = method.into();
            r.outer_iterations = (method.name() == "alm").then_some(3);
            if method.name() == "exact" {
                r.status = Status::Kernel;
                r.reason = Some("ε = 0 imposes the constraint exactly at the 8 points of gauss2, more than the 5 normal displacements on Γ_C".into());
                r.errors = None;
                r.solve_ms = None;
                r.newton_iterations = None;
            }
            rows.push(r);
        }
    }
    app.studies.insert(key.clone(), Ok(Arc::new(Study { key, rows })));
    app
}

/// The methods' chart and table at 80×24, with colour and without: `exact` says why it has
/// no curve, in the legend and in the table.
#[test]
fn convergence_methods_80x24() {
    let app = methods_app();
    assert!(
        app.clone().update(Msg::Resize).commands.is_empty(),
        "a cached study asks for nothing more"
    );
    let text = frame(&app, 80, 24);
    assert!(text.contains("exact: kernel"), "{text}");
    let mono = render_app(&app, &MONO, 80, 24);
    for entry in ["⠒P⠒ penalty p̄", "⠒A⠒ alm p̄", "⠒N⠒ nitsche p̄", "⠒E⠒ exact: kernel"] {
        assert!(mono.contains(entry), "legend entry `{entry}` in\n{mono}");
    }
    assert!(
        mono.contains("kernel: ε = 0 imposes"),
        "the table says why:\n{mono}"
    );
    snap!("tui__convergence_methods_80x24", text);
}

// ---- issue 11 item 7: views only draw ----------------------------------------------------

/// What the views show of a solution is computed once with it ([`riplab::tui::shown::Shown`]),
/// checked against the solution itself: a half model's p̄ mirrored about x = 0, the whole
/// body's load twice the half's, Hertz for that load, and a zoom range that is symmetric and
/// holds every vertex in contact; a full model is neither mirrored nor doubled.
#[test]
fn shown_is_the_solution_mirrored_once() {
    let app = settled(1, Scene::Explore);
    let solved = app.current().expect("solved");
    let (sol, shown) = (&solved.solution, &solved.shown);
    let xs = &sol.points.vertex_x;
    let n = sol.pbar.len();
    assert_eq!(shown.pbar.len(), 2 * n);
    for (i, (&x, &p)) in xs.iter().zip(&sol.pbar).enumerate() {
        assert_eq!(shown.pbar[n + i], (x, p));
        assert_eq!(shown.pbar[n - 1 - i], (-x, p));
    }
    let half_width = app.scenario.width / 2.0;
    assert_eq!(shown.x_range, [-half_width, half_width]);
    assert_eq!(shown.full_load, 2.0 * sol.load);
    let hertz = Hertz::for_load(&sol.params.obstacle, &app.scenario.material, 2.0 * sol.load);
    assert!(hertz.is_some());
    assert_eq!(shown.hertz, hertz);
    let [a, b] = shown.zone.expect("in contact");
    assert_eq!(a, -b);
    let in_contact = (0..n).filter(|&i| sol.pbar[i] > 0.0);
    assert!(in_contact.clone().count() > 0);
    for i in in_contact {
        assert!(a < -xs[i] && xs[i] < b, "x = ±{} in [{a}, {b}]", xs[i]);
    }
    let full = Scenario::load(std::path::Path::new("scenarios/hertz-paper-full.toml")).unwrap();
    assert!(!full.half_model);
    let mut app = App::new(full.clone());
    app.settings.level = 0;
    settle(&mut app, &mut Engine::new(full));
    let solved = app.current().expect("solved");
    assert_eq!(solved.shown.full_load, solved.solution.load);
    assert_eq!(solved.shown.pbar.len(), solved.solution.pbar.len());
}

// ---- issue 12: the lab draws as exactly as it computes ------------------------------------

use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::style::Color;
use riplab::tui::view::plot::{Axis as PlotAxis, Plot, Scale, Series as PlotSeries, Stroke};

/// The text of row `y` of `buf`, one char per cell (wide cells are not used by the charts).
fn row_text(buf: &Buffer, y: u16) -> Vec<String> {
    (0..buf.area.width)
        .map(|x| buf[(x, y)].symbol().to_string())
        .collect()
}

/// The centre column of each whole-word label in `row` that parses as a number.
fn numbers_in(row: &[String]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut x = 0;
    let gap = |c: &str| c.trim().is_empty() || ["│", "┤", "┬", "└", "─"].contains(&c);
    while x < row.len() {
        if gap(&row[x]) {
            x += 1;
            continue;
        }
        let start = x;
        let mut word = String::new();
        while x < row.len() && !gap(&row[x]) {
            word.push_str(&row[x]);
            x += 1;
        }
        if let Ok(v) = word.parse::<f64>() {
            out.push((v, (start + x - 1) as f64 / 2.0));
        }
    }
    out
}

/// A plot of one glyph series on an 80×14 test terminal.
fn plot_buffer(x: PlotAxis, y: PlotAxis, data: &[(f64, f64)]) -> Buffer {
    let mut terminal = ratatui::Terminal::new(TestBackend::new(80, 14)).unwrap();
    terminal
        .draw(|f| {
            Plot {
                title: " test ".into(),
                x: x.clone(),
                y: y.clone(),
                series: vec![PlotSeries {
                    name: "pts".into(),
                    color: Color::Red,
                    stroke: Stroke::None,
                    glyph: Some('@'),
                    data,
                }],
                marker: Marker::Braille,
                theme: Theme { color: true },
            }
            .render(f, f.area())
            .expect("room for the graph");
        })
        .unwrap();
    terminal.backend().buffer().clone()
}

/// Where `@` is drawn in the graph (below the border and the legend row): (column, row).
fn glyphs(buf: &Buffer) -> Vec<(u16, u16)> {
    let mut out = Vec::new();
    for y in 2..buf.area.height {
        for x in 0..buf.area.width {
            if buf[(x, y)].symbol() == "@" {
                out.push((x, y));
            }
        }
    }
    out
}

/// Item 1: every tick label sits within one cell of where a point of its value is drawn,
/// on linear and log axes, in x and in y.
#[test]
fn tick_labels_sit_at_their_values() {
    let xs = [-8.0, -6.0, -4.0, -2.0, 0.0, 2.0, 4.0, 6.0, 8.0];
    // x linear over [-8, 8] (the paper's mirrored Γ_C), y log10 over 10^-2.3 .. 10^0.4: a
    // row of points at y = 0.01, and points at x = 4 of y = 0.1 and 1.
    let mut points: Vec<(f64, f64)> = xs.iter().map(|&x| (x, -2.0)).collect();
    points.extend([(4.0, -1.0), (4.0, 0.0)]);
    let buf = plot_buffer(
        PlotAxis {
            title: "x".into(),
            bounds: [-8.0, 8.0],
            scale: Scale::Linear,
        },
        PlotAxis {
            title: "y".into(),
            bounds: [-2.3, 0.4],
            scale: Scale::Log10,
        },
        &points,
    );
    let at = glyphs(&buf);
    let bottom = at.iter().map(|p| p.1).max().unwrap();
    let mut cols: Vec<u16> = at.iter().filter(|p| p.1 == bottom).map(|p| p.0).collect();
    cols.sort();
    assert_eq!(cols.len(), xs.len(), "{}", riplab::tui::buffer_text(&buf));
    // x: the labels on the last row inside the border.
    let labels = numbers_in(&row_text(&buf, buf.area.height - 2));
    assert!(labels.len() >= 5, "{labels:?}");
    for (v, centre) in &labels {
        let i = xs.iter().position(|x| x == v).expect("a tick at a point");
        assert!(
            (f64::from(cols[i]) - centre).abs() <= 1.0,
            "label {v} centred at {centre}, its point at column {}",
            cols[i]
        );
    }
    // y: each label (in the left margin) on the row of a point of its value: 0.01 is the
    // bottom row of points, 1 the topmost point, 0.1 the other one.
    let upper: Vec<u16> = at.iter().filter(|p| p.1 != bottom).map(|p| p.1).collect();
    let row_of = |v: f64| -> u16 {
        match v {
            0.01 => bottom,
            1.0 => *upper.iter().min().unwrap(),
            0.1 => *upper.iter().max().unwrap(),
            _ => panic!("a label without a point: {v}"),
        }
    };
    let mut seen = 0;
    for row in 0..buf.area.height - 3 {
        for (v, _) in numbers_in(&row_text(&buf, row)[..8]) {
            let point_row = row_of(v);
            assert!(
                (i32::from(point_row) - i32::from(row)).abs() <= 1,
                "label {v} on row {row}, its point on row {point_row}"
            );
            seen += 1;
        }
    }
    assert_eq!(
        seen,
        3,
        "labels 0.01, 0.1 and 1:\n{}",
        riplab::tui::buffer_text(&buf)
    );
}

/// Item 1 on the lab's own pressure chart: at 80×24 the x labels are where their values are
/// (the contact edge of the paper's problem at x = ±3 lies between the labels 2 and 4).
#[test]
fn pressure_chart_labels_are_linear_in_their_values() {
    for (w, h) in [(80, 24), (100, 30)] {
        let text = render_to_string(&Scenario::paper(), "explore", w, h, Some(0), None, None, None)
            .unwrap()
            .text;
        let lines: Vec<Vec<String>> = text
            .lines()
            .map(|l| l.chars().map(String::from).collect())
            .collect();
        // The axis line of the pressure chart: "└┬───┬…"; its labels are the next row.
        let axis = lines
            .iter()
            .position(|l| l.iter().any(|c| c == "└") && l.iter().any(|c| c == "┬"))
            .unwrap();
        let ticks: Vec<usize> = (0..lines[axis].len())
            .filter(|&i| lines[axis][i] == "┬")
            .collect();
        let start = lines[axis].iter().position(|c| c == "└").unwrap() + 1;
        let end = lines[axis].iter().rposition(|c| c == "─" || c == "┬").unwrap();
        let labels = numbers_in(&lines[axis + 1]);
        assert!(labels.iter().any(|(v, _)| *v == 4.0), "{w}x{h}: {labels:?}");
        for (v, centre) in labels {
            let expected = start as f64 + (v + 8.0) / 16.0 * (end - start) as f64;
            assert!(
                (centre - expected).abs() <= 1.0,
                "{w}x{h}: label {v} at {centre}, value at {expected}"
            );
            assert!(
                ticks.iter().any(|&t| (t as f64 - centre).abs() <= 1.0),
                "{w}x{h}: a tick under label {v}"
            );
        }
    }
}

/// The test terminal's buffer of `app` drawn with `look` at `w`×`h`.
fn buffer(app: &App, look: &Look, w: u16, h: u16) -> Buffer {
    let mut terminal = ratatui::Terminal::new(TestBackend::new(w, h)).unwrap();
    terminal.draw(|f| riplab::tui::view::view(app, f, look)).unwrap();
    terminal.backend().buffer().clone()
}

const MONO: Look = Look {
    theme: Theme { color: false },
    marker: Marker::Braille,
};

/// Item 2: without colour every chart's series differ in their symbols, and the legend shows
/// each symbol.
#[test]
fn monochrome_series_have_distinct_symbols_in_the_legend() {
    let mut app = settled(1, Scene::Explore);
    app.show_hertz = true;
    app.show_gap = true;
    let text = render_app(&app, &MONO, 100, 30);
    for entry in ["⠒⠒⠒ p̄ smoothed", "⠒ ⠒ p gauss1", "+ Hertz", "· −g"] {
        assert!(text.contains(entry), "legend entry `{entry}` in\n{text}");
    }
    let text = render_app(&infsup_app(), &MONO, 80, 24);
    for entry in ["⠒1⠒ M1", "⠒2⠒ M2", "⠒3⠒ M3", "⠒4⠒ M4", "⠒*⠒ M1 p̄"] {
        assert!(text.contains(entry), "legend entry `{entry}` in\n{text}");
    }
    // The glyphs are on the curves too: each scheme's digit appears in the graph.
    let graph: String = text.lines().skip(4).take(8).collect();
    // (M3's β_h equals M1's β̄_h, so `*` covers `3`; M2's β_h is 0, off a log axis.)
    assert!(text.contains("M2 β=0, kernel"), "{text}");
    for digit in ['1', '4', '*'] {
        assert!(graph.contains(digit), "{digit} on a curve:\n{text}");
    }
    let text = render_app(&convergence_app(), &MONO, 80, 24);
    for entry in ["⠒ r ⠒ M1 p (raw)", "⠒1⠒ M1 p̄", "⠒4⠒ M4 p̄"] {
        assert!(text.contains(entry), "legend entry `{entry}` in\n{text}");
    }
}

/// Item 2: no tour caption relies on a colour's name.
#[test]
fn tour_captions_do_not_name_colours() {
    let tour = riplab::tui::tour::Tour::paper();
    for step in &tour.steps {
        let caption = step.caption.to_lowercase();
        for colour in ["yellow", "cyan", "magenta", "red", "green", "blue"] {
            assert!(
                !caption.split(|c: char| !c.is_alphabetic()).any(|w| w == colour),
                "step `{}` names {colour}",
                step.title
            );
        }
    }
}

/// Item 4: one size rule for the lab and render, checked before anything is allocated.
#[test]
fn sizes_outside_the_rule_are_refused() {
    use riplab::tui::parse_size;
    assert_eq!(parse_size("80x24"), Ok((80, 24)));
    assert_eq!(parse_size("80×24"), Ok((80, 24)));
    assert_eq!(parse_size("120X40"), Ok((120, 40)));
    for bad in [
        "1x1",
        "5x5",
        "79x24",
        "80x23",
        "10000x10000",
        "1001x40",
        "70000x30",
    ] {
        let e = parse_size(bad).unwrap_err();
        assert!(e.contains("allowed: 80x24 to 1000x500"), "{bad}: {e}");
    }
    assert!(parse_size("eighty").unwrap_err().contains("not a size"));
    assert!(render_to_string(&Scenario::paper(), "mesh", 5, 5, Some(0), None, None, None).is_err());
    for (size, code) in [("10000x10000", 2), ("5x5", 2), ("1x1", 2), ("80×24", 0)] {
        let (got, out, err) = crate::common::riplab(&["render", "--size", size, "--level", "0"]);
        assert_eq!(got, code, "--size {size}: {err}");
        if code == 2 {
            assert!(err.contains("--size") && err.contains("allowed"), "{err}");
            assert!(out.is_empty());
        }
    }
}

/// Item 5: at 80 columns the status line keeps its message whole (unit included) and drops
/// the key hints; a message too long is cut at a word with "…".
#[test]
fn status_message_wins_over_the_key_hints() {
    let mut app = settled(1, Scene::Explore);
    app.show_timing = true;
    let mut solved = (**app.solved.as_ref().unwrap()).clone();
    solved.total_ms = 3048.0;
    app.solved = Some(Arc::new(solved));
    let text = frame(&app, 80, 24);
    let last = text.lines().last().unwrap();
    assert!(last.contains("· 3050 ms") || last.contains("· 3048 ms"), "{last}");
    assert!(last.contains("load P=646.13 (full 1292.3)"), "{last}");
    let wide = frame(&app, 120, 40);
    assert!(wide.lines().last().unwrap().ends_with("? help  q quit"), "{wide}");
    let long = "a long notice with many words that cannot fit in eighty columns of a terminal window at all, none of them";
    app.notice = Some(riplab::tui::app::Notice::info(long));
    let last = frame(&app, 80, 24).lines().last().unwrap().to_string();
    let kept = last.trim_start().strip_suffix('…').expect("marked as cut");
    assert!(long.starts_with(&format!("{kept} ")), "cut at a word: {last}");
}

/// Item 6: a failed export shows in the status line with the absolute path; files are named
/// with ε and depth.
#[test]
fn export_failures_show_and_names_carry_epsilon_and_depth() {
    let mut app = settled(1, Scene::Explore);
    let solved = app.current().unwrap().clone();
    assert_eq!(
        riplab::tui::export::stem(&app.scenario, &solved),
        "hertz-paper-q1-gauss1-L1-eps1e-6-d0.8"
    );
    // A file where the directory should be: nothing can be written under it.
    let file = std::env::temp_dir().join(format!("riplab-not-a-dir-{}", std::process::id()));
    std::fs::write(&file, "x").unwrap();
    let err = riplab::tui::export::export_csv(&app.scenario, &solved, &file).unwrap_err();
    assert!(err.contains(&file.display().to_string()), "{err}");
    app.update(Msg::Exported(Err(err)));
    let text = frame(&app, 120, 40);
    let last = text.lines().last().unwrap();
    // The absolute directory, then why.
    assert!(
        last.contains(&format!("✗ export failed: {}: Not a directory", file.display())),
        "{last}"
    );
    std::fs::remove_file(&file).unwrap();
    // The help says where files go; the command line sets it.
    let (_, help, _) = crate::common::riplab(&["--help"]);
    assert!(help.contains("--export-dir"), "{help}");
}

/// A made-up estimate (the table's layout, not its numbers, is under test).
fn estimate(level: u32) -> riplab::tui::beta::InfSup {
    let h = 1.0 / f64::from(1 << level);
    riplab::tui::beta::InfSup {
        h,
        beta: 0.1 * h,
        beta_over_sqrt_h: 0.1 * h.sqrt(),
        beta_bar: 0.9 * h.sqrt(),
        beta_bar_over_sqrt_h: 0.9,
        kernel: None,
    }
}

/// Item 7: the current level's row is always shown and marked, whatever the height.
#[test]
fn infsup_table_shows_the_current_level() {
    let mut app = settled(0, Scene::Explore);
    let key = app.infsup_key();
    for level in 0..=MAX_APP_LEVEL {
        app.infsup
            .insert(riplab::tui::app::InfSupKey { level, ..key }, Ok(estimate(level)));
    }
    for current in [0, 2, MAX_APP_LEVEL] {
        app.settings.level = current;
        let text = frame(&app, 80, 24);
        let marked: Vec<&str> = text
            .lines()
            .filter(|l| l.contains(&format!("│▸ {current} ")))
            .collect();
        assert_eq!(marked.len(), 1, "level {current} marked:\n{text}");
        // Whole on its line (h at level 7, 0.00781, is a digit longer than the others).
        assert!(marked[0].contains(" 0.9│"), "level {current}:\n{text}");
        let of = format!(" of {}", MAX_APP_LEVEL + 1);
        assert!(text.contains(&of), "the title says rows are hidden:\n{text}");
    }
}

/// Item 7: stepping levels quickly loses no row: an estimate the worker drops as stale is
/// asked for again.
#[test]
fn stepping_levels_fast_loses_no_row() {
    let mut app = App::new(Scenario::paper());
    app.settings.level = 1;
    let mut queue: Vec<Command> = app.update(Msg::Resize).commands;
    queue.extend(app.update(key(KeyCode::Right)).commands);
    queue.extend(app.update(key(KeyCode::Right)).commands);
    assert_eq!(app.settings.level, 3);
    // The worker: solves fail fast, the stale estimate (level 2) is dropped unstarted, the
    // others are made up; replies may ask for more.
    let latest = app.generation;
    let mut rounds = 0;
    while let Some(command) = queue.pop() {
        rounds += 1;
        assert!(rounds < 100);
        let reply = match command {
            Command::Solve(r) => Response::Solved {
                generation: r.generation,
                result: Err("not under test".into()),
            },
            Command::InfSup(r) => Response::InfSup {
                key: r.key,
                result: (r.generation >= latest).then(|| Ok(estimate(r.key.level))),
            },
            _ => continue,
        };
        queue.extend(app.update(Msg::Worker(reply)).commands);
    }
    let text = frame(&app, 100, 40);
    for level in 1..=3 {
        assert!(
            text.lines()
                .any(|l| l.contains(&format!("│  {level} ")) || l.contains(&format!("│▸ {level} "))),
            "row {level}:\n{text}"
        );
    }
}

/// Item 8: the legend has a row of its own above the graph, at 80×24 too.
#[test]
fn legends_are_present_and_never_over_data() {
    let mut app = settled(1, Scene::Explore);
    app.show_hertz = true;
    for (text, name) in [
        (frame(&app, 80, 24), "Hertz"),
        (frame(&infsup_app(), 80, 24), "M4"),
        (frame(&convergence_app(), 80, 24), "M4 p̄"),
    ] {
        let row = text
            .lines()
            .find(|l| l.contains(&format!(" {name} ")) && l.contains("⠒"))
            .unwrap_or_else(|| panic!("legend with {name}:\n{text}"));
        let braille = row
            .chars()
            .filter(|c| ('\u{2801}'..='\u{28ff}').contains(c))
            .count();
        // The legend's own samples are the only braille on its row.
        let samples = row.matches('⠒').count();
        assert_eq!(braille, samples, "no data on the legend's row: {row}");
    }
}

/// Item 9: `z` zooms the pressure chart and the contact zone to where p̄ > 0, and back.
#[test]
fn zoom_narrows_to_the_contact_zone() {
    let scenario = Scenario::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenarios/hertz-block.toml"
    )))
    .unwrap();
    let mut app = App::new(scenario.clone());
    app.show_timing = false;
    settle(&mut app, &mut Engine::new(scenario));
    let x_labels = |text: &str| -> Vec<f64> {
        let lines: Vec<Vec<String>> = text
            .lines()
            .map(|l| l.chars().map(String::from).collect())
            .collect();
        let axis = lines.iter().position(|l| l.iter().any(|c| c == "┬")).unwrap();
        numbers_in(&lines[axis + 1]).into_iter().map(|(v, _)| v).collect()
    };
    let before = x_labels(&frame(&app, 100, 30));
    app.update(ch('z'));
    assert!(app.zoom);
    let text = frame(&app, 100, 30);
    assert!(text.contains("zoom"), "{text}");
    let after = x_labels(&text);
    let span = |v: &[f64]| {
        v.iter().cloned().fold(f64::NEG_INFINITY, f64::max) - v.iter().cloned().fold(f64::INFINITY, f64::min)
    };
    let solved = app.current().unwrap();
    let xs = &solved.solution.points.vertex_x;
    let reach = xs
        .iter()
        .zip(&solved.solution.pbar)
        .filter(|(_, p)| **p > 0.0)
        .map(|(x, _)| x.abs())
        .fold(0.0, f64::max);
    // The zone is under a tenth of the block: the zoomed axis spans the zone and its margin.
    assert!(reach < span(&before) / 20.0, "reach {reach}");
    assert!(
        span(&after) <= 2.0 * (2.0 * reach),
        "the zone and its margin: {after:?}, reach {reach}"
    );
    assert!(
        span(&after) >= 2.0 * reach * 0.9,
        "the whole zone: {after:?}, reach {reach}"
    );
    app.update(ch('z'));
    assert_eq!(x_labels(&frame(&app, 100, 30)), before);
    // The mesh scene says when it thins its lines.
    let text = render_to_string(&Scenario::paper(), "mesh", 80, 24, Some(4), None, None, None)
        .unwrap()
        .text;
    assert!(text.contains(" grid lines"), "{text}");
}

/// Item 10: the key that closes the help does nothing else; a key that does nothing says
/// why; ranges read "a to b"; Ctrl-Z suspends; `0` resets.
#[test]
fn keys_say_why_and_close_help_only() {
    let mut app = App::new(Scenario::paper());
    app.update(ch('?'));
    app.update(ch(']'));
    assert!(!app.show_help);
    assert_eq!(
        app.settings.level,
        Scenario::paper().level,
        "] only closed the help"
    );
    app.settings.level = MAX_APP_LEVEL;
    app.update(ch(']'));
    let notice = app.notice.clone().expect("says why").text;
    assert!(
        notice.contains("level 7") && notice.contains("level 8"),
        "{notice}"
    );
    // Whole on an 80-column status line (the cost is composed from `level_8_cost!`).
    assert!(notice.chars().count() < 80, "{notice}");
    app.settings.level = 0;
    app.update(key(KeyCode::Left));
    assert!(app.notice.is_some());
    for _ in 0..20 {
        app.update(ch('-'));
    }
    let notice = app.notice.clone().unwrap().text;
    assert!(
        notice.contains("1e-14 to 1e2") && !notice.contains("..="),
        "{notice}"
    );
    let effect = app.update(Msg::Key(KeyEvent::new(KeyCode::Char('z'), KeyModifiers::CONTROL)));
    assert_eq!(effect.commands, [Command::Suspend]);
    app.update(ch('D'));
    app.update(ch('2'));
    app.update(ch('g'));
    app.update(ch('0'));
    assert_eq!(app.settings, App::new(Scenario::paper()).settings);
    assert!(!app.show_gap);
    // No Hertz solution for a punch.
    let punch = Scenario::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenarios/flat-punch.toml"
    )))
    .unwrap();
    let mut app = App::new(punch);
    app.update(ch('h'));
    assert!(!app.show_hertz);
    assert!(app.notice.unwrap().text.contains("no Hertz"));
}

/// Item 11: the too-small message wraps to fit; units on the axes; kernel spelled out; the
/// convergence scene says whose ε; render explains its level range and lists every scene.
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
    let (code, _, err) = crate::common::riplab(&["render", "--level", "8", "--size", "80x24"]);
    assert_eq!(code, 2);
    assert!(err.contains("0 to 7") && err.contains("level 8 takes"), "{err}");
    let (_, help, _) = crate::common::riplab(&["render", "--help"]);
    for scene in Scene::ALL {
        assert!(help.contains(scene.name()), "{scene:?} in\n{help}");
    }
    assert!(
        help.contains("0 to 7") && help.contains("Mesh level 0 to 7"),
        "{help}"
    );
    // Started without a terminal, the lab says what to use instead.
    let (code, _, err) = crate::common::riplab(&[]);
    assert_eq!(code, 2);
    assert!(err.contains("riplab render"), "{err}");
}

/// Item 11: at level 5 the raw p is drawn over p̄ (its cells keep their colour).
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
    let status = frame(&app, 80, 24).lines().last().unwrap().to_string();
    assert!(
        status.contains("⟳ building level 7 for nitsche (1049088 unknowns) · about 7 s left"),
        "{status}"
    );
}

/// Item 12: the README's sample frame is what `riplab render` prints for the command it names.
#[test]
fn readme_frame_is_rendered() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let marker = "this is `riplab render ";
    let at = readme.find(marker).expect("the README names its render command");
    let rest = &readme[at + marker.len() - "render ".len()..];
    let command = &rest[..rest.find('`').unwrap()];
    let args: Vec<&str> = command.split_whitespace().collect();
    let fence = rest.find("```\n").unwrap() + 4;
    let frame = &rest[fence..fence + rest[fence..].find("```").unwrap()];
    let (code, out, err) = crate::common::riplab(&args);
    assert_eq!(code, 0, "{err}");
    assert_eq!(frame, out, "the README's frame differs from `riplab {command}`");
}

/// Issue 10, item 2: the lab's status line says what is known to be poor about the answer.
#[test]
fn the_status_line_shows_warnings() {
    let locking = crate::common::paper_with(&[("poisson", "poisson = 0.4999999")]);
    let mut app = App::new(locking.clone());
    app.show_timing = false;
    settle(&mut app, &mut Engine::new(locking));
    let text = frame(&app, 160, 40);
    let status = text.lines().last().unwrap();
    assert!(status.contains("⚠") && status.contains("locks"), "{status}");
    // The paper's problem has none.
    let text = frame(&settled(1, Scene::Explore), 160, 40);
    assert!(!text.lines().last().unwrap().contains("⚠"));
}

/// Issue 13 (every level step instant): a solve on another mesh or rule starts its Newton
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
fn finished(scenario: &Scenario, level: u32, element: Element) -> riplab::tui::worker::Built {
    Ok(riplab::tui::worker::Finished {
        disc: Arc::new(riplab::solve::Discretization::of(scenario, level, element).unwrap()),
        build_ms: Some(1.0),
        prepare_ms: None,
    })
}

/// Issue 13 item 4: meshes built for inf-sup estimates (the explore scene's table asks for
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

/// Issue 13 item 4: when idle, the engine names the next finer, then the next coarser level
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
    let too_large = riplab::error::SolveError::TooLarge("test".into());
    engine.adopt(MAX_APP_LEVEL - 1, Element::Q2, Err(too_large), Use::Background);
    assert_eq!(engine.next_prefetch(), None, "not retried");
}

/// Issue 13 item 4: the lab keeps (and builds in the background) level 7 beside level 6 with
/// Q1 or P1, and Q2's level 6 beside its level 5, but not Q2's level 7 (as many unknowns as
/// Q1's level 8), whose estimate alone exceeds the budget.
#[test]
fn the_cache_budget_holds_level_7_of_q1_not_of_q2() {
    use riplab::solve::Discretization;
    use riplab::tui::worker::CACHE_BYTES;
    let scenario = Scenario::paper();
    let engine = Engine::new(scenario.clone());
    let gib = |l, e| Discretization::sizes(&scenario, l, e).peak_bytes() as f64 / f64::from(1 << 30);
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

/// Issue 13 item 4, end to end: a worker left idle after a solve builds the next level in
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
    // Levels 3 and 1 take milliseconds each; two seconds leave room for a loaded machine.
    std::thread::sleep(Duration::from_secs(2));
    let seen = solve(2, 3);
    assert!(!assembling(&seen), "level 3 was built while idle: {seen:?}");
}

/// A worker on the paper's problem and the replies it sends: for the tests of the order in
/// which it answers.
struct PaperWorker {
    worker: riplab::tui::worker::Worker,
    replies: std::sync::mpsc::Receiver<Response>,
}

impl PaperWorker {
    fn spawn() -> Self {
        let (tx, replies) = std::sync::mpsc::channel();
        let worker = riplab::tui::worker::Worker::spawn(Scenario::paper(), move |r| tx.send(r).is_ok());
        PaperWorker { worker, replies }
    }

    /// Ask for a solve of the lab's default settings at `level`.
    fn solve(&self, generation: u64, level: u32) {
        self.solve_by(generation, level, App::defaults(&Scenario::paper()).method);
    }

    /// Ask for a solve of the lab's default settings at `level` by Nitsche's method (θ = 1,
    /// γ₀ auto); its key.
    fn solve_by_nitsche(&self, generation: u64, level: u32) -> riplab::tui::app::SolveKey {
        use riplab::contact::{Method, method::Gamma0};
        let nitsche = Method::Nitsche {
            theta: 1,
            gamma0: Gamma0::Auto,
        };
        self.solve_by(generation, level, nitsche)
    }

    fn solve_by(
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

    /// The next reply (two minutes at most).
    fn next(&self) -> Response {
        self.replies
            .recv_timeout(std::time::Duration::from_secs(120))
            .expect("the worker answers")
    }
}

/// Issue 13 item 4: a level that is not built is built beside the worker, which keeps
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

/// Issue 13 item 4: an inf-sup estimate (seconds at level 7: the H¹ form's factorisation and
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
    // Let the worker start the estimate, then ask for a solve of the same generation.
    std::thread::sleep(Duration::from_millis(20));
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

/// Issue 13 (every level step instant): the displacement of a solution (a quarter of a second
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
    // 20 ms into the work on level 6, a solve of level 1 is answered before it, and the work's
    // reply still comes.
    let answered_first = |generation, work: &str, of_work: &dyn Fn(&Response) -> bool| {
        std::thread::sleep(Duration::from_millis(20));
        solve(generation, 1);
        loop {
            match next() {
                Response::Solved { generation: g, .. } if g == generation => break,
                r if of_work(&r) => panic!("the solve waited for the {work}: {r:?}"),
                _ => {}
            }
        }
        while !of_work(&next()) {}
    };
    answered_first(
        3,
        "displacement",
        &|r| matches!(r, Response::Displaced { key } if key.level == 6),
    );
    // The stresses of level 6, then a solve.
    worker.send(&Command::Stresses(StressRequest { solved: fine.clone() }));
    answered_first(
        4,
        "stresses",
        &|r| matches!(r, Response::Stresses { key } if key.level == 6),
    );
    assert!(fine.stresses.get().is_some_and(|s| s.is_ok()));
    // The study of levels 0..=4 (M1–M4 against Q2's level 5), then a solve.
    let mut app = App::new(Scenario::paper());
    app.settings.level = 4;
    let study = app.study_key();
    worker.send(&Command::Study(StudyRequest {
        generation: 5,
        key: study.clone(),
    }));
    answered_first(
        6,
        "study",
        &|r| matches!(r, Response::Study { key, .. } if *key == study),
    );
}

/// Issue 13 item 4 for Nitsche's method: its preparation on a built mesh (another
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
    // Idle, the worker builds level 6 for the penalty (about a second).
    std::thread::sleep(std::time::Duration::from_millis(200));
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
    // The preparation is announced last; when the background build had begun (it has, but
    // for a scheduler that held the worker back 200 ms), the build first.
    assert_eq!(told.last(), Some(&(6, Some("nitsche"))), "{told:?}");
    assert!(
        told.len() == 1 || told == [(6, None), (6, Some("nitsche"))],
        "{told:?}"
    );
}

/// Issue 13 item 4: an estimate that waits for its mesh says so with the build's time left
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
    let status = frame(&app, 80, 24).lines().last().unwrap().to_string();
    assert!(
        status.contains("estimate(s) · building q2 level 7 · about 27 s left"),
        "{status}"
    );
    app.update(Msg::Worker(Response::InfSup {
        key: m4,
        result: Some(Err("test".into())),
    }));
    assert!(app.infsup_building().is_none() && !app.wants_tick());
}

/// Issue 13 item 4: a level whose build the memory guard refuses answers the solve that
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
            assert!(e.contains("needs about") && e.contains("coarser level"), "{e}");
            break;
        }
    }
}

/// Issue 13 item 4: coming back to the solution shown while a solve of other settings is
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
    riplab::tui::worker::carry_out(&mut app, &mut engine, commands);
    assert!(shown.displacement.get().is_some());
    assert!(!frame(&app, 100, 30).contains("computing the displacement"));
}

/// Issue 13 item 4: a solve's reply carries the pressures at once; the displacement (a solve
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

/// Issue 11 item 3: the key table drives the dispatch: every key it binds is handled by the
/// lab (the frame changes or a notice says why not), and a key it does not bind is not.
#[test]
fn every_key_of_the_table_is_handled_and_no_other() {
    use riplab::tui::keys::{CONTROL, LAB};
    for row in LAB {
        for &(code, action) in row.bindings {
            let mut app = App::new(Scenario::paper());
            assert!(app.update(key(code)).redraw, "{code:?} ({action:?}) does nothing");
        }
    }
    for row in CONTROL {
        for &(code, action) in row.bindings {
            let mut app = App::new(Scenario::paper());
            let ctrl = Msg::Key(KeyEvent::new(code, KeyModifiers::CONTROL));
            assert!(app.update(ctrl).redraw, "Ctrl {code:?} ({action:?}) does nothing");
        }
    }
    let mut app = App::new(Scenario::paper());
    assert!(!app.update(key(KeyCode::Char('x'))).redraw);
    assert!(!app.update(key(KeyCode::F(5))).redraw);
}

/// Issue 14: `m` cycles the method (penalty → exact → alm → nitsche → penalty); each change
/// re-solves, the line under the pressure chart names the method, what it needs and its
/// iteration counts (the ALM's updates and inner Newton steps), at 80×24 too.
#[test]
fn the_method_key_cycles_and_the_method_line_shows() {
    let mut engine = Engine::new(Scenario::paper());
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.settings.level = 1;
    app.settings.epsilon = 1e-3;
    settle(&mut app, &mut engine);
    let line = |app: &App| {
        frame(app, 80, 24)
            .lines()
            .find(|l| l.contains("needs"))
            .map(str::to_string)
            .unwrap_or_default()
    };
    assert!(
        line(&app).contains("penalty: needs ε > 0"),
        "{}",
        frame(&app, 80, 24)
    );
    let penalty_load = app.current().unwrap().solution.load;
    let mut seen = Vec::new();
    for _ in 0..4 {
        let commands = app.update(ch('m')).commands;
        riplab::tui::worker::carry_out(&mut app, &mut engine, commands);
        seen.push(app.settings.method.name());
        let text = frame(&app, 80, 24);
        match app.settings.method.name() {
            "exact" => assert!(line(&app).contains("exact: needs inf-sup"), "{text}"),
            "alm" => {
                let l = line(&app);
                assert!(l.contains("alm: needs ε > 0 (no ε error)"), "{text}");
                let sol = &app.current().unwrap().solution;
                let outer = sol.outer_iterations.unwrap();
                // Warm-started from `exact`'s multipliers: one update confirms them.
                let plural = if outer == 1 { "" } else { "s" };
                assert!(
                    l.contains(&format!(
                        "{outer} update{plural} × {} Newton",
                        sol.newton.iterations
                    )),
                    "{l}"
                );
                // The ALM at ε = 1e-3 carries the exact load, not the penalty's.
                assert!(
                    sol.load > 1.3 * penalty_load,
                    "{} against {penalty_load}",
                    sol.load
                );
                assert!(text.contains("alm ε=1e-3"), "the header names the method: {text}");
            }
            "nitsche" => {
                assert!(line(&app).contains("nitsche: needs γ₀"), "{text}");
                let sol = &app.current().unwrap().solution;
                assert!(sol.newton.converged && sol.load > 0.0, "{text}");
            }
            _ => assert!(line(&app).contains("penalty"), "{text}"),
        }
    }
    assert_eq!(seen, ["exact", "alm", "nitsche", "penalty"]);
}

/// The settings line at 80 columns never cuts a number: with a long method label (Nitsche's
/// parameters) at the finest level, the counts and then the parameters give way and the depth
/// is whole ("d=0" was drawn for d = 0.8).
#[test]
fn the_settings_line_drops_fields_rather_than_cutting_a_number() {
    use riplab::contact::Method;
    use riplab::contact::method::Gamma0;
    for method in [
        Method::Penalty,
        Method::Exact,
        Method::Alm { tolerance: 1e-10 },
        Method::Nitsche {
            theta: -1,
            gamma0: Gamma0::Given(100.0),
        },
        Method::Nitsche {
            theta: 1,
            gamma0: Gamma0::Auto,
        },
    ] {
        for level in [0, MAX_APP_LEVEL] {
            let mut app = App::new(Scenario::paper());
            (app.settings.method, app.settings.level) = (method, level);
            app.settings.rule = Rule::Trapezoid;
            let text = render_app(&app, &LOOK, 80, 24);
            let line = text.lines().nth(1).unwrap().trim_end();
            assert!(line.ends_with("│ d=0.8"), "{method:?} level {level}: {line}");
            assert!(line.contains(&format!("level {level} ")), "{line}");
        }
    }
}

/// Issue 31, hidden series: a series equal to an earlier one (as M1's β̄_h/√h equals M3's
/// β_h/√h, by (18)) is said to coincide in the legend, and its glyph stands beside the
/// other's at every point instead of under it; a series elsewhere keeps its cells.
#[test]
fn coinciding_series_are_named_and_both_drawn() {
    let same = [(-1.0, 0.0), (-0.5, 0.02), (0.0, 0.05)];
    let apart = [(-1.0, -1.0), (-0.5, -0.9), (0.0, -0.8)];
    for (width, height) in [(80, 14), (120, 30), (40, 10)] {
        let mut terminal = ratatui::Terminal::new(TestBackend::new(width, height)).unwrap();
        terminal
            .draw(|f| {
                let series = |name: &str, glyph: char, data| PlotSeries {
                    name: name.into(),
                    color: Color::Green,
                    stroke: Stroke::None,
                    glyph: Some(glyph),
                    data,
                };
                Plot {
                    title: " test ".into(),
                    x: PlotAxis {
                        title: "h".into(),
                        bounds: [-1.2, 0.2],
                        scale: Scale::Log10,
                    },
                    y: PlotAxis {
                        title: "β".into(),
                        bounds: [-1.5, 0.5],
                        scale: Scale::Log10,
                    },
                    series: vec![
                        series("M3", '3', &same[..]),
                        series("M4", '4', &apart[..]),
                        series("M1 p̄", '*', &same[..]),
                    ],
                    marker: Marker::Braille,
                    theme: Theme { color: false },
                }
                .render(f, f.area())
                .expect("room for the graph");
            })
            .unwrap();
        let buf = terminal.backend().buffer().clone();
        let text: Vec<String> = (0..height).map(|y| row_text(&buf, y).concat()).collect();
        let legend = text[1..3].concat();
        assert!(legend.contains("M1 p̄ (= 3)"), "{width}×{height}: {legend}");
        assert!(!legend.contains("M4 (="), "{width}×{height}: {legend}");
        let at = |g: &str| -> Vec<(u16, u16)> {
            let mut out = Vec::new();
            for y in 2..height {
                for x in 0..width {
                    if buf[(x, y)].symbol() == g {
                        out.push((x, y));
                    }
                }
            }
            out
        };
        let (threes, stars, fours) = (at("3"), at("*"), at("4"));
        assert_eq!(threes.len(), 3, "{width}×{height}:\n{}", text.join("\n"));
        assert_eq!(stars.len(), 3, "{width}×{height}:\n{}", text.join("\n"));
        assert_eq!(fours.len(), 3, "{width}×{height}:\n{}", text.join("\n"));
        for (t, s) in threes.iter().zip(&stars) {
            assert_eq!(t.1, s.1, "same row");
            assert_eq!(t.0.abs_diff(s.0), 1, "side by side: {t:?} {s:?}");
        }
    }
}
