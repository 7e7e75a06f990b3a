//! The driver on a toy law whose Newton target flips the sign of the iterate: from x = 1 the
//! targets are −1, 1, −1, …, so the active set {x > 0} repeats at the third iterate.

use super::*;

/// x ↦ −x, converged at |x| ≤ 1e-12; `STOPS`: a repeated set ends the iteration.
struct Flip<const STOPS: bool>;

impl<const STOPS: bool> SemismoothLaw for Flip<STOPS> {
    type States = bool;
    type Values = ();
    const CYCLE_STOPS: bool = STOPS;

    fn assess(&self, x: &[f64], _: Option<&bool>, _: &NewtonOptions) -> Assessment<bool, ()> {
        Assessment {
            states: x[0] > 0.0,
            active: usize::from(x[0] > 0.0),
            residual: x[0].abs(),
            verdict: if x[0].abs() <= 1e-12 {
                Verdict::Converged
            } else if x[0].is_nan() {
                Verdict::Fail(Diagnosis::Overflow)
            } else {
                Verdict::Continue
            },
            values: (),
        }
    }

    fn target(&self, x: &[f64], _: &Assessment<bool, ()>) -> Result<Vec<f64>, Diagnosis> {
        if x[0] > 10.0 {
            Err(Diagnosis::Singular {
                theta: 1.0,
                gamma0: 0.5,
            })
        } else {
            Ok(vec![-x[0]])
        }
    }

    /// Half a step on a repeated set: from 1 towards −1 lands on 0.
    fn step(&self, _: &[f64], _: &[f64], _: &Assessment<bool, ()>, repeated: bool) -> f64 {
        if repeated { 0.5 } else { 1.0 }
    }
}

fn run<const S: bool>(x: f64, opts: &NewtonOptions) -> Result<NewtonResult, SolveError> {
    let outcome = drive(&Flip::<S>, vec![x], opts, &mut |_| ControlFlow::Continue(()))?;
    let x = outcome.x.clone();
    Ok(outcome.result(x, vec![]))
}

/// Damping on the repeated set: the steps 1, 1, 1, then ½ at the repeat, which lands on the
/// solution x = 0 at the fourth iterate.
#[test]
fn a_repeated_set_is_damped() {
    let r = run::<false>(1.0, &NewtonOptions::default()).unwrap();
    assert!(r.converged && r.diagnosis.is_none());
    assert_eq!(r.iterations, 3);
    assert_eq!(r.forces, [0.0]);
    let steps: Vec<f64> = r.history.iter().map(|i| i.step).collect();
    assert_eq!(steps, [1.0, 1.0, 1.0, 0.5]);
    let active: Vec<usize> = r.history.iter().map(|i| i.active).collect();
    assert_eq!(active, [1, 0, 1, 0]);
}

/// A law that stops on a cycle: the set of x = 1 returns at iteration 2.
#[test]
fn a_repeated_set_is_a_cycle() {
    let r = run::<true>(1.0, &NewtonOptions::default()).unwrap();
    assert!(!r.converged);
    assert_eq!(
        r.diagnosis,
        Some(Diagnosis::Cycling {
            iterations: 2,
            residual: 1.0
        })
    );
    assert_eq!(r.failure(), r.diagnosis);
}

/// The limit, a law's failure, a target's failure and a cancel, each with its diagnosis.
#[test]
fn every_stop_says_why() {
    let opts = NewtonOptions {
        max_iterations: 1,
        rtol: 1e-9,
    };
    let r = run::<false>(1.0, &opts).unwrap();
    assert_eq!(
        r.diagnosis,
        Some(Diagnosis::Stalled {
            iterations: 1,
            residual: 1.0
        })
    );
    let r = run::<false>(f64::NAN, &opts).unwrap();
    assert_eq!(r.diagnosis, Some(Diagnosis::Overflow));
    assert_eq!(r.iterations, 0);
    let r = run::<false>(20.0, &opts).unwrap();
    assert!(matches!(r.diagnosis, Some(Diagnosis::Singular { .. })));
    let mut calls = 0;
    let cancelled = drive(&Flip::<false>, vec![1.0], &opts, &mut |_| {
        calls += 1;
        if calls < 2 {
            ControlFlow::Continue(())
        } else {
            ControlFlow::Break(())
        }
    });
    assert!(matches!(cancelled, Err(SolveError::Cancelled)));
}

/// The force balance on a hand-made iterate: implied forces (3, 0) against assumed (0, 4) give
/// R = (3, −4), ‖R‖ = 5 against the scale max(3, 4) = 4; a floor of norm 3 > 4/2 swamps them,
/// unless it lies at a point certainly out of contact; a sign change within the noise keeps
/// the active set settled.
#[test]
fn force_balance_by_hand() {
    let zero = [0.0, 0.0];
    let at = |gap, noise, floor| ForceBalance {
        gap,
        noise,
        implied: &[3.0, 0.0],
        assumed: &[0.0, 4.0],
        mismatch: &[3.0, -4.0],
        floor,
    };
    let m = at(&[1.0, -1.0], &zero, &zero).measure(None, 1e-9);
    assert_eq!(m.active, [true, false]);
    assert_eq!(m.residual, 1.25);
    assert!(m.settled && !m.accurate && !m.swamped);
    // The first point turns inactive by more than its noise: not settled.
    let m2 = at(&[-1.0, -1.0], &zero, &zero).measure(Some(&m.active), 1e-9);
    assert!(!m2.settled);
    // … by no more than its noise: settled; a floor of norm 3 swamps the scale 4.
    let m3 = at(&[-1.0, -1.0], &[1.5, 0.0], &[3.0, 0.0]).measure(Some(&m.active), 1e-9);
    assert!(m3.settled && m3.swamped && !m3.accurate);
    // A point out of contact by more than its noise has no floor: its force is exactly 0.
    let m4 = at(&[1.0, -1.0], &[0.0, 0.5], &[0.0, 3.0]).measure(None, 1e-9);
    assert!(!m4.swamped && !m4.accurate);
    // A tolerance of 2: 5 ≤ 2·4 is accurate.
    assert!(at(&[1.0, -1.0], &zero, &zero).measure(None, 2.0).accurate);
    assert_eq!(count(&m.active), 1);
}

/// A converged result has no failure; one marked not converged (e.g. by a caller's own check)
/// without a cause reads as stalled at its last iteration and residual.
#[test]
fn a_failure_always_has_a_cause() {
    let mut r = run::<false>(1.0, &NewtonOptions::default()).unwrap();
    assert_eq!(r.failure(), None);
    r.converged = false;
    assert_eq!(
        r.failure(),
        Some(Diagnosis::Stalled {
            iterations: 3,
            residual: 0.0
        })
    );
}
