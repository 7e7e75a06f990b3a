//! The parameters of a solve that have no answer ([`super::SolveError::Input`]): each fault
//! with the values that show it and the range allowed, its message naming the parameter.

use super::{FrictionError, MethodError};
use crate::text::num;

/// A parameter of the solve outside the range where its answer means something (or where
/// double precision can represent it).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InputFault {
    /// The method or one of its parameters ([`MethodError`]).
    #[error("the method: {0}")]
    Method(#[from] MethodError),
    /// A friction parameter ([`FrictionError`]).
    #[error("friction: {0}")]
    Friction(#[from] FrictionError),
    /// Friction on a mesh whose Γ_C u_x is held (a half model, a roller wall).
    #[error(
        "friction: friction needs the full model (body.model = \"full\"): Γ_C's u_x is held here (a half model's symmetry line holds u_x = 0)"
    )]
    HeldTangential,
    /// Friction asked of Nitsche's method.
    #[error("friction: friction is imposed by penalty, exact or alm, not nitsche")]
    FrictionOfNitsche,
    /// Friction asked of a study's edge-graded rows (`--refine-edges`).
    #[error(
        "friction: a study's edge-graded rows (--refine-edges) do not take friction; study uniform levels"
    )]
    GradedFriction,
    /// Friction asked of a graded mesh.
    #[error(
        "friction: a graded mesh (refine_edges = {grading}) does not take friction yet; solve a uniform level"
    )]
    FrictionGraded {
        /// The grading asked, as written (`3`, `auto`, `3z`).
        grading: String,
    },
    /// A tangential penalty ε_t given to the exact method.
    #[error("friction: epsilon_t is the tangential penalty of penalty and alm; exact takes none")]
    TangentialPenaltyOfExact,
    /// A shift that moves the obstacle's centre out of the body.
    #[error(
        "the shift: shift = {} moves the obstacle's centre to x = {} beyond the body; allowed: the centre strictly inside ({x0}, {x1})",
        num(*shift),
        num(*centre)
    )]
    ShiftBeyond {
        /// The shift given.
        shift: f64,
        /// Where it moves the obstacle's centre.
        centre: f64,
        /// The body's left side.
        x0: f64,
        /// The body's right side.
        x1: f64,
    },
    /// A method with a penalty parameter (penalty, ALM) asked for at ε = 0.
    #[error("the penalty parameter ε: {method} needs ε > 0; ε = 0 is the exact method (`exact`)")]
    NeedsEpsilon {
        /// The method's name.
        method: &'static str,
    },
    /// Nitsche's θ outside [−1, 1].
    #[error("Nitsche's θ: {theta} is outside [−1, 1] (1 symmetric, 0 incomplete, −1 skew-symmetric)")]
    Theta {
        /// The θ given.
        theta: f64,
    },
    /// Nitsche's γ₀ outside its range.
    #[error("Nitsche's γ₀: {gamma0} is outside [{lo:e}, {hi:e}] (γ = γ₀·E/h)")]
    Gamma0 {
        /// The γ₀ given.
        gamma0: f64,
        /// The smallest γ₀ allowed.
        lo: f64,
        /// The largest γ₀ allowed.
        hi: f64,
    },
    /// `auto` would choose a γ₀ above the range: cells too thin along Γ_C.
    #[error(
        "Nitsche's γ₀: `auto` would choose {} (10·γ₀*), above {} where γ's products leave double precision: the cells along Γ_C are too thin for Nitsche's method",
        num(*chosen),
        num(*limit)
    )]
    AutoGamma0 {
        /// The γ₀ `auto` would choose (NaN when γ₀* is not a number).
        chosen: f64,
        /// The largest γ₀ allowed.
        limit: f64,
    },
    /// A γ₀ below Nitsche's stability threshold for θ.
    #[error(
        "Nitsche's γ₀: {} is too small for θ = {theta}: the method is stable for γ₀ > ((1 + θ)²/4)·γ₀*{}, where K − ((1 + θ)²/4)(1/γ)∫σ_n σ_n stays positive definite (Chouly and Hild's condition); choose a larger γ₀ or θ = −1",
        num(*gamma0),
        threshold.map_or(String::new(), |t| format!(" (here γ₀* = {t:.3})"))
    )]
    Unstable {
        /// The γ₀ given.
        gamma0: f64,
        /// Nitsche's θ.
        theta: f64,
        /// γ₀* on this mesh and rule, when its eigenvalue solve succeeded.
        threshold: Option<f64>,
    },
    /// A study whose obstacle does not reach the body.
    #[error(
        "the reference has no contact: the obstacle at depth {} does not reach the body{}",
        num(*depth),
        NO_CONTACT
    )]
    NoContact {
        /// The indentation depth (≤ 0).
        depth: f64,
    },
    /// A study's reference with norms that are zero.
    #[error(
        "the reference has no contact: its norms are zero (‖p_ref‖₀ = {}, ‖u_ref‖₁ = {}, P_ref = {}){}",
        num(*p_norm),
        num(*u_norm),
        num(*load),
        NO_CONTACT
    )]
    ZeroReference {
        /// ‖p_ref‖₀ on Γ_C.
        p_norm: f64,
        /// ‖u_ref‖₁.
        u_norm: f64,
        /// P_ref.
        load: f64,
    },
    /// A study's reference with norms that are not finite.
    #[error(
        "the reference: its norms are not finite (‖p_ref‖₀ = {}, ‖u_ref‖₁ = {}, P_ref = {}); relative errors against it are undefined",
        num(*p_norm),
        num(*u_norm),
        num(*load)
    )]
    InfiniteReference {
        /// ‖p_ref‖₀ on Γ_C.
        p_norm: f64,
        /// ‖u_ref‖₁.
        u_norm: f64,
        /// P_ref.
        load: f64,
    },
}

/// The end of the no-contact refusals' messages.
const NO_CONTACT: &str = ", so p_ref = 0 on Γ_C and the relative errors, which divide by its norms, are undefined; choose a depth > 0";
