//! One shift step's semismooth Newton on the normal and tangential forces together
//! (docs/design.md §11), on the project's driver (`contact::newton::drive`): the
//! primal–dual active-set form of Hüeber, Stadler and Wohlmuth (2008), equivalently
//! Alart–Curnier's generalized Newton on the natural residual of [`super::law`]. The iterate
//! is x = (y, z); its state set is the points' codes (open, stick, slip + or −, so that a
//! reversed slip is a change); the target of a set is [`super::system::target`] (F is
//! piecewise linear, so a full step lands on the solution of the current sets). Converged:
//! the natural residual within the relative tolerance plus the round-off floor. Each step
//! backtracks on ‖F‖ (the first of 1, ½, …, 1/64 that decreases it); when none does, the
//! full step, or on a set seen before (a cycle) the best of them.

use std::ops::ControlFlow;

use super::State;
use super::law::{Eval, Imposition, StepProblem};
use super::system::target;
use crate::contact::newton::{Assessment, Iteration, NewtonOptions, SemismoothLaw, Verdict, drive};
use crate::error::{Diagnosis, SolveError};

/// The most halvings of a damped step.
const DAMPING_HALVINGS: i32 = 6;

/// A step's result.
#[derive(Clone, Debug)]
pub struct StepResult {
    /// Normal forces y at the points.
    pub y: Vec<f64>,
    /// Tangential forces z at the points (on the body, along +x).
    pub z: Vec<f64>,
    /// s = u_n − g at the points.
    pub s: Vec<f64>,
    /// The relative tangential displacement r at the points.
    pub r: Vec<f64>,
    /// The states of the last iterate.
    pub states: Vec<State>,
    /// Newton iterations taken.
    pub iterations: usize,
    /// The last relative natural residual.
    pub residual: f64,
    /// Why not converged (None when converged).
    pub diagnosis: Option<Diagnosis>,
    /// Every iteration.
    pub history: Vec<Iteration>,
}

impl StepResult {
    /// Whether the step converged.
    pub fn converged(&self) -> bool {
        self.diagnosis.is_none()
    }
}

/// The relative natural residual ‖F‖ of `ev` at (y, z), whether it is accurate (within
/// `rtol` plus the round-off floor) and whether round-off swamps it.
fn measure(ev: &Eval, y: &[f64], z: &[f64], rtol: f64) -> (f64, bool, bool) {
    let (res, scale, floor) = ev.residual(y, z);
    let rel = if scale > 0.0 { res / scale } else { res };
    (
        rel,
        res <= rtol * scale + floor,
        scale > 0.0 && floor > 0.5 * scale,
    )
}

/// The law of one step for the driver.
struct StepLaw<'a, 'b>(&'a StepProblem<'b>);

impl StepLaw<'_, '_> {
    fn split<'x>(&self, x: &'x [f64]) -> (&'x [f64], &'x [f64]) {
        x.split_at(self.0.len())
    }

    /// ‖F‖ at x, in force units.
    fn absolute_residual(&self, x: &[f64]) -> f64 {
        let (y, z) = self.split(x);
        self.0.evaluate(y, z).residual(y, z).0
    }
}

impl SemismoothLaw for StepLaw<'_, '_> {
    type States = Vec<u8>;
    type Values = Eval;

    fn assess(
        &self,
        x: &[f64],
        _previous: Option<&Vec<u8>>,
        opts: &NewtonOptions,
    ) -> Assessment<Vec<u8>, Eval> {
        let (y, z) = self.split(x);
        let ev = self.0.evaluate(y, z);
        let (residual, accurate, swamped) = measure(&ev, y, z, opts.rtol);
        let verdict = match self.0.imposition {
            Imposition::Penalty { epsilon, epsilon_t } if swamped => Verdict::Fail(Diagnosis::Swamped {
                epsilon: epsilon.min(epsilon_t),
            }),
            _ if accurate && residual.is_finite() => Verdict::Converged,
            _ => Verdict::Continue,
        };
        Assessment {
            states: ev.codes(),
            active: ev.states.iter().filter(|&&s| s != State::Open).count(),
            residual,
            verdict,
            values: ev,
        }
    }

    fn target(&self, _x: &[f64], now: &Assessment<Vec<u8>, Eval>) -> Result<Vec<f64>, Diagnosis> {
        let (mut y, z, _) = target(self.0, &now.values.states, &now.values.sign)?;
        y.extend(z);
        Ok(y)
    }

    fn step(&self, x: &[f64], target: &[f64], now: &Assessment<Vec<u8>, Eval>, repeated: bool) -> f64 {
        // Backtracking on ‖F‖: the first of 1, ½, …, 1/64 that decreases it enough; when none
        // does, the full step (the active-set jump) unless the set repeats, then the best.
        let (y, z) = self.split(x);
        let start = now.values.residual(y, z).0;
        let mut best = (f64::INFINITY, 1.0);
        for k in 0..=DAMPING_HALVINGS {
            let a = 0.5_f64.powi(k);
            let xa: Vec<f64> = x.iter().zip(target).map(|(p, q)| p + a * (q - p)).collect();
            let f = self.absolute_residual(&xa);
            if f < (1.0 - 1e-4 * a) * start {
                return a;
            }
            if f < best.0 {
                best = (f, a);
            }
        }
        if repeated { best.1 } else { 1.0 }
    }
}

/// Solve the step `pb` from the forces (y, z), reporting each iteration to `on_iteration`
/// (which may cancel).
pub fn solve_step(
    pb: &StepProblem,
    y: Vec<f64>,
    z: Vec<f64>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<StepResult, SolveError> {
    let n = pb.len();
    let mut x = y;
    x.extend(z);
    let out = drive(&StepLaw(pb), x, opts, on_iteration)?;
    let z = out.x[n..].to_vec();
    let mut y = out.x;
    y.truncate(n);
    let ev = out.last.values;
    Ok(StepResult {
        y,
        z,
        s: ev.s,
        r: ev.r,
        states: ev.states,
        iterations: out.iterations,
        residual: out.last.residual,
        diagnosis: out.diagnosis,
        history: out.history,
    })
}
