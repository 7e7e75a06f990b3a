//! The lab solves with the scenario's `[friction]` and shows the
//! numbers `riplab solve` prints (checked against the library's own entry on the command
//! line's full-trace discretisation); every key that names a solve carries the friction; the
//! refusals (Nitsche, a half model, edge grading) are said, never silent; the friction keys.

use std::hash::{BuildHasher, RandomState};
use std::ops::ControlFlow;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use riplab::contact::friction::{Friction, Law};
use riplab::contact::mindlin::stick_half_width;
use riplab::contact::newton::NewtonOptions;
use riplab::discretization::Trace;
use riplab::output::{FrictionReport, MindlinReport};
use riplab::scenario::Scenario;
use riplab::solve::solve_friction;
use riplab::tui::app::{App, Msg};
use riplab::tui::engine::Engine;
use riplab::tui::settle::{carry_out, settle};
use riplab::tui::theme::Theme;
use riplab::tui::view::Look;

/// Monochrome braille, as a projector without colour shows it.
pub const LOOK: Look = Look {
    theme: Theme { color: false },
    marker: ratatui::symbols::Marker::Braille,
};

/// `scenarios/cattaneo-mindlin.toml`.
pub fn cattaneo() -> Scenario {
    Scenario::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenarios/cattaneo-mindlin.toml"
    )))
    .unwrap()
}

/// `scenarios/hertz-paper-full.toml`.
pub fn paper_full() -> Scenario {
    Scenario::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenarios/hertz-paper-full.toml"
    )))
    .unwrap()
}

/// The lab on `scenario` at `level`, solved, timings hidden.
pub fn lab(scenario: &Scenario, level: u32) -> (App, Engine) {
    let mut app = App::new(scenario.clone());
    app.show_timing = false;
    app.settings.level = level;
    let mut engine = Engine::new(scenario.clone());
    settle(&mut app, &mut engine);
    (app, engine)
}

/// Press `keys` (characters) and run what they ask for.
pub fn press(app: &mut App, engine: &mut Engine, keys: &str) {
    for c in keys.chars() {
        let commands = app
            .update(Msg::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE)))
            .commands;
        carry_out(app, engine, commands);
    }
}

/// The last message of the status line (a friction key's "— re-solving" gives way to the
/// solve's readout when the solve arrives; the log keeps it).
fn said(app: &App) -> String {
    app.overlays
        .log
        .back()
        .map(|l| l.text.clone())
        .unwrap_or_default()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300)
}

/// Item 1's test: on cattaneo-mindlin at level 2 the lab's P, Q, stick half-width, Mindlin's c,
/// t̄'s distance from q and t̄ itself are those of the library's entry that `riplab solve`
/// calls, read through the same reports: to 1e-12 on the lab's kind of discretisation (the
/// normal trace, the tangential columns solved from its factor; measured: the same bits),
/// and to 1e-9 on the command line's full-trace one, whose factorisation orders the
/// unknowns otherwise — rounding of two factorisations of K at ν = 0.499 (measured: P
/// 1.4e-12 relative, t̄ 3.5e-11 of its peak, t̄'s distance from q 1.3e-11 relative).
#[test]
fn the_lab_solves_with_the_scenarios_friction_as_riplab_solve_does() {
    let scenario = cattaneo();
    let (app, _) = lab(&scenario, 2);
    let solved = app.current().expect("solved");
    assert_eq!(solved.key.friction, scenario.friction);
    assert!(solved.solution.newton.converged);
    let shown = solved.shown.friction.as_ref().expect("friction shown");
    for (trace, tol) in [(Trace::Normal, 1e-12), (Trace::Full, 1e-9)] {
        let disc = scenario.discretize_traced(2, scenario.element, trace).unwrap();
        let params = solved.solution.params.clone();
        let cli = solve_friction(
            &disc,
            &params,
            &scenario.friction,
            None,
            &NewtonOptions::default(),
            &mut |_| ControlFlow::Continue(()),
        )
        .unwrap();
        let close = |a: f64, b: f64| (a - b).abs() <= tol * a.abs().max(b.abs());
        let f = cli.friction.as_ref().unwrap();
        assert!(
            close(solved.solution.load, cli.load),
            "P {} vs {}",
            solved.solution.load,
            cli.load
        );
        assert!(close(shown.tangential_load, f.tangential_load), "{trace:?}");
        let report = FrictionReport::new(&cli);
        let mindlin = MindlinReport::new(&scenario, &cli).expect("Mindlin applies");
        assert!(close(shown.load_ratio.unwrap(), report.load_ratio.unwrap()));
        let width = stick_half_width(&cli.points, &f.states).unwrap().0;
        assert_eq!(shown.stick_half_width.unwrap(), width, "the same stick points");
        assert!(close(shown.mindlin.unwrap().c, mindlin.c));
        let (e, e_cli) = (shown.mindlin_error.unwrap(), mindlin.relative_error);
        assert!(close(e, e_cli), "{trace:?}: ‖t̄ − q‖/‖q‖ {e} vs {e_cli}");
        let scale = f.tbar.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(scale > 1.0, "a tangential traction: {scale}");
        assert_eq!(shown.tbar.len(), f.tbar.len());
        let off = shown
            .tbar
            .iter()
            .zip(&f.tbar)
            .fold(0.0f64, |m, (a, b)| m.max((a.1 - b).abs()));
        assert!(off <= tol * scale, "{trace:?}: t̄ off by {off:e} of {scale}");
    }
    // Independent of both: Q/(μP) from its definition, and c = a√(1 − Q/μP) from Hertz's a.
    let m = shown.mindlin.unwrap();
    let ratio = shown.tangential_load / (0.3 * solved.solution.load);
    assert!(close(shown.load_ratio.unwrap(), ratio));
    assert!((m.c - m.hertz.a * (1.0 - ratio).sqrt()).abs() <= 1e-12 * m.hertz.a);
}

/// The friction is part of every key that names a solve or a study — switched off,
/// the frictionless result is another solve (never the friction one shown for it), and a
/// study's key changes with it; the warm start of the next friction solve gives its answer.
#[test]
fn the_friction_is_part_of_every_key() {
    let scenario = cattaneo();
    let (mut app, mut engine) = lab(&scenario, 1);
    let with = app.current().unwrap().clone();
    let study = app.study_key();
    assert_eq!(*study.friction, scenario.friction);
    assert_eq!(
        study.label(),
        "M1–M4 (exact) with coulomb μ = 0.3, shift ξ = 0.0815",
        "the convergence scene says its study runs with the friction"
    );
    // F: coulomb → tresca → none.
    press(&mut app, &mut engine, "FF");
    assert_eq!(app.settings.friction.law, Law::None);
    let without = app.current().unwrap().clone();
    assert!(without.shown.friction.is_none() && without.solution.friction.is_none());
    assert_ne!(with.key, without.key);
    assert_ne!(app.study_key(), study);
    let state = RandomState::new();
    assert_ne!(state.hash_one(app.study_key()), state.hash_one(&study));
    // Back on: the same numbers as the cold solve (warm-started from the tresca solve's
    // forces on the same points).
    press(&mut app, &mut engine, "F");
    let again = app.current().unwrap();
    assert_eq!(again.key, with.key);
    let (a, b) = (
        again.shown.friction.as_ref().unwrap(),
        with.shown.friction.as_ref().unwrap(),
    );
    assert!(close(a.tangential_load, b.tangential_load));
    assert!(close(again.solution.load, with.solution.load));
}

/// Nitsche with friction and an edge-graded solve with friction are refused with the
/// library's (the lab's) reason in the banner and the status line, the last good frame kept.
#[test]
fn refused_friction_solves_say_why_and_keep_the_last_frame() {
    let scenario = cattaneo();
    let (mut app, mut engine) = lab(&scenario, 0);
    // exact → alm (solved) → nitsche.
    press(&mut app, &mut engine, "m");
    assert_eq!(app.settings.method.name(), "alm");
    let good = app.current().expect("alm takes friction").clone();
    assert!(good.solution.friction.is_some());
    press(&mut app, &mut engine, "m");
    assert_eq!(app.settings.method.name(), "nitsche");
    let error = app.error.as_ref().expect("refused").to_string();
    assert!(error.contains("not nitsche"), "{error}");
    assert!(std::sync::Arc::ptr_eq(app.solved.as_ref().unwrap(), &good));
    let frame = riplab::tui::render_app(&app, &LOOK, 80, 24);
    assert!(frame.contains("not nitsche"), "{frame}");
    assert!(frame.contains("no result for these settings"), "{frame}");
    // Back to exact, then edge grading: refused, saying how to go on.
    press(&mut app, &mut engine, "mm");
    assert_eq!(app.settings.method.name(), "exact");
    assert!(app.error.is_none());
    // Edge grading: refused before anything changes (the refusal alone, the settings kept).
    let before = app.settings;
    press(&mut app, &mut engine, "E");
    assert_eq!(app.settings, before);
    assert!(app.error.is_none());
    let notice = app.notice.clone().expect("refused");
    assert!(notice.failure, "{notice:?}");
    assert!(
        notice
            .text
            .contains("grading (at the edges or over the zone) does not take friction"),
        "{notice:?}"
    );
}

/// On a half model `F` does nothing and says why, naming `body.model` and the full
/// scenarios; the friction keys say what they did, or why not (off, at a bound).
#[test]
fn the_friction_keys_say_what_they_did() {
    let (mut app, mut engine) = lab(&Scenario::paper(), 0);
    let before = app.settings;
    press(&mut app, &mut engine, "F");
    assert_eq!(app.settings, before);
    let notice = app.notice.clone().unwrap();
    assert!(notice.failure, "{notice:?}");
    assert!(
        notice.text.contains("body.model = \"full\"") && notice.text.contains("cattaneo-mindlin.toml"),
        "{notice:?}"
    );
    for k in ["u", "U", "<", ">"] {
        press(&mut app, &mut engine, k);
        let text = app.notice.clone().unwrap().text;
        assert!(text.contains("friction is off (F switches it on)"), "{k}: {text}");
        assert_eq!(app.settings, before);
    }

    // A full model without [friction]: F switches Coulomb on at μ = 0.3 and ξ₀ = 2% of the
    // width the cylinder cuts through the top at d (2√(2Rd − d²), R = 8, d = 0.8).
    let (mut app, mut engine) = lab(&paper_full(), 0);
    press(&mut app, &mut engine, "F");
    let width = 2.0 * (2.0f64 * 8.0 * 0.8 - 0.8 * 0.8).sqrt();
    let xi0 = app.settings.friction.shift;
    assert!(
        (xi0 - 0.02 * width).abs() <= 5e-3 * xi0,
        "{xi0} vs {}",
        0.02 * width
    );
    assert_eq!(app.settings.friction.law, Law::Coulomb { mu: 0.3 });
    let text = said(&app);
    assert_eq!(
        text,
        format!(
            "friction: coulomb μ = 0.3, shift ξ = {} — re-solving",
            riplab::text::num(xi0)
        )
    );
    let solved = app.current().unwrap();
    assert!(solved.solution.newton.converged && solved.shown.friction.is_some());
    assert!(app.notice.is_none(), "the readout, once solved: {:?}", app.notice);
    // u/U through the list, to its ends.
    press(&mut app, &mut engine, "U");
    assert_eq!(app.settings.friction.law, Law::Coulomb { mu: 0.4 });
    press(&mut app, &mut engine, "uuuuuu");
    assert_eq!(app.settings.friction.law, Law::Coulomb { mu: 0.0 });
    let text = app.notice.clone().unwrap().text;
    assert!(text.contains("μ = 0 ends the lab's list"), "{text}");
    // > and < by 1.25, three digits.
    press(&mut app, &mut engine, ">");
    assert_eq!(
        app.settings.friction.shift,
        riplab::tui::friction_settings::round3(xi0 * 1.25)
    );
    assert!(said(&app).contains("shift ξ = "));
    // Tresca: g = μ × the shown p̄'s peak (μ at least 0.3), then ×/÷ 1.25.
    press(&mut app, &mut engine, "F");
    let Law::Tresca { threshold } = app.settings.friction.law else {
        panic!("{:?}", app.settings.friction)
    };
    assert!(threshold > 0.0);
    press(&mut app, &mut engine, "U");
    assert_eq!(
        app.settings.friction.law,
        Law::Tresca {
            threshold: riplab::tui::friction_settings::round3(threshold * 1.25)
        }
    );
    assert!(app.current().unwrap().solution.newton.converged);
    press(&mut app, &mut engine, "F");
    assert_eq!(app.settings.friction.law, Law::None);
    assert_eq!(said(&app), "friction off — re-solving");
    // 0 returns to the scenario's (frictionless) settings.
    press(&mut app, &mut engine, "0");
    assert_eq!(app.settings.friction, Friction::NONE);
}

/// The friction keys are in the help overlay, docs/lab.md's key table and `riplab
/// render --help`'s list, with the same words; `render --keys` can press them (`<lt>` is `<`),
/// and they act as in the lab.
#[test]
fn the_friction_keys_are_documented_everywhere() {
    let help = riplab::tui::keys::lab_help();
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/lab.md")).unwrap();
    let render = riplab::tui::keys::with_lab_keys("");
    for (keys, what) in [
        ("F", "friction law: none, coulomb, tresca"),
        ("u  U", "friction μ (or g) down / up a step"),
        ("<  >", "shift ξ ÷ 1.25 / × 1.25 after the press"),
    ] {
        assert!(help.contains(&(keys, what)), "{keys} in the help");
        let ticked: Vec<String> = keys.split_whitespace().map(|k| format!("`{k}`")).collect();
        let row = format!("| {} | {what} |", ticked.join(" "));
        assert!(readme.contains(&row), "{row} in docs/lab.md");
        assert!(
            render.contains(&format!("  {keys:<16}{what}\n")),
            "{keys} in render --help"
        );
    }
    let scenario = cattaneo();
    let (mut app, mut engine) = lab(&scenario, 0);
    for key in riplab::tui::render_keys::parse_keys("<lt>U").unwrap() {
        let commands = app.update(Msg::Key(key)).commands;
        carry_out(&mut app, &mut engine, commands);
    }
    assert_eq!(app.settings.friction.shift, 0.0652, "0.0815 ÷ 1.25");
    assert_eq!(app.settings.friction.law, Law::Coulomb { mu: 0.4 });
    let solved = app.current().unwrap();
    assert_eq!(solved.solution.friction.as_ref().unwrap().friction.shift, 0.0652);
}

/// An export's name carries the friction (a friction solve's file never takes a
/// frictionless one's name), and its CSV the tangential columns.
#[test]
fn an_export_names_the_friction() {
    let (app, _) = lab(&cattaneo(), 0);
    let solved = app.current().unwrap();
    let stem = riplab::tui::export::stem(&app.scenario, solved);
    assert!(stem.ends_with("-d0.35-coulomb0.3-xi0.0815"), "{stem}");
    let (plain, _) = lab(&paper_full(), 0);
    let stem = riplab::tui::export::stem(&plain.scenario, plain.current().unwrap());
    assert!(stem.ends_with("-d0.8"), "{stem}");
}

/// Item 1, the lab's `T`: a step written from a lab whose friction differs from the
/// scenario's carries it (law, μ, shift), and the tour plays it back with the same friction;
/// a step's friction keys are validated like the scenario's, naming the key.
#[test]
fn a_tour_step_carries_the_friction() {
    use riplab::tui::tour::Tour;
    let (mut app, mut engine) = lab(&cattaneo(), 0);
    press(&mut app, &mut engine, "U>");
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/cattaneo-mindlin.toml");
    let step = riplab::tui::tour::author::step_toml(&app, Some(path));
    assert!(
        step.contains("friction = \"coulomb\"\nmu = 0.4\nshift = 0.102\n"),
        "{step}"
    );
    let text = format!("title = \"friction\"\n{step}");
    let tour = Tour::parse(&text, "t.toml", Some(std::path::Path::new("/"))).unwrap();
    assert_eq!(tour.app(0).settings.friction, app.settings.friction);
    // The scenario's own friction is not written.
    let (plain, _) = lab(&cattaneo(), 0);
    assert!(!riplab::tui::tour::author::step_toml(&plain, None).contains("friction"));
    for (keys, key, says) in [
        ("mu = 0.3", "step[1].mu", "give friction = \"coulomb\""),
        ("friction = \"coulomb\"\nmu = -1.0", "step[1].mu", "μ ≥ 0"),
        ("friction = \"tresca\"", "step[1].threshold", "threshold"),
        ("friction = \"stiction\"", "step[1].friction", "stiction"),
    ] {
        let text = format!("title = \"t\"\n[[step]]\ntitle = \"s\"\ncaption = \"c\"\n{keys}\n");
        let e = Tour::parse(&text, "t.toml", None).unwrap_err().to_string();
        assert!(
            e.contains(key) && e.contains(says) && e.contains("t.toml"),
            "{keys}: {e}"
        );
    }
}
