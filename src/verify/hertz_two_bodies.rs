//! Hertz between two elastic bodies on meshes that do not match (docs/design.md §12):
//! `scenarios/hertz-two-bodies.toml`, an elastic cylinder segment on an elastic block, meshes
//! 3:2 across the contact, exact multipliers. Johnson §4.2: 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂,
//! a² = 4PR/(πE*), p₀ = 2P/(πa), P the full load per unit length.
//!
//! The computed half-width is read from the pressure's moments, not from where it ends (which
//! moves by a whole element): Hertz's p ∝ √(a² − x²) has ∫p x² / ∫p = a²/4, so
//! a_h = 2 √(Σ w_k p_k x_k² / Σ w_k p_k) over the constraints' forces w_k p_k. The peak is
//! max_k p_k. A run at level L measures the levels from L − 2 (but not below 2) to L and asks
//! a's error to fall: at level 1, a spans four and a half elements, short of the asymptotic
//! range (mortar-dual's error there is below level 2's).

use super::two_bodies::failed;
use super::{Case, Kind, MAX_VERIFY_LEVEL, Measured};
use crate::contact::half_plane::e_star;
use crate::contact::interface::InterfaceMethod;
use crate::error::SolveError;
use crate::scenario::upper::TwoBodies;
use crate::scenario::{Scenario, UpperShape};

/// The case.
pub const CASE: Case = Case {
    name: "hertz-two-bodies",
    description: "an elastic cylinder on an elastic block, meshes 3:2 across the contact, exact multipliers: mortar's and mortar-dual's a and p₀ against two-body Hertz, a's error falling over three levels",
    source: "two-body Hertz (Johnson, Contact Mechanics, §4.2): 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂, a² = 4PR/(πE*), p₀ = 2P/(πa); a from the pressure's moments, ∫p x²/∫p = a²/4",
    kind: Kind::ClosedForm,
    default_level: 3,
    max_level: MAX_VERIFY_LEVEL,
    run,
};

/// The scenario, embedded.
const HERTZ: &str = include_str!("../../scenarios/hertz-two-bodies.toml");

/// a within 1 % and p₀ within 2 % (the bodies are finite: the peak's model error is about
/// 0.2 % from level 2 on, docs/design.md §12).
const A_TOLERANCE: f64 = 0.01;
const P0_TOLERANCE: f64 = 0.02;

/// Hertz's (a, p₀) and the computed ones at one level.
pub(crate) struct Level {
    /// Johnson's (a, p₀) for the computed load.
    pub(crate) hertz: (f64, f64),
    /// The computed (a_h from the pressure's moments, the peak pressure).
    pub(crate) computed: (f64, f64),
}

impl Level {
    fn a_error(&self) -> f64 {
        (self.computed.0 / self.hertz.0 - 1.0).abs()
    }
}

fn solve(scenario: &Scenario, level: u32, method: InterfaceMethod) -> Result<Level, SolveError> {
    let solved = scenario.solve_bodies(level, method, 0.0).map_err(failed)?;
    Ok(measure(scenario, &solved).expect("the embedded scenario's cylinder carries a load"))
}

/// Hertz's (a, p₀) for the load of `solved`, a solve of `scenario`, beside the computed a_h
/// (from the pressure's moments) and peak; None unless the upper body is a cylinder and the
/// interface carries a load.
pub(crate) fn measure(scenario: &Scenario, solved: &TwoBodies) -> Option<Level> {
    let (c, sol) = (&solved.coupling, &solved.solution);
    let force = |k: usize| c.weight[k] * sol.p[k];
    let m0: f64 = (0..sol.p.len()).map(force).sum();
    let m2: f64 = (0..sol.p.len()).map(|k| force(k) * sol.x[k] * sol.x[k]).sum();
    let peak = sol.p.iter().fold(0.0_f64, |m, &p| m.max(p));
    let upper = scenario.upper.as_ref()?;
    let UpperShape::Cylinder { radius } = upper.shape else {
        return None;
    };
    if !(m0 > 0.0 && sol.load > 0.0) {
        return None;
    }
    let modulus = 1.0 / (1.0 / e_star(&scenario.material) + 1.0 / e_star(&upper.material));
    let full = if scenario.half_model {
        2.0 * sol.load
    } else {
        sol.load
    };
    let a = (4.0 * full * radius / (std::f64::consts::PI * modulus)).sqrt();
    Some(Level {
        hertz: (a, 2.0 * full / (std::f64::consts::PI * a)),
        computed: (2.0 * (m2 / m0).sqrt(), peak),
    })
}

/// The first level measured at `level`: two before it, but not below 2 (nor above `level`).
fn first(level: u32) -> u32 {
    level.saturating_sub(2).max(2).min(level)
}

fn run(level: u32) -> Result<Vec<Measured>, SolveError> {
    let scenario =
        Scenario::parse(HERTZ, "<embedded hertz-two-bodies.toml>").expect("the embedded scenario is valid");
    let mut out = Vec::new();
    for method in [InterfaceMethod::Mortar, InterfaceMethod::MortarDual] {
        let levels = (first(level)..=level)
            .map(|l| solve(&scenario, l, method))
            .collect::<Result<Vec<_>, _>>()?;
        let last = levels.last().expect("at least one level");
        let name = method.name();
        out.push(Measured::relative(
            format!("{name} level {level}: contact half-width a"),
            last.computed.0,
            last.hertz.0,
            A_TOLERANCE,
        ));
        out.push(Measured::relative(
            format!("{name} level {level}: peak pressure p₀"),
            last.computed.1,
            last.hertz.1,
            P0_TOLERANCE,
        ));
        let falling = levels.windows(2).all(|w| w[1].a_error() < w[0].a_error());
        out.push(Measured::absolute(
            format!(
                "{name}: a's error falls over levels {}..{level} (1: it does)",
                first(level)
            ),
            if falling { 1.0 } else { 0.0 },
            1.0,
            0.0,
        ));
    }
    Ok(out)
}
