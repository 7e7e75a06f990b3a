//! `riplab verify`: a pack of verification cases (docs/design.md §7). Every check is one
//! comparison of one of three kinds ([`Kind`]): **closed form** — riplab against a published
//! formula, within a tolerance that the discretisation at the case's level allows;
//! **consistency** — riplab against riplab (the ALM against the exact constraint, the
//! penalty's approach to it, the finite block against a larger one), which shows the numerics
//! agree with themselves but not that they are right; and **unchanged** — the value against
//! the one stored in `src/verify/stored.toml` at the default levels, within a tolerance tight
//! enough to catch any change of the numerics (`riplab verify --print-stored` writes that file
//! anew).
//!
//! Each case names its reference's source. The cases live one family per module:
//! [`half_space`] (Hertz, the exact circle, the rounded punch), [`patch`] (the contact patch
//! test; [`two_bodies`] that of two elastic bodies on meshes that do not match), [`infsup`]
//! (β_h's orders), [`manufactured`] (H¹ rates), [`constraint`] (ALM = exact,
//! the penalty's O(ε)), [`mindlin`] (Cattaneo–Mindlin's stick zone and traction).

pub mod constraint;
pub mod half_space;
pub mod hertz_two_bodies;
pub mod infsup;
pub mod manufactured;
pub mod mindlin;
pub mod patch;
pub mod stored;
pub mod two_bodies;

use serde::Serialize;

use crate::error::SolveError;

/// The finest level `riplab verify --level` accepts for the whole pack (the manufactured
/// solution's grid at level L has 2^(L+1) cells across, the infsup case's finest mesh the
/// scenario's level L); a case may accept more ([`Case::max_level`]).
pub const MAX_VERIFY_LEVEL: u32 = 5;
/// The coarsest level `riplab verify --level` accepts (the infsup case needs two levels below).
pub const MIN_VERIFY_LEVEL: u32 = 2;

/// What a check compares.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Kind {
    /// riplab against a published formula.
    #[serde(rename = "closed form")]
    ClosedForm,
    /// riplab against riplab: agreement of the numerics with themselves, not correctness.
    #[serde(rename = "consistency")]
    Consistency,
    /// The value against the one stored at the case's default level.
    #[serde(rename = "unchanged")]
    Unchanged,
}

impl Kind {
    /// The kinds, in the order the table shows them.
    pub const ALL: [Kind; 3] = [Kind::ClosedForm, Kind::Consistency, Kind::Unchanged];

    /// `closed form`, `consistency` or `unchanged` (as the JSON and CSV say it).
    pub fn name(self) -> &'static str {
        match self {
            Kind::ClosedForm => "closed form",
            Kind::Consistency => "consistency",
            Kind::Unchanged => "unchanged",
        }
    }

    /// What the kind compares, in a line.
    pub fn meaning(self) -> &'static str {
        match self {
            Kind::ClosedForm => "riplab against a published formula",
            Kind::Consistency => "riplab against riplab (agreement, not correctness)",
            Kind::Unchanged => "the value against src/verify/stored.toml's",
        }
    }
}

/// How a check's error is measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Measure {
    /// |computed − reference|.
    Absolute,
    /// |computed − reference| / |reference|.
    Relative,
}

/// One quantity a case measured, with its reference and tolerance.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    /// What was measured (a key of `src/verify/stored.toml` within its case).
    pub quantity: String,
    /// The computed value.
    pub computed: f64,
    /// The reference value.
    pub reference: f64,
    /// How the error is measured.
    pub measure: Measure,
    /// The largest error that passes.
    pub tolerance: f64,
    /// A kind and source other than its case's (e.g. a consistency check in a closed-form
    /// case).
    pub against: Option<(Kind, &'static str)>,
}

impl Measured {
    /// A quantity whose error is |computed − reference| / |reference|.
    pub fn relative(quantity: impl Into<String>, computed: f64, reference: f64, tolerance: f64) -> Self {
        Measured {
            quantity: quantity.into(),
            computed,
            reference,
            measure: Measure::Relative,
            tolerance,
            against: None,
        }
    }

    /// A quantity whose error is |computed − reference|.
    pub fn absolute(quantity: impl Into<String>, computed: f64, reference: f64, tolerance: f64) -> Self {
        Measured {
            quantity: quantity.into(),
            computed,
            reference,
            measure: Measure::Absolute,
            tolerance,
            against: None,
        }
    }

    /// This quantity compared as `kind` with the reference from `source`.
    pub fn against(self, kind: Kind, source: &'static str) -> Self {
        Measured {
            against: Some((kind, source)),
            ..self
        }
    }

    /// The error, as [`Measure`] says; NaN for a value that is not finite.
    pub fn error(&self) -> f64 {
        let diff = (self.computed - self.reference).abs();
        match self.measure {
            Measure::Absolute => diff,
            Measure::Relative => diff / self.reference.abs(),
        }
    }
}

/// A verification case: what it checks, where its reference comes from, and how it runs.
pub struct Case {
    /// Its name, for `--case`.
    pub name: &'static str,
    /// What it checks, in a line.
    pub description: &'static str,
    /// Where the reference comes from.
    pub source: &'static str,
    /// What its quantities compare (each may say otherwise, [`Measured::against`]).
    pub kind: Kind,
    /// The level it runs at by default (the stored values' level).
    pub default_level: u32,
    /// The finest level it accepts.
    pub max_level: u32,
    /// The case itself at a level.
    pub run: fn(u32) -> Result<Vec<Measured>, SolveError>,
}

/// Every case, in the order `riplab verify` runs them.
pub fn cases() -> Vec<Case> {
    let mut all = Vec::from(half_space::cases());
    all.extend([
        patch::CASE,
        two_bodies::CASE,
        hertz_two_bodies::CASE,
        infsup::CASE,
        manufactured::CASE,
    ]);
    all.extend(constraint::cases());
    all.push(mindlin::CASE);
    all
}

/// `sol`, or the error that says it did not converge.
pub fn converged(sol: &crate::contact::solution::Solution) -> Result<(), SolveError> {
    match sol.newton.failure() {
        None => Ok(()),
        Some(diagnosis) => Err(SolveError::NotConverged {
            what: "the case's solve",
            iterations: sol.newton.iterations,
            residual: sol.newton.residual,
            diagnosis,
        }),
    }
}

/// A `--case` that names no case.
#[derive(Debug, thiserror::Error)]
#[error("`{name}`; allowed: {allowed}")]
pub struct UnknownCase {
    /// The name asked for (sanitised).
    pub name: String,
    /// The cases' names, comma-separated.
    pub allowed: String,
}

/// The case of `all` named `name`, or every case when None.
pub fn select<'a>(all: &'a [Case], name: Option<&str>) -> Result<Vec<&'a Case>, UnknownCase> {
    let Some(name) = name else {
        return Ok(all.iter().collect());
    };
    match all.iter().find(|c| c.name == name) {
        Some(case) => Ok(vec![case]),
        None => Err(UnknownCase {
            name: crate::text::sanitize(name).into_owned(),
            allowed: all.iter().map(|c| c.name).collect::<Vec<_>>().join(", "),
        }),
    }
}

/// The two tiers' verdict on one quantity.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Verdict {
    /// Within the tolerance.
    #[serde(rename = "OK")]
    Ok,
    /// Outside it, or no value.
    #[serde(rename = "NOOK")]
    Nook,
}

impl Verdict {
    fn of(pass: bool) -> Self {
        if pass { Verdict::Ok } else { Verdict::Nook }
    }

    /// `OK` or `NOOK`.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Ok => "OK",
            Verdict::Nook => "NOOK",
        }
    }
}

/// One row of `riplab verify`: one comparison of a quantity of a case.
#[derive(Clone, Debug, Serialize)]
pub struct Check {
    /// The case's name.
    pub case: &'static str,
    /// What the row compares.
    pub kind: Kind,
    /// The quantity; for a case that failed to run, `run`.
    pub quantity: String,
    /// The level the case ran at.
    pub level: u32,
    /// The computed value (null where the case failed or the value is not finite).
    pub computed: Option<f64>,
    /// The reference value: a closed form's, riplab's own, or the stored one.
    pub reference: Option<f64>,
    /// How the error is measured.
    pub measure: Measure,
    /// The error against the reference (null without a computed value).
    pub error: Option<f64>,
    /// The largest error that passes.
    pub tolerance: Option<f64>,
    /// `OK` when the error is within the tolerance.
    pub verdict: Verdict,
    /// Why the case has no value, when it failed to run.
    pub reason: Option<String>,
    /// Where the reference comes from.
    pub source: &'static str,
}

/// The relative change from a stored value that counts as a change of the numerics (with an
/// absolute floor of [`CHANGE_FLOOR`] for values at round-off).
pub const CHANGE_RELATIVE: f64 = 1e-6;
/// The absolute change that counts as none: the pack's quantities that can be at round-off
/// (the patch test's and the ALM's relative differences, about 1e-12) are dimensionless, and
/// round-off may move them by their own size on another machine.
pub const CHANGE_FLOOR: f64 = 1e-10;

/// The source of the unchanged rows.
const STORED_SOURCE: &str =
    "src/verify/stored.toml (riplab verify --print-stored), at the case's default level";

/// Run `case` at `level` (its default when None): a row per quantity against its reference
/// and, at the default level, one against its stored value.
pub fn run(case: &Case, level: Option<u32>) -> Vec<Check> {
    let level = level.unwrap_or(case.default_level);
    let stored = (level == case.default_level).then(|| stored::values(case.name));
    let measured = match (case.run)(level) {
        Ok(measured) => measured,
        Err(e) => {
            return vec![Check {
                case: case.name,
                kind: case.kind,
                quantity: "run".into(),
                level,
                computed: None,
                reference: None,
                measure: Measure::Absolute,
                error: None,
                tolerance: None,
                verdict: Verdict::Nook,
                reason: Some(e.to_string()),
                source: case.source,
            }];
        }
    };
    let mut against = Vec::new();
    let mut unchanged = Vec::new();
    for m in measured {
        let finite = m.computed.is_finite();
        let error = m.error();
        let (kind, source) = m.against.unwrap_or((case.kind, case.source));
        let row = |kind, reference: f64, measure, error: f64, tolerance: f64, source| Check {
            case: case.name,
            kind,
            quantity: m.quantity.clone(),
            level,
            computed: finite.then_some(m.computed),
            reference: Some(reference),
            measure,
            error: (finite && error.is_finite()).then_some(error),
            tolerance: Some(tolerance),
            verdict: Verdict::of(finite && error <= tolerance),
            reason: None,
            source,
        };
        against.push(row(kind, m.reference, m.measure, error, m.tolerance, source));
        if let Some(&s) = stored.as_ref().and_then(|s| s.get(&m.quantity)) {
            let tolerance = (CHANGE_RELATIVE * s.abs()).max(CHANGE_FLOOR);
            let change = (m.computed - s).abs();
            unchanged.push(row(
                Kind::Unchanged,
                s,
                Measure::Absolute,
                change,
                tolerance,
                STORED_SOURCE,
            ));
        }
    }
    against.extend(unchanged);
    against
}

/// The checks of a run of the pack, and whether all passed.
#[derive(Debug, Serialize)]
pub struct Verification {
    /// Whether every check is `OK`.
    pub passed: bool,
    /// A row per quantity of every case run.
    pub checks: Vec<Check>,
}

impl Verification {
    /// `checks` with their overall verdict.
    pub fn new(checks: Vec<Check>) -> Self {
        Verification {
            passed: checks.iter().all(|c| c.verdict == Verdict::Ok),
            checks,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wrong(_: u32) -> Result<Vec<Measured>, SolveError> {
        Ok(vec![
            Measured::relative("off", 1.1, 1.0, 0.05),
            Measured::absolute("not finite", f64::NAN, 0.0, 1.0),
            Measured::absolute("‖p̄ − p‖₀/‖p‖₀", 7.6e-3, 0.0, 1e-2),
        ])
    }

    fn failing(_: u32) -> Result<Vec<Measured>, SolveError> {
        Err(SolveError::Eigen(faer::linalg::evd::EvdError::NoConvergence))
    }

    /// A value off its reference, one that is not finite, one that changed from its stored
    /// value (the circle's stored L² error is not 7.6e-3), and a case that fails are all NOOK.
    #[test]
    fn a_wrong_changed_or_failed_value_is_nook() {
        let case = Case {
            name: "circle",
            description: "",
            source: "test",
            kind: Kind::ClosedForm,
            default_level: 3,
            max_level: MAX_VERIFY_LEVEL,
            run: wrong,
        };
        let checks = run(&case, None);
        assert_eq!(checks[0].verdict, Verdict::Nook);
        assert!((checks[0].error.unwrap() - 0.1).abs() < 1e-12);
        assert_eq!((checks[1].computed, checks[1].verdict), (None, Verdict::Nook));
        assert_eq!(
            (checks[2].kind, checks[2].verdict),
            (Kind::ClosedForm, Verdict::Ok)
        );
        // The L² error's stored row: changed, NOOK.
        let stored = checks
            .iter()
            .find(|c| c.kind == Kind::Unchanged && c.quantity == checks[2].quantity)
            .unwrap();
        assert_eq!(stored.verdict, Verdict::Nook);
        // At another level nothing is stored: no unchanged row.
        let other = run(&case, Some(4));
        assert_eq!(other.len(), 3);
        assert_eq!(other[2].verdict, Verdict::Ok);
        assert!(!Verification::new(checks).passed);
        let failed = run(&Case { run: failing, ..case }, None);
        assert_eq!(failed.len(), 1);
        assert_eq!(failed[0].verdict, Verdict::Nook);
        assert!(failed[0].reason.as_deref().unwrap().contains("eigenvalue"));
    }
}
