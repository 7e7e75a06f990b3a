//! The upper elastic body of a two-body scenario (docs/design.md §12): its material, height
//! and shape, its mesh across the interface as a ratio to the lower body's elements and an
//! offset, its support and the prescribed displacement of (or the pressure on) its top, and
//! which side is the slave.
//!
//! Its [`Discretization`] is built on its mesh mirrored, local y' = top − y: the top (its
//! support) is the mesh's bottom row and its Γ_C, the interface, the mesh's top row, so that
//! the trace compliance C = E K⁻¹ Eᵀ on Γ_C's local u_y' = −u_y is the one every contact solver
//! uses, along the body's outward normal. The top's prescribed displacement δ (downwards) is a
//! rigid translation added to that solution; under a pressure the top is free but for a pin,
//! whose descent is found ([`pressed`]).

use std::time::Instant;

use crate::contact::half_plane::e_star;
use crate::contact::interface::solve::{
    Bodies, BodiesError, Enforcement, InterfaceSolution, couple, solve_cancellable,
};
use crate::contact::interface::{Coupling, InterfaceMethod, pressed};
use crate::discretization::Discretization;
use crate::error::SolveError;
use crate::fem::memory::Sizes;
use crate::fem::{DofMap, Support};
use crate::mesh::{Element, Mesh};
use crate::scenario::UpperShape;

use super::Scenario;

/// The largest of the two whole numbers of [`Upper::ratio`](super::Upper::ratio).
pub const MAX_RATIO: u32 = 64;

impl Scenario {
    /// The upper body's mesh at `level` with `element`, in its local coordinates (y' = top − y,
    /// its support the bottom row): ratio · the lower's cells under it across (the interior
    /// lines shifted by `offset` of a cell), cells as close to square as whole numbers allow.
    /// None for a one-body scenario.
    pub fn upper_mesh(&self, level: u32, element: Element) -> Option<Mesh> {
        let upper = self.upper.as_ref()?;
        let (x0, x1) = self.upper_x_range()?;
        // The lower body's elements under the upper one (all of them when it is as wide).
        let under = ((self.x_lines.len() - 1) << level) as f64 * upper.width / self.width;
        let (a, b) = upper.ratio;
        let nx = ((under * f64::from(a) / f64::from(b)).round() as usize).max(1);
        let h = (x1 - x0) / nx as f64;
        let xs: Vec<f64> = (0..=nx)
            .map(|i| match i {
                0 => x0,
                i if i == nx => x1,
                i => x0 + (i as f64 + upper.offset) * h,
            })
            .collect();
        let ny = ((upper.height / h).round() as usize).clamp(1, 1 << 16);
        let ys: Vec<f64> = (0..=ny).map(|j| upper.height * j as f64 / ny as f64).collect();
        Some(Mesh::from_lines(element, xs, ys, self.half_model))
    }

    /// The upper body's discretisation at `level` with `element` (None for a one-body
    /// scenario), refused before anything is allocated when its memory estimate exceeds what
    /// this process may use less `reserved` bytes.
    ///
    /// # Errors
    ///
    /// As [`Scenario::discretize`]'s.
    pub fn discretize_upper(
        &self,
        level: u32,
        element: Element,
        reserved: u64,
    ) -> Result<Option<Discretization>, SolveError> {
        let (Some(upper), Some(mesh)) = (&self.upper, self.upper_mesh(level, element)) else {
            return Ok(None);
        };
        super::discretize::fits(&self.upper_sizes_of(&mesh), level, reserved)?;
        let dofs = DofMap::supported(&mesh, upper.support);
        Discretization::with_dofs(mesh, dofs, upper.material, self.integration).map(Some)
    }

    /// The sizes that decide the memory of the upper body's discretisation at `level` with
    /// `element` ([`Sizes::peak_bytes`]); None for a one-body scenario.
    pub fn upper_sizes(&self, level: u32, element: Element) -> Option<Sizes> {
        self.upper_mesh(level, element)
            .map(|mesh| self.upper_sizes_of(&mesh))
    }

    /// The sizes of the upper body on `mesh`, its mesh (points: two per trace node, above
    /// every rule's).
    fn upper_sizes_of(&self, mesh: &Mesh) -> Sizes {
        let support = self.upper.as_ref().map_or(self.support, |u| u.support);
        Sizes {
            element: mesh.element,
            unknowns: DofMap::count_supported(mesh.nnx(), mesh.node_y.len(), self.half_model, support),
            trace: mesh.nnx(),
            points: 2 * mesh.nnx(),
        }
    }

    /// The pressure of the contact patch test (docs/design.md §12), when this scenario is one:
    /// two blocks of one width, the lower on rollers, the upper's top pressed δ > 0 on rollers
    /// or under a pressure q (lifted, they carry nothing; a narrower upper block is a punch,
    /// its pressure not uniform). Both bodies then carry the uniform σ_yy = −p with σ_xx = 0:
    /// under a pressure p = q; under δ each body is shortened by p·H/E' (E' the plane modulus)
    /// and the penalty's gap −εp closes the rest:
    ///
    /// p = δ / (H_l/E'_l + H_u/E'_u + ε).
    pub fn patch_pressure(&self, epsilon: f64) -> Option<f64> {
        let upper = self.upper.as_ref()?;
        let blocks =
            upper.shape == UpperShape::Block && upper.width == self.width && self.support == Support::Roller;
        match upper.pressure {
            Some(q) => blocks.then_some(q),
            None => (blocks && upper.support == Support::Roller && upper.displacement > 0.0)
                .then(|| upper.displacement / (self.compliance_across() + epsilon)),
        }
    }

    /// H_l/E'_l + H_u/E'_u: the two bodies' uniform compression per unit pressure (0 for a
    /// one-body scenario).
    fn compliance_across(&self) -> f64 {
        self.upper.as_ref().map_or(0.0, |upper| {
            self.height / e_star(&self.material) + upper.height / e_star(&upper.material)
        })
    }
}

/// A two-body scenario solved at a level ([`Scenario::solve_bodies`]).
pub struct TwoBodies {
    /// The lower body's discretisation.
    pub lower: Discretization,
    /// The upper body's, on its mirrored mesh.
    pub upper: Discretization,
    /// The constraint across the interface.
    pub coupling: Coupling,
    /// The solution.
    pub solution: InterfaceSolution,
    /// On the contact patch test ([`Scenario::patch_pressure`]): its exact pressure, and
    /// max_k |p_k − p| / p over the slave's constraints.
    pub patch: Option<(f64, f64)>,
    /// The descent of the upper body's top: prescribed, or under a pressure the pin's, found so
    /// that the interface carries the load ([`pressed`]).
    pub descent: f64,
}

/// The contact of a two-body scenario solved on its discretised bodies
/// ([`Scenario::solve_discretized`]).
pub struct Interface {
    /// The constraint across the interface.
    pub coupling: Coupling,
    /// The solution.
    pub solution: InterfaceSolution,
    /// On the contact patch test ([`Scenario::patch_pressure`]): its exact pressure, and
    /// max_k |p_k − p| / p over the slave's constraints.
    pub patch: Option<(f64, f64)>,
    /// The descent of the upper body's top: prescribed, or under a pressure the pin's, found so
    /// that the interface carries the load ([`pressed`]).
    pub descent: f64,
    /// The coupling's wall time, ms: the segmentation, the rows' integrals and the initial
    /// gaps (the rest of the solve across the interface is the condensation and Newton's).
    pub coupling_ms: f64,
}

impl Scenario {
    /// This two-body scenario's bodies discretised at `level` with its element: (the lower
    /// body, the upper body on its mirrored mesh), each refused before anything is allocated
    /// when its memory estimate exceeds what this process may use.
    ///
    /// # Errors
    ///
    /// A one-body scenario, or as [`Scenario::discretize`]'s.
    pub fn discretize_bodies(&self, level: u32) -> Result<(Discretization, Discretization), BodiesError> {
        self.upper.as_ref().ok_or(BodiesError::OneBody)?;
        let lower = self.discretize(level, self.element)?;
        let upper = self
            .discretize_upper(level, self.element, 0)?
            .ok_or(BodiesError::OneBody)?;
        Ok((lower, upper))
    }

    /// Solve the contact of this two-body scenario's bodies `lower` and `upper`, discretised
    /// at one level ([`Scenario::discretize_bodies`], or [`Scenario::discretize`] and
    /// [`Scenario::discretize_upper`] of a scenario with this one's `[upper]` body up to its
    /// mesh's ratio and offset), the interface discretised by `method`, the constraint
    /// enforced as `enforcement` says (an ε: the penalty at ε > 0, the exact multipliers at 0;
    /// or the ALM); given up as soon as `cancelled` says so.
    ///
    /// # Errors
    ///
    /// A one-body scenario, traces that cannot be coupled, or as
    /// [`crate::contact::interface::solve::solve_cancellable`]'s and
    /// [`pressed::solve_pressed`]'s ([`SolveError::Cancelled`] among them).
    pub fn solve_discretized(
        &self,
        lower: &Discretization,
        upper: &Discretization,
        method: InterfaceMethod,
        enforcement: impl Into<Enforcement>,
        cancelled: &dyn Fn() -> bool,
    ) -> Result<Interface, BodiesError> {
        let enforcement = enforcement.into();
        let upper_body = self.upper.as_ref().ok_or(BodiesError::OneBody)?;
        let bodies = Bodies {
            lower,
            upper,
            displacement: upper_body.displacement,
            slave: upper_body.slave,
        };
        let shape = upper_body.shape;
        let started = Instant::now();
        let (coupling, g0, rule) = couple(&bodies, method, |x| shape.initial_gap(x))?;
        let coupling_ms = started.elapsed().as_secs_f64() * 1e3;
        let (solution, descent) = match upper_body.pressure {
            None => (
                solve_cancellable(&bodies, &coupling, &g0, enforcement, rule, cancelled)?,
                upper_body.displacement,
            ),
            Some(q) => {
                let first = q * (self.compliance_across() + enforcement.epsilon());
                let coupled = (&coupling, g0.as_slice(), rule);
                pressed::solve_pressed(&bodies, coupled, enforcement, (q, first), cancelled)?
            }
        };
        // The penalty's patch pressure is softened by ε; the exact multipliers' and the ALM's is not.
        let softening = if enforcement.is_exact() {
            0.0
        } else {
            enforcement.epsilon()
        };
        let patch = self.patch_pressure(softening).map(|exact| {
            let error = solution
                .p
                .iter()
                .fold(0.0_f64, |m, p| m.max((p - exact).abs() / exact));
            (exact, error)
        });
        Ok(Interface {
            coupling,
            solution,
            patch,
            descent,
            coupling_ms,
        })
    }

    /// Solve this two-body scenario at `level` with its element, the interface discretised by
    /// `method`, the constraint enforced as `enforcement` says (an ε: the penalty at ε > 0, the
    /// exact multipliers at 0; or the ALM): [`Scenario::discretize_bodies`] then
    /// [`Scenario::solve_discretized`].
    ///
    /// # Errors
    ///
    /// A one-body scenario, a mesh too large for the memory, or as
    /// [`crate::contact::interface::solve::solve_method`]'s.
    pub fn solve_bodies(
        &self,
        level: u32,
        method: InterfaceMethod,
        enforcement: impl Into<Enforcement>,
    ) -> Result<TwoBodies, BodiesError> {
        let (lower, upper) = self.discretize_bodies(level)?;
        let interface = self.solve_discretized(&lower, &upper, method, enforcement, &|| false)?;
        Ok(TwoBodies::of(lower, upper, interface))
    }
}

impl TwoBodies {
    /// The bodies `lower` and `upper` with their `interface` solved
    /// ([`Scenario::solve_discretized`]).
    pub fn of(lower: Discretization, upper: Discretization, interface: Interface) -> TwoBodies {
        let Interface {
            coupling,
            solution,
            patch,
            descent,
            ..
        } = interface;
        TwoBodies {
            lower,
            upper,
            coupling,
            solution,
            patch,
            descent,
        }
    }
}
