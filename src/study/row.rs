//! One row of a study: a scheme's solve at one level (or ε), its errors, its time and whether
//! every number it reports is meaningful (its status).

use serde::Serialize;

use super::errors::{Errors, Kept};
use super::reference::{Reference, TARGET_SHARE, Target};
use crate::contact::method::MethodFields;
use crate::contact::solution::Solution;
use crate::contact::{Method, Rule};
use crate::discretization::Discretization;
use crate::error::SolveError;
use crate::grading::Grading;
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::warning::Warning;

/// Whether a row of a study or a sweep has a result, and if not, why.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Solved and converged.
    Ok,
    /// The solver ran but cannot certify its answer (the row's numbers are its last iterate).
    NotConverged,
    /// The scheme has no unique answer here (ε = 0 with more points than normal displacements).
    Kernel,
    /// The row could not be computed (too large for the memory, a failed factorisation, …).
    Failed,
}

impl Status {
    /// The status of a row whose solve returned `error`.
    pub fn of_error(error: &SolveError) -> Status {
        match error {
            SolveError::Kernel { .. } => Status::Kernel,
            SolveError::NotConverged { .. } => Status::NotConverged,
            _ => Status::Failed,
        }
    }

    /// The token of JSON and CSV: `ok`, `not_converged`, `kernel`, `failed`.
    pub fn token(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::NotConverged => "not_converged",
            Status::Kernel => "kernel",
            Status::Failed => "failed",
        }
    }

    /// The word shown in tables: `ok`, `not converged`, `kernel`, `failed`.
    pub fn word(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::NotConverged => "not converged",
            Status::Kernel => "kernel",
            Status::Failed => "failed",
        }
    }
}

/// JSON carries [`Status::token`], so that JSON and CSV cannot disagree.
impl Serialize for Status {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.token())
    }
}

/// One line of the study.
#[derive(Clone, Debug, Serialize)]
pub struct StudyRow {
    /// The scheme's label: M1–M4 or `element+rule`.
    pub scheme: String,
    /// The element: `q1`, `q2` or `p1`.
    pub element: Element,
    /// The contact rule.
    pub rule: &'static str,
    /// The mesh level.
    pub level: u32,
    /// The cell size h of the level: the largest cell side.
    pub h: f64,
    /// The penalty parameter ε (0 for `exact`).
    pub epsilon: f64,
    /// The contact method and its parameters (`method`, `theta`, `gamma0`, `alm_tol`).
    #[serde(flatten)]
    pub method: MethodFields,
    /// The number of free dofs.
    pub n_dofs: usize,
    /// The edge-grading passes its mesh had ([`crate::grading`]; 0: the uniform level).
    pub refine_edges: u32,
    /// The smallest cell side of its mesh (h on a uniform level of square cells).
    pub h_min: f64,
    /// The grading asked (`--refine-edges`): what tells its series apart.
    pub grading: Grading,
    /// Whether the row has a certified result.
    pub status: Status,
    /// Why the row has no (certified) result, when it has none.
    pub reason: Option<String>,
    /// Whether the penalty's own load error may be a tenth of the row's or more, so that its
    /// errors and rates may be ε's rather than the mesh's ([`crate::study::penalty_error::dominated`];
    /// set by the command line, false for a row without a penalty).
    pub epsilon_dominated: bool,
    /// Newton iterations (for the ALM, summed over the updates); None without a result.
    pub newton_iterations: Option<usize>,
    /// The ALM's multiplier updates (null for the other methods, or without a result).
    pub outer_iterations: Option<usize>,
    /// Whether Newton converged (false without a result).
    pub converged: bool,
    /// A fresh solve: the mesh's work and Newton (what the pressures need), ms.
    pub solve_ms: Option<f64>,
    /// The load P of the modelled body; None without a result.
    pub load: Option<f64>,
    /// Relative errors against the reference; None without a result.
    pub errors: Option<Errors>,
    /// Observed rates against h (or, in an ε sweep, against ε) from the previous row.
    pub rates: Option<Errors>,
    /// A penalty too soft for the depth ([`Warning::SoftPenalty`]): the row's numbers are the
    /// penalty's, far from the problem's (the study's other weaknesses are in its errors).
    pub warnings: Vec<Warning>,
}

impl StudyRow {
    /// The row of a solve: its result, or what stopped it, and what it keeps of its solution.
    pub(super) fn new(
        reference: &Reference,
        scenario: &Scenario,
        (element, rule): (Element, Rule),
        level: u32,
        (method, epsilon): (Method, f64),
        outcome: Result<(&Discretization, &Solution), &SolveError>,
    ) -> (Self, Option<Kept>) {
        let mut kept = None;
        let mut row = StudyRow {
            scheme: Scheme::new(element, rule).label(),
            element,
            rule: rule.name(),
            level,
            h: scenario.h(level),
            epsilon,
            method: method.into(),
            n_dofs: scenario.n_dofs(level, element),
            refine_edges: 0,
            h_min: scenario.uniform_grid(level).h_min(),
            grading: Grading::default(),
            status: Status::Ok,
            reason: None,
            epsilon_dominated: false,
            newton_iterations: None,
            outer_iterations: None,
            converged: false,
            solve_ms: None,
            load: None,
            errors: None,
            rates: None,
            warnings: Vec::new(),
        };
        match outcome {
            Ok((disc, sol)) => {
                row.method = sol.method_fields();
                row.newton_iterations = Some(sol.newton.iterations);
                row.outer_iterations = sol.outer_iterations;
                row.converged = sol.newton.converged;
                row.solve_ms = Some(sol.timing.total);
                row.load = Some(sol.load);
                row.warnings = sol
                    .warnings
                    .iter()
                    .filter(|w| matches!(w, Warning::SoftPenalty { .. }))
                    .cloned()
                    .collect();
                let k = Kept::of(disc, sol);
                row.errors = Some(k.errors(reference));
                kept = Some(k);
                if !sol.newton.converged {
                    row.status = Status::NotConverged;
                    row.reason = sol.newton.diagnosis.as_ref().map(ToString::to_string);
                }
            }
            Err(e) => {
                row.status = Status::of_error(e);
                row.reason = Some(e.to_string());
            }
        }
        row.certify();
        (row, kept)
    }
}

/// True when every row has a certified result (the study's exit code: 0, else 1).
pub fn all_ok(rows: &[StudyRow]) -> bool {
    rows.iter().all(|r| r.status == Status::Ok)
}

impl Target {
    /// A tenth of the smallest p (or p̄) and u errors of the rows with a result (None when no
    /// row has one).
    pub fn of(rows: &[StudyRow]) -> Option<Self> {
        let ok = || {
            rows.iter()
                .filter(|r| r.status == Status::Ok)
                .filter_map(|r| r.errors)
        };
        let smallest =
            |v: &mut dyn Iterator<Item = f64>| v.filter(|e| *e > 0.0).fold(f64::INFINITY, f64::min);
        let p = smallest(&mut ok().flat_map(|e| [e.p, e.pbar]));
        let u = smallest(&mut ok().map(|e| e.u));
        (p.is_finite() && u.is_finite()).then_some(Target {
            p: TARGET_SHARE * p,
            u: TARGET_SHARE * u,
        })
    }
}
