//! A flat rigid punch with rounded corners on an elastic half-plane, in closed form
//! (M. Ciavarella, D. A. Hills and G. Monno, "The influence of rounded edges on indentation by
//! a flat punch", Proc. IMechE C 212 (1998) 319–328): a flat face |x| < b with corners of
//! radius R, taken as parabolas h = (|x| − b)²/2R, in contact on |x| < a. With
//! sin φ₀ = b/a and x = a sin φ the half-plane's integrals (src/contact/half_plane.rs) give
//!
//!   P = (E*a²/2R) (π/2 − φ₀ − sin φ₀ cos φ₀),
//!   p(φ) = (E*a/2πR) [(π − 2φ₀) cos φ − (sin φ − sin φ₀) ln|sin((φ₀ − φ)/2)/cos((φ₀ + φ)/2)|
//!                      + (sin φ + sin φ₀) ln|sin((φ₀ + φ)/2)/cos((φ − φ₀)/2)|],
//!
//! bounded at both ends and peaking near the corners; b = 0 is Hertz. riplab's punch has
//! circular corners: their parabola is exact to (a − b)²/4R² in h″, 2e-4 for
//! scenarios/rounded-punch.toml.

use super::distance::relative_l2_error;
use super::{ContactPoints, Obstacle, half_plane};
use crate::material::Material;

/// The rounded punch's contact for a given load.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoundedPunch {
    /// The contact half-width a > b.
    pub a: f64,
    /// The flat face's half-width b.
    pub face: f64,
    /// The corners' radius R.
    pub radius: f64,
    /// The plane modulus E*.
    pub e_star: f64,
    /// The centre of the face.
    pub center: f64,
}

impl RoundedPunch {
    /// The load P = (E*a²/2R)(π/2 − φ₀ − sin φ₀ cos φ₀), sin φ₀ = b/a, of a contact of
    /// half-width `a` ≥ `face`.
    pub fn load_of(e_star: f64, face: f64, radius: f64, a: f64) -> f64 {
        let phi0 = (face / a).min(1.0).asin();
        e_star * a * a / (2.0 * radius) * (std::f64::consts::FRAC_PI_2 - phi0 - phi0.sin() * phi0.cos())
    }

    /// The contact of a punch `obstacle` pressed into `material` by the full-body load
    /// `full_load`; None for other shapes, no load, or a contact beyond the corners' quarter
    /// circles (a − b ≥ R/2, where the parabola no longer describes them).
    pub fn for_load(obstacle: &Obstacle, material: &Material, full_load: f64) -> Option<RoundedPunch> {
        let Obstacle::Punch {
            half_width,
            corner_radius,
            center,
            ..
        } = *obstacle
        else {
            return None;
        };
        if full_load.is_nan() || full_load <= 0.0 {
            return None;
        }
        let e_star = half_plane::e_star(material);
        let most = half_width + corner_radius / 2.0;
        if full_load > Self::load_of(e_star, half_width, corner_radius, most) {
            return None;
        }
        let a = half_plane::invert(
            |a| Self::load_of(e_star, half_width, corner_radius, a),
            full_load,
            half_width,
            most,
        );
        Some(RoundedPunch {
            a,
            face: half_width,
            radius: corner_radius,
            e_star,
            center,
        })
    }

    /// p(x), zero outside the contact.
    pub fn pressure(&self, x: f64) -> f64 {
        let s = (x - self.center) / self.a;
        if s.abs() >= 1.0 {
            return 0.0;
        }
        let (phi, phi0) = (s.asin(), (self.face / self.a).asin());
        // f ln|num/den|, 0 where f = 0 (at the corners' start, where num = 0 too).
        let f_ln = |f: f64, num: f64, den: f64| {
            if f == 0.0 {
                0.0
            } else {
                f * (num.abs() / den.abs()).ln()
            }
        };
        let bracket = (std::f64::consts::PI - 2.0 * phi0) * phi.cos()
            - f_ln(
                phi.sin() - phi0.sin(),
                ((phi0 - phi) / 2.0).sin(),
                ((phi0 + phi) / 2.0).cos(),
            )
            + f_ln(
                phi.sin() + phi0.sin(),
                ((phi0 + phi) / 2.0).sin(),
                ((phi - phi0) / 2.0).cos(),
            );
        self.e_star * self.a / (2.0 * std::f64::consts::PI * self.radius) * bracket
    }

    /// The largest pressure, just beyond the corners' start |x − c| = b (where p′ is
    /// infinite): sampled on [b, a], then the best sample's neighbourhood by golden section.
    pub fn peak(&self) -> f64 {
        let n = 1000;
        let at = |i: usize| self.face + (self.a - self.face) * i as f64 / n as f64;
        let best = (0..=n)
            .max_by(|&i, &j| {
                self.pressure(self.center + at(i))
                    .total_cmp(&self.pressure(self.center + at(j)))
            })
            .unwrap_or(0);
        let (mut lo, mut hi) = (at(best.saturating_sub(1)), at((best + 1).min(n)));
        let ratio = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..80 {
            let (m1, m2) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
            if self.pressure(self.center + m1) < self.pressure(self.center + m2) {
                lo = m1;
            } else {
                hi = m2;
            }
        }
        self.pressure(self.center + (lo + hi) / 2.0)
    }

    /// ‖p̄ − p‖₀ / ‖p‖₀ over Γ_C for nodal values `pbar` at `cp`'s vertices, integrated to
    /// round-off across the square-root ends c ± a and the corners' starts c ± b, where p′ is
    /// infinite ([`relative_l2_error`]).
    pub fn relative_error(&self, cp: &ContactPoints, pbar: &[f64]) -> f64 {
        let (c, a, b) = (self.center, self.a, self.face);
        relative_l2_error(cp, pbar, |x| self.pressure(x), &[c - a, c - b, c + b, c + a])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Plane;

    /// The closed form equals the half-plane's integrals by quadrature (a derivation
    /// independent of the closed form's logarithms), and b → 0 is Hertz.
    #[test]
    fn the_closed_form_is_the_half_planes_integral() {
        let material = Material {
            young: 1000.0,
            poisson: 0.3,
            plane: Plane::Strain,
        };
        let (b, r) = (1.0, 20.0);
        let e = half_plane::e_star(&material);
        let slope = |s: f64| {
            let t = s.abs() - b;
            if t > 0.0 { t * s.signum() / r } else { 0.0 }
        };
        let curvature = |s: f64| if s.abs() > b { 1.0 / r } else { 0.0 };
        let a = 1.4;
        let p = RoundedPunch::load_of(e, b, r, a);
        // h′ has a kink at ±b: the quadrature converges as n⁻², hence many points.
        let quadrature = half_plane::load(e, a, slope, 20000);
        assert!((p - quadrature).abs() < 1e-6 * p, "{p} vs {quadrature}");
        let punch = Obstacle::Punch {
            half_width: b,
            corner_radius: r,
            depth: 0.1,
            center: 0.0,
        };
        let c = RoundedPunch::for_load(&punch, &material, p).unwrap();
        assert!((c.a - a).abs() < 1e-12);
        for x in [0.0, 0.5, 0.99, 1.01, 1.2, -1.35] {
            let q = half_plane::pressure(e, a, slope, curvature, x, 20000);
            assert!(
                (c.pressure(x) - q).abs() < 1e-4 * c.peak(),
                "x = {x}: {} vs {q}",
                c.pressure(x)
            );
        }
        assert!(c.peak() > c.pressure(1.0) && c.peak() >= c.pressure(1.02));
        assert!(c.peak() > c.pressure(0.0) && c.peak() > c.pressure(1.1));
        assert_eq!(c.pressure(1.4), 0.0);
        // A vanishing face: Hertz's p₀ = aE*/2R.
        let hertz = RoundedPunch {
            a,
            face: 1e-12,
            radius: r,
            e_star: e,
            center: 0.0,
        };
        assert!((hertz.pressure(0.0) - a * e / (2.0 * r)).abs() < 1e-9 * e);
    }
}
