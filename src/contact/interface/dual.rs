//! The dual (biorthogonal) multiplier basis on the slave's edges (docs/design.md §12;
//! Wohlmuth 2000): on the part [c, d] of an edge that the master covers, ψ_a = Σ_b A_ab φ_b
//! with ∫_c^d ψ_a φ_b = δ_ab ∫_c^d φ_b, i.e. A = D M⁻¹, D = diag ∫_c^d φ_a, M the Gram
//! matrix of the φ_a on [c, d]. On a whole edge A is the same for every edge; on a part of
//! one (where the overlap ends inside it) it is built on that part, so that D stays diagonal
//! there too.

use super::trace::Trace;
use crate::fem::basis::lagrange_1d;

/// ∫ L_b / len of the Lagrange basis on an interval: (1/2, 1/2), (1/6, 2/3, 1/6).
const WEIGHTS: [[f64; 3]; 2] = [[0.5, 0.5, 0.0], [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0]];

/// len · M⁻¹ of the Lagrange basis's Gram matrix M on an interval of length len: linear
/// M = len/6 [[2, 1], [1, 2]]; quadratic M = len/30 [[4, 2, −1], [2, 16, 2], [−1, 2, 4]].
const GRAM_INVERSE: [[[f64; 3]; 3]; 2] = [
    [[4.0, -2.0, 0.0], [-2.0, 4.0, 0.0], [0.0, 0.0, 0.0]],
    [[9.0, -1.5, 3.0], [-1.5, 2.25, -1.5], [3.0, -1.5, 9.0]],
];

/// A = diag(WEIGHTS) · GRAM_INVERSE on a whole edge: linear [[2, −1], [−1, 2]]; quadratic
/// [[3/2, −1/4, 1/2], [−1, 3/2, −1], [1/2, −1/4, 3/2]] — well defined (∫_e φ_a > 0 for every
/// node of a 3-node edge), but ψ_mid = −1 at the edge's ends and ψ_end = −1/4 at its middle.
const WHOLE_EDGE: [[[f64; 3]; 3]; 2] = [
    [[2.0, -1.0, 0.0], [-1.0, 2.0, 0.0], [0.0, 0.0, 0.0]],
    [[1.5, -0.25, 0.5], [-1.0, 1.5, -1.0], [0.5, -0.25, 1.5]],
];

/// The dual basis on [c, d] ⊂ slave edge e, in the Lagrange basis L_b on [c, d] (equispaced
/// nodes): ψ_a = Σ_b coef_ab L_b.
#[derive(Clone, Debug)]
pub(crate) struct DualBasis {
    c: f64,
    d: f64,
    order: usize,
    coef: [[f64; 3]; 3],
}

impl DualBasis {
    /// The dual basis of slave edge `e` on its part [c, d] (c < d).
    ///
    /// With T_ab = φ_a(x'_b), x'_b the nodes of [c, d], φ_a = Σ_b T_ab L_b there, so
    /// ∫φ_a = len (T w)_a and the Gram matrix is T M_L Tᵀ: ψ = coef L with
    /// coef = diag(T w) · T⁻ᵀ · (len M_L⁻¹), well conditioned in the local basis (a sliver
    /// [c, d] makes T, not the Gram matrix, near singular).
    pub fn on(slave: &Trace, e: usize, c: f64, d: f64) -> Self {
        let p = slave.order;
        let (a, b) = slave.edge(e);
        let coef = if (c, d) == (a, b) {
            WHOLE_EDGE[p - 1]
        } else {
            let mut t = [[0.0; 3]; 3];
            for bb in 0..=p {
                let x = c + (d - c) * bb as f64 / p as f64;
                let (_, phi) = slave.basis(e, x);
                for (t_a, phi_a) in t.iter_mut().zip(phi).take(p + 1) {
                    t_a[bb] = phi_a;
                }
            }
            partial_coefficients(p, &t)
        };
        DualBasis { c, d, order: p, coef }
    }

    /// ψ_a(x), a = 0..=order (the rest 0).
    pub fn at(&self, x: f64) -> [f64; 3] {
        let xi = 2.0 * (x - self.c) / (self.d - self.c) - 1.0;
        let (l, _) = lagrange_1d(self.order, xi);
        let mut psi = [0.0; 3];
        for (p, row) in psi.iter_mut().zip(&self.coef).take(self.order + 1) {
            *p = row.iter().zip(&l).map(|(c, v)| c * v).sum();
        }
        psi
    }
}

/// coef = diag(T w) · T⁻ᵀ · GRAM_INVERSE for order p (T the first p + 1 rows and columns).
fn partial_coefficients(p: usize, t: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let n = p + 1;
    let w = &WEIGHTS[p - 1];
    // Solve Tᵀ X = GRAM_INVERSE by Gauss elimination with partial pivoting.
    let mut m = [[0.0; 3]; 3];
    let mut rhs = GRAM_INVERSE[p - 1];
    for (i, m_i) in m.iter_mut().enumerate().take(n) {
        for (j, m_ij) in m_i.iter_mut().enumerate().take(n) {
            *m_ij = t[j][i];
        }
    }
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))
            .unwrap_or(col);
        m.swap(col, pivot);
        rhs.swap(col, pivot);
        for row in col + 1..n {
            let f = m[row][col] / m[col][col];
            for k in 0..n {
                m[row][k] -= f * m[col][k];
                rhs[row][k] -= f * rhs[col][k];
            }
        }
    }
    let mut x = [[0.0; 3]; 3];
    for row in (0..n).rev() {
        for k in 0..n {
            let s: f64 = (row + 1..n).map(|j| m[row][j] * x[j][k]).sum();
            x[row][k] = (rhs[row][k] - s) / m[row][row];
        }
    }
    let mut coef = [[0.0; 3]; 3];
    for a in 0..n {
        let tw: f64 = (0..n).map(|b| t[a][b] * w[b]).sum();
        for k in 0..n {
            coef[a][k] = tw * x[a][k];
        }
    }
    coef
}

#[cfg(test)]
mod tests {
    use super::super::Side;
    use super::*;
    use crate::fem::quadrature::gauss_legendre;

    /// ∫_c^d ψ_a φ_b by 5-point Gauss (exact to degree 9).
    fn biorthogonality(t: &Trace, basis: &DualBasis, c: f64, d: f64) -> [[f64; 3]; 3] {
        let mut g = [[0.0; 3]; 3];
        for (xi, w) in gauss_legendre(5) {
            let x = 0.5 * (c + d) + 0.5 * (d - c) * xi;
            let (_, phi) = t.basis(0, x);
            for (g_a, psi_a) in g.iter_mut().zip(basis.at(x)) {
                for (g_ab, phi_b) in g_a.iter_mut().zip(phi) {
                    *g_ab += 0.5 * (d - c) * w * psi_a * phi_b;
                }
            }
        }
        g
    }

    #[test]
    fn whole_edges_and_parts_are_biorthogonal() {
        // ∫ψ_a φ_b = δ_ab ∫φ_b on a whole edge [1, 3] and on parts of it, linear and
        // quadratic; ∫φ_b by hand (the edge's x ↦ s = (x − 1)/2: φ₀ = 1 − s, φ₁ = s, …).
        let lin = [1.0, 3.0];
        let quad = [1.0, 2.0, 3.0];
        for (x, order) in [(&lin[..], 1), (&quad[..], 2)] {
            let t = Trace::new(Side { x, order }, "slave").unwrap();
            for (c, d) in [(1.0, 3.0), (1.6, 3.0), (1.0, 1.2), (2.5, 2.9)] {
                let basis = DualBasis::on(&t, 0, c, d);
                let g = biorthogonality(&t, &basis, c, d);
                let (s0, s1) = ((c - 1.0) / 2.0, (d - 1.0) / 2.0);
                // Antiderivatives in s of φ_b, times dx/ds = 2.
                let prim: [fn(f64) -> f64; 3] = if order == 1 {
                    [|s| s - s * s / 2.0, |s| s * s / 2.0, |_| 0.0]
                } else {
                    [
                        |s| s - 1.5 * s * s + 2.0 * s.powi(3) / 3.0,
                        |s| 2.0 * s * s - 4.0 * s.powi(3) / 3.0,
                        |s| -s * s / 2.0 + 2.0 * s.powi(3) / 3.0,
                    ]
                };
                for (a, g_a) in g.iter().enumerate().take(order + 1) {
                    for (b, g_ab) in g_a.iter().enumerate().take(order + 1) {
                        let want = if a == b {
                            2.0 * (prim[a](s1) - prim[a](s0))
                        } else {
                            0.0
                        };
                        assert!(
                            (g_ab - want).abs() < 1e-13,
                            "order {order} [{c}, {d}] {a}{b}: {g_ab} vs {want}"
                        );
                    }
                }
            }
            // The general construction on the whole edge is the constants'.
            let mut identity = [[0.0; 3]; 3];
            for (a, row) in identity.iter_mut().enumerate().take(order + 1) {
                row[a] = 1.0;
            }
            let general = partial_coefficients(order, &identity);
            for a in 0..=order {
                for b in 0..=order {
                    let want = WHOLE_EDGE[order - 1][a][b];
                    assert!((general[a][b] - want).abs() < 1e-14, "{order} {a}{b}");
                }
            }
        }
    }

    #[test]
    fn the_quadratic_mid_function_is_minus_one_at_the_ends() {
        let x = [0.0, 0.5, 1.0];
        let t = Trace::new(Side { x: &x, order: 2 }, "slave").unwrap();
        let basis = DualBasis::on(&t, 0, 0.0, 1.0);
        assert_eq!(basis.at(0.0)[1], -1.0);
        assert_eq!(basis.at(1.0)[1], -1.0);
        assert_eq!(basis.at(0.5)[0], -0.25);
    }
}
