//! A scenario's graded requests sized before anything is built (docs/design.md §6): the
//! uniform level's lines and the obstacle handed to [`crate::grading::estimate`], which
//! predicts the passes from them and refuses a request that does not fit the memory.

use crate::error::SolveError;
use crate::fem::memory::{Limits, Sizes};
use crate::grading::estimate::{self, predicted};
use crate::grading::{GradedGrid, Grading};
use crate::mesh::Element;

use super::Scenario;

impl Scenario {
    /// The uniform grid of `level`: the vertex lines of [`Scenario::mesh`], no pass yet.
    pub fn uniform_grid(&self, level: u32) -> GradedGrid {
        GradedGrid::uniform(level, &self.mesh(level, Element::Q1))
    }

    /// The grids a solve at `level` graded as `grading` is predicted to pass through, the
    /// uniform level first ([`predicted`], from this scenario's obstacle).
    pub fn graded_grids(&self, level: u32, grading: Grading) -> Vec<GradedGrid> {
        predicted(self.uniform_grid(level), &self.obstacle, grading)
    }

    /// The estimate of a solve at `level` with `element` graded as `grading`, with `extra`
    /// bytes of work on its last grid's sizes beside it (an inf-sup estimate's; 0 for a
    /// solve): the last grid's sizes and the peak, bytes ([`estimate::estimate`]).
    pub fn graded_estimate(
        &self,
        level: u32,
        element: Element,
        grading: Grading,
        extra: impl Fn(&Sizes) -> u64,
    ) -> (Sizes, u64) {
        estimate::estimate(
            &self.graded_grids(level, grading),
            (element, self.half_model),
            extra,
        )
    }

    /// Refuse a solve at `level` with `element` graded as `grading` (with `extra`, as
    /// [`Scenario::graded_estimate`]) when its estimate exceeds what this process may use;
    /// before anything is assembled. Nothing to check without a grading.
    ///
    /// # Errors
    ///
    /// [`SolveError::TooLarge`], naming the level, the element, the grading and the memory.
    pub fn graded_fits(
        &self,
        level: u32,
        element: Element,
        grading: Grading,
        extra: impl Fn(&Sizes) -> u64,
    ) -> Result<(), SolveError> {
        self.graded_fits_within((level, element), grading, extra, &Limits::of_process())
    }

    /// [`Scenario::graded_fits`] against `limits`.
    ///
    /// # Errors
    ///
    /// As [`Scenario::graded_fits`]'s.
    pub fn graded_fits_within(
        &self,
        (level, element): (u32, Element),
        grading: Grading,
        extra: impl Fn(&Sizes) -> u64,
        limits: &Limits,
    ) -> Result<(), SolveError> {
        estimate::fits_within(
            &self.graded_grids(level, grading),
            (element, self.half_model),
            grading,
            extra,
            limits,
        )
    }
}
