//! Friction's cost against the frictionless solve (BENCHMARKS.md "Friction"):
//! `cargo bench --bench friction`. A fresh frictionless solve of `hertz-paper-full` at level 5
//! (M1, the scenario's method) against a fresh Coulomb solve (μ = 0.3, shift 0.2: Q/(μP) ≈
//! 0.47, the default steps) on a full-trace discretisation, and the Coulomb path alone on a
//! prepared one. As the binary: the cores available unless `RIPLAB_THREADS` says how many.

use std::ops::ControlFlow;
use std::path::Path;

use divan::Bencher;
use riplab::contact::friction::FrictionTrace;
use riplab::contact::friction::{Friction, Law};
use riplab::contact::newton::NewtonOptions;
use riplab::contact::{ContactParams, ContactPoints};
use riplab::discretization::Trace;
use riplab::scenario::Scenario;
use riplab::solve::solve_friction;
use riplab::solve::solve_scenario;

/// As the binary: huge pages for the large blocks (`riplab::huge_pages`).
#[global_allocator]
static ALLOCATOR: riplab::huge_pages::HugePages = riplab::huge_pages::HugePages;

const LEVEL: u32 = 5;

fn main() {
    let threads = std::env::var("RIPLAB_THREADS")
        .ok()
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(riplab::fem::available_threads);
    riplab::fem::set_threads(threads);
    divan::main();
}

fn scenario(friction: bool) -> Scenario {
    let mut s = Scenario::load(Path::new("scenarios/hertz-paper-full.toml")).unwrap();
    s.level = LEVEL;
    if friction {
        s.friction = Friction {
            law: Law::Coulomb { mu: 0.3 },
            shift: 0.2,
            ..Friction::NONE
        };
    }
    s
}

/// The frictionless fresh solve: assembly, factorisation, compliance, Newton.
#[divan::bench(sample_count = 5)]
fn fresh_frictionless(bencher: Bencher) {
    let s = scenario(false);
    bencher.bench(|| solve_scenario(&s).unwrap().1.load);
}

/// The Coulomb fresh solve: the full trace's factorisation and compliance, the press and
/// the shift.
#[divan::bench(sample_count = 5)]
fn fresh_coulomb(bencher: Bencher) {
    let s = scenario(true);
    bencher.bench(|| solve_scenario(&s).unwrap().1.load);
}

/// The press and the shift alone, on a prepared full-trace discretisation (its couplings
/// built): the dense work on Γ_C.
#[divan::bench(sample_count = 5)]
fn coulomb_path(bencher: Bencher) {
    let s = scenario(true);
    let disc = s.discretize_traced(LEVEL, s.element, Trace::Full).unwrap();
    let params = ContactParams {
        rule: s.rule,
        method: s.method,
        epsilon: s.epsilon,
        obstacle: s.obstacle.clone(),
    };
    let points = ContactPoints::on(&disc, s.rule);
    FrictionTrace::of(&disc)
        .unwrap()
        .couplings(&disc, s.rule, &points);
    bencher.bench(|| {
        solve_friction(
            &disc,
            &params,
            &s.friction,
            None,
            &NewtonOptions::default(),
            &mut |_| ControlFlow::Continue(()),
        )
        .unwrap()
        .load
    });
}
