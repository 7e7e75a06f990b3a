//! Mortar segment-to-segment coupling (docs/design.md §12): the integrals
//! D_jk = ∫ μ_j φ_k and M_jl = ∫ μ_j φ^m_l over the overlap, μ the multiplier basis — the
//! slave's trace basis φ (standard) or its biorthogonal dual ψ ([`super::dual`]) — by Gauss
//! on each segment of the exact segmentation, exact for the products.

use super::Coupling;
use super::InterfaceError;
use super::dual::DualBasis;
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

/// Normalised coefficients below this are a zero's round-off (e.g. the dual's
/// M_jl = ∫ψ_j φ^m_l off node j on matching sides) and are left out.
const ZERO_COEFFICIENT: f64 = 1e-13;

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
    let (lo, hi) = overlap(slave, master)?;
    let n = slave.x.len();
    let (mut d, mut m) = (vec![Vec::new(); n], vec![Vec::new(); n]);
    let mut psi: Option<(usize, DualBasis)> = None;
    for seg in segments(slave, master)? {
        let e = seg.slave_edge;
        if dual && psi.as_ref().is_none_or(|(at, _)| *at != e) {
            let (a, b) = slave.edge(e);
            psi = Some((e, DualBasis::on(slave, e, a.max(lo), b.min(hi))));
        }
        let (mid, half) = (0.5 * (seg.a + seg.b), 0.5 * (seg.b - seg.a));
        for &(xi, wg) in &gauss {
            let (x, w) = (mid + half * xi, half * wg);
            let (s0, phi) = slave.basis(e, x);
            let (m0, phi_m) = master.basis(seg.master_edge, x);
            let mu = match &psi {
                Some((_, basis)) => basis.at(x),
                None => phi,
            };
            for (a, &mu_a) in mu.iter().enumerate().take(slave.order + 1) {
                let row = s0 + a;
                if dual {
                    // ∫ψ_a φ_c = δ_ac ∫φ_a on the covered part: D is diagonal by
                    // construction, its entry integrated with φ (free of the round-off of ψ's
                    // cancellations, which grows as (h/len)^order on a sliver).
                    add(&mut d[row], row, w * phi[a]);
                } else {
                    for (c, &phi_c) in phi.iter().enumerate().take(slave.order + 1) {
                        add(&mut d[row], s0 + c, w * mu_a * phi_c);
                    }
                }
                for (b, &phi_b) in phi_m.iter().enumerate().take(master.order + 1) {
                    add(&mut m[row], m0 + b, w * mu_a * phi_b);
                }
            }
        }
    }
    let measure = slave.measures();
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
            overlap: (lo, hi),
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
        for (j, mass_j) in mass.iter().enumerate() {
            let row: Vec<f64> = dense(&c.slave[j], 4).iter().map(|v| v * c.weight[j]).collect();
            assert!(close(&row, mass_j, 1e-15), "{j}: {row:?}");
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
}
