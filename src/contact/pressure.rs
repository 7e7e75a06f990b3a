//! Contact pressures (docs/design.md §4): the raw pressure p at the rule's points (12), the smoothed
//! nodal pressure p̄ of (16)–(17), the load P, and the trapezoid form Î of (18).

use super::rule::ContactPoints;

/// p_q = (1/ε)(u_n(x_q) − g(x_q))⁺ ≥ 0, compression positive (12); `violation` is u_n − g.
pub fn raw_pressure(violation: &[f64], epsilon: f64) -> Vec<f64> {
    violation.iter().map(|&s| s.max(0.0) / epsilon).collect()
}

/// p̄_i = I(p, φ_i) / I(1, φ_i) at the vertices of Γ_C, φ_i the vertex hat function: the
/// nodal contact force over the node's tributary length. For one-point Gauss this is exactly
/// the weighted average (17); for the trapezoid rule it is the identity.
pub fn smoothed_pressure(cp: &ContactPoints, p: &[f64]) -> Vec<f64> {
    let n = cp.vertex_x.len();
    let (mut force, mut length) = (vec![0.0; n], vec![0.0; n]);
    for (q, &pq) in cp.points.iter().zip(p) {
        for (i, phi) in cp.hats_at(q) {
            force[i] += q.weight * pq * phi;
            length[i] += q.weight * phi;
        }
    }
    force.iter().zip(&length).map(|(f, l)| f / l).collect()
}

/// The load carried by the modelled body, P = I(p, 1).
pub fn load(cp: &ContactPoints, p: &[f64]) -> f64 {
    cp.points.iter().zip(p).map(|(q, pq)| q.weight * pq).sum()
}

/// I(q, v) of (10) for q at the rule's points and a function v evaluated there.
pub fn rule_product(cp: &ContactPoints, q: &[f64], v_at_points: &[f64]) -> f64 {
    cp.points
        .iter()
        .zip(q)
        .zip(v_at_points)
        .map(|((pt, a), b)| pt.weight * a * b)
        .sum()
}

/// Î(a, b) of (18): the trapezoid rule for nodal values a, b at the vertices `x`.
pub fn trapezoid_product(x: &[f64], a: &[f64], b: &[f64]) -> f64 {
    (0..x.len() - 1)
        .map(|e| (x[e + 1] - x[e]) / 2.0 * (a[e] * b[e] + a[e + 1] * b[e + 1]))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::rule::Rule;

    #[test]
    fn gauss1_smoothing_is_formula_17() {
        let x = [0.0, 1.0, 3.0, 3.5];
        let cp = ContactPoints::new(Rule::Gauss1, &x, 1);
        let q = [2.0, 5.0, 7.0];
        let pbar = smoothed_pressure(&cp, &q);
        let expect = [
            2.0,
            (1.0 * 2.0 + 2.0 * 5.0) / 3.0,
            (2.0 * 5.0 + 0.5 * 7.0) / 2.5,
            7.0,
        ];
        for (a, b) in pbar.iter().zip(expect) {
            assert!((a - b).abs() < 1e-14, "{pbar:?}");
        }
    }

    #[test]
    fn trapezoid_smoothing_is_identity() {
        let x = [0.0, 0.3, 1.0, 1.1];
        let cp = ContactPoints::new(Rule::Trapezoid, &x, 1);
        let p = [1.0, 4.0, 2.0, 0.5];
        let pbar = smoothed_pressure(&cp, &p);
        for (a, b) in pbar.iter().zip(p) {
            assert!((a - b).abs() < 1e-14);
        }
    }
}
