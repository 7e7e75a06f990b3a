//! What the views show of a solution, computed once when it arrives ([`Shown::new`], by the
//! worker) so that the views only draw: the pressures along Γ_C mirrored to the full width
//! for a half model, the load of the whole body, the Hertz solution and the exact circle's for
//! that load, and the
//! contact zone the views zoom to.

use super::shown_friction::FrictionShown;
use crate::contact::circle::CircleContact;
use crate::contact::hertz::Hertz;
use crate::contact::solution::Solution;
use crate::plot::raw_pressure_edges;
use crate::scenario::Scenario;

/// A solution as the views show it.
#[derive(Clone, Debug)]
pub struct Shown {
    /// The x range of the whole body (from −x to x for a half model, mirrored).
    pub x_range: [f64; 2],
    /// Raw p as drawn: the function of Q_h through the rule's points, edge by edge, mirrored.
    pub raw: Vec<(f64, f64)>,
    /// p̄ at the vertices of Γ_C, mirrored.
    pub pbar: Vec<(f64, f64)>,
    /// The largest value of p and p̄ (0 without contact).
    pub peak: f64,
    /// The load of the whole body: twice the computed one for a half model.
    pub full_load: f64,
    /// Hertz's solution for that load, where the obstacle has one (a cylinder).
    pub hertz: Option<Hertz>,
    /// ‖p̄ − p_Hertz‖₀ / ‖p_Hertz‖₀ on Γ_C ([`Hertz::relative_error`], as `riplab solve`'s
    /// `hertz.relative_error`), with Hertz.
    pub hertz_error: Option<f64>,
    /// The exact circular indenter for that load (the circle, not Hertz's parabola).
    pub circle: Option<CircleContact>,
    /// The x range to zoom to ([`zoom_range`] over [`Shown::x_range`]); None without contact.
    pub zone: Option<[f64; 2]>,
    /// The tangential traction and its numbers, with friction ([`FrictionShown`]).
    pub friction: Option<FrictionShown>,
}

impl Shown {
    /// What the views show of `solution`, computed on `scenario`.
    pub fn new(scenario: &Scenario, solution: &Solution) -> Shown {
        let half = scenario.half_model;
        let mirror = |pts: Vec<(f64, f64)>| -> Vec<(f64, f64)> {
            if !half {
                return pts;
            }
            let mut out: Vec<(f64, f64)> = pts.iter().rev().map(|&(x, y)| (-x, y)).collect();
            out.extend(pts);
            out
        };
        let (x0, x1) = scenario.x_range();
        let x_range = if half { [-x1, x1] } else { [x0, x1] };
        let full_load = if half { 2.0 * solution.load } else { solution.load };
        let hertz = Hertz::for_load(&solution.params.obstacle, &scenario.material, full_load);
        Shown {
            x_range,
            raw: mirror(raw_pressure_edges(&solution.points, &solution.p).concat()),
            pbar: mirror(
                solution
                    .points
                    .vertex_x
                    .iter()
                    .copied()
                    .zip(solution.pbar.iter().copied())
                    .collect(),
            ),
            peak: solution
                .p
                .iter()
                .chain(&solution.pbar)
                .fold(0.0f64, |m, &v| m.max(v)),
            full_load,
            hertz,
            // Not a number for a contact too small to have a norm: then none shown.
            hertz_error: hertz
                .map(|h| h.relative_error(&solution.points, &solution.pbar))
                .filter(|e| e.is_finite()),
            circle: CircleContact::for_load(&solution.params.obstacle, &scenario.material, full_load),
            zone: zoom_range(solution, half, (x_range[0], x_range[1])),
            friction: FrictionShown::new(scenario, solution),
        }
    }
}

/// The x range to zoom to: the contact zone (the vertices where p̄ > 0, with the neighbouring
/// vertices where p̄ falls to 0), mirrored for a half model, plus a quarter of its width on
/// each side (at least two of the mesh's cells at the zone's edges), within `[lo, hi]`; None
/// without contact.
pub fn zoom_range(solution: &Solution, half: bool, (lo, hi): (f64, f64)) -> Option<[f64; 2]> {
    let xs = &solution.points.vertex_x;
    let pbar = &solution.pbar;
    let inside: Vec<usize> = (0..pbar.len()).filter(|&i| pbar[i] > 0.0).collect();
    let (&first, &last) = (inside.first()?, inside.last()?);
    let (i, j) = (first.saturating_sub(1), (last + 1).min(xs.len() - 1));
    let (a, b) = (xs[i], xs[j]);
    // The local cell size at the zone's edges (graded meshes are finer there).
    let cell = (xs[i + 1] - xs[i]).max(xs[j] - xs[j - 1]);
    let (a, b) = if half { (-b, b) } else { (a, b) };
    let margin = (0.25 * (b - a)).max(2.0 * cell);
    Some([(a - margin).max(lo), (b + margin).min(hi)])
}

/// The share of Γ_C that the obstacle reaches at the scenario's depth (its outline below the
/// undeformed top), when under a twentieth: the lab then opens zoomed in on the contact zone,
/// which on the whole of Γ_C is a spike at its centre (hertz-block: a ≈ 1 on a block 320
/// wide).
pub fn narrow_contact(scenario: &Scenario) -> Option<f64> {
    let (x0, x1) = scenario.x_range();
    let (lo, hi) = if scenario.half_model { (-x1, x1) } else { (x0, x1) };
    let (a, b) = scenario.obstacle.contact_extent(lo, hi)?;
    let share = (b - a) / (hi - lo);
    (share < 0.05).then_some(share)
}
