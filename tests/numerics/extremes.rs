//! Stability at the extremes: geometry that strains the contact logic, sizes the
//! machine cannot hold, and determinism.

use std::ops::ControlFlow;

use crate::common::{paper_with, riplab_under_half_of};
use riplab::contact::ContactParams;
use riplab::contact::newton::NewtonOptions;
use riplab::contact::solution::Solution;
use riplab::contact::{Obstacle, Rule};
use riplab::discretization::Discretization;
use riplab::error::{SolveError, Workload};
use riplab::fem::DofMap;
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::solve::{solve_contact, solve_scenario};

fn solve_with(disc: &Discretization, rule: Rule, obstacle: Obstacle) -> Solution {
    let params = ContactParams::by_epsilon(rule, 1e-6, obstacle);
    let sol = solve_contact(disc, &params, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap();
    assert!(sol.newton.converged, "{:?}", sol.newton.history);
    sol
}

#[test]
fn unknowns_are_counted_without_building_the_mesh() {
    for (model, nx) in [("half", "8"), ("full", "16")] {
        let s = paper_with(&[
            ("model", &format!("model = \"{model}\"")),
            ("nx =", &format!("nx = {nx}")),
        ]);
        for element in Element::ALL {
            for level in 0..3 {
                let mesh = s.mesh(level, element);
                assert_eq!(
                    s.n_dofs(level, element),
                    DofMap::model(&mesh).n_free(),
                    "{model} {element:?} {level}"
                );
            }
        }
    }
}

#[test]
fn a_size_beyond_the_machine_is_refused_before_allocating() {
    let s = paper_with(&[("nx =", "nx = 4096"), ("ny =", "ny = 4096")]);
    match s.discretize(8, Element::Q2) {
        Err(SolveError::TooLarge {
            workload: Workload::Level { level: 8, .. },
            need,
            available,
            ..
        }) => assert!(need > available, "{need} ≤ {available}"),
        Err(e) => panic!("wrong error: {e}"),
        Ok(_) => panic!("a 10¹³-unknown problem was accepted"),
    }
}

#[test]
fn no_contact_gives_zero_pressure_at_once() {
    let s = paper_with(&[]);
    let disc = s.discretize(2, Element::Q1).unwrap();
    for rule in Rule::ALL {
        let sol = solve_with(&disc, rule, s.obstacle.with_depth(-0.1));
        assert!(sol.p.iter().chain(&sol.pbar).all(|&p| p == 0.0) && sol.load == 0.0);
        assert!(
            sol.newton.iterations <= 1,
            "{rule:?}: {} iterations",
            sol.newton.iterations
        );
    }
}

#[test]
fn geometric_extremes_converge() {
    let s = paper_with(&[]);
    let disc = s.discretize(2, Element::Q1).unwrap();
    // Indentation approaching the body's height (3.5 of 4; linear elasticity, so a stress test
    // of the solver, not of the physics).
    let deep = solve_with(&disc, Rule::Gauss1, s.obstacle.with_depth(3.5));
    assert!(deep.load > 0.0);
    // An obstacle far wider than the body: every point of Γ_C is in contact.
    let wide = Obstacle::Cylinder {
        radius: 1000.0,
        depth: 0.1,
        center: 0.0,
    };
    for rule in Rule::ALL {
        let sol = solve_with(&disc, rule, wide.clone());
        assert!(
            sol.p.iter().all(|&p| p > 0.0),
            "{rule:?}: some point lost contact"
        );
    }
    // A contact zone of one rule point: the paper's mesh, a shallow indentation.
    let coarse = s.discretize(0, Element::Q1).unwrap();
    let one = solve_with(&coarse, Rule::Gauss1, s.obstacle.with_depth(0.02));
    assert_eq!(one.p.iter().filter(|&&p| p > 0.0).count(), 1, "{:?}", one.p);
    // A level-0 mesh one element high.
    let thin = paper_with(&[("ny =", "ny = 1")]);
    for element in Element::ALL {
        let d = thin.discretize(0, element).unwrap();
        assert!(solve_with(&d, Rule::Trapezoid, thin.obstacle.clone()).load > 0.0);
    }
}

#[test]
fn repeated_solves_are_bit_identical() {
    let mut s = paper_with(&[]);
    s.level = 3;
    let (_, a) = solve_scenario(&s).unwrap();
    let (_, b) = solve_scenario(&s).unwrap();
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a.p), bits(&b.p));
    assert_eq!(bits(&a.pbar), bits(&b.pbar));
    assert_eq!(a.load.to_bits(), b.load.to_bits());
}

/// A long flat strip has small sparse work but m² dense blocks on Γ_C (m =
/// 8193 trace dofs at level 1: C alone is 0.5 GiB). Under half the memory riplab estimates for
/// it, it is refused before allocating, with the estimate, instead of aborting or reporting a
/// rigid motion.
#[test]
fn a_long_strip_is_refused_for_its_dense_blocks() {
    let dir = std::env::temp_dir().join(format!("riplab-strip-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("strip.toml");
    let text = riplab::scenario::DEFAULT_SCENARIO
        .replace("nx = 8 ", "nx = 4096 ")
        .replace("ny = 4 ", "ny = 1 ");
    std::fs::write(&file, text).unwrap();
    let strip = Scenario::load(&file).unwrap();
    let sizes = strip.sizes(1, Element::Q1);
    let (code, _, err) = riplab_under_half_of(&sizes, &["solve", file.to_str().unwrap(), "--level", "1"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("32770 unknowns (8193 on Γ_C) and needs about") && err.contains("GiB available"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `ulimit -v 1500000; riplab solve --level 7 --element q2` once aborted with SIGABRT; under half the memory riplab estimates for it, it is refused with a clear message
/// and exit 2.
#[test]
fn an_address_space_limit_is_honoured() {
    let sizes = paper_with(&[]).sizes(7, Element::Q2);
    let (code, _, err) = riplab_under_half_of(&sizes, &["solve", "--level", "7", "--element", "q2"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("level 7 with q2") && err.contains("choose a coarser level"),
        "{err}"
    );
    assert!(!err.contains("rigid motion"), "{err}");
}
