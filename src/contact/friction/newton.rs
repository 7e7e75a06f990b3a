//! One shift step's semismooth Newton on the normal and tangential forces together
//! (docs/design.md §11): the primal–dual active-set form of Hüeber, Stadler and Wohlmuth
//! (2008), equivalently Alart–Curnier's generalized Newton on the natural residual of
//! [`super::law`]. Each iterate's states (open, stick, slip ±) give the next iterate as the
//! solution of [`super::system::target`]: F is piecewise linear, so a full step lands on the
//! solution of the current sets. Converged means the natural residual is within the
//! relative tolerance plus the round-off floor. A set of states seen before (a cycle) takes a
//! damped step instead, the best of 1, ½, …, 1/64 on ‖F‖; a system that does not solve, the
//! iteration limit or a non-finite residual end the step as not converged, with why.
//!
//! The iterate/stop/damp logic here is independent of the law (it sees codes and norms):
//! it is meant to move onto the project's single semismooth Newton driver (issue 33).

use std::collections::HashSet;
use std::ops::ControlFlow;

use super::State;
use super::law::{Eval, StepProblem};
use super::system::target;
use crate::contact::penalty::{Iteration, NewtonOptions};
use crate::error::SolveError;

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
    /// Whether the natural residual met the tolerance.
    pub converged: bool,
    /// The last relative natural residual.
    pub residual: f64,
    /// Why not, when not converged.
    pub diagnosis: Option<String>,
    /// Every iteration.
    pub history: Vec<Iteration>,
}

/// The relative natural residual of `ev` at (y, z) and whether it is accurate (within
/// `rtol` plus the floor) or swamped by round-off.
fn measure(ev: &Eval, y: &[f64], z: &[f64], rtol: f64) -> (f64, bool, bool) {
    let (res, scale, floor) = ev.residual(y, z);
    let rel = if scale > 0.0 { res / scale } else { res };
    let swamped = scale > 0.0 && floor > 0.5 * scale;
    (rel, res <= rtol * scale + floor, swamped)
}

/// Solve the step `pb` from the forces (y, z), reporting each iteration to `on_iteration`
/// (which may cancel).
pub fn solve_step(
    pb: &StepProblem,
    mut y: Vec<f64>,
    mut z: Vec<f64>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<StepResult, SolveError> {
    let mut seen: HashSet<Vec<u8>> = HashSet::new();
    let mut history = Vec::new();
    let mut step = 1.0;
    for it in 0.. {
        let ev = pb.evaluate(&y, &z);
        let (residual, accurate, swamped) = measure(&ev, &y, &z, opts.rtol);
        let info = Iteration {
            iteration: it,
            residual,
            active: ev.states.iter().filter(|&&s| s != State::Open).count(),
            step,
        };
        history.push(info);
        if on_iteration(&info).is_break() {
            return Err(SolveError::Cancelled);
        }
        let finish = |y, z, converged, diagnosis: Option<String>| StepResult {
            y,
            z,
            s: ev.s.clone(),
            r: ev.r.clone(),
            states: ev.states.clone(),
            iterations: it,
            converged,
            residual,
            diagnosis,
            history: history.clone(),
        };
        if accurate && !swamped && residual.is_finite() {
            return Ok(finish(y, z, true, None));
        }
        if swamped {
            return Ok(finish(y, z, false, Some("ε or ε_t is below what double precision resolves here: round-off in u − g, amplified by 1/ε, is as large as the forces; use a larger ε".into())));
        }
        if !residual.is_finite() || it >= opts.max_iterations {
            let why = if residual.is_finite() {
                format!("no convergence in {it} Newton iterations (relative residual {residual:.1e})")
            } else {
                "the residual is not finite".into()
            };
            return Ok(finish(y, z, false, Some(why)));
        }
        let (ty, tz) = match target(pb, &ev.states, &ev.sign) {
            Ok((ty, tz, _)) => (ty, tz),
            Err(e) => return Ok(finish(y, z, false, Some(e.to_string()))),
        };
        step = 1.0;
        if !seen.insert(ev.codes()) {
            // A cycle: the best damped step on ‖F‖.
            let mut best = (f64::INFINITY, 1.0);
            for k in 0..=DAMPING_HALVINGS {
                let a = 0.5_f64.powi(k);
                let (ya, za) = blend(&y, &ty, &z, &tz, a);
                let (res, scale, _) = pb.evaluate(&ya, &za).residual(&ya, &za);
                let rel = if scale > 0.0 { res / scale } else { res };
                if rel < best.0 {
                    best = (rel, a);
                }
            }
            step = best.1;
        }
        (y, z) = blend(&y, &ty, &z, &tz, step);
    }
    unreachable!("the loop returns")
}

/// (y + a(ty − y), z + a(tz − z)).
fn blend(y: &[f64], ty: &[f64], z: &[f64], tz: &[f64], a: f64) -> (Vec<f64>, Vec<f64>) {
    let mix = |u: &[f64], v: &[f64]| {
        u.iter()
            .zip(v)
            .map(|(p, q)| if a == 1.0 { *q } else { p + a * (q - p) })
            .collect()
    };
    (mix(y, ty), mix(z, tz))
}
