//! Mortar segment-to-segment coupling (docs/design.md §12): the integrals
//! D_jk = ∫ μ_j φ_k and M_jl = ∫ μ_j φ^m_l over the overlap, μ the multiplier basis — the
//! slave's trace basis φ (standard) or its biorthogonal dual ψ (Wohlmuth 2000) — by Gauss on
//! each segment of the exact segmentation, exact for the products.

use super::Coupling;
use super::InterfaceError;
use super::segments::segments;
use super::trace::{Trace, overlap};
use crate::fem::quadrature::gauss_legendre;

/// Gauss points per segment: three are exact to degree 5, above the degree 2·order ≤ 4 of
/// every product of two edge bases.
const GAUSS_POINTS: usize = 3;

/// A row whose measure D̂_j is at most this fraction of its node's ∫_Γs φ_j is left out: a
/// node whose support the master covers by a sliver (or, on a quadratic edge, where its
/// function is negative); its normalised coefficients would be ill-conditioned.
const MIN_ROW_MEASURE: f64 = 1e-9;

/// Normalised coefficients below this are a zero's round-off (e.g. the dual D's
/// off-diagonal) and are left out.
const ZERO_COEFFICIENT: f64 = 1e-13;

/// The dual basis ψ_a = Σ_b A_ab φ_b on an edge, A = D_e M_e⁻¹ with D_e = diag(∫_e φ_a) and
/// M_e the edge's mass matrix; both scale with the edge's length, so A is the same on every
/// edge. Linear: M_e = h/6 [[2, 1], [1, 2]], D_e = h/2 I.
const DUAL_LINEAR: [[f64; 3]; 3] = [[2.0, -1.0, 0.0], [-1.0, 2.0, 0.0], [0.0, 0.0, 0.0]];

/// Quadratic: M_e = h/30 [[4, 2, −1], [2, 16, 2], [−1, 2, 4]], D_e = h diag(1/6, 2/3, 1/6).
/// Well defined (∫_e φ_a > 0 for every node of a 3-node edge), but ψ_mid = −1 at the edge's
/// ends and ψ_end = −1/4 at its middle (docs/design.md §12).
const DUAL_QUADRATIC: [[f64; 3]; 3] = [[1.5, -0.25, 0.5], [-1.0, 1.5, -1.0], [0.5, -0.25, 1.5]];

/// The multiplier basis at a point from the slave's edge basis there.
fn multipliers(order: usize, dual: bool, phi: &[f64; 3]) -> [f64; 3] {
    if !dual {
        return *phi;
    }
    let a = if order == 1 { &DUAL_LINEAR } else { &DUAL_QUADRATIC };
    let mut psi = [0.0; 3];
    for (p, row) in psi.iter_mut().zip(a) {
        *p = row.iter().zip(phi).map(|(c, f)| c * f).sum();
    }
    psi
}

/// Add `value` to the entry of `node` in a short sparse row.
fn add(row: &mut Vec<(usize, f64)>, node: usize, value: f64) {
    match row.iter_mut().find(|(k, _)| *k == node) {
        Some((_, v)) => *v += value,
        None => row.push((node, value)),
    }
}

/// The mortar coupling: a row per slave node j with D̂_j = Σ_k D_jk = ∫_overlap μ_j above
/// [`MIN_ROW_MEASURE`] of ∫_Γs φ_j, slave coefficients D_jk/D̂_j, master coefficients
/// M_jl/D̂_j, weight D̂_j. Both sum to 1 (Σ_k φ_k = Σ_l φ^m_l = 1 on the overlap).
pub(crate) fn mortar(slave: &Trace, master: &Trace, dual: bool) -> Result<Coupling, InterfaceError> {
    let gauss = gauss_legendre(GAUSS_POINTS);
    let n = slave.x.len();
    let (mut d, mut m) = (vec![Vec::new(); n], vec![Vec::new(); n]);
    for seg in segments(slave, master)? {
        let (mid, half) = (0.5 * (seg.a + seg.b), 0.5 * (seg.b - seg.a));
        for &(xi, wg) in &gauss {
            let (x, w) = (mid + half * xi, half * wg);
            let (s0, phi) = slave.basis(seg.slave_edge, x);
            let (m0, phi_m) = master.basis(seg.master_edge, x);
            let mu = multipliers(slave.order, dual, &phi);
            for a in 0..=slave.order {
                for c in 0..=slave.order {
                    add(&mut d[s0 + a], s0 + c, w * mu[a] * phi[c]);
                }
                for b in 0..=master.order {
                    add(&mut m[s0 + a], m0 + b, w * mu[a] * phi_m[b]);
                }
            }
        }
    }
    let measure = slave.measures();
    let overlap = overlap(slave, master)?;
    let mut out = Coupling::default();
    for (j, (dj, mj)) in d.into_iter().zip(m).enumerate() {
        let dhat: f64 = dj.iter().map(|(_, v)| v).sum();
        if dhat <= MIN_ROW_MEASURE * measure[j] {
            continue;
        }
        let scaled = |row: Vec<(usize, f64)>| -> Vec<(usize, f64)> {
            row.into_iter()
                .map(|(k, v)| (k, v / dhat))
                .filter(|(_, v)| v.abs() > ZERO_COEFFICIENT)
                .collect()
        };
        out.x.push(slave.x[j]);
        out.weight.push(dhat);
        out.slave.push(scaled(dj));
        out.master.push(scaled(mj));
    }
    if out.x.is_empty() {
        return Err(InterfaceError::NoConstraint {
            method: if dual { "mortar-dual" } else { "mortar" },
            what: "slave node with a positive measure",
            overlap,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::super::{Coupling, Side};
    use super::*;

    fn couple(s: &[f64], ps: usize, m: &[f64], pm: usize, dual: bool) -> Coupling {
        let ts = Trace::new(Side { x: s, order: ps }, "slave").unwrap();
        let tm = Trace::new(Side { x: m, order: pm }, "master").unwrap();
        mortar(&ts, &tm, dual).unwrap()
    }

    /// Row k's coefficients on `nodes` nodes as a dense vector.
    fn dense(row: &[(usize, f64)], nodes: usize) -> Vec<f64> {
        let mut v = vec![0.0; nodes];
        for &(k, c) in row {
            v[k] += c;
        }
        v
    }

    fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn one_edge_against_two_by_hand() {
        // Slave [0, 1] linear, master [0, 0.5, 1]: D = [[1/3, 1/6], [1/6, 1/3]],
        // M = [[5, 6, 1], [1, 6, 5]]/24 (∫(1−x)(1−2x) on [0, ½] = 5/24, …), D̂ = 1/2.
        let c = couple(&[0.0, 1.0], 1, &[0.0, 0.5, 1.0], 1, false);
        assert_eq!(c.weight.len(), 2);
        assert!(close(&c.weight, &[0.5, 0.5], 1e-15));
        assert!(close(&dense(&c.slave[0], 2), &[2.0 / 3.0, 1.0 / 3.0], 1e-15));
        assert!(close(&dense(&c.slave[1], 2), &[1.0 / 3.0, 2.0 / 3.0], 1e-15));
        let m0 = [5.0 / 12.0, 0.5, 1.0 / 12.0];
        assert!(close(&dense(&c.master[0], 3), &m0, 1e-15), "{:?}", c.master[0]);
        assert!(close(&dense(&c.master[1], 3), &[m0[2], m0[1], m0[0]], 1e-15));
        // Dual: ψ₀ = 2 − 3x, ψ₁ = 3x − 1: D = I/2, ∫ψ₀φ^m = (9, 6, −3)/24.
        let c = couple(&[0.0, 1.0], 1, &[0.0, 0.5, 1.0], 1, true);
        assert!(close(&c.weight, &[0.5, 0.5], 1e-15));
        assert_eq!(c.slave[0].len(), 1, "the dual D is diagonal: {:?}", c.slave[0]);
        assert!(close(&dense(&c.slave[0], 2), &[1.0, 0.0], 1e-15));
        assert!(close(&dense(&c.master[0], 3), &[0.75, 0.5, -0.25], 1e-15));
        assert!(close(&dense(&c.master[1], 3), &[-0.25, 0.5, 0.75], 1e-15));
    }

    #[test]
    fn matching_sides_give_the_mass_matrix() {
        // Three linear edges 0.5, 1, 0.25 long, the same on both sides: D is the mass matrix
        // h/6 [[2, 1], [1, 2]] assembled, M = D; dual: D the lumped masses, M = I.
        let x = [0.0, 0.5, 1.5, 1.75];
        let c = couple(&x, 1, &x, 1, false);
        let h = [0.5, 1.0, 0.25];
        let mut mass = [[0.0; 4]; 4];
        for (e, he) in h.iter().enumerate() {
            mass[e][e] += he / 3.0;
            mass[e + 1][e + 1] += he / 3.0;
            mass[e][e + 1] += he / 6.0;
            mass[e + 1][e] += he / 6.0;
        }
        for j in 0..4 {
            let row: Vec<f64> = dense(&c.slave[j], 4).iter().map(|v| v * c.weight[j]).collect();
            assert!(close(&row, &mass[j], 1e-15), "{j}: {row:?}");
            assert!(close(&dense(&c.master[j], 4), &dense(&c.slave[j], 4), 1e-15));
        }
        let c = couple(&x, 1, &x, 1, true);
        assert!(
            close(&c.weight, &[0.25, 0.75, 0.625, 0.125], 1e-15),
            "{:?}",
            c.weight
        );
        for j in 0..4 {
            assert_eq!(c.slave[j].len(), 1, "{:?}", c.slave[j]);
            assert_eq!(c.slave[j][0].0, j);
            assert!((c.slave[j][0].1 - 1.0).abs() < 1e-14, "{:?}", c.slave[j]);
            assert_eq!(c.master[j].len(), 1, "{:?}", c.master[j]);
            assert_eq!(c.master[j][0].0, j);
            assert!((c.master[j][0].1 - 1.0).abs() < 1e-14, "{:?}", c.master[j]);
        }
    }

    #[test]
    fn quadratic_dual_basis_is_biorthogonal() {
        // ∫ψ_a φ_b = δ_ab ∫φ_b on the reference edge [0, 1], by a 5-point Gauss rule (exact
        // to degree 9), and ∫ψ_a = ∫φ_a = 1/6, 2/3, 1/6 > 0: the basis is well defined.
        let t = Trace::new(
            Side {
                x: &[0.0, 0.5, 1.0],
                order: 2,
            },
            "slave",
        )
        .unwrap();
        let lumped = [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0];
        let mut g = [[0.0; 3]; 3];
        for (xi, w) in gauss_legendre(5) {
            let x = 0.5 + 0.5 * xi;
            let (_, phi) = t.basis(0, x);
            let psi = multipliers(2, true, &phi);
            for a in 0..3 {
                for b in 0..3 {
                    g[a][b] += 0.5 * w * psi[a] * phi[b];
                }
            }
        }
        for a in 0..3 {
            for b in 0..3 {
                let want = if a == b { lumped[a] } else { 0.0 };
                assert!((g[a][b] - want).abs() < 1e-14, "{a}{b}: {}", g[a][b]);
            }
        }
        // The sign issue: the mid node's ψ is −1 at the edge's ends.
        let (_, phi) = t.basis(0, 0.0);
        assert_eq!(multipliers(2, true, &phi)[1], -1.0);
    }
}
