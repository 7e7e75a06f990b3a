//! Accuracy against work (docs/design.md §6, Theorem 2 (26)): errors of every scheme against a
//! reference solution of the continuous problem, observed rates, and the time each solve took.
//!
//! The reference is independent of the penalty: the exact-constraint problem (ε = 0, see
//! [`crate::contact::signorini`]) with Q2 and nodal multipliers (Simpson's points), on a level
//! finer than any studied one. Coarse solutions live on nested meshes and are evaluated
//! exactly at the reference's quadrature points: the pressures on every reference edge of
//! Γ_C, the displacement in every reference cell.
//!
//! The reference carries its own estimated error (its difference from the next coarser
//! reference) and is refined where it is weakest, at the contact edges where p has a
//! square-root profile, until that estimate is at most a tenth of the smallest error any row
//! reports ([`study`], docs/design.md §6).

use std::ops::ControlFlow;
use std::time::Instant;

use serde::Serialize;

use crate::contact::method::MethodFields;
use crate::contact::penalty::{NewtonOptions, SolveError};
use crate::contact::{ContactPoints, Method, Rule};
use crate::fem::basis::{CellRule, evaluate, field_at};
use crate::fem::memory::{Limits, Sizes};
use crate::fem::quadrature::gauss_legendre;
use crate::grading::{GradedGrid, RefineEdges};
use crate::mesh::{Element, MAX_LEVEL, Mesh};
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::solve::{ContactParams, Discretization, Solution, solve_contact};

mod graded;
mod meaning;
mod source;
pub use meaning::check_contact;
pub use source::ReferenceSource;

/// Gauss points per direction for the error integrals (exact for the Q2 reference's products).
const ERROR_POINTS: usize = 4;

/// A displacement and its gradient at a weighted point.
struct Sample {
    x: f64,
    y: f64,
    weight: f64,
    value: [f64; 2],
    grad: [f64; 4],
}

/// The most edge refinements `--reference-refinements` accepts.
pub const MAX_REFINEMENTS: u32 = 8;

/// Why a study's levels and reference level do not fit together.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ReferenceLevelError {
    /// The requested reference is not finer than every studied level.
    #[error("{requested} must be finer than the finest studied level {finest}")]
    NotFiner {
        /// The reference level asked for.
        requested: u32,
        /// The finest studied level.
        finest: u32,
    },
    /// The finest studied level leaves no finer level for the reference.
    #[error("the reference needs a level finer than {finest}; allowed up to {}", MAX_LEVEL - 1)]
    NoFinerLevel {
        /// The finest studied level.
        finest: u32,
    },
}

/// The uniform level of a study's reference (docs/design.md §6): `requested`, or one finer than
/// the finest of `levels`; either way finer than every studied level (coarse solutions are
/// measured on the reference's nested mesh) and at most [`MAX_LEVEL`].
pub fn reference_level(levels: &[u32], requested: Option<u32>) -> Result<u32, ReferenceLevelError> {
    let finest = levels.iter().copied().max().unwrap_or(0);
    match requested {
        Some(requested) if requested <= finest => Err(ReferenceLevelError::NotFiner { requested, finest }),
        Some(requested) => Ok(requested),
        None if finest >= MAX_LEVEL => Err(ReferenceLevelError::NoFinerLevel { finest }),
        None => Ok(finest + 1),
    }
}

/// The reference's grid: the uniform level's vertex lines, with the intervals around the
/// contact edges and next to Γ_C bisected `refinements` times ([`ReferenceMesh::refined`]).
/// Its lines are a superset of the uniform level's, so every studied mesh stays nested in it.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceMesh {
    /// The uniform level it refines.
    pub level: u32,
    /// How many edge refinements it has had (0: the uniform level).
    pub refinements: u32,
    /// Vertex lines x₀ < … and y₀ < … (Γ_C is y = ys.last()).
    pub xs: Vec<f64>,
    /// The horizontal vertex lines y₀ < …, Γ_C the last.
    pub ys: Vec<f64>,
}

impl ReferenceMesh {
    /// The uniform grid of `level` (the lines of [`Scenario::mesh`]).
    pub fn uniform(scenario: &Scenario, level: u32) -> Self {
        let m = scenario.mesh(level, Element::Q1);
        ReferenceMesh {
            level,
            refinements: 0,
            xs: m.xs,
            ys: m.ys,
        }
    }

    /// The Q2 mesh on these lines.
    pub fn mesh(&self, scenario: &Scenario) -> Mesh {
        let (element, _) = REFERENCE_SCHEME;
        Mesh::from_lines(element, self.xs.clone(), self.ys.clone(), scenario.half_model)
    }

    /// Q2 nodes per node row and per node column.
    fn node_counts(&self) -> (usize, usize) {
        let p = REFERENCE_SCHEME.0.order();
        (p * (self.xs.len() - 1) + 1, p * (self.ys.len() - 1) + 1)
    }

    /// The free dofs (bottom clamped; u_x fixed on a half model's symmetry line), as
    /// [`Scenario::n_dofs`] counts them on a uniform grid.
    pub fn n_dofs(&self, scenario: &Scenario) -> usize {
        let (nnx, nny) = self.node_counts();
        let symmetric = if scenario.half_model { nny - 1 } else { 0 };
        2 * nnx * (nny - 1) - symmetric
    }

    /// The lengths of u (every dof of the Q2 mesh) and of p (Simpson's points on Γ_C).
    pub fn lengths(&self) -> (usize, usize) {
        let (nnx, nny) = self.node_counts();
        (2 * nnx * nny, REFERENCE_SCHEME.1.n_points(self.xs.len() - 1))
    }

    /// The smallest cell side (h of the uniform level when unrefined).
    pub fn h_min(&self) -> f64 {
        crate::grading::h_min(&self.xs, &self.ys)
    }

    /// The contact edges of the pressure `p` (at Simpson's points on these lines): every
    /// pair of neighbouring points where p goes from > 0 to 0, as the vertex interval that
    /// holds both.
    pub fn contact_edges(&self, p: &[f64]) -> Vec<usize> {
        let (element, rule) = REFERENCE_SCHEME;
        let (nnx, _) = self.node_counts();
        let node_x: Vec<f64> = (0..nnx)
            .map(|i| match i % 2 {
                0 => self.xs[i / 2],
                _ => 0.5 * (self.xs[i / 2] + self.xs[i / 2 + 1]),
            })
            .collect();
        let points = ContactPoints::new(rule, &node_x, element.order());
        crate::grading::contact_edges(&points, p)
    }

    /// The next refinement, as a graded solve's ([`crate::grading::refine_lines`]): the
    /// `EDGE_WIDTH` (2) x-intervals on each side of every contact edge of `p` (and the edge's
    /// own) bisected, and the `EDGE_WIDTH` rows of cells next to Γ_C; None when `p` has no
    /// contact edge (nothing to refine).
    pub fn refined(&self, p: &[f64]) -> Option<Self> {
        let (xs, ys) = crate::grading::refine_lines(&self.xs, &self.ys, &self.contact_edges(p))?;
        Some(ReferenceMesh {
            level: self.level,
            refinements: self.refinements + 1,
            xs,
            ys,
        })
    }
}

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
    edge_points: Vec<(f64, f64, f64)>,
    /// u_ref at Gauss points of every reference cell.
    cell_points: Vec<Sample>,
    p_norm: f64,
    u_norm: f64,
}

fn solve_fresh(disc: &Discretization, params: &ContactParams) -> Result<Solution, SolveError> {
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

/// Relative errors of one solution against the reference.
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct Errors {
    /// ‖p − p_ref‖₀ / ‖p_ref‖₀ on Γ_C, p the raw pressure in Q_h.
    pub p: f64,
    /// ‖p̄ − p_ref‖₀ / ‖p_ref‖₀, p̄ the smoothed pressure (16)–(17).
    pub pbar: f64,
    /// ‖u − u_ref‖₁ / ‖u_ref‖₁ of (7) over the body.
    pub u: f64,
    /// |P − P_ref| / P_ref.
    pub load: f64,
}

/// A solution as the error integrals see it: a displacement on a mesh nested in the
/// reference's, its pressure at a rule's points, its smoothed pressure at Γ_C's vertices (None:
/// p itself stands for it) and its load.
struct Field<'a> {
    mesh: &'a Mesh,
    u: &'a [f64],
    points: &'a ContactPoints,
    p: &'a [f64],
    pbar: Option<&'a [f64]>,
    load: f64,
}

/// The relative differences of `field` from the reference.
fn differences(reference: &Reference, field: &Field) -> Errors {
    let (mut ep, mut epbar) = (0.0, 0.0);
    for &(x, w, pref) in &reference.edge_points {
        let p = field.points.interpolate(field.p, x);
        let pbar = field.pbar.map_or(p, |v| field.points.interpolate_vertices(v, x));
        ep += w * (p - pref).powi(2);
        epbar += w * (pbar - pref).powi(2);
    }
    let mut eu = 0.0;
    for c in &reference.cell_points {
        let (vh, gh) = evaluate(field.mesh, field.u, c.x, c.y);
        let d2: f64 = vh
            .iter()
            .zip(&c.value)
            .chain(gh.iter().zip(&c.grad))
            .map(|(a, b)| (a - b).powi(2))
            .sum();
        eu += c.weight * d2;
    }
    Errors {
        p: ep.sqrt() / reference.p_norm,
        pbar: epbar.sqrt() / reference.p_norm,
        u: eu.sqrt() / reference.u_norm,
        load: (field.load - reference.load).abs() / reference.load,
    }
}

/// What a row keeps of its solution, so that its errors can be measured again against a
/// refined reference without solving again.
struct Kept {
    mesh: Mesh,
    u: Vec<f64>,
    points: ContactPoints,
    p: Vec<f64>,
    pbar: Vec<f64>,
    load: f64,
}

impl Kept {
    fn of(disc: &Discretization, sol: &Solution) -> Self {
        Kept {
            mesh: disc.mesh.clone(),
            u: sol.displacement(disc),
            points: sol.points.clone(),
            p: sol.p.clone(),
            pbar: sol.pbar.clone(),
            load: sol.load,
        }
    }

    fn errors(&self, reference: &Reference) -> Errors {
        differences(
            reference,
            &Field {
                mesh: &self.mesh,
                u: &self.u,
                points: &self.points,
                p: &self.p,
                pbar: Some(&self.pbar),
                load: self.load,
            },
        )
    }
}

/// The errors of `sol` on `disc` (a mesh nested in the reference's).
pub fn errors(reference: &Reference, disc: &Discretization, sol: &Solution) -> Errors {
    Kept::of(disc, sol).errors(reference)
}

/// Whether a row of a study or a sweep has a result, and if not, why.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Solved and converged.
    Ok,
    /// The solver ran but cannot certify its answer (the row's numbers are its last iterate).
    NotConverged,
    /// The scheme has no unique answer here (ε = 0 with more points than normal displacements).
    Kernel,
    /// The row could not be computed (too large for the memory, a failed factorisation, …).
    Failed,
}

impl Status {
    /// The status of a row whose solve returned `error`.
    pub fn of_error(error: &SolveError) -> Status {
        match error {
            SolveError::Kernel { .. } => Status::Kernel,
            SolveError::NotConverged { .. } => Status::NotConverged,
            _ => Status::Failed,
        }
    }

    /// The token of JSON and CSV: `ok`, `not_converged`, `kernel`, `failed`.
    pub fn token(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::NotConverged => "not_converged",
            Status::Kernel => "kernel",
            Status::Failed => "failed",
        }
    }

    /// The word shown in tables: `ok`, `not converged`, `kernel`, `failed`.
    pub fn word(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::NotConverged => "not converged",
            Status::Kernel => "kernel",
            Status::Failed => "failed",
        }
    }
}

/// JSON carries [`Status::token`], so that JSON and CSV cannot disagree.
impl Serialize for Status {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.token())
    }
}

/// One line of the study.
#[derive(Clone, Debug, Serialize)]
pub struct StudyRow {
    /// The scheme's label: M1–M4 or `element+rule`.
    pub scheme: String,
    /// The element: `q1`, `q2` or `p1`.
    pub element: &'static str,
    /// The contact rule.
    pub rule: &'static str,
    /// The mesh level.
    pub level: u32,
    /// The cell size h of the level: the largest cell side.
    pub h: f64,
    /// The penalty parameter ε (0 for `exact`).
    pub epsilon: f64,
    /// The contact method and its parameters (`method`, `theta`, `gamma0`, `alm_tol`).
    #[serde(flatten)]
    pub method: MethodFields,
    /// The number of free dofs.
    pub n_dofs: usize,
    /// The edge-grading passes its mesh had ([`crate::grading`]; 0: the uniform level).
    pub refine_edges: u32,
    /// The smallest cell side of its mesh (h on a uniform level of square cells).
    pub h_min: f64,
    /// The grading asked (`--refine-edges`): what tells its series apart.
    #[serde(skip)]
    pub grading: RefineEdges,
    /// Whether the row has a certified result.
    pub status: Status,
    /// Why the row has no (certified) result, when it has none.
    pub reason: Option<String>,
    /// Newton iterations (for the ALM, summed over the updates); None without a result.
    pub newton_iterations: Option<usize>,
    /// The ALM's multiplier updates (null for the other methods, or without a result).
    pub outer_iterations: Option<usize>,
    /// Whether Newton converged (false without a result).
    pub converged: bool,
    /// A fresh solve: the mesh's work and Newton (what the pressures need), ms.
    pub solve_ms: Option<f64>,
    /// The load P of the modelled body; None without a result.
    pub load: Option<f64>,
    /// Relative errors against the reference; None without a result.
    pub errors: Option<Errors>,
    /// Observed rates against h (or, in an ε sweep, against ε) from the previous row.
    pub rates: Option<Errors>,
}

impl StudyRow {
    /// The row of a solve: its result, or what stopped it, and what it keeps of its solution.
    fn new(
        reference: &Reference,
        scenario: &Scenario,
        (element, rule): (Element, Rule),
        level: u32,
        (method, epsilon): (Method, f64),
        outcome: Result<(&Discretization, &Solution), &SolveError>,
    ) -> (Self, Option<Kept>) {
        let mut kept = None;
        let mut row = StudyRow {
            scheme: Scheme::new(element, rule).label(),
            element: element.name(),
            rule: rule.name(),
            level,
            h: scenario.h(level),
            epsilon,
            method: method.into(),
            n_dofs: scenario.n_dofs(level, element),
            refine_edges: 0,
            h_min: GradedGrid::uniform(scenario, level).h_min(),
            grading: RefineEdges::default(),
            status: Status::Ok,
            reason: None,
            newton_iterations: None,
            outer_iterations: None,
            converged: false,
            solve_ms: None,
            load: None,
            errors: None,
            rates: None,
        };
        match outcome {
            Ok((disc, sol)) => {
                row.method = sol.method_fields();
                row.newton_iterations = Some(sol.newton.iterations);
                row.outer_iterations = sol.outer_iterations;
                row.converged = sol.newton.converged;
                row.solve_ms = Some(sol.timing.total);
                row.load = Some(sol.load);
                let k = Kept::of(disc, sol);
                row.errors = Some(k.errors(reference));
                kept = Some(k);
                if !sol.newton.converged {
                    row.status = Status::NotConverged;
                    row.reason = sol.newton.diagnosis.clone();
                }
            }
            Err(e) => {
                row.status = Status::of_error(e);
                row.reason = Some(e.to_string());
            }
        }
        row.certify();
        (row, kept)
    }
}

/// True when every row has a certified result (the study's exit code: 0, else 1).
pub fn all_ok(rows: &[StudyRow]) -> bool {
    rows.iter().all(|r| r.status == Status::Ok)
}

/// Observed rates between two rows with results (None unless both are [`Status::Ok`]).
fn rates(prev: &StudyRow, row: &StudyRow, by_epsilon: bool) -> Option<Errors> {
    if prev.status != Status::Ok || row.status != Status::Ok {
        return None;
    }
    let (a, b) = (prev.errors?, row.errors?);
    let scale = if by_epsilon {
        (row.epsilon / prev.epsilon).ln()
    } else {
        (row.abscissa() / prev.abscissa()).ln()
    };
    let r = |a: f64, b: f64| (b / a).ln() / scale;
    let rates = Errors {
        p: r(a.p, b.p),
        pbar: r(a.pbar, b.pbar),
        u: r(a.u, b.u),
        load: r(a.load, b.load),
    };
    // An error of 0 (or a scale of 0) has no rate: never a non-finite one.
    [rates.p, rates.pbar, rates.u, rates.load]
        .iter()
        .all(|v| v.is_finite())
        .then_some(rates)
}

/// The elements of `schemes`, each once, in order of first appearance.
fn elements(schemes: &[(Element, Rule)]) -> Vec<Element> {
    let mut out: Vec<Element> = Vec::new();
    for &(e, _) in schemes {
        if !out.contains(&e) {
            out.push(e);
        }
    }
    out
}

/// Rows grouped per scheme, in `schemes`' order, each group with its rates from the row
/// before it (`by_epsilon`: rates against ε; rows with ε = 0 get none).
fn with_rates(groups: Vec<Vec<StudyRow>>, by_epsilon: bool) -> Vec<StudyRow> {
    let mut rows = Vec::new();
    for group in groups {
        for (i, mut row) in group.iter().cloned().enumerate() {
            let prev = i.checked_sub(1).map(|j| &group[j]);
            if let Some(prev) = prev.filter(|p| !by_epsilon || (p.epsilon > 0.0 && row.epsilon > 0.0)) {
                row.rates = rates(prev, &row, by_epsilon);
            }
            rows.push(row);
        }
    }
    rows
}

/// The method a study's row at `epsilon` uses ([`Method::resolve`]: None and ε = 0 is
/// `exact`), or why it has none.
fn row_method(method: Option<Method>, epsilon: f64) -> Result<(Method, f64), SolveError> {
    Method::resolve(method, epsilon).map_err(|e| SolveError::Input {
        what: "the method",
        message: e.to_string(),
    })
}

/// A row's contact parameters with `rule` at `epsilon`, and whether its method resolves (a row
/// whose method does not still gets parameters, the penalty's, to name it in the table).
fn row_params(
    scenario: &Scenario,
    rule: Rule,
    method: Option<Method>,
    epsilon: f64,
) -> (Result<(), SolveError>, ContactParams) {
    let resolved = row_method(method, epsilon);
    let (method, epsilon) = resolved.clone().unwrap_or((Method::Penalty, epsilon));
    let params = ContactParams {
        rule,
        method,
        epsilon,
        obstacle: scenario.obstacle.clone(),
    };
    (resolved.map(|_| ()), params)
}

/// Every scheme at every level (fresh solves with `method` at ε; None: penalty, or exact for
/// ε = 0), against `reference`.
/// Each mesh is assembled and factorised once and shared by the schemes of its element; each
/// row's `solve_ms` is still a fresh solve's cost (that mesh's work plus the scheme's Newton).
/// A row that cannot be computed says why ([`StudyRow::status`]) and the others go on.
pub fn convergence(
    scenario: &Scenario,
    reference: &Reference,
    schemes: &[(Element, Rule)],
    levels: &[u32],
    method: Option<Method>,
    epsilon: f64,
) -> Vec<StudyRow> {
    let groups = convergence_kept(scenario, reference, schemes, levels, method, epsilon);
    with_rates(strip(groups), false)
}

/// The rows of [`convergence`] per scheme, each with what it keeps of its solution.
fn convergence_kept(
    scenario: &Scenario,
    reference: &Reference,
    schemes: &[(Element, Rule)],
    levels: &[u32],
    method: Option<Method>,
    epsilon: f64,
) -> Vec<Vec<(StudyRow, Option<Kept>)>> {
    let mut groups: Vec<Vec<(StudyRow, Option<Kept>)>> = (0..schemes.len()).map(|_| Vec::new()).collect();
    for element in elements(schemes) {
        for &level in levels {
            let disc = Discretization::of(scenario, level, element);
            for (i, &scheme) in schemes.iter().enumerate().filter(|(_, s)| s.0 == element) {
                let (resolved, params) = row_params(scenario, scheme.1, method, epsilon);
                let (m, e) = (params.method, params.epsilon);
                let solved = disc.as_ref().map_err(Clone::clone).and_then(|disc| {
                    resolved?;
                    let mut sol = solve_fresh(disc, &params)?;
                    sol.timing.include_mesh_work(disc);
                    Ok((disc, sol))
                });
                let outcome = solved.as_ref().map(|(d, s)| (*d, s));
                groups[i].push(StudyRow::new(reference, scenario, scheme, level, (m, e), outcome));
            }
        }
    }
    groups
}

/// Every scheme at one level over several ε (re-solves on one mesh, warm-started from the
/// previous ε), against `reference`; one mesh per element. Rows that cannot be computed say
/// why, as in [`convergence`].
pub fn epsilon_sweep(
    scenario: &Scenario,
    reference: &Reference,
    schemes: &[(Element, Rule)],
    level: u32,
    method: Option<Method>,
    epsilons: &[f64],
) -> Vec<StudyRow> {
    let groups = epsilon_sweep_kept(scenario, reference, schemes, level, method, epsilons);
    with_rates(strip(groups), true)
}

/// The rows of [`epsilon_sweep`] per scheme, each with what it keeps of its solution.
fn epsilon_sweep_kept(
    scenario: &Scenario,
    reference: &Reference,
    schemes: &[(Element, Rule)],
    level: u32,
    method: Option<Method>,
    epsilons: &[f64],
) -> Vec<Vec<(StudyRow, Option<Kept>)>> {
    let mut groups: Vec<Vec<(StudyRow, Option<Kept>)>> = (0..schemes.len()).map(|_| Vec::new()).collect();
    for element in elements(schemes) {
        let disc = Discretization::of(scenario, level, element);
        for (i, &scheme) in schemes.iter().enumerate().filter(|(_, s)| s.0 == element) {
            let mut previous: Option<Vec<f64>> = None;
            for &epsilon in epsilons {
                let (resolved, params) = row_params(scenario, scheme.1, method, epsilon);
                let (m, e) = (params.method, params.epsilon);
                let solved = disc.as_ref().map_err(Clone::clone).and_then(|disc| {
                    resolved?;
                    let sol = solve_contact(
                        disc,
                        &params,
                        previous.as_deref(),
                        &NewtonOptions::default(),
                        &mut |_| ControlFlow::Continue(()),
                    )?;
                    Ok((disc, sol))
                });
                if let Ok((_, sol)) = &solved {
                    previous = Some(sol.newton.forces.clone());
                }
                let outcome = solved.as_ref().map(|(d, s)| (*d, s));
                groups[i].push(StudyRow::new(reference, scenario, scheme, level, (m, e), outcome));
            }
        }
    }
    groups
}

/// The rows of every group, without what they keep.
fn strip(groups: Vec<Vec<(StudyRow, Option<Kept>)>>) -> Vec<Vec<StudyRow>> {
    groups
        .into_iter()
        .map(|g| g.into_iter().map(|(row, _)| row).collect())
        .collect()
}

/// The least-squares slope of y against x over `points` (None with fewer than two distinct x).
pub fn least_squares_slope(points: &[(f64, f64)]) -> Option<f64> {
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let sxx: f64 = points.iter().map(|(x, _)| (x - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    (points.len() >= 2 && sxx > 0.0).then(|| sxy / sxx)
}

/// The least-squares rates of one scheme (and method) over its rows: the slopes of log error
/// against log h (an ε sweep: log ε), beside the row-to-row [`StudyRow::rates`].
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Fit {
    /// The scheme's label: M1–M4 or `element+rule`.
    pub scheme: String,
    /// The element: `q1`, `q2` or `p1`.
    pub element: &'static str,
    /// The contact rule.
    pub rule: &'static str,
    /// The contact method and its parameters (`method`, `theta`, `gamma0`, `alm_tol`).
    #[serde(flatten)]
    /// The method as asked ([`MethodFields::setting`]: `auto`'s γ₀ varies by level).
    pub method: MethodFields,
    /// The edge-grading passes asked of its rows (`0`, `3` or `auto`; [`crate::grading`]).
    pub refine_edges: String,
    /// Its abscissa: `h`, `epsilon`, or for graded rows `n^-1/2` (the unknowns n).
    pub abscissa: &'static str,
    /// The rows fitted: those with a result ([`Status::Ok`]), every error > 0, and h (ε) > 0.
    pub rows: usize,
    /// The slopes (None with fewer than two such rows).
    pub rates: Option<Errors>,
}

/// One [`Fit`] per run of rows with the same scheme and method, in the rows' order.
pub fn fits(rows: &[StudyRow], by_epsilon: bool) -> Vec<Fit> {
    let mut out: Vec<Fit> = Vec::new();
    let mut start = 0;
    while start < rows.len() {
        let first = &rows[start];
        let len = rows[start..].iter().take_while(|r| r.same_series(first)).count();
        let usable: Vec<(f64, Errors)> = rows[start..start + len]
            .iter()
            .filter(|r| r.status == Status::Ok)
            .filter_map(|r| Some((if by_epsilon { r.epsilon } else { r.abscissa() }, r.errors?)))
            .filter(|(x, e)| {
                *x > 0.0
                    && [e.p, e.pbar, e.u, e.load]
                        .iter()
                        .all(|v| *v > 0.0 && v.is_finite())
            })
            .collect();
        let slope = |f: fn(&Errors) -> f64| {
            let points: Vec<(f64, f64)> = usable.iter().map(|(x, e)| (x.ln(), f(e).ln())).collect();
            least_squares_slope(&points)
        };
        let rates = (|| {
            Some(Errors {
                p: slope(|e| e.p)?,
                pbar: slope(|e| e.pbar)?,
                u: slope(|e| e.u)?,
                load: slope(|e| e.load)?,
            })
        })();
        out.push(Fit {
            scheme: first.scheme.clone(),
            element: first.element,
            rule: first.rule,
            method: first.method.setting(),
            refine_edges: first.grading.to_string(),
            abscissa: match (by_epsilon, first.grading.grades()) {
                (true, _) => "epsilon",
                (false, true) => "n^-1/2",
                (false, false) => "h",
            },
            rows: usable.len(),
            rates,
        });
        start += len;
    }
    out
}

/// What a study measures: a refinement over levels at one ε, or a sweep of ε at one level.
#[derive(Clone, Copy, Debug)]
pub enum Plan<'a> {
    /// Every scheme at each of `levels`, at `epsilon` ([`convergence`]), for each grading of
    /// `refine` (`--refine-edges`; `[RefineEdges::default()]`: uniform levels only).
    Levels {
        /// The levels studied.
        levels: &'a [u32],
        /// The penalty parameter ε of every row.
        epsilon: f64,
        /// The edge gradings, each a series per scheme ([`crate::grading`]).
        refine: &'a [RefineEdges],
    },
    /// Every scheme at `level`, at each of `epsilons` ([`epsilon_sweep`]).
    Sweep {
        /// The level of every row.
        level: u32,
        /// The ε swept.
        epsilons: &'a [f64],
    },
}

/// A study's result: its reference (with its estimated error and refinements), its rows with
/// their row-to-row rates, and the least-squares rate of every scheme.
pub struct Study {
    /// The reference, as refined, with its estimated error.
    pub reference: Reference,
    /// The rows, grouped per scheme in the order asked, each group in the plan's order of
    /// levels (or ε).
    pub rows: Vec<StudyRow>,
    /// One least-squares fit per scheme (and method), in the rows' order.
    pub fits: Vec<Fit>,
}

/// Every scheme of `plan` against a reference at `reference_level` (≥ 1) that is refined at
/// its contact edges, at most `max_refinements` times, until its estimated error is at most a
/// tenth of the smallest error any row reports ([`Target`]). The rows are solved once: after a
/// refinement their errors are measured again against the refined reference from what they
/// kept. `fetch` provides the reference's fields on a grid (solved, or from the cache).
pub fn study(
    scenario: &Scenario,
    schemes: &[(Element, Rule)],
    method: Option<Method>,
    plan: Plan,
    (reference_level, max_refinements): (u32, u32),
    fetch: &mut Fetch,
) -> Result<Study, SolveError> {
    check_contact(scenario)?;
    let (mut reference, mut fields) = uniform_reference(scenario, reference_level, fetch)?;
    let (mut groups, by_epsilon) = match plan {
        Plan::Levels {
            levels,
            epsilon,
            refine,
        } => (
            graded::levels_kept(scenario, &reference, schemes, levels, (method, epsilon), refine),
            false,
        ),
        Plan::Sweep { level, epsilons } => (
            epsilon_sweep_kept(scenario, &reference, schemes, level, method, epsilons),
            true,
        ),
    };
    let rows = |groups: &Vec<Vec<(StudyRow, Option<Kept>)>>| -> Vec<StudyRow> {
        groups.iter().flatten().map(|(r, _)| r.clone()).collect()
    };
    let mut target = Target::of(&rows(&groups));
    // Refine, measure the rows again, and refine on if their new errors ask for more.
    loop {
        let refinements = reference.grid.refinements;
        (reference, fields) = refine_reference(scenario, (reference, fields), target, max_refinements, fetch);
        if reference.grid.refinements == refinements {
            break;
        }
        for (row, kept) in groups.iter_mut().flatten() {
            if let Some(kept) = kept {
                row.errors = Some(kept.errors(&reference));
                row.certify();
            }
        }
        target = Target::of(&rows(&groups));
        reference.target = target;
        let met = match (&target, &reference.estimate) {
            (Some(t), Some(e)) => t.met_by(e),
            _ => true,
        };
        if met {
            reference.stopped = None;
        }
        if met || reference.stopped.is_some() {
            break;
        }
    }
    let rows = with_rates(strip(groups), by_epsilon);
    let fits = fits(&rows, by_epsilon);
    Ok(Study {
        reference,
        rows,
        fits,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reference is one level finer than the finest studied by default, any finer level
    /// when asked; never one a studied mesh is not nested in, never past MAX_LEVEL.
    #[test]
    fn the_reference_level_is_finer_than_every_studied_level() {
        assert_eq!(reference_level(&[0, 3, 1], None), Ok(4));
        assert_eq!(reference_level(&[0, 1], Some(5)), Ok(5));
        assert_eq!(
            reference_level(&[0, 3], Some(3)),
            Err(ReferenceLevelError::NotFiner {
                requested: 3,
                finest: 3
            })
        );
        assert_eq!(reference_level(&[7], None), Ok(8));
        let none = reference_level(&[MAX_LEVEL], None).unwrap_err();
        assert_eq!(none, ReferenceLevelError::NoFinerLevel { finest: MAX_LEVEL });
        assert_eq!(
            none.to_string(),
            "the reference needs a level finer than 8; allowed up to 7"
        );
    }
}
