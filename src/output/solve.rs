//! `riplab solve`'s report: the solution's nodes, points and pressures, its timing and the overlays (Hertz, the exact circle).

use std::fmt::Write as _;

use serde::Serialize;

use super::Report;
use super::friction::{FrictionReport, MindlinReport, NO_NORM};
use crate::contact::circle::CircleContact;
use crate::contact::friction::State;
use crate::contact::hertz::Hertz;
use crate::contact::method::MethodFields;
use crate::contact::solution::{Solution, Timing};
use crate::discretization::Discretization;
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::study::Status;
use crate::text::{fixed, num, sci};
use crate::warning::Warning;

/// The `nodes` object of docs/design.md §7: Γ_C's vertices, ascending x.
#[derive(Serialize)]
pub struct Nodes {
    /// The vertices' x.
    pub x: Vec<f64>,
    /// u_n = u_y at each vertex.
    pub uy: Vec<f64>,
    /// The smoothed pressure p̄ (16)–(17) at each vertex.
    pub pbar: Vec<f64>,
    /// u_x at each vertex, with friction (null without).
    pub ux: Option<Vec<f64>>,
    /// The smoothed tangential traction t̄ at each vertex, p̄'s weights, with friction.
    pub tbar: Option<Vec<f64>>,
}

/// The `points` object of docs/design.md §7: the rule's points, ascending x, each distinct
/// point once.
#[derive(Serialize)]
pub struct Points {
    /// The points' x.
    pub x: Vec<f64>,
    /// The raw pressure p (12) at each point, compression positive.
    pub p: Vec<f64>,
    /// The raw tangential traction t at each point (on the body, along +x), with friction.
    pub t: Option<Vec<f64>>,
    /// Each point's `stick`, `slip` or `open`, with friction.
    pub state: Option<Vec<State>>,
}

/// The JSON object of docs/design.md §7 (fields may be added, never change meaning).
#[derive(Serialize)]
pub struct SolveReport {
    /// The scenario's name.
    pub scenario: String,
    /// The element: `q1`, `q2` or `p1`.
    pub element: &'static str,
    /// The contact rule: `gauss1`, `gauss2`, `trapezoid` or `simpson`.
    pub rule: &'static str,
    /// The paper's scheme `M1`–`M4`; None for another element × rule pair.
    pub scheme: Option<&'static str>,
    /// The mesh level (each level bisects every level-0 cell once more).
    pub level: u32,
    /// The cell size h: the largest cell side.
    pub h: f64,
    /// The edge-grading passes the mesh had ([`crate::grading`]; 0: the uniform level).
    pub refine_edges: u32,
    /// The grading asked, as `--refine-edges` writes it (`0`, `3`, `auto`, `3z`: over the
    /// contact zone).
    pub grading: crate::grading::Grading,
    /// The smallest cell side of the mesh.
    pub h_min: f64,
    /// The penalty parameter ε (0 for `exact`).
    pub epsilon: f64,
    /// The contact method and its parameters (`method`, `theta`, `gamma0`, `alm_tol`).
    #[serde(flatten)]
    pub method: MethodFields,
    /// The obstacle's depth d.
    pub depth: f64,
    /// Whether the body is a half model (x ≥ 0; its load is half the full body's).
    pub half_model: bool,
    /// The number of elements.
    pub n_elements: usize,
    /// The number of free dofs.
    pub n_dofs: usize,
    /// Newton iterations (for the ALM, its inner iterations summed over the updates).
    pub newton_iterations: usize,
    /// The ALM's multiplier updates; null for a method without an outer iteration.
    pub outer_iterations: Option<usize>,
    /// `ok`, or `not_converged` (the numbers are then the last iterate's).
    pub status: Status,
    /// Whether Newton converged.
    pub converged: bool,
    /// Newton's final relative residual.
    pub residual: f64,
    /// Why Newton did not converge, when it did not.
    pub diagnosis: Option<String>,
    /// The load P = I(p, 1) of the modelled body (half the full body's for a half model).
    pub load: f64,
    /// Γ_C's vertices: x, u_y, p̄.
    pub nodes: Nodes,
    /// The rule's points: x, p.
    pub points: Points,
    /// For a cylinder: the Hertz profile of the computed load and p̄'s distance from it.
    pub hertz: Option<HertzReport>,
    /// The friction law, its loading and Q (law `none` without friction).
    pub friction: FrictionReport,
    /// Cattaneo–Mindlin for the computed P and Q (a cylinder with Coulomb friction).
    pub mindlin: Option<MindlinReport>,
    /// Wall time of the solve's parts, in milliseconds.
    pub timing_ms: Timing,
    /// What is known to be poor about this answer ([`crate::warning`]).
    pub warnings: Vec<Warning>,
}

/// The `hertz` object of docs/design.md §7: the plane Hertz solution for the computed load of
/// the full body (docs/design.md §6).
#[derive(Serialize)]
pub struct HertzReport {
    /// The contact half-width a.
    pub a: f64,
    /// The peak pressure p₀.
    pub p0: f64,
    /// ‖p̄ − p_Hertz‖₀ / ‖p_Hertz‖₀ on Γ_C.
    pub relative_error: f64,
    /// The exact circular indenter for the same load (the circle, not Hertz's parabola;
    /// [`CircleContact`]); null for a load that would bury the cylinder beyond a = 0.9 R.
    pub circle: Option<CircleReport>,
}

/// The `hertz.circle` object: the exact rigid circular cylinder on a half-plane for the
/// computed load ([`CircleContact`]).
#[derive(Serialize)]
pub struct CircleReport {
    /// The contact half-width a.
    pub a: f64,
    /// The peak pressure p₀.
    pub p0: f64,
    /// ‖p̄ − p_circle‖₀ / ‖p_circle‖₀ on Γ_C.
    pub relative_error: f64,
}

impl HertzReport {
    /// Hertz's and the exact circle's solutions for the full body's load `full_load` on
    /// `scenario`, and p̄'s distances from them; None for an obstacle other than a cylinder.
    pub fn new(scenario: &Scenario, sol: &Solution, full_load: f64) -> Option<Self> {
        let obstacle = &sol.params.obstacle;
        let h = Hertz::for_load(obstacle, &scenario.material, full_load)?;
        Some(HertzReport {
            a: h.a,
            p0: h.p0,
            relative_error: h.relative_error(&sol.points, &sol.pbar),
            circle: CircleContact::for_load(obstacle, &scenario.material, full_load).map(|c| CircleReport {
                a: c.a,
                p0: c.p0,
                relative_error: c.relative_error(&sol.points, &sol.pbar),
            }),
        })
    }
}

impl SolveReport {
    /// The report of `sol` on `disc`, solved on `scenario` at `level`.
    pub fn new(scenario: &Scenario, level: u32, disc: &Discretization, sol: &Solution) -> Self {
        let element = disc.mesh.element;
        SolveReport {
            scenario: scenario.name.clone(),
            element: element.name(),
            rule: sol.params.rule.name(),
            scheme: Scheme::new(element, sol.params.rule).name(),
            level,
            h: disc.mesh.h(),
            refine_edges: 0,
            grading: Default::default(),
            h_min: crate::grading::h_min(&disc.mesh.xs, &disc.mesh.ys),
            epsilon: sol.params.epsilon,
            method: sol.method_fields(),
            depth: sol.params.obstacle.depth(),
            half_model: disc.mesh.symmetric_left,
            n_elements: disc.mesh.n_elements(),
            n_dofs: disc.n_dofs(),
            newton_iterations: sol.newton.iterations,
            outer_iterations: sol.outer_iterations,
            status: if sol.newton.converged {
                Status::Ok
            } else {
                Status::NotConverged
            },
            converged: sol.newton.converged,
            residual: sol.newton.residual,
            diagnosis: sol.newton.diagnosis.as_ref().map(ToString::to_string),
            load: sol.load,
            nodes: Nodes {
                x: sol.points.vertex_x.clone(),
                uy: sol.vertex_uy.clone(),
                pbar: sol.pbar.clone(),
                ux: sol.friction.as_ref().map(|f| f.vertex_ux.clone()),
                tbar: sol.friction.as_ref().map(|f| f.tbar.clone()),
            },
            points: Points {
                x: sol.points.points.iter().map(|q| q.x).collect(),
                p: sol.p.clone(),
                t: sol.friction.as_ref().map(|f| f.t.clone()),
                state: sol.friction.as_ref().map(|f| f.states.clone()),
            },
            friction: FrictionReport::new(sol),
            mindlin: MindlinReport::new(scenario, sol),
            hertz: {
                let full = if disc.mesh.symmetric_left {
                    2.0 * sol.load
                } else {
                    sol.load
                };
                HertzReport::new(scenario, sol, full)
            },
            timing_ms: sol.timing,
            warnings: sol.warnings.clone(),
        }
    }

    /// The scheme's label: "M1 (q1 + gauss1)" or "q1 + simpson".
    pub fn scheme_label(&self) -> String {
        match self.scheme {
            Some(m) => format!("{m} ({} + {})", self.element, self.rule),
            None => format!("{} + {}", self.element, self.rule),
        }
    }
}

/// One solve: its header, Γ_C's vertices and the rule's points.
impl Report for SolveReport {
    fn table(&self) -> String {
        let mut s = String::new();
        let model = if self.half_model {
            "half model"
        } else {
            "full model"
        };
        let _ = writeln!(
            s,
            "{} — {}, level {} (h = {}{}), {} elements, {} dofs, {model}",
            self.scenario,
            self.scheme_label(),
            self.level_label(),
            self.h,
            self.h_min_note(),
            self.n_elements,
            self.n_dofs
        );
        let state = if self.converged {
            "converged"
        } else {
            "NOT CONVERGED"
        };
        let plural = |n: usize| if n == 1 { "" } else { "s" };
        let outer = self
            .outer_iterations
            .map_or(String::new(), |n| format!("{n} multiplier update{}, ", plural(n)));
        let epsilon = if self.method.uses_epsilon() {
            format!(", ε = {:e}", self.epsilon)
        } else {
            String::new()
        };
        let _ = writeln!(
            s,
            "method {}{epsilon}, depth = {}, {outer}Newton: {} iteration{}, {state} (relative residual {:.1e})",
            self.method.label(),
            num(self.depth),
            self.newton_iterations,
            plural(self.newton_iterations),
            self.residual
        );
        let full = if self.half_model {
            format!(" (full body {})", fixed(2.0 * self.load, 6))
        } else {
            String::new()
        };
        let _ = writeln!(s, "load P = {}{full}", fixed(self.load, 6));
        if let Some(h) = &self.hertz {
            let _ = writeln!(
                s,
                "Hertz (plane, for this load): a = {}, p₀ = {}; ‖p̄ − p_Hertz‖₀/‖p_Hertz‖₀ = {} (Hertz's parabola x²/2R: off the circle by O(a²/R²); meaningful when the body is much larger than a)",
                fixed(h.a, 5),
                fixed(h.p0, 5),
                sci(h.relative_error, 3, NO_NORM)
            );
            if let Some(c) = &h.circle {
                let _ = writeln!(
                    s,
                    "exact circle (half-plane, for this load): a = {}, p₀ = {}; ‖p̄ − p_circle‖₀/‖p_circle‖₀ = {}",
                    fixed(c.a, 5),
                    fixed(c.p0, 5),
                    sci(c.relative_error, 3, NO_NORM)
                );
            }
        }
        if let Some(line) = self.friction.line() {
            let _ = writeln!(s, "{line}");
        }
        if let Some(m) = &self.mindlin {
            let _ = writeln!(s, "{}", m.line());
        }
        let t = &self.timing_ms;
        let _ = writeln!(
            s,
            "time: assembly {:.1} ms, symbolic {:.1} ms, factorisations {:.1} ms, Newton {:.1} ms, total {:.1} ms",
            t.assembly, t.symbolic, t.factorization, t.newton, t.total
        );
        let _ = writeln!(s);
        let _ = writeln!(s, "Γ_C vertices ({}):", self.nodes.x.len());
        let _ = writeln!(s, "{:>12} {:>14} {:>14}", "x", "u_y", "p̄");
        for i in 0..self.nodes.x.len() {
            let _ = writeln!(
                s,
                "{:>12.6} {:>14.6e} {:>14.6}",
                self.nodes.x[i], self.nodes.uy[i], self.nodes.pbar[i]
            );
        }
        let _ = writeln!(s);
        let _ = writeln!(s, "rule points ({}):", self.points.x.len());
        let _ = writeln!(s, "{:>12} {:>14}", "x", "p");
        for i in 0..self.points.x.len() {
            let _ = writeln!(s, "{:>12.6} {:>14.6}", self.points.x[i], self.points.p[i]);
        }
        s
    }

    /// One row per Γ_C vertex (`node`: x, u_y, p̄) and per rule point (`point`: x, p), from
    /// `nodes` and `points`.
    fn csv(&self) -> String {
        if self.friction.law != "none" {
            return friction_csv(&self.nodes, &self.points);
        }
        let mut s = String::from("kind,x,uy,pbar,p\n");
        for i in 0..self.nodes.x.len() {
            let _ = writeln!(
                s,
                "node,{},{},{},",
                self.nodes.x[i], self.nodes.uy[i], self.nodes.pbar[i]
            );
        }
        for i in 0..self.points.x.len() {
            let _ = writeln!(s, "point,{},,,{}", self.points.x[i], self.points.p[i]);
        }
        s
    }
}

/// A friction solve's CSV: one row per Γ_C vertex (`node`: x, u_y, p̄, u_x, t̄) and per rule
/// point (`point`: x, p, t, state).
fn friction_csv(nodes: &Nodes, points: &Points) -> String {
    let mut s = String::from("kind,x,uy,pbar,p,ux,tbar,t,state\n");
    let (ux, tbar) = (
        nodes.ux.as_deref().unwrap_or(&[]),
        nodes.tbar.as_deref().unwrap_or(&[]),
    );
    for i in 0..nodes.x.len() {
        let _ = writeln!(
            s,
            "node,{},{},{},,{},{},,",
            nodes.x[i],
            nodes.uy[i],
            nodes.pbar[i],
            cell(ux.get(i)),
            cell(tbar.get(i))
        );
    }
    let (t, state) = (
        points.t.as_deref().unwrap_or(&[]),
        points.state.as_deref().unwrap_or(&[]),
    );
    for i in 0..points.x.len() {
        let _ = writeln!(
            s,
            "point,{},,,{},,,{},{}",
            points.x[i],
            points.p[i],
            cell(t.get(i)),
            state.get(i).map_or("", |s| s.name())
        );
    }
    s
}

/// A number's CSV cell, empty where there is none.
fn cell(v: Option<&f64>) -> String {
    v.map_or(String::new(), f64::to_string)
}
