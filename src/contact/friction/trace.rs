//! Γ_C's full trace for friction (docs/design.md §11): the compliance C = E K⁻¹ Eᵀ on
//! E = [u_x(Γ_C), u_y(Γ_C)] (each ascending x) and, per rule, its blocks seen from the rule's
//! points, G_nn = T C_nn Tᵀ (the frictionless coupling), G_nt = T C_nt Tᵀ = G_tnᵀ and
//! G_tt = T C_tt Tᵀ. A [`Trace::Full`] discretisation has C from its own factorisation; on a
//! [`Trace::Normal`] one (the lab, a sweep) the tangential columns are solved with the mesh's
//! factor, in batches, once per mesh.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use faer::{Mat, MatRef};

use crate::contact::friction::law::Couplings;
use crate::contact::{ContactPoints, Rule};
use crate::discretization::{Discretization, Trace};
use crate::error::InputFault;
use crate::error::SolveError;

/// Columns solved at once when C's tangential columns come from the mesh's factor.
const BATCH: usize = 32;

/// The full trace compliance of a mesh and its per-rule couplings.
pub struct FrictionTrace {
    /// The free dof of u_x at each Γ_C node, ascending x.
    pub tangential_dofs: Vec<usize>,
    /// C on [u_x(Γ_C), u_y(Γ_C)], 2N × 2N.
    pub c_full: Mat<f64>,
    couplings: Mutex<HashMap<Rule, Arc<Couplings>>>,
}

impl FrictionTrace {
    /// The full trace of `disc`, made on first use and kept with it; refused when Γ_C's u_x
    /// is held (a half model).
    pub fn of(disc: &Discretization) -> Result<Arc<FrictionTrace>, SolveError> {
        let tangential = disc
            .dofs
            .tangential_dofs(&disc.mesh)
            .ok_or(InputFault::HeldTangential)?;
        Ok(disc.kept.get_or_init(|| Self::build(disc, tangential)))
    }

    fn build(disc: &Discretization, tangential: Vec<usize>) -> FrictionTrace {
        if let Some((dofs, full)) = &disc.full_compliance {
            return FrictionTrace {
                tangential_dofs: dofs.clone(),
                c_full: full.clone(),
                couplings: Mutex::new(HashMap::new()),
            };
        }
        debug_assert_eq!(disc.trace, Trace::Normal);
        let n = tangential.len();
        let normal = &disc.contact_dofs;
        let mut c_full = Mat::<f64>::zeros(2 * n, 2 * n);
        let dofs = disc.n_dofs();
        for start in (0..n).step_by(BATCH) {
            let cols = BATCH.min(n - start);
            let mut b = vec![0.0; dofs * cols];
            for j in 0..cols {
                b[j * dofs + tangential[start + j]] = 1.0;
            }
            disc.factor.solve_in_place(&mut b, cols);
            for j in 0..cols {
                let u = &b[j * dofs..(j + 1) * dofs];
                for (i, &dof) in tangential.iter().enumerate() {
                    c_full[(i, start + j)] = u[dof];
                }
                for (i, &dof) in normal.iter().enumerate() {
                    c_full[(n + i, start + j)] = u[dof];
                }
            }
        }
        // C_tn = C_ntᵀ, C_nn the mesh's own.
        for j in 0..n {
            for i in 0..n {
                c_full[(j, n + i)] = c_full[(n + i, j)];
                c_full[(n + i, n + j)] = disc.compliance[(i, j)];
            }
        }
        FrictionTrace {
            tangential_dofs: tangential,
            c_full,
            couplings: Mutex::new(HashMap::new()),
        }
    }

    /// The number N of Γ_C nodes.
    pub fn nodes(&self) -> usize {
        self.tangential_dofs.len()
    }

    /// C_tt, C_tn, C_nt or C_nn: `(row, col)` each 0 for t, 1 for n.
    pub fn block(&self, row: usize, col: usize) -> MatRef<'_, f64> {
        let n = self.nodes();
        self.c_full.as_ref().submatrix(row * n, col * n, n, n)
    }

    /// The couplings of `rule` (computed once per rule).
    pub fn couplings(&self, disc: &Discretization, rule: Rule, points: &ContactPoints) -> Arc<Couplings> {
        let mut cache = self.couplings.lock().unwrap_or_else(|e| e.into_inner());
        cache
            .entry(rule)
            .or_insert_with(|| {
                Arc::new(Couplings {
                    g_nn: crate::contact::coupling::of(disc, rule, points),
                    g_nt: t_c_t(points, self.block(1, 0)),
                    g_tt: t_c_t(points, self.block(0, 0)),
                })
            })
            .clone()
    }
}

/// T C Tᵀ between the points (T: each point's shape values at its nodes).
pub(crate) fn t_c_t(points: &ContactPoints, c: MatRef<'_, f64>) -> Mat<f64> {
    let nq = points.len();
    // C Tᵀ, a point's column combining its nodes' columns of C.
    let mut ct = Mat::<f64>::zeros(c.nrows(), nq);
    for (q, pt) in points.points.iter().enumerate() {
        for (&k, &t) in pt.nodes.iter().zip(&pt.trace) {
            for i in 0..c.nrows() {
                ct[(i, q)] += t * c[(i, k)];
            }
        }
    }
    Mat::from_fn(nq, nq, |p, q| {
        let pt = &points.points[p];
        pt.nodes.iter().zip(&pt.trace).map(|(&k, t)| t * ct[(k, q)]).sum()
    })
}

/// Tᵀ f: the nodal values on Γ_C of forces `f` at the points.
pub(crate) fn nodal(points: &ContactPoints, f: &[f64], nodes: usize) -> Vec<f64> {
    points.nodal_forces(f, nodes)
}

/// C_block x for a nodal vector x.
pub(crate) fn apply(c: MatRef<'_, f64>, x: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; c.nrows()];
    for (j, &xj) in x.iter().enumerate() {
        if xj != 0.0 {
            for (i, o) in out.iter_mut().enumerate() {
                *o += c[(i, j)] * xj;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Element;
    use crate::scenario::Scenario;

    /// The full trace compliance is E K⁻¹ Eᵀ by plain solves with the factor, whether it
    /// comes from a Full discretisation's own factorisation or from solves on a Normal one,
    /// and its normal block is the Normal discretisation's C (another ordering, another
    /// factor) to 1e-12.
    #[test]
    fn full_trace_compliance_is_the_inverse() {
        let scenario = Scenario::load(std::path::Path::new("scenarios/hertz-paper-full.toml")).unwrap();
        for element in [Element::Q1, Element::Q2] {
            let full = scenario.discretize_traced(1, element, Trace::Full).unwrap();
            let normal = scenario.discretize(1, element).unwrap();
            let a = FrictionTrace::of(&full).unwrap();
            let b = FrictionTrace::of(&normal).unwrap();
            let n = a.nodes();
            // E K⁻¹ Eᵀ by one solve per trace dof on the Full disc's factor.
            let trace: Vec<usize> = a
                .tangential_dofs
                .iter()
                .chain(&full.contact_dofs)
                .copied()
                .collect();
            let dofs = full.n_dofs();
            let mut expect = Mat::<f64>::zeros(2 * n, 2 * n);
            for (j, &dj) in trace.iter().enumerate() {
                let mut u = vec![0.0; dofs];
                u[dj] = 1.0;
                full.factor.solve_in_place(&mut u, 1);
                for (i, &di) in trace.iter().enumerate() {
                    expect[(i, j)] = u[di];
                }
            }
            let scale = expect.norm_max();
            assert!((&a.c_full - &expect).norm_max() <= 1e-12 * scale, "{element:?}");
            assert!((&b.c_full - &expect).norm_max() <= 1e-12 * scale, "{element:?}");
            assert!((full.compliance() - normal.compliance()).norm_max() <= 1e-12 * scale);
            // The half model holds Γ_C's u_x at x = 0: refused.
            let half = Scenario::paper().discretize(0, element).unwrap();
            assert!(matches!(
                FrictionTrace::of(&half),
                Err(SolveError::Input(crate::error::InputFault::HeldTangential))
            ));
        }
    }
}
