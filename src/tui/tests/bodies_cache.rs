//! The two-body scene's speed (docs/lab.md, "Two bodies"): the bodies' discretisations kept
//! by what each depends on, so that a key re-discretises only what it changes.

use std::path::Path;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use riplab::contact::interface::InterfaceMethod;
use riplab::scenario::Scenario;
use riplab::tui::bodies::BodiesApp;
use riplab::tui::bodies::cache::{BodiesCache, Built};

const PATCH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/patch-two-blocks.toml");

fn key(c: char) -> KeyEvent {
    KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE)
}

/// The patch scenario's scene with `method` and an empty cache for it.
fn scene(method: InterfaceMethod) -> (BodiesApp, BodiesCache) {
    let scenario = Scenario::load(Path::new(PATCH)).unwrap();
    let app = BodiesApp::new(scenario, method).expect("two bodies");
    let cache = BodiesCache::new(app.scenario.clone());
    (app, cache)
}

/// `c` pressed in `app`, its solve answered from `cache` (solved, or refused: on the patch
/// scenario's exact multipliers a rule with more points than the slave has nodes is).
fn press(app: &mut BodiesApp, cache: &mut BodiesCache, c: char) {
    let (_, request) = app.key(key(c));
    let (generation, settings) = request.expect("a solve");
    let result = cache.solve(&settings);
    assert!(app.reply(generation, result));
    assert!(app.settled());
}

/// `n` (the discretisation across the interface) solves on both bodies as they are; `k` (the
/// ratio) and `J` (the offset) build the upper body only, `→` (the level) both, and a step
/// back finds them kept.
#[test]
fn a_key_discretises_only_the_bodies_it_changes() {
    let (mut app, mut cache) = scene(InterfaceMethod::Mortar);
    let (generation, settings) = app.start();
    assert!(app.reply(generation, cache.solve(&settings)));
    let both = Built { lower: 1, upper: 1 };
    assert_eq!(cache.built(), both);
    for _ in 0..3 {
        press(&mut app, &mut cache, 'n');
    }
    assert_eq!(cache.built(), both, "n builds nothing");
    press(&mut app, &mut cache, 'k');
    assert_eq!(
        cache.built(),
        Built { lower: 1, upper: 2 },
        "k builds the upper body"
    );
    press(&mut app, &mut cache, 'J');
    assert_eq!(
        cache.built(),
        Built { lower: 1, upper: 3 },
        "J builds the upper body"
    );
    press(&mut app, &mut cache, 'j');
    press(&mut app, &mut cache, 'K');
    assert_eq!(
        cache.built(),
        Built { lower: 1, upper: 3 },
        "back where it was: kept"
    );
    let right = KeyEvent::new(KeyCode::Right, KeyModifiers::NONE);
    let (_, request) = app.key(right);
    let (generation, settings) = request.unwrap();
    assert!(app.reply(generation, cache.solve(&settings)));
    assert_eq!(cache.built(), Built { lower: 2, upper: 4 }, "→ builds both");
}

/// The kept bodies give the solve of fresh ones: the same frame's data.
#[test]
fn kept_bodies_solve_as_fresh_ones() {
    let (mut app, mut cache) = scene(InterfaceMethod::Mortar);
    let (generation, settings) = app.start();
    assert!(app.reply(generation, cache.solve(&settings)));
    press(&mut app, &mut cache, 'n');
    let fresh = BodiesCache::new(app.scenario.clone())
        .solve(&app.settings)
        .unwrap();
    assert_eq!(app.solved.as_ref(), Some(&fresh));
}
