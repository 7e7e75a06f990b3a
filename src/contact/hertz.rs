//! The plane-strain (or plane-stress) Hertz solution for a cylinder on a half-space
//! (docs/design.md §6): for the full-body load P per unit length, a² = 4PR/(πE*), p₀ = 2P/(πa),
//! p(x) = p₀√(1 − (x − c)²/a²), with E* = E/(1 − ν²) in plane strain and E in plane stress.

use serde::Serialize;

use super::distance::relative_l2_error;
use super::{ContactPoints, Obstacle};
use crate::material::Material;

/// The Hertz contact half-width, peak pressure and centre for a given load.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Hertz {
    /// The contact half-width a = √(4PR/(πE*)).
    pub a: f64,
    /// The peak pressure p₀ = 2P/(πa), at the centre.
    pub p0: f64,
    /// The centre c of the contact: x of the obstacle's lowest point.
    pub center: f64,
}

impl Hertz {
    /// The profile for the full-body load `full_load` pressing `obstacle` (a cylinder) into
    /// `material`; None for other shapes or no load.
    pub fn for_load(obstacle: &Obstacle, material: &Material, full_load: f64) -> Option<Hertz> {
        let radius = obstacle.hertz_radius()?;
        if full_load.is_nan() || full_load <= 0.0 {
            return None;
        }
        let e_star = super::half_plane::e_star(material);
        let a = (4.0 * full_load * radius / (std::f64::consts::PI * e_star)).sqrt();
        Some(Hertz {
            a,
            p0: 2.0 * full_load / (std::f64::consts::PI * a),
            center: obstacle.center(),
        })
    }

    /// p(x), zero outside the contact.
    pub fn pressure(&self, x: f64) -> f64 {
        let r = (x - self.center) / self.a;
        if r.abs() < 1.0 {
            self.p0 * (1.0 - r * r).sqrt()
        } else {
            0.0
        }
    }

    /// ‖p̄ − p_Hertz‖₀ / ‖p_Hertz‖₀ over Γ_C for nodal values `pbar` at `cp`'s vertices,
    /// integrated to round-off across the square-root ends c ± a ([`relative_l2_error`]);
    /// NaN for a contact too small to have a norm.
    pub fn relative_error(&self, cp: &ContactPoints, pbar: &[f64]) -> f64 {
        relative_l2_error(cp, pbar, |x| self.pressure(x), &self.ends())
    }

    /// The contact's ends c ± a, where p falls to 0 as a square root.
    pub fn ends(&self) -> [f64; 2] {
        [self.center - self.a, self.center + self.a]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Rule;
    use crate::material::Plane;

    #[test]
    fn formulas_by_hand() {
        let m = Material {
            young: 1000.0,
            poisson: 0.0,
            plane: Plane::Strain,
        };
        let c = Obstacle::Cylinder {
            radius: 10.0,
            depth: 0.1,
            center: 0.0,
        };
        // P = 25π: a² = 4·25π·10/(1000π) = 1, a = 1, p₀ = 50π/π = 50.
        let h = Hertz::for_load(&c, &m, 25.0 * std::f64::consts::PI).unwrap();
        assert!((h.a - 1.0).abs() < 1e-15 && (h.p0 - 50.0).abs() < 1e-12);
        assert!((h.pressure(0.6) - 40.0).abs() < 1e-12);
        assert_eq!(h.pressure(1.2), 0.0);
        // The exact profile sampled at fine vertices is within interpolation error of itself.
        let x: Vec<f64> = (0..=400).map(|i| -2.0 + i as f64 / 100.0).collect();
        let cp = ContactPoints::new(Rule::Trapezoid, &x, 1);
        let p: Vec<f64> = x.iter().map(|&x| h.pressure(x)).collect();
        assert!(h.relative_error(&cp, &p) < 5e-3);
        assert!(
            Hertz::for_load(
                &Obstacle::Punch {
                    half_width: 1.0,
                    corner_radius: 0.5,
                    depth: 0.1,
                    center: 0.0
                },
                &m,
                1.0
            )
            .is_none()
        );
    }
}
