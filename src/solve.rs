//! From a scenario to a solution: the work that depends only on the mesh (assembly of K, its
//! factorisation, the trace compliance) is held in a [`Discretization`] and done once; each
//! contact solve (rule, ε, obstacle) reuses it and costs only dense work on Γ_C.

use std::ops::ControlFlow;
use std::time::Instant;

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use faer::Mat;
use serde::Serialize;

use crate::check;
use crate::contact::nitsche::{self, NitscheCache, NitscheParams};
use crate::contact::penalty::{self, Iteration, NewtonOptions, NewtonResult, Penalty, SolveError};
use crate::contact::signorini::solve_exact;
use crate::contact::{ContactPoints, Method, Obstacle, Rule, alm, load, raw_pressure, smoothed_pressure};
use crate::fem::error::gib;
use crate::fem::factor::{Analysis, Factor};
use crate::fem::memory::{Limits, Sizes};
use crate::fem::{DofMap, FemError, Form, Integration, assemble};
use crate::material::Material;
pub use crate::material::{KAPPA_RANGE, epsilon_range};
use crate::mesh::{Element, Mesh};
use crate::scenario::Scenario;
use crate::warning::{self, Warning};

fn ms_since(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// Everything that depends on the mesh alone: K assembled, analysed and factorised once
/// with the Γ_C normal dofs last, and its trace compliance C (see [`crate::fem::condense`]).
pub struct Discretization {
    pub(crate) mesh: Mesh,
    pub(crate) dofs: DofMap,
    /// The symbolic analysis of K's pattern (shared by every form on this mesh).
    pub(crate) ordering: Analysis,
    /// K factorised: one factor, or two subdomains and the dense S (see [`crate::fem::factor`]).
    pub(crate) factor: Factor,
    /// C = E K⁻¹ Eᵀ on the Γ_C normal dofs, ascending x.
    pub(crate) compliance: Mat<f64>,
    /// The free dof of u_n = u_y at each Γ_C node, in ascending x.
    pub(crate) contact_dofs: Vec<usize>,
    pub(crate) assembly_ms: f64,
    pub(crate) symbolic_ms: f64,
    /// Numeric factorisation and the trace compliance.
    pub(crate) factorization_ms: f64,
    /// Young's modulus, the scale of the penalty parameter's range ([`epsilon_range`]).
    young: f64,
    /// What is known to be poor about this stiffness before any solve (locking).
    stiffness_warning: Option<Warning>,
    /// G = T C Tᵀ for each rule met so far.
    couplings: Mutex<HashMap<Rule, Arc<Mat<f64>>>>,
    /// Nitsche's method's own factor and couplings, built on its first solve
    /// ([`crate::contact::nitsche`]).
    pub(crate) nitsche: NitscheCache,
}

impl Discretization {
    /// The mesh of the body.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The map from nodes to free dofs (the roller on a half model's axis removed).
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }

    /// The symbolic analysis of K's pattern, Γ_C's normal dofs last (docs/design.md §6).
    pub fn ordering(&self) -> &Analysis {
        &self.ordering
    }

    /// The factorisation of K (one factor, or two subdomains and the dense S).
    pub fn factor(&self) -> &Factor {
        &self.factor
    }

    /// The trace compliance C = E K⁻¹ Eᵀ on the Γ_C normal dofs, ascending x.
    pub fn compliance(&self) -> &Mat<f64> {
        &self.compliance
    }

    /// The free dof of u_n = u_y at each Γ_C node, ascending x.
    pub fn contact_dofs(&self) -> &[usize] {
        &self.contact_dofs
    }

    pub fn new(mesh: Mesh, material: Material, integration: Integration) -> Result<Self, SolveError> {
        let dofs = DofMap::model(&mesh);
        Self::with_dofs(mesh, dofs, material, integration)
    }

    /// As [`Discretization::new`] with other supports than the model's (`dofs`), e.g. rollers
    /// on both sides for a patch test. Γ_C's normal dofs must be free.
    pub fn with_dofs(
        mesh: Mesh,
        dofs: DofMap,
        material: Material,
        integration: Integration,
    ) -> Result<Self, SolveError> {
        let mesh_element = mesh.element;
        let t = Instant::now();
        let stiffness = assemble(&mesh, &dofs, Form::Elasticity(material, integration));
        let assembly_ms = ms_since(t);
        let contact_dofs: Vec<usize> = mesh
            .top_nodes()
            .iter()
            .map(|&n| {
                dofs.free_index(2 * n + 1)
                    .expect("Γ_C is not on the clamped side")
            })
            .collect();
        let n = dofs.n_free();
        let t = Instant::now();
        let ordering =
            Analysis::grid(&stiffness, &mesh, &dofs, &contact_dofs).map_err(|e| fem_error(e, n))?;
        let symbolic_ms = ms_since(t);
        let t = Instant::now();
        let factor = Factor::new(&ordering, &stiffness).map_err(|e| fem_error(e, n))?;
        let compliance = factor.compliance();
        let factorization_ms = ms_since(t);
        Ok(Discretization {
            mesh,
            dofs,
            ordering,
            factor,
            compliance,
            contact_dofs,
            assembly_ms,
            symbolic_ms,
            factorization_ms,
            young: material.young,
            stiffness_warning: warning::of_material(&material, mesh_element, integration),
            couplings: Mutex::new(HashMap::new()),
            nitsche: NitscheCache::new(material, integration),
        })
    }

    /// What is known to be poor about this stiffness before any solve (locking).
    pub fn stiffness_warning(&self) -> Option<Warning> {
        self.stiffness_warning.clone()
    }

    /// The body's height H (the range of the depth).
    pub fn height(&self) -> f64 {
        self.mesh.ys.last().copied().unwrap_or(0.0)
    }

    /// The discretisation of `scenario` at `level` with `element`, refused before anything is
    /// allocated when its memory estimate exceeds the memory this process may use
    /// ([`crate::fem::memory`]).
    pub fn of(scenario: &Scenario, level: u32, element: Element) -> Result<Self, SolveError> {
        let mesh = scenario.mesh(level, element);
        let trace = mesh.nnx();
        let sizes = Sizes {
            element,
            unknowns: scenario.n_dofs(level, element),
            trace,
            points: Rule::ALL
                .iter()
                .map(|&rule| ContactPoints::new(rule, &mesh.node_x, element.order()).len())
                .max()
                .unwrap_or(trace),
        };
        sizes.check(&Limits::of_process()).map_err(|e| match e {
            FemError::TooLarge {
                unknowns,
                need,
                available,
            } => SolveError::TooLarge(format!(
                "level {level} with {} has {unknowns} unknowns ({trace} on Γ_C) and needs about {}; this process has {} available (free memory, ulimit -v and the control group's limit): choose a coarser level",
                element.name(),
                gib(need),
                gib(available)
            )),
            e => fem_error(e, sizes.unknowns),
        })?;
        Self::new(mesh, scenario.material, scenario.integration)
    }

    /// `rule` laid on Γ_C.
    pub fn contact_points(&self, rule: Rule) -> ContactPoints {
        let nnx = self.mesh.nnx();
        ContactPoints::new(rule, &self.mesh.node_x[..nnx], self.mesh.element.order())
    }

    /// G = B K⁻¹ Bᵀ = T C Tᵀ between the points of `rule` (computed once per rule).
    pub fn coupling(&self, rule: Rule, points: &ContactPoints) -> Arc<Mat<f64>> {
        let mut cache = self.couplings.lock().unwrap_or_else(|e| e.into_inner());
        cache
            .entry(rule)
            .or_insert_with(|| {
                let c = &self.compliance;
                let nq = points.len();
                // C Tᵀ, column by column, then T (C Tᵀ).
                let ct = Mat::<f64>::from_fn(c.nrows(), nq, |i, q| {
                    let pt = &points.points[q];
                    pt.nodes.iter().zip(&pt.trace).map(|(&k, t)| t * c[(i, k)]).sum()
                });
                Arc::new(Mat::<f64>::from_fn(nq, nq, |p, q| {
                    let pt = &points.points[p];
                    pt.nodes.iter().zip(&pt.trace).map(|(&k, t)| t * ct[(k, q)]).sum()
                }))
            })
            .clone()
    }

    pub fn n_dofs(&self) -> usize {
        self.dofs.n_free()
    }

    /// The penalty parameters this mesh and material can represent ([`epsilon_range`]).
    pub fn epsilon_range(&self) -> (f64, f64) {
        epsilon_range(self.young, self.mesh.h())
    }

    /// `params` checked against what this discretisation can answer ([`check_params`]).
    pub fn check(&self, params: &ContactParams, n_points: usize) -> Result<(), SolveError> {
        let height = self.height();
        let (range, normals) = (self.epsilon_range(), self.contact_dofs.len());
        check_params(params, range, height, n_points, normals)
    }

    /// Nodal contact forces Tᵀy on the Γ_C nodes from the forces y at the rule's points.
    fn nodal_forces(points: &ContactPoints, forces: &[f64], n_nodes: usize) -> Vec<f64> {
        let mut f = vec![0.0; n_nodes];
        for (q, &y) in points.points.iter().zip(forces) {
            for (&k, t) in q.nodes.iter().zip(&q.trace) {
                f[k] += t * y;
            }
        }
        f
    }
}

/// The solver's error for a failure of the finite element layer on `n` unknowns.
pub(crate) fn fem_error(e: FemError, n: usize) -> SolveError {
    match e {
        FemError::NotPositiveDefinite => SolveError::Factorization("a zero or negative pivot".into()),
        FemError::OutOfMemory(what) => SolveError::TooLarge(format!(
            "out of memory in {what} with {n} unknowns: choose a coarser level"
        )),
        FemError::TooLarge {
            unknowns,
            need,
            available,
        } => SolveError::TooLarge(format!(
            "{unknowns} unknowns need about {} and {} is available: choose a coarser level",
            gib(need),
            gib(available)
        )),
    }
}

/// A contact solve's parameters checked against what it can answer: the method's own
/// parameters ([`Method::check`]), ε within `range` (from [`epsilon_range`]) and > 0 for the
/// methods that use it (ε = 0 for `exact`), the depth within the body's `height`, and `exact`
/// only for a rule with no more points (`n_points`) than Γ_C has normal displacements
/// (`normals`).
pub fn check_params(
    params: &ContactParams,
    range: (f64, f64),
    height: f64,
    n_points: usize,
    normals: usize,
) -> Result<(), SolveError> {
    params.method.check().map_err(|e| SolveError::Input {
        what: "the method",
        message: e.to_string(),
    })?;
    check::epsilon_in(params.epsilon, range).map_err(|e| SolveError::Input {
        what: "the penalty parameter ε",
        message: e.to_string(),
    })?;
    if params.method.uses_epsilon() && params.epsilon == 0.0 {
        return Err(SolveError::Input {
            what: "the penalty parameter ε",
            message: format!(
                "{} needs ε > 0; ε = 0 is the exact method (`exact`)",
                params.method.name()
            ),
        });
    }
    check::depth(params.obstacle.depth(), height).map_err(|e| SolveError::Input {
        what: "the indentation depth",
        message: e.to_string(),
    })?;
    if params.method == Method::Exact && n_points > normals {
        return Err(SolveError::Kernel {
            rule: params.rule,
            points: n_points,
            normals,
        });
    }
    Ok(())
}

/// [`check_params`] before anything is built: from the scenario's numbers at `level` with
/// `element`, so that a request with no answer is refused without assembling a stiffness.
pub fn check_request(
    scenario: &Scenario,
    level: u32,
    element: Element,
    params: &ContactParams,
) -> Result<(), SolveError> {
    let n_edges = (scenario.x_lines.len() - 1) << level;
    check_params(
        params,
        scenario.epsilon_range(level),
        scenario.height,
        params.rule.n_points(n_edges),
        element.order() * n_edges + 1,
    )
}

/// What a contact solve depends on beyond the mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactParams {
    pub rule: Rule,
    /// How the constraint is imposed ([`Method`]).
    pub method: Method,
    /// The penalty parameter ε > 0 of (8) for `penalty` and `alm`; 0 for `exact` (the
    /// limit; [`Method::resolve`]).
    pub epsilon: f64,
    pub obstacle: Obstacle,
}

impl ContactParams {
    /// `penalty` at ε > 0, `exact` at ε = 0 ([`Method::resolve`] with no method named).
    pub fn by_epsilon(rule: Rule, epsilon: f64, obstacle: Obstacle) -> Self {
        let method = if epsilon == 0.0 {
            Method::Exact
        } else {
            Method::Penalty
        };
        ContactParams {
            rule,
            method,
            epsilon,
            obstacle,
        }
    }
}

/// Wall-clock time of the parts of one solve, in milliseconds.
#[derive(Clone, Copy, Debug, Default, Serialize, PartialEq)]
pub struct Timing {
    /// Assembly of K (0 when the mesh's work was reused).
    pub assembly: f64,
    /// Ordering and symbolic factorisation (0 when reused).
    pub symbolic: f64,
    /// Numeric factorisation of K and its trace compliance (0 when reused).
    pub factorization: f64,
    /// The Newton solve on the contact points (and the rule's coupling, the first time).
    pub newton: f64,
    /// Everything this solve did.
    pub total: f64,
}

/// The solution of (11) with its pressures.
#[derive(Clone, Debug)]
pub struct Solution {
    pub params: ContactParams,
    pub points: ContactPoints,
    /// The (inner) Newton's result; for the ALM its iterations are summed over the updates.
    pub newton: NewtonResult,
    /// The ALM's multiplier updates (None for a method without an outer iteration).
    pub outer_iterations: Option<usize>,
    /// Raw pressure p at the rule's points (12); for `exact` and `alm` the multiplier per
    /// unit length.
    pub p: Vec<f64>,
    /// Smoothed pressure p̄ at the Γ_C vertices (16)–(17).
    pub pbar: Vec<f64>,
    /// u_y at the Γ_C vertices.
    pub vertex_uy: Vec<f64>,
    /// P = I(p, 1), the load carried by the modelled body.
    pub load: f64,
    pub timing: Timing,
    /// What is known to be poor about this answer ([`crate::warning`]).
    pub warnings: Vec<Warning>,
    /// The load f on the free dofs, K u = f, when the contact acts on more than Γ_C's normal
    /// dofs (Nitsche's σ_n terms); None when u = −K⁻¹ Eᵀ Tᵀ y.
    pub nodal_forces: Option<Vec<f64>>,
}

impl Solution {
    /// Displacement on every dof (zero on the constrained ones): u = −K⁻¹ Eᵀ Tᵀ y (or
    /// K⁻¹ f with [`Solution::nodal_forces`]), one solve with the mesh's factor, done only
    /// when asked.
    pub fn displacement(&self, disc: &Discretization) -> Vec<f64> {
        if let Some(f) = &self.nodal_forces {
            let mut u = f.clone();
            disc.factor.solve_in_place(&mut u, 1);
            return disc.dofs.expand(&u, |_| 0.0);
        }
        let forces = Discretization::nodal_forces(&self.points, &self.newton.forces, disc.contact_dofs.len());
        let mut u = vec![0.0; disc.n_dofs()];
        for (&d, f) in disc.contact_dofs.iter().zip(&forces) {
            u[d] = -f;
        }
        disc.factor.solve_in_place(&mut u, 1);
        disc.dofs.expand(&u, |_| 0.0)
    }
}

/// Solve the contact problem on `disc`, from the contact forces of an earlier solution with
/// the same rule (`initial`, ignored if it does not fit).
pub fn solve_contact(
    disc: &Discretization,
    params: &ContactParams,
    initial: Option<&[f64]>,
    opts: &NewtonOptions,
    on_iteration: &mut dyn FnMut(&Iteration) -> ControlFlow<()>,
) -> Result<Solution, SolveError> {
    let t = Instant::now();
    let points = disc.contact_points(params.rule);
    disc.check(params, points.len())?;
    if let Method::Nitsche { theta, gamma0 } = params.method {
        let nitsche = NitscheParams {
            theta: f64::from(theta),
            gamma0,
        };
        return nitsche::solve(disc, params, nitsche, initial, opts, on_iteration);
    }
    let coupling = disc.coupling(params.rule, &points);
    let weight: Vec<f64> = points.points.iter().map(|q| q.weight).collect();
    // No body force or traction (docs/design.md §1): u₀ = 0 and d = −g.
    let free_violation: Vec<f64> = points.points.iter().map(|q| -params.obstacle.gap(q.x)).collect();
    let problem = Penalty {
        coupling: &coupling,
        free_violation: &free_violation,
        weight: &weight,
        epsilon: params.epsilon,
    };
    // The multiplier per unit tributary length.
    let per_length =
        |forces: &[f64]| -> Vec<f64> { forces.iter().zip(&weight).map(|(y, w)| y / w).collect() };
    let (mut newton, p, outer_iterations) = match params.method {
        Method::Exact => {
            let newton = solve_exact(&problem, initial, opts, on_iteration)?;
            let p = per_length(&newton.forces);
            (newton, p, None)
        }
        // The penalty (Nitsche's solve returned above, on its own operator).
        Method::Penalty | Method::Nitsche { .. } => {
            let newton = penalty::solve(&problem, initial, opts, on_iteration)?;
            let p = raw_pressure(&newton.violation, params.epsilon);
            (newton, p, None)
        }
        Method::Alm { tolerance } => {
            // Unique multipliers (no kernel) allow the ALM's Newton step on them.
            let unique = points.len() <= disc.contact_dofs.len();
            let result = alm::solve(&problem, unique, tolerance, initial, opts, on_iteration)?;
            let p = per_length(&result.newton.forces);
            (result.newton, p, Some(result.outer))
        }
    };
    let pbar = smoothed_pressure(&points, &p);
    let nodal = Discretization::nodal_forces(&points, &newton.forces, disc.contact_dofs.len());
    let loaded: Vec<usize> = (0..nodal.len()).filter(|&k| nodal[k] != 0.0).collect();
    let order = disc.mesh.element.order();
    let vertex_uy: Vec<f64> = (0..nodal.len())
        .step_by(order)
        .map(|i| {
            -loaded
                .iter()
                .map(|&k| disc.compliance[(i, k)] * nodal[k])
                .sum::<f64>()
        })
        .collect();
    let load = load(&points, &p);
    // A number that is not finite is never a result (the input checks should make this
    // unreachable; this is the last line of defence).
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    if newton.converged
        && !(load.is_finite()
            && newton.residual.is_finite()
            && finite(&newton.forces)
            && finite(&p)
            && finite(&pbar)
            && finite(&vertex_uy))
    {
        newton.converged = false;
        newton.diagnosis = Some(
            "a contact force, pressure or displacement is not finite: the problem's scaling overflows double precision".into(),
        );
    }
    let mut warnings: Vec<Warning> = disc.stiffness_warning.iter().cloned().collect();
    warnings.extend(warning::of_contact(&params.obstacle, &points, &p, disc.mesh.h()));
    let newton_ms = ms_since(t);
    let timing = Timing {
        newton: newton_ms,
        total: newton_ms,
        ..Timing::default()
    };
    Ok(Solution {
        params: params.clone(),
        points,
        newton,
        outer_iterations,
        p,
        pbar,
        vertex_uy,
        load,
        timing,
        warnings,
        nodal_forces: None,
    })
}

/// A fresh solve of `scenario` as given (its level, element, rule, ε and obstacle).
pub fn solve_scenario(scenario: &Scenario) -> Result<(Discretization, Solution), SolveError> {
    let disc = Discretization::of(scenario, scenario.level, scenario.element)?;
    // A scenario whose ε was set to 0 after parsing asks for the exact constraint.
    let method = match scenario.method {
        Method::Penalty if scenario.epsilon == 0.0 => Method::Exact,
        m => m,
    };
    let params = ContactParams {
        rule: scenario.rule,
        method,
        epsilon: scenario.epsilon,
        obstacle: scenario.obstacle.clone(),
    };
    let mut sol = solve_contact(&disc, &params, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })?;
    sol.timing.include_mesh_work(&disc);
    Ok((disc, sol))
}

/// Solve every instance of `params` on `disc` in order, each warm-started from the contact
/// forces of the last one that solved (a sweep over ε or the depth costs one mesh's work and
/// a few Newton steps per value). The first solution is charged with the mesh's work; a
/// failure is its instance's result, and the sweep goes on.
pub fn sweep(disc: &Discretization, params: &[ContactParams]) -> Vec<Result<Solution, SolveError>> {
    let mut previous: Option<Vec<f64>> = None;
    let mut results = Vec::with_capacity(params.len());
    for p in params {
        let solved = solve_contact(
            disc,
            p,
            previous.as_deref(),
            &NewtonOptions::default(),
            &mut |_| ControlFlow::Continue(()),
        );
        let solved = solved.map(|mut sol| {
            if results.is_empty() {
                sol.timing.include_mesh_work(disc);
            }
            previous = Some(sol.newton.forces.clone());
            sol
        });
        results.push(solved);
    }
    results
}

impl Timing {
    /// Charge this solve with the mesh's work too (a fresh solve).
    pub fn include_mesh_work(&mut self, disc: &Discretization) {
        self.assembly = disc.assembly_ms;
        self.symbolic = disc.symbolic_ms;
        // Added: a Nitsche solve has charged its own operator here already.
        self.factorization += disc.factorization_ms;
        self.total += disc.assembly_ms + disc.symbolic_ms + disc.factorization_ms;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 10 item 5: an allocation failure is reported as out of memory (exit 2 through
    /// `TooLarge`), and only a non-positive pivot asks about rigid motion.
    #[test]
    fn out_of_memory_is_not_called_a_rigid_motion() {
        let oom = fem_error(FemError::OutOfMemory("the factor"), 1000);
        assert!(
            matches!(&oom, SolveError::TooLarge(m) if m.contains("out of memory in the factor with 1000 unknowns"))
        );
        assert!(!oom.to_string().contains("rigid"));
        let big = fem_error(
            FemError::TooLarge {
                unknowns: 7,
                need: 3 << 30,
                available: 1 << 30,
            },
            7,
        );
        assert_eq!(
            big.to_string(),
            "7 unknowns need about 3.0 GiB and 1.0 GiB is available: choose a coarser level"
        );
        let pivot = fem_error(FemError::NotPositiveDefinite, 7);
        assert!(matches!(pivot, SolveError::Factorization(_)) && pivot.to_string().contains("rigid motion"));
    }

    /// Issue 11 item 5: a sweep on one mesh gives each instance the solution a fresh solve
    /// gives, charges the mesh's work to the first only, and goes on past a failure.
    #[test]
    fn a_sweep_equals_fresh_solves_and_goes_on_past_a_failure() {
        let mut scenario = Scenario::paper();
        scenario.level = 1;
        let disc = Discretization::of(&scenario, 1, scenario.element).unwrap();
        let at = |epsilon: f64, depth: f64| {
            ContactParams::by_epsilon(scenario.rule, epsilon, scenario.obstacle.with_depth(depth))
        };
        // The middle instance's depth is beyond the body: refused, the sweep goes on.
        let params = [at(1e-6, 0.8), at(1e-6, 1e9), at(1e-7, 0.6)];
        let results = sweep(&disc, &params);
        assert!(matches!(results[1], Err(SolveError::Input { .. })));
        for k in [0, 2] {
            let swept = results[k].as_ref().unwrap();
            let fresh = solve_contact(&disc, &params[k], None, &NewtonOptions::default(), &mut |_| {
                ControlFlow::Continue(())
            })
            .unwrap();
            assert!((swept.load - fresh.load).abs() < 1e-9 * fresh.load, "{k}");
        }
        let first = &results[0].as_ref().unwrap().timing;
        let last = &results[2].as_ref().unwrap().timing;
        assert!(first.assembly > 0.0 && last.assembly == 0.0);
    }
}
