//! The convergence study's machinery: errors of the reference against itself vanish, and
//! the observed behaviour matches Theorem 2 (26) and the paper's claim about p and p̄.

mod common;

use common::paper_with;
use riplab::contact::Rule;
use riplab::mesh::Element;
use riplab::study::{Reference, Status, convergence};

#[test]
fn errors_rates_and_the_smoothing_claim() {
    let scenario = paper_with(&[]);
    let reference = Reference::compute(&scenario, 4).unwrap();
    // The reference scheme at the reference level against itself: zero (checks evaluation and
    // integration on nested meshes).
    let itself = convergence(&scenario, &reference, &[(Element::Q2, Rule::Simpson)], &[4], 0.0);
    let e = itself[0].errors.unwrap();
    assert!(
        e.p < 1e-12 && e.pbar < 0.1 && e.u < 1e-12 && e.load < 1e-12,
        "{e:?}"
    );
    let rows = convergence(
        &scenario,
        &reference,
        &[(Element::Q1, Rule::Gauss1), (Element::Q1, Rule::Trapezoid)],
        &[1, 2, 3],
        1e-10,
    );
    for r in &rows {
        assert!(r.converged && r.status == Status::Ok, "{r:?}");
    }
    // H¹ error of Q1 at rate 1 (the h term of (26); ε is too small to matter).
    for r in rows.iter().filter(|r| r.level > 1) {
        let u_rate = r.rates.unwrap().u;
        assert!(
            (0.85..1.2).contains(&u_rate),
            "{} level {}: u rate {u_rate}",
            r.scheme,
            r.level
        );
    }
    // M1 on the finest level: the smoothed pressure is much closer to the truth than the raw one.
    let m1 = rows.iter().find(|r| r.scheme == "M1" && r.level == 3).unwrap();
    let e = m1.errors.unwrap();
    assert!(e.pbar < 0.6 * e.p, "M1: p̄ error {} vs p error {}", e.pbar, e.p);
}
