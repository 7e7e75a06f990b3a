//! The lab's friction settings (docs/design.md §11, "The lab"): the law `F` cycles, the
//! steps of μ or g (`u`/`U`) and of the shift ξ (`<`/`>`), the defaults a scenario without
//! `[friction]` switches on with, the settings' label, and their hash in a study's key.

use crate::contact::friction::{Friction, Law};
use crate::scenario::Scenario;

/// The coefficient μ that `F` switches Coulomb on with when the scenario has none: the
/// value of `scenarios/cattaneo-mindlin.toml` (and of the tests).
pub const DEFAULT_MU: f64 = 0.3;
/// The values of μ `u`/`U` step through (a μ between two steps to the next one).
pub const MU_STEPS: [f64; 10] = [0.0, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0];
/// The factor of a step of g (`u`/`U`) and of the shift (`<`/`>`).
pub const FACTOR: f64 = 1.25;
/// The default shift ξ₀ as a share of the width the obstacle's outline cuts through the top
/// at the depth d: 2%, partial slip (a stick and a slip zone) at μ = 0.3 on the repository's
/// cylinders (measured in docs/design.md §11, "The lab").
pub const SHIFT_SHARE: f64 = 0.02;
/// The shifts `<`/`>` reach: |ξ| from ξ₀/100 to 20 ξ₀.
pub const SHIFT_RANGE: (f64, f64) = (0.01, 20.0);
/// The thresholds g `u`/`U` reach, as shares of E.
pub const THRESHOLD_RANGE: (f64, f64) = (1e-4, 1.0);

/// The default shift ξ₀ of `scenario` at `depth` ([`SHIFT_SHARE`] of the width the
/// obstacle's outline cuts through the top); None where it cuts nothing (d = 0).
pub fn default_shift(scenario: &Scenario, depth: f64) -> Option<f64> {
    let (x0, x1) = scenario.x_range();
    let (a, b) = scenario.obstacle.with_depth(depth).contact_extent(x0, x1)?;
    Some(round3(SHIFT_SHARE * (b - a)))
}

/// `value` rounded to three significant digits (the steps print short).
pub fn round3(value: f64) -> f64 {
    format!("{value:.2e}").parse().unwrap_or(value)
}

/// The next μ of [`MU_STEPS`] above (`up`) or below `mu`; None past the list's end.
pub fn step_mu(mu: f64, up: bool) -> Option<f64> {
    if up {
        MU_STEPS.into_iter().find(|&m| m > mu + 1e-12)
    } else {
        MU_STEPS.into_iter().rev().find(|&m| m < mu - 1e-12)
    }
}

/// `value` × or ÷ [`FACTOR`] (three digits) if its magnitude stays within `[lo, hi]`.
pub fn step_scaled(value: f64, up: bool, (lo, hi): (f64, f64)) -> Option<f64> {
    let next = round3(if up { value * FACTOR } else { value / FACTOR });
    (next.abs() >= lo * (1.0 - 1e-9) && next.abs() <= hi * (1.0 + 1e-9)).then_some(next)
}

/// "coulomb μ = 0.3, shift ξ = 0.0815", "tresca g = 23, shift ξ = 0.1" or "no friction".
pub fn label(friction: &Friction) -> String {
    let shift = format!("shift ξ = {}", crate::text::num(friction.shift));
    match friction.law {
        Law::None => "no friction".into(),
        Law::Coulomb { mu } => format!("coulomb μ = {}, {shift}", crate::text::num(mu)),
        Law::Tresca { threshold } => format!("tresca g = {}, {shift}", crate::text::num(threshold)),
    }
}

/// Feed `friction` to `state` (its numbers by their bits: they are finite, [`Friction::check`]).
pub fn hash_friction<H: std::hash::Hasher>(friction: &Friction, state: &mut H) {
    use std::hash::Hash;
    friction.law.name().hash(state);
    friction.law.mu().map(f64::to_bits).hash(state);
    friction.law.threshold().map(f64::to_bits).hash(state);
    friction.shift.to_bits().hash(state);
    friction.steps.hash(state);
    friction.epsilon_t.map(f64::to_bits).hash(state);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// μ steps through the list from a value between two steps; g and ξ by 1.25 within their
    /// ranges, rounded to three digits.
    #[test]
    fn the_steps_stay_in_their_lists_and_ranges() {
        assert_eq!(step_mu(0.3, true), Some(0.4));
        assert_eq!(step_mu(0.3, false), Some(0.2));
        assert_eq!(step_mu(0.25, true), Some(0.3));
        assert_eq!(step_mu(0.25, false), Some(0.2));
        assert_eq!(step_mu(1.0, true), None);
        assert_eq!(step_mu(0.0, false), None);
        assert_eq!(step_scaled(0.0815, true, (1e-3, 1.0)), Some(0.102));
        assert_eq!(step_scaled(-0.0815, false, (1e-3, 1.0)), Some(-0.0652));
        assert_eq!(step_scaled(0.9, true, (1e-3, 1.0)), None);
        assert_eq!(round3(0.0815 * 1.25), 0.102);
    }
}
