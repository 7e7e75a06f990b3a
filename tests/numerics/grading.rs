//! Meshes graded at the contact edges against the study's certified reference.

use riplab::contact::Rule;
use riplab::grading::{Grading, RefineEdges};
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::study::{Plan, ReferenceFields, ReferenceMesh, study};

/// On the default scenario M1's p̄ error at level 2 falls with every pass N = 0 … 3 (no
/// sawtooth), measured by the study against its reference refined until its estimated error
/// is a tenth of the smallest row error (certified).
#[test]
fn m1_pbar_error_falls_with_every_pass() {
    let s = Scenario::paper();
    let refine = [0, 1, 2, 3].map(|n| RefineEdges::Passes(n).into());
    let plan = Plan::Levels {
        levels: &[2],
        epsilon: riplab::study::penalty_error::default_epsilon(&s, 2),
        refine: &refine,
    };
    let mut fetch = |grid: &ReferenceMesh| ReferenceFields::solve_on(&s, grid);
    let st = study(&s, &[(Element::Q1, Rule::Gauss1)], None, plan, (3, 4), &mut fetch).unwrap();
    // The reference's estimate of p meets its target (u's is the uniform level's: not asked).
    let (estimate, target) = (
        st.reference.estimate.as_ref().unwrap(),
        st.reference.target.unwrap(),
    );
    assert!(estimate.p <= target.p, "{estimate:?} {target:?}");
    let errors: Vec<f64> = st.rows.iter().map(|r| r.errors.unwrap().pbar).collect();
    assert_eq!(
        st.rows.iter().map(|r| r.refine_edges).collect::<Vec<_>>(),
        [0, 1, 2, 3]
    );
    assert!(errors.windows(2).all(|w| w[1] < w[0]), "{errors:?}");
}

/// Over the contact zone too: on the default scenario M1's p̄ error at level 2 falls with every
/// zone pass N = 0 … 3 against the study's certified reference (its estimate of p within a
/// tenth of the smallest row error), and the last pass's error is below the edge grading's
/// after as many passes (2+3z against 2+3e: the zone keeps (17)'s edges equal where p > 0).
#[test]
fn m1_pbar_error_falls_with_every_zone_pass() {
    let s = Scenario::paper();
    let refine = [
        Grading::default(),
        Grading::Zone(1),
        Grading::Zone(2),
        Grading::Zone(3),
        RefineEdges::Passes(3).into(),
    ];
    let plan = Plan::Levels {
        levels: &[2],
        epsilon: riplab::study::penalty_error::default_epsilon(&s, 2),
        refine: &refine,
    };
    let mut fetch = |grid: &ReferenceMesh| ReferenceFields::solve_on(&s, grid);
    let st = study(&s, &[(Element::Q1, Rule::Gauss1)], None, plan, (4, 4), &mut fetch).unwrap();
    let (estimate, target) = (
        st.reference.estimate.as_ref().unwrap(),
        st.reference.target.unwrap(),
    );
    assert!(estimate.p <= target.p, "{estimate:?} {target:?}");
    let labels: Vec<String> = st.rows.iter().map(|r| r.level_label()).collect();
    assert_eq!(labels, ["2", "2+1z", "2+2z", "2+3z", "2+3e"]);
    let errors: Vec<f64> = st.rows.iter().map(|r| r.errors.unwrap().pbar).collect();
    assert!(errors[..4].windows(2).all(|w| w[1] < w[0]), "{errors:?}");
    assert!(errors[3] < errors[4], "{errors:?}");
}
