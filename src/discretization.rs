//! The work that depends on the mesh alone (docs/design.md §6): K assembled, analysed and
//! factorised once with Γ_C's normal dofs last, and its trace compliance C; every contact
//! solve on the mesh ([`crate::solve()`]) reuses it.

use std::any::Any;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use faer::Mat;

use crate::error::{InputFault, SolveError, Workload};
use crate::fem::factor::{Analysis, Factor};
use crate::fem::{DofMap, FemError, Form, Integration, assemble};
use crate::material::{Material, epsilon_range};
use crate::mesh::Mesh;
use crate::warning::{self, Warning};

/// Milliseconds since `t`.
pub(crate) fn ms_since(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// Everything that depends on the mesh alone: K assembled, analysed and factorised once
/// with the Γ_C normal dofs last, and its trace compliance C (see [`crate::fem::condense`]).
pub struct Discretization {
    pub(crate) mesh: Mesh,
    pub(crate) dofs: DofMap,
    /// The analysis of K's pattern: the grid's order and its supernodes (shared by every form
    /// on this mesh).
    pub(crate) ordering: Analysis,
    /// K factorised: the whole grid as one part, or two subdomains, and the dense S (see
    /// [`crate::fem::factor`]).
    pub(crate) factor: Factor,
    /// C = E K⁻¹ Eᵀ on the Γ_C normal dofs, ascending x.
    pub(crate) compliance: Mat<f64>,
    /// The free dof of u_n = u_y at each Γ_C node, in ascending x.
    pub(crate) contact_dofs: Vec<usize>,
    pub(crate) assembly_ms: f64,
    pub(crate) symbolic_ms: f64,
    /// Numeric factorisation and the trace compliance.
    pub(crate) factorization_ms: f64,
    /// The material (its Young's modulus is the scale of ε's range, [`epsilon_range`]) and the
    /// stiffness's integration, for the methods that need more than K (Nitsche's σ_n).
    pub(crate) material: Material,
    pub(crate) integration: Integration,
    /// What is known to be poor about this stiffness before any solve (locking).
    stiffness_warning: Option<Warning>,
    /// What the methods build on their first solve on this mesh and keep with it (a rule's
    /// coupling, the full trace of friction, Nitsche's layer factor).
    pub(crate) kept: Kept,
    /// The trace factorised last: Γ_C's normal dofs, or both components for friction.
    pub(crate) trace: Trace,
    /// On a [`Trace::Full`] discretisation: the u_x free dof of each Γ_C node (ascending x) and
    /// the full trace compliance E K⁻¹ Eᵀ on [u_x(Γ_C), u_y(Γ_C)], 2N × 2N.
    pub(crate) full_compliance: Option<(Vec<usize>, Mat<f64>)>,
}

/// Which of Γ_C's dofs a [`Discretization`] orders last and condenses onto.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Trace {
    /// u_y of Γ_C's nodes: the frictionless contact (docs/design.md §6).
    Normal,
    /// [u_x(Γ_C), u_y(Γ_C)], each ascending x: friction's trace (docs/design.md §11); the
    /// normal block of its compliance is the [`Trace::Normal`] one.
    Full,
}

/// Per-mesh state of the solve methods, one value per type, made on first use and dropped
/// with the [`Discretization`]: a slot the discretisation attaches without knowing the
/// methods' types (they sit above it, in [`crate::contact`]).
#[derive(Default)]
pub(crate) struct Kept(Mutex<Vec<Arc<dyn Any + Send + Sync>>>);

impl Kept {
    /// The kept value of type `T`, made by `make` the first time.
    pub(crate) fn get_or_init<T: Any + Send + Sync>(&self, make: impl FnOnce() -> T) -> Arc<T> {
        let mut kept = self.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(found) = kept.iter().find_map(|v| v.clone().downcast::<T>().ok()) {
            return found;
        }
        let made = Arc::new(make());
        kept.push(made.clone());
        made
    }
}

impl Discretization {
    /// The mesh of the body.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The map from nodes to free dofs (the roller on a half model's axis removed).
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }

    /// The symbolic analysis of K's pattern, Γ_C's normal dofs last (docs/design.md §6).
    pub fn ordering(&self) -> &Analysis {
        &self.ordering
    }

    /// The factorisation of K (the whole grid as one part, or two subdomains, and the dense S).
    pub fn factor(&self) -> &Factor {
        &self.factor
    }

    /// The trace compliance C = E K⁻¹ Eᵀ on the Γ_C normal dofs, ascending x.
    pub fn compliance(&self) -> &Mat<f64> {
        &self.compliance
    }

    /// The free dof of u_n = u_y at each Γ_C node, ascending x.
    pub fn contact_dofs(&self) -> &[usize] {
        &self.contact_dofs
    }

    /// The per-mesh work for `mesh` with the model's supports ([`DofMap::model`]): K assembled,
    /// analysed and factorised with Γ_C's normal dofs last, and the trace compliance C.
    ///
    /// # Errors
    ///
    /// The stiffness is not positive definite (a mesh free to move), or memory runs out
    /// ([`SolveError`]).
    pub fn new(mesh: Mesh, material: Material, integration: Integration) -> Result<Self, SolveError> {
        let dofs = DofMap::model(&mesh);
        Self::with_dofs(mesh, dofs, material, integration)
    }

    /// As [`Discretization::new`] with other supports than the model's (`dofs`), e.g. rollers
    /// on both sides for a patch test. Γ_C's normal dofs must be free.
    ///
    /// # Errors
    ///
    /// As [`Discretization::new`]'s.
    pub fn with_dofs(
        mesh: Mesh,
        dofs: DofMap,
        material: Material,
        integration: Integration,
    ) -> Result<Self, SolveError> {
        Self::with_trace(mesh, dofs, material, integration, Trace::Normal)
    }

    /// As [`Discretization::with_dofs`], ordering `trace` last: [`Trace::Full`] also
    /// condenses onto Γ_C's u_x (friction), refused when one of them is held.
    ///
    /// # Errors
    ///
    /// As [`Discretization::new`]'s, and [`Trace::Full`] with one of Γ_C's u_x held.
    pub fn with_trace(
        mesh: Mesh,
        dofs: DofMap,
        material: Material,
        integration: Integration,
        trace: Trace,
    ) -> Result<Self, SolveError> {
        let mesh_element = mesh.element;
        let contact_dofs = dofs.contact_dofs(&mesh);
        let tangential = match trace {
            Trace::Normal => None,
            Trace::Full => Some(dofs.tangential_dofs(&mesh).ok_or(InputFault::HeldTangential)?),
        };
        let t = Instant::now();
        let stiffness = assemble(&mesh, &dofs, Form::Elasticity(material, integration));
        let assembly_ms = ms_since(t);
        let n = dofs.n_free();
        let ordered: Vec<usize> = tangential
            .iter()
            .flatten()
            .chain(&contact_dofs)
            .copied()
            .collect();
        let t = Instant::now();
        let ordering = Analysis::grid(&stiffness, &mesh, &dofs, &ordered).map_err(|e| fem_error(e, n))?;
        let symbolic_ms = ms_since(t);
        let t = Instant::now();
        let factor = Factor::new(&ordering, stiffness).map_err(|e| fem_error(e, n))?;
        let (compliance, full_compliance) = match tangential {
            None => (factor.compliance(), None),
            Some(tangential) => {
                let full = factor.compliance();
                let nn = contact_dofs.len();
                let normal = full.submatrix(nn, nn, nn, nn).to_owned();
                (normal, Some((tangential, full)))
            }
        };
        let factorization_ms = ms_since(t);
        Ok(Discretization {
            mesh,
            dofs,
            ordering,
            factor,
            compliance,
            contact_dofs,
            assembly_ms,
            symbolic_ms,
            factorization_ms,
            material,
            integration,
            stiffness_warning: warning::of_material(&material, mesh_element, integration),
            kept: Kept::default(),
            trace,
            full_compliance,
        })
    }

    /// What is known to be poor about this stiffness before any solve (locking).
    pub fn stiffness_warning(&self) -> Option<Warning> {
        self.stiffness_warning.clone()
    }

    /// The body's height H (the range of the depth).
    pub fn height(&self) -> f64 {
        self.mesh.ys.last().copied().unwrap_or(0.0)
    }

    /// The trace this discretisation condensed onto.
    pub fn trace(&self) -> Trace {
        self.trace
    }

    /// The number of free dofs.
    pub fn n_dofs(&self) -> usize {
        self.dofs.n_free()
    }

    /// The penalty parameters this mesh and material can represent ([`epsilon_range`]).
    pub fn epsilon_range(&self) -> (f64, f64) {
        epsilon_range(self.material.young, self.mesh.h())
    }
}

/// The solver's error for a failure of the finite element layer on `n` unknowns.
pub(crate) fn fem_error(e: FemError, n: usize) -> SolveError {
    refused(e, Workload::Unknowns, n)
}

/// The solver's error for a failure of the finite element layer on `n` unknowns of
/// `workload`: a refusal for memory names the workload ([`SolveError::TooLarge`]).
pub(crate) fn refused(e: FemError, workload: Workload, n: usize) -> SolveError {
    match e {
        FemError::NotPositiveDefinite { pivot } => SolveError::Factorization {
            matrix: "stiffness",
            pivot,
        },
        FemError::OutOfMemory(step) => SolveError::OutOfMemory { step, unknowns: n },
        FemError::TooLarge {
            unknowns,
            need,
            available,
        } => SolveError::TooLarge {
            workload,
            unknowns,
            need,
            available,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An allocation failure is reported as out of memory (exit 2: an input error), and only a non-positive pivot asks about rigid motion.
    #[test]
    fn out_of_memory_is_not_called_a_rigid_motion() {
        let oom = fem_error(FemError::OutOfMemory("the factor"), 1000);
        assert_eq!(
            oom,
            SolveError::OutOfMemory {
                step: "the factor",
                unknowns: 1000
            }
        );
        assert_eq!(
            oom.to_string(),
            "out of memory in the factor with 1000 unknowns: choose a coarser level"
        );
        assert!(!oom.to_string().contains("rigid"));
        let big = fem_error(
            FemError::TooLarge {
                unknowns: 7,
                need: 3 << 30,
                available: 1 << 30,
            },
            7,
        );
        assert_eq!(
            big.to_string(),
            "7 unknowns need about 3.0 GiB and 1.0 GiB is available: choose a coarser level"
        );
        let pivot = fem_error(FemError::NotPositiveDefinite { pivot: 3 }, 7);
        assert_eq!(
            pivot,
            SolveError::Factorization {
                matrix: "stiffness",
                pivot: 3
            }
        );
        assert!(pivot.to_string().contains("rigid motion"));
    }
}
