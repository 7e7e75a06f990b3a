//! Run time of each stage per mesh level on the paper's problem (M1): `cargo bench`.
//!
//! assembly → ordering (symbolic analysis with Γ_C last) → factorisation (numeric, plus the
//! trace compliance) → Newton (a fresh contact solve) → re-solve (ε changed, warm start) →
//! inf-sup (H¹ condensation and the dense eigenproblems of one rule). As the binary: the cores
//! available, unless `RIPLAB_THREADS` says how many (`--threads`; K is factorised as two
//! subdomains from level 5 on, side by side from two threads, `riplab::fem::factor`), and its
//! allocator.

use std::ops::ControlFlow;

use divan::Bencher;
use riplab::contact::ContactParams;
use riplab::contact::Rule;
use riplab::contact::newton::NewtonOptions;
use riplab::discretization::Discretization;
use riplab::fem::factor::{Analysis, Factor};
use riplab::fem::{DofMap, Form, SymCsc, assemble};
use riplab::infsup::{TraceCompliance, estimate};
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::solve::solve_contact;

const LEVELS: &[u32] = &[3, 4, 5, 6];

/// As the binary: huge pages for the large blocks (`riplab::huge_pages`).
#[global_allocator]
static ALLOCATOR: riplab::huge_pages::HugePages = riplab::huge_pages::HugePages;

/// `RIPLAB_THREADS`, else the cores available (as `--threads`).
fn threads() -> usize {
    std::env::var("RIPLAB_THREADS")
        .ok()
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(riplab::fem::available_threads)
}

fn main() {
    riplab::fem::set_threads(threads());
    divan::main();
}

fn params(scenario: &Scenario, epsilon: f64) -> ContactParams {
    ContactParams::by_epsilon(Rule::Gauss1, epsilon, scenario.obstacle.clone())
}

#[divan::bench(args = LEVELS, sample_count = 10)]
fn assembly(bencher: Bencher, level: u32) {
    let s = Scenario::paper();
    let mesh = s.mesh(level, Element::Q1);
    let dofs = DofMap::model(&mesh);
    bencher.bench(|| assemble(&mesh, &dofs, Form::Elasticity(s.material, s.integration)));
}

/// The paper's mesh at `level` with its stiffness assembled.
fn stiffness(level: u32) -> (Discretization, SymCsc) {
    let s = Scenario::paper();
    let disc = s.discretize(level, Element::Q1).unwrap();
    let k = assemble(
        disc.mesh(),
        disc.dofs(),
        Form::Elasticity(s.material, s.integration),
    );
    (disc, k)
}

#[divan::bench(args = LEVELS, sample_count = 10)]
fn ordering(bencher: Bencher, level: u32) {
    let (disc, k) = stiffness(level);
    bencher.bench(|| Analysis::grid(&k, disc.mesh(), disc.dofs(), disc.contact_dofs()).unwrap());
}

#[divan::bench(args = LEVELS, sample_count = 10)]
fn factorisation(bencher: Bencher, level: u32) {
    let (disc, k) = stiffness(level);
    bencher
        .with_inputs(|| k.clone())
        .bench_values(|k| Factor::new(disc.ordering(), k).unwrap().compliance());
}

#[divan::bench(args = LEVELS, sample_count = 10)]
fn newton(bencher: Bencher, level: u32) {
    let s = Scenario::paper();
    let disc = s.discretize(level, Element::Q1).unwrap();
    let p = params(&s, 1e-6);
    bencher.bench(|| {
        solve_contact(&disc, &p, None, &NewtonOptions::default(), &mut |_| {
            ControlFlow::Continue(())
        })
        .unwrap()
    });
}

#[divan::bench(args = LEVELS, sample_count = 10)]
fn resolve(bencher: Bencher, level: u32) {
    let s = Scenario::paper();
    let disc = s.discretize(level, Element::Q1).unwrap();
    let go = |eps: f64, warm: Option<&[f64]>| {
        solve_contact(
            &disc,
            &params(&s, eps),
            warm,
            &NewtonOptions::default(),
            &mut |_| ControlFlow::Continue(()),
        )
        .unwrap()
    };
    let previous = go(1e-6, None);
    bencher.bench(|| go(1e-7, Some(&previous.newton.forces)));
}

#[divan::bench(args = LEVELS, sample_count = 10)]
fn inf_sup(bencher: Bencher, level: u32) {
    let s = Scenario::paper();
    let disc = s.discretize(level, Element::Q1).unwrap();
    bencher.bench(|| estimate(&disc, &TraceCompliance::new(&disc).unwrap(), Rule::Gauss1).unwrap());
}
