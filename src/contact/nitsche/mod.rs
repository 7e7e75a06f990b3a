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
//! **Condensation** (so that θ, γ₀ and the depth change fast). With S
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
//! dense work (for θ = 1 one triangular solve and half a product fewer, as H = H₀ + MᵀM is
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

use crate::contact::method::Gamma0;
use crate::contact::newton::{Iteration, NewtonOptions};
use crate::contact::solution::{Solution, Timing};
use crate::contact::{ContactParams, ContactPoints, Rule, load, smoothed_pressure};
use crate::discretization::Discretization;
use crate::error::{Diagnosis, SolveError};

mod couplings;
mod layer;
mod newton;
mod operator;
mod threshold;
use couplings::Couplings;
use layer::{Layer, edge_points};
use newton::newton;
use operator::Operator;
pub use threshold::{check_params, gamma0, stability_threshold};

/// Nitsche's parameters: θ ∈ [−1, 1] (1 symmetric, 0 incomplete, −1 skew-symmetric) and
/// γ₀ > 0, the dimensionless γ = γ₀·E/h.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NitscheParams {
    /// θ ∈ [−1, 1].
    pub theta: f64,
    /// γ₀ > 0, dimensionless.
    pub gamma0: f64,
}

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
            let _ = Operator::of(disc, &ContactPoints::on(disc, rule), params);
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
    let points = ContactPoints::on(disc, params.rule);
    crate::check::depth(params.obstacle.depth(), disc.height()).map_err(|source| SolveError::Range {
        what: "the indentation depth",
        source,
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
        newton.diagnosis = Some(Diagnosis::Overflow);
    }
    let mut warnings: Vec<_> = disc.stiffness_warning().into_iter().collect();
    warnings.extend(crate::contact::warnings::of_contact(
        &params.obstacle,
        &points,
        &p,
        disc.mesh.h(),
    ));
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
        friction: None,
    })
}
