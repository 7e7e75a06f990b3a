//! The errors of a row against the reference (Theorem 2 (26)): p and p̄ in L²(Γ_C), u in H¹ (7)
//! and the load, integrated at the reference's Gauss points; with friction also the smoothed
//! tangential traction t̄ and the tangential load Q (docs/design.md §11), each relative to the
//! normal one's norm (‖p_ref‖₀, P_ref: t ≤ μp, and t vanishes at μ = 0).

use serde::Serialize;

use super::grid::{REFERENCE_SCHEME, ReferenceMesh};
use super::reference::{Estimate, Reference, ReferenceFields};
use crate::contact::ContactPoints;
use crate::contact::solution::Solution;
use crate::discretization::Discretization;
use crate::fem::basis::evaluate;
use crate::mesh::Mesh;
use crate::scenario::Scenario;

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
    /// With friction: ‖t̄ − t_ref‖₀ / ‖p_ref‖₀ on Γ_C, t̄ the smoothed tangential traction
    /// (t's (16)–(17)); None without friction.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tbar: Option<f64>,
    /// With friction: |Q − Q_ref| / P_ref, Q = ∫ t dx the tangential load; None without.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tangential_load: Option<f64>,
}

impl Errors {
    /// Every error it reports (t̄'s and Q's when it has them).
    pub fn values(&self) -> impl Iterator<Item = f64> {
        [self.p, self.pbar, self.u, self.load]
            .into_iter()
            .chain(self.tbar)
            .chain(self.tangential_load)
    }
}

/// A solution's friction as the error integrals see it: t̄ at Γ_C's vertices and Q.
#[derive(Clone, Copy)]
pub(super) struct Tangential<'a> {
    pub(super) tbar: &'a [f64],
    pub(super) load: f64,
}

/// A solution as the error integrals see it: a displacement on a mesh nested in the
/// reference's, its pressure at a rule's points, its smoothed pressure at Γ_C's vertices (None:
/// p itself stands for it) and its load.
pub(super) struct Field<'a> {
    pub(super) mesh: &'a Mesh,
    pub(super) u: &'a [f64],
    pub(super) points: &'a ContactPoints,
    pub(super) p: &'a [f64],
    pub(super) pbar: Option<&'a [f64]>,
    pub(super) load: f64,
    pub(super) tangential: Option<Tangential<'a>>,
}

/// The relative differences of `field` from the reference.
pub(super) fn differences(reference: &Reference, field: &Field) -> Errors {
    let (mut ep, mut epbar) = (0.0, 0.0);
    for &(x, w, pref) in &reference.edge_points {
        let p = field.points.interpolate(field.p, x);
        let pbar = field.pbar.map_or(p, |v| field.points.interpolate_vertices(v, x));
        ep += w * (p - pref).powi(2);
        epbar += w * (pbar - pref).powi(2);
    }
    let (tbar, tangential_load) = match (&field.tangential, &reference.tangential) {
        (Some(t), Some(r)) => {
            let mut et = 0.0;
            for (&(x, w, _), tref) in reference.edge_points.iter().zip(&r.edge_t) {
                et += w * (field.points.interpolate_vertices(t.tbar, x) - tref).powi(2);
            }
            (
                Some(et.sqrt() / reference.p_norm),
                Some((t.load - r.load).abs() / reference.load),
            )
        }
        _ => (None, None),
    };
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
        tbar,
        tangential_load,
    }
}

/// What a row keeps of its solution, so that its errors can be measured again against a
/// refined reference without solving again.
pub(super) struct Kept {
    pub(super) mesh: Mesh,
    pub(super) u: Vec<f64>,
    pub(super) points: ContactPoints,
    pub(super) p: Vec<f64>,
    pub(super) pbar: Vec<f64>,
    pub(super) load: f64,
    /// t̄ at Γ_C's vertices and Q, with friction.
    pub(super) tangential: Option<(Vec<f64>, f64)>,
}

impl Kept {
    pub(super) fn of(disc: &Discretization, sol: &Solution) -> Self {
        Kept {
            mesh: disc.mesh.clone(),
            u: sol.displacement(disc),
            points: sol.points.clone(),
            p: sol.p.clone(),
            pbar: sol.pbar.clone(),
            load: sol.load,
            tangential: sol.friction.as_ref().map(|f| (f.tbar.clone(), f.tangential_load)),
        }
    }

    pub(super) fn errors(&self, reference: &Reference) -> Errors {
        differences(
            reference,
            &Field {
                mesh: &self.mesh,
                u: &self.u,
                points: &self.points,
                p: &self.p,
                pbar: Some(&self.pbar),
                load: self.load,
                tangential: self
                    .tangential
                    .as_ref()
                    .map(|(tbar, load)| Tangential { tbar, load: *load }),
            },
        )
    }
}

/// The errors of `sol` on `disc` (a mesh nested in the reference's).
pub fn errors(reference: &Reference, disc: &Discretization, sol: &Solution) -> Errors {
    Kept::of(disc, sol).errors(reference)
}

impl Reference {
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
                tangential: None,
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
