//! Answers that are computed correctly but known to be poor: a solve that converged can still
//! describe the wrong physics (volumetric locking) or a contact the mesh does not resolve. Each
//! warning says what is wrong and what to change; the CLI prints them on stderr and in the
//! JSON `warnings`, the lab in its status line.

use std::fmt;

use crate::fem::Integration;
use crate::material::{Material, Plane};
use crate::mesh::Element;
use crate::text::num;

/// Poisson's ratio from which a displacement element integrated exactly locks noticeably in
/// plane strain (Q1 is 1.005× too stiff at 0.49 and 1.04× at 0.499, STABILITY.md).
pub const LOCKING_POISSON: f64 = 0.495;

/// The largest relative round-off of the penalty's pressure accepted without a warning.
pub const ROUND_OFF_LIMIT: f64 = 1e-6;

/// The measured amplification of the round-off of u_n − g into p = (u_n − g)⁺/ε, against the
/// estimate u·d/(ε max p) (u the unit round-off, d the depth): 1–3 for Q1 at levels 2–4 on the
/// paper's problem and hertz-block, 9–11 for Q2 at level 6 (STABILITY.md, "Round-off of the
/// pressure").
pub const ROUND_OFF_AMPLIFICATION: f64 = 10.0;

/// The largest penetration max(u_n − g)⁺ of a penalty solve accepted without a warning, as a
/// share of the indentation depth d. The penalty's pressure is the penetration over ε, so a
/// penetration δ leaves the body indented by about d − δ, not d: its load and pressure are
/// low by about δ/d (the load 1.87 against 643 at ε = 1 on the paper's problem at level 4,
/// where δ is nearly d). At 1% of d the load is within about 1% (docs/design.md §3, "Too
/// soft a penalty").
pub const SOFT_PENETRATION_LIMIT: f64 = 0.01;

/// The fewest elements of Γ_C in contact for a pressure profile worth reading.
pub const MIN_CONTACT_ELEMENTS: usize = 3;

/// A known weakness of an answer.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Warning {
    /// Near-incompressible plane strain with an element that locks as integrated.
    Locking {
        /// Poisson's ratio ν ≥ [`LOCKING_POISSON`].
        poisson: f64,
        /// The element.
        element: Element,
        /// The stiffness's integration.
        integration: Integration,
    },
    /// The obstacle overlaps the body on an interval that holds none of the rule's points: the
    /// solve cannot see it, and its load of 0 is wrong.
    Unresolved {
        /// The left end of the overlap, x.
        from: f64,
        /// The right end of the overlap, x.
        to: f64,
        /// The mesh's h (its largest cell side).
        h: f64,
    },
    /// The penalty's pressure, formed as penetration/ε, may carry round-off above
    /// [`ROUND_OFF_LIMIT`] of its size ([`of_round_off`]).
    RoundOff {
        /// The estimated relative round-off of p.
        estimate: f64,
        /// The penalty parameter ε.
        epsilon: f64,
        /// κ = εE/h.
        kappa: f64,
    },
    /// The penalty is so soft that the body penetrates the obstacle by more than
    /// [`SOFT_PENETRATION_LIMIT`] of the depth ([`crate::contact::warnings::of_soft_penalty`]): the load and the
    /// pressure are too low by about as much.
    SoftPenalty {
        /// The largest penetration max(u_n − g)⁺ = ε max p.
        penetration: f64,
        /// The indentation depth d.
        depth: f64,
        /// The penalty parameter ε.
        epsilon: f64,
        /// An ε that brings the penetration to half the limit ([`crate::contact::warnings::of_soft_penalty`]).
        sufficient: f64,
    },
    /// `--refine-edges auto` made its cap of passes, every one changing p̄ by more than its
    /// tolerance.
    GradingCap {
        /// The passes made (the cap).
        passes: u32,
        /// The smallest relative change of p̄ (L²(Γ_C)) a pass made: the kept grid's.
        change: f64,
        /// The change of p̄ below which `auto` stops.
        tolerance: f64,
        /// The passes of the grid kept (the one whose pass changed p̄ least).
        kept: u32,
    },
    /// Contact on fewer than [`MIN_CONTACT_ELEMENTS`] elements of Γ_C.
    NarrowContact {
        /// The elements of Γ_C with a positive pressure.
        elements: usize,
        /// The mesh's h (its largest cell side).
        h: f64,
    },
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Warning::Locking {
                poisson,
                element,
                integration,
            } => {
                let cure = if *element == Element::P1 {
                    "use q1 or q2 with mesh.integration = \"selective\""
                } else {
                    "set mesh.integration = \"selective\" in the scenario"
                };
                write!(
                    f,
                    "ν = {} with {} ({} integration) locks in plane strain: the body is too stiff and the load too high; {cure}",
                    num(*poisson),
                    element.name(),
                    match integration {
                        Integration::Full => "full",
                        Integration::Selective => "selective",
                    }
                )
            }
            Warning::Unresolved { from, to, h } => write!(
                f,
                "the obstacle overlaps Γ_C on x = {} to {} ({} wide), between the contact points of a mesh with h = {}: the mesh does not resolve it; choose a finer level",
                num(*from),
                num(*to),
                num(to - from),
                num(*h)
            ),
            Warning::RoundOff {
                estimate,
                epsilon,
                kappa,
            } => write!(
                f,
                "round-off: p may be off by {estimate:.0e} of its size (above {}), as it is formed as penetration/ε at ε = {} (κ = εE/h = {}); the displacement and the load are less affected. Use a larger ε, or ε = 0 for the exact constraint",
                num(ROUND_OFF_LIMIT),
                num(*epsilon),
                num(*kappa)
            ),
            Warning::SoftPenalty {
                penetration,
                depth,
                epsilon,
                sufficient,
            } => write!(
                f,
                "soft penalty: the body penetrates the obstacle by {penetration:.3e} ({:.1}% of the depth {}, above the {}% allowed) at ε = {}: the load and the pressure are too low by about as much. Use ε ≤ {sufficient:.1e} (or ε = 0 for the exact constraint)",
                100.0 * penetration / depth,
                num(*depth),
                num(100.0 * SOFT_PENETRATION_LIMIT),
                num(*epsilon),
            ),
            Warning::GradingCap {
                passes,
                change,
                tolerance,
                kept,
            } => write!(
                f,
                "--refine-edges auto reached its cap of {passes} passes with p̄ still changing by {change:.1e} or more per pass (it stops below {}): the grading has not settled; kept the grid of {kept} pass{}, whose pass changed p̄ least; a finer --level resolves the contact edges better",
                num(*tolerance),
                if *kept == 1 { "" } else { "es" }
            ),
            Warning::NarrowContact { elements, h } => write!(
                f,
                "the contact zone spans only {elements} element{} of Γ_C (h = {}): the pressure is resolved by too few points to be trusted; choose a finer level",
                if *elements == 1 { "" } else { "s" },
                num(*h)
            ),
        }
    }
}

impl serde::Serialize for Warning {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// The warning about the stiffness itself, known before any solve.
pub fn of_material(material: &Material, element: Element, integration: Integration) -> Option<Warning> {
    let locks = match (element, integration) {
        (Element::P1, _) | (_, Integration::Full) => true,
        (_, Integration::Selective) => false,
    };
    (material.plane == Plane::Strain && material.poisson >= LOCKING_POISSON && locks).then_some(
        Warning::Locking {
            poisson: material.poisson,
            element,
            integration,
        },
    )
}

/// The warning that the penalty's pressure `p` at `epsilon`, pressed to the depth `depth`, may
/// carry round-off above [`ROUND_OFF_LIMIT`] of its largest value: u_n − g, a difference of
/// numbers of the size of d, carries round-off of about u·d (u = 2.2e-16), which 1/ε
/// amplifies, estimated as [`ROUND_OFF_AMPLIFICATION`] · u·d/(ε max p). `h` and `young` give
/// κ = εE/h for the message. None without contact.
pub fn of_round_off(depth: f64, epsilon: f64, p: &[f64], h: f64, young: f64) -> Option<Warning> {
    let top = p.iter().copied().fold(0.0, f64::max);
    if top <= 0.0 || epsilon <= 0.0 {
        return None;
    }
    let estimate = ROUND_OFF_AMPLIFICATION * f64::EPSILON * depth.abs() / (epsilon * top);
    (estimate > ROUND_OFF_LIMIT).then_some(Warning::RoundOff {
        estimate,
        epsilon,
        kappa: epsilon * young / h,
    })
}
