//! What the two-body scene solves ([`Settings`]) and what it draws of the solution
//! ([`Solved`]): the interface pressure of the chosen discretisation at the slave's contact
//! points, p̄ on the slave's vertices (for the reduced-integration rules, (17)), the patch
//! test's exact pressure and error (docs/design.md §12) and the load.

use crate::contact::Method;
use crate::contact::interface::InterfaceMethod;
use crate::contact::interface::solve::{Enforcement, Slave};
use crate::discretization::Discretization;
use crate::scenario::Scenario;
use crate::scenario::upper::Interface;

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
        Solved {
            settings: *settings,
            p,
            pbar,
            patch: interface.patch,
            load: sol.load,
            iterations: sol.iterations,
            edges: (slave_edges, master_edges),
            slave,
            x_range: [x0, x1],
        }
    }

    /// The contact zone: from the first to the last contact point where p > 0 (None where
    /// the bodies do not touch).
    pub fn zone(&self) -> Option<[f64; 2]> {
        let mut pressed = self.p.iter().filter(|q| q.1 > 0.0).map(|q| q.0);
        let first = pressed.next()?;
        Some([first, pressed.next_back().unwrap_or(first)])
    }
}
