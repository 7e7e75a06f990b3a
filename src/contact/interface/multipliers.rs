//! The multiplier spaces of the discretisations across the interface and their L² Gram
//! matrices on the slave's side of the overlap (docs/design.md §12, "The inf-sup constant
//! across the interface"): what a multiplier is measured by when the constraint's inf-sup
//! constant is estimated.

use faer::Mat;

use super::dual::DualBasis;
use super::trace::{Trace, overlap};
use super::{Coupling, InterfaceError, Side};
use crate::contact::rule::{ContactPoints, Rule};
use crate::fem::quadrature::gauss_legendre;

/// The functions a coupling's multipliers are the coefficients of, on the slave's edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MultiplierBasis {
    /// The slave's trace basis φ_j, one per slave node: standard mortar's, and node-to-segment's
    /// nodal pressures read as the function the slave's own basis interpolates (on linear
    /// edges the trapezoid's space, on quadratic ones Simpson's).
    Trace,
    /// The biorthogonal basis ψ_j of mortar-dual, on each edge's covered part.
    Dual,
    /// The Lagrange functions through the rule's points on each slave edge: the
    /// reduced-integration penalty's pressure space Q_h (docs/design.md §5).
    Rule(Rule),
}

/// Gauss points per edge: three are exact to degree 5, above the degree ≤ 4 of a product of
/// two of the functions.
const GAUSS_POINTS: usize = 3;

/// The L² Gram matrix M_jk = ∫ μ_j μ_k over the overlap of the functions μ of `basis` that
/// carry the rows of `coupling` — the one [`super::coupling`] gives on `slave` and `master`:
/// row j's function is the one at `coupling.x[j]` (a slave node for [`MultiplierBasis::Trace`]
/// and [`MultiplierBasis::Dual`], a point of the rule for [`MultiplierBasis::Rule`]), as
/// mortar, mortar-dual, one-pass NTS and the reduced-integration penalty lay their rows. A
/// function whose row was left out (a node the master covers by a sliver, a point off the
/// master) is left out here too.
///
/// # Errors
/// As [`super::coupling`]'s for the two sides.
pub fn multiplier_mass(
    basis: MultiplierBasis,
    slave: Side,
    master: Side,
    coupling: &Coupling,
) -> Result<Mat<f64>, InterfaceError> {
    let (s, m) = (Trace::new(slave, "slave")?, Trace::new(master, "master")?);
    let (lo, hi) = overlap(&s, &m)?;
    let points = match basis {
        MultiplierBasis::Rule(rule) => Some(ContactPoints::new(rule, s.x, s.order)),
        _ => None,
    };
    let row_of = |x: f64| coupling.x.binary_search_by(|v| v.total_cmp(&x)).ok();
    let n = coupling.x.len();
    let mut gram = Mat::<f64>::zeros(n, n);
    let gauss = gauss_legendre(GAUSS_POINTS);
    for e in 0..s.n_edges() {
        let (a, b) = s.edge(e);
        let (c, d) = (a.max(lo), b.min(hi));
        if c >= d {
            continue;
        }
        // The rows of the edge's functions, in the order their values come.
        let rows: Vec<Option<usize>> = match &points {
            Some(cp) => cp.edge_points[e]
                .iter()
                .map(|&k| row_of(cp.points[k].x))
                .collect(),
            None => (0..=s.order).map(|i| row_of(s.x[e * s.order + i])).collect(),
        };
        let dual = (basis == MultiplierBasis::Dual).then(|| DualBasis::on(&s, e, c, d));
        let (mid, half) = (0.5 * (c + d), 0.5 * (d - c));
        for &(xi, wg) in &gauss {
            let (x, w) = (mid + half * xi, half * wg);
            let values: Vec<f64> = match (&points, &dual) {
                (Some(cp), _) => cp.edge_basis(e, (x - a) / (b - a)),
                (None, Some(psi)) => psi.at(x)[..=s.order].to_vec(),
                (None, None) => s.basis(e, x).1[..=s.order].to_vec(),
            };
            for (i, ri) in rows.iter().enumerate() {
                for (j, rj) in rows.iter().enumerate() {
                    if let (Some(ri), Some(rj)) = (ri, rj) {
                        gram[(*ri, *rj)] += w * values[i] * values[j];
                    }
                }
            }
        }
    }
    Ok(gram)
}

#[cfg(test)]
mod tests {
    use super::super::{InterfaceMethod, coupling};
    use super::*;

    fn gram(basis: MultiplierBasis, method: InterfaceMethod, s: &[f64], m: &[f64], order: usize) -> Mat<f64> {
        let (slave, master) = (Side { x: s, order }, Side { x: m, order });
        let c = coupling(method, slave, master).unwrap();
        multiplier_mass(basis, slave, master, &c).unwrap()
    }

    fn close(g: &Mat<f64>, want: &[&[f64]], tol: f64) {
        assert_eq!(g.nrows(), want.len());
        for (i, row) in want.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert!(
                    (g[(i, j)] - v).abs() <= tol,
                    "({i}, {j}): {} against {v}",
                    g[(i, j)]
                );
            }
        }
    }

    /// By hand on the linear edges [0, 1], [1, 3]: the mass matrix h/6 [[2, 1], [1, 2]]
    /// assembled; the dual's h [[1, −½], [−½, 1]] per edge (ψ₀ = 2φ₀ − φ₁: ∫ψ₀² = h(4/3 −
    /// 4/6 + 1/3) = h, ∫ψ₀ψ₁ = h(−2/3 − 2/3 + 5/6) = −h/2); gauss1's piecewise constants h.
    #[test]
    fn the_gram_matrices_by_hand() {
        let x = [0.0, 1.0, 3.0];
        let trace = gram(MultiplierBasis::Trace, InterfaceMethod::Mortar, &x, &x, 1);
        close(
            &trace,
            &[
                &[1.0 / 3.0, 1.0 / 6.0, 0.0],
                &[1.0 / 6.0, 1.0, 1.0 / 3.0],
                &[0.0, 1.0 / 3.0, 2.0 / 3.0],
            ],
            1e-15,
        );
        let nts = gram(MultiplierBasis::Trace, InterfaceMethod::Nts, &x, &x, 1);
        assert_eq!(nts, trace);
        let dual = gram(MultiplierBasis::Dual, InterfaceMethod::MortarDual, &x, &x, 1);
        close(
            &dual,
            &[&[1.0, -0.5, 0.0], &[-0.5, 3.0, -1.0], &[0.0, -1.0, 2.0]],
            1e-14,
        );
        let g1 = gram(
            MultiplierBasis::Rule(Rule::Gauss1),
            InterfaceMethod::Rip(Rule::Gauss1),
            &x,
            &x,
            1,
        );
        close(&g1, &[&[1.0, 0.0], &[0.0, 2.0]], 1e-15);
    }

    /// The overlap bounds the integrals: a master over [0, 2] of the slave's [0, 1, 3]. Mortar
    /// keeps the node at 3 (∫ φ₂ over [1, 2] = 1/4), its function integrated over [1, 2]
    /// only (there φ₁ = 1 − t/2, φ₂ = t/2, t = x − 1); NTS leaves that node out (it is off
    /// the master). Each basis sums to 1 on the overlap, so its Gram matrix's entries add up
    /// to the overlap's length — the dual's built on the covered part [1, 2] of its edge too.
    #[test]
    fn the_overlap_bounds_the_integrals() {
        let (s, m) = ([0.0, 1.0, 3.0], [0.0, 2.0]);
        let trace = gram(MultiplierBasis::Trace, InterfaceMethod::Mortar, &s, &m, 1);
        close(
            &trace,
            &[
                &[1.0 / 3.0, 1.0 / 6.0, 0.0],
                &[1.0 / 6.0, 1.0 / 3.0 + 7.0 / 12.0, 1.0 / 6.0],
                &[0.0, 1.0 / 6.0, 1.0 / 12.0],
            ],
            1e-15,
        );
        let nts = gram(MultiplierBasis::Trace, InterfaceMethod::Nts, &s, &m, 1);
        close(
            &nts,
            &[&[1.0 / 3.0, 1.0 / 6.0], &[1.0 / 6.0, 1.0 / 3.0 + 7.0 / 12.0]],
            1e-15,
        );
        let dual = gram(MultiplierBasis::Dual, InterfaceMethod::MortarDual, &s, &m, 1);
        assert_eq!(dual.nrows(), 3);
        let total = |g: &Mat<f64>| {
            (0..g.nrows())
                .flat_map(|i| (0..g.ncols()).map(move |j| (i, j)))
                .map(|(i, j)| g[(i, j)])
                .sum::<f64>()
        };
        assert!((total(&trace) - 2.0).abs() < 1e-14, "{}", total(&trace));
        assert!((total(&dual) - 2.0).abs() < 1e-13, "{}", total(&dual));
        // Quadratic edges: the mass matrix h/30 [[4, 2, −1], [2, 16, 2], [−1, 2, 4]].
        let q = [0.0, 0.5, 1.0];
        let p2 = gram(MultiplierBasis::Trace, InterfaceMethod::Mortar, &q, &q, 2);
        close(
            &p2,
            &[
                &[4.0 / 30.0, 2.0 / 30.0, -1.0 / 30.0],
                &[2.0 / 30.0, 16.0 / 30.0, 2.0 / 30.0],
                &[-1.0 / 30.0, 2.0 / 30.0, 4.0 / 30.0],
            ],
            1e-15,
        );
    }
}
