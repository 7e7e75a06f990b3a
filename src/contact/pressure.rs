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

/// The contact forces y_q = w_q p(x_q) at the points of `to` for the pressure `p` given at
/// the ascending abscissae `x` of another mesh's points: p piecewise linear between them and
/// constant beyond. A start for the Newton iteration of a finer or coarser mesh (the forces
/// are the iteration's state, docs/design.md §3); not a result.
pub fn carried_forces(x: &[f64], p: &[f64], to: &ContactPoints) -> Vec<f64> {
    to.points
        .iter()
        .map(|q| {
            let at = match x.partition_point(|&xi| xi < q.x) {
                _ if x.is_empty() => 0.0,
                0 => p[0],
                k if k == x.len() => p[k - 1],
                k => {
                    let t = (q.x - x[k - 1]) / (x[k] - x[k - 1]);
                    p[k - 1] + t * (p[k] - p[k - 1])
                }
            };
            q.weight * at
        })
        .collect()
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

    #[test]
    fn carried_forces_by_hand() {
        // p = 2, 4, 0 at x = 0, 1, 3; the trapezoid's points at the vertices −1, 0.5, 2, 4
        // weigh half of each neighbouring edge: 0.75, 1.5, 1.75, 1.
        let to = ContactPoints::new(Rule::Trapezoid, &[-1.0, 0.5, 2.0, 4.0], 1);
        let y = carried_forces(&[0.0, 1.0, 3.0], &[2.0, 4.0, 0.0], &to);
        let expect = [0.75 * 2.0, 1.5 * 3.0, 1.75 * 2.0, 0.0];
        for (a, b) in y.iter().zip(expect) {
            assert!((a - b).abs() < 1e-14, "{y:?}");
        }
        assert_eq!(carried_forces(&[], &[], &to), vec![0.0; 4]);
    }
}
