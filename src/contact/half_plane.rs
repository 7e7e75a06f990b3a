//! A rigid punch of smooth symmetric profile h(x) pressed into an elastic half-plane, without
//! friction: the reference solutions that riplab's pressures are compared with (`riplab
//! verify`, the `hertz` object of docs/design.md §7).
//!
//! Within the contact |x| < a the surface displacement follows the punch, which makes the
//! pressure the solution of the half-plane's singular integral equation
//! h′(x) = (2/(πE*)) PV∫ p(s)/(x − s) ds. Its solution bounded at both ends (Johnson,
//! *Contact Mechanics*, 1985, §2.8 and ch. 5; Barber, *Contact Mechanics*, 2018, ch. on 2-D
//! punch problems) is
//!
//!   p(x) = (E*/2π) √(a² − x²) PV∫ h′(s) / ((s − x)√(a² − s²)) ds,
//!
//! and its consistency condition gives the load, P = (E*/2) ∫ s h′(s)/√(a² − s²) ds. For
//! Hertz's parabola h = x²/2R these are p = p₀√(1 − x²/a²) and P = πa²E*/4R. Both integrals
//! carry the weight 1/√(a² − s²), which Gauss–Chebyshev quadrature integrates exactly: with
//! the principal value removed (PV∫ ds/((s − x)√(a² − s²)) = 0 for |x| < a) the integrands are
//! as smooth as h′, and for the circle, whose h′ is analytic on [−a, a], the quadrature
//! converges exponentially.

use crate::material::{Material, Plane};

/// The plane modulus E* = E/(1 − ν²) in plane strain, E in plane stress.
pub fn e_star(material: &Material) -> f64 {
    match material.plane {
        Plane::Strain => material.young / (1.0 - material.poisson * material.poisson),
        Plane::Stress => material.young,
    }
}

/// The n Gauss–Chebyshev nodes on [−a, a]: ∫ f(s)/√(a² − s²) ds ≈ (π/n) Σ f(sᵢ).
fn chebyshev_nodes(a: f64, n: usize) -> impl Iterator<Item = f64> {
    (1..=n).map(move |i| a * ((2 * i - 1) as f64 * std::f64::consts::PI / (2 * n) as f64).cos())
}

/// The load P = (E*/2) ∫ s h′(s)/√(a² − s²) ds of a punch of slope `slope` = h′ in contact
/// on |x| < a, by `n`-point Gauss–Chebyshev quadrature.
pub fn load(e_star: f64, a: f64, slope: impl Fn(f64) -> f64, n: usize) -> f64 {
    let sum: f64 = chebyshev_nodes(a, n).map(|s| s * slope(s)).sum();
    e_star / 2.0 * std::f64::consts::PI / n as f64 * sum
}

/// The pressure p(x) of a punch of slope `slope` = h′ and curvature `curvature` = h″ in
/// contact on |x| < a, by `n`-point Gauss–Chebyshev quadrature of the regular integral
/// ∫ (h′(s) − h′(x))/((s − x)√(a² − s²)) ds; zero outside the contact.
pub fn pressure(
    e_star: f64,
    a: f64,
    slope: impl Fn(f64) -> f64,
    curvature: impl Fn(f64) -> f64,
    x: f64,
    n: usize,
) -> f64 {
    if x.abs() >= a {
        return 0.0;
    }
    let hx = slope(x);
    let sum: f64 = chebyshev_nodes(a, n)
        .map(|s| {
            if (s - x).abs() < 1e-12 * a {
                curvature(x)
            } else {
                (slope(s) - hx) / (s - x)
            }
        })
        .sum();
    e_star / (2.0 * std::f64::consts::PI) * (a * a - x * x).sqrt() * std::f64::consts::PI / n as f64 * sum
}

/// The complete elliptic integrals K(k) and E(k) of modulus k (0 ≤ k < 1), by the
/// arithmetic–geometric mean (Abramowitz & Stegun 17.6): K = π/(2 AGM(1, k′)),
/// E = K (1 − Σ 2ⁿ⁻¹ cₙ²).
pub fn elliptic_ke(k: f64) -> (f64, f64) {
    let (big_k, k_minus_e) = elliptic_k_minus_e(k);
    (big_k, big_k - k_minus_e)
}

/// K(k) and K(k) − E(k) = K Σ 2ⁿ⁻¹ cₙ², the difference without the cancellation of K − E
/// ≈ πk²/4 for small k.
pub fn elliptic_k_minus_e(k: f64) -> (f64, f64) {
    let (mut a, mut b, mut c) = (1.0_f64, (1.0 - k * k).sqrt(), k);
    let (mut sum, mut weight) = (0.5 * c * c, 0.5);
    // Until a and b agree to round-off: beyond, c = (a − b)/2 is round-off, which the
    // doubling weights would amplify.
    for _ in 0..64 {
        if c.abs() <= f64::EPSILON * a {
            break;
        }
        let (a1, b1) = ((a + b) / 2.0, (a * b).sqrt());
        c = (a - b) / 2.0;
        weight *= 2.0;
        sum += weight * c * c;
        (a, b) = (a1, b1);
    }
    let big_k = std::f64::consts::PI / (2.0 * a);
    (big_k, big_k * sum)
}

/// The x in (lo, hi) where the increasing `f` equals `target`, by bisection to round-off:
/// from lo = 0 that can take a halving per binary exponent down to the smallest double
/// (about 2,100), where 200 halvings stopped at 2⁻²⁰⁰ hi (a contact of 1e-150 read 2e-60).
pub fn invert(f: impl Fn(f64) -> f64, target: f64, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..2200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::quadrature::gauss_legendre;

    /// ∫₀^{π/2} f(φ) dφ by 8-point Gauss–Legendre on 64 panels.
    fn quarter(f: impl Fn(f64) -> f64) -> f64 {
        let (n, w) = (64, std::f64::consts::FRAC_PI_2 / 64.0);
        let g = gauss_legendre(8);
        (0..n)
            .flat_map(|i| g.iter().map(move |&(xi, wi)| (i, xi, wi)))
            .map(|(i, xi, wi)| wi * w / 2.0 * f(w * (i as f64 + (xi + 1.0) / 2.0)))
            .sum()
    }

    #[test]
    fn the_agm_gives_legendres_integrals() {
        for k in [0.0, 0.1, 0.5, 0.9, 0.99] {
            let (big_k, big_e) = elliptic_ke(k);
            let kq = quarter(|p| 1.0 / (1.0 - k * k * p.sin().powi(2)).sqrt());
            let eq = quarter(|p| (1.0 - k * k * p.sin().powi(2)).sqrt());
            assert!(
                (big_k - kq).abs() < 1e-13 && (big_e - eq).abs() < 1e-13,
                "k = {k}"
            );
        }
    }

    #[test]
    fn the_parabola_gives_hertz() {
        // h = x²/2R: p = E*√(a² − x²)/2R, P = πa²E*/4R.
        let (e, a, r) = (1000.0, 1.3, 10.0);
        let p_load = load(e, a, |s| s / r, 16);
        assert!((p_load - std::f64::consts::PI * a * a * e / (4.0 * r)).abs() < 1e-12 * p_load);
        for x in [0.0, 0.4, -1.1, 1.29] {
            let p = pressure(e, a, |s| s / r, |_| 1.0 / r, x, 16);
            let hertz = e * (a * a - x * x).sqrt() / (2.0 * r);
            assert!((p - hertz).abs() < 1e-12 * e, "{x}: {p} vs {hertz}");
        }
        assert_eq!(pressure(e, a, |s| s / r, |_| 1.0 / r, 1.3, 16), 0.0);
    }

    #[test]
    fn bisection_inverts() {
        let x = invert(|x| x * x * x, 2.0, 0.0, 5.0);
        assert!((x - 2f64.cbrt()).abs() < 1e-15);
    }
}
