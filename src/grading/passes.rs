//! A solve graded at its contact edges: solve on the uniform level, find where the
//! pressure's contact edges are, bisect the lines around them ([`GradedGrid::refined`]; over
//! the contact zone: [`GradedGrid::zoned`]) and solve again, pass after pass. Each pass
//! starts Newton from the last pass's pressure carried to the new points (forces = p(x)·w);
//! the new grid has its own assembly, ordering and factor (nothing of the mesh's work carries
//! over: its lines changed), with the uniform level's material, integration and model. Every
//! method and element goes through the entry's solve on one mesh, which the solve entry gives
//! the passes, and whose smoothing (17) uses the graded mesh's own weights.

use super::zone::contact_zones;
use super::{AUTO_TOLERANCE, GradedGrid, Grading, MAX_PASSES, RefineEdges, contact_edges};
use crate::contact::solution::{Solution, Timing};
use crate::contact::{ContactPoints, Rule};
use crate::discretization::{Discretization, refused};
use crate::error::{SolveError, Workload};
use crate::fem::memory::Limits;
use crate::mesh::Element;
use crate::warning::Warning;

/// The entry's frictionless solve on one mesh from a warm start (the forces at the rule's
/// points), as the passes are given it.
pub(crate) type SolveOn<'a> = dyn FnMut(&Discretization, Option<&[f64]>) -> Result<Solution, SolveError> + 'a;

/// One pass of a graded solve, as reported.
#[derive(Clone, Debug, PartialEq)]
pub struct Pass {
    /// The free dofs of its mesh.
    pub n_dofs: usize,
    /// Its smallest cell side.
    pub h_min: f64,
    /// The relative change of p̄ in L²(Γ_C) from the previous pass (None for the uniform one).
    pub pbar_change: Option<f64>,
    /// What the pass cost, ms (its mesh's work and Newton).
    pub ms: f64,
}

/// A graded solve's grids: the final grid, its discretisation, and the passes (the solution is
/// returned beside them).
pub struct Grids {
    /// The final grid.
    pub grid: GradedGrid,
    /// The final grid's discretisation (None: no pass was made; the uniform level's, given).
    pub disc: Option<Discretization>,
    /// Every pass, the uniform level first.
    pub passes: Vec<Pass>,
}

/// Solve with `solve_on` (the entry's frictionless solve on one mesh, from the warm start it
/// is given) on `uniform`, the discretisation of a uniform `level` (from `warm`), then grade at
/// the contact edges (or over the contact zone) as `refine` asks ([`Grading::wants_pass`]),
/// each pass discretised as `uniform` is (its material, integration and model) and
/// warm-started from the last. The grading stops early when the pressure has no contact edge
/// (zone), or a pass does not converge (its solution is the result, not converged). A grid
/// that does not fit the memory is refused before it is built. The uniform level's mesh
/// work is the caller's to charge ([`Timing`] of the result: every pass's solve and every
/// graded mesh's work).
pub(crate) fn solve_graded(
    (level, uniform): (u32, &Discretization),
    refine: Grading,
    rule: Rule,
    warm: Option<&[f64]>,
    solve_on: &mut SolveOn<'_>,
) -> Result<(Solution, Grids), SolveError> {
    let element = uniform.mesh.element;
    let half_model = uniform.mesh.symmetric_left;
    let discretize = |grid: &GradedGrid| {
        Discretization::new(
            grid.mesh(element, half_model),
            uniform.material,
            uniform.integration,
        )
    };
    let base = GradedGrid::uniform(level, &uniform.mesh);
    let mut grid = base.clone();
    let mut graded: Option<Discretization> = None;
    let mut sol = solve_on(uniform, warm)?;
    let mut passes = vec![Pass {
        n_dofs: uniform.n_dofs(),
        h_min: grid.h_min(),
        pbar_change: None,
        ms: sol.timing.total,
    }];
    let mut spent = sol.timing;
    let auto = refine == Grading::Edges(RefineEdges::Auto);
    // `auto`'s best earlier grid: the one whose pass changed p̄ least (its estimate).
    let mut best: Option<Candidate> = None;
    while refine.wants_pass(grid.passes, passes[passes.len() - 1].pbar_change) && sol.newton.converged {
        let next = match refine {
            Grading::Edges(_) => grid.refined(&contact_edges(&sol.points, &sol.p)),
            Grading::Zone(_) => grid.zoned(&base, &contact_zones(&sol.points, &sol.p)),
        };
        let Some(next) = next else {
            break;
        };
        fits(&next, (element, half_model), refine)?;
        let d = discretize(&next)?;
        let points = ContactPoints::on(&d, rule);
        let initial = carried(&sol.points, &sol.p, &points);
        let mut s = solve_on(&d, Some(&initial))?;
        s.timing.include_mesh_work(&d);
        let change = pbar_change(&sol, &s);
        let previous_estimate = passes[passes.len() - 1].pbar_change;
        passes.push(Pass {
            n_dofs: d.n_dofs(),
            h_min: next.h_min(),
            pbar_change: Some(change),
            ms: s.timing.total,
        });
        spent.add(&s.timing);
        let (previous, previous_sol) = (std::mem::replace(&mut grid, next), std::mem::replace(&mut sol, s));
        graded = Some(d);
        if let Some(estimate) =
            previous_estimate.filter(|&e| auto && best.as_ref().is_none_or(|b| e < b.estimate))
        {
            best = Some(Candidate {
                grid: previous,
                sol: previous_sol,
                estimate,
            });
        }
        if auto && stopped_falling(&passes) {
            break;
        }
    }
    // `auto` ends on the grid of the smallest estimate: the last, or an earlier one, whose
    // discretisation is built again.
    let last_change = passes[passes.len() - 1].pbar_change;
    if let Some(b) = best.filter(|b| last_change.is_some_and(|c| c > b.estimate)) {
        graded = match b.grid.passes {
            0 => None,
            _ => {
                let d = discretize(&b.grid)?;
                spent.add(&Timing::mesh_work(&d));
                Some(d)
            }
        };
        (grid, sol) = (b.grid, b.sol);
    }
    // At the cap with every estimate above the tolerance: the grading has not settled.
    let smallest = passes
        .iter()
        .filter_map(|p| p.pbar_change)
        .fold(f64::INFINITY, f64::min);
    if auto && passes.len() > MAX_PASSES as usize && smallest >= AUTO_TOLERANCE {
        sol.warnings.insert(
            0,
            Warning::GradingCap {
                passes: MAX_PASSES,
                change: smallest,
                tolerance: AUTO_TOLERANCE,
                kept: grid.passes,
            },
        );
    }
    sol.timing = spent;
    Ok((
        sol,
        Grids {
            grid,
            disc: graded,
            passes,
        },
    ))
}

/// An earlier grid of `auto`: its grid, its solution, and its estimated error, the change of
/// p̄ its pass made (the difference from the coarser grid, as a reference's estimate is,
/// docs/design.md §6).
struct Candidate {
    grid: GradedGrid,
    sol: Solution,
    estimate: f64,
}

/// Whether `auto`'s estimate, the change of p̄ its pass made, has stopped falling: neither of
/// the last two passes brought it below its smallest before them (one pass that does not is
/// the estimate's noise: at level 4 of the paper's problem with ε = 1.5625e-11 the changes
/// run 2.1e-3, 3.1e-3, 1.3e-3, 1.18e-3, 1.23e-3, 1.7e-3, and the grid of 4 passes is kept).
fn stopped_falling(passes: &[Pass]) -> bool {
    let changes: Vec<f64> = passes.iter().filter_map(|p| p.pbar_change).collect();
    match changes.len().checked_sub(2) {
        Some(k) if k > 0 => {
            let before = changes[..k].iter().copied().fold(f64::INFINITY, f64::min);
            changes[k..].iter().all(|&c| c >= before)
        }
        _ => false,
    }
}

/// Refuse `grid` with `element` (a pass of `grading`) when its memory estimate exceeds what
/// this process may use beside what it holds (the up-front estimate, [`super::estimate`],
/// predicted the passes; this is the pass the solve found).
fn fits(
    grid: &GradedGrid,
    (element, half_model): (Element, bool),
    grading: Grading,
) -> Result<(), SolveError> {
    let sizes = grid.sizes(element, half_model);
    sizes.check(&Limits::of_process()).map_err(|e| {
        let workload = Workload::Graded {
            level: grid.level,
            element,
            grading: grading.described(),
        };
        refused(e, workload, sizes.unknowns)
    })
}

/// The contact forces at `to`'s points of the pressure `p` at `from`'s points: p(x)·w, the
/// warm start of the next pass.
fn carried(from: &ContactPoints, p: &[f64], to: &ContactPoints) -> Vec<f64> {
    to.points
        .iter()
        .map(|q| from.interpolate(p, q.x).max(0.0) * q.weight)
        .collect()
}

/// The relative change of p̄ in L²(Γ_C) from `old` to `new`: both piecewise linear on the
/// new grid's vertices (whose lines contain the old's), integrated exactly.
fn pbar_change(old: &Solution, new: &Solution) -> f64 {
    let x = &new.points.vertex_x;
    let d: Vec<f64> = x
        .iter()
        .zip(&new.pbar)
        .map(|(&x, &p)| p - old.points.interpolate_vertices(&old.pbar, x))
        .collect();
    // ∫ of the square of a linear function on [a, b]: (b − a)(f_a² + f_a f_b + f_b²)/3.
    let l2 = |f: &[f64]| -> f64 {
        (0..x.len() - 1)
            .map(|e| (x[e + 1] - x[e]) * (f[e] * f[e] + f[e] * f[e + 1] + f[e + 1] * f[e + 1]) / 3.0)
            .sum::<f64>()
            .sqrt()
    };
    let norm = l2(&new.pbar);
    if norm > 0.0 { l2(&d) / norm } else { 0.0 }
}
