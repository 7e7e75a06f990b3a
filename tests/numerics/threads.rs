//! Results do not depend on the thread count (issue 13): one test in its own process, since
//! the thread count is process-wide.

use std::ops::ControlFlow;

use crate::common::paper_with;
use riplab::contact::penalty::NewtonOptions;
use riplab::mesh::Element;
use riplab::solve::{ContactParams, Discretization, solve_contact};

/// Everything a solve reports, and the trace compliance, as bits.
fn run(threads: usize, element: Element, level: u32) -> Vec<u64> {
    riplab::fem::set_threads(threads);
    let s = paper_with(&[]);
    let disc = Discretization::of(&s, level, element).unwrap();
    let params = ContactParams::by_epsilon(s.rule, s.epsilon, s.obstacle.clone());
    let sol = solve_contact(&disc, &params, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap();
    let c = disc.compliance();
    (0..c.ncols())
        .flat_map(|j| (0..c.nrows()).map(move |i| c[(i, j)]))
        .chain(
            sol.p
                .iter()
                .chain(&sol.pbar)
                .chain(&sol.displacement(&disc))
                .copied(),
        )
        .chain([sol.load])
        .map(f64::to_bits)
        .collect()
}

/// One and two threads give the same bits, on meshes large enough for faer to split its
/// dense blocks (level 6 Q1: a last separator of 513 dofs; level 4 Q2).
#[test]
fn one_and_two_threads_agree_bit_for_bit() {
    for (element, level) in [(Element::Q1, 6), (Element::Q2, 4), (Element::P1, 5)] {
        let one = run(1, element, level);
        let two = run(2, element, level);
        assert_eq!(one.len(), two.len());
        let differ = one.iter().zip(&two).filter(|(a, b)| a != b).count();
        assert_eq!(
            differ,
            0,
            "{element:?} level {level}: {differ} of {} values differ",
            one.len()
        );
    }
}
