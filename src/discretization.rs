//! The work that depends on the mesh alone (docs/design.md §6): K assembled, analysed and
//! factorised once with Γ_C's normal dofs last, and its trace compliance C; every contact
//! solve on the mesh ([`crate::solve()`]) reuses it.

use std::any::Any;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use faer::Mat;

use crate::contact::{ContactPoints, Rule};
use crate::error::{InputFault, SolveError, Workload};
use crate::fem::factor::{Analysis, Factor};
use crate::fem::memory::{Limits, Sizes};
use crate::fem::{DofMap, FemError, Form, Integration, assemble};
use crate::material::{Material, epsilon_range};
use crate::mesh::{Element, Mesh};
use crate::scenario::Scenario;
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
    /// G = T C Tᵀ for each rule met so far.
    couplings: Mutex<HashMap<Rule, Arc<Mat<f64>>>>,
    /// What a method builds on its first solve on this mesh and keeps with it (Nitsche's layer
    /// factor and couplings, [`crate::solve::nitsche`]).
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
/// with the [`Discretization`]. The discretisation does not know the methods' types (they sit
/// above it).
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
            couplings: Mutex::new(HashMap::new()),
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

    /// The discretisation of `scenario` at `level` with `element`, refused before anything is
    /// allocated when its memory estimate exceeds the memory this process may use
    /// ([`crate::fem::memory`]).
    ///
    /// # Errors
    ///
    /// The estimate does not fit the memory ([`SolveError::TooLarge`]), or as
    /// [`Discretization::new`]'s.
    pub fn of(scenario: &Scenario, level: u32, element: Element) -> Result<Self, SolveError> {
        Self::of_beside(scenario, level, element, 0)
    }

    /// [`Discretization::of`] with `trace` ordered last ([`Trace::Full`] for friction: one
    /// factorisation gives both the normal and the full trace compliance).
    ///
    /// # Errors
    ///
    /// As [`Discretization::of`]'s and [`Discretization::with_trace`]'s.
    pub fn of_traced(
        scenario: &Scenario,
        level: u32,
        element: Element,
        trace: Trace,
    ) -> Result<Self, SolveError> {
        if trace == Trace::Normal {
            return Self::of(scenario, level, element);
        }
        let mut sizes = Self::sizes(scenario, level, element);
        sizes.trace *= 2;
        sizes.check(&Limits::of_process()).map_err(|e| {
            let workload = Workload::Level {
                level,
                element,
                trace: sizes.trace,
                reserved: false,
            };
            refused(e, workload, sizes.unknowns)
        })?;
        let mesh = scenario.mesh(level, element);
        let dofs = DofMap::model(&mesh);
        Self::with_trace(mesh, dofs, scenario.material, scenario.integration, trace)
    }

    /// The trace this discretisation condensed onto.
    pub fn trace(&self) -> Trace {
        self.trace
    }

    /// [`Discretization::of`] beside other work under way that may still take `reserved`
    /// bytes: refused when its estimate exceeds what this process may use less `reserved`.
    ///
    /// # Errors
    ///
    /// As [`Discretization::of`]'s, with `reserved` counted.
    pub fn of_beside(
        scenario: &Scenario,
        level: u32,
        element: Element,
        reserved: u64,
    ) -> Result<Self, SolveError> {
        Self::fits_beside(scenario, level, element, reserved)?;
        Self::new(
            scenario.mesh(level, element),
            scenario.material,
            scenario.integration,
        )
    }

    /// Whether the memory this process may use less `reserved` bytes holds the estimated peak
    /// of the mesh of `level` with `element` (its build, or another factorisation of the same
    /// size); why not otherwise.
    ///
    /// # Errors
    ///
    /// [`SolveError::TooLarge`], naming the unknowns, the memory needed and what is available.
    pub fn fits_beside(
        scenario: &Scenario,
        level: u32,
        element: Element,
        reserved: u64,
    ) -> Result<(), SolveError> {
        let sizes = Self::sizes(scenario, level, element);
        sizes.check(&Limits::of_process().less(reserved)).map_err(|e| {
            let workload = Workload::Level {
                level,
                element,
                trace: sizes.trace,
                reserved: reserved > 0,
            };
            refused(e, workload, sizes.unknowns)
        })
    }

    /// The sizes that decide the memory of the discretisation of `scenario` at `level` with
    /// `element` ([`Sizes::peak_bytes`]), counted on the mesh's lines without assembling.
    pub fn sizes(scenario: &Scenario, level: u32, element: Element) -> Sizes {
        let mesh = scenario.mesh(level, element);
        let trace = mesh.nnx();
        Sizes {
            element,
            unknowns: scenario.n_dofs(level, element),
            trace,
            points: Rule::ALL
                .iter()
                .map(|&rule| ContactPoints::new(rule, &mesh.node_x, element.order()).len())
                .max()
                .unwrap_or(trace),
        }
    }

    /// `rule` laid on Γ_C.
    pub fn contact_points(&self, rule: Rule) -> ContactPoints {
        let nnx = self.mesh.nnx();
        ContactPoints::new(rule, &self.mesh.node_x[..nnx], self.mesh.element.order())
    }

    /// G = B K⁻¹ Bᵀ = T C Tᵀ between the points of `rule` (computed once per rule).
    pub fn coupling(&self, rule: Rule, points: &ContactPoints) -> Arc<Mat<f64>> {
        let mut cache = self.couplings.lock().unwrap_or_else(|e| e.into_inner());
        cache
            .entry(rule)
            .or_insert_with(|| {
                let c = &self.compliance;
                let nq = points.len();
                // C Tᵀ, column by column (a point's column combines its nodes' columns of C),
                // then T (C Tᵀ), column by column: contiguous slices, no index checks.
                let mut ct = Mat::<f64>::zeros(c.nrows(), nq);
                for (q, pt) in points.points.iter().enumerate() {
                    let out = column_mut(&mut ct, q);
                    for (&k, &t) in pt.nodes.iter().zip(&pt.trace) {
                        for (o, v) in out.iter_mut().zip(column(c, k)) {
                            *o += t * v;
                        }
                    }
                }
                let mut g = Mat::<f64>::zeros(nq, nq);
                for q in 0..nq {
                    let ctq = column(&ct, q);
                    for (o, pt) in column_mut(&mut g, q).iter_mut().zip(&points.points) {
                        *o = pt.nodes.iter().zip(&pt.trace).map(|(&k, t)| t * ctq[k]).sum();
                    }
                }
                Arc::new(g)
            })
            .clone()
    }

    /// The number of free dofs.
    pub fn n_dofs(&self) -> usize {
        self.dofs.n_free()
    }

    /// The penalty parameters this mesh and material can represent ([`epsilon_range`]).
    pub fn epsilon_range(&self) -> (f64, f64) {
        epsilon_range(self.material.young, self.mesh.h())
    }

    /// Nodal contact forces Tᵀy on the Γ_C nodes from the forces y at the rule's points.
    pub(crate) fn nodal_forces(points: &ContactPoints, forces: &[f64], n_nodes: usize) -> Vec<f64> {
        let mut f = vec![0.0; n_nodes];
        for (q, &y) in points.points.iter().zip(forces) {
            for (&k, t) in q.nodes.iter().zip(&q.trace) {
                f[k] += t * y;
            }
        }
        f
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

/// Column `j` of `m` as a slice (a [`Mat`]'s columns are contiguous).
fn column(m: &Mat<f64>, j: usize) -> &[f64] {
    m.col(j)
        .try_as_col_major()
        .expect("a Mat's column is contiguous")
        .as_slice()
}

/// Column `j` of `m` as a mutable slice.
fn column_mut(m: &mut Mat<f64>, j: usize) -> &mut [f64] {
    m.col_mut(j)
        .try_as_col_major_mut()
        .expect("a Mat's column is contiguous")
        .as_slice_mut()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// G = T C Tᵀ, computed column by column, is the product of the dense trace matrix T (one
    /// row per point: its shape values at its nodes) with C, by faer's matmul: for Q1 and Q2 and
    /// every rule (two and three nodes per point).
    #[test]
    fn the_coupling_is_t_c_t_transposed() {
        let scenario = crate::scenario::Scenario::paper();
        for element in [Element::Q1, Element::Q2] {
            let disc = Discretization::of(&scenario, 2, element).unwrap();
            for rule in [Rule::Gauss1, Rule::Gauss2, Rule::Trapezoid] {
                let points = disc.contact_points(rule);
                let c = &disc.compliance;
                let mut t = Mat::<f64>::zeros(points.len(), c.nrows());
                for (q, pt) in points.points.iter().enumerate() {
                    for (&k, &v) in pt.nodes.iter().zip(&pt.trace) {
                        t[(q, k)] += v;
                    }
                }
                let expect = &t * c * t.transpose();
                let g = disc.coupling(rule, &points);
                let scale = expect.norm_max();
                assert!(
                    (&*g - &expect).norm_max() <= 1e-14 * scale,
                    "{element:?} {rule:?}"
                );
            }
        }
    }

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
