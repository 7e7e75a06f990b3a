//! A study with friction (docs/design.md §11): every row and the reference solved
//! with the scenario's friction, t̄'s and Q's errors beside p̄'s and P's, μ = 0 the
//! frictionless study's numbers, and a row whose friction solve is refused reported per row.

use super::*;
use crate::contact::friction::{Friction, Law, Press};
use crate::error::InputFault;
use crate::grading::RefineEdges;

/// `scenarios/hertz-paper-full.toml` (Kikuchi's example, modelled whole).
fn full() -> Scenario {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-paper-full.toml");
    Scenario::load(std::path::Path::new(path)).unwrap()
}

/// Coulomb's μ with the shift 0.05 in 4 steps.
fn coulomb(mu: f64) -> Friction {
    Friction {
        law: Law::Coulomb { mu },
        shift: 0.05,
        steps: 4,
        epsilon_t: None,
        press: Press::WithFriction,
    }
}

/// The study of `scenario` at `plan` with `schemes` against the uniform reference at
/// `reference_level` (no edge refinement, no cache).
fn run(scenario: &Scenario, schemes: &[(Element, Rule)], plan: Plan, reference_level: u32) -> Study {
    let mut fetch = |grid: &ReferenceMesh| ReferenceFields::solve_on(scenario, grid);
    study(scenario, schemes, None, plan, (reference_level, 0), &mut fetch).unwrap()
}

const M1: (Element, Rule) = (Element::Q1, Rule::Gauss1);
const M3: (Element, Rule) = (Element::Q1, Rule::Trapezoid);

/// With μ = 0.3, t̄'s and Q's errors fall level by level for M1 and M3, they have rates and a
/// fit; the reference's Q is the horizontal reaction of its clamped bottom (equilibrium,
/// independent of the solver that made it).
#[test]
fn the_tangential_errors_fall_with_the_level() {
    let mut s = full();
    s.friction = coulomb(0.3);
    let levels = [0, 1, 2];
    let plan = Plan::Levels {
        levels: &levels,
        epsilon: 1e-6,
        refine: &[Grading::default()],
    };
    let study = run(&s, &[M1, M3], plan, 3);
    let q = study.reference.tangential_load().unwrap();
    // Q > 0 (the obstacle drags the top to +x) and below μP (partial slip).
    assert!(q > 0.0 && q < 0.3 * study.reference.load, "{q}");
    assert_eq!(study.rows.len(), 6);
    for series in study.rows.chunks(3) {
        let errors: Vec<Errors> = series.iter().map(|r| r.errors.unwrap()).collect();
        for pair in errors.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            assert!(
                b.tbar.unwrap() < a.tbar.unwrap(),
                "{}: {a:?} → {b:?}",
                series[0].scheme
            );
            assert!(
                b.tangential_load.unwrap() < a.tangential_load.unwrap(),
                "{}: {a:?} → {b:?}",
                series[0].scheme
            );
        }
        assert!(series.iter().all(|r| r.status == Status::Ok));
        assert!(series[1..].iter().all(|r| r.rates.unwrap().tbar.unwrap() > 0.0));
    }
    for fit in &study.fits {
        assert!(fit.rates.as_ref().unwrap().tbar.unwrap() > 0.3, "{fit:?}");
    }
}

/// μ = 0 with a shift gives the frictionless study's numbers (two solvers: the friction path
/// and the frictionless Newton, each to its own tolerance), t̄'s and Q's errors 0, and no
/// t̄ rate or fit (an error of 0 has none); the frictionless study reports no t̄ at all.
#[test]
fn mu_zero_is_the_frictionless_study() {
    let plain = full();
    let mut zero = full();
    zero.friction = coulomb(0.0);
    let levels = [0, 1];
    let plan = Plan::Levels {
        levels: &levels,
        epsilon: 1e-6,
        refine: &[Grading::default()],
    };
    let (a, b) = (run(&plain, &[M1, M3], plan, 2), run(&zero, &[M1, M3], plan, 2));
    assert_eq!(a.reference.tangential_load(), None);
    assert_eq!(b.reference.tangential_load(), Some(0.0));
    assert!((a.reference.load - b.reference.load).abs() <= 1e-12 * a.reference.load);
    for (ra, rb) in a.rows.iter().zip(&b.rows) {
        let (ea, eb) = (ra.errors.unwrap(), rb.errors.unwrap());
        assert_eq!((ea.tbar, ea.tangential_load), (None, None));
        assert_eq!((eb.tbar, eb.tangential_load), (Some(0.0), Some(0.0)));
        let (la, lb) = (ra.load.unwrap(), rb.load.unwrap());
        assert!((la - lb).abs() <= 1e-11 * la, "{la} vs {lb}");
        // Errors are differences of near numbers: compared absolutely.
        for (x, y) in [(ea.p, eb.p), (ea.pbar, eb.pbar), (ea.u, eb.u), (ea.load, eb.load)] {
            assert!((x - y).abs() <= 1e-11, "{}: {ea:?} vs {eb:?}", ra.scheme);
        }
        assert!(rb.rates.is_none_or(|r| r.tbar.is_none()));
    }
    for (fa, fb) in a.fits.iter().zip(&b.fits) {
        let (ra, rb) = (fa.rates.as_ref().unwrap(), fb.rates.as_ref().unwrap());
        assert!((ra.p - rb.p).abs() <= 1e-8 && (ra.u - rb.u).abs() <= 1e-8);
        assert_eq!((ra.tbar, rb.tbar), (None, None));
    }
}

/// A row whose friction solve is refused says so in its row and the others stand: an ε
/// sweep at level 1 with ε_t given, whose ε = 0 row is the exact method (which takes no
/// tangential penalty) and whose ε = 1e-6 row is the penalty.
#[test]
fn a_refused_friction_row_is_reported_in_its_row() {
    let mut s = full();
    s.friction = Friction {
        epsilon_t: Some(1e-6),
        ..coulomb(0.3)
    };
    let plan = Plan::Sweep {
        level: 1,
        epsilons: &[0.0, 1e-6],
    };
    let study = run(&s, &[M3], plan, 2);
    let [exact, penalty] = &study.rows[..] else {
        panic!("two rows")
    };
    assert_eq!(exact.status, Status::Failed);
    let refused = SolveError::from(InputFault::TangentialPenaltyOfExact).to_string();
    assert_eq!(exact.reason.as_deref(), Some(refused.as_str()));
    assert!(exact.errors.is_none() && exact.load.is_none());
    assert_eq!(penalty.status, Status::Ok);
    assert!(penalty.errors.unwrap().tbar.unwrap() > 0.0);
    assert!(!all_ok(&study.rows));
}

/// Edge-graded rows do not take friction: refused before anything is solved.
#[test]
fn graded_rows_refuse_friction() {
    let mut s = full();
    s.friction = coulomb(0.3);
    let plan = Plan::Levels {
        levels: &[0],
        epsilon: 1e-6,
        refine: &[Grading::default(), RefineEdges::Passes(1).into()],
    };
    let mut fetch =
        |_: &ReferenceMesh| -> Result<ReferenceFields, SolveError> { panic!("nothing is solved") };
    let refused = study(&s, &[M3], None, plan, (1, 0), &mut fetch).err();
    assert_eq!(refused, Some(InputFault::GradedFriction.into()));
}
