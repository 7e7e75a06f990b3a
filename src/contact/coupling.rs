//! A contact rule laid on a discretisation's Γ_C and its coupling G = B K⁻¹ Bᵀ = T C Tᵀ
//! between the rule's points (docs/design.md §6): the rule's view of the mesh's trace
//! compliance C, computed once per rule and kept with the [`Discretization`].

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use faer::Mat;

use super::{ContactPoints, Rule};
use crate::discretization::Discretization;

/// G for each rule met so far on one discretisation (kept with it).
#[derive(Default)]
struct RuleCouplings(Mutex<HashMap<Rule, Arc<Mat<f64>>>>);

impl ContactPoints {
    /// `rule` laid on Γ_C of `disc`.
    pub fn on(disc: &Discretization, rule: Rule) -> ContactPoints {
        let mesh = disc.mesh();
        let nnx = mesh.nnx();
        ContactPoints::new(rule, &mesh.node_x[..nnx], mesh.element.order())
    }

    /// Nodal contact forces Tᵀy on the Γ_C nodes from the forces y at these points.
    pub(crate) fn nodal_forces(&self, forces: &[f64], n_nodes: usize) -> Vec<f64> {
        let mut f = vec![0.0; n_nodes];
        for (q, &y) in self.points.iter().zip(forces) {
            for (&k, t) in q.nodes.iter().zip(&q.trace) {
                f[k] += t * y;
            }
        }
        f
    }
}

/// G = B K⁻¹ Bᵀ = T C Tᵀ between the points of `rule` on `disc` (computed once per rule and
/// kept with `disc`).
pub fn of(disc: &Discretization, rule: Rule, points: &ContactPoints) -> Arc<Mat<f64>> {
    let kept = disc.kept.get_or_init(RuleCouplings::default);
    let mut cache = kept.0.lock().unwrap_or_else(|e| e.into_inner());
    cache
        .entry(rule)
        .or_insert_with(|| {
            let c = disc.compliance();
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
    use crate::mesh::Element;

    /// G = T C Tᵀ, computed column by column, is the product of the dense trace matrix T (one
    /// row per point: its shape values at its nodes) with C, by faer's matmul: for Q1 and Q2 and
    /// every rule (two and three nodes per point).
    #[test]
    fn the_coupling_is_t_c_t_transposed() {
        let scenario = crate::scenario::Scenario::paper();
        for element in [Element::Q1, Element::Q2] {
            let disc = scenario.discretize(2, element).unwrap();
            for rule in [Rule::Gauss1, Rule::Gauss2, Rule::Trapezoid] {
                let points = ContactPoints::on(&disc, rule);
                let c = disc.compliance();
                let mut t = Mat::<f64>::zeros(points.len(), c.nrows());
                for (q, pt) in points.points.iter().enumerate() {
                    for (&k, &v) in pt.nodes.iter().zip(&pt.trace) {
                        t[(q, k)] += v;
                    }
                }
                let expect = &t * c * t.transpose();
                let g = of(&disc, rule, &points);
                let scale = expect.norm_max();
                assert!(
                    (&*g - &expect).norm_max() <= 1e-14 * scale,
                    "{element:?} {rule:?}"
                );
            }
        }
    }
}
