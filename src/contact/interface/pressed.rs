//! The upper body's top under a uniform pressure q (docs/design.md §12, "A pressure on the
//! top"): the top then free but for one pin that removes the vertical translation
//! ([`Support::Free`](crate::fem::Support::Free); the half model's symmetry line holds the
//! horizontal one and the rotation), and the load q·w balanced by the interface alone.
//!
//! The top's consistent load f_q = q ∫ φ_i on its nodes gives, alone, the displacement
//! u_q = K⁻¹ f_q with the pin held; across the interface the rows see u_q on the upper's trace
//! as a shift of the initial gap, g̃₀ = g₀ − G_u u_q, and the pin's descent δ is a rigid
//! translation, as the prescribed displacement of the top is. δ is the one unknown more, set by
//! the scalar equation P(δ) = q·w: the load carried, P, is continuous and nondecreasing in δ
//! (piecewise linear for the exact multipliers, each piece an active set), 0 while no row
//! penetrates (δ ≤ min g̃₀, every row's upper part summing to 1), and it is solved by the
//! Illinois variant of regula falsi from that bracket. The pin then carries q·w − P, 0 to the
//! tolerance.

use super::Coupling;
use super::solve::{Bodies, BodiesError, Condensed, Enforcement, InterfaceSolution, Slave};
use crate::contact::Rule;
use crate::discretization::Discretization;

/// The relative misfit |P − q·w| / (q·w) that ends the search for δ.
pub const BALANCE: f64 = 1e-12;

/// The most descents δ tried (the doublings that bracket the root and regula falsi's steps).
const MAX_STEPS: usize = 200;

/// The upper body's displacement under the top's pressure alone, the pin held.
struct TopLoad {
    /// u_q along the body's outward normal at its Γ_C nodes (the contact dofs' order).
    normal: Vec<f64>,
    /// u_q at every node in the global frame, (u_x, u_y) by node.
    global: Vec<f64>,
}

/// u_q = K⁻¹ f_q of `upper` (its mirrored mesh: the top is the mesh's bottom row) under the
/// pressure `q` on its top, f_q = q ∫_top φ_i on each top node's u_y' (y' = top − y points
/// into the body, as the pressure does).
fn top_load(upper: &Discretization, q: f64) -> Result<TopLoad, BodiesError> {
    let mesh = upper.mesh();
    let order = mesh.element.order();
    let side = super::Side {
        x: &mesh.node_x,
        order,
    };
    let measures = super::trace::Trace::new(side, "upper")?.measures();
    let dofs = upper.dofs();
    let mut f = vec![0.0; upper.n_dofs()];
    for (i, m) in measures.iter().enumerate() {
        if let Some(k) = dofs.free_index(2 * mesh.node(i, 0) + 1) {
            f[k] += q * m;
        }
    }
    upper.factor().solve_in_place(&mut f, 1);
    let normal = upper.contact_dofs().iter().map(|&k| f[k]).collect();
    let mut global = dofs.expand(&f, |_| 0.0);
    for uy in global.iter_mut().skip(1).step_by(2) {
        *uy = -*uy;
    }
    Ok(TopLoad { normal, global })
}

/// Solve the contact of `bodies` (its `displacement` unused) across the interface discretised
/// by `coupling` (`solve::couple`'s: its rows, their initial gaps `g0` and the rule of
/// a reduced-integration coupling), the upper body's top under the pressure `q` > 0 and held
/// by the pin of [`Support::Free`](crate::fem::Support::Free): the solution (its Newton
/// iterations summed over every δ tried, the upper's trace and displacement with u_q in them)
/// and the pin's descent δ. `first` is a first guess of δ's scale (the two bodies' uniform
/// compression under q, q (H_l/E'_l + H_u/E'_u + ε)). Given up as soon as `cancelled` says
/// so.
///
/// # Errors
///
/// As [`super::solve::solve_cancellable`]'s, and [`BodiesError::Unbalanced`] when no
/// δ balances the load within [`BALANCE`] in `MAX_STEPS` solves.
pub fn solve_pressed(
    bodies: &Bodies,
    (coupling, g0, rule): (&Coupling, &[f64], Option<Rule>),
    enforcement: Enforcement,
    (q, first): (f64, f64),
    cancelled: &dyn Fn() -> bool,
) -> Result<(InterfaceSolution, f64), BodiesError> {
    let top = top_load(bodies.upper, q)?;
    let upper_rows = match bodies.slave {
        Slave::Upper => &coupling.slave,
        Slave::Lower => &coupling.master,
    };
    let shifted: Vec<f64> = g0
        .iter()
        .zip(upper_rows)
        .map(|(g, row)| g - row.iter().map(|&(i, s)| s * top.normal[i]).sum::<f64>())
        .collect();
    let mesh = bodies.upper.mesh();
    let load = q * (mesh.node_x[mesh.nnx() - 1] - mesh.node_x[0]);
    // The rows, A and the multipliers' uniqueness are the same for every δ: condensed once.
    let condensed = Condensed::new(*bodies, coupling, &shifted, enforcement, rule, cancelled)?;
    let mut iterations = 0usize;
    let mut at = |delta: f64| -> Result<(f64, InterfaceSolution), BodiesError> {
        let sol = condensed.solve(delta, &shifted, cancelled)?;
        iterations += sol.iterations;
        Ok((sol.load - load, sol))
    };
    let unbalanced = |fb: f64, steps: usize| BodiesError::Unbalanced {
        load,
        carried: fb + load,
        steps,
    };
    // The bracket: nothing penetrates at δ = min g̃₀; from there the descent doubles until
    // the interface carries the load.
    let lowest = shifted.iter().copied().fold(f64::INFINITY, f64::min);
    let spread = shifted.iter().copied().fold(f64::NEG_INFINITY, f64::max) - lowest;
    let (mut a, mut fa) = (lowest, -load);
    let mut step = (first.abs() + spread).max(f64::MIN_POSITIVE);
    let mut b = lowest + step;
    let (mut fb, mut best) = at(b)?;
    let mut tried = 1;
    while fb < 0.0 {
        if tried >= MAX_STEPS || !step.is_finite() {
            return Err(unbalanced(fb, tried));
        }
        (a, fa) = (b, fb);
        step *= 2.0;
        b = lowest + step;
        (fb, best) = at(b)?;
        tried += 1;
    }
    // Illinois: regula falsi that halves the stale end's value when one end stays twice.
    while fb.abs() > BALANCE * load && (b - a).abs() > 4.0 * f64::EPSILON * b.abs().max(a.abs()) {
        if tried >= MAX_STEPS {
            return Err(unbalanced(fb, tried));
        }
        // The ratio first: fb·(b − a) underflows under a pressure of 1e-200.
        let c = b - (b - a) * (fb / (fb - fa));
        let (fc, sol) = at(c)?;
        tried += 1;
        if (fc < 0.0) != (fb < 0.0) {
            (a, fa) = (b, fb);
        } else {
            fa *= 0.5;
        }
        (b, fb, best) = (c, fc, sol);
    }
    let mut sol = best;
    sol.iterations = iterations;
    let trace = match bodies.slave {
        Slave::Upper => &mut sol.slave,
        Slave::Lower => &mut sol.master,
    };
    for (k, &n) in mesh.top_nodes().iter().enumerate() {
        trace.ux[k] += top.global[2 * n];
        trace.uy[k] += top.global[2 * n + 1];
    }
    for (u, du) in sol.bodies[1].iter_mut().zip(&top.global) {
        *u += du;
    }
    Ok((sol, b))
}
