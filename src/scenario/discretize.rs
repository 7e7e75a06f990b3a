//! A scenario's [`Discretization`] at a level, refused before anything is allocated when its
//! memory estimate exceeds the memory this process may use ([`crate::fem::memory`],
//! docs/design.md §6).

use crate::contact::{ContactPoints, Rule};
use crate::discretization::{Discretization, Trace, refused};
use crate::error::{SolveError, Workload};
use crate::fem::DofMap;
use crate::fem::memory::{Limits, Sizes};
use crate::mesh::Element;

use super::Scenario;

impl Scenario {
    /// The discretisation of this scenario at `level` with `element`, refused before anything
    /// is allocated when its memory estimate exceeds the memory this process may use
    /// ([`crate::fem::memory`]).
    ///
    /// # Errors
    ///
    /// The estimate does not fit the memory ([`SolveError::TooLarge`]), or as
    /// [`Discretization::new`]'s.
    pub fn discretize(&self, level: u32, element: Element) -> Result<Discretization, SolveError> {
        self.discretize_beside(level, element, 0)
    }

    /// [`Scenario::discretize`] with `trace` ordered last ([`Trace::Full`] for friction: one
    /// factorisation gives both the normal and the full trace compliance).
    ///
    /// # Errors
    ///
    /// As [`Scenario::discretize`]'s and [`Discretization::with_trace`]'s.
    pub fn discretize_traced(
        &self,
        level: u32,
        element: Element,
        trace: Trace,
    ) -> Result<Discretization, SolveError> {
        if trace == Trace::Normal {
            return self.discretize(level, element);
        }
        let mut sizes = self.sizes(level, element);
        sizes.trace *= 2;
        sizes.check(&Limits::of_process()).map_err(|e| {
            let workload = Workload::Level {
                level,
                element,
                trace: sizes.trace,
                reserved: false,
            };
            refused(e, workload, sizes.unknowns)
        })?;
        let mesh = self.mesh(level, element);
        let dofs = DofMap::supported(&mesh, self.support);
        Discretization::with_trace(mesh, dofs, self.material, self.integration, trace)
    }

    /// [`Scenario::discretize`] beside other work under way that may still take `reserved`
    /// bytes: refused when its estimate exceeds what this process may use less `reserved`.
    ///
    /// # Errors
    ///
    /// As [`Scenario::discretize`]'s, with `reserved` counted.
    pub fn discretize_beside(
        &self,
        level: u32,
        element: Element,
        reserved: u64,
    ) -> Result<Discretization, SolveError> {
        self.fits_beside(level, element, reserved)?;
        let mesh = self.mesh(level, element);
        let dofs = DofMap::supported(&mesh, self.support);
        Discretization::with_dofs(mesh, dofs, self.material, self.integration)
    }

    /// Whether the memory this process may use less `reserved` bytes holds the estimated peak
    /// of the mesh of `level` with `element` (its build, or another factorisation of the same
    /// size); why not otherwise.
    ///
    /// # Errors
    ///
    /// [`SolveError::TooLarge`], naming the unknowns, the memory needed and what is available.
    pub fn fits_beside(&self, level: u32, element: Element, reserved: u64) -> Result<(), SolveError> {
        fits(&self.sizes(level, element), level, reserved)
    }

    /// The sizes that decide the memory of the discretisation of this scenario at `level`
    /// with `element` ([`Sizes::peak_bytes`]), counted on the mesh's lines without
    /// assembling.
    pub fn sizes(&self, level: u32, element: Element) -> Sizes {
        let mesh = self.mesh(level, element);
        let trace = mesh.nnx();
        Sizes {
            element,
            unknowns: self.n_dofs(level, element),
            trace,
            points: Rule::ALL
                .iter()
                .map(|&rule| ContactPoints::new(rule, &mesh.node_x, element.order()).len())
                .max()
                .unwrap_or(trace),
        }
    }
}

/// `sizes` (a mesh of `level`) checked against what this process may use less `reserved`
/// bytes: [`SolveError::TooLarge`] naming the level, the element and the memory when they do
/// not fit.
pub(super) fn fits(sizes: &Sizes, level: u32, reserved: u64) -> Result<(), SolveError> {
    sizes.check(&Limits::of_process().less(reserved)).map_err(|e| {
        let workload = Workload::Level {
            level,
            element: sizes.element,
            trace: sizes.trace,
            reserved: reserved > 0,
        };
        refused(e, workload, sizes.unknowns)
    })
}
