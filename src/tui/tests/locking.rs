//! The header shows ν and the volumetric
//! integration where locking is the lesson (a selective integration, or ν from 0.495 with the
//! full one), at 80 and 120 columns; the paper's ν = 0.3 with full integration does not.

use riplab::fem::Integration;
use riplab::scenario::Scenario;
use riplab::tui::app::App;
use riplab::tui::render_app;

const LOOK: riplab::tui::view::Look = riplab::tui::view::Look {
    theme: riplab::tui::theme::Theme { color: false },
    marker: ratatui::symbols::Marker::Braille,
};

fn header(scenario: Scenario, width: u16) -> String {
    let frame = render_app(&App::new(scenario), &LOOK, width, 24);
    frame.lines().nth(1).unwrap().to_string()
}

#[test]
fn the_header_shows_nu_and_the_integration_where_locking_is_the_lesson() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/near-incompressible.toml");
    let scenario = Scenario::load(std::path::Path::new(path)).unwrap();
    assert_eq!(scenario.integration, Integration::Selective);
    for width in [80, 120] {
        let line = header(scenario.clone(), width);
        assert!(line.ends_with("│ ν=0.49 selective"), "{line}");
        assert!(line.chars().count() <= usize::from(width), "{line}");
    }
    let mut locking = Scenario::paper();
    locking.material.poisson = 0.4999999;
    assert!(header(locking, 80).ends_with("│ ν=0.4999999 full"));
    let paper = header(Scenario::paper(), 120);
    assert!(!paper.contains('ν'), "{paper}");
}

fn press_i(app: &mut riplab::tui::app::App, engine: &mut riplab::tui::engine::Engine) {
    use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
    let commands = app
        .update(riplab::tui::app::Msg::Key(KeyEvent::new(
            KeyCode::Char('i'),
            KeyModifiers::NONE,
        )))
        .commands;
    riplab::tui::settle::carry_out(app, engine, commands);
}

/// The library's solve of `scenario` integrated as `integration`: its load P.
fn library_load(scenario: &Scenario, integration: Integration) -> f64 {
    let scenario = Scenario {
        integration,
        ..scenario.clone()
    };
    riplab::solve::solve_scenario(&scenario).unwrap().1.load
}

/// The key: `i` switches near-incompressible's volumetric integration, says
/// what it set, the header shows it, the load shown is the library's solve with that
/// integration (the scenario file's own numbers: 1289.7 selective, 1311.8 full at level 2),
/// and switching back serves the first solve's mesh from the cache (a stale mesh was served
/// before the integration joined the engine's cache key: it had none).
#[test]
fn i_switches_the_integration_and_the_lab_solves_with_it() {
    use riplab::tui::engine::Engine;
    use riplab::tui::settle::settle;
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/near-incompressible.toml");
    let scenario = Scenario::load(std::path::Path::new(path)).unwrap();
    let mut app = App::new(scenario.clone());
    let mut engine = Engine::new(scenario.clone());
    settle(&mut app, &mut engine);
    let first = app.current().expect("the selective solve").clone();
    let selective = library_load(&scenario, Integration::Selective);
    let full = library_load(&scenario, Integration::Full);
    assert!((first.solution.load - selective).abs() <= 1e-12 * selective);
    assert_eq!((selective * 10.0).round(), 12897.0, "{selective}");
    assert_eq!((full * 10.0).round(), 13118.0, "{full}");

    press_i(&mut app, &mut engine);
    let notice = &app.notice.as_ref().expect("what i set").text;
    assert!(notice.starts_with("integration full:"), "{notice}");
    assert!(notice.contains("ν = 0.49"), "{notice}");
    let shown = app.current().expect("the full solve").clone();
    assert_eq!(shown.key.integration, Integration::Full);
    let load = shown.solution.load;
    assert!((load - full).abs() <= 1e-12 * full, "{load} against {full}");
    let frame = render_app(&app, &LOOK, 80, 24);
    let line = frame.lines().nth(1).unwrap();
    assert!(line.ends_with("│ ν=0.49 full"), "{line}");
    let said = "integration full: λ div u exact (Q1 locks as ν → ½; ν = 0.49)";
    assert!(
        frame.lines().any(|l| l.contains(said)),
        "said in one row\n{frame}"
    );
    assert!(!std::sync::Arc::ptr_eq(&shown.disc, &first.disc));

    press_i(&mut app, &mut engine);
    let back = app.current().expect("the selective solve again").clone();
    assert!(
        std::sync::Arc::ptr_eq(&back.disc, &first.disc),
        "the first mesh, from the cache"
    );
    let load = back.solution.load;
    assert!(
        (load - selective).abs() <= 1e-12 * selective,
        "{load} against {selective}"
    );
    let notice = &app.notice.as_ref().unwrap().text;
    assert!(notice.starts_with("integration selective:"), "{notice}");
    let frame = render_app(&app, &LOOK, 80, 24);
    assert!(
        frame.lines().nth(1).unwrap().ends_with("│ ν=0.49 selective"),
        "{frame}"
    );
}

/// Where it makes no difference to speak of (P1's constant strains), `i` still says what it
/// set, and why it changes nothing; on the paper's ν = 0.3 the header shows the switch.
#[test]
fn i_says_what_it_set_where_it_changes_nothing() {
    use riplab::mesh::Element;
    let mut app = App::new(Scenario::paper());
    app.settings.element = Element::P1;
    let mut engine = riplab::tui::engine::Engine::new(Scenario::paper());
    press_i(&mut app, &mut engine);
    let notice = &app.notice.as_ref().unwrap().text;
    assert!(notice.starts_with("integration selective:"), "{notice}");
    assert!(notice.contains("p1's strains are constant"), "{notice}");
    assert_eq!(app.settings.integration, Integration::Selective);
    let frame = render_app(&app, &LOOK, 80, 24);
    assert!(
        frame.lines().nth(1).unwrap().ends_with("│ ν=0.3 selective"),
        "{frame}"
    );
}

/// A tour step takes `integration` like the other mesh settings, and `T` writes it when the
/// lab's differs from the scenario's: the step plays back with it.
#[test]
fn a_tour_step_carries_the_integration() {
    use riplab::tui::tour::Tour;
    use riplab::tui::tour::author::{LabSource, save_step};
    let dir = std::env::temp_dir().join(format!("riplab-integration-tour-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let source = LabSource {
        tour_out: dir.join("t.toml"),
        scenario_file: None,
    };
    let mut app = App::new(Scenario::paper());
    assert!(!save_step(&app, &source).failure);
    app.settings.integration = Integration::Selective;
    assert!(!save_step(&app, &source).failure);
    let written = std::fs::read_to_string(&source.tour_out).unwrap();
    assert_eq!(
        written.matches("integration = \"selective\"\n").count(),
        1,
        "{written}"
    );
    let tour = Tour::load(&source.tour_out).unwrap();
    assert_eq!(tour.steps[0].integration, None);
    assert_eq!(tour.steps[1].integration, Some(Integration::Selective));
    assert_eq!(tour.app(0).settings.integration, Integration::Full);
    assert_eq!(tour.app(1).settings.integration, Integration::Selective);
    let bad = "title = \"t\"\n[[step]]\ntitle = \"a\"\ncaption = \"b\"\nintegration = \"half\"\n";
    let e = Tour::parse(bad, "bad.toml", None).unwrap_err().to_string();
    assert!(e.contains("integration") && e.contains("selective"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The stresses of a solve switched to full integration are those of its own mesh's
/// integration, not the scenario's (selective, whose volumetric stress is taken at the
/// reduced points).
#[test]
fn the_stresses_follow_the_solves_integration() {
    use riplab::stress::StressField;
    use riplab::tui::engine::Engine;
    use riplab::tui::settle::settle;
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/near-incompressible.toml");
    let mut scenario = Scenario::load(std::path::Path::new(path)).unwrap();
    scenario.level = 1;
    let mut app = App::new(scenario.clone());
    let mut engine = Engine::new(scenario.clone());
    press_i(&mut app, &mut engine);
    settle(&mut app, &mut engine);
    let solved = app.current().unwrap().clone();
    assert_eq!(solved.key.integration, Integration::Full);
    let shown = solved.stress_field(&scenario).unwrap();
    let u = solved.u();
    let full = StressField::new(&solved.disc.mesh, &scenario.material, Integration::Full, u).unwrap();
    let selective =
        StressField::new(&solved.disc.mesh, &scenario.material, Integration::Selective, u).unwrap();
    assert!(shown.elements == full.elements && shown.nodal == full.nodal);
    assert!(shown.elements != selective.elements);
}
