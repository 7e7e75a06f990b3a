//! The 2-D Cattaneo–Mindlin partial slip of a cylinder pressed by P and then loaded
//! tangentially by Q < μP, for elastically similar (or decoupled: Dundurs' β = 0) bodies
//! (Johnson, *Contact Mechanics*, §7.2; docs/design.md §11): on the Hertz contact |x| < a,
//! a central stick zone |x| < c with c/a = √(1 − Q/(μP)) and the traction
//!
//!   q(x) = μp₀√(1 − x²/a²) − μp₀ (c/a)√(1 − x²/c²)   (|x| < c),   q(x) = μ p(x)   (c ≤ |x| ≤ a),
//!
//! the full-sliding traction less a scaled copy on the stick zone. Checked here by two
//! identities independent of the formula's source: ∫q = Q, and the half-plane's surface
//! tangential strain, ∝ PV∫ q(s)/(x − s) ds, vanishes on the stick zone (it moves rigidly).

use serde::Serialize;

use super::distance::relative_l2_error;
use super::friction::State;
use super::hertz::Hertz;
use super::{ContactPoints, Obstacle};
use crate::material::Material;

/// The Cattaneo–Mindlin traction of a computed solve.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Mindlin {
    /// The Hertz contact of the load P.
    #[serde(skip)]
    pub hertz: Hertz,
    /// μ.
    #[serde(skip)]
    pub mu: f64,
    /// The stick half-width c = a√(1 − |Q|/(μP)).
    pub c: f64,
    /// The sign of Q (the traction's direction).
    #[serde(skip)]
    pub sign: f64,
}

impl Mindlin {
    /// The solution for the full-body loads P and Q with μ, pressing `obstacle` (a cylinder)
    /// into `material`; None for other shapes, or unless 0 < |Q| < μP.
    pub fn for_loads(obstacle: &Obstacle, material: &Material, p: f64, q: f64, mu: f64) -> Option<Mindlin> {
        let hertz = Hertz::for_load(obstacle, material, p)?;
        let ratio = q.abs() / (mu * p);
        if !(ratio > 0.0 && ratio < 1.0) {
            return None;
        }
        Some(Mindlin {
            hertz,
            mu,
            c: hertz.a * (1.0 - ratio).sqrt(),
            sign: q.signum(),
        })
    }

    /// q(x), zero outside the contact.
    pub fn traction(&self, x: f64) -> f64 {
        let (a, p0, c) = (self.hertz.a, self.hertz.p0, self.c);
        let r = x - self.hertz.center;
        if r.abs() >= a {
            return 0.0;
        }
        let slide = self.mu * p0 * (1.0 - (r / a).powi(2)).sqrt();
        let stick = if r.abs() < c {
            self.mu * p0 * (c / a) * (1.0 - (r / c).powi(2)).sqrt()
        } else {
            0.0
        };
        self.sign * (slide - stick)
    }

    /// ‖t̄ − q‖₀ / ‖q‖₀ over Γ_C for nodal values `tbar` at `cp`'s vertices, integrated to
    /// round-off across the square-root ends ±a and the stick zone's ends ±c
    /// ([`relative_l2_error`]).
    pub fn relative_error(&self, cp: &ContactPoints, tbar: &[f64]) -> f64 {
        let (x0, a, c) = (self.hertz.center, self.hertz.a, self.c);
        relative_l2_error(cp, tbar, |x| self.traction(x), &[x0 - a, x0 - c, x0 + c, x0 + a])
    }
}

/// Dundurs' |β| for a rigid indenter on `material`: (κ − 1)/(κ + 1) = μ/(λ + 2μ) with the
/// model's Lamé constants, (1 − 2ν)/(2(1 − ν)) in plane strain (Johnson §5.8). Cattaneo and
/// Mindlin's solution assumes β = 0, where the shear does not change the pressure.
pub fn dundurs_beta(material: &Material) -> f64 {
    let (lambda, mu) = material.lame();
    mu / (lambda + 2.0 * mu)
}

/// The computed stick zone: half the distance between the midpoints that lie outside the
/// outermost stick points (between each and its outer neighbour), and the number of runs of
/// consecutive stick points (1 for one zone); None with no stick point.
pub fn stick_half_width(cp: &ContactPoints, states: &[State]) -> Option<(f64, usize)> {
    stick_extent(cp, states).map(|(left, right, runs)| (0.5 * (right - left), runs))
}

/// The computed stick zone's ends (the midpoints outside its outermost stick points, or
/// the outermost point itself at an end of Γ_C) and its number of runs; None with no stick
/// point. [`stick_half_width`] is half the distance between the ends.
pub fn stick_extent(cp: &ContactPoints, states: &[State]) -> Option<(f64, f64, usize)> {
    let stick: Vec<usize> = (0..states.len()).filter(|&q| states[q] == State::Stick).collect();
    let (&first, &last) = (stick.first()?, stick.last()?);
    let x = |q: usize| cp.points[q].x;
    let left = if first == 0 {
        x(0)
    } else {
        0.5 * (x(first - 1) + x(first))
    };
    let right = if last + 1 == states.len() {
        x(last)
    } else {
        0.5 * (x(last) + x(last + 1))
    };
    let runs = 1 + stick.windows(2).filter(|w| w[1] != w[0] + 1).count();
    Some((left, right, runs))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::quadrature::gauss_legendre;
    use crate::material::Plane;

    /// β by hand: ν = 0.3 in plane strain, 0.4/1.4; in plane stress (1 − ν)/2; ν = ½ − 10⁻³
    /// (cattaneo-mindlin's 0.499) about 10⁻³.
    #[test]
    fn dundurs_beta_by_hand() {
        let at = |poisson, plane| {
            dundurs_beta(&Material {
                young: 1000.0,
                poisson,
                plane,
            })
        };
        assert!((at(0.3, Plane::Strain) - 0.4 / 1.4).abs() < 1e-15);
        assert!((at(0.3, Plane::Stress) - 0.35).abs() < 1e-15);
        assert!((at(0.499, Plane::Strain) - 0.002 / 1.002).abs() < 1e-15);
    }

    fn mindlin(q_over_mup: f64) -> Mindlin {
        let material = Material {
            young: 1000.0,
            poisson: 0.3,
            plane: Plane::Strain,
        };
        let obstacle = Obstacle::Cylinder {
            radius: 10.0,
            depth: 0.3,
            center: 0.0,
        };
        let (p, mu) = (20.0, 0.3);
        Mindlin::for_loads(&obstacle, &material, p, q_over_mup * mu * p, mu).unwrap()
    }

    /// ∫ over [lo, hi] of f by 16-point Gauss on `n` equal pieces.
    fn integrate(f: impl Fn(f64) -> f64, lo: f64, hi: f64, n: usize) -> f64 {
        let g = gauss_legendre(16);
        let h = (hi - lo) / n as f64;
        (0..n)
            .map(|i| {
                let x0 = lo + i as f64 * h;
                g.iter()
                    .map(|&(xi, w)| w * h / 2.0 * f(x0 + h * (xi + 1.0) / 2.0))
                    .sum::<f64>()
            })
            .sum()
    }

    /// ∫q dx = Q (the tangential load), by quadrature on x = a sin θ, where the √ edges are
    /// smooth; c → a as Q → 0 and c → 0 as Q → μP; q is continuous at ±c.
    #[test]
    fn the_traction_carries_q() {
        for ratio in [0.1, 0.5, 0.9] {
            let m = mindlin(ratio);
            let a = m.hertz.a;
            let p_total = std::f64::consts::PI * a * m.hertz.p0 / 2.0;
            // Split at ±c (q's kink): x = a sin θ on the slip zones, x = c sin φ on the stick
            // zone, so that every √ edge is smooth in the variable.
            let tc = (m.c / a).asin();
            let outer = |t: f64| m.traction(a * t.sin()) * a * t.cos();
            let inner = |t: f64| m.traction(m.c * t.sin()) * m.c * t.cos();
            let half = std::f64::consts::FRAC_PI_2;
            let total = integrate(outer, -half, -tc, 200)
                + integrate(inner, -half, half, 200)
                + integrate(outer, tc, half, 200);
            let q = ratio * m.mu * p_total;
            assert!((total - q).abs() <= 1e-8 * q, "{ratio}: {total} vs {q}");
            let (below, above) = (m.traction(m.c * (1.0 - 1e-12)), m.traction(m.c * (1.0 + 1e-12)));
            assert!((below - above).abs() <= 1e-5 * m.mu * m.hertz.p0);
        }
        assert!((mindlin(1e-9).c / mindlin(1e-9).hertz.a - 1.0).abs() < 1e-8);
        assert!(mindlin(1.0 - 1e-9).c / mindlin(1.0 - 1e-9).hertz.a < 1e-4);
    }

    /// On the stick zone the half-plane's surface tangential strain, ∝ PV∫_{−a}^{a}
    /// q(s)/(x − s) ds, is zero: the stick zone moves as one (it does not in the slip zone).
    /// The principal value as ∫(q(s) − q(x))/(x − s) ds + q(x) ln((x + a)/(a − x)).
    #[test]
    fn the_stick_zone_moves_rigidly() {
        let m = mindlin(0.5);
        let (a, c) = (m.hertz.a, m.c);
        let pv = |x: f64| {
            let qx = m.traction(x);
            let f = |s: f64| {
                if s == x {
                    0.0
                } else {
                    (m.traction(s) - qx) / (x - s)
                }
            };
            // Pieces between the kinks (±c), the edges (±a) and x, each on θ where √ edges sit.
            let mut cuts = [-a, -c, c, a, x];
            cuts.sort_by(f64::total_cmp);
            let smooth = cuts
                .windows(2)
                .map(|w| integrate(f, w[0], w[1], 400))
                .sum::<f64>();
            smooth + qx * ((x + a) / (a - x)).ln()
        };
        let scale = m.mu * m.hertz.p0;
        for frac in [0.0, 0.1, 0.3, 0.5, 0.65, 0.9] {
            let x = frac * c;
            assert!(pv(x).abs() <= 1e-3 * scale, "x = {x}: {}", pv(x));
        }
        // In the slip zone it is not zero.
        assert!(pv(0.5 * (a + c)).abs() > 0.05 * scale);
    }
}
