//! The loading path (docs/design.md §11): the press to depth d at ξ = 0 from rest (anchors
//! r̂ = 0; with the law's bound, or frictionless when [`super::Press::Frictionless`]), then the shift in `steps` equal quasi-static steps ξ_k = kξ/m, each warm-started
//! from the last and followed by the anchors' update (exact and ALM: r̂ ← r; penalty:
//! r̂ ← r + (ε_t/w) z at contact points, so that a stuck point keeps its spring's rest
//! position). A step that does not converge is bisected, up to [`MAX_BISECTIONS`] levels;
//! then the solve stops, not converged, saying at which shift. Coulomb's law is
//! history-dependent: the answer depends on the steps (docs/design.md §11, the measured
//! default [`super::DEFAULT_STEPS`]).
//!
//! The augmented Lagrangian is Uzawa on (λ_n, λ_t) per unit length around the penalised
//! step, as [`crate::contact::alm`]: the inner step is the penalty with d + ελ_n and the
//! anchors r̂ + ε_t λ_t, and the updates λ ← (y, z)/w converge to the exact law.

use std::ops::ControlFlow;

use serde::Serialize;

use super::State;
use super::law::Couplings;
use super::law::{Bound, Imposition, StepProblem};
use super::newton::{StepResult, solve_step};
use crate::contact::alm::MAX_OUTER;
use crate::contact::newton::{Iteration, NewtonOptions};
use crate::error::{Diagnosis, SolveError};

/// The most bisections of a failing shift step (2⁵ = 32 sub-steps).
pub const MAX_BISECTIONS: u32 = 5;

/// What one shift step took.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct StepReport {
    /// The shift ξ at the end of the step (0: the press).
    pub shift: f64,
    /// Newton iterations (summed over sub-steps and ALM updates).
    pub iterations: usize,
    /// Sub-steps the step was cut into (1 when it converged at once).
    pub substeps: usize,
}

/// The path's problem: one mesh and rule, one law and imposition.
pub struct PathProblem<'a> {
    /// G_nn, G_nt, G_tt between the points.
    pub couplings: &'a Couplings,
    /// d = B_n u₀ − g.
    pub d: &'a [f64],
    /// e = B_t u₀.
    pub e: &'a [f64],
    /// The rule's weights.
    pub weight: &'a [f64],
    /// The law's bound.
    pub bound: Bound<'a>,
    /// The bound during the press: the law's, or Coulomb's with μ = 0 for a frictionless
    /// press.
    pub press_bound: Bound<'a>,
    /// Exact or penalised (ALM: penalised, with `alm`).
    pub imposition: Imposition,
    /// The ALM's tolerance on the multipliers' relative change, when the ALM.
    pub alm: Option<f64>,
    /// The final shift ξ.
    pub shift: f64,
    /// The shift steps m.
    pub steps: usize,
}

/// The end of a path.
#[derive(Clone, Debug)]
pub struct PathResult {
    /// The last step's result (at the final shift when converged).
    pub last: StepResult,
    /// Per step, the press first.
    pub steps: Vec<StepReport>,
    /// ALM multiplier updates, summed (None for other impositions).
    pub outer: Option<usize>,
    /// Every iteration of every step.
    pub history: Vec<Iteration>,
}

/// The state carried between steps.
#[derive(Clone)]
struct Carried {
    y: Vec<f64>,
    z: Vec<f64>,
    anchor: Vec<f64>,
}

impl<'a> PathProblem<'a> {
    /// The step problem at `shift` with the normal data `d`, the anchors `anchor` (the
    /// ALM's inner problems shift both by its multipliers) and the bound `bound`.
    fn at<'b>(&self, d: &'b [f64], shift: f64, anchor: &'b [f64], bound: Bound<'b>) -> StepProblem<'b>
    where
        'a: 'b,
    {
        StepProblem {
            couplings: self.couplings,
            d,
            e: self.e,
            weight: self.weight,
            bound,
            imposition: self.imposition,
            shift,
            anchor,
        }
    }

    /// The step at `shift` from `from` (forces warm, anchors fixed) under `bound`.
    fn step(
        &self,
        from: &Carried,
        shift: f64,
        bound: Bound<'a>,
        opts: &NewtonOptions,
        outer: &mut usize,
        on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
    ) -> Result<StepResult, SolveError> {
        let Some(tolerance) = self.alm else {
            let pb = self.at(self.d, shift, &from.anchor, bound);
            return solve_step(&pb, from.y.clone(), from.z.clone(), opts, on_iteration);
        };
        let Imposition::Penalty { epsilon, epsilon_t } = self.imposition else {
            unreachable!("the ALM is penalised")
        };
        let n = self.d.len();
        let w = self.weight;
        let (mut y, mut z) = (from.y.clone(), from.z.clone());
        let inner = NewtonOptions {
            rtol: opts.rtol.min(1e-2 * tolerance),
            ..*opts
        };
        let mut iterations = 0;
        let mut history = Vec::new();
        for k in 1..=MAX_OUTER {
            let d: Vec<f64> = (0..n).map(|q| self.d[q] + epsilon * y[q] / w[q]).collect();
            let anchor: Vec<f64> = (0..n).map(|q| from.anchor[q] + epsilon_t * z[q] / w[q]).collect();
            let pb = self.at(&d, shift, &anchor, bound);
            let mut r = solve_step(&pb, y.clone(), z.clone(), &inner, on_iteration)?;
            iterations += r.iterations;
            history.append(&mut r.history);
            *outer += 1;
            let change: f64 = (0..n)
                .map(|q| (r.y[q] - y[q]).powi(2) + (r.z[q] - z[q]).powi(2))
                .sum();
            let size: f64 = (0..n).map(|q| r.y[q].powi(2) + r.z[q].powi(2)).sum();
            // The true s: the inner's less the shift ελ_n.
            for q in 0..n {
                r.s[q] -= epsilon * y[q] / w[q];
            }
            (y, z) = (r.y.clone(), r.z.clone());
            r.iterations = iterations;
            r.history = history.clone();
            if let Some(inner) = r.diagnosis.take() {
                r.diagnosis = Some(Diagnosis::Inner {
                    outer: k,
                    inner: Box::new(inner),
                });
                return Ok(r);
            }
            if change.sqrt() <= tolerance * size.sqrt() || size == 0.0 {
                return Ok(r);
            }
            if k == MAX_OUTER {
                r.diagnosis = Some(Diagnosis::Updates {
                    updates: MAX_OUTER,
                    change: (change / size).sqrt(),
                });
                return Ok(r);
            }
        }
        unreachable!("the loop returns")
    }

    /// The anchors after a converged step.
    fn anchors(&self, r: &StepResult) -> Vec<f64> {
        (0..r.r.len())
            .map(|q| match self.imposition {
                Imposition::Penalty { epsilon_t, .. } if self.alm.is_none() && r.states[q] != State::Open => {
                    r.r[q] + epsilon_t / self.weight[q] * r.z[q]
                }
                _ => r.r[q],
            })
            .collect()
    }

    /// The press and the shift steps, from the forces `initial` (y, z) when given.
    pub fn solve(
        &self,
        initial: Option<(&[f64], &[f64])>,
        opts: &NewtonOptions,
        on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
    ) -> Result<PathResult, SolveError> {
        let n = self.d.len();
        let (y, z) = initial
            .filter(|(y, z)| y.len() == n && z.len() == n)
            .map_or_else(|| (vec![0.0; n], vec![0.0; n]), |(y, z)| (y.to_vec(), z.to_vec()));
        let mut carried = Carried {
            y,
            z,
            anchor: vec![0.0; n],
        };
        let mut outer = 0;
        let mut reports = Vec::new();
        let mut history = Vec::new();
        let press = self.step(&carried, 0.0, self.press_bound, opts, &mut outer, on_iteration)?;
        history.extend_from_slice(&press.history);
        reports.push(StepReport {
            shift: 0.0,
            iterations: press.iterations,
            substeps: 1,
        });
        let mut last = press;
        if last.converged() {
            carried = Carried {
                y: last.y.clone(),
                z: last.z.clone(),
                anchor: self.anchors(&last),
            };
            for k in 1..=self.steps {
                let (from, to) = (
                    self.shift * (k - 1) as f64 / self.steps as f64,
                    self.shift * k as f64 / self.steps as f64,
                );
                let mut report = StepReport {
                    shift: to,
                    iterations: 0,
                    substeps: 0,
                };
                let (end, ok) = self.advance(
                    &mut carried,
                    from,
                    to,
                    0,
                    &mut report,
                    &mut history,
                    &mut outer,
                    opts,
                    on_iteration,
                )?;
                reports.push(report);
                last = end;
                if !ok {
                    break;
                }
            }
        } else {
            last.diagnosis = last.diagnosis.map(|d| Diagnosis::Press(Box::new(d)));
        }
        let iterations = reports.iter().map(|r| r.iterations).sum();
        last.iterations = iterations;
        Ok(PathResult {
            last,
            steps: reports,
            outer: self.alm.map(|_| outer),
            history,
        })
    }

    /// Advance `carried` from shift `from` to `to`, bisecting a failing step; the last step's
    /// result and whether it converged.
    #[allow(clippy::too_many_arguments)]
    fn advance(
        &self,
        carried: &mut Carried,
        from: f64,
        to: f64,
        depth: u32,
        report: &mut StepReport,
        history: &mut Vec<Iteration>,
        outer: &mut usize,
        opts: &NewtonOptions,
        on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
    ) -> Result<(StepResult, bool), SolveError> {
        let r = self.step(carried, to, self.bound, opts, outer, on_iteration)?;
        report.iterations += r.iterations;
        history.extend_from_slice(&r.history);
        if r.converged() {
            report.substeps += 1;
            *carried = Carried {
                y: r.y.clone(),
                z: r.z.clone(),
                anchor: self.anchors(&r),
            };
            return Ok((r, true));
        }
        if depth >= MAX_BISECTIONS {
            let mut r = r;
            let cause = r.diagnosis.take().unwrap_or(Diagnosis::Stalled {
                iterations: r.iterations,
                residual: r.residual,
            });
            r.diagnosis = Some(Diagnosis::Shift {
                from,
                to,
                bisections: MAX_BISECTIONS,
                cause: Box::new(cause),
            });
            return Ok((r, false));
        }
        let mid = 0.5 * (from + to);
        let (r, ok) = self.advance(
            carried,
            from,
            mid,
            depth + 1,
            report,
            history,
            outer,
            opts,
            on_iteration,
        )?;
        if !ok {
            return Ok((r, false));
        }
        self.advance(
            carried,
            mid,
            to,
            depth + 1,
            report,
            history,
            outer,
            opts,
            on_iteration,
        )
    }
}

/// What a friction solve adds to a [`crate::contact::solution::Solution`].
#[derive(Clone, Debug)]
pub struct FrictionSolution {
    /// The law and loading used.
    pub friction: super::Friction,
    /// Tangential forces z at the rule's points (on the body, along +x).
    pub z: Vec<f64>,
    /// The raw tangential traction t = z/w at the points.
    pub t: Vec<f64>,
    /// The smoothed t̄ at the Γ_C vertices, p̄'s weights (16)–(17).
    pub tbar: Vec<f64>,
    /// Each point's state.
    pub states: Vec<State>,
    /// u_x at the Γ_C vertices.
    pub vertex_ux: Vec<f64>,
    /// Q = I(t, 1) = Σ z.
    pub tangential_load: f64,
    /// Per step, the press first.
    pub steps: Vec<StepReport>,
}
