//! `riplab study` on a two-body scenario (docs/design.md §12, "The study across the
//! interface"): each discretisation of the interface at each level, the two meshes refined
//! together at the scenario's ratio and offset, its error against the scenario's closed form and
//! the observed rate between consecutive levels, its Newton iterations and its time.
//!
//! The closed form: on the contact patch test ([`Scenario::patch_pressure`]) the patch error
//! max_k |p_k − p|/p; on an upper cylinder two-body Hertz, the errors of the half-width a (from
//! the pressure's moments) and of the peak p₀ against Johnson §4.2
//! (`verify::hertz_two_bodies::measure`, the verify pack's own); on any other two-body scenario none, and a
//! row gives the load P and the contact zone instead.

use std::time::Instant;

use serde::Serialize;

use super::Status;
use crate::contact::interface::InterfaceMethod;
use crate::contact::interface::solve::{BodiesError, Enforcement};
use crate::scenario::upper::TwoBodies;
use crate::scenario::{Scenario, UpperShape};
use crate::verify::hertz_two_bodies::measure;

/// An error below this is round-off, not a discretisation error: mortar's patch error is
/// 1e−15 to 1e−13 at every ratio (docs/design.md §12, the contact patch test), so the slope
/// between two such errors is noise. A rate is given only where both errors are at or above it.
pub const ROUND_OFF: f64 = 1e-10;

/// What a two-body scenario's rows are measured against.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ClosedForm {
    /// The contact patch test: the exact pressure is uniform ([`Scenario::patch_pressure`]).
    Patch,
    /// Two-body Hertz (Johnson §4.2): an upper cylinder on the block.
    Hertz,
    /// No closed form: the rows give the load and the contact zone.
    None,
}

impl ClosedForm {
    /// The closed form of `scenario` (a two-body one).
    pub fn of(scenario: &Scenario) -> Self {
        match scenario.upper.as_ref().map(|u| u.shape) {
            _ if scenario.patch_pressure(0.0).is_some() => ClosedForm::Patch,
            Some(UpperShape::Cylinder { .. }) => ClosedForm::Hertz,
            _ => ClosedForm::None,
        }
    }
}

/// A row's relative errors against the closed form (or, as [`InterfaceStudyRow::rates`],
/// their observed rates); each null where the closed form has no such quantity.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct InterfaceErrors {
    /// The patch test's max_k |p_k − p|/p.
    pub patch: Option<f64>,
    /// Hertz's |a_h − a|/a, a_h from the pressure's moments.
    pub a: Option<f64>,
    /// Hertz's |max p − p₀|/p₀.
    pub p0: Option<f64>,
}

impl InterfaceErrors {
    /// The rates from `coarser` (at h0) to `self` (at h1): log(e0/e1)/log(h0/h1) for each
    /// quantity both have at or above [`ROUND_OFF`].
    fn rates_from(&self, coarser: &InterfaceErrors, (h0, h1): (f64, f64)) -> InterfaceErrors {
        let rate = |e0: Option<f64>, e1: Option<f64>| match (e0, e1) {
            (Some(e0), Some(e1)) if e0 >= ROUND_OFF && e1 >= ROUND_OFF && h0 != h1 => {
                Some((e0 / e1).ln() / (h0 / h1).ln())
            }
            _ => None,
        };
        InterfaceErrors {
            patch: rate(coarser.patch, self.patch),
            a: rate(coarser.a, self.a),
            p0: rate(coarser.p0, self.p0),
        }
    }
}

/// Where the pressure is positive: the first and last constraint's x with p > 0.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Zone {
    /// The leftmost x with p > 0.
    pub from: f64,
    /// The rightmost.
    pub to: f64,
}

/// One row: a discretisation at a level.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct InterfaceStudyRow {
    /// The discretisation's name ([`InterfaceMethod::name`]).
    pub contact: &'static str,
    /// The lower body's level (the upper's mesh follows at the ratio).
    pub level: u32,
    /// The lower body's widest cell at the level ([`Scenario::h`]): it halves with each level,
    /// and the upper's with it.
    pub h: f64,
    /// The lower body's unknowns.
    pub dofs_lower: usize,
    /// The upper body's unknowns.
    pub dofs_upper: usize,
    /// `ok`, `not_converged`, `kernel` (exact multipliers that are not unique) or `failed`.
    pub status: &'static str,
    /// Why a row has no result.
    pub reason: Option<String>,
    /// Newton (active-set) iterations (the ALM's over all its updates).
    pub newton_iterations: Option<usize>,
    /// The ALM's multiplier updates.
    pub outer_iterations: Option<usize>,
    /// The two-body solve's wall time (both meshes, their factorisations, the coupling and the
    /// Newton solve), ms.
    pub solve_ms: Option<f64>,
    /// The load carried across the interface.
    #[serde(rename = "P")]
    pub load: Option<f64>,
    /// Where p > 0 (null where no constraint carries a pressure).
    pub contact_zone: Option<Zone>,
    /// The errors against the closed form.
    pub errors: InterfaceErrors,
    /// Their rates from the discretisation's previous level (null on its first row, where
    /// either error is below [`ROUND_OFF`], and where a row has no result).
    pub rates: InterfaceErrors,
}

impl InterfaceStudyRow {
    /// Whether the row has a result.
    pub fn ok(&self) -> bool {
        self.status == Status::Ok.token()
    }
}

/// A study of `methods` at `levels` on the two-body `scenario`, the constraint enforced as
/// `enforcement` says: grouped per method in `methods`' order by ascending level, each row's
/// rates from the one before. A level is solved fresh for each method (its time is the whole
/// two-body solve's).
///
/// # Errors
///
/// The input's faults, which no row can report: a level too large for the memory, two traces
/// that cannot be coupled, an ε the bodies cannot represent, a one-body scenario. A solve
/// that does not converge, has no unique multipliers or fails otherwise is a row with its
/// status and reason.
pub fn study_interface(
    scenario: &Scenario,
    methods: &[InterfaceMethod],
    levels: &[u32],
    enforcement: Enforcement,
) -> Result<Vec<InterfaceStudyRow>, BodiesError> {
    let closed = ClosedForm::of(scenario);
    let mut rows: Vec<InterfaceStudyRow> = Vec::new();
    for &method in methods {
        let mut previous: Option<InterfaceStudyRow> = None;
        for &level in levels {
            let mut row = blank(scenario, method, level)?;
            let t = Instant::now();
            match scenario.solve_bodies(level, method, enforcement) {
                Ok(solved) => fill(&mut row, scenario, closed, &solved, t),
                Err(e) => {
                    let (status, why) = row_failure(e)?;
                    (row.status, row.reason) = (status.token(), Some(why));
                }
            }
            if let Some(prev) = previous.as_ref().filter(|p| p.ok() && row.ok()) {
                row.rates = row.errors.rates_from(&prev.errors, (prev.h, row.h));
            }
            previous = Some(row.clone());
            rows.push(row);
        }
    }
    Ok(rows)
}

/// The row of `method` at `level` before its solve: its sizes, no result yet.
fn blank(scenario: &Scenario, method: InterfaceMethod, level: u32) -> Result<InterfaceStudyRow, BodiesError> {
    let element = scenario.element;
    let upper = scenario.upper_sizes(level, element).ok_or(BodiesError::OneBody)?;
    Ok(InterfaceStudyRow {
        contact: method.name(),
        level,
        h: scenario.h(level),
        dofs_lower: scenario.n_dofs(level, element),
        dofs_upper: upper.unknowns,
        status: Status::Ok.token(),
        reason: None,
        newton_iterations: None,
        outer_iterations: None,
        solve_ms: None,
        load: None,
        contact_zone: None,
        errors: InterfaceErrors::default(),
        rates: InterfaceErrors::default(),
    })
}

/// `row` from `solved`, a solve started at `t`.
fn fill(
    row: &mut InterfaceStudyRow,
    scenario: &Scenario,
    closed: ClosedForm,
    solved: &TwoBodies,
    t: Instant,
) {
    row.solve_ms = Some(t.elapsed().as_secs_f64() * 1e3);
    let sol = &solved.solution;
    row.newton_iterations = Some(sol.iterations);
    row.outer_iterations = sol.outer_iterations;
    row.load = Some(sol.load);
    let mut pressed = sol
        .x
        .iter()
        .zip(&sol.p)
        .filter(|(_, p)| **p > 0.0)
        .map(|(x, _)| *x);
    row.contact_zone = pressed.next().map(|from| Zone {
        from,
        to: pressed.next_back().unwrap_or(from),
    });
    let relative = |computed: f64, exact: f64| ((computed - exact) / exact).abs();
    row.errors = match closed {
        ClosedForm::Patch => InterfaceErrors {
            patch: solved.patch.map(|p| p.1),
            ..InterfaceErrors::default()
        },
        ClosedForm::Hertz => {
            measure(scenario, solved).map_or_else(InterfaceErrors::default, |m| InterfaceErrors {
                a: Some(relative(m.computed.0, m.hertz.0)),
                p0: Some(relative(m.computed.1, m.hertz.1)),
                ..InterfaceErrors::default()
            })
        }
        ClosedForm::None => InterfaceErrors::default(),
    };
}

/// The status and reason of a row whose solve failed with `e`, or `e` itself when it is the
/// input's fault (no row can report it: the study stops).
fn row_failure(e: BodiesError) -> Result<(Status, String), BodiesError> {
    let status = match &e {
        BodiesError::NotUnique { .. } => Status::Kernel,
        BodiesError::NotConverged(_) => Status::NotConverged,
        BodiesError::Mismatch(_) | BodiesError::NonFinite(_) | BodiesError::Unbalanced { .. } => {
            Status::Failed
        }
        BodiesError::Solve(s) if !s.is_input() => Status::of_error(s),
        BodiesError::Solve(_)
        | BodiesError::Epsilon { .. }
        | BodiesError::Coupling(_)
        | BodiesError::OneBody => {
            return Err(e);
        }
    };
    Ok((status, e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    const PATCH: &str = include_str!("../../scenarios/patch-two-blocks.toml");
    const HERTZ: &str = include_str!("../../scenarios/hertz-two-bodies.toml");

    /// The rate is log(e₀/e₁)/log(h₀/h₁) (by hand: 1e-3 to 2.5e-4 as h halves is 2), absent
    /// where either error is round-off or the closed form has no such quantity.
    #[test]
    fn rates_and_the_round_off_floor() {
        let errors = |patch: f64| InterfaceErrors {
            patch: Some(patch),
            ..InterfaceErrors::default()
        };
        let halving = (0.5, 0.25);
        let r = errors(2.5e-4).rates_from(&errors(1e-3), halving);
        assert!((r.patch.unwrap() - 2.0).abs() < 1e-12, "{r:?}");
        assert_eq!((r.a, r.p0), (None, None));
        for (e0, e1) in [(3e-15, 7e-15), (1e-3, 1e-16), (1e-16, 1e-3), (1e-3, 0.0)] {
            assert_eq!(
                errors(e1).rates_from(&errors(e0), halving).patch,
                None,
                "{e0} {e1}"
            );
        }
        // At the floor itself the rate is given.
        let r = errors(ROUND_OFF).rates_from(&errors(2.0 * ROUND_OFF), halving);
        assert!((r.patch.unwrap() - 1.0).abs() < 1e-12, "{r:?}");
    }

    /// The bundled scenarios' closed forms, and none once the patch test's rollers are gone.
    #[test]
    fn each_scenario_has_its_closed_form() {
        let patch = Scenario::parse(PATCH, "patch").unwrap();
        assert_eq!(ClosedForm::of(&patch), ClosedForm::Patch);
        let hertz = Scenario::parse(HERTZ, "hertz").unwrap();
        assert_eq!(ClosedForm::of(&hertz), ClosedForm::Hertz);
        let clamped = PATCH.replacen("support = \"roller\"", "support = \"clamped\"", 1);
        let clamped = Scenario::parse(&clamped, "clamped").unwrap();
        assert_eq!(ClosedForm::of(&clamped), ClosedForm::None);
    }
}
