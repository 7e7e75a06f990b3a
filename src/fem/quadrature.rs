//! Gauss–Legendre quadrature on [-1, 1] and the collapsed (Duffy) rule on a triangle.

/// Gauss–Legendre points and weights on [-1, 1] with `n` points (exact for degree 2n − 1).
///
/// Computed by Newton's method on the Legendre polynomial Pₙ, which converges to machine
/// precision from the Chebyshev initial guesses for every n used here.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    assert!(n >= 1, "a Gauss rule needs at least one point");
    let mut rule = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = -(std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (p, d) = legendre(n, x);
            dp = d;
            let dx = p / d;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        let (_, d) = legendre(n, x);
        dp = if d != 0.0 { d } else { dp };
        rule.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    rule
}

/// Pₙ(x) and Pₙ'(x) by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let k = k as f64;
        let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    let d = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, d)
}

/// A rule on the reference triangle {(r, s): r, s ≥ 0, r + s ≤ 1}: points (r, s) and weights
/// summing to 1/2, from the n × n Gauss rule on the square collapsed onto the triangle
/// (exact for polynomials of degree 2n − 2).
pub fn triangle_rule(n: usize) -> Vec<(f64, f64, f64)> {
    let g = gauss_legendre(n);
    let mut rule = Vec::with_capacity(n * n);
    for &(a, wa) in &g {
        for &(b, wb) in &g {
            let (u, v) = ((a + 1.0) / 2.0, (b + 1.0) / 2.0);
            // (u, v) ∈ [0,1]² ↦ (r, s) = (u, v(1 − u)), Jacobian (1 − u).
            rule.push((u, v * (1.0 - u), wa * wb / 4.0 * (1.0 - u)));
        }
    }
    rule
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_is_exact_to_degree_2n_minus_1() {
        for n in 1..=8 {
            let rule = gauss_legendre(n);
            for deg in 0..2 * n {
                let num: f64 = rule.iter().map(|&(x, w)| w * x.powi(deg as i32)).sum();
                let exact = if deg % 2 == 1 {
                    0.0
                } else {
                    2.0 / (deg as f64 + 1.0)
                };
                assert!((num - exact).abs() < 1e-14, "n={n} deg={deg}: {num} vs {exact}");
            }
        }
    }

    #[test]
    fn triangle_rule_integrates_monomials() {
        // ∫_T r^a s^b = a! b! / (a + b + 2)!
        let fact = |k: u32| (1..=k).map(f64::from).product::<f64>();
        let rule = triangle_rule(4);
        for a in 0..=3u32 {
            for b in 0..=(6 - a).min(3) {
                let num: f64 = rule
                    .iter()
                    .map(|&(r, s, w)| w * r.powi(a as i32) * s.powi(b as i32))
                    .sum();
                let exact = fact(a) * fact(b) / fact(a + b + 2);
                assert!((num - exact).abs() < 1e-15, "r^{a} s^{b}: {num} vs {exact}");
            }
        }
    }
}
