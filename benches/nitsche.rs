//! Nitsche's method on the paper's problem (`riplab::contact::nitsche`), per level, for M3's
//! pair (q1 + trapezoid) and M4's (q2 + simpson): `cargo bench --bench nitsche`.
//!
//! fresh: the first Nitsche solve on a new discretisation (the layer's factorisation, the
//! rule's point couplings, the θ/γ₀ operator, Newton), the discretisation itself excluded
//! (it is the penalty's; BENCHMARKS.md "Fresh solve per level"). gamma0: a re-solve after a
//! change of γ₀ (the operator rebuilt, dense work on the points). depth: a re-solve after a
//! change of depth (the operator reused: Newton alone). θ = 1, γ₀ = 10 γ₀*-ish values.

use divan::Bencher;
use riplab::contact::ContactParams;
use riplab::contact::Rule;
use riplab::contact::nitsche::{NitscheParams, solve_once};
use riplab::discretization::Discretization;
use riplab::mesh::Element;
use riplab::scenario::Scenario;

/// As the binary: huge pages for the large blocks (`riplab::huge_pages`).
#[global_allocator]
static ALLOCATOR: riplab::huge_pages::HugePages = riplab::huge_pages::HugePages;

const CASES: &[(u32, &str)] = &[(4, "m3"), (5, "m3"), (6, "m3"), (4, "m4"), (5, "m4"), (6, "m4")];

fn main() {
    riplab::fem::set_threads(1);
    divan::main();
}

fn pair(scheme: &str) -> (Element, Rule) {
    if scheme == "m3" {
        (Element::Q1, Rule::Trapezoid)
    } else {
        (Element::Q2, Rule::Simpson)
    }
}

fn setup(level: u32, scheme: &str) -> (Discretization, ContactParams) {
    let s = Scenario::paper();
    let (element, rule) = pair(scheme);
    let disc = s.discretize(level, element).unwrap();
    let params = ContactParams::by_epsilon(rule, 0.0, s.obstacle.clone());
    (disc, params)
}

fn run(disc: &Discretization, params: &ContactParams, gamma0: f64) {
    let sol = solve_once(disc, params, NitscheParams { theta: 1.0, gamma0 }).unwrap();
    assert!(sol.newton.converged);
}

#[divan::bench(args = CASES, sample_count = 2)]
fn fresh(bencher: Bencher, &(level, scheme): &(u32, &str)) {
    bencher
        .with_inputs(|| setup(level, scheme))
        .bench_values(|(disc, params)| run(&disc, &params, 100.0));
}

#[divan::bench(args = CASES, sample_count = 4)]
fn gamma0(bencher: Bencher, &(level, scheme): &(u32, &str)) {
    let (disc, params) = setup(level, scheme);
    run(&disc, &params, 100.0);
    let mut k = 0;
    bencher.bench_local(|| {
        k += 1;
        run(&disc, &params, if k % 2 == 0 { 100.0 } else { 200.0 });
    });
}

#[divan::bench(args = CASES, sample_count = 4)]
fn depth(bencher: Bencher, &(level, scheme): &(u32, &str)) {
    let (disc, params) = setup(level, scheme);
    run(&disc, &params, 100.0);
    let mut k = 0;
    bencher.bench_local(|| {
        k += 1;
        let depth = if k % 2 == 0 { 0.8 } else { 0.6 };
        let p = ContactParams {
            obstacle: params.obstacle.with_depth(depth),
            ..params.clone()
        };
        run(&disc, &p, 100.0);
    });
}
