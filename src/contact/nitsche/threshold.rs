//! Nitsche's parameters checked: θ ∈ [−1, 1], γ₀ in its range, and the stability threshold γ₀*
//! (module doc of [`super`], **Stability**) that `auto` scales.

use faer::Side;

use super::{NitscheParams, couplings};
use crate::contact::method::{AUTO_GAMMA0_FACTOR, GAMMA0_RANGE, Gamma0};
use crate::contact::{ContactPoints, Rule};
use crate::discretization::Discretization;
use crate::error::{InputFault, SolveError};

/// γ₀* of θ = 1 for `rule` on `disc`: K − (1/γ)SᵀWS is positive definite exactly for
/// γ₀ > γ₀* = λ_max(C^½ G_SS C^½), C = diag(w_q h_q / E). θ needs γ₀ > ((1 + θ)²/4)·γ₀*
/// (module doc). Computed once per rule (a dense symmetric eigenproblem of the edge points'
/// size), then kept.
pub fn stability_threshold(disc: &Discretization, rule: Rule) -> Result<f64, SolveError> {
    let points = ContactPoints::on(disc, rule);
    let cp = couplings(disc, &points)?;
    cp.threshold
        .get_or_init(|| {
            let young = disc.material.young;
            let c: Vec<f64> = cp.points.iter().map(|q| q.weight * q.h / young).collect();
            let eig = cp
                .scaled_ss(&c)
                .self_adjoint_eigenvalues(Side::Lower)
                .map_err(SolveError::Eigen)?;
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
            return Err(InputFault::AutoGamma0 { chosen, limit: hi }.into());
        }
        return Ok(chosen);
    };
    Ok(given)
}

/// θ and γ₀ checked: θ ∈ [−1, 1], γ₀ within [`GAMMA0_RANGE`].
pub fn check_params(nitsche: &NitscheParams) -> Result<(), SolveError> {
    if !(nitsche.theta.is_finite() && (-1.0..=1.0).contains(&nitsche.theta)) {
        return Err(InputFault::Theta { theta: nitsche.theta }.into());
    }
    let (lo, hi) = GAMMA0_RANGE;
    if !(nitsche.gamma0.is_finite() && (lo..=hi).contains(&nitsche.gamma0)) {
        return Err(InputFault::Gamma0 {
            gamma0: nitsche.gamma0,
            lo,
            hi,
        }
        .into());
    }
    Ok(())
}
