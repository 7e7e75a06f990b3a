//! `riplab infsup` on a two-body scenario (docs/design.md §12, "The inf-sup constant across
//! the interface"): β_h of each multiplier space at each level, the two meshes refined at the
//! scenario's fixed ratio and offset, with the observed slope from the level before.

use std::time::Instant;

use faer::Mat;
use serde::Serialize;

use super::interface::{Space, Traces, estimate};
use super::{TraceCompliance, log_slope};
use crate::contact::interface::Side;
use crate::contact::interface::solve::{BodiesError, Slave};
use crate::error::{SolveError, Workload};
use crate::fem::DofMap;
use crate::fem::error::FemError;
use crate::fem::memory::Limits;
use crate::mesh::{Element, Mesh};
use crate::scenario::Scenario;

/// One row: a space at a level.
#[derive(Serialize, Clone, Debug, PartialEq)]
pub struct InterfaceRow {
    /// The mesh level (of the lower body; the upper's follows at the ratio).
    pub level: u32,
    /// The slave's widest edge on the interface.
    pub h: f64,
    /// The master's widest edge on the interface.
    pub h_master: f64,
    /// The element's name ([`Element::name`]), both bodies'.
    pub element: &'static str,
    /// The rule of the reduced-integration penalty's spaces; null for the others.
    pub rule: Option<&'static str>,
    /// The multiplier space ([`Space::name`]).
    pub space: &'static str,
    /// The number of multipliers.
    pub multipliers: usize,
    /// β_h.
    pub beta: f64,
    /// β_h/√h.
    pub beta_over_sqrt_h: f64,
    /// The observed exponent of β_h ∝ h^slope from the previous level of the same space
    /// ([`log_slope`]); null on a space's first row and where β_h = 0.
    pub slope: Option<f64>,
    /// Why β_h = 0 when the multipliers are not unique.
    pub kernel: Option<String>,
    /// The two meshes and their trace compliances (shared by the spaces), ms.
    pub mesh_ms: f64,
    /// The space's own dense work, ms.
    pub space_ms: f64,
}

/// The widest edge of a trace of order `order` (its vertices every `order` nodes).
fn widest_edge(x: &[f64], order: usize) -> f64 {
    x.iter()
        .step_by(order)
        .zip(x.iter().step_by(order).skip(1))
        .map(|(a, b)| b - a)
        .fold(0.0, f64::max)
}

/// Whether the estimate at `level` with `element` fits what this process may use, from the
/// two meshes' lines before anything is assembled: each body's discretisation peak
/// ([`crate::fem::memory::Sizes::peak_bytes`]: its sparse factorisation and the dense trace
/// compliance) and, on the interface, at most 2 multipliers per slave node (every rule's
/// points) with six such square matrices at once and the couplings G C (multipliers × trace).
///
/// # Errors
///
/// [`SolveError::TooLarge`] naming the level and the memory; a one-body scenario
/// ([`BodiesError::OneBody`]).
pub fn fits(scenario: &Scenario, level: u32, element: Element) -> Result<(), BodiesError> {
    let lower = scenario.sizes(level, element);
    let upper = scenario.upper_sizes(level, element).ok_or(BodiesError::OneBody)?;
    let q = 2.0 * lower.trace.max(upper.trace) as f64;
    let m = (lower.trace + upper.trace) as f64;
    let dense = 8.0 * (6.0 * q * q + 2.0 * q * m);
    let need = lower.peak_bytes() + upper.peak_bytes() + dense as u64;
    let unknowns = lower.unknowns + upper.unknowns;
    lower
        .check_need(need, &Limits::of_process())
        .map_err(|e| match e {
            FemError::TooLarge { need, available, .. } => SolveError::TooLarge {
                workload: Workload::Interface {
                    level,
                    element,
                    trace: lower.trace + upper.trace,
                },
                unknowns,
                need,
                available,
            },
            e => crate::discretization::fem_error(e, unknowns),
        })?;
    Ok(())
}

/// One body at a level: its mesh (the trace nodes its top row) and its trace compliance of A.
struct Body {
    mesh: Mesh,
    compliance: Mat<f64>,
}

impl Body {
    fn new(mesh: Mesh, dofs: &DofMap) -> Result<Self, SolveError> {
        let compliance = TraceCompliance::of_mesh(&mesh, dofs)?.c;
        Ok(Body { mesh, compliance })
    }
}

/// The two bodies of `scenario` at `level` with `element`: (slave, master).
fn bodies(scenario: &Scenario, level: u32, element: Element) -> Result<(Body, Body), BodiesError> {
    let upper = scenario.upper.as_ref().ok_or(BodiesError::OneBody)?;
    let lower_mesh = scenario.mesh(level, element);
    let lower_dofs = DofMap::supported(&lower_mesh, scenario.support);
    let lower = Body::new(lower_mesh, &lower_dofs)?;
    let upper_mesh = scenario.upper_mesh(level, element).ok_or(BodiesError::OneBody)?;
    let upper_dofs = DofMap::supported(&upper_mesh, upper.support);
    let upper_body = Body::new(upper_mesh, &upper_dofs)?;
    Ok(match upper.slave {
        Slave::Upper => (upper_body, lower),
        Slave::Lower => (lower, upper_body),
    })
}

/// The table of `riplab infsup` on a two-body scenario: every space of `spaces` at every level
/// of `levels` with the scenario's element, grouped per space in `spaces`' order by ascending
/// level, each row with its slope from the one before. One mesh and one factorisation of A
/// per body and level, shared by the spaces (each row says what the shared work and its own
/// cost).
///
/// # Errors
///
/// A one-body scenario; the first level that does not fit the memory ([`fits`]) or does not
/// factorise; traces that cannot be coupled.
pub fn interface_table(
    scenario: &Scenario,
    spaces: &[Space],
    levels: &[u32],
) -> Result<Vec<InterfaceRow>, BodiesError> {
    let element = scenario.element;
    let order = element.order();
    let mut rows = Vec::new();
    for &level in levels {
        fits(scenario, level, element)?;
        let t = Instant::now();
        let (slave, master) = bodies(scenario, level, element)?;
        let mesh_ms = t.elapsed().as_secs_f64() * 1e3;
        let traces = Traces {
            slave: Side {
                x: &slave.mesh.node_x,
                order,
            },
            master: Side {
                x: &master.mesh.node_x,
                order,
            },
            slave_compliance: &slave.compliance,
            master_compliance: &master.compliance,
        };
        let (h, h_master) = (
            widest_edge(&slave.mesh.node_x, order),
            widest_edge(&master.mesh.node_x, order),
        );
        for &space in spaces {
            let t = Instant::now();
            let est = estimate(space, &traces)?;
            rows.push(InterfaceRow {
                level,
                h,
                h_master,
                element: element.name(),
                rule: space.rule().map(|r| r.name()),
                space: space.name(),
                multipliers: est.multipliers,
                beta: est.beta,
                beta_over_sqrt_h: est.beta / h.sqrt(),
                slope: None,
                kernel: est.kernel,
                mesh_ms,
                space_ms: t.elapsed().as_secs_f64() * 1e3,
            });
        }
    }
    let order_of = |r: &InterfaceRow| spaces.iter().position(|s| s.name() == r.space);
    rows.sort_by_key(|r| (order_of(r), r.level));
    for i in 1..rows.len() {
        if rows[i - 1].space == rows[i].space {
            rows[i].slope = log_slope((rows[i - 1].h, rows[i - 1].beta), (rows[i].h, rows[i].beta));
        }
    }
    Ok(rows)
}
