//! What the views show of a solve with friction (docs/design.md §11), computed with
//! [`super::shown::Shown`]: the raw tangential traction t at the rule's points, the smoothed
//! t̄ at Γ_C's vertices, the stick zone's ends, and the numbers `riplab solve` prints — Q,
//! Q/(μP), the stick half-width, Cattaneo–Mindlin's c and t̄'s L² distance from q — taken
//! from the same reports ([`FrictionReport`], [`MindlinReport`]) so that the lab and the
//! command line cannot disagree.

use crate::contact::friction::Law;
use crate::contact::mindlin::{Mindlin, dundurs_beta, stick_extent};
use crate::contact::solution::Solution;
use crate::output::{FrictionReport, MindlinReport};
use crate::scenario::Scenario;

/// A solve with friction as the views show it (a full model: nothing is mirrored).
#[derive(Clone, Debug)]
pub struct FrictionShown {
    /// The law, with μ or g.
    pub law: Law,
    /// The shift ξ after the press.
    pub shift: f64,
    /// Raw t at each of the rule's points (x, t).
    pub t: Vec<(f64, f64)>,
    /// Raw t as the cursor reads it: the function of Q_h through the rule's points, edge by
    /// edge (as p's [`super::shown::Shown::raw`]).
    pub t_edges: Vec<(f64, f64)>,
    /// t̄ at Γ_C's vertices (x, t̄).
    pub tbar: Vec<(f64, f64)>,
    /// The tangential load Q = ∫ t dx.
    pub tangential_load: f64,
    /// Q/(μP), Coulomb only.
    pub load_ratio: Option<f64>,
    /// The stick zone's ends (the midpoints outside its outermost stick points) and its
    /// number of runs of consecutive stick points; None with no stick point.
    pub stick: Option<(f64, f64, usize)>,
    /// The computed stick half-width, as `riplab solve` prints it.
    pub stick_half_width: Option<f64>,
    /// Cattaneo–Mindlin for the computed P and Q (a cylinder, Coulomb, 0 < |Q| < μP).
    pub mindlin: Option<Mindlin>,
    /// ‖t̄ − q‖₀/‖q‖₀, with Mindlin.
    pub mindlin_error: Option<f64>,
    /// The body's Dundurs |β|: Mindlin's q assumes 0.
    pub beta: f64,
}

impl FrictionShown {
    /// What the views show of `solution`'s friction, on `scenario`; None without friction.
    pub fn new(scenario: &Scenario, solution: &Solution) -> Option<FrictionShown> {
        let f = solution.friction.as_ref()?;
        let report = FrictionReport::new(solution);
        let mindlin_report = MindlinReport::new(scenario, solution);
        let mindlin = f.friction.law.mu().and_then(|mu| {
            Mindlin::for_loads(
                &solution.params.obstacle,
                &scenario.material,
                solution.load,
                f.tangential_load,
                mu,
            )
        });
        let points = &solution.points;
        let t: Vec<(f64, f64)> = points
            .points
            .iter()
            .map(|q| q.x)
            .zip(f.t.iter().copied())
            .collect();
        let tbar: Vec<(f64, f64)> = points
            .vertex_x
            .iter()
            .copied()
            .zip(f.tbar.iter().copied())
            .collect();
        Some(FrictionShown {
            law: f.friction.law,
            shift: f.friction.shift,
            t,
            t_edges: crate::plot::raw_pressure_edges(points, &f.t).concat(),
            tbar,
            tangential_load: report.tangential_load,
            load_ratio: report.load_ratio,
            stick: stick_extent(points, &f.states),
            stick_half_width: report.stick_half_width,
            mindlin,
            mindlin_error: mindlin_report.map(|m| m.relative_error).filter(|e| e.is_finite()),
            beta: dundurs_beta(&scenario.material),
        })
    }
}
