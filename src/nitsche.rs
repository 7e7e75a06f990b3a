//! Nitsche's method for unilateral contact (Chouly and Hild 2013, SIAM J. Numer. Anal. 51(2);
//! Chouly, Hild and Renard 2015, Math. Comp. 84): the contact condition is imposed weakly
//! through the normal stress, with no multiplier space and no inf-sup condition.
//!
//! **Signs** (docs/design.md §1): Γ_C is the top side, n = (0, 1), u_n = u_y, σ_n(u) = σ_yy(u),
//! and the constraint is u_n − g ≤ 0. The contact conditions u_n − g ≤ 0, σ_n ≤ 0,
//! σ_n (u_n − g) = 0 are equivalent, for any γ > 0, to σ_n = [P_γ(u)]₋ with
//! P_γ(u) = σ_n(u) − γ(u_n − g) and \[x\]₋ = min(x, 0). Green's formula on the body (no body
//! force or traction; the sides free or held, Γ_D clamped, no friction on Γ_C) gives
//! a(u, v) = ∫_ΓC σ_n(u) v_n, and writing γ v_n = θσ_n(v) − P_θγ(v), P_θγ(v) = θσ_n(v) − γv_n,
//! then replacing σ_n(u) by [P_γ(u)]₋ in the second part gives Nitsche's problem
//!
//!   a(u, v) − (θ/γ) ∫_ΓC σ_n(u) σ_n(v) + (1/γ) ∫_ΓC [P_γ(u)]₋ P_θγ(v) = 0   for all v,
//!
//! which the exact solution satisfies (consistency). θ = 1 is symmetric (the optimality
//! condition of a convex energy when K − (1/γ)SᵀWS is positive definite), θ = 0 incomplete,
//! θ = −1 skew-symmetric. The contact pressure, compression positive like the penalty's (§4),
//! is p = −[P_γ(u)]₋ = (γ(u_n − g) − σ_n(u))⁺ ≥ 0. Here γ = γ₀·E/h_K with h_K the longest side
//! of the boundary cell.
//!
//! **Quadrature.** ∫_ΓC is the contact rule I of (10) on each edge, at the *edge's* points: a
//! point shared by two edges (trapezoid, Simpson) is two points here, one per edge, because
//! σ_n(u_h) jumps across cells. The reported p at a shared point is the weighted mean of its two
//! one-sided values, so that I(p, 1) is the method's load.
//!
//! **Condensation** (the design the issue asks for: θ, γ₀ and the depth change fast). With S
//! and B the rows giving σ_n and u_n at the n edge points (both supported on dofs of the cells
//! along Γ_C: the *layer* is the dofs they use, `layer_dofs`) the discrete problem is
//!
//!   K_θ u = Σ_q γ_q⁻¹ P_θ,qᵀ y_q,   y_q = w_q p_q,  p_q = (−P_1,q u − γ_q g_q)⁺,
//!
//! with K_θ = K − Sᵀ D S, D = θ W Γ⁻¹, P_θ = θS − ΓB. Everything needed lives on the n points:
//! once per mesh, K is factorised a second time with the layer's dofs last; its trailing block
//! L_BB gives G = R K⁻¹ Rᵀ for R = [S; B] as (L_BB⁻¹ R_Bᵀ)ᵀ(L_BB⁻¹ R_Bᵀ), once per rule. Per
//! (θ, γ₀), Woodbury turns K⁻¹ into K_θ⁻¹ = K⁻¹ + K⁻¹Sᵀ Z S K⁻¹, Z = (I − D G_SS)⁻¹ D, and
//! gives H = P_1 K_θ⁻¹ P_θᵀ, an n×n dense matrix with P_1 u = H ỹ for the scaled forces
//! ỹ = Γ⁻¹y. The semismooth Newton on ỹ then lives on the points like the penalty's
//! (`super::penalty`): with
//! v = −Γg − H ỹ = γ(u_n − g) − σ_n and the active set A = {v > 0}, each step solves
//! (W_A⁻¹Γ_A + H_AA) ỹ_A = −Γ_A g_A, by Cholesky for θ = 1 and by LU otherwise (H is
//! non-symmetric unless θ = 1). A depth change costs only the Newton; θ or γ₀ costs O(n³)
//! dense work (for θ = 1 one triangular solve and half a product fewer, as H = H₀ + WᵀW is
//! symmetric: `Correction`); K is never refactorised.
//!
//! **Stability.** On any active set the symmetric part of the Jacobian is bounded below by
//! K − κ(1/γ)SᵀWS, κ = (1 + θ)²/4 (Young's inequality on the cross term (1 + θ)σ_n v_n; the
//! inactive points give K − (θ/γ)SᵀWS, and θ ≤ κ): the method is well posed (its operator
//! strongly monotone) when that matrix is positive definite, i.e. when the symmetric matrix
//! I − κ C_γ^½ G_SS C_γ^½ is, C_γ = WΓ⁻¹. Its Cholesky factorisation decides, and the
//! threshold is γ₀ > κ γ₀* with γ₀* = λ_max(C^½ G_SS C^½), C = diag(w_q h_q / E)
//! ([`stability_threshold`]): γ₀* for θ = 1 (where it is also exactly where K_1 stops being
//! positive definite, the loss of the energy's convexity), γ₀*/4 for θ = 0, nothing for
//! θ = −1. Below it the solve is refused with a typed error, never a result.

use std::collections::HashMap;
use std::ops::ControlFlow;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::linalg::solvers::Solve;
use faer::{Accum, ColRef, Mat, Par, Side};

use crate::contact::method::{AUTO_GAMMA0_FACTOR, GAMMA0_RANGE, Gamma0};
use crate::contact::penalty::{
    Iterate, Iteration, NewtonOptions, NewtonResult, Progress, active_block, dot, round_off, stalled,
};
use crate::contact::{ContactParams, ContactPoints, Rule, load, smoothed_pressure};
use crate::discretization::{Discretization, fem_error};
use crate::error::SolveError;
use crate::fem::basis::lagrange_1d;
use crate::fem::error::gib;
use crate::fem::factor::{Analysis, Factor};
use crate::fem::memory::Limits;
use crate::fem::{Form, assemble};
use crate::material::Material;
use crate::mesh::{Diagonal, Element, Mesh};
use crate::solution::{Solution, Timing};
use crate::stress::Stress;
use crate::text::num;
use crate::warning;

/// Nitsche's parameters: θ ∈ [−1, 1] (1 symmetric, 0 incomplete, −1 skew-symmetric) and
/// γ₀ > 0, the dimensionless γ = γ₀·E/h.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NitscheParams {
    /// θ ∈ [−1, 1].
    pub theta: f64,
    /// γ₀ > 0, dimensionless.
    pub gamma0: f64,
}

/// Columns per triangular solve in [`Layer::couplings`].
const SOLVE_BLOCK: usize = 64;

/// The per-mesh state of Nitsche's method, built only when a Nitsche solve asks for it and
/// kept with the [`Discretization`] ([`cache`]): the layer's factor, then the point couplings
/// of each rule and the last (rule, θ, γ₀)'s operator.
#[derive(Default)]
struct NitscheCache {
    layer: OnceLock<Result<Arc<Layer>, SolveError>>,
    couplings: Mutex<HashMap<Rule, Arc<Couplings>>>,
    operator: Mutex<Option<Arc<Operator>>>,
}

/// The Nitsche state kept with `disc`, made empty on first use.
fn cache(disc: &Discretization) -> Arc<NitscheCache> {
    disc.kept.get_or_init(NitscheCache::default)
}

/// K factorised with the layer's dofs last: L_BB, the trailing block, with L_BB L_BBᵀ the
/// Schur complement of K on the layer.
struct Layer {
    /// For each free dof, its position in the layer (usize::MAX when outside it).
    position: Vec<usize>,
    l: Mat<f64>,
}

/// A linear functional of the displacement: Σ c·u over (free dof, c).
type Row = Vec<(usize, f64)>;

/// One point of the rule on one edge of Γ_C, with the rows of σ_n and u_n there.
#[derive(Clone, Debug)]
struct EdgePoint {
    /// The distinct point of [`ContactPoints`] it is.
    point: usize,
    /// w_i^e h_e of (10).
    weight: f64,
    /// The boundary cell's longest side.
    h: f64,
    /// σ_n.
    sigma: Row,
    /// u_n.
    normal: Row,
}

/// G = R K⁻¹ Rᵀ for R = [S; B] at the edge points of one rule.
struct Couplings {
    points: Vec<EdgePoint>,
    g: Mat<f64>,
    /// E K⁻¹ Rᵀ, E the u_y of Γ_C's vertices: their displacement under the point loads.
    vertex: Mat<f64>,
    /// γ₀* ([`stability_threshold`]) or why it could not be computed, when first asked.
    threshold: OnceLock<Result<f64, SolveError>>,
}

/// Everything one (rule, θ, γ₀) needs: H and the maps back to σ_n.
struct Operator {
    rule: Rule,
    params: NitscheParams,
    couplings: Arc<Couplings>,
    gamma: Vec<f64>,
    /// H = P_1 K_θ⁻¹ P_θᵀ: P_1 u = H ỹ for the scaled forces ỹ = Γ⁻¹y.
    h: Mat<f64>,
    /// V = S K⁻¹ P_θᵀ: σ = (V + G_SS ZV) ỹ.
    v: Mat<f64>,
    /// Woodbury's correction ZV, for θ ≠ 0.
    correction: Option<Correction>,
}

/// ZV = θ C^½ N⁻¹ C^½ V (module doc) kept as N's Cholesky factor L (N = L Lᵀ) and
/// W = L⁻¹ C^½ V: ZV ỹ = θ C^½ L⁻ᵀ (W ỹ) costs a product and a triangular solve with one
/// right-hand side, and the operator one triangular solve with n right-hand sides fewer than
/// forming ZV.
struct Correction {
    /// C^½, C = W Γ⁻¹.
    r: Vec<f64>,
    l: Mat<f64>,
    w: Mat<f64>,
}

impl Correction {
    /// ZV ỹ.
    fn zv(&self, theta: f64, y: &[f64]) -> Vec<f64> {
        let mut t = Mat::<f64>::zeros(y.len(), 1);
        faer::linalg::matmul::matmul(
            t.as_mut(),
            Accum::Replace,
            self.w.as_ref(),
            ColRef::from_slice(y).as_mat(),
            1.0,
            Par::Seq,
        );
        faer::linalg::triangular_solve::solve_upper_triangular_in_place(
            self.l.transpose(),
            t.as_mut(),
            Par::Seq,
        );
        (0..y.len()).map(|i| theta * self.r[i] * t[(i, 0)]).collect()
    }
}

/// The cell shape functions of the boundary cell over edge `ci` at the point s ∈ [0, 1] of
/// its top edge: (node, value, gradient). For P1 the triangle with the top edge.
fn top_shape(mesh: &Mesh, ci: usize, s: f64) -> Vec<(usize, f64, [f64; 2])> {
    let cj = mesh.ny() - 1;
    let (x0, x1, y0, y1) = mesh.cell_rect(ci, cj);
    let (a, b) = (x1 - x0, y1 - y0);
    let nodes = mesh.cell_nodes(ci, cj);
    match mesh.element {
        Element::Q1 | Element::Q2 => {
            let p = mesh.element.order();
            let ((nx, dx), (ny, dy)) = (lagrange_1d(p, 2.0 * s - 1.0), lagrange_1d(p, 1.0));
            let mut out = Vec::with_capacity(nodes.len());
            for lj in 0..=p {
                for li in 0..=p {
                    out.push((
                        nodes[lj * (p + 1) + li],
                        nx[li] * ny[lj],
                        [dx[li] * ny[lj] * 2.0 / a, nx[li] * dy[lj] * 2.0 / b],
                    ));
                }
            }
            out
        }
        // Corners in tensor order 0 = (x0,y0), 1 = (x1,y0), 2 = (x0,y1), 3 = (x1,y1); the top
        // edge 2–3 lies in (0,3,2) for a rising diagonal, (1,3,2) for a falling one.
        Element::P1 => match mesh.diagonal(ci) {
            Diagonal::Rising => vec![
                (nodes[0], 0.0, [0.0, -1.0 / b]),
                (nodes[3], s, [1.0 / a, 0.0]),
                (nodes[2], 1.0 - s, [-1.0 / a, 1.0 / b]),
            ],
            Diagonal::Falling => vec![
                (nodes[1], 0.0, [0.0, -1.0 / b]),
                (nodes[3], s, [1.0 / a, 1.0 / b]),
                (nodes[2], 1.0 - s, [-1.0 / a, 0.0]),
            ],
        },
    }
}

/// The rows of σ_n = σ_yy (the full tensor of (2) at the point, [`Stress`]) and u_n = u_y at
/// s on the top edge of cell `ci`, over free dofs.
fn rows(disc: &Discretization, material: &Material, ci: usize, s: f64) -> (Row, Row) {
    let (mut sigma, mut normal) = (Vec::new(), Vec::new());
    for (node, value, g) in top_shape(&disc.mesh, ci, s) {
        for comp in 0..2 {
            let Some(dof) = disc.dofs.free_index(2 * node + comp) else {
                continue;
            };
            // σ is linear in the gradient (u_x,x, u_x,y, u_y,x, u_y,y): the dof's coefficient
            // is the stress of its shape function's gradient.
            let mut grad = [0.0; 4];
            grad[2 * comp] = g[0];
            grad[2 * comp + 1] = g[1];
            let c = Stress::of_gradient(material, grad, None).yy;
            if c != 0.0 {
                sigma.push((dof, c));
            }
            if comp == 1 && value != 0.0 {
                normal.push((dof, value));
            }
        }
    }
    (sigma, normal)
}

/// The rule's points on every edge, with their rows.
fn edge_points(disc: &Discretization, material: &Material, points: &ContactPoints) -> Vec<EdgePoint> {
    let mut out = Vec::new();
    let cj = disc.mesh.ny() - 1;
    for (e, mine) in points.edge_points.iter().enumerate() {
        let (x0, x1, y0, y1) = disc.mesh.cell_rect(e, cj);
        for (&point, (s, w)) in mine.iter().zip(points.rule.points()) {
            let (sigma, normal) = rows(disc, material, e, s);
            out.push(EdgePoint {
                point,
                weight: w * (x1 - x0),
                h: (x1 - x0).max(y1 - y0),
                sigma,
                normal,
            });
        }
    }
    out
}

/// The layer B: the free dofs the rows of σ_n and u_n use at any rule's points on Γ_C's edges,
/// node column by node column, so that a point's rows start late in the layer when it lies
/// far along Γ_C ([`Layer::couplings`] skips the leading zeros). G = R K⁻¹ Rᵀ needs K's Schur
/// complement on no more than these: u_x of Γ_C's nodes and u_y of the nodes of the elements
/// on Γ_C (σ_yy = λ u_x,x + (λ + 2μ) u_y,y on the top edge, where u_x,x sees only the edge's
/// nodes), about three dofs per node column for Q1 and P1 and four for Q2, where every dof of
/// those elements would be four and six.
fn layer_dofs(disc: &Discretization) -> Vec<usize> {
    let mesh = &disc.mesh;
    let mut used = vec![false; disc.n_dofs()];
    for ci in 0..mesh.nx() {
        for (s, _) in Rule::ALL.iter().flat_map(|r| r.points()) {
            let (sigma, normal) = rows(disc, &disc.material, ci, s);
            for (d, _) in sigma.into_iter().chain(normal) {
                used[d] = true;
            }
        }
    }
    let nny = mesh.node_y.len();
    let below = nny.saturating_sub(mesh.element.order() + 1);
    let mut dofs = Vec::new();
    for i in 0..mesh.nnx() {
        for j in below..nny {
            for comp in 0..2 {
                if let Some(d) = disc
                    .dofs
                    .free_index(2 * mesh.node(i, j) + comp)
                    .filter(|&d| used[d])
                {
                    dofs.push(d);
                }
            }
        }
    }
    dofs
}

impl Layer {
    /// Factorise K with the layer's dofs last ([`layer_dofs`]; two subdomains on two cores
    /// from [`crate::fem::factor::SPLIT_UNKNOWNS`] unknowns, as the mesh's own factor) and keep
    /// the Schur complement's factor.
    fn build(disc: &Discretization) -> Result<Layer, SolveError> {
        let mesh = &disc.mesh;
        let dofs = layer_dofs(disc);
        let n = disc.n_dofs();
        // The dense work: L_BB, the couplings' right-hand sides (at most 3 points per edge, and
        // the vertices), G and the operator's n×n matrices.
        let (nb, points) = (dofs.len() as u64, 3 * mesh.nx() as u64);
        let need = 8 * (nb * nb + nb * (2 * points + points / 3 + 1) + 12 * points * points);
        if let Some(available) = Limits::of_process().available()
            && need > available
        {
            return Err(SolveError::TooLarge(format!(
                "Nitsche's method at this level needs about {} for its dense work on the {nb} unknowns along Γ_C, and this process has {} available: choose a coarser level",
                gib(need),
                gib(available)
            )));
        }
        let stiffness = assemble(
            mesh,
            &disc.dofs,
            Form::Elasticity(disc.material, disc.integration),
        );
        // The layer alone last: the elements' other dofs just before it cost fewer flops with
        // faer's single factor, but 9–22% more instructions in a fresh solve with the whole
        // grid as one part, whose dense S they join (BENCHMARKS.md, "Nitsche's operator and the
        // active-set systems").
        let analysis = Analysis::grid(&stiffness, mesh, &disc.dofs, &dofs).map_err(|e| fem_error(e, n))?;
        let factor = Factor::new(&analysis, stiffness).map_err(|e| fem_error(e, n))?;
        let mut position = vec![usize::MAX; n];
        for (k, &d) in dofs.iter().enumerate() {
            position[d] = k;
        }
        Ok(Layer {
            position,
            l: factor.schur_factor(),
        })
    }

    /// G = R K⁻¹ Rᵀ for the σ_n rows then the u_n rows of `points`, and E K⁻¹ Rᵀ for the
    /// u_y dofs `vertices` of Γ_C's vertices.
    fn couplings(&self, points: Vec<EdgePoint>, vertices: &[usize]) -> Couplings {
        let n = points.len();
        let nb = self.l.nrows();
        let mut x = Mat::<f64>::zeros(nb, 2 * n + vertices.len());
        for (q, pt) in points.iter().enumerate() {
            for &(d, c) in &pt.sigma {
                x[(self.position[d], q)] += c;
            }
            for &(d, c) in &pt.normal {
                x[(self.position[d], n + q)] += c;
            }
        }
        for (k, &d) in vertices.iter().enumerate() {
            x[(self.position[d], 2 * n + k)] = 1.0;
        }
        let par = crate::fem::dense_parallelism(nb);
        // L⁻¹ keeps a column's leading zeros: solve each block of columns with the trailing
        // part of L below its first non-zero row (about a third of the full solve's work).
        let m = x.ncols();
        let first: Vec<usize> = (0..m)
            .map(|j| (0..nb).find(|&i| x[(i, j)] != 0.0).unwrap_or(nb))
            .collect();
        let mut j0 = 0;
        while j0 < m {
            let width = SOLVE_BLOCK.min(m - j0);
            let k = first[j0..j0 + width].iter().copied().min().unwrap_or(nb);
            faer::linalg::triangular_solve::solve_lower_triangular_in_place(
                self.l.as_ref().submatrix(k, k, nb - k, nb - k),
                x.as_mut().submatrix_mut(k, j0, nb - k, width),
                par,
            );
            j0 += width;
        }
        let (rows, ends) = x.as_ref().split_at_col(2 * n);
        let mut g = Mat::<f64>::zeros(2 * n, 2 * n);
        faer::linalg::matmul::matmul(g.as_mut(), Accum::Replace, rows.transpose(), rows, 1.0, par);
        let mut vertex = Mat::<f64>::zeros(vertices.len(), 2 * n);
        faer::linalg::matmul::matmul(vertex.as_mut(), Accum::Replace, ends.transpose(), rows, 1.0, par);
        Couplings {
            points,
            g,
            vertex,
            threshold: OnceLock::new(),
        }
    }
}

impl Couplings {
    fn n(&self) -> usize {
        self.points.len()
    }
    /// The blocks of G: (σ, σ), (σ, u_n), (u_n, σ), (u_n, u_n).
    fn ss(&self, i: usize, j: usize) -> f64 {
        self.g[(i, j)]
    }
    fn sb(&self, i: usize, j: usize) -> f64 {
        self.g[(i, self.n() + j)]
    }
    fn bs(&self, i: usize, j: usize) -> f64 {
        self.g[(self.n() + i, j)]
    }
    fn bb(&self, i: usize, j: usize) -> f64 {
        self.g[(self.n() + i, self.n() + j)]
    }
    /// C^½ G_SS C^½ with C = diag(c).
    fn scaled_ss(&self, c: &[f64]) -> Mat<f64> {
        let r: Vec<f64> = c.iter().map(|v| v.sqrt()).collect();
        Mat::<f64>::from_fn(self.n(), self.n(), |i, j| r[i] * self.ss(i, j) * r[j])
    }
}

/// The layer of `disc`, built on first use.
fn layer(disc: &Discretization) -> Result<Arc<Layer>, SolveError> {
    cache(disc)
        .layer
        .get_or_init(|| Layer::build(disc).map(Arc::new))
        .clone()
}

/// The couplings of `rule` on `disc`, computed once per rule.
fn couplings(disc: &Discretization, points: &ContactPoints) -> Result<Arc<Couplings>, SolveError> {
    let layer = layer(disc)?;
    let cache = cache(disc);
    let mut map = cache.couplings.lock().unwrap_or_else(|e| e.into_inner());
    Ok(map
        .entry(points.rule)
        .or_insert_with(|| {
            let vertices: Vec<usize> = disc
                .contact_dofs
                .iter()
                .step_by(disc.mesh.element.order())
                .copied()
                .collect();
            Arc::new(layer.couplings(edge_points(disc, &disc.material, points), &vertices))
        })
        .clone())
}

/// γ₀* of θ = 1 for `rule` on `disc`: K − (1/γ)SᵀWS is positive definite exactly for
/// γ₀ > γ₀* = λ_max(C^½ G_SS C^½), C = diag(w_q h_q / E). θ needs γ₀ > ((1 + θ)²/4)·γ₀*
/// (module doc). Computed once per rule (a dense symmetric eigenproblem of the edge points'
/// size), then kept.
pub fn stability_threshold(disc: &Discretization, rule: Rule) -> Result<f64, SolveError> {
    let points = disc.contact_points(rule);
    let cp = couplings(disc, &points)?;
    cp.threshold
        .get_or_init(|| {
            let young = disc.material.young;
            let c: Vec<f64> = cp.points.iter().map(|q| q.weight * q.h / young).collect();
            let eig = cp
                .scaled_ss(&c)
                .self_adjoint_eigenvalues(Side::Lower)
                .map_err(|e| SolveError::Eigen(format!("{e:?}")))?;
            Ok(eig.last().copied().unwrap_or(0.0))
        })
        .clone()
}

/// The γ₀ a solve with `gamma0` uses for `rule` on `disc`: the given one, or for `auto`
/// [`AUTO_GAMMA0_FACTOR`]·γ₀* ([`stability_threshold`]), raised to [`GAMMA0_RANGE`]'s lower
/// end and refused above its upper end (cells so thin that γ₀* leaves double precision).
pub fn gamma0(disc: &Discretization, rule: Rule, gamma0: Gamma0) -> Result<f64, SolveError> {
    let Gamma0::Given(given) = gamma0 else {
        let (lo, hi) = GAMMA0_RANGE;
        let chosen = (AUTO_GAMMA0_FACTOR * stability_threshold(disc, rule)?).max(lo);
        if chosen.is_nan() || chosen > hi {
            return Err(SolveError::Input {
                what: "Nitsche's γ₀",
                message: format!(
                    "`auto` would choose {} (10·γ₀*), above {} where γ's products leave double precision: the cells along Γ_C are too thin for Nitsche's method",
                    num(chosen),
                    num(hi)
                ),
            });
        }
        return Ok(chosen);
    };
    Ok(given)
}

/// Build what a solve with θ and γ₀ on `rule` needs on `disc`, each part kept with it: the
/// layer's factor, the rule's couplings, γ₀* for `auto`, and the operator. Seconds at level 7
/// (BENCHMARKS.md, "The study and Nitsche's method beside the lab's worker"), so the lab does
/// it on a thread of its own while the worker keeps answering. What fails is met again by the solve, which reports it
/// (the layer's and γ₀*'s failures are kept, so that [`prepared`] holds after them too).
pub fn prepare(disc: &Discretization, rule: Rule, theta: i8, gamma0: Gamma0) {
    if let Ok(gamma0) = self::gamma0(disc, rule, gamma0) {
        let params = NitscheParams {
            theta: f64::from(theta),
            gamma0,
        };
        if check_params(&params).is_ok() {
            // A refused (θ, γ₀) is the solve's to report.
            let _ = Operator::of(disc, &disc.contact_points(rule), params);
        }
    }
}

/// Whether [`prepare`] on `disc` would factorise K again (its layer is not built yet).
pub fn factorises(disc: &Discretization) -> bool {
    cache(disc).layer.get().is_none()
}

/// Whether a solve on `rule` with `gamma0` finds the long parts of [`prepare`] built (or failed)
/// on `disc`: the layer's factor, the rule's couplings and, for `auto`, γ₀*. The operator is
/// left out: dense work on the points that θ and γ₀ change.
pub fn prepared(disc: &Discretization, rule: Rule, gamma0: Gamma0) -> bool {
    let cache = cache(disc);
    match cache.layer.get() {
        None => false,
        Some(Err(_)) => true,
        Some(Ok(_)) => {
            let couplings = cache.couplings.lock().unwrap_or_else(|e| e.into_inner());
            couplings
                .get(&rule)
                .is_some_and(|cp| gamma0 != Gamma0::Auto || cp.threshold.get().is_some())
        }
    }
}

/// θ and γ₀ checked: θ ∈ [−1, 1], γ₀ within [`GAMMA0_RANGE`].
pub fn check_params(nitsche: &NitscheParams) -> Result<(), SolveError> {
    if !(nitsche.theta.is_finite() && (-1.0..=1.0).contains(&nitsche.theta)) {
        return Err(SolveError::Input {
            what: "Nitsche's θ",
            message: format!(
                "{} is outside [−1, 1] (1 symmetric, 0 incomplete, −1 skew-symmetric)",
                nitsche.theta
            ),
        });
    }
    let (lo, hi) = GAMMA0_RANGE;
    if !(nitsche.gamma0.is_finite() && (lo..=hi).contains(&nitsche.gamma0)) {
        return Err(SolveError::Input {
            what: "Nitsche's γ₀",
            message: format!("{} is outside [{lo:e}, {hi:e}] (γ = γ₀·E/h)", nitsche.gamma0),
        });
    }
    Ok(())
}

impl Operator {
    /// H, V and Woodbury's correction for θ, γ₀ (module doc): dense work on the points only.
    fn new(rule: Rule, cp: Arc<Couplings>, params: NitscheParams, young: f64) -> Result<Self, SolveError> {
        let n = cp.n();
        let theta = params.theta;
        let gamma: Vec<f64> = cp.points.iter().map(|q| params.gamma0 * young / q.h).collect();
        // c = W Γ⁻¹, D = θ c.
        let c: Vec<f64> = cp.points.iter().zip(&gamma).map(|(q, g)| q.weight / g).collect();
        // P_1 K⁻¹ P_θᵀ, U = P_1 K⁻¹ Sᵀ and V = S K⁻¹ P_θᵀ.
        let mut h = Mat::<f64>::from_fn(n, n, |i, j| {
            theta * cp.ss(i, j) - cp.sb(i, j) * gamma[j] - gamma[i] * theta * cp.bs(i, j)
                + gamma[i] * cp.bb(i, j) * gamma[j]
        });
        let v = Mat::<f64>::from_fn(n, n, |i, j| theta * cp.ss(i, j) - cp.sb(i, j) * gamma[j]);
        // Well-posedness: on every active set the symmetric part of the Jacobian is at least
        // K − κ (1/γ) SᵀWS with κ = (1 + θ)²/4 (Young's inequality on (1 + θ) σ_n v_n), so it
        // is positive definite for γ₀ > κ γ₀*; θ = −1 needs nothing.
        let kappa = (1.0 + theta).powi(2) / 4.0;
        let scaled = cp.scaled_ss(&c);
        let shifted = |factor: f64| {
            Mat::<f64>::from_fn(n, n, |i, j| f64::from(u8::from(i == j)) - factor * scaled[(i, j)])
        };
        // λ_max(C_γ^½ G_SS C_γ^½) = γ₀*/γ₀: computed only to say what γ₀ would do.
        let refused = || {
            let star = scaled
                .self_adjoint_eigenvalues(Side::Lower)
                .ok()
                .and_then(|e| e.last().copied())
                .map_or(String::new(), |l| {
                    format!(" (here γ₀* = {:.3})", l * params.gamma0)
                });
            SolveError::Input {
                what: "Nitsche's γ₀",
                message: format!(
                    "{} is too small for θ = {theta}: the method is stable for γ₀ > ((1 + θ)²/4)·γ₀*{star}, where K − ((1 + θ)²/4)(1/γ)∫σ_n σ_n stays positive definite (Chouly and Hild's condition); choose a larger γ₀ or θ = −1",
                    num(params.gamma0)
                ),
            }
        };
        if kappa > 0.0 && kappa != theta && shifted(kappa).llt(Side::Lower).is_err() {
            return Err(refused());
        }
        let mut correction = None;
        if theta != 0.0 {
            // Z = (I − D G_SS)⁻¹ D = θ C^½ N⁻¹ C^½ with N = I − θ C^½ G_SS C^½ = L Lᵀ symmetric,
            // positive definite when the check above passed (θ ≤ κ). With W = L⁻¹ C^½ V,
            // U Z V = θ (L⁻¹ C^½ Uᵀ)ᵀ W.
            let r: Vec<f64> = c.iter().map(|v| v.sqrt()).collect();
            let l = shifted(theta)
                .llt(Side::Lower)
                .map_err(|_| refused())?
                .L()
                .to_owned();
            drop(scaled);
            let par = crate::fem::dense_parallelism(n);
            let lower = |mut m: Mat<f64>| {
                faer::linalg::triangular_solve::solve_lower_triangular_in_place(l.as_ref(), m.as_mut(), par);
                m
            };
            let w = lower(Mat::<f64>::from_fn(n, n, |i, j| r[i] * v[(i, j)]));
            if theta == 1.0 {
                // Uᵀ = V (G is symmetric), so U Z V = WᵀW: symmetric, its lower half alone.
                let mut wtw = Mat::<f64>::zeros(n, n);
                triangular::matmul(
                    wtw.as_mut(),
                    BlockStructure::TriangularLower,
                    Accum::Replace,
                    w.transpose(),
                    BlockStructure::Rectangular,
                    w.as_ref(),
                    BlockStructure::Rectangular,
                    1.0,
                    par,
                );
                for j in 0..n {
                    h[(j, j)] += wtw[(j, j)];
                    for i in j + 1..n {
                        h[(i, j)] += wtw[(i, j)];
                        h[(j, i)] += wtw[(i, j)];
                    }
                }
            } else {
                // C^½ Uᵀ, U = P_1 K⁻¹ Sᵀ = G_SS − Γ G_BS.
                let x = lower(Mat::<f64>::from_fn(n, n, |i, j| {
                    r[i] * (cp.ss(j, i) - gamma[j] * cp.bs(j, i))
                }));
                faer::linalg::matmul::matmul(h.as_mut(), Accum::Add, x.transpose(), w.as_ref(), theta, par);
            }
            correction = Some(Correction { r, l, w });
        }
        Ok(Operator {
            rule,
            params,
            couplings: cp,
            gamma,
            h,
            v,
            correction,
        })
    }

    /// The operator for (rule, θ, γ₀) on `disc`, reusing the last one when it matches.
    fn of(
        disc: &Discretization,
        points: &ContactPoints,
        params: NitscheParams,
    ) -> Result<Arc<Self>, SolveError> {
        let cp = couplings(disc, points)?;
        let cache = cache(disc);
        let mut last = cache.operator.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(op) = last.as_ref()
            && op.rule == points.rule
            && op.params == params
            && Arc::ptr_eq(&op.couplings, &cp)
        {
            return Ok(op.clone());
        }
        let op = Arc::new(Operator::new(points.rule, cp, params, disc.material.young)?);
        *last = Some(op.clone());
        Ok(op)
    }

    /// u_n at the edge points and u_y at Γ_C's vertices for the scaled forces ỹ, and the
    /// nodal load f of K u = f.
    fn fields(&self, y: &[f64], n_dofs: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let cp = &self.couplings;
        let n = cp.n();
        let theta = self.params.theta;
        let (g, col) = (cp.g.as_ref(), ColRef::from_slice);
        let (ss, bs, bb) = (
            g.submatrix(0, 0, n, n),
            g.submatrix(n, 0, n, n),
            g.submatrix(n, n, n, n),
        );
        // σ = (V + G_SS ZV) ỹ.
        let zvy = self.correction.as_ref().map(|c| c.zv(theta, y));
        let mut sigma = &self.v * col(y);
        if let Some(zvy) = &zvy {
            sigma += ss * col(zvy);
        }
        // K u = Sᵀ a + Bᵀ b with a = Dσ + θỹ, b = −Γỹ.
        let a: Vec<f64> = (0..n)
            .map(|q| theta * (cp.points[q].weight / self.gamma[q] * sigma[q] + y[q]))
            .collect();
        let b: Vec<f64> = (0..n).map(|q| -self.gamma[q] * y[q]).collect();
        let normal = bs * col(&a) + bb * col(&b);
        let (vertices, e) = (cp.vertex.nrows(), cp.vertex.as_ref());
        let vertex_uy = e.submatrix(0, 0, vertices, n) * col(&a) + e.submatrix(0, n, vertices, n) * col(&b);
        let normal: Vec<f64> = normal.iter().copied().collect();
        let vertex_uy: Vec<f64> = vertex_uy.iter().copied().collect();
        let mut f = vec![0.0; n_dofs];
        for (q, pt) in cp.points.iter().enumerate() {
            for &(d, c) in &pt.sigma {
                f[d] += c * a[q];
            }
            for &(d, c) in &pt.normal {
                f[d] += c * b[q];
            }
        }
        (normal, vertex_uy, f)
    }
}

/// ỹ_A from (W_A⁻¹Γ_A + H_AA) ỹ_A = d_A, zero off A (None when the system is singular). For
/// θ = 1 (`symmetric`) H = P_1 K_1⁻¹ P_1ᵀ, and the matrix is positive definite where the method
/// is stable (module doc): Cholesky, half of LU's work, with LU where Cholesky fails.
fn active_forces(h: &Mat<f64>, c: &[f64], d: &[f64], a: &[usize], symmetric: bool) -> Option<Vec<f64>> {
    let mut y = vec![0.0; h.nrows()];
    if a.is_empty() {
        return Some(y);
    }
    let m = active_block(h, a, |q| 1.0 / c[q]);
    let rhs = Mat::<f64>::from_fn(a.len(), 1, |i, _| d[a[i]]);
    let sol = symmetric
        .then(|| m.llt(Side::Lower).ok())
        .flatten()
        .map_or_else(|| m.partial_piv_lu().solve(&rhs), |llt| llt.solve(&rhs));
    for (i, &q) in a.iter().enumerate() {
        y[q] = sol[(i, 0)];
    }
    y.iter().all(|v| v.is_finite()).then_some(y)
}

/// v = d − H ỹ for ỹ supported on `support`.
fn gap_function(h: &Mat<f64>, d: &[f64], y: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = d.len();
    let mut hy = vec![0.0; n];
    for j in (0..n).filter(|&j| y[j] != 0.0) {
        let col = h.col(j);
        for (i, o) in hy.iter_mut().enumerate() {
            *o += col[i] * y[j];
        }
    }
    ((0..n).map(|q| d[q] - hy[q]).collect(), hy)
}

/// The semismooth Newton on the scaled forces ỹ (module doc): full steps; when an active set
/// repeats, the step is halved until the residual ‖c v⁺ − ỹ‖ decreases.
fn newton(
    op: &Operator,
    c: &[f64],
    d: &[f64],
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<(Vec<f64>, Vec<f64>, NewtonResult), SolveError> {
    let n = d.len();
    let gamma = &op.gamma;
    // The forces y = Γỹ are the state kept between solves.
    let mut y: Vec<f64> = initial
        .filter(|y| y.len() == n && y.iter().all(|v| v.is_finite()))
        .map_or_else(
            || vec![0.0; n],
            |y0| y0.iter().zip(gamma).map(|(a, g)| a / g).collect(),
        );
    let mismatch = |y: &[f64]| -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let (v, hy) = gap_function(&op.h, d, y);
        let r = (0..n).map(|q| gamma[q] * (c[q] * v[q].max(0.0) - y[q])).collect();
        (v, hy, r)
    };
    let norm = |v: &[f64]| dot(v, v).sqrt();
    let mut progress = Progress::new(opts, on_iteration);
    let mut step = 1.0;
    for it in 0.. {
        let (v, hy, r) = mismatch(&y);
        // In force units: the contact forces w p against Γỹ, and the round-off floor in v.
        let force: Vec<f64> = (0..n).map(|q| gamma[q] * c[q] * v[q].max(0.0)).collect();
        let scaled: Vec<f64> = (0..n).map(|q| gamma[q] * y[q]).collect();
        let noise = round_off(d, &hy);
        let floor: Vec<f64> = (0..n).map(|q| gamma[q] * c[q] * noise[q]).collect();
        let m = progress.measure(
            it,
            step,
            &Iterate {
                gap: &v,
                noise: &noise,
                implied: &force,
                assumed: &scaled,
                mismatch: &r,
                floor: &floor,
            },
        )?;
        let done = m.settled && m.accurate && m.residual.is_finite();
        let a: Vec<usize> = (0..n).filter(|&q| m.active[q]).collect();
        let stop = done || it == opts.max_iterations || !m.residual.is_finite();
        let target = if stop {
            None
        } else {
            active_forces(&op.h, c, d, &a, op.params.theta == 1.0)
        };
        let Some(target) = target else {
            let diagnosis = (!done).then(|| {
                if stop {
                    stalled(it, m.residual)
                } else {
                    format!(
                        "the Newton system of the active set is singular (θ = {}, γ₀ = {}): choose a larger γ₀",
                        op.params.theta, op.params.gamma0
                    )
                }
            });
            let result = progress.finish(scaled, Vec::new(), it, done, m.residual, diagnosis);
            return Ok((y, v, result));
        };
        step = 1.0;
        let delta: Vec<f64> = (0..n).map(|q| target[q] - y[q]).collect();
        if progress.repeated(&m.active) {
            // A repeated active set: halve the step until the residual decreases.
            let r0 = norm(&r);
            step = 0.5;
            while step > 1e-12 {
                let trial: Vec<f64> = (0..n).map(|q| y[q] + step * delta[q]).collect();
                if norm(&mismatch(&trial).2) < r0 {
                    break;
                }
                step *= 0.5;
            }
        }
        for q in 0..n {
            y[q] += step * delta[q];
        }
        progress.advance(m.active);
    }
    unreachable!("the loop returns")
}

/// [`solve`] once from rest: no earlier forces, the default Newton options, no progress
/// report (a one-off solve, as in the tests and `examples/nitsche_convergence.rs`).
pub fn solve_once(
    disc: &Discretization,
    params: &ContactParams,
    nitsche: NitscheParams,
) -> Result<Solution, SolveError> {
    solve(
        disc,
        params,
        nitsche,
        None,
        &NewtonOptions::default(),
        &mut |_| ControlFlow::Continue(()),
    )
}

/// Solve the contact problem on `disc` by Nitsche's method (module doc), from the forces of an
/// earlier Nitsche solve with the same rule, or forces at the rule's distinct points
/// (`initial`, ignored if it fits neither).
/// `params.epsilon` is not used. The result's `newton.forces` (w p) and `newton.violation`
/// (u_n − g) are at the rule's points on each edge (a point two edges share appears twice);
/// `p`, `pbar`, `load` and `vertex_uy` are as for the penalty, and `nodal_forces` gives u.
pub fn solve(
    disc: &Discretization,
    params: &ContactParams,
    nitsche: NitscheParams,
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<Solution, SolveError> {
    let t = Instant::now();
    check_params(&nitsche)?;
    let points = disc.contact_points(params.rule);
    crate::check::depth(params.obstacle.depth(), disc.height()).map_err(|e| SolveError::Input {
        what: "the indentation depth",
        message: e.to_string(),
    })?;
    let op = Operator::of(disc, &points, nitsche)?;
    let prepared_ms = t.elapsed().as_secs_f64() * 1e3;
    let cp = &op.couplings;
    let n = cp.n();
    let c: Vec<f64> = (0..n).map(|q| cp.points[q].weight / op.gamma[q]).collect();
    let g: Vec<f64> = cp
        .points
        .iter()
        .map(|q| params.obstacle.gap(points.points[q.point].x))
        .collect();
    // d = −Γg (−∞ where the obstacle does not reach).
    let d: Vec<f64> = (0..n).map(|q| -op.gamma[q] * g[q]).collect();
    // Forces at the distinct points (another method's, or carried from another mesh) are
    // shared between the edges that have a point in proportion to their weights.
    let start: Option<Vec<f64>> = initial.and_then(|y| {
        if y.len() == n {
            Some(y.to_vec())
        } else if y.len() == points.len() {
            Some(
                cp.points
                    .iter()
                    .map(|q| q.weight * y[q.point] / points.points[q.point].weight)
                    .collect(),
            )
        } else {
            None
        }
    });
    let (y, v, mut newton) = newton(&op, &c, &d, start.as_deref(), opts, on_iteration)?;
    let (normal, vertex_uy, forces) = op.fields(&y, disc.n_dofs());
    newton.violation = (0..n).map(|q| normal[q] - g[q]).collect();
    // p at the distinct points: the weighted mean of the edge points' p = v⁺.
    let mut p = vec![0.0; points.len()];
    for (q, pt) in cp.points.iter().enumerate() {
        p[pt.point] += pt.weight * v[q].max(0.0);
    }
    for (pq, pt) in p.iter_mut().zip(&points.points) {
        *pq /= pt.weight;
    }
    let pbar = smoothed_pressure(&points, &p);
    let load = load(&points, &p);
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    if newton.converged
        && !(load.is_finite() && finite(&p) && finite(&pbar) && finite(&vertex_uy) && finite(&forces))
    {
        newton.converged = false;
        newton.diagnosis = Some(
            "a contact pressure or displacement is not finite: the problem's scaling overflows double precision".into(),
        );
    }
    let mut warnings: Vec<_> = disc.stiffness_warning().into_iter().collect();
    warnings.extend(warning::of_contact(&params.obstacle, &points, &p, disc.mesh.h()));
    let ms = t.elapsed().as_secs_f64() * 1e3;
    let timing = Timing {
        // What this solve built of the layer's factor, the rule's couplings and the (θ, γ₀)
        // operator; the rest is Newton and the fields.
        factorization: prepared_ms,
        newton: ms - prepared_ms,
        total: ms,
        ..Timing::default()
    };
    Ok(Solution {
        params: params.clone(),
        points,
        newton,
        outer_iterations: None,
        p,
        pbar,
        vertex_uy,
        load,
        timing,
        warnings,
        nodal_forces: Some(forces),
        gamma0: Some(nitsche.gamma0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::basis::evaluate;
    use crate::scenario::Scenario;

    /// The layer is u_x of Γ_C's nodes and u_y of the nodes of the elements on Γ_C (two node
    /// rows of the boundary cells for Q1, three for Q2; for P1 Γ_C's nodes and each top
    /// triangle's third vertex), the free ones, counted here from the dof map: distinct free
    /// dofs of the boundary cells.
    #[test]
    fn the_layer_is_the_dofs_the_rows_use() {
        for element in Element::ALL {
            let disc = Discretization::of(&Scenario::paper(), 2, element).unwrap();
            let mesh = &disc.mesh;
            let nny = mesh.node_y.len();
            let free = |i, j, comp| disc.dofs.free_index(2 * mesh.node(i, j) + comp).is_some();
            let rows = match element {
                Element::Q2 => 3,
                Element::Q1 | Element::P1 => 2,
            };
            // P1's third vertices: below the left end of a rising diagonal's cell, below the
            // right end of a falling one's.
            let third: Vec<usize> = (0..mesh.nx())
                .map(|ci| match mesh.diagonal(ci) {
                    Diagonal::Rising => ci,
                    Diagonal::Falling => ci + 1,
                })
                .collect();
            let below = |i: usize, j: usize| element != Element::P1 || j == nny - 1 || third.contains(&i);
            let expected: usize = (0..mesh.nnx())
                .map(|i| {
                    usize::from(free(i, nny - 1, 0))
                        + (nny - rows..nny)
                            .filter(|&j| below(i, j) && free(i, j, 1))
                            .count()
                })
                .sum();
            let in_cells: std::collections::BTreeSet<usize> = (0..mesh.nnx())
                .flat_map(|i| (nny - rows..nny).flat_map(move |j| [(i, j, 0), (i, j, 1)]))
                .filter_map(|(i, j, comp)| disc.dofs.free_index(2 * mesh.node(i, j) + comp))
                .collect();
            let layer = layer_dofs(&disc);
            assert_eq!(layer.len(), expected, "{element:?}");
            let distinct: std::collections::BTreeSet<usize> = layer.iter().copied().collect();
            assert!(
                distinct.len() == layer.len() && distinct.is_subset(&in_cells),
                "{element:?}: distinct dofs of the boundary cells"
            );
            assert!(
                layer.len() < 2 * rows * mesh.nnx() - 1,
                "{element:?}: fewer than the cells' dofs"
            );
        }
    }

    /// K's Schur complement on the layer is the same from two subdomains (the split the layer
    /// uses from 50,000 unknowns), from faer's one factor, and from the layer's own factor (the
    /// whole grid as one part, below 50,000), to round-off.
    #[test]
    fn the_layers_schur_complement_is_the_same_split_or_whole() {
        for element in [Element::Q1, Element::Q2] {
            let disc = Discretization::of(&Scenario::paper(), 3, element).unwrap();
            let stiffness = assemble(
                &disc.mesh,
                &disc.dofs,
                Form::Elasticity(disc.material, disc.integration),
            );
            let dofs = layer_dofs(&disc);
            let schur = |analysis: Analysis| {
                let l = Factor::new(&analysis, stiffness.clone()).unwrap().schur_factor();
                l.as_ref() * l.transpose()
            };
            let split = Analysis::split(&stiffness, &disc.mesh, &disc.dofs, &dofs).unwrap();
            assert!(matches!(split, Analysis::Split(_)), "{element:?}");
            let whole = Analysis::whole(&stiffness, &disc.mesh, &disc.dofs, &dofs).unwrap();
            let l = Layer::build(&disc).unwrap().l;
            let (a, b, c) = (schur(split), schur(whole), l.as_ref() * l.transpose());
            let scale = b.norm_max();
            assert!((&a - &b).norm_max() <= 1e-11 * scale, "{element:?}");
            assert!((&c - &b).norm_max() <= 1e-11 * scale, "{element:?}");
        }
    }

    /// Where Cholesky fails on a symmetric active-set matrix (indefinite: [[0, 2], [2, 0]]),
    /// LU solves it: (2ỹ₂, 2ỹ₁) = (2, 4).
    #[test]
    fn active_forces_fall_back_to_lu_where_cholesky_fails() {
        let h = Mat::<f64>::from_fn(2, 2, |i, j| if i == j { -1.0 } else { 2.0 });
        let y = active_forces(&h, &[1.0, 1.0], &[2.0, 4.0], &[0, 1], true).unwrap();
        assert_eq!(y, [2.0, 1.0]);
    }

    /// The boundary cell's shape functions at the top edge agree with the field evaluation of
    /// `basis::evaluate` just below it (inside the same element), for a random field.
    #[test]
    fn top_shape_matches_the_field_evaluation() {
        for element in Element::ALL {
            let mesh = Mesh::uniform(element, (-2.0, 2.0, 4), (0.0, 1.5, 2), false);
            let u: Vec<f64> = (0..2 * mesh.n_nodes())
                .map(|k| ((k * 7919) % 101) as f64 / 50.0 - 1.0)
                .collect();
            let top = mesh.ys[mesh.ys.len() - 1];
            for ci in 0..mesh.nx() {
                for s in [0.2, 0.5, 0.7] {
                    let x = mesh.xs[ci] + s * (mesh.xs[ci + 1] - mesh.xs[ci]);
                    let (val, grad) = evaluate(&mesh, &u, x, top - 1e-12);
                    let (mut v, mut g) = ([0.0; 2], [0.0; 4]);
                    for (node, n, d) in top_shape(&mesh, ci, s) {
                        for c in 0..2 {
                            v[c] += n * u[2 * node + c];
                            g[2 * c] += d[0] * u[2 * node + c];
                            g[2 * c + 1] += d[1] * u[2 * node + c];
                        }
                    }
                    for k in 0..2 {
                        assert!((v[k] - val[k]).abs() < 1e-9, "{element:?} value");
                    }
                    for k in 0..4 {
                        assert!(
                            (g[k] - grad[k]).abs() < 1e-9,
                            "{element:?} {ci} {s} {g:?} {grad:?}"
                        );
                    }
                }
            }
        }
    }
}
