//! The reference solution of a study (docs/design.md §6): the exact-constraint problem with Q2
//! and Simpson multipliers on the reference grid, its memory guard, its estimated error (the
//! difference from the next coarser reference) and the target the rows ask of it.

use std::ops::ControlFlow;
use std::time::Instant;

use serde::Serialize;

use super::errors::{ERROR_POINTS, Field, Sample, differences};
use super::grid::ReferenceMesh;
use super::row::{Status, StudyRow};
use crate::contact::penalty::{NewtonOptions, SolveError};
use crate::contact::{ContactPoints, Method, Rule};
use crate::fem::basis::{CellRule, field_at};
use crate::fem::memory::{Limits, Sizes};
use crate::fem::quadrature::gauss_legendre;
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::solve::{ContactParams, Discretization, Solution, solve_contact};
use crate::study::source::ReferenceSource;

/// The reference's estimated error: its relative difference from the next coarser reference
/// (the previous refinement, or the uniform level − 1), p in L²(Γ_C), u in H¹ (7), the load.
/// After edge refinements u keeps the uniform level's estimate: a refinement leaves the
/// body's error away from the contact edges as it was, so the difference of two refinements
/// would miss it (docs/design.md §6).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Estimate {
    /// Relative difference of p in L²(Γ_C).
    pub p: f64,
    /// Relative difference of u in H¹ (7) (after edge refinements the uniform level's).
    pub u: f64,
    /// Relative difference of the load P.
    pub load: f64,
    /// What p and the load were compared with: `level L` (uniform) or `refinement k`.
    pub against: String,
}

/// What the study asks of its reference: an estimated error at most a tenth of the smallest
/// error any row reports, for p (raw or smoothed) and for u.
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct Target {
    /// The largest estimated error of p allowed (relative, L²(Γ_C)).
    pub p: f64,
    /// The largest estimated error of u allowed (relative, H¹ (7)).
    pub u: f64,
}

/// The share of the smallest row error the reference's estimated error may reach.
pub const TARGET_SHARE: f64 = 0.1;

impl Target {
    /// A tenth of the smallest p (or p̄) and u errors of the rows with a result (None when no
    /// row has one).
    pub fn of(rows: &[StudyRow]) -> Option<Self> {
        let ok = || {
            rows.iter()
                .filter(|r| r.status == Status::Ok)
                .filter_map(|r| r.errors)
        };
        let smallest =
            |v: &mut dyn Iterator<Item = f64>| v.filter(|e| *e > 0.0).fold(f64::INFINITY, f64::min);
        let p = smallest(&mut ok().flat_map(|e| [e.p, e.pbar]));
        let u = smallest(&mut ok().map(|e| e.u));
        (p.is_finite() && u.is_finite()).then_some(Target {
            p: TARGET_SHARE * p,
            u: TARGET_SHARE * u,
        })
    }

    /// Whether `estimate` meets it.
    pub fn met_by(&self, estimate: &Estimate) -> bool {
        estimate.p <= self.p && estimate.u <= self.u
    }
}

/// The reference solution, with its values where errors are integrated.
pub struct Reference {
    /// Its uniform level.
    pub level: u32,
    /// Its element: Q2 ([`REFERENCE_SCHEME`]).
    pub element: Element,
    /// Its rule: Simpson ([`REFERENCE_SCHEME`]).
    pub rule: Rule,
    /// Its grid (the uniform level, and its edge refinements).
    pub grid: ReferenceMesh,
    /// Its number of free dofs.
    pub n_dofs: usize,
    /// Its load P of the modelled body.
    pub load: f64,
    /// The time its solve took, ms (as solved, also when read from the cache).
    pub ms: f64,
    /// Solved by this run or read from the cache.
    pub source: ReferenceSource,
    /// Its estimated error (None until compared with a coarser reference).
    pub estimate: Option<Estimate>,
    /// What the study asked of it (None before any row was computed).
    pub target: Option<Target>,
    /// Why the refinement stopped before the target was met (the cap), if it did.
    pub stopped: Option<String>,
    /// (x, weight, p_ref) at Gauss points of every reference edge of Γ_C.
    pub(super) edge_points: Vec<(f64, f64, f64)>,
    /// u_ref at Gauss points of every reference cell.
    pub(super) cell_points: Vec<Sample>,
    pub(super) p_norm: f64,
    pub(super) u_norm: f64,
}

pub(super) fn solve_fresh(disc: &Discretization, params: &ContactParams) -> Result<Solution, SolveError> {
    solve_contact(disc, params, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
}

/// What the reference is made of: the displacement on every dof of the Q2 mesh and the
/// exact-constraint pressure at Simpson's points (what [`crate::cache`] stores).
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceFields {
    /// The displacement on every dof of the Q2 mesh, node-major (u_x at `2n`, u_y at `2n + 1`).
    pub u: Vec<f64>,
    /// The exact-constraint pressure at Simpson's points on Γ_C, ascending x.
    pub p: Vec<f64>,
    /// The load P of the modelled body.
    pub load: f64,
    /// The number of free dofs.
    pub n_dofs: usize,
    /// The time the solve took, ms.
    pub ms: f64,
    /// Solved now or read from the cache (not stored in the cache's entries).
    pub source: ReferenceSource,
}

/// The reference's element and rule: Q2 + Simpson (M4) with the exact constraint.
pub const REFERENCE_SCHEME: (Element, Rule) = (Element::Q2, Rule::Simpson);

impl ReferenceFields {
    /// Solve Q2 + Simpson with the exact constraint at `level` (expensive: only when asked).
    pub fn solve(scenario: &Scenario, level: u32) -> Result<Self, SolveError> {
        Self::solve_on(scenario, &ReferenceMesh::uniform(scenario, level))
    }

    /// Solve Q2 + Simpson with the exact constraint on `grid`, refused before anything is
    /// allocated when it does not fit the memory ([`crate::fem::memory`]).
    pub fn solve_on(scenario: &Scenario, grid: &ReferenceMesh) -> Result<Self, SolveError> {
        let t = Instant::now();
        let rule = REFERENCE_SCHEME.1;
        fits_memory(scenario, grid)?;
        let disc = Discretization::new(grid.mesh(scenario), scenario.material, scenario.integration)?;
        let params = ContactParams {
            rule,
            method: Method::Exact,
            epsilon: 0.0,
            obstacle: scenario.obstacle.clone(),
        };
        let sol = solve_fresh(&disc, &params)?;
        if !sol.newton.converged {
            return Err(SolveError::NotConverged {
                what: "the reference solution (q2 + simpson, ε = 0)",
                iterations: sol.newton.iterations,
                residual: sol.newton.residual,
                diagnosis: sol.newton.diagnosis.clone().unwrap_or_default(),
            });
        }
        Ok(ReferenceFields {
            u: sol.displacement(&disc),
            p: sol.p,
            load: sol.load,
            n_dofs: disc.n_dofs(),
            ms: t.elapsed().as_secs_f64() * 1e3,
            source: ReferenceSource::Computed,
        })
    }
}

/// Refuse `grid` when its memory estimate exceeds what this process may use.
fn fits_memory(scenario: &Scenario, grid: &ReferenceMesh) -> Result<(), SolveError> {
    let (nnx, _) = grid.node_counts();
    let sizes = Sizes {
        element: REFERENCE_SCHEME.0,
        unknowns: grid.n_dofs(scenario),
        trace: nnx,
        points: grid.lengths().1,
    };
    sizes.check(&Limits::of_process()).map_err(|e| {
        let refined = match grid.refinements {
            0 => String::new(),
            k => format!(" + {k} edge refinements"),
        };
        SolveError::TooLarge(format!(
            "the reference (q2 + simpson) at level {}{refined}: {e}; choose a coarser --reference-level",
            grid.level
        ))
    })
}

impl Reference {
    /// Q2 + Simpson with the exact constraint at `level` (expensive: compute only when asked;
    /// [`crate::cache::reference`] keeps it between runs).
    pub fn compute(scenario: &Scenario, level: u32) -> Result<Self, SolveError> {
        let grid = ReferenceMesh::uniform(scenario, level);
        let fields = ReferenceFields::solve_on(scenario, &grid)?;
        Ok(Reference::from_fields(scenario, &grid, &fields))
    }

    /// The reference from its fields on `grid` (solved now or read from the cache): its
    /// values at the points where errors are integrated.
    pub fn from_fields(scenario: &Scenario, grid: &ReferenceMesh, fields: &ReferenceFields) -> Self {
        let (element, rule) = REFERENCE_SCHEME;
        let mesh = grid.mesh(scenario);
        let points = ContactPoints::new(rule, &mesh.node_x[..mesh.nnx()], element.order());
        let (u, p) = (&fields.u, &fields.p);
        let gauss = gauss_legendre(ERROR_POINTS);
        let vx = &points.vertex_x;
        let mut edge_points = Vec::with_capacity(gauss.len() * vx.len());
        for e in 0..vx.len() - 1 {
            let h = vx[e + 1] - vx[e];
            for &(xi, w) in &gauss {
                let x = vx[e] + h * (xi + 1.0) / 2.0;
                edge_points.push((x, w * h / 2.0, points.interpolate(p, x)));
            }
        }
        let mut cells = Vec::with_capacity(mesh.n_cells() * ERROR_POINTS * ERROR_POINTS);
        let (cell_rule, mut quad, mut nodes) = (CellRule::new(element, ERROR_POINTS), Vec::new(), Vec::new());
        for cj in 0..mesh.ny() {
            for ci in 0..mesh.nx() {
                nodes.clear();
                nodes.extend(mesh.cell_node_iter(ci, cj));
                cell_rule.points_into(&mesh, ci, cj, &mut quad);
                for q in &quad {
                    // The point's own cell: its shape functions are already at hand.
                    let (value, grad) = field_at(q, &nodes, u);
                    cells.push(Sample {
                        x: q.x,
                        y: q.y,
                        weight: q.weight,
                        value,
                        grad,
                    });
                }
            }
        }
        let p_norm = edge_points.iter().map(|(_, w, p)| w * p * p).sum::<f64>().sqrt();
        let u_norm = cells
            .iter()
            .map(|c| c.weight * c.value.iter().chain(&c.grad).map(|a| a * a).sum::<f64>())
            .sum::<f64>()
            .sqrt();
        Reference {
            level: grid.level,
            element,
            rule,
            grid: grid.clone(),
            n_dofs: fields.n_dofs,
            load: fields.load,
            ms: fields.ms,
            source: fields.source,
            estimate: None,
            target: None,
            stopped: None,
            edge_points,
            cell_points: cells,
            p_norm,
            u_norm,
        }
    }

    /// This reference's difference from a coarser one (`fields` on `grid`, nested in this
    /// one's): its [`Estimate`].
    pub fn estimate_against(
        &self,
        scenario: &Scenario,
        grid: &ReferenceMesh,
        fields: &ReferenceFields,
    ) -> Estimate {
        let (element, rule) = REFERENCE_SCHEME;
        let mesh = grid.mesh(scenario);
        let points = ContactPoints::new(rule, &mesh.node_x[..mesh.nnx()], element.order());
        let e = differences(
            self,
            &Field {
                mesh: &mesh,
                u: &fields.u,
                points: &points,
                p: &fields.p,
                pbar: None,
                load: fields.load,
            },
        );
        Estimate {
            p: e.p,
            u: e.u,
            load: e.load,
            against: match grid.refinements {
                0 => format!("level {}", grid.level),
                k => format!("refinement {k}"),
            },
        }
    }
}

/// Where a study's reference comes from: the fields on a grid, solved or read from a cache
/// ([`crate::cache::fields`]), with whatever the caller reports on the way.
pub type Fetch<'a> = dyn FnMut(&ReferenceMesh) -> Result<ReferenceFields, SolveError> + 'a;

/// The uniform reference at `level` with its estimated error against level − 1 (none at
/// level 0), and its fields.
pub fn uniform_reference(
    scenario: &Scenario,
    level: u32,
    fetch: &mut Fetch,
) -> Result<(Reference, ReferenceFields), SolveError> {
    let grid = ReferenceMesh::uniform(scenario, level);
    let fields = fetch(&grid)?;
    let mut reference = Reference::from_fields(scenario, &grid, &fields);
    reference.check_meaningful()?;
    if let Some(coarser) = level.checked_sub(1) {
        let coarse = ReferenceMesh::uniform(scenario, coarser);
        reference.estimate = Some(reference.estimate_against(scenario, &coarse, &fetch(&coarse)?));
    }
    Ok((reference, fields))
}

/// Refine `reference` (whose fields are `fields`) at its contact edges until its estimated
/// error meets `target`, to at most `max_refinements` refinements in all. The memory guard or
/// the cap stops it without failing: [`Reference::stopped`] says why. A refinement that does
/// not fit the memory, or whose solve fails, leaves the last good reference in place.
pub fn refine_reference(
    scenario: &Scenario,
    (mut reference, mut fields): (Reference, ReferenceFields),
    target: Option<Target>,
    max_refinements: u32,
    fetch: &mut Fetch,
) -> (Reference, ReferenceFields) {
    reference.target = target;
    reference.stopped = None;
    let Some(target) = target else {
        return (reference, fields);
    };
    loop {
        if reference.estimate.as_ref().is_some_and(|e| target.met_by(e)) {
            return (reference, fields);
        }
        let stop = |mut r: Reference, f: ReferenceFields, why: String| {
            r.stopped = Some(why);
            (r, f)
        };
        if reference.estimate.as_ref().is_some_and(|e| e.p <= target.p) {
            let why = "u's estimated error is the uniform level's, which edge refinements do not lower: a finer --reference-level meets it".to_string();
            return stop(reference, fields, why);
        }
        if reference.grid.refinements >= max_refinements {
            let why = format!("the cap of {max_refinements} edge refinements (--reference-refinements)");
            return stop(reference, fields, why);
        }
        let Some(grid) = reference.grid.refined(&fields.p) else {
            let why = "the reference's pressure has no contact edge to refine".to_string();
            return stop(reference, fields, why);
        };
        let finer = match fits_memory(scenario, &grid).and_then(|()| fetch(&grid)) {
            Ok(f) => f,
            Err(e) => {
                let why = format!("refinement {} failed: {e}", grid.refinements);
                return stop(reference, fields, why);
            }
        };
        let mut next = Reference::from_fields(scenario, &grid, &finer);
        if let Err(e) = next.check_meaningful() {
            let why = format!("refinement {}: {e}", grid.refinements);
            return stop(reference, fields, why);
        }
        let mut estimate = next.estimate_against(scenario, &reference.grid, &fields);
        if let Some(previous) = &reference.estimate {
            estimate.u = previous.u;
        }
        next.estimate = Some(estimate);
        next.target = Some(target);
        (reference, fields) = (next, finer);
    }
}
