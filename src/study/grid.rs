//! The reference's grid (docs/design.md §6): the uniform level finer than every studied one, and
//! its refinement at the contact edges, where p has a square-root profile.

use crate::contact::ContactPoints;
use crate::contact::Rule;
use crate::mesh::{Element, MAX_LEVEL, Mesh};
use crate::scenario::Scenario;

/// The most edge refinements `--reference-refinements` accepts.
pub const MAX_REFINEMENTS: u32 = 8;

/// Why a study's levels and reference level do not fit together.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ReferenceLevelError {
    /// The requested reference is not finer than every studied level.
    #[error("{requested} must be finer than the finest studied level {finest}")]
    NotFiner {
        /// The reference level asked for.
        requested: u32,
        /// The finest studied level.
        finest: u32,
    },
    /// The finest studied level leaves no finer level for the reference.
    #[error("the reference needs a level finer than {finest}; allowed up to {}", MAX_LEVEL - 1)]
    NoFinerLevel {
        /// The finest studied level.
        finest: u32,
    },
}

/// The uniform level of a study's reference (docs/design.md §6): `requested`, or one finer than
/// the finest of `levels`; either way finer than every studied level (coarse solutions are
/// measured on the reference's nested mesh) and at most [`MAX_LEVEL`].
///
/// # Errors
///
/// `requested` not finer than every studied level, or above [`MAX_LEVEL`].
pub fn reference_level(levels: &[u32], requested: Option<u32>) -> Result<u32, ReferenceLevelError> {
    let finest = levels.iter().copied().max().unwrap_or(0);
    match requested {
        Some(requested) if requested <= finest => Err(ReferenceLevelError::NotFiner { requested, finest }),
        Some(requested) => Ok(requested),
        None if finest >= MAX_LEVEL => Err(ReferenceLevelError::NoFinerLevel { finest }),
        None => Ok(finest + 1),
    }
}

/// The reference's grid: the uniform level's vertex lines, with the intervals around the
/// contact edges and next to Γ_C bisected `refinements` times ([`ReferenceMesh::refined`]).
/// Its lines are a superset of the uniform level's, so every studied mesh stays nested in it.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceMesh {
    /// The uniform level it refines.
    pub level: u32,
    /// How many edge refinements it has had (0: the uniform level).
    pub refinements: u32,
    /// Vertex lines x₀ < … and y₀ < … (Γ_C is y = ys.last()).
    pub xs: Vec<f64>,
    /// The horizontal vertex lines y₀ < …, Γ_C the last.
    pub ys: Vec<f64>,
}

impl ReferenceMesh {
    /// The uniform grid of `level` (the lines of [`Scenario::mesh`]).
    pub fn uniform(scenario: &Scenario, level: u32) -> Self {
        let m = scenario.mesh(level, Element::Q1);
        ReferenceMesh {
            level,
            refinements: 0,
            xs: m.xs,
            ys: m.ys,
        }
    }

    /// The Q2 mesh on these lines.
    pub fn mesh(&self, scenario: &Scenario) -> Mesh {
        let (element, _) = REFERENCE_SCHEME;
        Mesh::from_lines(element, self.xs.clone(), self.ys.clone(), scenario.half_model)
    }

    /// Q2 nodes per node row and per node column.
    pub(super) fn node_counts(&self) -> (usize, usize) {
        let p = REFERENCE_SCHEME.0.order();
        (p * (self.xs.len() - 1) + 1, p * (self.ys.len() - 1) + 1)
    }

    /// The free dofs (bottom clamped; u_x fixed on a half model's symmetry line), as
    /// [`Scenario::n_dofs`] counts them on a uniform grid.
    pub fn n_dofs(&self, scenario: &Scenario) -> usize {
        let (nnx, nny) = self.node_counts();
        let symmetric = if scenario.half_model { nny - 1 } else { 0 };
        2 * nnx * (nny - 1) - symmetric
    }

    /// The lengths of u (every dof of the Q2 mesh) and of p (Simpson's points on Γ_C).
    pub fn lengths(&self) -> (usize, usize) {
        let (nnx, nny) = self.node_counts();
        (2 * nnx * nny, REFERENCE_SCHEME.1.n_points(self.xs.len() - 1))
    }

    /// The smallest cell side (h of the uniform level when unrefined).
    pub fn h_min(&self) -> f64 {
        crate::grading::h_min(&self.xs, &self.ys)
    }

    /// The contact edges of the pressure `p` (at Simpson's points on these lines): every
    /// pair of neighbouring points where p goes from > 0 to 0, as the vertex interval that
    /// holds both.
    pub fn contact_edges(&self, p: &[f64]) -> Vec<usize> {
        let (element, rule) = REFERENCE_SCHEME;
        let (nnx, _) = self.node_counts();
        let node_x: Vec<f64> = (0..nnx)
            .map(|i| match i % 2 {
                0 => self.xs[i / 2],
                _ => 0.5 * (self.xs[i / 2] + self.xs[i / 2 + 1]),
            })
            .collect();
        let points = ContactPoints::new(rule, &node_x, element.order());
        crate::grading::contact_edges(&points, p)
    }

    /// The next refinement, as a graded solve's ([`crate::grading::refine_lines`]): the
    /// `EDGE_WIDTH` (2) x-intervals on each side of every contact edge of `p` (and the edge's
    /// own) bisected, and the `EDGE_WIDTH` rows of cells next to Γ_C; None when `p` has no
    /// contact edge (nothing to refine).
    pub fn refined(&self, p: &[f64]) -> Option<Self> {
        let (xs, ys) = crate::grading::refine_lines(&self.xs, &self.ys, &self.contact_edges(p))?;
        Some(ReferenceMesh {
            level: self.level,
            refinements: self.refinements + 1,
            xs,
            ys,
        })
    }
}

/// The reference's element and rule: Q2 + Simpson (M4) with the exact constraint.
pub const REFERENCE_SCHEME: (Element, Rule) = (Element::Q2, Rule::Simpson);

#[cfg(test)]
mod tests {
    use super::*;

    /// The reference is one level finer than the finest studied by default, any finer level
    /// when asked; never one a studied mesh is not nested in, never past MAX_LEVEL.
    #[test]
    fn the_reference_level_is_finer_than_every_studied_level() {
        assert_eq!(reference_level(&[0, 3, 1], None), Ok(4));
        assert_eq!(reference_level(&[0, 1], Some(5)), Ok(5));
        assert_eq!(
            reference_level(&[0, 3], Some(3)),
            Err(ReferenceLevelError::NotFiner {
                requested: 3,
                finest: 3
            })
        );
        assert_eq!(reference_level(&[7], None), Ok(8));
        let none = reference_level(&[MAX_LEVEL], None).unwrap_err();
        assert_eq!(none, ReferenceLevelError::NoFinerLevel { finest: MAX_LEVEL });
        assert_eq!(
            none.to_string(),
            "the reference needs a level finer than 8; allowed up to 7"
        );
    }
}
