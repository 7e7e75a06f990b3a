//! A contact solve's result: the pressures p and p̄, the load, the vertices' displacement and
//! what the solve cost, with the displacement and stresses everywhere computed only when
//! asked.

use serde::Serialize;

use super::friction::{FrictionSolution, Frictional};
use super::method::MethodFields;
use super::newton::NewtonResult;
use super::{ContactParams, ContactPoints};
use crate::discretization::Discretization;
use crate::stress::{StressError, StressField};
use crate::warning::Warning;

/// Wall-clock time of the parts of one solve, in milliseconds.
#[derive(Clone, Copy, Debug, Default, Serialize, PartialEq)]
pub struct Timing {
    /// Assembly of K (0 when the mesh's work was reused).
    pub assembly: f64,
    /// Ordering and symbolic factorisation (0 when reused).
    pub symbolic: f64,
    /// Numeric factorisation of K and its trace compliance (0 when reused).
    pub factorization: f64,
    /// The Newton solve on the contact points (and the rule's coupling, the first time).
    pub newton: f64,
    /// Everything this solve did.
    pub total: f64,
}

/// The solution of (11) with its pressures.
#[derive(Clone, Debug)]
pub struct Solution {
    /// What the solve depended on beyond the mesh.
    pub params: ContactParams,
    /// The rule's points on Γ_C.
    pub points: ContactPoints,
    /// The (inner) Newton's result; for the ALM its iterations are summed over the updates.
    pub newton: NewtonResult,
    /// The ALM's multiplier updates (None for a method without an outer iteration).
    pub outer_iterations: Option<usize>,
    /// Raw pressure p at the rule's points (12); for `exact` and `alm` the multiplier per
    /// unit length.
    pub p: Vec<f64>,
    /// Smoothed pressure p̄ at the Γ_C vertices (16)–(17).
    pub pbar: Vec<f64>,
    /// u_y at the Γ_C vertices.
    pub vertex_uy: Vec<f64>,
    /// P = I(p, 1), the load carried by the modelled body.
    pub load: f64,
    /// Where the time went.
    pub timing: Timing,
    /// What is known to be poor about this answer ([`crate::warning`]).
    pub warnings: Vec<Warning>,
    /// The load f on the free dofs, K u = f, when the contact acts on more than Γ_C's normal
    /// dofs (Nitsche's σ_n terms); None when u = −K⁻¹ Eᵀ Tᵀ y.
    pub nodal_forces: Option<Vec<f64>>,
    /// Nitsche's γ₀ as used (`auto`'s choice included); None for the other methods.
    pub gamma0: Option<f64>,
    /// The tangential forces, tractions and states of a solve with friction
    /// ([`crate::contact::friction`]); None without.
    pub friction: Option<FrictionSolution>,
}

impl From<Frictional> for Solution {
    /// A solve with friction's answer as a solution, its time all on Γ_C and no warnings yet
    /// (they are the entry's, [`crate::solve()`]).
    fn from(f: Frictional) -> Self {
        Solution {
            params: f.params,
            points: f.points,
            newton: f.newton,
            outer_iterations: f.outer_iterations,
            p: f.p,
            pbar: f.pbar,
            vertex_uy: f.vertex_uy,
            load: f.load,
            timing: Timing {
                newton: f.newton_ms,
                total: f.newton_ms,
                ..Timing::default()
            },
            warnings: Vec::new(),
            nodal_forces: None,
            gamma0: None,
            friction: Some(f.friction),
        }
    }
}

impl Solution {
    /// The method and the parameters this solve used, as every output carries them.
    pub fn method_fields(&self) -> MethodFields {
        MethodFields::used(self.params.method, self.gamma0)
    }

    /// The stresses of this solution ([`StressField`]), with the material and the integration
    /// of the stiffness it was solved with (`disc`'s).
    ///
    /// # Errors
    ///
    /// As [`StressField::new`]'s.
    pub fn stress_field(&self, disc: &Discretization) -> Result<StressField, StressError> {
        StressField::new(
            &disc.mesh,
            &disc.material,
            disc.integration,
            &self.displacement(disc),
        )
    }

    /// Displacement on every dof (zero on the constrained ones): u = −K⁻¹ Eᵀ Tᵀ y (with
    /// friction + K⁻¹ E_tᵀ Tᵀ z; or K⁻¹ f with [`Solution::nodal_forces`]), one solve with the
    /// mesh's factor, done only when asked.
    pub fn displacement(&self, disc: &Discretization) -> Vec<f64> {
        if let Some(f) = &self.nodal_forces {
            let mut u = f.clone();
            disc.factor.solve_in_place(&mut u, 1);
            return disc.dofs.expand(&u, |_| 0.0);
        }
        let forces = self
            .points
            .nodal_forces(&self.newton.forces, disc.contact_dofs.len());
        let mut u = vec![0.0; disc.n_dofs()];
        for (&d, f) in disc.contact_dofs.iter().zip(&forces) {
            u[d] = -f;
        }
        if let Some(friction) = &self.friction
            && let Some(dofs) = disc.dofs.tangential_dofs(&disc.mesh)
        {
            let tangential = self.points.nodal_forces(&friction.z, dofs.len());
            for (&d, f) in dofs.iter().zip(&tangential) {
                u[d] += f;
            }
        }
        disc.factor.solve_in_place(&mut u, 1);
        disc.dofs.expand(&u, |_| 0.0)
    }
}

impl Timing {
    /// The mesh's work alone (assembly, ordering, factorisation) of `disc`.
    pub fn mesh_work(disc: &Discretization) -> Self {
        Timing {
            assembly: disc.assembly_ms,
            symbolic: disc.symbolic_ms,
            factorization: disc.factorization_ms,
            newton: 0.0,
            total: disc.assembly_ms + disc.symbolic_ms + disc.factorization_ms,
        }
    }

    /// Add `other`'s times to these.
    pub fn add(&mut self, other: &Timing) {
        self.assembly += other.assembly;
        self.symbolic += other.symbolic;
        self.factorization += other.factorization;
        self.newton += other.newton;
        self.total += other.total;
    }

    /// Charge this solve with the mesh's work too (a fresh solve).
    pub fn include_mesh_work(&mut self, disc: &Discretization) {
        self.assembly = disc.assembly_ms;
        self.symbolic = disc.symbolic_ms;
        // Added: a Nitsche solve has charged its own operator here already.
        self.factorization += disc.factorization_ms;
        self.total += disc.assembly_ms + disc.symbolic_ms + disc.factorization_ms;
    }
}
