//! The semismooth Newton driver shared by every contact method (docs/design.md §3): the
//! penalty (11) ([`super::penalty`]), the exact multipliers ([`super::signorini`]), the
//! augmented Lagrangian's inner solves ([`super::alm`]) and Nitsche ([`crate::contact::nitsche`]).
//!
//! A method supplies only its law (`SemismoothLaw`): the state set of an iterate (the active
//! set u_n − g > 0 of the complementarity, or any other method-defined set of point states),
//! the relative residual and its stop test, the target of the linear system of a state set,
//! and the step towards it. The driver owns the rest: the iterate, the report of each
//! iteration (which the caller may cancel), the state sets seen (a repeated one is a cycle: the
//! law damps the step, or the iteration stops), the iteration limit, the diagnosis of a
//! non-convergence ([`Diagnosis`]) and the result.

use std::collections::HashSet;
use std::hash::Hash;
use std::ops::ControlFlow;

use crate::error::{Diagnosis, SolveError};

/// The stopping rules of the semismooth Newton iteration.
#[derive(Clone, Copy, Debug)]
pub struct NewtonOptions {
    /// The most Newton iterations before giving up (not converged).
    pub max_iterations: usize,
    /// Relative residual (e.g. ‖Bᵀ(Wp − y)‖ / ‖BᵀWp‖ for (11)) below which an unchanged
    /// active set is accepted (plus the floor that round-off in u_n − g sets at small ε).
    pub rtol: f64,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions {
            max_iterations: 100,
            rtol: 1e-9,
        }
    }
}

/// The state after `iteration` Newton steps, reported to the caller as it goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iteration {
    /// Newton steps taken so far.
    pub iteration: usize,
    /// The relative residual of [`NewtonOptions::rtol`] after them.
    pub residual: f64,
    /// The number of active points (u_n − g > 0).
    pub active: usize,
    /// The step length that led here (1 for a full Newton step).
    pub step: f64,
}

/// The result of a semismooth Newton solve on the rule's points.
#[derive(Clone, Debug)]
pub struct NewtonResult {
    /// Contact forces y = W p at the rule's points (the warm start of a later solve).
    pub forces: Vec<f64>,
    /// u_n − g at the contact points.
    pub violation: Vec<f64>,
    /// Newton iterations taken.
    pub iterations: usize,
    /// Whether the convergence test of [`NewtonOptions`] was met.
    pub converged: bool,
    /// The final relative residual ([`NewtonOptions::rtol`]).
    pub residual: f64,
    /// Every iteration, in order.
    pub history: Vec<Iteration>,
    /// Why the solve did not converge, when it did not.
    pub diagnosis: Option<Diagnosis>,
}

impl NewtonResult {
    /// Why the solve did not converge (None when it did); a result marked not converged
    /// without a cause reads as stalled at its last residual.
    pub fn failure(&self) -> Option<Diagnosis> {
        (!self.converged).then(|| {
            self.diagnosis.clone().unwrap_or(Diagnosis::Stalled {
                iterations: self.iterations,
                residual: self.residual,
            })
        })
    }
}

/// What a law finds of an iterate ([`SemismoothLaw::assess`]).
pub(crate) struct Assessment<S, V> {
    /// The iterate's state set (e.g. the active set).
    pub states: S,
    /// How many points are active, for the report.
    pub active: usize,
    /// The relative residual.
    pub residual: f64,
    /// Whether to stop here.
    pub verdict: Verdict,
    /// What else the law computed of the iterate (e.g. u_n − g), for its step and its result.
    pub values: V,
}

/// A law's verdict on an iterate.
pub(crate) enum Verdict {
    /// The iterate meets the law's stop test.
    Converged,
    /// No iterate can be certified, for the reason given.
    Fail(Diagnosis),
    /// On to the next Newton step (unless the driver stops: a cycle, the limit).
    Continue,
}

/// A contact law solved by [`drive`]: what distinguishes one method's Newton from another's.
pub(crate) trait SemismoothLaw {
    /// The state set of an iterate: the active set, or the states of the points.
    type States: Clone + Eq + Hash;
    /// What [`SemismoothLaw::assess`] computes beside the state set.
    type Values;
    /// Whether a repeated state set ends the iteration as a cycle ([`Diagnosis::Cycling`])
    /// instead of being handed to [`SemismoothLaw::step`].
    const CYCLE_STOPS: bool = false;

    /// The state set, the residual and the verdict of the iterate `x`; `previous` is the state
    /// set of the iterate before it (None at the start).
    fn assess(
        &self,
        x: &[f64],
        previous: Option<&Self::States>,
        opts: &NewtonOptions,
    ) -> Assessment<Self::States, Self::Values>;

    /// The Newton target of the state set of `now`: the solution of its linear system, or why
    /// there is none.
    fn target(&self, x: &[f64], now: &Assessment<Self::States, Self::Values>) -> Result<Vec<f64>, Diagnosis>;

    /// The step length from `x` towards `target` (damping or a line search); `repeated`:
    /// the state set was seen before. A full step by default.
    fn step(
        &self,
        _x: &[f64],
        _target: &[f64],
        _now: &Assessment<Self::States, Self::Values>,
        _repeated: bool,
    ) -> f64 {
        1.0
    }

    /// The next iterate: x + step (target − x).
    fn update(&self, x: &mut Vec<f64>, target: Vec<f64>, step: f64) {
        for (xq, tq) in x.iter_mut().zip(&target) {
            *xq += step * (tq - *xq);
        }
    }
}

/// Where [`drive`] stopped.
pub(crate) struct Outcome<S, V> {
    /// The last iterate.
    pub x: Vec<f64>,
    /// The law's assessment of it.
    pub last: Assessment<S, V>,
    /// Newton iterations taken.
    pub iterations: usize,
    /// Why it is not converged (None when it is).
    pub diagnosis: Option<Diagnosis>,
    /// Every iteration, in order.
    pub history: Vec<Iteration>,
}

impl<S, V> Outcome<S, V> {
    /// The result with the contact forces `forces` and the violation `violation`.
    pub fn result(self, forces: Vec<f64>, violation: Vec<f64>) -> NewtonResult {
        NewtonResult {
            forces,
            violation,
            iterations: self.iterations,
            converged: self.diagnosis.is_none(),
            residual: self.last.residual,
            history: self.history,
            diagnosis: self.diagnosis,
        }
    }
}

/// Iterate the law from `x`, reporting each iteration to `on_iteration` (its break is
/// [`SolveError::Cancelled`]), until the law's test is met, it fails, a state set repeats
/// ([`SemismoothLaw::CYCLE_STOPS`]), the residual is not finite or the iteration limit is
/// reached.
pub(crate) fn drive<L: SemismoothLaw>(
    law: &L,
    mut x: Vec<f64>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<Outcome<L::States, L::Values>, SolveError> {
    let mut history = Vec::new();
    let mut seen: HashSet<L::States> = HashSet::new();
    let mut previous: Option<L::States> = None;
    let mut step = 1.0;
    for iterations in 0.. {
        let now = law.assess(&x, previous.as_ref(), opts);
        let info = Iteration {
            iteration: iterations,
            residual: now.residual,
            active: now.active,
            step,
        };
        history.push(info);
        if on_iteration(&info).is_break() {
            return Err(SolveError::Cancelled);
        }
        let repeated = !seen.insert(now.states.clone());
        let residual = now.residual;
        let stop = match &now.verdict {
            Verdict::Converged => Some(None),
            Verdict::Fail(why) => Some(Some(why.clone())),
            Verdict::Continue if repeated && L::CYCLE_STOPS => {
                Some(Some(Diagnosis::Cycling { iterations, residual }))
            }
            Verdict::Continue if iterations == opts.max_iterations || !residual.is_finite() => {
                Some(Some(Diagnosis::Stalled { iterations, residual }))
            }
            Verdict::Continue => None,
        };
        let target = match stop {
            Some(diagnosis) => Err(diagnosis),
            None => law.target(&x, &now).map_err(Some),
        };
        let target = match target {
            Ok(target) => target,
            Err(diagnosis) => {
                return Ok(Outcome {
                    x,
                    last: now,
                    iterations,
                    diagnosis,
                    history,
                });
            }
        };
        step = law.step(&x, &target, &now, repeated);
        law.update(&mut x, target, step);
        previous = Some(now.states);
    }
    unreachable!("the loop returns")
}

/// An iterate of a law whose residual is a mismatch of contact forces at the rule's points
/// (the penalty (11), Nitsche), in force units.
pub(crate) struct ForceBalance<'a> {
    /// u_n − g (or a positive multiple of it): the point is active where it is > 0.
    pub gap: &'a [f64],
    /// The round-off in `gap` ([`super::penalty::round_off`]).
    pub noise: &'a [f64],
    /// The forces the displacement implies.
    pub implied: &'a [f64],
    /// The forces assumed.
    pub assumed: &'a [f64],
    /// The mismatch of the two (the residual R).
    pub mismatch: &'a [f64],
    /// The round-off floor of the implied forces at each point. It counts only where the
    /// point may be active (`gap` > −`noise`): elsewhere the implied force is exactly 0, so a
    /// point far outside the contact zone (its round-off O(|g|) huge next to a press of
    /// 1e-300) neither loosens the tolerance nor swamps the forces.
    pub floor: &'a [f64],
}

/// What [`ForceBalance::measure`] finds.
pub(crate) struct Balance {
    /// The active set: the points with `gap` > 0.
    pub active: Vec<bool>,
    /// ‖R‖ relative to the larger of the implied and the assumed forces (0 with no force).
    pub residual: f64,
    /// The active set is the previous iterate's, but for points whose sign is round-off.
    pub settled: bool,
    /// ‖R‖ within the relative tolerance plus the round-off floor.
    pub accurate: bool,
    /// Round-off alone could account for forces as large as the forces themselves: no
    /// iterate can be certified (the penalty's ε too small for double precision).
    pub swamped: bool,
}

impl ForceBalance<'_> {
    /// The stop test of a force balance: the active set unchanged since `previous` and ‖R‖
    /// below `rtol` relative plus the round-off floor.
    pub fn measure(&self, previous: Option<&Vec<bool>>, rtol: f64) -> Balance {
        let active: Vec<bool> = self.gap.iter().map(|&v| v > 0.0).collect();
        let scale = norm(self.implied).max(norm(self.assumed));
        let residual = if scale > 0.0 {
            norm(self.mismatch) / scale
        } else {
            0.0
        };
        let settled = previous.is_none_or(|prev| {
            (0..active.len()).all(|q| prev[q] == active[q] || self.gap[q].abs() <= self.noise[q])
        });
        let floor: Vec<f64> = (0..self.floor.len())
            .map(|q| {
                if self.gap[q] > -self.noise[q] {
                    self.floor[q]
                } else {
                    0.0
                }
            })
            .collect();
        let floor = norm(&floor);
        Balance {
            active,
            residual,
            settled,
            accurate: norm(self.mismatch) <= rtol * scale + floor,
            swamped: scale > 0.0 && floor > 0.5 * scale,
        }
    }
}

impl Balance {
    /// The assessment of an iterate so measured, with the law's `verdict` and `values`.
    pub fn assessment<V>(self, verdict: Verdict, values: V) -> Assessment<Vec<bool>, V> {
        Assessment {
            active: count(&self.active),
            states: self.active,
            residual: self.residual,
            verdict,
            values,
        }
    }
}

/// The number of `true` in an active set.
pub(crate) fn count(active: &[bool]) -> usize {
    active.iter().filter(|&&a| a).count()
}

/// ‖v‖₂ scaled by its largest entry, so that forces of 1e-297 (a press of 1e-300) neither
/// square to 0 nor read as no force.
pub(crate) fn norm(v: &[f64]) -> f64 {
    let m = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * v.iter().map(|x| (x / m) * (x / m)).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests;
