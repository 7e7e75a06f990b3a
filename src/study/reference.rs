//! The reference solution of a study (docs/design.md §6): the exact-constraint problem with Q2
//! and Simpson multipliers on the reference grid, its memory guard, its estimated error (the
//! difference from the next coarser reference) and the target the rows ask of it.

use std::ops::ControlFlow;
use std::time::Instant;

use serde::Serialize;

use super::grid::{REFERENCE_SCHEME, ReferenceMesh};
use super::source::ReferenceSource;
use crate::contact::ContactParams;
use crate::contact::friction::Friction;
use crate::contact::newton::NewtonOptions;
use crate::contact::pressure::load;
use crate::contact::solution::Solution;
use crate::contact::{ContactPoints, Method, Rule};
use crate::discretization::Discretization;
use crate::discretization::refused;
use crate::error::{SolveError, Workload};
use crate::fem::basis::{CellRule, field_at};
use crate::fem::memory::{Limits, Sizes};
use crate::fem::quadrature::gauss_legendre;
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::solve::{Request, Warm, solve};

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
    /// With friction: its tangential traction where p's is, and Q.
    pub(super) tangential: Option<TangentialReference>,
}

/// The reference's friction (docs/design.md §11): t_ref at the Gauss points of
/// [`Reference::edge_points`], in their order, and its tangential load Q_ref = ∫ t_ref dx.
pub(super) struct TangentialReference {
    pub(super) edge_t: Vec<f64>,
    pub(super) load: f64,
}

/// A fresh solve of `params` on `disc` with `friction` (the library's entry, [`solve`]).
pub(super) fn solve_row(
    disc: &Discretization,
    params: &ContactParams,
    friction: &Friction,
) -> Result<Solution, SolveError> {
    solve_warm(disc, params, friction, None)
}

/// [`solve_row`] warm-started from an earlier solve's forces (frictionless only: a friction
/// path starts from its press).
pub(super) fn solve_warm(
    disc: &Discretization,
    params: &ContactParams,
    friction: &Friction,
    initial: Option<&[f64]>,
) -> Result<Solution, SolveError> {
    let warm = match initial {
        Some(y) if !friction.is_on() => Warm::Forces(y),
        _ => Warm::Rest,
    };
    let request = Request::new(params.clone())
        .with_friction(*friction)
        .warm_from(warm);
    let go_on = &mut |_: &_| ControlFlow::Continue(());
    Ok(solve(disc, &request, &NewtonOptions::default(), go_on)?.sol)
}

impl Reference {
    /// With friction, its tangential load Q_ref = ∫ t_ref dx (None without friction).
    pub fn tangential_load(&self) -> Option<f64> {
        self.tangential.as_ref().map(|t| t.load)
    }
}

/// The friction of a study's reference: the scenario's, without a tangential penalty (the
/// reference imposes both conditions exactly, ε = 0; ε_t belongs to the rows).
pub fn reference_friction(scenario: &Scenario) -> Friction {
    Friction {
        epsilon_t: None,
        ..scenario.friction
    }
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
    /// With friction, the exact tangential traction t at Simpson's points on Γ_C, ascending x
    /// (empty without friction).
    pub t: Vec<f64>,
    /// The number of free dofs.
    pub n_dofs: usize,
    /// The time the solve took, ms.
    pub ms: f64,
    /// Solved now or read from the cache (not stored in the cache's entries).
    pub source: ReferenceSource,
}

impl ReferenceFields {
    /// Solve Q2 + Simpson with the exact constraint at `level` (expensive: only when asked).
    ///
    /// # Errors
    ///
    /// As [`ReferenceFields::solve_on`]'s.
    pub fn solve(scenario: &Scenario, level: u32) -> Result<Self, SolveError> {
        Self::solve_on(scenario, &ReferenceMesh::uniform(scenario, level))
    }

    /// Solve Q2 + Simpson with the exact constraint on `grid` (and the scenario's friction,
    /// imposed exactly too: [`reference_friction`]), refused before anything is allocated when
    /// it does not fit the memory ([`crate::fem::memory`]).
    ///
    /// # Errors
    ///
    /// The grid does not fit the memory, or the solve fails or does not converge ([`SolveError`]).
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
        let friction = reference_friction(scenario);
        let sol = solve_row(&disc, &params, &friction)?;
        if let Some(diagnosis) = sol.newton.failure() {
            return Err(SolveError::NotConverged {
                what: if friction.is_on() {
                    "the reference solution (q2 + simpson, ε = 0, with friction)"
                } else {
                    "the reference solution (q2 + simpson, ε = 0)"
                },
                iterations: sol.newton.iterations,
                residual: sol.newton.residual,
                diagnosis,
            });
        }
        Ok(ReferenceFields {
            u: sol.displacement(&disc),
            t: sol.friction.as_ref().map(|f| f.t.clone()).unwrap_or_default(),
            p: sol.p,
            load: sol.load,
            n_dofs: disc.n_dofs(),
            ms: t.elapsed().as_secs_f64() * 1e3,
            source: ReferenceSource::Computed,
        })
    }
}

/// Refuse `grid` when its memory estimate exceeds what this process may use.
pub(super) fn fits_memory(scenario: &Scenario, grid: &ReferenceMesh) -> Result<(), SolveError> {
    let (nnx, _) = grid.node_counts();
    let sizes = Sizes {
        element: REFERENCE_SCHEME.0,
        unknowns: grid.n_dofs(scenario),
        trace: nnx,
        points: grid.lengths().1,
    };
    sizes.check(&Limits::of_process()).map_err(|e| {
        let workload = Workload::Reference {
            level: grid.level,
            refinements: grid.refinements,
        };
        refused(e, workload, sizes.unknowns)
    })
}

impl Reference {
    /// Q2 + Simpson with the exact constraint at `level` (expensive: compute only when asked;
    /// [`crate::cache::reference`] keeps it between runs).
    ///
    /// # Errors
    ///
    /// As [`ReferenceFields::solve_on`]'s, or the reference is not meaningful
    /// ([`Reference::check_meaningful`]).
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
        let tangential = (!fields.t.is_empty()).then(|| TangentialReference {
            edge_t: edge_points
                .iter()
                .map(|&(x, _, _)| points.interpolate(&fields.t, x))
                .collect(),
            load: load(&points, &fields.t),
        });
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
            tangential,
        }
    }
}

/// Gauss points per direction for the error integrals (exact for the Q2 reference's products).
pub(super) const ERROR_POINTS: usize = 4;

/// A displacement and its gradient at a weighted point.
pub(super) struct Sample {
    pub(super) x: f64,
    pub(super) y: f64,
    pub(super) weight: f64,
    pub(super) value: [f64; 2],
    pub(super) grad: [f64; 4],
}
