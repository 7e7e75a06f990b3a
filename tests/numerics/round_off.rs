//! Round-off said aloud: the penalty's pressure, formed as penetration/ε,
//! loses digits as ε shrinks; a solve warns where the estimate of that round-off exceeds 1e-6
//! of p, and the estimate bounds the error measured against the exact constraint.

use riplab::error::Diagnosis;
use riplab::scenario::Scenario;
use riplab::solve::solve_scenario;
use riplab::warning::{ROUND_OFF_LIMIT, Warning};

/// The paper's problem at level 4, M3 (unique multipliers at ε = 0), at `epsilon`.
fn solve_at(epsilon: f64) -> riplab::contact::solution::Solution {
    let mut scenario = Scenario::paper();
    scenario.level = 4;
    scenario.rule = riplab::contact::Rule::Trapezoid;
    scenario.epsilon = epsilon;
    scenario.method = if epsilon == 0.0 {
        riplab::contact::Method::Exact
    } else {
        riplab::contact::Method::Penalty
    };
    solve_scenario(&scenario).unwrap().1
}

/// [`solve_at`], converged.
fn solve(epsilon: f64) -> riplab::contact::solution::Solution {
    let sol = solve_at(epsilon);
    assert!(sol.newton.converged, "ε = {epsilon}");
    sol
}

fn round_off(sol: &riplab::contact::solution::Solution) -> Option<f64> {
    sol.warnings.iter().find_map(|w| match w {
        Warning::RoundOff { estimate, .. } => Some(*estimate),
        _ => None,
    })
}

/// ε = 1e-14 (κ = 1.6e-10) warns, ε = 1e-11 (κ = 1.6e-7) does not; where it warns the
/// estimate is at least the error of p against the exact constraint (whose own O(ε) error is
/// 1e-10 of p there), and the error exceeds the limit.
#[test]
fn a_penalty_below_the_round_off_onset_warns() {
    let exact = solve(0.0);
    let top = exact.p.iter().copied().fold(0.0, f64::max);
    assert_eq!(round_off(&solve(1e-11)), None);
    assert_eq!(round_off(&exact), None);
    for epsilon in [1e-13, 1e-14] {
        let sol = solve(epsilon);
        let estimate = round_off(&sol).unwrap_or_else(|| panic!("ε = {epsilon}: no warning"));
        let error = sol
            .p
            .iter()
            .zip(&exact.p)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / top;
        // Measured: 1.6e-5 and 1.4e-4 against estimates of 6e-5 and 6e-4.
        assert!(
            error > ROUND_OFF_LIMIT && error <= estimate,
            "ε = {epsilon}: error {error:e}, estimate {estimate:e}"
        );
        let text = sol.warnings.iter().map(|w| w.to_string()).collect::<String>();
        assert!(text.contains("round-off") && text.contains("κ = εE/h"), "{text}");
    }
}

/// Far below the onset (ε = 1e-20, κ = 1.6e-16) round-off in u_n − g, amplified by 1/ε, is as
/// large as the forces: no iterate is certified, and the diagnosis says so with the ε.
#[test]
fn a_penalty_swamped_by_round_off_is_not_converged() {
    let sol = solve_at(1e-20);
    assert!(!sol.newton.converged);
    assert_eq!(sol.newton.diagnosis, Some(Diagnosis::Swamped { epsilon: 1e-20 }));
}
