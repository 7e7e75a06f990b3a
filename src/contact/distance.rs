//! The L²(Γ_C) distance of a computed profile (p̄, t̄: continuous and piecewise linear on Γ_C's
//! vertices) from a closed form (Hertz, the exact circle, the rounded punch,
//! Cattaneo–Mindlin's q), integrated to round-off (docs/design.md §6, "Errors against a closed
//! form").
//!
//! A closed form is smooth except at a few points: the contact's ends ±a, where it falls to 0
//! as √(a − |x|); the stick zone's ends ±c of Cattaneo–Mindlin, where q has the same square
//! root on one side; the rounded punch's corners ±b, where p′ has a logarithmic singularity.
//! Each edge is split at those points, and on a piece that ends at one the variable
//! x = l + (r − l)t² (or its mirror) turns √(x − l) into (r − l)^½ t: the integrand becomes
//! smooth in t and Gauss–Legendre converges exponentially. A piece with such an end on both
//! sides is halved first. With [`PIECE_POINTS`] points the quadrature error is below 1e-10
//! relative (the module's tests, against closed-form integrals and adaptive quadrature).

use super::ContactPoints;
use crate::fem::quadrature::gauss_legendre;

/// Gauss–Legendre points on each piece: the smoothed integrands converge exponentially, the
/// punch's t³ ln t as n⁻⁸.
pub const PIECE_POINTS: usize = 16;

/// ‖v̄ − f‖₀ / ‖f‖₀ over Γ_C for nodal values `values` at `cp`'s vertices (continuous, linear
/// on each edge) and a closed form `f` that is smooth but at `ends` (its kinks and square-root
/// ends; any order, points off Γ_C ignored). NaN when ‖f‖₀ is 0 or either integral is not a
/// finite number: the relative distance is then undefined, and its printers say so
/// (`text::sci`, private to the crate).
pub fn relative_l2_error(cp: &ContactPoints, values: &[f64], f: impl Fn(f64) -> f64, ends: &[f64]) -> f64 {
    let (err, norm) = squared_distance_and_norm(cp, values, f, ends);
    if norm > 0.0 && norm.is_finite() && err.is_finite() {
        (err / norm).sqrt()
    } else {
        f64::NAN
    }
}

/// (∫(v̄ − f)², ∫f²) over Γ_C, [`relative_l2_error`]'s two integrals.
fn squared_distance_and_norm(
    cp: &ContactPoints,
    values: &[f64],
    f: impl Fn(f64) -> f64,
    ends: &[f64],
) -> (f64, f64) {
    let gauss = gauss_legendre(PIECE_POINTS);
    let mut ends: Vec<f64> = ends.iter().copied().filter(|x| x.is_finite()).collect();
    ends.sort_by(f64::total_cmp);
    let (mut err, mut norm) = (0.0, 0.0);
    for e in 0..cp.n_edges() {
        let (x0, x1) = (cp.vertex_x[e], cp.vertex_x[e + 1]);
        let (v0, v1) = (values[e], values[e + 1]);
        let linear = |x: f64| v0 + (v1 - v0) * (x - x0) / (x1 - x0);
        // A vertex within round-off of an end is that end.
        let near = 1e-12 * (x1 - x0);
        let is_end = |x: f64| ends.iter().any(|&c| (c - x).abs() <= near);
        let mut cuts = vec![x0];
        cuts.extend(ends.iter().copied().filter(|&c| c > x0 + near && c < x1 - near));
        cuts.push(x1);
        for w in cuts.windows(2) {
            let (l, r) = (w[0], w[1]);
            let mut add = |x: f64, weight: f64| {
                let fx = f(x);
                err += weight * (linear(x) - fx).powi(2);
                norm += weight * fx * fx;
            };
            match (is_end(l), is_end(r)) {
                (false, false) => {
                    for &(xi, wi) in &gauss {
                        add(l + (r - l) * (xi + 1.0) / 2.0, wi * (r - l) / 2.0);
                    }
                }
                (left, right) => {
                    // Each end piece on x = end ± (length) t², t ∈ [0, 1]; halved when both
                    // ends are singular.
                    let m = (l + r) / 2.0;
                    let halves: &[(f64, f64)] = match (left, right) {
                        (true, true) => &[(l, m), (r, m)],
                        (true, false) => &[(l, r)],
                        _ => &[(r, l)],
                    };
                    for &(end, other) in halves {
                        let length = other - end;
                        for &(xi, wi) in &gauss {
                            let t = (xi + 1.0) / 2.0;
                            // dx = 2·length·t dt, dt = dξ/2.
                            add(end + length * t * t, wi / 2.0 * 2.0 * length.abs() * t);
                        }
                    }
                }
            }
        }
    }
    (err, norm)
}

#[cfg(test)]
mod tests {
    use super::super::circle::CircleContact;
    use super::super::hertz::Hertz;
    use super::super::mindlin::Mindlin;
    use super::super::rounded_punch::RoundedPunch;
    use super::super::{Obstacle, Rule};
    use super::*;
    use crate::material::{Material, Plane};

    const MATERIAL: Material = Material {
        young: 1000.0,
        poisson: 0.3,
        plane: Plane::Strain,
    };

    /// A coarse, uneven Γ_C on [lo, hi] whose vertices miss the closed forms' ends.
    fn coarse(lo: f64, hi: f64, n: usize) -> ContactPoints {
        let x: Vec<f64> = (0..=n)
            .map(|i| {
                let s = i as f64 / n as f64;
                lo + (hi - lo) * (s + 0.02 * (2.0 * std::f64::consts::PI * s).sin())
            })
            .collect();
        ContactPoints::new(Rule::Trapezoid, &x, 1)
    }

    /// Nodal values near `f`'s, off by a smooth few per cent (a computed profile's stand-in).
    fn near(cp: &ContactPoints, f: impl Fn(f64) -> f64) -> Vec<f64> {
        cp.vertex_x
            .iter()
            .map(|&x| f(x) * (1.0 + 0.05 * (3.0 * x).sin()) + 0.01 * f(0.0) * (x * 2.0).cos())
            .collect()
    }

    /// ∫ₗʳ f by adaptive Simpson with Richardson's correction to `tol` (absolute), written
    /// independently of the module's splitting: it finds the ends and kinks by bisection.
    fn adaptive(f: &dyn Fn(f64) -> f64, l: f64, r: f64, tol: f64) -> f64 {
        /// One interval (its ends `lr`, f at its ends and middle `fs`, its Simpson value).
        fn step(
            f: &dyn Fn(f64) -> f64,
            lr: (f64, f64),
            fs: (f64, f64, f64),
            whole: f64,
            tol: f64,
            depth: u32,
        ) -> f64 {
            let ((l, r), (fl, fm, fr)) = (lr, fs);
            let m = (l + r) / 2.0;
            let (lm, rm) = ((l + m) / 2.0, (m + r) / 2.0);
            let (flm, frm) = (f(lm), f(rm));
            let left = (m - l) / 6.0 * (fl + 4.0 * flm + fm);
            let right = (r - m) / 6.0 * (fm + 4.0 * frm + fr);
            let delta = left + right - whole;
            if depth == 0 || delta.abs() <= 15.0 * tol {
                return left + right + delta / 15.0;
            }
            step(f, (l, m), (fl, flm, fm), left, tol / 2.0, depth - 1)
                + step(f, (m, r), (fm, frm, fr), right, tol / 2.0, depth - 1)
        }
        let (fl, fm, fr) = (f(l), f((l + r) / 2.0), f(r));
        let whole = (r - l) / 6.0 * (fl + 4.0 * fm + fr);
        step(f, (l, r), (fl, fm, fr), whole, tol, 60)
    }

    /// The relative distance by [`adaptive`] on every edge.
    fn reference(cp: &ContactPoints, v: &[f64], f: impl Fn(f64) -> f64, scale: f64) -> f64 {
        let (mut err, mut norm) = (0.0, 0.0);
        for e in 0..cp.n_edges() {
            let (x0, x1) = (cp.vertex_x[e], cp.vertex_x[e + 1]);
            let lin = |x: f64| v[e] + (v[e + 1] - v[e]) * (x - x0) / (x1 - x0);
            let tol = 1e-14 * scale * scale * (x1 - x0);
            err += adaptive(&|x| (lin(x) - f(x)).powi(2), x0, x1, tol);
            norm += adaptive(&|x| f(x).powi(2), x0, x1, tol);
        }
        (err / norm).sqrt()
    }

    fn assert_close(got: f64, want: f64, what: &str) {
        assert!(
            (got - want).abs() <= 1e-9 * want,
            "{what}: {got:.12e} against {want:.12e} ({:.1e} relative)",
            (got - want) / want
        );
    }

    fn cylinder() -> Obstacle {
        Obstacle::Cylinder {
            radius: 10.0,
            depth: 0.3,
            center: 0.0,
        }
    }

    /// Hertz against its integrals in closed form: ∫√(a² − x²) = (x√(a² − x²) + a² asin(x/a))/2,
    /// ∫x√(a² − x²) = −(a² − x²)^{3/2}/3, ∫(1 − x²/a²) = x − x³/3a², edge by edge.
    #[test]
    fn hertz_distance_equals_its_closed_form() {
        let h = Hertz::for_load(&cylinder(), &MATERIAL, 25.0).unwrap();
        let (a, p0) = (h.a, h.p0);
        for (lo, n) in [(-2.1, 7), (-1.3, 3), (0.0, 5), (-3.0, 40)] {
            let cp = coarse(lo, 2.0, n);
            let v = near(&cp, |x| h.pressure(x));
            let clip = |x: f64| x.clamp(-a, a);
            let f1 = |x: f64| (x * (a * a - x * x).sqrt() + a * a * (x / a).asin()) / 2.0;
            let f2 = |x: f64| -(a * a - x * x).powf(1.5) / 3.0;
            let f3 = |x: f64| x - x.powi(3) / (3.0 * a * a);
            let (mut err, mut norm) = (0.0, 0.0);
            for e in 0..cp.n_edges() {
                let (x0, x1) = (cp.vertex_x[e], cp.vertex_x[e + 1]);
                let beta = (v[e + 1] - v[e]) / (x1 - x0);
                let alpha = v[e] - beta * x0;
                let (u, w) = (clip(x0), clip(x1));
                let squares = p0 * p0 * (f3(w) - f3(u));
                let cross = 2.0 * p0 / a * (alpha * (f1(w) - f1(u)) + beta * (f2(w) - f2(u)));
                let linear = (x1 - x0) * (v[e] * v[e] + v[e] * v[e + 1] + v[e + 1] * v[e + 1]) / 3.0;
                err += linear - cross + squares;
                norm += squares;
            }
            assert_close(
                h.relative_error(&cp, &v),
                (err / norm).sqrt(),
                &format!("lo {lo}, {n} edges"),
            );
        }
    }

    /// The exact circle, Cattaneo–Mindlin's q (its kinks at ±c) and the rounded punch (its
    /// corners at ±b) against adaptive quadrature.
    #[test]
    fn closed_form_distances_equal_adaptive_quadrature() {
        let circle = CircleContact::for_load(&cylinder(), &MATERIAL, 25.0).unwrap();
        for (lo, n) in [(-2.1, 7), (0.0, 4)] {
            let cp = coarse(lo, 2.0, n);
            let v = near(&cp, |x| circle.pressure(x));
            let want = reference(&cp, &v, |x| circle.pressure(x), circle.p0);
            assert_close(circle.relative_error(&cp, &v), want, "circle");
        }
        let m = Mindlin::for_loads(&cylinder(), &MATERIAL, 25.0, 4.0, 0.3).unwrap();
        for (lo, n) in [(-2.1, 7), (0.0, 5), (-1.7, 2)] {
            let cp = coarse(lo, 2.0, n);
            let v = near(&cp, |x| m.traction(x));
            let want = reference(&cp, &v, |x| m.traction(x), m.mu * m.hertz.p0);
            assert_close(m.relative_error(&cp, &v), want, "mindlin");
        }
        let punch = Obstacle::Punch {
            half_width: 1.0,
            corner_radius: 20.0,
            depth: 0.1,
            center: 0.0,
        };
        let p = RoundedPunch::load_of(crate::contact::half_plane::e_star(&MATERIAL), 1.0, 20.0, 1.4);
        let r = RoundedPunch::for_load(&punch, &MATERIAL, p).unwrap();
        for (lo, n) in [(-2.1, 7), (0.0, 3)] {
            let cp = coarse(lo, 2.0, n);
            let v = near(&cp, |x| r.pressure(x));
            let want = reference(&cp, &v, |x| r.pressure(x), r.peak());
            assert_close(r.relative_error(&cp, &v), want, "punch");
        }
    }
}
