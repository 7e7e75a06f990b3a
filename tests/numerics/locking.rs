//! Near-incompressibility (ν → 1/2): Q1 with full integration locks, selective reduced
//! integration of the volumetric term removes the locking.

use crate::common::{paper_with, rel};
use riplab::solve::solve_scenario;

/// The exact-constraint load of the paper's problem with ν = 0.4999 and the given discretisation.
fn load(element: &str, rule: &str, integration: &str, level: u32) -> f64 {
    let mut s = paper_with(&[
        ("poisson", "poisson = 0.4999"),
        ("element", &format!("element = \"{element}\"")),
        (
            "level",
            &format!("level = {level}\nintegration = \"{integration}\""),
        ),
        ("rule", &format!("rule = \"{rule}\"")),
        ("epsilon", "epsilon = 0.0"),
    ]);
    s.level = level;
    let (_, sol) = solve_scenario(&s).unwrap();
    assert!(sol.newton.converged);
    sol.load
}

#[test]
fn selective_integration_removes_volumetric_locking() {
    // Reference: Q2 with Simpson nodes (it hardly locks) at level 4; full and selective
    // integration of Q2 agree on it to 0.01%.
    let reference = load("q2", "simpson", "selective", 4);
    assert!(rel(load("q2", "simpson", "full", 4), reference, 1.0) < 1e-3);
    // Q1, full integration: far too stiff on coarse meshes, and still off after refinement.
    let full2 = load("q1", "trapezoid", "full", 2);
    let full3 = load("q1", "trapezoid", "full", 3);
    assert!(
        full2 > 1.5 * reference,
        "Q1 full at level 2 should lock: {full2} vs {reference}"
    );
    assert!(
        full3 > 1.2 * reference,
        "Q1 full at level 3 should still lock: {full3} vs {reference}"
    );
    // Q1, selective: right on the coarse meshes already.
    for level in [1, 2, 3] {
        let sel = load("q1", "trapezoid", "selective", level);
        assert!(
            rel(sel, reference, 1.0) < 5e-3,
            "Q1 selective at level {level}: {sel} vs {reference}"
        );
    }
}

#[test]
fn selective_integration_changes_nothing_essential_at_moderate_poisson() {
    let at = |integration: &str| {
        let mut s = paper_with(&[("level", &format!("level = 3\nintegration = \"{integration}\""))]);
        s.level = 3;
        solve_scenario(&s).unwrap().1.load
    };
    assert!(rel(at("selective"), at("full"), 1.0) < 5e-4);
}
