//! The rigid obstacle and the gap g of the constraint (4): u_n − g ≤ 0 on Γ_C.
//!
//! Every shape is described by its lower outline, the height η(x) ≥ 0 of the obstacle above
//! its lowest point; pressed down by the depth d, its gap to the undeformed surface is
//! g(x) = η(x) − d (+∞ where the obstacle does not reach, e.g. beyond a cylinder's radius or a
//! punch's flank). A library user may bring an outline of their own ([`Outline`],
//! `examples/custom_obstacle.rs`).

use std::fmt;
use std::sync::Arc;

/// An obstacle's lower outline of the library user's own: everything riplab needs of a shape.
///
/// The paper's problem pressed by a flat-bottomed wedge, in a few lines:
///
/// ```
/// use std::sync::Arc;
/// use riplab::contact::{Obstacle, Outline};
/// use riplab::{scenario::Scenario, solve::solve_scenario};
///
/// struct Wedge; // η(x) = |x| / 4: flanks of slope 1/4
/// impl Outline for Wedge {
///     fn outline(&self, x: f64) -> f64 { x.abs() / 4.0 }
/// }
/// let mut scenario = Scenario::paper();
/// scenario.obstacle = Obstacle::Custom { outline: Arc::new(Wedge), depth: 0.5 };
/// let (_, sol) = solve_scenario(&scenario).expect("the wedge's problem solves");
/// assert!(sol.newton.converged && sol.load > 0.0);
/// ```
pub trait Outline: Send + Sync {
    /// η(x) ≥ 0: the outline's height above its lowest point at x, +∞ where the obstacle does
    /// not reach.
    fn outline(&self, x: f64) -> f64;
    /// The x of its lowest point (where views centre).
    fn center(&self) -> f64 {
        0.0
    }
    /// A few words for messages and output.
    fn describe(&self) -> String {
        "a custom outline".into()
    }
}

impl fmt::Debug for dyn Outline {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Outline({})", self.describe())
    }
}

/// Two custom outlines are the same when they are the same object.
impl PartialEq for dyn Outline {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::addr_eq(self, other)
    }
}

/// A rigid obstacle above the contact side of the body.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Obstacle {
    /// A rigid cylinder of radius R with its axis at x = `center` (the paper's, docs/design.md §1).
    Cylinder {
        /// The radius R > 0.
        radius: f64,
        /// The indentation depth d.
        depth: f64,
        /// x of the axis.
        center: f64,
    },
    /// A flat rigid punch: a flat face of half-width `half_width` with rounded corners of
    /// radius `corner_radius`, vertical flanks beyond them.
    Punch {
        /// Half-width of the flat face, > 0.
        half_width: f64,
        /// Radius of the rounded corners, > 0.
        corner_radius: f64,
        /// The indentation depth d.
        depth: f64,
        /// x of the face's centre.
        center: f64,
    },
    /// Several cylinders side by side, each lifted by `lift` above the lowest point: the
    /// obstacle's outline is the lowest of them at each x.
    Bumps {
        /// The cylinders.
        bumps: Vec<Bump>,
        /// The indentation depth d of the lowest point.
        depth: f64,
    },
    /// A polyline outline through (x, height) points, heights measured upwards; +∞ outside.
    Polyline {
        /// The outline's (x, height) points.
        points: Vec<(f64, f64)>,
        /// The indentation depth d of the lowest point.
        depth: f64,
    },
    /// An outline of the library user's own.
    Custom {
        /// The outline η(x).
        outline: Arc<dyn Outline>,
        /// The indentation depth d.
        depth: f64,
    },
}

/// One cylinder of [`Obstacle::Bumps`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bump {
    /// x of the cylinder's axis.
    pub center: f64,
    /// The cylinder's radius R > 0.
    pub radius: f64,
    /// Height of its lowest point; only the differences between bumps count.
    pub lift: f64,
}

/// Height above its lowest point of a circle of radius r at distance dx from its centre,
/// r − √(r² − dx²) evaluated as dx²/(r + √(r² − dx²)) to avoid cancellation; +∞ beyond r.
fn circle(r: f64, dx: f64) -> f64 {
    if dx.abs() >= r {
        f64::INFINITY
    } else {
        dx * dx / (r + (r * r - dx * dx).sqrt())
    }
}

impl Obstacle {
    /// η(x): the outline's height above the obstacle's lowest point (+∞ where it does not reach).
    pub fn outline(&self, x: f64) -> f64 {
        match self {
            Obstacle::Cylinder { radius, center, .. } => circle(*radius, x - center),
            Obstacle::Punch {
                half_width,
                corner_radius,
                center,
                ..
            } => {
                let beyond = (x - center).abs() - half_width;
                if beyond <= 0.0 {
                    0.0
                } else {
                    circle(*corner_radius, beyond)
                }
            }
            Obstacle::Bumps { bumps, .. } => {
                let lowest = bumps.iter().map(|b| b.lift).fold(f64::INFINITY, f64::min);
                bumps
                    .iter()
                    .map(|b| b.lift - lowest + circle(b.radius, x - b.center))
                    .fold(f64::INFINITY, f64::min)
            }
            Obstacle::Polyline { points, .. } => {
                let lowest = points.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
                let k = points.partition_point(|p| p.0 <= x);
                if k == 0 || (k == points.len() && x > points[k - 1].0) {
                    return f64::INFINITY;
                }
                if k == points.len() {
                    return points[k - 1].1 - lowest;
                }
                let ((x0, y0), (x1, y1)) = (points[k - 1], points[k]);
                y0 + (y1 - y0) * (x - x0) / (x1 - x0) - lowest
            }
            Obstacle::Custom { outline, .. } => outline.outline(x),
        }
    }

    /// g(x) = η(x) − d.
    pub fn gap(&self, x: f64) -> f64 {
        self.outline(x) - self.depth()
    }

    /// The indentation depth d.
    pub fn depth(&self) -> f64 {
        match self {
            Obstacle::Cylinder { depth, .. }
            | Obstacle::Punch { depth, .. }
            | Obstacle::Bumps { depth, .. }
            | Obstacle::Polyline { depth, .. }
            | Obstacle::Custom { depth, .. } => *depth,
        }
    }

    /// The same obstacle at another depth.
    pub fn with_depth(&self, d: f64) -> Self {
        let mut o = self.clone();
        match &mut o {
            Obstacle::Cylinder { depth, .. }
            | Obstacle::Punch { depth, .. }
            | Obstacle::Bumps { depth, .. }
            | Obstacle::Polyline { depth, .. }
            | Obstacle::Custom { depth, .. } => *depth = d,
        }
        o
    }

    /// The x about which the obstacle is centred (its lowest point's x for a polyline).
    pub fn center(&self) -> f64 {
        match self {
            Obstacle::Cylinder { center, .. } | Obstacle::Punch { center, .. } => *center,
            Obstacle::Bumps { bumps, .. } => {
                bumps.iter().map(|b| b.center).sum::<f64>() / bumps.len().max(1) as f64
            }
            Obstacle::Polyline { points, .. } => points
                .iter()
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map_or(0.0, |p| p.0),
            Obstacle::Custom { outline, .. } => outline.center(),
        }
    }

    /// The radius of curvature at the lowest point, for the Hertz profile: a cylinder's radius
    /// (None for shapes that Hertz's theory does not describe).
    pub fn hertz_radius(&self) -> Option<f64> {
        match self {
            Obstacle::Cylinder { radius, .. } => Some(*radius),
            _ => None,
        }
    }

    /// The x-interval where the obstacle, at its depth, overlaps the undeformed body (g < 0)
    /// within [x_lo, x_hi]: sampled, then each end bisected to round-off. None when it does
    /// not touch.
    pub fn contact_extent(&self, x_lo: f64, x_hi: f64) -> Option<(f64, f64)> {
        let n = 2000;
        let at = |i: usize| x_lo + (x_hi - x_lo) * i as f64 / n as f64;
        let inside: Vec<usize> = (0..=n).filter(|&i| self.gap(at(i)) < 0.0).collect();
        let (first, last) = (*inside.first()?, *inside.last()?);
        // Bisect between a point inside (g < 0) and one outside.
        let edge = |mut inner: f64, mut outer: f64| {
            for _ in 0..60 {
                let mid = 0.5 * (inner + outer);
                if self.gap(mid) < 0.0 {
                    inner = mid
                } else {
                    outer = mid
                }
            }
            inner
        };
        let lo = if first == 0 {
            x_lo
        } else {
            edge(at(first), at(first - 1))
        };
        let hi = if last == n {
            x_hi
        } else {
            edge(at(last), at(last + 1))
        };
        Some((lo, hi))
    }

    /// The deepest indentation that keeps the obstacle's outline meaningful: half a cylinder's
    /// radius, a punch's corner radius plus its face, the smallest bump's radius; unbounded for
    /// a polyline.
    pub fn max_depth(&self) -> f64 {
        match self {
            Obstacle::Cylinder { radius, .. } => radius / 2.0,
            Obstacle::Punch { corner_radius, .. } => *corner_radius,
            Obstacle::Bumps { bumps, .. } => {
                bumps.iter().map(|b| b.radius / 2.0).fold(f64::INFINITY, f64::min)
            }
            Obstacle::Polyline { .. } | Obstacle::Custom { .. } => f64::INFINITY,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cylinder_gap_by_hand() {
        let c = Obstacle::Cylinder {
            radius: 8.0,
            depth: 0.8,
            center: 0.0,
        };
        assert_eq!(c.gap(0.0), -0.8);
        // x = 4.8: √(64 − 23.04) = 6.4, g = 8 − 0.8 − 6.4 = 0.8.
        assert!((c.gap(4.8) - 0.8).abs() < 1e-15);
        assert!((c.gap(-4.8) - 0.8).abs() < 1e-15);
        assert_eq!(c.gap(8.0), f64::INFINITY);
    }

    #[test]
    fn punch_gap_by_hand() {
        let p = Obstacle::Punch {
            half_width: 2.0,
            corner_radius: 0.5,
            depth: 0.1,
            center: 1.0,
        };
        assert_eq!(p.gap(1.0), -0.1);
        assert_eq!(p.gap(3.0), -0.1);
        assert_eq!(p.gap(-1.0), -0.1);
        // 0.3 into the corner: 0.5 − √(0.25 − 0.09) = 0.5 − 0.4 = 0.1.
        assert!((p.gap(3.3) - 0.0).abs() < 1e-15);
        assert!((p.gap(-1.3) - 0.0).abs() < 1e-15);
        assert_eq!(p.gap(3.5), f64::INFINITY);
    }

    #[test]
    fn bumps_gap_by_hand() {
        let b = Obstacle::Bumps {
            bumps: vec![
                Bump {
                    center: -2.0,
                    radius: 5.0,
                    lift: 0.0,
                },
                Bump {
                    center: 2.0,
                    radius: 5.0,
                    lift: 0.1,
                },
            ],
            depth: 0.2,
        };
        assert_eq!(b.gap(-2.0), -0.2);
        assert!((b.gap(2.0) - (0.1 - 0.2)).abs() < 1e-15);
        // x = 1: left bump 3 away, 5 − 4 = 1; right bump 1 away, 0.1 + 5 − √24; the lower wins.
        let right = 0.1 + 5.0 - 24f64.sqrt();
        assert!((b.gap(1.0) - (right - 0.2)).abs() < 1e-14);
        // x = 0: both 2 away: 5 − √21, and 0.1 more for the right one.
        assert!((b.gap(0.0) - (5.0 - 21f64.sqrt() - 0.2)).abs() < 1e-14);
    }

    #[test]
    fn polyline_gap_by_hand() {
        let p = Obstacle::Polyline {
            points: vec![(-4.0, 3.0), (0.0, 1.0), (2.0, 2.0)],
            depth: 0.5,
        };
        assert_eq!(p.gap(0.0), -0.5);
        assert_eq!(p.gap(-2.0), 1.0 - 0.5);
        assert_eq!(p.gap(1.0), 0.5 - 0.5);
        assert_eq!(p.gap(2.0), 1.0 - 0.5);
        assert_eq!(p.gap(-4.0), 2.0 - 0.5);
        assert_eq!(p.gap(2.5), f64::INFINITY);
        assert_eq!(p.gap(-4.5), f64::INFINITY);
    }

    #[test]
    fn extent_of_the_papers_cylinder() {
        let c = Obstacle::Cylinder {
            radius: 8.0,
            depth: 0.8,
            center: 0.0,
        };
        let (lo, hi) = c.contact_extent(-8.0, 8.0).unwrap();
        // g = 0 at x² = R² − (R − d)² = 64 − 51.84 = 12.16, x = 3.487.
        assert!((hi - 12.16f64.sqrt()).abs() < 1e-12 && (lo + hi).abs() < 1e-12);
        assert!(c.with_depth(-0.1).contact_extent(-8.0, 8.0).is_none());
    }
}
