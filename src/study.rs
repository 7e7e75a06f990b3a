//! Accuracy against work (docs/design.md §6, Theorem 2 (26)): errors of every scheme against a
//! reference solution of the continuous problem, observed rates, and the time each solve took.
//!
//! The reference is independent of the penalty: the exact-constraint problem (ε = 0, see
//! [`crate::contact::signorini`]) with Q2 and nodal multipliers (Simpson's points), on a level
//! finer than any studied one. Coarse solutions live on nested meshes and are evaluated
//! exactly at the reference's quadrature points: the pressures on every reference edge of
//! Γ_C, the displacement in every reference cell.

use std::ops::ControlFlow;
use std::time::Instant;

use serde::Serialize;

use crate::contact::method::MethodFields;
use crate::contact::penalty::{NewtonOptions, SolveError};
use crate::contact::{ContactPoints, Method, Rule};
use crate::fem::basis::{cell_points, evaluate};
use crate::fem::quadrature::gauss_legendre;
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::solve::{ContactParams, Discretization, Solution, solve_contact};

/// Gauss points per direction for the error integrals (exact for the Q2 reference's products).
const ERROR_POINTS: usize = 4;

/// A displacement and its gradient at a weighted point.
struct Sample {
    x: f64,
    y: f64,
    weight: f64,
    value: [f64; 2],
    grad: [f64; 4],
}

/// The reference solution, with its values where errors are integrated.
pub struct Reference {
    pub level: u32,
    pub element: Element,
    pub rule: Rule,
    pub n_dofs: usize,
    pub load: f64,
    pub ms: f64,
    /// (x, weight, p_ref) at Gauss points of every reference edge of Γ_C.
    edge_points: Vec<(f64, f64, f64)>,
    /// u_ref at Gauss points of every reference cell.
    cell_points: Vec<Sample>,
    p_norm: f64,
    u_norm: f64,
}

fn solve_fresh(disc: &Discretization, params: &ContactParams) -> Result<Solution, SolveError> {
    solve_contact(disc, params, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
}

/// What the reference is made of: the displacement on every dof of the Q2 mesh and the
/// exact-constraint pressure at Simpson's points (what [`crate::cache`] stores).
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceFields {
    pub u: Vec<f64>,
    pub p: Vec<f64>,
    pub load: f64,
    pub n_dofs: usize,
    /// The time the solve took, ms.
    pub ms: f64,
}

/// The reference's element and rule: Q2 + Simpson (M4) with the exact constraint.
pub const REFERENCE_SCHEME: (Element, Rule) = (Element::Q2, Rule::Simpson);

impl ReferenceFields {
    /// Solve Q2 + Simpson with the exact constraint at `level` (expensive: only when asked).
    pub fn solve(scenario: &Scenario, level: u32) -> Result<Self, SolveError> {
        let t = Instant::now();
        let (element, rule) = REFERENCE_SCHEME;
        let disc = Discretization::of(scenario, level, element)?;
        let params = ContactParams {
            rule,
            method: Method::Exact,
            epsilon: 0.0,
            obstacle: scenario.obstacle.clone(),
        };
        let sol = solve_fresh(&disc, &params)?;
        if !sol.newton.converged {
            return Err(SolveError::NotConverged {
                what: "the reference solution (q2 + simpson, ε = 0)",
                iterations: sol.newton.iterations,
                residual: sol.newton.residual,
                diagnosis: sol.newton.diagnosis.clone().unwrap_or_default(),
            });
        }
        Ok(ReferenceFields {
            u: sol.displacement(&disc),
            p: sol.p,
            load: sol.load,
            n_dofs: disc.n_dofs(),
            ms: t.elapsed().as_secs_f64() * 1e3,
        })
    }
}

impl Reference {
    /// Q2 + Simpson with the exact constraint at `level` (expensive: compute only when asked;
    /// [`crate::cache::reference`] keeps it between runs).
    pub fn compute(scenario: &Scenario, level: u32) -> Result<Self, SolveError> {
        Ok(Reference::from_fields(
            scenario,
            level,
            &ReferenceFields::solve(scenario, level)?,
        ))
    }

    /// The reference from its fields (solved now or read from the cache): its values at the
    /// points where errors are integrated.
    pub fn from_fields(scenario: &Scenario, level: u32, fields: &ReferenceFields) -> Self {
        let (element, rule) = REFERENCE_SCHEME;
        let mesh = scenario.mesh(level, element);
        let points = ContactPoints::new(rule, &mesh.node_x[..mesh.nnx()], element.order());
        let (u, p) = (&fields.u, &fields.p);
        let gauss = gauss_legendre(ERROR_POINTS);
        let vx = &points.vertex_x;
        let mut edge_points = Vec::with_capacity(gauss.len() * vx.len());
        for e in 0..vx.len() - 1 {
            let h = vx[e + 1] - vx[e];
            for &(xi, w) in &gauss {
                let x = vx[e] + h * (xi + 1.0) / 2.0;
                edge_points.push((x, w * h / 2.0, points.interpolate(p, x)));
            }
        }
        let mut cells = Vec::with_capacity(mesh.n_cells() * ERROR_POINTS * ERROR_POINTS);
        for cj in 0..mesh.ny() {
            for ci in 0..mesh.nx() {
                for q in cell_points(&mesh, ci, cj, ERROR_POINTS) {
                    let (value, grad) = evaluate(&mesh, u, q.x, q.y);
                    cells.push(Sample {
                        x: q.x,
                        y: q.y,
                        weight: q.weight,
                        value,
                        grad,
                    });
                }
            }
        }
        let p_norm = edge_points.iter().map(|(_, w, p)| w * p * p).sum::<f64>().sqrt();
        let u_norm = cells
            .iter()
            .map(|c| c.weight * c.value.iter().chain(&c.grad).map(|a| a * a).sum::<f64>())
            .sum::<f64>()
            .sqrt();
        Reference {
            level,
            element,
            rule,
            n_dofs: fields.n_dofs,
            load: fields.load,
            ms: fields.ms,
            edge_points,
            cell_points: cells,
            p_norm,
            u_norm,
        }
    }
}

/// Relative errors of one solution against the reference.
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct Errors {
    /// ‖p − p_ref‖₀ / ‖p_ref‖₀ on Γ_C, p the raw pressure in Q_h.
    pub p: f64,
    /// ‖p̄ − p_ref‖₀ / ‖p_ref‖₀, p̄ the smoothed pressure (16)–(17).
    pub pbar: f64,
    /// ‖u − u_ref‖₁ / ‖u_ref‖₁ of (7) over the body.
    pub u: f64,
    /// |P − P_ref| / P_ref.
    pub load: f64,
}

/// The errors of `sol` on `disc` (a mesh nested in the reference's).
pub fn errors(reference: &Reference, disc: &Discretization, sol: &Solution) -> Errors {
    let (mut ep, mut epbar) = (0.0, 0.0);
    for &(x, w, pref) in &reference.edge_points {
        ep += w * (sol.points.interpolate(&sol.p, x) - pref).powi(2);
        epbar += w * (sol.points.interpolate_vertices(&sol.pbar, x) - pref).powi(2);
    }
    let u = sol.displacement(disc);
    let mut eu = 0.0;
    for c in &reference.cell_points {
        let (vh, gh) = evaluate(&disc.mesh, &u, c.x, c.y);
        let d2: f64 = vh
            .iter()
            .zip(&c.value)
            .chain(gh.iter().zip(&c.grad))
            .map(|(a, b)| (a - b).powi(2))
            .sum();
        eu += c.weight * d2;
    }
    Errors {
        p: ep.sqrt() / reference.p_norm,
        pbar: epbar.sqrt() / reference.p_norm,
        u: eu.sqrt() / reference.u_norm,
        load: (sol.load - reference.load).abs() / reference.load,
    }
}

/// Whether a row of a study or a sweep has a result, and if not, why.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Solved and converged.
    Ok,
    /// The solver ran but cannot certify its answer (the row's numbers are its last iterate).
    NotConverged,
    /// The scheme has no unique answer here (ε = 0 with more points than normal displacements).
    Kernel,
    /// The row could not be computed (too large for the memory, a failed factorisation, …).
    Failed,
}

impl Status {
    /// The status of a row whose solve returned `error`.
    pub fn of_error(error: &SolveError) -> Status {
        match error {
            SolveError::Kernel { .. } => Status::Kernel,
            SolveError::NotConverged { .. } => Status::NotConverged,
            _ => Status::Failed,
        }
    }

    /// The token of JSON and CSV: `ok`, `not_converged`, `kernel`, `failed`.
    pub fn token(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::NotConverged => "not_converged",
            Status::Kernel => "kernel",
            Status::Failed => "failed",
        }
    }

    /// The word shown in tables: `ok`, `not converged`, `kernel`, `failed`.
    pub fn word(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::NotConverged => "not converged",
            Status::Kernel => "kernel",
            Status::Failed => "failed",
        }
    }
}

/// JSON carries [`Status::token`], so that JSON and CSV cannot disagree.
impl Serialize for Status {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.token())
    }
}

/// One line of the study.
#[derive(Clone, Debug, Serialize)]
pub struct StudyRow {
    pub scheme: String,
    pub element: &'static str,
    pub rule: &'static str,
    pub level: u32,
    pub h: f64,
    pub epsilon: f64,
    /// The contact method and its parameters (`method`, `theta`, `gamma0`, `alm_tol`).
    #[serde(flatten)]
    pub method: MethodFields,
    pub n_dofs: usize,
    pub status: Status,
    /// Why the row has no (certified) result, when it has none.
    pub reason: Option<String>,
    pub newton_iterations: Option<usize>,
    /// The ALM's multiplier updates (null for the other methods, or without a result).
    pub outer_iterations: Option<usize>,
    pub converged: bool,
    /// A fresh solve: the mesh's work and Newton (what the pressures need), ms.
    pub solve_ms: Option<f64>,
    pub load: Option<f64>,
    pub errors: Option<Errors>,
    /// Observed rates against h (or, in an ε sweep, against ε) from the previous row.
    pub rates: Option<Errors>,
}

impl StudyRow {
    /// The row of a solve: its result, or what stopped it.
    fn new(
        reference: &Reference,
        scenario: &Scenario,
        (element, rule): (Element, Rule),
        level: u32,
        (method, epsilon): (Method, f64),
        outcome: Result<(&Discretization, &Solution), &SolveError>,
    ) -> Self {
        let mut row = StudyRow {
            scheme: Scheme::new(element, rule).label(),
            element: element.name(),
            rule: rule.name(),
            level,
            h: scenario.h(level),
            epsilon,
            method: method.into(),
            n_dofs: scenario.n_dofs(level, element),
            status: Status::Ok,
            reason: None,
            newton_iterations: None,
            outer_iterations: None,
            converged: false,
            solve_ms: None,
            load: None,
            errors: None,
            rates: None,
        };
        match outcome {
            Ok((disc, sol)) => {
                row.newton_iterations = Some(sol.newton.iterations);
                row.outer_iterations = sol.outer_iterations;
                row.converged = sol.newton.converged;
                row.solve_ms = Some(sol.timing.total);
                row.load = Some(sol.load);
                row.errors = Some(errors(reference, disc, sol));
                if !sol.newton.converged {
                    row.status = Status::NotConverged;
                    row.reason = sol.newton.diagnosis.clone();
                }
            }
            Err(e) => {
                row.status = Status::of_error(e);
                row.reason = Some(e.to_string());
            }
        }
        row
    }
}

/// True when every row has a certified result (the study's exit code: 0, else 1).
pub fn all_ok(rows: &[StudyRow]) -> bool {
    rows.iter().all(|r| r.status == Status::Ok)
}

/// Observed rates between two rows with results (None unless both are [`Status::Ok`]).
fn rates(prev: &StudyRow, row: &StudyRow, by_epsilon: bool) -> Option<Errors> {
    if prev.status != Status::Ok || row.status != Status::Ok {
        return None;
    }
    let (a, b) = (prev.errors?, row.errors?);
    let scale = if by_epsilon {
        (row.epsilon / prev.epsilon).ln()
    } else {
        (row.h / prev.h).ln()
    };
    let r = |a: f64, b: f64| (b / a).ln() / scale;
    Some(Errors {
        p: r(a.p, b.p),
        pbar: r(a.pbar, b.pbar),
        u: r(a.u, b.u),
        load: r(a.load, b.load),
    })
}

/// The elements of `schemes`, each once, in order of first appearance.
fn elements(schemes: &[(Element, Rule)]) -> Vec<Element> {
    let mut out: Vec<Element> = Vec::new();
    for &(e, _) in schemes {
        if !out.contains(&e) {
            out.push(e);
        }
    }
    out
}

/// Rows grouped per scheme, in `schemes`' order, each group with its rates from the row
/// before it (`by_epsilon`: rates against ε; rows with ε = 0 get none).
fn with_rates(groups: Vec<Vec<StudyRow>>, by_epsilon: bool) -> Vec<StudyRow> {
    let mut rows = Vec::new();
    for group in groups {
        for (i, mut row) in group.iter().cloned().enumerate() {
            let prev = i.checked_sub(1).map(|j| &group[j]);
            if let Some(prev) = prev.filter(|p| !by_epsilon || (p.epsilon > 0.0 && row.epsilon > 0.0)) {
                row.rates = rates(prev, &row, by_epsilon);
            }
            rows.push(row);
        }
    }
    rows
}

/// The method a study's row at `epsilon` uses ([`Method::resolve`]: None and ε = 0 is
/// `exact`), or why it has none.
fn row_method(method: Option<Method>, epsilon: f64) -> Result<(Method, f64), SolveError> {
    Method::resolve(method, epsilon).map_err(|e| SolveError::Input {
        what: "the method",
        message: e.to_string(),
    })
}

/// Every scheme at every level (fresh solves with `method` at ε; None: penalty, or exact for
/// ε = 0), against `reference`.
/// Each mesh is assembled and factorised once and shared by the schemes of its element; each
/// row's `solve_ms` is still a fresh solve's cost (that mesh's work plus the scheme's Newton).
/// A row that cannot be computed says why ([`StudyRow::status`]) and the others go on.
pub fn convergence(
    scenario: &Scenario,
    reference: &Reference,
    schemes: &[(Element, Rule)],
    levels: &[u32],
    method: Option<Method>,
    epsilon: f64,
) -> Vec<StudyRow> {
    let mut groups: Vec<Vec<StudyRow>> = vec![Vec::new(); schemes.len()];
    for element in elements(schemes) {
        for &level in levels {
            let disc = Discretization::of(scenario, level, element);
            for (i, &scheme) in schemes.iter().enumerate().filter(|(_, s)| s.0 == element) {
                let resolved = row_method(method, epsilon);
                let (m, e) = resolved.clone().unwrap_or((Method::Penalty, epsilon));
                let params = ContactParams {
                    rule: scheme.1,
                    method: m,
                    epsilon: e,
                    obstacle: scenario.obstacle.clone(),
                };
                let solved = disc.as_ref().map_err(Clone::clone).and_then(|disc| {
                    resolved?;
                    let mut sol = solve_fresh(disc, &params)?;
                    sol.timing.include_mesh_work(disc);
                    Ok((disc, sol))
                });
                let outcome = solved.as_ref().map(|(d, s)| (*d, s));
                groups[i].push(StudyRow::new(reference, scenario, scheme, level, (m, e), outcome));
            }
        }
    }
    with_rates(groups, false)
}

/// Every scheme at one level over several ε (re-solves on one mesh, warm-started from the
/// previous ε), against `reference`; one mesh per element. Rows that cannot be computed say
/// why, as in [`convergence`].
pub fn epsilon_sweep(
    scenario: &Scenario,
    reference: &Reference,
    schemes: &[(Element, Rule)],
    level: u32,
    method: Option<Method>,
    epsilons: &[f64],
) -> Vec<StudyRow> {
    let mut groups: Vec<Vec<StudyRow>> = vec![Vec::new(); schemes.len()];
    for element in elements(schemes) {
        let disc = Discretization::of(scenario, level, element);
        for (i, &scheme) in schemes.iter().enumerate().filter(|(_, s)| s.0 == element) {
            let mut previous: Option<Vec<f64>> = None;
            for &epsilon in epsilons {
                let resolved = row_method(method, epsilon);
                let (m, e) = resolved.clone().unwrap_or((Method::Penalty, epsilon));
                let params = ContactParams {
                    rule: scheme.1,
                    method: m,
                    epsilon: e,
                    obstacle: scenario.obstacle.clone(),
                };
                let solved = disc.as_ref().map_err(Clone::clone).and_then(|disc| {
                    resolved?;
                    let sol = solve_contact(
                        disc,
                        &params,
                        previous.as_deref(),
                        &NewtonOptions::default(),
                        &mut |_| ControlFlow::Continue(()),
                    )?;
                    Ok((disc, sol))
                });
                if let Ok((_, sol)) = &solved {
                    previous = Some(sol.newton.forces.clone());
                }
                let outcome = solved.as_ref().map(|(d, s)| (*d, s));
                groups[i].push(StudyRow::new(reference, scenario, scheme, level, (m, e), outcome));
            }
        }
    }
    with_rates(groups, true)
}
