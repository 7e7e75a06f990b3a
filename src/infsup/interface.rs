//! The discrete inf-sup constant of each multiplier space across the interface of two bodies
//! (docs/design.md §12, "The inf-sup constant across the interface"), on one level:
//!
//!   β_h² = λ_min(B A⁻¹ Bᵀ, M),
//!
//! A the H¹ Gram matrix of (7) of each body (block-diagonal over the two), B the constraint of
//! a [`Coupling`] — row k the weighted gap w_k (Σ_i S_ki u_s,i − Σ_l M_kl u_m,l), the slave's
//! trace minus the master's — and M the space's L² Gram matrix on the slave's side of the
//! overlap ([`multiplier_mass`]; for p̄, Sᵀ M₁ S as the one-body β̄_h of (21)). Only the two
//! traces enter B, so A⁻¹ is needed there alone: B A⁻¹ Bᵀ = W (S C_s Sᵀ + M C_m Mᵀ) W, C_s and
//! C_m the bodies' trace compliances of A ([`crate::infsup::TraceCompliance`]), G C Gᵀ the two-body solve's
//! own ([`delassus`]).

use faer::Mat;

use super::{generalized_eigenvalues, p1_mass, smoothing_matrix};
use crate::contact::interface::solve::{BodiesError, KERNEL, delassus};
use crate::contact::interface::{
    Coupling, InterfaceMethod, MultiplierBasis, Side, coupling, multiplier_mass,
};
use crate::contact::{ContactPoints, Rule};

/// A multiplier space across the interface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Space {
    /// Standard mortar: the slave's trace space.
    Mortar,
    /// Mortar's dual (biorthogonal) basis.
    MortarDual,
    /// One-pass node-to-segment's nodal pressures, interpolated by the slave's trace basis.
    Nts,
    /// The reduced-integration penalty's pressures at the rule's points (its Q_h).
    Point(Rule),
    /// The same pressures smoothed by (17) to the slave's vertices: p̄.
    Smoothed(Rule),
}

impl Space {
    /// Mortar, mortar-dual and NTS, then the point space and p̄ of each rule of `rules`.
    pub fn with_rules(rules: &[Rule]) -> Vec<Space> {
        let mut spaces = vec![Space::Mortar, Space::MortarDual, Space::Nts];
        for &rule in rules {
            spaces.extend([Space::Point(rule), Space::Smoothed(rule)]);
        }
        spaces
    }

    /// Its name in the outputs: the discretisation's ([`InterfaceMethod::name`]), `-pbar`
    /// added for the smoothed pressure (e.g. `rip-gauss1-pbar`).
    pub fn name(self) -> &'static str {
        match self {
            Space::Smoothed(Rule::Gauss1) => "rip-gauss1-pbar",
            Space::Smoothed(Rule::Gauss2) => "rip-gauss2-pbar",
            Space::Smoothed(Rule::Trapezoid) => "rip-trapezoid-pbar",
            Space::Smoothed(Rule::Simpson) => "rip-simpson-pbar",
            space => space.method().name(),
        }
    }

    /// The discretisation whose constraint it carries.
    pub fn method(self) -> InterfaceMethod {
        match self {
            Space::Mortar => InterfaceMethod::Mortar,
            Space::MortarDual => InterfaceMethod::MortarDual,
            Space::Nts => InterfaceMethod::Nts,
            Space::Point(rule) | Space::Smoothed(rule) => InterfaceMethod::Rip(rule),
        }
    }

    /// The rule of the reduced-integration penalty's spaces.
    pub fn rule(self) -> Option<Rule> {
        match self {
            Space::Point(rule) | Space::Smoothed(rule) => Some(rule),
            _ => None,
        }
    }
}

/// The two traces across the interface and their bodies' trace compliances of A.
#[derive(Clone, Copy)]
pub struct Traces<'a> {
    /// The slave's trace.
    pub slave: Side<'a>,
    /// The master's trace.
    pub master: Side<'a>,
    /// C_s on the slave's trace nodes, ascending x.
    pub slave_compliance: &'a Mat<f64>,
    /// C_m on the master's.
    pub master_compliance: &'a Mat<f64>,
}

/// The estimate of one space on one pair of traces.
#[derive(Clone, Debug, PartialEq)]
pub struct InterfaceInfSup {
    /// β_h (0 where the space has a kernel).
    pub beta: f64,
    /// The number of multipliers (the coupling's rows).
    pub multipliers: usize,
    /// Why β_h = 0 when the multipliers are not unique.
    pub kernel: Option<String>,
}

/// B A⁻¹ Bᵀ = W (S C_s Sᵀ + M C_m Mᵀ) W of `coupling` on `traces`.
pub fn schur(coupling: &Coupling, traces: &Traces) -> Mat<f64> {
    let g = delassus(&coupling.slave, traces.slave_compliance)
        + delassus(&coupling.master, traces.master_compliance);
    let w = &coupling.weight;
    Mat::from_fn(g.nrows(), g.ncols(), |j, k| w[j] * g[(j, k)] * w[k])
}

/// The p̄ space's Gram matrix Sᵀ M₁ S on the coupling's rows: S the smoothing (17) of the
/// rule's points on the slave to its vertices, a point without a row (off the master)
/// carrying p = 0, as the two-body solve's p̄ does ([`crate::contact::interface::smoothed_pressure`]).
fn smoothed_mass(rule: Rule, slave: Side, coupling: &Coupling) -> Mat<f64> {
    let cp = ContactPoints::new(rule, slave.x, slave.order);
    let s = smoothing_matrix(&cp);
    let columns: Vec<usize> = coupling
        .x
        .iter()
        .filter_map(|&x| cp.points.iter().position(|q| q.x == x))
        .collect();
    let s = Mat::<f64>::from_fn(s.nrows(), columns.len(), |i, k| s[(i, columns[k])]);
    s.transpose() * p1_mass(&cp.vertex_x) * &s
}

/// β_h of `space` across `traces`: 0 with the reason where its multipliers are not unique —
/// more of them than the two traces' nodes, or (found by the eigenvalues) constraints that are
/// not independent. p̄'s is measured on the range of Sᵀ M₁ S, as the one-body β̄_h
/// ([`super::min_generalized_eigenvalue`]): a kernel only where a p̄ ≠ 0 is not constrained.
///
/// # Errors
///
/// Traces that cannot be coupled ([`coupling`]'s), an eigendecomposition that did not converge.
pub fn estimate(space: Space, traces: &Traces) -> Result<InterfaceInfSup, BodiesError> {
    let c = coupling(space.method(), traces.slave, traces.master)?;
    let k = c.x.len();
    let nodes = traces.slave.x.len() + traces.master.x.len();
    let answer = |beta, kernel| InterfaceInfSup {
        beta,
        multipliers: k,
        kernel,
    };
    if k > nodes && !matches!(space, Space::Smoothed(_)) {
        let why = format!(
            "{k} multipliers but the two traces only {nodes} normal dofs: a kernel of dimension {}",
            k - nodes
        );
        return Ok(answer(0.0, Some(why)));
    }
    let mass = match space {
        Space::Mortar | Space::Nts => {
            multiplier_mass(MultiplierBasis::Trace, traces.slave, traces.master, &c)?
        }
        Space::MortarDual => multiplier_mass(MultiplierBasis::Dual, traces.slave, traces.master, &c)?,
        Space::Point(rule) => multiplier_mass(MultiplierBasis::Rule(rule), traces.slave, traces.master, &c)?,
        Space::Smoothed(rule) => smoothed_mass(rule, traces.slave, &c),
    };
    let lambda = generalized_eigenvalues(&schur(&c, traces), &mass)?;
    let top = lambda.last().copied().unwrap_or(0.0);
    let dim = lambda.iter().filter(|&&l| l <= KERNEL * top).count();
    if dim > 0 || top <= 0.0 {
        let why = format!(
            "the {k} constraints are not independent on the two traces: a kernel of dimension {}",
            dim.max(1)
        );
        return Ok(answer(0.0, Some(why)));
    }
    Ok(answer(lambda[0].sqrt(), None))
}
