//! The Cattaneo–Mindlin case (docs/design.md §11): a rigid cylinder pressed on a large
//! near-incompressible block (Dundurs' β ≈ 0) and shifted sideways with Q < μP, Coulomb
//! friction imposed exactly at the trapezoid points (M3); the stick half-width and the
//! smoothed traction t̄ against the closed form of src/contact/mindlin.rs at the computed P
//! and Q.

use super::{Case, Measured, converged};
use crate::contact::mindlin::{Mindlin, stick_half_width};
use crate::error::SolveError;
use crate::scenario::Scenario;
use crate::solve::solve_scenario;

/// scenarios/cattaneo-mindlin.toml, embedded.
const CATTANEO_MINDLIN: &str = include_str!("../../scenarios/cattaneo-mindlin.toml");

/// The case.
pub const CASE: Case = Case {
    name: "cattaneo-mindlin",
    description: "cylinder R = 10 on a 320 × 160 block, ν = 0.499 selective, pressed then shifted (Coulomb μ = 0.3, exact, M3): stick zone and t̄",
    source: "Cattaneo (1938), Mindlin (1949); Johnson, Contact Mechanics (1985) §7.2 for β = 0: c/a = √(1 − Q/μP), q = μp₀√(1 − x²/a²) − μp₀(c/a)√(1 − x²/c²) on |x| < c, μp beyond",
    default_level: 3,
    run: cattaneo_mindlin,
};

/// The case at `level`: the stick half-width against c (relative, 5%: half a cell at level 3
/// is 2% of c) and ‖t̄ − q‖₀/‖q‖₀ (against 0, 5%).
fn cattaneo_mindlin(level: u32) -> Result<Vec<Measured>, SolveError> {
    let mut scenario = Scenario::parse(CATTANEO_MINDLIN, "cattaneo-mindlin.toml")
        .expect("riplab's own scenario files parse");
    scenario.level = level;
    let (_, sol) = solve_scenario(&scenario)?;
    converged(&sol)?;
    let f = sol
        .friction
        .as_ref()
        .expect("the scenario's [friction] is Coulomb");
    let mu = f.friction.law.mu().expect("the scenario's law is Coulomb");
    let closed = Mindlin::for_loads(
        &sol.params.obstacle,
        &scenario.material,
        sol.load,
        f.tangential_load,
        mu,
    )
    .expect("a cylinder with Q < μP has a stick zone");
    let width = stick_half_width(&sol.points, &f.states).map_or(f64::NAN, |w| w.0);
    Ok(vec![
        Measured::relative("stick half-width against c", width, closed.c, 0.05),
        Measured::absolute(
            "‖t̄ − q‖₀/‖q‖₀",
            closed.relative_error(&sol.points, &f.tbar),
            0.0,
            0.05,
        ),
    ])
}
