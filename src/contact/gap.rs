//! The rigid obstacle and the gap g of the constraint (4): u_n − g ≤ 0 on Γ_C.

use serde::{Deserialize, Serialize};

/// A rigid obstacle above the contact side y = top of the body.
///
/// New shapes are new variants: each defines the gap g(x) between the undeformed surface and
/// the obstacle, measured along the outward normal n = (0, 1).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "lowercase", deny_unknown_fields)]
pub enum Obstacle {
    /// A rigid cylinder of radius R whose axis is at x = `center`, pushed down so that its
    /// lowest point is at depth d below the undeformed surface (DESIGN §1).
    Cylinder { radius: f64, depth: f64, center: f64 },
}

impl Obstacle {
    /// g(x) = R − d − √(R² − (x − c)²), evaluated as (x − c)²/(R + √(R² − (x − c)²)) − d to
    /// avoid cancellation; +∞ where the cylinder does not reach (|x − c| ≥ R).
    pub fn gap(&self, x: f64) -> f64 {
        match *self {
            Obstacle::Cylinder {
                radius,
                depth,
                center,
            } => {
                let dx = x - center;
                if dx.abs() >= radius {
                    f64::INFINITY
                } else {
                    dx * dx / (radius + (radius * radius - dx * dx).sqrt()) - depth
                }
            }
        }
    }

    /// The indentation depth d.
    pub fn depth(&self) -> f64 {
        match *self {
            Obstacle::Cylinder { depth, .. } => depth,
        }
    }

    /// The same obstacle at another depth.
    pub fn with_depth(&self, d: f64) -> Self {
        match *self {
            Obstacle::Cylinder { radius, center, .. } => Obstacle::Cylinder {
                radius,
                depth: d,
                center,
            },
        }
    }

    /// The obstacle's lower outline y(x) relative to the undeformed surface (for drawing):
    /// y = −d + R − √(R² − (x − c)²), None where it does not exist.
    pub fn outline(&self, x: f64) -> Option<f64> {
        let g = self.gap(x);
        g.is_finite().then_some(g)
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
}
