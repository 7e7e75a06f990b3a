//! Meshes graded over the contact zone (`--refine-edges Nz`; docs/design.md §6).
//!
//! Grading at the edges alone stalls: (17) averages the pressures of two neighbouring edges
//! of Γ_C with their lengths as weights, so where the edge length changes inside the contact
//! zone the smoothed p̄ is off by about p′·(h₂ − h₁)/2, first order in h, and a band graded
//! around a contact edge, where p′ is largest, puts such steps just where they cost most.
//! A zone pass therefore keeps Γ_C uniform over the whole contact zone: it bisects every
//! vertex interval between the zone's edges (and [`EDGE_WIDTH`] beyond each), and every row of
//! cells near Γ_C, and lets the cells grow away from both, at most a [`SPREAD`]th of their
//! distance from the zone (across) or from Γ_C (down), never coarser than the uniform level.
//! Outside the zone p vanishes, so the growing edges there cost (17) nothing.
//!
//! Pass j asks of a cell side in the zone (and at Γ_C) the uniform level's side over 2^j; the
//! lines only ever gain bisections of the uniform level's intervals, so they nest.

use super::{EDGE_WIDTH, GradedGrid};
use crate::contact::ContactPoints;

/// Away from the contact zone (across) and from Γ_C (down) a cell side is at most its distance
/// from them over this: cells grow by about 1/8 from one to the next.
pub const SPREAD: f64 = 8.0;

/// The contact zones of the pressure `p` at `points`: each run of vertex intervals of Γ_C that
/// hold a pressed point (p > 0), as (first, last) interval.
pub fn contact_zones(points: &ContactPoints, p: &[f64]) -> Vec<(usize, usize)> {
    let top = p.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let pressed = |e: &Vec<usize>| e.iter().any(|&k| p[k] > 1e-9 * top);
    let mut zones: Vec<(usize, usize)> = Vec::new();
    for (e, _) in points.edge_points.iter().enumerate().filter(|(_, e)| pressed(e)) {
        match zones.last_mut() {
            Some(z) if z.1 + 1 == e => z.1 = e,
            _ => zones.push((e, e)),
        }
    }
    zones
}

impl GradedGrid {
    /// The next zone pass of this grid, graded from `uniform` (its level's grid) at the
    /// contact `zones` (vertex intervals of `xs`, [`contact_zones`]); None without a zone.
    pub fn zoned(&self, uniform: &GradedGrid, zones: &[(usize, usize)]) -> Option<Self> {
        if zones.is_empty() {
            return None;
        }
        let scale = f64::from(1u32 << (self.passes + 1).min(30));
        let last = self.xs.len() - 1;
        let spans: Vec<(f64, f64)> = zones
            .iter()
            .map(|&(a, b)| {
                let (a, b) = (a.saturating_sub(EDGE_WIDTH), (b + EDGE_WIDTH).min(last - 1));
                (self.xs[a], self.xs[b + 1])
            })
            .collect();
        let across = |x0: f64, x1: f64| {
            spans
                .iter()
                .map(|&(a, b)| (a - x1).max(x0 - b).max(0.0))
                .fold(f64::INFINITY, f64::min)
        };
        let top = self.ys[self.ys.len() - 1];
        let xs = graded(&self.xs, &uniform.xs, scale, across);
        let ys = graded(&self.ys, &uniform.ys, scale, |_, y1| top - y1);
        Some(GradedGrid {
            level: self.level,
            passes: self.passes + 1,
            xs,
            ys,
        })
    }
}

/// `lines` with each interval bisected until its side is at most its uniform interval's (of
/// `uniform`, whose lines `lines` contain) over `scale`, or further from the zone than that,
/// its distance (`distance(x0, x1)`) over [`SPREAD`].
fn graded(lines: &[f64], uniform: &[f64], scale: f64, distance: impl Fn(f64, f64) -> f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(2 * lines.len());
    let mut stack: Vec<(f64, f64)> = Vec::new();
    for w in lines.windows(2) {
        let k = uniform
            .partition_point(|&u| u <= w[0])
            .clamp(1, uniform.len() - 1);
        let side = uniform[k] - uniform[k - 1];
        let wanted = |x0: f64, x1: f64| (distance(x0, x1) / SPREAD).clamp(side / scale, side);
        stack.push((w[0], w[1]));
        while let Some((x0, x1)) = stack.pop() {
            if x1 - x0 > wanted(x0, x1) * (1.0 + 1e-9) {
                let mid = 0.5 * (x0 + x1);
                stack.push((mid, x1));
                stack.push((x0, mid));
            } else {
                out.push(x0);
            }
        }
    }
    out.push(lines[lines.len() - 1]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Rule;

    fn grid(xs: Vec<f64>, ys: Vec<f64>) -> GradedGrid {
        GradedGrid {
            level: 0,
            passes: 0,
            xs,
            ys,
        }
    }

    /// The zones are the runs of intervals with a pressed point: two runs here, the second
    /// reaching the last interval.
    #[test]
    fn zones_are_the_runs_of_pressed_intervals() {
        let x: Vec<f64> = (0..=8).map(f64::from).collect();
        let points = ContactPoints::new(Rule::Gauss1, &x, 1);
        let p = [1.0, 2.0, 0.0, 0.0, 3.0, 0.0, 1.0, 1.0];
        assert_eq!(contact_zones(&points, &p), [(0, 1), (4, 4), (6, 7)]);
        assert_eq!(contact_zones(&points, &[0.0; 8]), []);
        // Trapezoid: a pressed vertex presses both intervals that share it.
        let points = ContactPoints::new(Rule::Trapezoid, &x, 1);
        let p = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        assert_eq!(contact_zones(&points, &p), [(2, 3)]);
    }

    /// One pass on a uniform grid of side 1: the zone (interval 1) and EDGE_WIDTH intervals
    /// beyond each side ([0, 4]) are halved, and so are the cells within a distance of 8 =
    /// SPREAD · 1 from it (side r/SPREAD < 1, never below the half); the rows at Γ_C likewise
    /// to a depth of 8; every old line is kept.
    #[test]
    fn a_zone_pass_halves_the_zone_and_the_rows_at_the_top() {
        let xs: Vec<f64> = (0..=32).map(f64::from).collect();
        let ys: Vec<f64> = (0..=16).map(f64::from).collect();
        let uniform = grid(xs.clone(), ys.clone());
        let next = uniform.zoned(&uniform, &[(1, 1)]).unwrap();
        let halves = |a: i32, b: i32| (2 * a..2 * b).map(|i| f64::from(i) / 2.0);
        let whole = |a: i32, b: i32| (a..=b).map(f64::from);
        assert_eq!(next.xs, halves(0, 12).chain(whole(12, 32)).collect::<Vec<_>>());
        assert_eq!(
            next.ys,
            whole(0, 7).chain(halves(8, 16)).chain([16.0]).collect::<Vec<_>>()
        );
        assert_eq!((next.passes, next.h_min()), (1, 0.5));
        assert!(xs.iter().all(|x| next.xs.contains(x)) && ys.iter().all(|y| next.ys.contains(y)));
        // The second pass quarters the zone (intervals 0..=3 of the halves, ± 2: [0, 3]).
        let zone = (0, 3);
        let second = next.zoned(&uniform, &[zone]).unwrap();
        assert_eq!(second.h_min(), 0.25);
        assert!(next.xs.iter().all(|x| second.xs.contains(x)));
        let sides = |a: f64, b: f64| -> Vec<f64> {
            let inside = second.xs.windows(2).filter(|w| w[0] >= a && w[1] <= b);
            inside.map(|w| w[1] - w[0]).collect()
        };
        assert_eq!(sides(0.0, 3.0), [0.25; 12]);
        assert!(sides(7.0, 12.0).iter().all(|&h| h == 0.5) && sides(12.0, 32.0).iter().all(|&h| h == 1.0));
        assert_eq!(uniform.zoned(&uniform, &[]), None);
    }
}
