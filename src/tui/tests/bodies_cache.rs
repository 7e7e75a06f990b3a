//! The two-body scene's speed (docs/lab.md, "Two bodies"): the bodies' discretisations kept
//! by what each depends on, so that a key re-discretises only what it changes.

use std::path::Path;

use std::cell::Cell;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use riplab::contact::interface::InterfaceMethod;
use riplab::contact::interface::solve::BodiesError;
use riplab::error::SolveError;
use riplab::scenario::Scenario;
use riplab::tui::bodies::BodiesApp;
use riplab::tui::bodies::cache::{BodiesCache, Built};

const PATCH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/patch-two-blocks.toml");

/// A solve nobody cancels.
fn never() -> bool {
    false
}

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
    let result = cache.solve(&settings, &never);
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
    assert!(app.reply(generation, cache.solve(&settings, &never)));
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
    assert!(app.reply(generation, cache.solve(&settings, &never)));
    assert_eq!(cache.built(), Built { lower: 2, upper: 4 }, "→ builds both");
}

/// The kept bodies give the solve of fresh ones: the same frame's data.
#[test]
fn kept_bodies_solve_as_fresh_ones() {
    let (mut app, mut cache) = scene(InterfaceMethod::Mortar);
    let (generation, settings) = app.start();
    assert!(app.reply(generation, cache.solve(&settings, &never)));
    press(&mut app, &mut cache, 'n');
    let fresh = BodiesCache::new(app.scenario.clone())
        .solve(&app.settings, &never)
        .unwrap();
    assert_eq!(app.solved.as_ref(), Some(&fresh));
}

/// A solve asked to stop before it begins gives the cancelled error and builds nothing.
#[test]
fn a_cancelled_solve_stops_before_it_builds() {
    let (app, mut cache) = scene(InterfaceMethod::Mortar);
    let cancelled = cache.solve(&app.settings, &|| true);
    assert_eq!(cancelled, Err(BodiesError::Solve(SolveError::Cancelled)));
    assert_eq!(cache.built(), Built::default());
}

/// The interface's solve asks whether to go on at every Newton iteration: a request that
/// turns stale at its first iteration stops it with the cancelled error; not asked to stop,
/// the same solve converges.
#[test]
fn the_interface_solve_stops_in_its_newton_loop() {
    let scenario = Scenario::load(Path::new(PATCH)).unwrap();
    let (lower, upper) = scenario.discretize_bodies(1).unwrap();
    let solve = |cancelled: &dyn Fn() -> bool| {
        scenario.solve_discretized(&lower, &upper, InterfaceMethod::Mortar, 0.0, cancelled)
    };
    // Asked before the constraints are condensed, after, then at each iteration.
    let asked = Cell::new(0);
    let stale_at_the_first_iteration = || {
        asked.set(asked.get() + 1);
        asked.get() > 2
    };
    assert!(matches!(
        solve(&stale_at_the_first_iteration),
        Err(BodiesError::Solve(SolveError::Cancelled))
    ));
    assert_eq!(asked.get(), 3);
    let solved = solve(&never).expect("solved");
    assert!(solved.solution.iterations >= 1);
}

/// Idle after a solve, the cache builds the upper bodies `k` and `K` ask for and both bodies
/// `→` asks for: the keys then build nothing; asked to stop at once, it builds nothing.
#[test]
fn an_idle_prefetch_has_the_next_keys_bodies_ready() {
    let (mut app, mut cache) = scene(InterfaceMethod::Mortar);
    let (generation, settings) = app.start();
    assert!(app.reply(generation, cache.solve(&settings, &never)));
    cache.prefetch_ratios(&app.settings, &|| true);
    cache.prefetch_finer(&app.settings, &|| true);
    assert_eq!(cache.built(), Built { lower: 1, upper: 1 }, "stopped at once");
    cache.prefetch_ratios(&app.settings, &never);
    cache.prefetch_finer(&app.settings, &never);
    let ready = Built { lower: 2, upper: 4 };
    assert_eq!(
        cache.built(),
        ready,
        "two ratios' upper bodies, both a level finer"
    );
    press(&mut app, &mut cache, 'k');
    assert_eq!(cache.built(), ready, "k finds its upper body");
    press(&mut app, &mut cache, 'K');
    press(&mut app, &mut cache, 'K');
    assert_eq!(cache.built(), ready, "K finds its upper body");
    press(&mut app, &mut cache, 'k');
    let right = KeyEvent::new(KeyCode::Right, KeyModifiers::NONE);
    let (_, request) = app.key(right);
    let (generation, settings) = request.unwrap();
    assert!(app.reply(generation, cache.solve(&settings, &never)));
    assert_eq!(cache.built(), ready, "→ finds both bodies");
}

/// A prefetch stops between the two bodies of a level: asked to stop after its first body,
/// it builds that one only.
#[test]
fn a_prefetch_stops_between_bodies() {
    let (mut app, mut cache) = scene(InterfaceMethod::Mortar);
    let (generation, settings) = app.start();
    assert!(app.reply(generation, cache.solve(&settings, &never)));
    let asked = Cell::new(0);
    cache.prefetch_finer(&app.settings, &|| {
        asked.set(asked.get() + 1);
        asked.get() > 1
    });
    assert_eq!(cache.built(), Built { lower: 2, upper: 1 });
}
