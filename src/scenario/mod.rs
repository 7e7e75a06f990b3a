//! Scenarios: the model of a problem (docs/design.md §1), with the paper's problem embedded as
//! the default. A scenario is read from its TOML file by the library's reader
//! ([`Scenario::load`], [`Scenario::parse`], [`Scenario::paper`]) and discretised at a level
//! ([`Scenario::discretize`], [`discretize`]: the memory it needs checked before anything is
//! built); a graded request on it is sized from its lines the same way
//! ([`Scenario::graded_fits`], [`crate::grading::estimate`]).

use crate::contact::friction::Friction;
use crate::contact::interface::solve::Slave;
use crate::contact::{Method, Obstacle, Rule};
use crate::fem::{DofMap, Integration, Support};
use crate::grading::{Grading, RefineEdges};
use crate::material::Material;
use crate::mesh::{self, Element, Mesh};

pub mod discretize;
mod graded;
#[doc(hidden)]
pub mod upper;

/// The paper's problem, half model: `scenarios/hertz-paper.toml`.
pub const DEFAULT_SCENARIO: &str = include_str!("../../scenarios/hertz-paper.toml");
/// The name under which the embedded default is reported.
pub const DEFAULT_SOURCE: &str = "<embedded hertz-paper.toml>";

/// A validated problem.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    /// Its name: the file's `name`, or the file name without extension (sanitised).
    pub name: String,
    /// The file's `description`, free text (sanitised).
    pub description: String,
    /// Where it was read from (a path, or [`DEFAULT_SOURCE`]).
    pub source: String,
    /// Full width and height of the body.
    pub width: f64,
    /// Full height of the body.
    pub height: f64,
    /// Model the right half only, u_x = 0 on the symmetry line x = 0.
    pub half_model: bool,
    /// The body's material.
    pub material: Material,
    /// The rigid obstacle pressed into the top Γ_C; with an upper body, its rigid limit: a
    /// flat pressed its top's displacement δ.
    pub obstacle: Obstacle,
    /// How the body's bottom is held (`[body] support`; clamped by default).
    pub support: Support,
    /// The upper elastic body in place of the rigid obstacle (`[upper]`; none by default).
    pub upper: Option<Upper>,
    /// The element of the displacement.
    pub element: Element,
    /// Vertex lines of the level-0 grid across the modelled width and the height (uniform,
    /// or graded); each level bisects every cell.
    pub x_lines: Vec<f64>,
    /// Vertex lines of the level-0 grid up the height (see `x_lines`).
    pub y_lines: Vec<f64>,
    /// Integration of the stiffness: full, or selective (reduced for the volumetric part).
    pub integration: Integration,
    /// The mesh level, 0 ..= [`MAX_LEVEL`](crate::mesh::MAX_LEVEL).
    pub level: u32,
    /// How many times a solve grades its mesh at the contact edges (`[mesh] refine_edges`;
    /// [`crate::grading`]).
    pub refine_edges: RefineEdges,
    /// How many times a solve grades its mesh over the contact zone instead (`[mesh]
    /// refine_edges = "Nz"`; 0: none, and then `refine_edges` says; [`Scenario::grading`]).
    pub refine_zone: u32,
    /// The contact rule on Γ_C.
    pub rule: Rule,
    /// How the constraint is imposed: `[contact] method` (with its parameters), or by ε:
    /// `penalty` for ε > 0, `exact` for ε = 0 ([`Method::resolve`]).
    pub method: Method,
    /// The penalty parameter (0 for `exact`).
    pub epsilon: f64,
    /// Friction on Γ_C and the shift after the press (`[friction]`; [`Friction::NONE`]
    /// without it).
    pub friction: Friction,
}

impl Scenario {
    /// The x-range of the modelled body.
    pub fn x_range(&self) -> (f64, f64) {
        if self.half_model {
            (0.0, self.width / 2.0)
        } else {
            (-self.width / 2.0, self.width / 2.0)
        }
    }

    /// The x-range of the modelled upper body, within [`Scenario::x_range`] (None for a
    /// one-body scenario).
    pub fn upper_x_range(&self) -> Option<(f64, f64)> {
        let width = self.upper.as_ref()?.width;
        Some(if self.half_model {
            (0.0, width / 2.0)
        } else {
            (-width / 2.0, width / 2.0)
        })
    }

    /// The mesh of `level` with `element`: the level-0 grid with every cell bisected `level`
    /// times in each direction.
    pub fn mesh(&self, level: u32, element: Element) -> Mesh {
        Mesh::from_lines(
            element,
            bisect(&self.x_lines, level),
            bisect(&self.y_lines, level),
            self.half_model,
        )
    }

    /// The number of free dofs at `level` with `element`, counted as the mesh and the dof map
    /// count them ([`Element::node_lines`], [`DofMap::count_supported`]) without building the mesh.
    pub fn n_dofs(&self, level: u32, element: Element) -> usize {
        let (cells_x, cells_y) = self.cells(level);
        DofMap::count_supported(
            element.node_lines(cells_x),
            element.node_lines(cells_y),
            self.half_model,
            self.support,
        )
    }

    /// The number of elements at `level` with `element`, counted as the mesh counts them
    /// ([`Element::elements`]) without building it.
    pub fn n_elements(&self, level: u32, element: Element) -> usize {
        let (cells_x, cells_y) = self.cells(level);
        element.elements(cells_x * cells_y)
    }

    /// The cells across and up at `level`: every level bisects each level-0 cell.
    fn cells(&self, level: u32) -> (usize, usize) {
        (
            (self.x_lines.len() - 1) << level,
            (self.y_lines.len() - 1) << level,
        )
    }

    /// How a solve grades its mesh: over the contact zone when `refine_zone` > 0, else at the
    /// contact edges as `refine_edges` says.
    pub fn grading(&self) -> Grading {
        match self.refine_zone {
            0 => Grading::Edges(self.refine_edges),
            n => Grading::Zone(n),
        }
    }

    /// Set how a solve grades its mesh (both fields of [`Scenario::grading`]).
    pub fn set_grading(&mut self, grading: Grading) {
        (self.refine_edges, self.refine_zone) = match grading {
            Grading::Edges(r) => (r, 0),
            Grading::Zone(n) => (RefineEdges::default(), n),
        };
    }

    /// The penalty parameters accepted at `level` ([`crate::material::epsilon_range`]).
    pub fn epsilon_range(&self, level: u32) -> (f64, f64) {
        crate::material::epsilon_range(self.material.young, self.h(level))
    }

    /// The largest cell side at `level` ([`mesh::cell_size`], as [`Mesh::h`]).
    pub fn h(&self, level: u32) -> f64 {
        mesh::cell_size(&self.x_lines, &self.y_lines, level)
    }
}

/// The shape of the upper body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum UpperShape {
    /// A rectangle as wide as the lower body, its bottom flat.
    Block,
    /// A cylinder segment whose bottom is an arc of `radius` touching the lower body at x = 0:
    /// meshed as the block, its arc the initial gap g₀(x) = R − √(R² − x²) (R beyond |x| = R),
    /// measured vertically — the half-space idealisation Hertz's solution itself makes.
    Cylinder {
        /// The arc's radius R.
        radius: f64,
    },
}

impl UpperShape {
    /// The shape's name in scenario files and the outputs.
    pub fn name(self) -> &'static str {
        match self {
            UpperShape::Block => "block",
            UpperShape::Cylinder { .. } => "cylinder",
        }
    }

    /// The initial gap g₀(x) between the shape's bottom and the flat top of the lower body.
    pub fn initial_gap(self, x: f64) -> f64 {
        match self {
            UpperShape::Block => 0.0,
            UpperShape::Cylinder { radius } => {
                let inside = (radius * radius - x * x).max(0.0);
                // x²/(R + √(R² − x²)) against cancellation near x = 0.
                if inside > 0.0 {
                    x * x / (radius + inside.sqrt())
                } else {
                    radius
                }
            }
        }
    }

    /// The arc's radius, for a cylinder.
    pub fn radius(self) -> Option<f64> {
        match self {
            UpperShape::Block => None,
            UpperShape::Cylinder { radius } => Some(radius),
        }
    }
}

/// The upper body of a two-body scenario (`[upper]`).
#[derive(Clone, Debug, PartialEq)]
pub struct Upper {
    /// Its material (the plane strain or stress of the lower body's).
    pub material: Material,
    /// Its height H_u.
    pub height: f64,
    /// Its width, at most the lower body's (the whole body's, centred on x = 0; a half model
    /// meshes its half): narrower, it presses a part of the lower body's top.
    pub width: f64,
    /// Its shape.
    pub shape: UpperShape,
    /// Its elements across the interface against the lower body's: `ratio.0` upper elements
    /// for every `ratio.1` lower ones (rounded to a whole number, at least one).
    pub ratio: (u32, u32),
    /// The fraction of its element width by which its interior vertex lines are shifted (the
    /// ends kept aligned with the lower body's), |offset| < 1/2.
    pub offset: f64,
    /// How its top is held.
    pub support: Support,
    /// The prescribed downward displacement δ of its top (0 under a pressure).
    pub displacement: f64,
    /// A uniform pressure q on its top instead of the displacement: the top is then free but
    /// for a pin (its support [`Support::Free`]) and the pin's descent is found so that the
    /// interface carries q·w (docs/design.md §12).
    pub pressure: Option<f64>,
    /// Which side's trace carries the contact integral.
    pub slave: Slave,
}

/// Vertex lines with every interval bisected `level` times.
fn bisect(lines: &[f64], level: u32) -> Vec<f64> {
    let f = 1usize << level;
    let mut out = Vec::with_capacity((lines.len() - 1) * f + 1);
    for w in lines.windows(2) {
        out.extend((0..f).map(|i| w[0] + (w[1] - w[0]) * i as f64 / f as f64));
    }
    out.push(lines[lines.len() - 1]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_the_paper() {
        let s = Scenario::paper();
        assert_eq!(s.name, "hertz-paper");
        assert_eq!((s.width, s.height, s.half_model), (16.0, 4.0, true));
        assert_eq!(
            s.obstacle,
            Obstacle::Cylinder {
                radius: 8.0,
                depth: 0.8,
                center: 0.0
            }
        );
        assert_eq!(
            (s.x_lines.len(), s.y_lines.len(), s.element, s.rule, s.epsilon),
            (9, 5, Element::Q1, Rule::Gauss1, 1e-6)
        );
        assert_eq!(s.mesh(1, Element::Q1).n_elements(), 128);
        assert_eq!(s.h(1), 0.5);
    }
}
