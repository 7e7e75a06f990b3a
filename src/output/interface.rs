//! The report of a two-body solve (docs/design.md §7, §12): the interface's pressures and both
//! traces' displacements, the bodies, the load and, on the contact patch test, its error.

use std::fmt::Write as _;

use serde::Serialize;

use super::{Cell, Report, csv_table};
use crate::contact::interface::InterfaceMethod;
use crate::contact::interface::solve::{Enforcement, TraceDisplacement};
use crate::scenario::Scenario;
use crate::scenario::upper::TwoBodies;
use crate::text::num;

/// One body's material and shape, as the scenario gives them.
#[derive(Serialize)]
pub struct BodyReport {
    /// Young's modulus E.
    pub young: f64,
    /// Poisson's ratio ν.
    pub poisson: f64,
    /// Its shape: `block` or `cylinder`.
    pub shape: &'static str,
    /// A cylinder's radius (null for a block).
    pub radius: Option<f64>,
    /// Its full width.
    pub width: f64,
    /// Its height.
    pub height: f64,
    /// `clamped` or `roller`.
    pub support: &'static str,
    /// Its elements across the interface at the level solved.
    pub elements_across: usize,
    /// The downward displacement δ of the upper body's top: prescribed, or under a pressure
    /// its pin's descent, found so that the interface carries the load (null for the lower).
    pub displacement: Option<f64>,
    /// The uniform pressure q on the upper body's top (null when its displacement is
    /// prescribed, and for the lower).
    pub pressure: Option<f64>,
}

/// Both bodies.
#[derive(Serialize)]
pub struct Bodies {
    /// The lower body.
    pub lower: BodyReport,
    /// The upper body.
    pub upper: BodyReport,
}

/// The slave's interface vertices.
#[derive(Serialize)]
pub struct SlaveNodes {
    /// The vertices' x.
    pub x: Vec<f64>,
    /// u_x at each.
    pub ux: Vec<f64>,
    /// u_y at each (global, y up).
    pub uy: Vec<f64>,
    /// p̄ at each: I(p, φ_i)/I(1, φ_i), (17) for the reduced-integration rules.
    pub pbar: Vec<f64>,
}

/// The master's interface vertices.
#[derive(Serialize)]
pub struct MasterNodes {
    /// The vertices' x.
    pub x: Vec<f64>,
    /// u_x at each.
    pub ux: Vec<f64>,
    /// u_y at each (global, y up).
    pub uy: Vec<f64>,
}

/// The constraints' points.
#[derive(Serialize)]
pub struct InterfacePoints {
    /// Where each constraint sits.
    pub x: Vec<f64>,
    /// Its pressure, compression positive.
    pub p: Vec<f64>,
}

/// The interface: the discretisation's name, the slave's vertices and points, the master's
/// vertices.
#[derive(Serialize)]
pub struct Interface {
    /// `nts`, `nts2`, `mortar`, `mortar-dual` or `rip-<rule>`.
    pub contact: &'static str,
    /// `upper` or `lower`.
    pub slave: &'static str,
    /// The slave's interface vertices.
    pub nodes: SlaveNodes,
    /// The constraints.
    pub points: InterfacePoints,
    /// The master's interface vertices.
    pub master: MasterNodes,
}

/// The wall time of a two-body solve and the parts of it each body's discretisation measured
/// (summed over both bodies), then the solve across the interface, ms: as the one-body JSON's
/// `timing_ms` (docs/design.md §7).
#[derive(Serialize)]
pub struct BodiesTiming {
    /// Assembly of both bodies' K.
    pub assembly: f64,
    /// Their orderings and symbolic factorisations.
    pub symbolic: f64,
    /// Their numeric factorisations and trace compliances.
    pub factorization: f64,
    /// The solve across the interface on the bodies built: the coupling, the condensation,
    /// the Newton solve (under a pressure, every descent tried) and the bodies' displacements.
    pub interface: f64,
    /// Of `interface`, the coupling: the segmentation, the rows' integrals, the initial gaps.
    pub coupling: f64,
    /// Of `interface`, the rest: the condensation, Newton's iterations and the displacements.
    pub contact: f64,
    /// The whole solve: both meshes and discretisations, the coupling, the Newton solve and
    /// the traces' displacements.
    pub total: f64,
}

/// The JSON object of a two-body solve.
#[derive(Serialize)]
pub struct InterfaceReport {
    /// The scenario's name.
    pub scenario: String,
    /// The element of both bodies.
    pub element: &'static str,
    /// The lower body's level.
    pub level: u32,
    /// How the constraint is enforced: `penalty`, `exact` or `alm`.
    pub method: &'static str,
    /// ε (0: the exact multipliers).
    pub epsilon: f64,
    /// The ALM's tolerance on the multipliers' change.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub alm_tolerance: Option<f64>,
    /// The free dofs of both bodies.
    pub n_dofs: usize,
    /// Newton (active-set) iterations (the ALM's: over all its updates).
    pub newton_iterations: usize,
    /// The ALM's multiplier updates.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub outer_iterations: Option<usize>,
    /// Always true: a solve that does not converge is an error.
    pub converged: bool,
    /// Whether the half model is solved.
    pub half_model: bool,
    /// Both bodies.
    pub bodies: Bodies,
    /// The interface.
    pub interface: Interface,
    /// The load carried across the interface by the modelled bodies.
    #[serde(rename = "P")]
    pub load: f64,
    /// On the contact patch test: the exact uniform pressure.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub p_applied: Option<f64>,
    /// On the contact patch test: max |p − p_applied| / p_applied over the constraints.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub patch_error: Option<f64>,
    /// The solve's wall time and its parts, ms.
    pub timing_ms: BodiesTiming,
}

/// Every `order`-th value: the vertices among a trace's nodes.
fn vertices(v: &[f64], order: usize) -> Vec<f64> {
    v.iter().step_by(order).copied().collect()
}

impl InterfaceReport {
    /// The report of `solved`, `scenario` at `level` with `method` and ε: its solve across the
    /// interface took `interface_ms` of the whole `total_ms`, its coupling `coupling_ms` of those.
    pub fn new(
        scenario: &Scenario,
        level: u32,
        method: InterfaceMethod,
        enforcement: impl Into<Enforcement>,
        solved: &TwoBodies,
        (coupling_ms, interface_ms, total_ms): (f64, f64, f64),
    ) -> Self {
        let enforcement = enforcement.into();
        let upper = scenario.upper.as_ref().expect("a two-body scenario");
        let order = scenario.element.order();
        let sol = &solved.solution;
        let trace = |t: &TraceDisplacement| {
            (
                vertices(&t.x, order),
                vertices(&t.ux, order),
                vertices(&t.uy, order),
            )
        };
        let (sx, sux, suy) = trace(&sol.slave);
        let (mx, mux, muy) = trace(&sol.master);
        InterfaceReport {
            scenario: scenario.name.clone(),
            element: scenario.element.name(),
            level,
            method: match enforcement {
                Enforcement::Exact => "exact",
                Enforcement::Penalty(_) => "penalty",
                Enforcement::Alm { .. } => "alm",
            },
            epsilon: enforcement.epsilon(),
            alm_tolerance: match enforcement {
                Enforcement::Alm { tolerance, .. } => Some(tolerance),
                _ => None,
            },
            n_dofs: solved.lower.n_dofs() + solved.upper.n_dofs(),
            newton_iterations: sol.iterations,
            outer_iterations: sol.outer_iterations,
            converged: true,
            half_model: scenario.half_model,
            bodies: Bodies {
                lower: BodyReport {
                    young: scenario.material.young,
                    poisson: scenario.material.poisson,
                    shape: "block",
                    radius: None,
                    width: scenario.width,
                    height: scenario.height,
                    support: scenario.support.name(),
                    elements_across: solved.lower.mesh().nx(),
                    displacement: None,
                    pressure: None,
                },
                upper: BodyReport {
                    young: upper.material.young,
                    poisson: upper.material.poisson,
                    shape: upper.shape.name(),
                    radius: upper.shape.radius(),
                    width: upper.width,
                    height: upper.height,
                    support: upper.support.name(),
                    elements_across: solved.upper.mesh().nx(),
                    displacement: Some(solved.descent),
                    pressure: upper.pressure,
                },
            },
            interface: Interface {
                contact: method.name(),
                slave: upper.slave.name(),
                nodes: SlaveNodes {
                    x: sx,
                    ux: sux,
                    uy: suy,
                    pbar: sol.pbar.clone(),
                },
                points: InterfacePoints {
                    x: sol.x.clone(),
                    p: sol.p.clone(),
                },
                master: MasterNodes {
                    x: mx,
                    ux: mux,
                    uy: muy,
                },
            },
            load: sol.load,
            p_applied: solved.patch.map(|p| p.0),
            patch_error: solved.patch.map(|p| p.1),
            timing_ms: BodiesTiming {
                assembly: solved.lower.assembly_ms + solved.upper.assembly_ms,
                symbolic: solved.lower.symbolic_ms + solved.upper.symbolic_ms,
                factorization: solved.lower.factorization_ms + solved.upper.factorization_ms,
                interface: interface_ms,
                coupling: coupling_ms,
                contact: interface_ms - coupling_ms,
                total: total_ms,
            },
        }
    }
}

impl Report for InterfaceReport {
    fn table(&self) -> String {
        let mut s = String::new();
        let (l, u) = (&self.bodies.lower, &self.bodies.upper);
        let _ = writeln!(
            s,
            "{} — two bodies, {}, level {}, {} dofs; contact {} ({} slave), {}, {} Newton iteration{}, {:.1} ms",
            self.scenario,
            self.element,
            self.level,
            self.n_dofs,
            self.interface.contact,
            self.interface.slave,
            match (self.method, self.alm_tolerance, self.outer_iterations) {
                ("alm", Some(tolerance), Some(updates)) => format!(
                    "ALM at ε = {:e} (tolerance {tolerance:e}), {updates} multiplier update{}",
                    self.epsilon,
                    if updates == 1 { "" } else { "s" }
                ),
                ("penalty", ..) => format!("penalty ε = {:e}", self.epsilon),
                _ => "exact multipliers (ε = 0)".to_string(),
            },
            self.newton_iterations,
            if self.newton_iterations == 1 { "" } else { "s" },
            self.timing_ms.total
        );
        for (name, b) in [("lower", l), ("upper", u)] {
            let _ = writeln!(
                s,
                "  {name}: {} {} × {}, E = {}, ν = {}, {} support, {} elements across{}",
                b.shape,
                b.width,
                b.height,
                b.young,
                b.poisson,
                b.support,
                b.elements_across,
                match (b.pressure, b.displacement) {
                    (Some(q), Some(d)) =>
                        format!(", top under pressure {}, its pin descended {}", num(q), num(d)),
                    (None, Some(d)) => format!(", top pressed {}", num(d)),
                    _ => String::new(),
                }
            );
        }
        let _ = writeln!(s, "load P = {:.6e}", self.load);
        if let (Some(p), Some(e)) = (self.p_applied, self.patch_error) {
            let _ = writeln!(s, "patch test: p_applied = {p:.6e}, patch error = {e:.3e}");
        }
        let _ = writeln!(s, "{:>12} {:>14} {:>14} {:>14}", "x", "u_x", "u_y", "p̄");
        let n = &self.interface.nodes;
        for i in 0..n.x.len() {
            let _ = writeln!(
                s,
                "{:>12.6} {:>14.6e} {:>14.6e} {:>14.6e}",
                n.x[i], n.ux[i], n.uy[i], n.pbar[i]
            );
        }
        s
    }

    /// One row: the summary of [`INTERFACE_COLUMNS`].
    fn csv(&self) -> String {
        csv_table(std::slice::from_ref(self), &INTERFACE_COLUMNS)
    }
}

/// The CSV columns of a two-body solve, each a field of its JSON.
pub const INTERFACE_COLUMNS: [(&str, Cell); 10] = [
    ("scenario", Cell::Field("/scenario")),
    ("contact", Cell::Field("/interface/contact")),
    ("slave", Cell::Field("/interface/slave")),
    ("level", Cell::Field("/level")),
    ("method", Cell::Field("/method")),
    ("epsilon", Cell::Field("/epsilon")),
    ("n_dofs", Cell::Field("/n_dofs")),
    ("P", Cell::Field("/P")),
    ("max_p", Cell::Max("/interface/points/p")),
    ("patch_error", Cell::Field("/patch_error")),
];
