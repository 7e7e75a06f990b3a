//! A graded solve's memory, estimated before anything is assembled (docs/design.md §6): its
//! grids are a choice of lines, so their sizes follow from the lines alone. The passes to come
//! are predicted with the obstacle's overlap with the undeformed body standing for the
//! contact zone (the body gives way under the obstacle: the zone it presses lies within the
//! overlap), its ends for the contact edges; the solve's peak holds the uniform level's
//! discretisation, the previous pass's and the last pass's being built ([`super::passes`]). A
//! request whose estimate exceeds what the process may use is refused naming the level, the
//! element, the grading and the memory.

use crate::contact::{Obstacle, Rule};
use crate::discretization::refused;
use crate::error::{SolveError, Workload};
use crate::fem::DofMap;
use crate::fem::memory::{Limits, Sizes};
use crate::mesh::Element;

use super::{GradedGrid, Grading, MAX_PASSES, RefineEdges};

impl GradedGrid {
    /// The sizes that decide the memory of this grid's discretisation with `element`
    /// ([`Sizes::peak_bytes`]), counted on its lines.
    pub fn sizes(&self, element: Element, half_model: bool) -> Sizes {
        let edges = self.xs.len() - 1;
        let nnx = element.node_lines(edges);
        Sizes {
            element,
            unknowns: DofMap::count(nnx, element.node_lines(self.ys.len() - 1), half_model),
            trace: nnx,
            points: Rule::ALL
                .iter()
                .map(|rule| rule.n_points(edges))
                .max()
                .unwrap_or(nnx),
        }
    }
}

/// The grids a solve from the `uniform` grid graded as `grading` asks passes through, the
/// uniform level first, predicted from the `obstacle`'s overlap with the undeformed body
/// ([`Obstacle::contact_extent`]): a zone pass grades the intervals it covers, an edge pass
/// those that hold its ends inside the body. `auto` is predicted at its cap, [`MAX_PASSES`].
/// Only the uniform level when the obstacle does not reach the body.
pub fn predicted(uniform: GradedGrid, obstacle: &Obstacle, grading: Grading) -> Vec<GradedGrid> {
    let (x0, x1) = (uniform.xs[0], uniform.xs[uniform.xs.len() - 1]);
    let passes = match grading {
        Grading::Edges(RefineEdges::Passes(n)) | Grading::Zone(n) => n,
        Grading::Edges(RefineEdges::Auto) => MAX_PASSES,
    };
    let mut grids = vec![uniform.clone()];
    let Some((lo, hi)) = obstacle.contact_extent(x0, x1) else {
        return grids;
    };
    // The vertex interval of `xs` that holds x.
    let interval = |xs: &[f64], x: f64| xs.partition_point(|&v| v <= x).clamp(1, xs.len() - 1) - 1;
    for _ in 0..passes {
        let grid = &grids[grids.len() - 1];
        let next = match grading {
            Grading::Zone(_) => grid.zoned(&uniform, &[(interval(&grid.xs, lo), interval(&grid.xs, hi))]),
            Grading::Edges(_) => {
                let edges: Vec<usize> = [(lo, lo > x0), (hi, hi < x1)]
                    .iter()
                    .filter(|(_, inside)| *inside)
                    .map(|&(x, _)| interval(&grid.xs, x))
                    .collect();
                grid.refined(&edges)
            }
        };
        match next {
            Some(next) => grids.push(next),
            None => break,
        }
    }
    grids
}

/// The estimated peak of a graded solve through `grids` ([`predicted`]) with `element`: the
/// uniform level's discretisation kept throughout, and at each pass the previous pass's kept
/// while the next is built; the largest such sum, bytes.
pub fn peak_bytes(grids: &[GradedGrid], element: Element, half_model: bool) -> u64 {
    let peak = |g: &GradedGrid| g.sizes(element, half_model).peak_bytes();
    let uniform = peak(&grids[0]);
    let mut most = uniform;
    for (k, grid) in grids.iter().enumerate().skip(1) {
        let previous = if k > 1 { peak(&grids[k - 1]) } else { 0 };
        most = most.max(uniform + previous + peak(grid));
    }
    most
}

/// The estimate of a solve through `grids` ([`predicted`]) with `element` (on a half model or
/// not), with `extra` bytes of work on its last grid's sizes beside it (an inf-sup estimate's;
/// 0 for a solve): the last grid's sizes and the peak, bytes.
pub fn estimate(
    grids: &[GradedGrid],
    (element, half_model): (Element, bool),
    extra: impl Fn(&Sizes) -> u64,
) -> (Sizes, u64) {
    let last = grids[grids.len() - 1].sizes(element, half_model);
    let need = peak_bytes(grids, element, half_model).saturating_add(extra(&last));
    (last, need)
}

/// Refuse a solve through `grids` ([`predicted`], the uniform level's first) with `element`
/// graded as `grading` (with `extra`, as [`estimate`]) when its estimate exceeds `limits`;
/// before anything is assembled. Nothing to check without a grading.
///
/// # Errors
///
/// [`SolveError::TooLarge`], naming the level, the element, the grading and the memory.
pub fn fits_within(
    grids: &[GradedGrid],
    (element, half_model): (Element, bool),
    grading: Grading,
    extra: impl Fn(&Sizes) -> u64,
    limits: &Limits,
) -> Result<(), SolveError> {
    if !grading.grades() {
        return Ok(());
    }
    let (last, need) = estimate(grids, (element, half_model), extra);
    last.check_need(need, limits).map_err(|e| {
        let workload = Workload::Graded {
            level: grids[0].level,
            element,
            grading: grading.described(),
        };
        refused(e, workload, last.unknowns)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::ContactParams;
    use crate::contact::newton::NewtonOptions;
    use crate::scenario::Scenario;
    use crate::solve::solve_graded;

    /// The grids [`predicted`] for `s` at `level` graded as `grading`.
    fn grids_of(s: &Scenario, level: u32, grading: Grading) -> Vec<GradedGrid> {
        predicted(
            GradedGrid::uniform(level, &s.mesh(level, Element::Q1)),
            &s.obstacle,
            grading,
        )
    }

    /// The prediction's last grid holds at least the unknowns the paper's graded solves end on
    /// (levels 1 and 2, M1 and M3, two and three passes at the edges and over the zone), and
    /// at most twice as many: the overlap holds the contact zone and is not much wider.
    #[test]
    fn the_predicted_grid_bounds_the_graded_solves() {
        let s = Scenario::paper();
        for (level, element, rule) in [(1, Element::Q1, Rule::Gauss1), (2, Element::Q1, Rule::Trapezoid)] {
            let uniform = s.discretize(level, element).unwrap();
            let params = ContactParams::by_epsilon(rule, s.epsilon, s.obstacle.clone());
            for grading in [
                Grading::Edges(RefineEdges::Passes(2)),
                Grading::Edges(RefineEdges::Passes(3)),
                Grading::Zone(2),
                Grading::Zone(3),
            ] {
                let solved =
                    solve_graded(&s, (level, &uniform), &params, grading, &NewtonOptions::default()).unwrap();
                let grids = grids_of(&s, level, grading);
                assert_eq!(grids.len() as u32, solved.grid.passes + 1, "{grading}");
                let predicted = grids[grids.len() - 1].sizes(element, s.half_model).unknowns;
                let actual = solved.grid.sizes(element, s.half_model).unknowns;
                assert_eq!(
                    actual,
                    solved.disc(&uniform).n_dofs(),
                    "the sizes count the map's dofs"
                );
                assert!(
                    actual <= predicted && predicted <= 2 * actual,
                    "level {level} {grading}: predicted {predicted}, solved {actual}"
                );
            }
        }
    }

    /// Level 8 graded 8 times over the zone: its last grid has hundreds of millions of
    /// unknowns (counted from its lines, in a moment); refused one byte short of its estimate,
    /// naming the level, the element and the grading, and accepted with it. No grading is
    /// never refused here.
    #[test]
    fn a_zone_grading_of_level_8_is_refused_from_its_lines() {
        let s = Scenario::paper();
        let zone = Grading::Zone(8);
        let grids = grids_of(&s, 8, zone);
        let (last, need) = estimate(&grids, (Element::Q1, s.half_model), |_| 0);
        assert!(last.unknowns > 100_000_000, "{}", last.unknowns);
        let room = |bytes: u64| Limits {
            machine: Some(bytes),
            ..Limits::default()
        };
        let e = fits_within(&grids, (Element::Q1, s.half_model), zone, |_| 0, &room(need - 1)).unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("level 8 with q1 graded over the contact zone, 8 passes (8z): ")
                && text.contains(&format!("{} unknowns", last.unknowns)),
            "{text}"
        );
        assert!(e.is_input());
        assert_eq!(
            fits_within(&grids, (Element::Q1, s.half_model), zone, |_| 0, &room(need)),
            Ok(())
        );
        let none = Grading::default();
        assert_eq!(
            fits_within(
                &grids_of(&s, 8, none),
                (Element::Q1, s.half_model),
                none,
                |_| u64::MAX,
                &room(0)
            ),
            Ok(())
        );
    }
}
