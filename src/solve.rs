//! From a scenario to a solution: the work that depends only on the mesh (assembly of K,
//! symbolic factorisation) is held in a [`Discretization`] and done once; each contact solve
//! (rule, ε, obstacle) reuses it.

use std::ops::ControlFlow;
use std::time::Instant;

use faer::Side;
use faer::sparse::linalg::solvers::SymbolicLlt;
use serde::Serialize;

use crate::contact::penalty::{self, Iteration, NewtonOptions, NewtonResult, Penalty, SolveError, Trace};
use crate::contact::{ContactPoints, Obstacle, Rule, load, raw_pressure, smoothed_pressure};
use crate::fem::{DofMap, Form, SymCsc, assemble};
use crate::material::Material;
use crate::mesh::{Element, Mesh};
use crate::scenario::Scenario;

fn ms_since(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// Everything that depends on the mesh alone.
pub struct Discretization {
    pub mesh: Mesh,
    pub material: Material,
    pub dofs: DofMap,
    /// K of (2) on the free dofs.
    pub stiffness: SymCsc,
    /// K's symbolic Cholesky factorisation (fill-reducing ordering and elimination tree).
    pub symbolic: SymbolicLlt<usize>,
    /// The free dof of u_n = u_y at each Γ_C node, in ascending x.
    pub contact_dofs: Vec<usize>,
    pub assembly_ms: f64,
    pub symbolic_ms: f64,
}

impl Discretization {
    pub fn new(mesh: Mesh, material: Material) -> Result<Self, SolveError> {
        let t = Instant::now();
        let dofs = DofMap::model(&mesh);
        let stiffness = assemble(&mesh, &dofs, Form::Elasticity(material));
        let assembly_ms = ms_since(t);
        let t = Instant::now();
        let symbolic = SymbolicLlt::try_new(stiffness.symbolic(), Side::Lower)
            .map_err(|e| SolveError::Factorization(format!("{e:?}")))?;
        let symbolic_ms = ms_since(t);
        let contact_dofs = mesh
            .top_nodes()
            .iter()
            .map(|&n| {
                dofs.free_index(2 * n + 1)
                    .expect("Γ_C is not on the clamped side")
            })
            .collect();
        Ok(Discretization {
            mesh,
            material,
            dofs,
            stiffness,
            symbolic,
            contact_dofs,
            assembly_ms,
            symbolic_ms,
        })
    }

    /// The discretisation of `scenario` at `level` with `element`.
    pub fn of(scenario: &Scenario, level: u32, element: Element) -> Result<Self, SolveError> {
        Self::new(scenario.mesh(level, element), scenario.material)
    }

    /// `rule` laid on Γ_C.
    pub fn contact_points(&self, rule: Rule) -> ContactPoints {
        let nnx = self.mesh.nnx();
        ContactPoints::new(rule, &self.mesh.node_x[..nnx], self.mesh.element.order())
    }

    /// The trace operator B on the free dofs for `points`.
    pub fn trace(&self, points: &ContactPoints) -> Trace {
        Trace {
            rows: points
                .points
                .iter()
                .map(|q| {
                    q.nodes
                        .iter()
                        .zip(&q.trace)
                        .map(|(&k, &c)| (self.contact_dofs[k], c))
                        .collect()
                })
                .collect(),
        }
    }

    pub fn n_dofs(&self) -> usize {
        self.dofs.n_free()
    }
}

/// What a contact solve depends on beyond the mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactParams {
    pub rule: Rule,
    pub epsilon: f64,
    pub obstacle: Obstacle,
}

/// Wall-clock time of the parts of one solve, in milliseconds.
#[derive(Clone, Copy, Debug, Default, Serialize, PartialEq)]
pub struct Timing {
    /// Assembly of K (0 when the mesh's work was reused).
    pub assembly: f64,
    /// Symbolic factorisation (0 when reused).
    pub symbolic: f64,
    /// Numeric factorisations and solves inside Newton.
    pub factorization: f64,
    /// The whole Newton solve, factorisations included.
    pub newton: f64,
    /// Everything this solve did.
    pub total: f64,
}

/// The solution of (11) with its pressures.
#[derive(Clone, Debug)]
pub struct Solution {
    pub params: ContactParams,
    pub points: ContactPoints,
    pub newton: NewtonResult,
    /// Raw pressure p at the rule's points (12).
    pub p: Vec<f64>,
    /// Smoothed pressure p̄ at the Γ_C vertices (16)–(17).
    pub pbar: Vec<f64>,
    /// u_y at the Γ_C vertices.
    pub vertex_uy: Vec<f64>,
    /// P = I(p, 1), the load carried by the modelled body.
    pub load: f64,
    pub timing: Timing,
}

impl Solution {
    /// Displacement on every dof (zero on the constrained ones).
    pub fn displacement(&self, disc: &Discretization) -> Vec<f64> {
        disc.dofs.expand(&self.newton.u, |_| 0.0)
    }
}

/// Solve the contact problem on `disc`, from `initial` (free dofs) if given.
pub fn solve_contact(
    disc: &Discretization,
    params: &ContactParams,
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<Solution, SolveError> {
    let t = Instant::now();
    let points = disc.contact_points(params.rule);
    let trace = disc.trace(&points);
    let weight: Vec<f64> = points.points.iter().map(|q| q.weight).collect();
    let gap: Vec<f64> = points.points.iter().map(|q| params.obstacle.gap(q.x)).collect();
    let f = vec![0.0; disc.n_dofs()];
    let problem = Penalty {
        stiffness: &disc.stiffness,
        symbolic: &disc.symbolic,
        load: &f,
        trace: &trace,
        weight: &weight,
        gap: &gap,
        epsilon: params.epsilon,
    };
    let newton = penalty::solve(&problem, initial, opts, on_iteration)?;
    let newton_ms = ms_since(t);
    let p = raw_pressure(&newton.violation, params.epsilon);
    let pbar = smoothed_pressure(&points, &p);
    let order = disc.mesh.element.order();
    let vertex_uy = disc
        .contact_dofs
        .iter()
        .step_by(order)
        .map(|&d| newton.u[d])
        .collect();
    let load = load(&points, &p);
    let timing = Timing {
        assembly: 0.0,
        symbolic: 0.0,
        factorization: newton.factorization_ms,
        newton: newton_ms,
        total: ms_since(t),
    };
    Ok(Solution {
        params: params.clone(),
        points,
        newton,
        p,
        pbar,
        vertex_uy,
        load,
        timing,
    })
}

/// A fresh solve of `scenario` as given (its level, element, rule, ε and obstacle).
pub fn solve_scenario(scenario: &Scenario) -> Result<(Discretization, Solution), SolveError> {
    let t = Instant::now();
    let disc = Discretization::of(scenario, scenario.level, scenario.element)?;
    let params = ContactParams {
        rule: scenario.rule,
        epsilon: scenario.epsilon,
        obstacle: scenario.obstacle.clone(),
    };
    let mut sol = solve_contact(&disc, &params, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })?;
    sol.timing.assembly = disc.assembly_ms;
    sol.timing.symbolic = disc.symbolic_ms;
    sol.timing.total = ms_since(t);
    Ok((disc, sol))
}

/// The paper's name for an element × rule pair (DESIGN §2), if it has one.
pub fn scheme_name(element: Element, rule: Rule) -> Option<&'static str> {
    match (element, rule) {
        (Element::Q1, Rule::Gauss1) => Some("M1"),
        (Element::Q1, Rule::Gauss2) => Some("M2"),
        (Element::Q1, Rule::Trapezoid) => Some("M3"),
        (Element::Q2, Rule::Simpson) => Some("M4"),
        _ => None,
    }
}

/// The element × rule pair of a preset M1–M4.
pub fn preset(name: &str) -> Option<(Element, Rule)> {
    match name.to_ascii_uppercase().as_str() {
        "M1" => Some((Element::Q1, Rule::Gauss1)),
        "M2" => Some((Element::Q1, Rule::Gauss2)),
        "M3" => Some((Element::Q1, Rule::Trapezoid)),
        "M4" => Some((Element::Q2, Rule::Simpson)),
        _ => None,
    }
}
