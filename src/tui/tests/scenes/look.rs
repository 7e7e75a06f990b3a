//! How the lab looks: styles, legends, glyphs.

use super::*;

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
    let levels = |commands: &[Command]| -> Vec<u32> {
        let mut out: Vec<u32> = commands
            .iter()
            .filter_map(|c| match c {
                Command::InfSup(r) => Some(r.key.level),
                _ => None,
            })
            .collect();
        out.sort();
        out
    };
    let mut app = App::new(Scenario::paper());
    app.settings.level = 2;
    assert_eq!(
        levels(&app.update(Msg::Resize).commands),
        [2],
        "explore: the current level"
    );
    let more = app.update(ch('a')).commands;
    assert!(app.all_levels);
    assert_eq!(levels(&more), [0, 1], "and with a, the levels below it");
    // The inf-sup scene asks for M1–M4 at levels 0 to 4, or to the lab's level when
    // finer, from the first look (less the three of M1 already asked for).
    app.scene = Scene::InfSup;
    app.settings.level = 5;
    let all = levels(&app.update(Msg::Resize).commands);
    assert_eq!(all.len(), 4 * 6 - 3, "{all:?}");
    assert_eq!((all[0], all[all.len() - 1]), (0, 5));
}

#[test]
fn no_contact_renders() {
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.settings.depth = 0.0;
    app.guides = riplab::tui::app::Guides::ALL;
    for scene in Scene::ALL {
        app.scene = scene;
        settle(&mut app, &mut Engine::new(Scenario::paper()));
        let text = frame(&app, 80, 24);
        if scene.needs_solution() {
            assert!(text.contains(" P=0 (full 0)"), "{text}");
        }
    }
}
