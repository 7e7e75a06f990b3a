//! The exact rigid circular cylinder on an elastic half-plane (src/contact/half_plane.rs):
//! the profile h(x) = R − √(R² − x²), not Hertz's parabola x²/2R. For contact on |x| < a,
//! k = a/R, the load is P = E*R [K(k) − E(k)] and the peak pressure p₀ = E*a K(k)/(πR)
//! (the half-plane's integrals in closed form, K and E the complete elliptic integrals); the
//! profile p(x) is the Gauss–Chebyshev quadrature of its integral. As a/R → 0 these tend to
//! Hertz's a² = 4PR/(πE*) and p₀ = 2P/(πa); at a/R = 0.11 (scenarios/hertz-block.toml) the
//! parabola's pressure is 4.7e-3 off in L², more than the finite element error from level 4 on.

use super::distance::relative_l2_error;
use super::{ContactPoints, Obstacle, half_plane};
use crate::material::Material;

/// Gauss–Chebyshev points of the profile's quadrature: h′ is analytic on [−a, a] with its
/// singularities at ±R, so 64 points give p to round-off for a/R ≤ 0.9.
const QUADRATURE_POINTS: usize = 64;

/// The exact circular indenter's contact for a given load.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CircleContact {
    /// The contact half-width a, from P = E*R [K(a/R) − E(a/R)].
    pub a: f64,
    /// The peak pressure p₀ = E*a K(a/R)/(πR), at the centre.
    pub p0: f64,
    /// The cylinder's radius R.
    pub radius: f64,
    /// The plane modulus E*.
    pub e_star: f64,
    /// The centre of the contact: the cylinder's axis.
    pub center: f64,
}

impl CircleContact {
    /// The load P = E*R [K(k) − E(k)], k = a/R, that makes a contact of half-width `a`.
    pub fn load_of(e_star: f64, radius: f64, a: f64) -> f64 {
        e_star * radius * half_plane::elliptic_k_minus_e(a / radius).1
    }

    /// The contact of a cylinder `obstacle` pressed into `material` by the full-body load
    /// `full_load`; None for other shapes, no load, or a load that would bury the cylinder
    /// beyond a = 0.9 R (where the half-plane's small strains no longer hold either).
    pub fn for_load(obstacle: &Obstacle, material: &Material, full_load: f64) -> Option<CircleContact> {
        let radius = obstacle.hertz_radius()?;
        if full_load.is_nan() || full_load <= 0.0 {
            return None;
        }
        let e_star = half_plane::e_star(material);
        let most = 0.9 * radius;
        if full_load > Self::load_of(e_star, radius, most) {
            return None;
        }
        let a = half_plane::invert(|a| Self::load_of(e_star, radius, a), full_load, 0.0, most);
        let (big_k, _) = half_plane::elliptic_ke(a / radius);
        Some(CircleContact {
            a,
            p0: e_star * a * big_k / (std::f64::consts::PI * radius),
            radius,
            e_star,
            center: obstacle.center(),
        })
    }

    /// p(x), zero outside the contact.
    pub fn pressure(&self, x: f64) -> f64 {
        let r2 = self.radius * self.radius;
        half_plane::pressure(
            self.e_star,
            self.a,
            |s| s / (r2 - s * s).sqrt(),
            |s| r2 / (r2 - s * s).powf(1.5),
            x - self.center,
            QUADRATURE_POINTS,
        )
    }

    /// ‖p̄ − p‖₀ / ‖p‖₀ over Γ_C for nodal values `pbar` at `cp`'s vertices, integrated to
    /// round-off across the square-root ends c ± a ([`relative_l2_error`]).
    pub fn relative_error(&self, cp: &ContactPoints, pbar: &[f64]) -> f64 {
        relative_l2_error(
            cp,
            pbar,
            |x| self.pressure(x),
            &[self.center - self.a, self.center + self.a],
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::hertz::Hertz;
    use crate::fem::quadrature::gauss_legendre;
    use crate::material::Plane;

    const MATERIAL: Material = Material {
        young: 1000.0,
        poisson: 0.3,
        plane: Plane::Strain,
    };

    fn cylinder(radius: f64) -> Obstacle {
        Obstacle::Cylinder {
            radius,
            depth: 0.1,
            center: 0.5,
        }
    }

    /// The closed-form load equals the quadrature of the consistency condition, the profile
    /// carries that load (∫p dx = P), its peak is the closed-form p₀, and a small contact is
    /// Hertz's.
    #[test]
    fn the_circle_is_in_equilibrium_and_tends_to_hertz() {
        let radius = 10.0;
        for a in [0.05, 1.1, 5.0] {
            let e = half_plane::e_star(&MATERIAL);
            let p = CircleContact::load_of(e, radius, a);
            let quadrature = half_plane::load(e, a, |s| s / (radius * radius - s * s).sqrt(), 64);
            assert!((p - quadrature).abs() < 1e-12 * p, "a = {a}: {p} vs {quadrature}");
            let c = CircleContact::for_load(&cylinder(radius), &MATERIAL, p).unwrap();
            assert!((c.a - a).abs() < 1e-12 * a, "{} vs {a}", c.a);
            assert!((c.pressure(0.5) - c.p0).abs() < 1e-12 * c.p0);
            // ∫p dx with x = c + a sin φ (the edges' square roots become smooth).
            let g = gauss_legendre(8);
            let panels = 32;
            let w = std::f64::consts::PI / panels as f64;
            let carried: f64 = (0..panels)
                .flat_map(|i| g.iter().map(move |&(xi, wi)| (i, xi, wi)))
                .map(|(i, xi, wi)| {
                    let phi = -std::f64::consts::FRAC_PI_2 + w * (i as f64 + (xi + 1.0) / 2.0);
                    wi * w / 2.0 * c.pressure(0.5 + a * phi.sin()) * a * phi.cos()
                })
                .sum();
            assert!(
                (carried - p).abs() < 1e-10 * p,
                "a = {a}: ∫p = {carried}, P = {p}"
            );
        }
        let e = half_plane::e_star(&MATERIAL);
        let p = CircleContact::load_of(e, radius, 0.01);
        let c = CircleContact::for_load(&cylinder(radius), &MATERIAL, p).unwrap();
        let h = Hertz::for_load(&cylinder(radius), &MATERIAL, p).unwrap();
        assert!((c.a - h.a).abs() < 1e-5 * h.a && (c.p0 - h.p0).abs() < 1e-5 * h.p0);
        // A load of 1e-295 (a ~ 1e-150): Hertz's to round-off (it read a = 2e-60).
        let c = CircleContact::for_load(&cylinder(radius), &MATERIAL, 1e-295).unwrap();
        let h = Hertz::for_load(&cylinder(radius), &MATERIAL, 1e-295).unwrap();
        assert!((c.a - h.a).abs() < 1e-12 * h.a, "{} vs {}", c.a, h.a);
        assert!(CircleContact::for_load(&cylinder(radius), &MATERIAL, 1e9).is_none());
        assert!(CircleContact::for_load(&cylinder(radius), &MATERIAL, 0.0).is_none());
    }
}
