//! Whether a solve's contact edges still lie in a graded grid's refined band: the
//! lab keeps a graded grid across ε and depth changes while they do, and grades again from the
//! uniform level when they left it (docs/design.md §6, edge grading).

use crate::contact::ContactPoints;

use super::zone::contact_zones;
use super::{GradedGrid, contact_edges};

impl GradedGrid {
    /// Whether the contact edges of the pressure `p` at `points` (a solve on this grid) all
    /// lie in its finest band ([`GradedGrid::in_band`]): the grid has had a pass (a uniform
    /// grid has no band) and the pressure has at least one edge.
    pub fn holds_edges(&self, points: &ContactPoints, p: &[f64]) -> bool {
        let edges = contact_edges(points, p);
        let x = &points.vertex_x;
        self.passes > 0 && !edges.is_empty() && edges.iter().all(|&e| self.in_band(0.5 * (x[e] + x[e + 1])))
    }

    /// Whether the contact zones of the pressure `p` at `points` (a solve on this zone-graded
    /// grid, [`GradedGrid::zoned`]) lie in its finest band: every pressed vertex interval and
    /// the interval beyond each end of a zone, so that Γ_C's edges are equal wherever (17)
    /// averages a pressure (docs/design.md §6, zone grading). False for a grid without a pass
    /// or a pressure without a zone.
    pub fn holds_zone(&self, points: &ContactPoints, p: &[f64]) -> bool {
        let zones = contact_zones(points, p);
        let x = &points.vertex_x;
        let last = x.len() - 2;
        self.passes > 0
            && !zones.is_empty()
            && zones.iter().all(|&(a, b)| {
                (a.saturating_sub(1)..=(b + 1).min(last)).all(|e| self.in_band(0.5 * (x[e] + x[e + 1])))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Rule;
    use crate::mesh::Element;

    /// The paper's level 2 of its half model: 32 × 16 cells of side 1/4 over [0, 8] × [0, 4].
    fn level_2() -> GradedGrid {
        let lines = |n: u32, to: f64| (0..=n).map(|k| to * f64::from(k) / f64::from(n)).collect();
        GradedGrid {
            level: 2,
            passes: 0,
            xs: lines(32, 8.0),
            ys: lines(16, 4.0),
        }
    }

    /// A pressure p(x) = max(0, 1 − x/a) at `points`: one contact edge, at x = a.
    fn pressed_to(points: &ContactPoints, a: f64) -> Vec<f64> {
        points.points.iter().map(|q| (1.0 - q.x / a).max(0.0)).collect()
    }

    /// A grid graded twice around the vertex interval that holds x = a holds an edge at a, or
    /// a little beside it in the band, but not one two of the level's cells away, nor a
    /// pressure without an edge; the uniform grid holds none (it has no band).
    #[test]
    fn a_graded_grid_holds_the_edges_in_its_band_only() {
        let uniform = level_2();
        let at = |grid: &GradedGrid| {
            let mesh = grid.mesh(Element::Q1, true);
            ContactPoints::new(Rule::Gauss1, &mesh.node_x, 1)
        };
        let h = uniform.xs[1] - uniform.xs[0];
        let a = uniform.xs[2] + 0.3 * h;
        let once = uniform.refined(&[2]).unwrap();
        let e = once.xs.iter().position(|&x| x > a).unwrap() - 1;
        let twice = once.refined(&[e]).unwrap();
        let points = at(&twice);
        assert!(twice.holds_edges(&points, &pressed_to(&points, a)));
        assert!(twice.holds_edges(&points, &pressed_to(&points, a + 0.4 * h)));
        assert!(!twice.holds_edges(&points, &pressed_to(&points, a + 2.0 * h)));
        assert!(!twice.holds_edges(&points, &vec![1.0; points.points.len()]));
        let flat = at(&uniform);
        assert!(!uniform.holds_edges(&flat, &pressed_to(&flat, a)));
    }

    /// A grid zone-graded once for a zone of x < a holds a pressure over x < a, or over a
    /// narrower zone, but not one whose zone reaches three of the level's cells further (past
    /// the halved band) nor one pressed everywhere; the uniform grid holds none.
    #[test]
    fn a_zone_grid_holds_its_contact_zone_in_its_finest_band_only() {
        let uniform = level_2();
        let at = |grid: &GradedGrid| {
            let mesh = grid.mesh(Element::Q1, true);
            ContactPoints::new(Rule::Gauss1, &mesh.node_x, 1)
        };
        let h = uniform.xs[1] - uniform.xs[0];
        let a = uniform.xs[2] + 0.3 * h;
        let flat = at(&uniform);
        let zones = contact_zones(&flat, &pressed_to(&flat, a));
        let once = uniform.zoned(&uniform, &zones).unwrap();
        let points = at(&once);
        assert!(once.holds_zone(&points, &pressed_to(&points, a)));
        assert!(once.holds_zone(&points, &pressed_to(&points, a - h)));
        // The halved band: the zone's intervals, EDGE_WIDTH beyond, and SPREAD·h/2 further.
        let band_end = once.xs.windows(2).take_while(|w| w[1] - w[0] < 0.75 * h).count();
        let past = once.xs[band_end] + 0.5 * h;
        assert!(!once.holds_zone(&points, &pressed_to(&points, past)));
        assert!(!once.holds_zone(&points, &vec![1.0; points.points.len()]));
        assert!(!uniform.holds_zone(&flat, &pressed_to(&flat, a)));
    }
}
