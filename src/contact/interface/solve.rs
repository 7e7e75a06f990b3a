//! The contact solve of two bodies across their interface (docs/design.md §12).
//!
//! Each body's [`Discretization`] condenses it onto its Γ_C's displacement along its own
//! outward normal (the upper body's on its mirrored mesh, [`crate::scenario::Upper`]), C_b its
//! trace compliance. A [`Coupling`]'s forces y_k = weight_k λ_k push each trace inwards, f_b =
//! −G_bᵀ y (G_s the slave rows, G_m the master's), so that the gaps are
//!
//!   g = g̃0 + (G_s C_s G_sᵀ + G_m C_m G_mᵀ) y,  g̃0_k = g0_k − δ Σ_i G_upper\[k\]_i,
//!
//! δ the downward displacement of the upper body's top (a rigid translation of it). With the
//! penetration s = −g = d − A y this is the one-body problem condensed on the rule's points
//! ([`crate::contact::penalty`]): the same semismooth Newton solves the penalty λ = (1/ε)[−g]₊
//! (ε > 0) and the primal–dual active set the exact multipliers λ ≥ 0, g ≥ 0, λ·g = 0 (ε = 0).
//! The traces' displacements follow by one back-substitution per body.

use std::ops::ControlFlow;

use faer::{Mat, Side as FaerSide};

pub use super::condense::delassus;
use super::condense::smoothed;
use super::{Coupling, InterfaceError, InterfaceMethod, Side, coupling, smoothed_pressure};
use crate::contact::Rule;
use crate::contact::newton::{NewtonOptions, NewtonResult};
use crate::contact::penalty::{self, Penalty};
use crate::contact::{alm, signorini};
use crate::discretization::Discretization;
use crate::error::{Diagnosis, SolveError};

/// Which body's trace carries the contact integral (the slave); the other is the master.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Slave {
    /// The upper body (the default).
    #[default]
    Upper,
    /// The lower body.
    Lower,
}

impl Slave {
    /// The names in scenario files and the outputs.
    pub const NAMES: [&'static str; 2] = ["upper", "lower"];

    /// The side's name: `upper` or `lower`.
    pub fn name(self) -> &'static str {
        match self {
            Slave::Upper => "upper",
            Slave::Lower => "lower",
        }
    }
}

/// The two bodies across their interface.
#[derive(Clone, Copy)]
pub struct Bodies<'a> {
    /// The lower body, Γ_C its top.
    pub lower: &'a Discretization,
    /// The upper body on its mirrored mesh: its support the mesh's bottom row, Γ_C its top.
    pub upper: &'a Discretization,
    /// The prescribed downward displacement δ of the upper body's top.
    pub displacement: f64,
    /// Which body is the slave.
    pub slave: Slave,
}

impl<'a> Bodies<'a> {
    /// (slave, master).
    pub fn pair(&self) -> (&'a Discretization, &'a Discretization) {
        match self.slave {
            Slave::Upper => (self.upper, self.lower),
            Slave::Lower => (self.lower, self.upper),
        }
    }

    /// The slave's and the master's trace nodes, ascending x.
    pub fn trace_x(&self) -> (&'a [f64], &'a [f64]) {
        let (s, m) = self.pair();
        (&s.mesh.node_x, &m.mesh.node_x)
    }
}

/// The displacements of a trace's nodes, in the global frame (y up).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TraceDisplacement {
    /// The nodes, ascending.
    pub x: Vec<f64>,
    /// u_x at each.
    pub ux: Vec<f64>,
    /// u_y at each.
    pub uy: Vec<f64>,
}

/// How the constraint is enforced across the interface (docs/design.md §10's methods).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Enforcement {
    /// The exact multipliers (ε = 0), by the active set.
    Exact,
    /// The penalty (11) at ε > 0.
    Penalty(f64),
    /// The augmented Lagrangian at ε > 0: penalty solves with the multipliers updated until
    /// they change by less than `tolerance` relative — the exact multipliers' answer.
    Alm {
        /// ε > 0.
        epsilon: f64,
        /// The relative change of the multipliers that ends the updates, 0 < tolerance < 1.
        tolerance: f64,
    },
}

impl Enforcement {
    /// ε (0 for the exact multipliers).
    pub fn epsilon(self) -> f64 {
        match self {
            Enforcement::Exact => 0.0,
            Enforcement::Penalty(epsilon) | Enforcement::Alm { epsilon, .. } => epsilon,
        }
    }

    /// Whether the answer is the exact multipliers' (the exact law, or the ALM's limit).
    pub fn is_exact(self) -> bool {
        !matches!(self, Enforcement::Penalty(_))
    }
}

/// ε = 0: the exact multipliers; ε > 0: the penalty.
impl From<f64> for Enforcement {
    fn from(epsilon: f64) -> Self {
        if epsilon == 0.0 {
            Enforcement::Exact
        } else {
            Enforcement::Penalty(epsilon)
        }
    }
}

/// The interface's solution.
#[derive(Clone, Debug, PartialEq)]
pub struct InterfaceSolution {
    /// Where each constraint sits ([`Coupling::x`]).
    pub x: Vec<f64>,
    /// The pressure λ_k ≥ 0 at each constraint (compression positive).
    pub p: Vec<f64>,
    /// The gap g_k at each constraint (−ε p_k where the penalty presses).
    pub gap: Vec<f64>,
    /// The slave's vertices, ascending.
    pub vertex_x: Vec<f64>,
    /// p̄ at the slave's vertices: I(p, φ_i)/I(1, φ_i) over the constraints, φ_i the vertex's
    /// hat function — (17) for the reduced-integration rules (docs/design.md §4).
    pub pbar: Vec<f64>,
    /// The slave's trace.
    pub slave: TraceDisplacement,
    /// The master's trace.
    pub master: TraceDisplacement,
    /// Every node's displacement in the lower body and in the upper one, (u_x, u_y) by node in
    /// its mesh's order, in the global frame (the upper's mirrored back and translated by −δ,
    /// as its trace): what the traces were read from, kept for drawing the meshes.
    pub bodies: [Vec<f64>; 2],
    /// The load carried across the interface, P = Σ_k weight_k p_k.
    pub load: f64,
    /// Newton (active-set) iterations taken (the ALM's: over all its updates).
    pub iterations: usize,
    /// The ALM's multiplier updates (None for the other enforcements).
    pub outer_iterations: Option<usize>,
}

/// Why the interface's solve gave no result.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum BodiesError {
    /// A scenario with one body (no `[upper]`) asked for a two-body solve.
    #[error("the scenario has one body: a solve across an interface needs an [upper] body")]
    OneBody,
    /// The two traces cannot be coupled ([`super::coupling`]).
    #[error(transparent)]
    Coupling(#[from] InterfaceError),
    /// The coupling does not fit the two traces (a caller's error).
    #[error("the coupling does not fit the traces: {0}")]
    Mismatch(String),
    /// ε = 0 with constraints that are not independent: the multipliers are not unique.
    #[error(
        "the exact multipliers are not unique: {constraints} constraints are not independent on these traces; give ε > 0 (the penalty)"
    )]
    NotUnique {
        /// The number of constraints.
        constraints: usize,
    },
    /// ε outside the range both bodies' meshes and materials can represent
    /// ([`crate::material::epsilon_range`]).
    #[error("ε = {epsilon:e} is outside what both bodies can represent: allowed 0 or {lo:e} to {hi:e}")]
    Epsilon {
        /// The ε asked.
        epsilon: f64,
        /// The smallest allowed ε > 0.
        lo: f64,
        /// The largest allowed.
        hi: f64,
    },
    /// The Newton iteration did not converge.
    #[error("the interface's contact solve did not converge: {0}")]
    NotConverged(Diagnosis),
    /// A value came out non-finite (round-off beyond double precision).
    #[error("the interface's contact solve gave a non-finite {0}: use a larger ε")]
    NonFinite(&'static str),
    /// The solver's own error (cancelled, an eigendecomposition that failed).
    #[error(transparent)]
    Solve(#[from] SolveError),
    /// A pressure on the upper body's top that no descent δ balanced ([`super::pressed`]).
    #[error(
        "the pressure on the upper body's top was not balanced: the interface carries P = {carried:e} of its load {load:e} after {steps} descents δ; a smaller pressure or a larger ε"
    )]
    Unbalanced {
        /// The top's load q · width.
        load: f64,
        /// The load carried at the last δ tried.
        carried: f64,
        /// The δ tried.
        steps: usize,
    },
}

/// Solve the contact of `bodies` across their interface discretised by `method`
/// ([`super::coupling`], the initial gap `gap0` at each row's x), the constraint enforced as
/// `enforcement` says (an ε: the penalty at ε > 0, the exact multipliers at 0); p̄ by (17) for
/// the reduced-integration rules ([`smoothed_pressure`]). The coupling is returned with the
/// solution.
///
/// # Errors
///
/// As [`solve`]'s, and two traces that cannot be coupled.
pub fn solve_method(
    bodies: &Bodies,
    method: InterfaceMethod,
    enforcement: impl Into<Enforcement>,
    gap0: impl Fn(f64) -> f64,
) -> Result<(Coupling, InterfaceSolution), BodiesError> {
    let (coupling, g0, rule) = couple(bodies, method, gap0)?;
    let sol = solve(bodies, &coupling, &g0, enforcement.into(), rule)?;
    Ok((coupling, sol))
}

/// The coupling of `bodies` by `method`, the initial gap `gap0` at each of its rows, and the
/// reduced-integration rule whose points the rows are (for p̄ by (17)).
pub(crate) fn couple(
    bodies: &Bodies,
    method: InterfaceMethod,
    gap0: impl Fn(f64) -> f64,
) -> Result<(Coupling, Vec<f64>, Option<Rule>), BodiesError> {
    let (slave, _) = bodies.pair();
    let order = slave.mesh.element.order();
    let (sx, mx) = bodies.trace_x();
    let side = |x| Side { x, order };
    let coupling = coupling(method, side(sx), side(mx))?;
    let g0: Vec<f64> = coupling.x.iter().map(|&x| gap0(x)).collect();
    let rule = match method {
        InterfaceMethod::Rip(rule) => Some(rule),
        _ => None,
    };
    Ok((coupling, g0, rule))
}

/// Solve the contact of `bodies` across the interface discretised by `coupling`, from the
/// initial gaps `g0` (one per constraint), the constraint enforced as `enforcement` says. p̄:
/// by (17) over the points of `rule` when the rows are a reduced-integration
/// rule's ([`smoothed_pressure`], a point off the master at p = 0), else the rows' own hat
/// average (`smoothed`).
///
/// # Errors
///
/// [`BodiesError`]: a coupling that does not fit, exact multipliers that are not unique, a
/// solve that does not converge or a non-finite result.
pub fn solve(
    bodies: &Bodies,
    coupling: &Coupling,
    g0: &[f64],
    enforcement: Enforcement,
    rule: Option<Rule>,
) -> Result<InterfaceSolution, BodiesError> {
    solve_cancellable(bodies, coupling, g0, enforcement, rule, &|| false)
}

/// [`solve`], given up ([`SolveError::Cancelled`]) as soon as `cancelled` says so: it is
/// asked before the constraints are condensed, after, and at every Newton (active-set)
/// iteration — what a caller with a newer question does not wait for.
///
/// # Errors
///
/// As [`solve`]'s, and [`SolveError::Cancelled`].
pub fn solve_cancellable(
    bodies: &Bodies,
    coupling: &Coupling,
    g0: &[f64],
    enforcement: Enforcement,
    rule: Option<Rule>,
    cancelled: &dyn Fn() -> bool,
) -> Result<InterfaceSolution, BodiesError> {
    Condensed::new(*bodies, coupling, g0, enforcement, rule, cancelled)?.solve(
        bodies.displacement,
        g0,
        cancelled,
    )
}

/// The constraint across the interface condensed on the two traces: A = G_s C_s G_sᵀ +
/// G_m C_m G_mᵀ ([`delassus`]) and, for the exact multipliers and the ALM, whether they are
/// unique — what every solve with these rows shares, whatever the upper top's descent δ and
/// the initial gaps (under a pressure the search for δ solves many: [`super::pressed`]).
pub(crate) struct Condensed<'a> {
    bodies: Bodies<'a>,
    coupling: &'a Coupling,
    enforcement: Enforcement,
    rule: Option<Rule>,
    a: Mat<f64>,
    /// The multipliers are unique (A positive definite); asked of the exact multipliers and the ALM only.
    unique: bool,
}

impl<'a> Condensed<'a> {
    /// `coupling` of `bodies` condensed, checked against the traces and initial gaps like
    /// `g0`; given up as soon as `cancelled` says so.
    ///
    /// # Errors
    ///
    /// As [`solve`]'s before its Newton iteration: a coupling that does not fit, ε out of
    /// range, the exact multipliers not unique; and [`SolveError::Cancelled`].
    pub(crate) fn new(
        bodies: Bodies<'a>,
        coupling: &'a Coupling,
        g0: &[f64],
        enforcement: Enforcement,
        rule: Option<Rule>,
        cancelled: &dyn Fn() -> bool,
    ) -> Result<Self, BodiesError> {
        let go_on = || {
            if cancelled() {
                Err(SolveError::Cancelled)
            } else {
                Ok(())
            }
        };
        go_on()?;
        let epsilon = enforcement.epsilon();
        let (slave, master) = bodies.pair();
        check(coupling, g0, slave.contact_dofs.len(), master.contact_dofs.len())?;
        let (lo, hi) = epsilon_range(&bodies);
        if epsilon != 0.0 && !(epsilon >= lo && epsilon <= hi) {
            return Err(BodiesError::Epsilon { epsilon, lo, hi });
        }
        let a = delassus(&coupling.slave, &slave.compliance) + delassus(&coupling.master, &master.compliance);
        go_on()?;
        let unique = match enforcement {
            Enforcement::Penalty(_) => false,
            Enforcement::Exact => {
                unique(&a)?;
                true
            }
            Enforcement::Alm { .. } => unique(&a).is_ok(),
        };
        Ok(Condensed {
            bodies,
            coupling,
            enforcement,
            rule,
            a,
            unique,
        })
    }

    /// The solve with the upper top's descent `displacement` and the initial gaps `g0` (one
    /// per row, as [`Condensed::new`]'s); given up as soon as `cancelled` says so.
    ///
    /// # Errors
    ///
    /// As [`solve`]'s.
    pub(crate) fn solve(
        &self,
        displacement: f64,
        g0: &[f64],
        cancelled: &dyn Fn() -> bool,
    ) -> Result<InterfaceSolution, BodiesError> {
        let (coupling, enforcement, a) = (self.coupling, self.enforcement, &self.a);
        let bodies = Bodies {
            displacement,
            ..self.bodies
        };
        let (slave, master) = bodies.pair();
        check(coupling, g0, slave.contact_dofs.len(), master.contact_dofs.len())?;
        let n = coupling.x.len();
        let upper_rows = match bodies.slave {
            Slave::Upper => &coupling.slave,
            Slave::Lower => &coupling.master,
        };
        // The penetration with no contact force: d = −g̃0.
        let d: Vec<f64> = (0..n)
            .map(|k| displacement * upper_rows[k].iter().map(|e| e.1).sum::<f64>() - g0[k])
            .collect();
        let pb = Penalty {
            coupling: a,
            free_violation: &d,
            weight: &coupling.weight,
            epsilon: enforcement.epsilon(),
        };
        let opts = NewtonOptions::default();
        let mut go_on = |_: &_| {
            if cancelled() {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        };
        let (result, outer_iterations) = match enforcement {
            Enforcement::Penalty(_) => (penalty::solve(&pb, None, &opts, &mut go_on)?, None),
            Enforcement::Exact => (signorini::solve_exact(&pb, None, &opts, &mut go_on)?, None),
            Enforcement::Alm { tolerance, .. } => {
                // The Newton step on the multipliers where they are unique, Uzawa's where not.
                let alm = alm::solve(&pb, self.unique, tolerance, None, &opts, &mut go_on)?;
                (alm.newton, Some(alm.outer))
            }
        };
        if let Some(why) = result.failure() {
            return Err(BodiesError::NotConverged(why));
        }
        self.finish(&bodies, &result, outer_iterations)
    }

    /// The solution from the Newton iteration's `result` on `bodies`.
    fn finish(
        &self,
        bodies: &Bodies,
        result: &NewtonResult,
        outer_iterations: Option<usize>,
    ) -> Result<InterfaceSolution, BodiesError> {
        let (coupling, enforcement, rule) = (self.coupling, self.enforcement, self.rule);
        let (slave, master) = bodies.pair();
        let y = &result.forces;
        let p: Vec<f64> = match enforcement {
            Enforcement::Penalty(epsilon) => crate::contact::raw_pressure(&result.violation, epsilon),
            Enforcement::Exact | Enforcement::Alm { .. } => {
                y.iter().zip(&coupling.weight).map(|(y, w)| y / w).collect()
            }
        };
        let gap: Vec<f64> = result.violation.iter().map(|s| -s).collect();
        let order = slave.mesh.element.order();
        let vertex_x: Vec<f64> = slave.mesh.node_x.iter().step_by(order).copied().collect();
        let pbar = match rule {
            Some(rule) => {
                let side = Side {
                    x: &slave.mesh.node_x,
                    order,
                };
                smoothed_pressure(rule, side, coupling, &p)?
            }
            None => smoothed(&vertex_x, &coupling.x, &coupling.weight, &p),
        };
        let load = coupling.weight.iter().zip(&p).map(|(w, p)| w * p).sum();
        let trace = |disc: &Discretization, rows: &[Vec<(usize, f64)>]| {
            let upper = std::ptr::eq(disc, bodies.upper);
            displacement(disc, rows, y, upper.then_some(bodies.displacement))
        };
        let ((slave_trace, slave_field), (master_trace, master_field)) =
            (trace(slave, &coupling.slave), trace(master, &coupling.master));
        let fields = match bodies.slave {
            Slave::Upper => [master_field, slave_field],
            Slave::Lower => [slave_field, master_field],
        };
        let solution = InterfaceSolution {
            x: coupling.x.clone(),
            p,
            gap,
            vertex_x,
            pbar,
            slave: slave_trace,
            master: master_trace,
            bodies: fields,
            load,
            iterations: result.iterations,
            outer_iterations,
        };
        finite(&solution)?;
        Ok(solution)
    }
}

/// The penalty parameters both bodies can represent: the intersection of their
/// [`Discretization::epsilon_range`]s.
pub fn epsilon_range(bodies: &Bodies) -> (f64, f64) {
    let (l, u) = (bodies.lower.epsilon_range(), bodies.upper.epsilon_range());
    (l.0.max(u.0), l.1.min(u.1))
}

/// The coupling's rows against the traces' sizes and `g0`'s.
fn check(coupling: &Coupling, g0: &[f64], n_slave: usize, n_master: usize) -> Result<(), BodiesError> {
    let n = coupling.x.len();
    let lengths = [
        coupling.weight.len(),
        coupling.slave.len(),
        coupling.master.len(),
        g0.len(),
    ];
    if lengths.iter().any(|&l| l != n) {
        return Err(BodiesError::Mismatch(format!(
            "{n} constraints but {lengths:?} weights, slave rows, master rows and initial gaps"
        )));
    }
    if g0.iter().any(|g| !g.is_finite()) {
        return Err(BodiesError::Mismatch("an initial gap is not finite".into()));
    }
    if coupling.weight.iter().any(|w| !(w.is_finite() && *w > 0.0)) {
        return Err(BodiesError::Mismatch("a weight is not positive".into()));
    }
    let fits = |rows: &[Vec<(usize, f64)>], len: usize| {
        rows.iter().flatten().all(|&(i, c)| i < len && c.is_finite())
    };
    if !fits(&coupling.slave, n_slave) || !fits(&coupling.master, n_master) {
        return Err(BodiesError::Mismatch(format!(
            "a coefficient is not finite or names a node beyond the traces' {n_slave} and {n_master}"
        )));
    }
    Ok(())
}

/// An eigenvalue at most this fraction of the largest is a kernel's: the constraints are then
/// not independent on the two traces (the exact multipliers are not unique; the inf-sup
/// estimate across the interface, [`crate::infsup`], is 0).
pub(crate) const KERNEL: f64 = 1e-12;

/// Refuse a singular A = Σ G C Gᵀ (constraints not independent): the exact multipliers would
/// not be unique.
fn unique(a: &Mat<f64>) -> Result<(), BodiesError> {
    let n = a.nrows();
    if n == 0 {
        return Ok(());
    }
    let values = a
        .self_adjoint_eigenvalues(FaerSide::Lower)
        .map_err(SolveError::Eigen)?;
    let largest = values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let smallest = values.iter().fold(f64::INFINITY, |m, &v| m.min(v));
    if smallest <= KERNEL * largest {
        return Err(BodiesError::NotUnique { constraints: n });
    }
    Ok(())
}

/// The global displacements of `disc`'s nodes under the forces −Gᵀy of `rows` (inwards): one
/// back-substitution; for the upper body (`upper` = its top's δ) mirrored back and translated
/// by −δ. Its trace's, and every node's ((u_x, u_y) by node).
fn displacement(
    disc: &Discretization,
    rows: &[Vec<(usize, f64)>],
    y: &[f64],
    upper: Option<f64>,
) -> (TraceDisplacement, Vec<f64>) {
    let mut u = vec![0.0; disc.n_dofs()];
    for (row, &yk) in rows.iter().zip(y) {
        for &(i, g) in row {
            u[disc.contact_dofs[i]] -= g * yk;
        }
    }
    disc.factor.solve_in_place(&mut u, 1);
    let mut u = disc.dofs.expand(&u, |_| 0.0);
    if let Some(delta) = upper {
        for uy in u.iter_mut().skip(1).step_by(2) {
            *uy = -*uy - delta;
        }
    }
    let top = disc.mesh.top_nodes();
    let trace = TraceDisplacement {
        x: disc.mesh.node_x.clone(),
        ux: top.iter().map(|&n| u[2 * n]).collect(),
        uy: top.iter().map(|&n| u[2 * n + 1]).collect(),
    };
    (trace, u)
}

/// Refuse a solution with a non-finite value.
fn finite(s: &InterfaceSolution) -> Result<(), BodiesError> {
    let bad = |v: &[f64]| v.iter().any(|x| !x.is_finite());
    let checks: [(&'static str, bool); 6] = [
        ("pressure", bad(&s.p) || bad(&s.pbar) || !s.load.is_finite()),
        ("gap", bad(&s.gap)),
        ("slave displacement", bad(&s.slave.ux) || bad(&s.slave.uy)),
        ("master displacement", bad(&s.master.ux) || bad(&s.master.uy)),
        ("displacement", bad(&s.bodies[0]) || bad(&s.bodies[1])),
        ("position", bad(&s.x)),
    ];
    match checks.iter().find(|c| c.1) {
        Some((what, _)) => Err(BodiesError::NonFinite(what)),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests;
