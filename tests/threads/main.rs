//! Results do not depend on the thread count, to the bit: the thread count is process-wide,
//! so this one test changes it in a test binary of its own (no other test runs beside it with
//! a count it did not choose), and each run reads which factorisation it got.

#[path = "../common/mod.rs"]
mod common;

use std::ops::ControlFlow;

use crate::common::paper_with;
use riplab::contact::ContactParams;
use riplab::contact::newton::NewtonOptions;
use riplab::fem::factor::Factor;
use riplab::fem::split::{SplitFactor, SplitOrdering};
use riplab::fem::{DofMap, Form, Integration, assemble};
use riplab::material::{Material, Plane};
use riplab::mesh::{Element, Mesh};
use riplab::solve::solve_contact;

/// What a solve reports, by quantity: the trace compliance C, p, p̄, u and the load; and
/// whether K was factorised as two subdomains (rather than the whole grid as one part).
fn run(threads: usize, element: Element, level: u32) -> ([(&'static str, Vec<f64>); 5], bool) {
    riplab::fem::set_threads(threads);
    let s = paper_with(&[]);
    let disc = s.discretize(level, element).unwrap();
    let params = ContactParams::by_epsilon(s.rule, s.epsilon, s.obstacle.clone());
    let sol = solve_contact(&disc, &params, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap();
    let c = disc.compliance();
    let c = (0..c.ncols())
        .flat_map(|j| (0..c.nrows()).map(move |i| c[(i, j)]))
        .collect();
    let split = matches!(disc.factor(), Factor::Split(f) if f.parts() == 2);
    let u = sol.displacement(&disc);
    riplab::fem::set_threads(1);
    (
        [
            ("C", c),
            ("p", sol.p),
            ("p̄", sol.pbar),
            ("u", u),
            ("load", vec![sol.load]),
        ],
        split,
    )
}

/// One, two and three threads give the same bits: below the split's size (level 4 Q1) the
/// whole grid as one part, whose dense kernels (faer's) sum in the same order on any thread
/// count; from it on (levels 5 Q1 and P1, level 4 Q2) two subdomains, factorised one after
/// the other on one thread and side by side on more, with the same arithmetic. The assembly's two threads each
/// sum their own columns. One test, so that nothing else changes the thread count while it runs.
#[test]
fn results_do_not_depend_on_the_threads() {
    split_factor_bits_do_not_depend_on_threads();
    friction_bits_do_not_depend_on_threads();
    for (element, level) in [
        (Element::Q1, 4),
        (Element::Q1, 5),
        (Element::Q2, 4),
        (Element::P1, 5),
    ] {
        let (one, split) = run(1, element, level);
        assert_eq!(
            split,
            level == 5 || element == Element::Q2,
            "{element:?} level {level}"
        );
        for threads in [2, 3] {
            let (more, split_more) = run(threads, element, level);
            assert_eq!(split_more, split, "{element:?} level {level}, {threads} threads");
            for ((name, a), (_, b)) in one.iter().zip(&more) {
                assert_eq!(a.len(), b.len());
                let differ = a
                    .iter()
                    .zip(b)
                    .filter(|(x, y)| x.to_bits() != y.to_bits())
                    .count();
                assert_eq!(
                    differ,
                    0,
                    "{element:?} level {level}, {threads} threads: {differ} of {} values of {name} differ from one thread's",
                    a.len()
                );
            }
        }
    }
}

/// The two-subdomain factor's solve and compliance as bits, on one and on two threads: each
/// half's arithmetic is the same, and S is summed in the same order.
fn split_factor_bits_do_not_depend_on_threads() {
    let bits = |threads: usize| {
        riplab::fem::set_threads(threads);
        let mesh = Mesh::uniform(Element::Q1, (0.0, 8.0, 64), (0.0, 4.0, 16), true);
        let dofs = DofMap::model(&mesh);
        let material = Material {
            young: 1000.0,
            poisson: 0.3,
            plane: Plane::Strain,
        };
        let k = assemble(&mesh, &dofs, Form::Elasticity(material, Integration::Full));
        let trace: Vec<usize> = mesh
            .top_nodes()
            .iter()
            .map(|&t| dofs.free_index(2 * t + 1).unwrap())
            .collect();
        let split = SplitOrdering::new(&k, &mesh, &dofs, &trace).unwrap().unwrap();
        let split = SplitFactor::new(&split, &k).unwrap();
        let mut u: Vec<f64> = (0..2 * k.n)
            .map(|i| ((i * 7919 + 17) % 2003) as f64 - 1001.0)
            .collect();
        split.solve_in_place(&mut u, 2);
        let c = split.compliance();
        riplab::fem::set_threads(1);
        let c: Vec<f64> = (0..c.ncols())
            .flat_map(|j| (0..c.nrows()).map(move |i| (i, j)))
            .map(|(i, j)| c[(i, j)])
            .collect();
        u.into_iter().chain(c).map(f64::to_bits).collect::<Vec<_>>()
    };
    assert!(
        bits(1) == bits(2),
        "the split factor differs on one and two threads"
    );
}

/// A friction solve (cattaneo-mindlin at its level 3: 57,840 unknowns, two subdomains with
/// the full trace last) gives the same p, t, t̄, u_x and Q on one and two threads.
fn friction_bits_do_not_depend_on_threads() {
    let bits = |threads: usize| {
        riplab::fem::set_threads(threads);
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/cattaneo-mindlin.toml");
        let s = riplab::scenario::Scenario::load(&path).unwrap();
        let (_, sol) = riplab::solve::solve_scenario(&s).unwrap();
        riplab::fem::set_threads(1);
        let f = sol.friction.unwrap();
        sol.p
            .iter()
            .chain(&f.t)
            .chain(&f.tbar)
            .chain(&f.vertex_ux)
            .chain([f.tangential_load, sol.load].iter())
            .map(|v| v.to_bits())
            .collect::<Vec<_>>()
    };
    assert!(
        bits(1) == bits(2),
        "a friction solve differs on one and two threads"
    );
}
