//! What the two-body scene solves ([`Settings`]) and what it draws of the solution
//! ([`Solved`]): the interface pressure of the chosen discretisation at the slave's contact
//! points, p̄ on the slave's vertices (for the reduced-integration rules, (17)), the patch
//! test's exact pressure and error (docs/design.md §12), the load, and both meshes near the
//! interface with their displacements ([`Strip`]).

use crate::contact::Method;
use crate::contact::interface::InterfaceMethod;
use crate::contact::interface::solve::{Enforcement, Slave};
use crate::discretization::Discretization;
use crate::scenario::upper::Interface;
use crate::scenario::{Scenario, UpperShape};

/// The element ratios the lab's `k` and `K` step through (upper elements : lower ones across
/// the interface): matching, then ever less commensurate.
pub const RATIOS: [(u32, u32); 4] = [(1, 1), (2, 3), (3, 4), (5, 7)];

/// The ratios `k` and `K` step through on a scenario whose own is `own`: [`RATIOS`], `own`
/// after them when it is not one of them.
pub fn ratios(own: (u32, u32)) -> Vec<(u32, u32)> {
    let mut list = RATIOS.to_vec();
    if !list.contains(&own) {
        list.push(own);
    }
    list
}

/// The offset's step (`j`, `J`), a fraction of the upper body's element.
pub const OFFSET_STEP: f64 = 0.1;

/// The largest offset the keys reach (the scenario's check: |offset| < 1/2).
pub const MAX_OFFSET: f64 = 0.4;

/// The two-body scene's settings: what a solve depends on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The mesh level (both bodies).
    pub level: u32,
    /// The discretisation across the interface.
    pub method: InterfaceMethod,
    /// Upper elements : lower elements across the interface.
    pub ratio: (u32, u32),
    /// The upper mesh's interior vertex lines shifted by this fraction of its element.
    pub offset: f64,
    /// How the constraint is enforced: the penalty's ε, the exact multipliers or the ALM.
    pub enforcement: Enforcement,
}

impl Settings {
    /// The scenario's own settings with `method` (None for a one-body scenario).
    pub fn of(scenario: &Scenario, method: InterfaceMethod) -> Option<Settings> {
        let upper = scenario.upper.as_ref()?;
        Some(Settings {
            level: scenario.level,
            method,
            ratio: upper.ratio,
            offset: upper.offset,
            enforcement: match scenario.method {
                Method::Alm { tolerance } => Enforcement::Alm {
                    epsilon: scenario.epsilon,
                    tolerance,
                },
                _ => Enforcement::from(scenario.epsilon),
            },
        })
    }

    /// `scenario` with these settings' level, ratio and offset.
    pub fn apply(&self, scenario: &Scenario) -> Scenario {
        let mut s = scenario.clone();
        s.level = self.level;
        if let Some(upper) = s.upper.as_mut() {
            upper.ratio = self.ratio;
            upper.offset = self.offset;
        }
        s
    }

    /// `2:3`.
    pub fn ratio_text(&self) -> String {
        format!("{}:{}", self.ratio.0, self.ratio.1)
    }
}

/// A solved two-body scene, as drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct Solved {
    /// What was solved.
    pub settings: Settings,
    /// p at the slave's contact points, ascending x.
    pub p: Vec<(f64, f64)>,
    /// p̄ at the slave's vertices.
    pub pbar: Vec<(f64, f64)>,
    /// On the contact patch test: the exact pressure and max |p − p_exact| / p_exact.
    pub patch: Option<(f64, f64)>,
    /// The load carried across the interface (the modelled bodies).
    pub load: f64,
    /// Active-set (Newton) iterations.
    pub iterations: usize,
    /// The slave's and the master's interface edges.
    pub edges: (usize, usize),
    /// Which body is the slave.
    pub slave: Slave,
    /// The x range of the interface.
    pub x_range: [f64; 2],
    /// The window the meshes are drawn in, across: [`MESH_WINDOW`] of the coarser body's
    /// elements about the middle of the contact zone, within the interface.
    pub window: [f64; 2],
    /// The lower body's mesh near the interface, and the upper body's.
    pub strips: [Strip; 2],
}

/// The meshes' window across, in elements of the coarser body.
pub const MESH_WINDOW: f64 = 12.0;

/// A body's mesh near the interface: its node rows from the interface into the body, as deep
/// as [`STRIP_DEPTH`] windows' widths, each with the nodes over the window (and the next one
/// each side, so that lines reach its edges).
#[derive(Clone, Debug, PartialEq)]
pub struct Strip {
    /// The element's order: every `order`-th node row and column is a vertex line.
    pub order: usize,
    /// The mesh's node column of each row's first node.
    pub first_column: usize,
    /// Node rows, the interface's first (a vertex row).
    pub rows: Vec<Vec<StripNode>>,
}

/// How deep a [`Strip`] reaches, in widths of the window: the meshes' panel shows about a
/// width's depth on either side in a terminal as tall as it is wide.
pub const STRIP_DEPTH: f64 = 1.5;

/// A node of a [`Strip`], in the global frame (y up, the lower body's top at its height).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StripNode {
    /// Where it is, the bodies unpressed: x …
    pub x: f64,
    /// … and y, the upper body's nodes as if it were a block on the lower (its shape's
    /// initial gap g₀ apart, in [`StripNode::lift`]).
    pub y: f64,
    /// The upper body's initial gap g₀ at x (0 in the lower body).
    pub lift: f64,
    /// u_x.
    pub ux: f64,
    /// u_y.
    pub uy: f64,
}

impl Solved {
    /// The frame's data of `interface`, solved with `settings` on `scenario` with those
    /// settings applied ([`Settings::apply`]) across its bodies `lower` and `upper`.
    pub fn of(
        settings: &Settings,
        scenario: &Scenario,
        lower: &Discretization,
        upper: &Discretization,
        interface: Interface,
    ) -> Solved {
        let sol = interface.solution;
        let mut p: Vec<(f64, f64)> = sol.x.iter().copied().zip(sol.p.iter().copied()).collect();
        p.sort_by(|a, b| a.0.total_cmp(&b.0));
        let pbar = sol
            .vertex_x
            .iter()
            .copied()
            .zip(sol.pbar.iter().copied())
            .collect();
        let (x0, x1) = scenario.x_range();
        let slave = scenario.upper.as_ref().map_or(Slave::Upper, |u| u.slave);
        let (slave_edges, master_edges) = match slave {
            Slave::Upper => (upper.mesh.xs.len() - 1, lower.mesh.xs.len() - 1),
            Slave::Lower => (lower.mesh.xs.len() - 1, upper.mesh.xs.len() - 1),
        };
        let element = |xs: &[f64]| (xs[xs.len() - 1] - xs[0]) / (xs.len() - 1) as f64;
        let coarser = element(&lower.mesh.xs).max(element(&upper.mesh.xs));
        let half = (0.5 * MESH_WINDOW * coarser).min(0.5 * (x1 - x0));
        let mut solved = Solved {
            settings: *settings,
            p,
            pbar,
            patch: interface.patch,
            load: sol.load,
            iterations: sol.iterations,
            edges: (slave_edges, master_edges),
            slave,
            x_range: [x0, x1],
            window: [x0, x1],
            strips: [Strip::empty(), Strip::empty()],
        };
        let centre = solved.zone().map_or(0.5 * (x0 + x1), |[a, b]| 0.5 * (a + b));
        let centre = centre.clamp(x0 + half, x1 - half);
        let window = [centre - half, centre + half];
        let depth = STRIP_DEPTH * 2.0 * half;
        let top = scenario.height;
        let lower_strip = Strip::of(&lower.mesh, &sol.bodies[0], window, depth, |x, y| {
            (top - y, [x, y, 0.0])
        });
        let (shape, height) = scenario
            .upper
            .as_ref()
            .map_or((UpperShape::Block, 0.0), |u| (u.shape, u.height));
        // The upper mesh's local y' is its depth below its top: the interface is y' = height.
        let upper_strip = Strip::of(&upper.mesh, &sol.bodies[1], window, depth, |x, y| {
            (height - y, [x, top + height - y, shape.initial_gap(x)])
        });
        solved.window = window;
        solved.strips = [lower_strip, upper_strip];
        solved
    }

    /// The contact zone: from the first to the last contact point where p > 0 (None where
    /// the bodies do not touch).
    pub fn zone(&self) -> Option<[f64; 2]> {
        let mut pressed = self.p.iter().filter(|q| q.1 > 0.0).map(|q| q.0);
        let first = pressed.next()?;
        Some([first, pressed.next_back().unwrap_or(first)])
    }
}

impl Strip {
    /// No rows.
    fn empty() -> Strip {
        Strip {
            order: 1,
            first_column: 0,
            rows: Vec::new(),
        }
    }

    /// The node rows of `mesh` (displacements `u`, (u_x, u_y) by node) whose depth below the
    /// interface is at most `depth` (and the next one), over `window` across: `place` gives a
    /// node's (depth, [x, y, lift]) from its mesh coordinates.
    fn of(
        mesh: &crate::mesh::Mesh,
        u: &[f64],
        window: [f64; 2],
        depth: f64,
        place: impl Fn(f64, f64) -> (f64, [f64; 3]),
    ) -> Strip {
        let nx = &mesh.node_x;
        let first = nx.partition_point(|&x| x < window[0]).saturating_sub(1);
        let last = nx.partition_point(|&x| x <= window[1]).min(nx.len() - 1);
        let mut rows = Vec::new();
        for j in (0..mesh.node_y.len()).rev() {
            let row: Vec<StripNode> = (first..=last)
                .map(|i| {
                    let n = mesh.node(i, j);
                    let (_, [x, y, lift]) = place(nx[i], mesh.node_y[j]);
                    StripNode {
                        x,
                        y,
                        lift,
                        ux: u[2 * n],
                        uy: u[2 * n + 1],
                    }
                })
                .collect();
            rows.push(row);
            if place(nx[first], mesh.node_y[j]).0 >= depth {
                break;
            }
        }
        Strip {
            order: mesh.element.order(),
            first_column: first,
            rows,
        }
    }
}
