//! The penalty's share of a refinement study's errors: the study measures the
//! discretisation only where the penalty's own error is well below each row's. A penalty at
//! κ = εE/h is off in the load by at most 0.3 κ (STABILITY.md, "ε over twelve decades": κ from
//! 1e-2 to 1e-7, levels 0–6, M1 and M3), and its pressure's round-off is estimated by
//! [`crate::warning::of_round_off`]; so the study's default ε is κ = [`STUDY_KAPPA`] at its
//! finest level, and a row whose load error is within ten times the penalty's bound is noted
//! as dominated by ε.

use crate::scenario::Scenario;
use crate::study::{Status, StudyRow};

/// κ = εE/h of a study's default ε at its finest level: the penalty's load error at most
/// 3e-7 there (and less at the coarser levels, where κ is smaller), while the pressure's
/// round-off stays below 1e-6 (its estimate is 2e-7 on the paper's problem at level 5).
pub const STUDY_KAPPA: f64 = 1e-6;

/// The measured bound of the penalty's relative load error, as a multiple of κ.
pub const LOAD_ERROR_PER_KAPPA: f64 = 0.3;

/// The default ε of a refinement study of `scenario` whose finest level is `finest`: κ =
/// [`STUDY_KAPPA`] there, or the scenario's own ε when it is smaller (ε = 0: the exact
/// constraint).
pub fn default_epsilon(scenario: &Scenario, finest: u32) -> f64 {
    let chosen = STUDY_KAPPA * scenario.h(finest) / scenario.material.young;
    scenario.epsilon.min(chosen)
}

/// The penalty's bound on `row`'s relative load error, LOAD_ERROR_PER_KAPPA · εE/h; None for a
/// row without a penalty (ε = 0, or a method without ε error).
pub fn load_error_bound(row: &StudyRow, young: f64) -> Option<f64> {
    (row.method.method == "penalty" && row.epsilon > 0.0)
        .then(|| LOAD_ERROR_PER_KAPPA * row.epsilon * young / row.h)
}

/// The note on a row of a study whose load error is within ten times the penalty's bound (the
/// penalty's share may exceed a tenth of it, and the row's rates may be ε's); None for every
/// other row.
pub fn dominated(r: &StudyRow, young: f64) -> Option<String> {
    if r.status != Status::Ok {
        return None;
    }
    let bound = load_error_bound(r, young)?;
    let error = r.errors?.load;
    (error <= 10.0 * bound).then(|| {
        format!(
            "{} level {}: the load's error {error:.1e} is within ten times the penalty's bound ({bound:.1e} at ε = {:e}): ε may account for a tenth of it or more, and its rate may be ε's; --method exact measures the mesh alone",
            r.scheme,
            r.level_label(),
            r.epsilon
        )
    })
}
