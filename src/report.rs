//! What the CLI prints (docs/design.md §7): every result is a [`Report`], printed by one
//! function per format — a human table, CSV, or JSON — chosen once by [`output`]. CSV cells are
//! read from the JSON of the same struct ([`csv_table`]), so the two cannot drift apart.

mod graded;

use std::fmt::Write as _;

use serde::Serialize;

use crate::contact::circle::CircleContact;
use crate::contact::hertz::Hertz;
use crate::contact::method::MethodFields;
use crate::error::SolveError;
use crate::infsup::InfSupRow;
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::solve::{ContactParams, Discretization, Solution, Timing};
use crate::study::{Errors, Reference, Status, Study};
use crate::warning::Warning;

/// Output format of the CLI.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Format {
    /// The human table.
    Table,
    /// CSV: a header line, then a row per record.
    Csv,
    /// JSON (docs/design.md §7), pretty-printed.
    Json,
}

/// A result in each of the CLI's formats.
pub trait Report: Serialize {
    /// The human table.
    fn table(&self) -> String;
    /// CSV: a header line, then a row per record.
    fn csv(&self) -> String;
    /// JSON (docs/design.md §7), pretty-printed, with a final newline.
    fn json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a report is plain data") + "\n"
    }
}

/// `report` in `format` (the one place a format is chosen).
pub fn output(report: &impl Report, format: Format) -> String {
    match format {
        Format::Table => report.table(),
        Format::Csv => report.csv(),
        Format::Json => report.json(),
    }
}

/// Where a CSV column's cells come from, in the JSON of its record.
#[derive(Clone, Copy, Debug)]
pub enum Cell {
    /// The field at this JSON pointer (`/errors/p`); empty where it is null or absent.
    Field(&'static str),
    /// The largest number of the array at this pointer.
    Max(&'static str),
    /// The first of these fields that is present and not null.
    First(&'static [&'static str]),
}

/// CSV of `records` with `columns` (header, cell): each cell is read from the record's JSON, so
/// a column names a field the JSON has (the tests check every column against a full record).
pub fn csv_table<T: Serialize>(records: &[T], columns: &[(&str, Cell)]) -> String {
    let mut s = columns.iter().map(|c| c.0).collect::<Vec<_>>().join(",");
    s.push('\n');
    for record in records {
        let json = serde_json::to_value(record).expect("a record is plain data");
        let cells: Vec<String> = columns.iter().map(|&(_, cell)| csv_cell(&json, cell)).collect();
        s.push_str(&cells.join(","));
        s.push('\n');
    }
    s
}

/// One cell of [`csv_table`].
fn csv_cell(json: &serde_json::Value, cell: Cell) -> String {
    use serde_json::Value;
    let value = match cell {
        Cell::Field(pointer) => json.pointer(pointer).cloned(),
        Cell::Max(pointer) => json.pointer(pointer).and_then(Value::as_array).map(|a| {
            let max = a.iter().filter_map(Value::as_f64).fold(0.0, f64::max);
            Value::from(max)
        }),
        Cell::First(pointers) => pointers
            .iter()
            .filter_map(|p| json.pointer(p))
            .find(|v| !v.is_null())
            .cloned(),
    };
    match value {
        None | Some(Value::Null) => String::new(),
        Some(Value::String(text)) => csv_field(&text),
        // Floats as Rust prints them (the shortest form that reads back the same).
        Some(Value::Number(n)) => match (n.as_u64(), n.as_i64(), n.as_f64()) {
            (Some(u), _, _) => u.to_string(),
            (None, Some(i), _) => i.to_string(),
            (None, None, Some(f)) => f.to_string(),
            _ => n.to_string(),
        },
        Some(other) => csv_field(&other.to_string()),
    }
}

/// The `nodes` object of docs/design.md §7: Γ_C's vertices, ascending x.
#[derive(Serialize)]
pub struct Nodes {
    /// The vertices' x.
    pub x: Vec<f64>,
    /// u_n = u_y at each vertex.
    pub uy: Vec<f64>,
    /// The smoothed pressure p̄ (16)–(17) at each vertex.
    pub pbar: Vec<f64>,
}

/// The `points` object of docs/design.md §7: the rule's points, ascending x, each distinct
/// point once.
#[derive(Serialize)]
pub struct Points {
    /// The points' x.
    pub x: Vec<f64>,
    /// The raw pressure p (12) at each point, compression positive.
    pub p: Vec<f64>,
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
    /// Wall time of the solve's parts, in milliseconds.
    pub timing_ms: Timing,
    /// What is known to be poor about this answer ([`crate::warning`]).
    pub warnings: Vec<Warning>,
}

/// A row of a sweep that has no result: which parameters, and why (`status`, `reason`).
#[derive(Serialize)]
pub struct SweepFailure {
    /// The scenario's name.
    pub scenario: String,
    /// The element: `q1`, `q2` or `p1`.
    pub element: &'static str,
    /// The contact rule.
    pub rule: &'static str,
    /// The mesh level.
    pub level: u32,
    /// The penalty parameter ε of the row.
    pub epsilon: f64,
    /// The contact method and its parameters (`method`, `theta`, `gamma0`, `alm_tol`).
    #[serde(flatten)]
    pub method: MethodFields,
    /// The obstacle's depth d of the row.
    pub depth: f64,
    /// `kernel`, `not_converged` or `failed`.
    pub status: Status,
    /// Why the row has no result.
    pub reason: String,
}

impl SweepFailure {
    /// The row of `params` on `disc` whose solve returned `error`.
    pub fn new(
        scenario: &Scenario,
        disc: &Discretization,
        params: &ContactParams,
        error: &SolveError,
    ) -> Self {
        SweepFailure {
            scenario: scenario.name.clone(),
            element: disc.mesh.element.name(),
            rule: params.rule.name(),
            level: scenario.level,
            epsilon: params.epsilon,
            method: params.method.into(),
            depth: params.obstacle.depth(),
            status: Status::of_error(error),
            reason: error.to_string(),
        }
    }
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
            diagnosis: sol.newton.diagnosis.clone(),
            load: sol.load,
            nodes: Nodes {
                x: sol.points.vertex_x.clone(),
                uy: sol.vertex_uy.clone(),
                pbar: sol.pbar.clone(),
            },
            points: Points {
                x: sol.points.points.iter().map(|q| q.x).collect(),
                p: sol.p.clone(),
            },
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
            self.depth,
            self.newton_iterations,
            plural(self.newton_iterations),
            self.residual
        );
        let full = if self.half_model {
            format!(" (full body {:.6})", 2.0 * self.load)
        } else {
            String::new()
        };
        let _ = writeln!(s, "load P = {:.6}{full}", self.load);
        if let Some(h) = &self.hertz {
            let _ = writeln!(
                s,
                "Hertz (plane, for this load): a = {:.5}, p₀ = {:.5}; ‖p̄ − p_Hertz‖₀/‖p_Hertz‖₀ = {:.3e} (Hertz's parabola x²/2R: off the circle by O(a²/R²); meaningful when the body is much larger than a)",
                h.a, h.p0, h.relative_error
            );
            if let Some(c) = &h.circle {
                let _ = writeln!(
                    s,
                    "exact circle (half-plane, for this load): a = {:.5}, p₀ = {:.5}; ‖p̄ − p_circle‖₀/‖p_circle‖₀ = {:.3e}",
                    c.a, c.p0, c.relative_error
                );
            }
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

/// A row of a sweep: a solve's report, or why the row has none.
#[derive(Serialize)]
#[serde(untagged)]
pub enum SweepRow {
    /// A solved row: docs/design.md §7's object.
    Solved(Box<SolveReport>),
    /// A row with no result: its parameters, `status` and `reason`.
    Failed(SweepFailure),
}

/// A sweep (several ε or depths on one mesh): in JSON an array of docs/design.md §7's objects (a
/// row with no result is `{…, "status", "reason"}`); a summary table or CSV, a row each.
#[derive(Serialize)]
#[serde(transparent)]
pub struct Sweep {
    /// A row per ε or depth, in the order asked.
    pub rows: Vec<SweepRow>,
}

/// The sweep's CSV columns: the parameters, the outcome, and each row's largest p and p̄.
pub const SWEEP_COLUMNS: [(&str, Cell); 18] = [
    ("epsilon", Cell::Field("/epsilon")),
    ("method", Cell::Field("/method")),
    ("theta", Cell::Field("/theta")),
    ("gamma0", Cell::Field("/gamma0")),
    ("gamma0_auto", Cell::Field("/gamma0_auto")),
    ("alm_tol", Cell::Field("/alm_tol")),
    ("depth", Cell::Field("/depth")),
    ("status", Cell::Field("/status")),
    ("newton_iterations", Cell::Field("/newton_iterations")),
    ("outer_iterations", Cell::Field("/outer_iterations")),
    ("converged", Cell::Field("/converged")),
    ("load", Cell::Field("/load")),
    ("max_p", Cell::Max("/points/p")),
    ("max_pbar", Cell::Max("/nodes/pbar")),
    ("total_ms", Cell::Field("/timing_ms/total")),
    ("refine_edges", Cell::Field("/refine_edges")),
    ("h_min", Cell::Field("/h_min")),
    ("reason", Cell::First(&["/diagnosis", "/reason"])),
];

impl Report for Sweep {
    fn csv(&self) -> String {
        csv_table(&self.rows, &SWEEP_COLUMNS)
    }

    fn table(&self) -> String {
        let mut s = String::new();
        let max = |v: &[f64]| v.iter().cloned().fold(0.0, f64::max);
        if let Some(SweepRow::Solved(r)) = self.rows.iter().find(|r| matches!(r, SweepRow::Solved(_))) {
            let _ = writeln!(
                s,
                "{} — {}, level {} (h = {}{}), {} dofs",
                r.scenario,
                r.scheme_label(),
                r.level_label(),
                r.h,
                r.h_min_note(),
                r.n_dofs
            );
        }
        let _ = writeln!(
            s,
            "{:>10} {:>8} {:>7} {:>10} {:>14} {:>12} {:>12} {:>10}  method",
            "ε", "depth", "Newton", "converged", "load", "max p", "max p̄", "total ms"
        );
        for row in &self.rows {
            let _ = match row {
                SweepRow::Solved(r) => writeln!(
                    s,
                    "{} {:>8} {:>7} {:>10} {:>14.6} {:>12.4} {:>12.4} {:>10.1}  {}",
                    r.method.epsilon_text(r.epsilon, 10),
                    r.depth,
                    r.newton_iterations,
                    r.converged,
                    r.load,
                    max(&r.points.p),
                    max(&r.nodes.pbar),
                    r.timing_ms.total,
                    r.method.label()
                ),
                SweepRow::Failed(f) => writeln!(
                    s,
                    "{:>10.1e} {:>8}  {}: {}",
                    f.epsilon,
                    f.depth,
                    f.status.word(),
                    short_reason(&f.reason)
                ),
            };
        }
        s
    }
}

/// `riplab infsup`: a row per element × rule pair and level ([`crate::infsup::table`]); JSON
/// is the array of docs/design.md §7.
#[derive(Serialize)]
#[serde(transparent)]
pub struct InfSupTable {
    /// A row per element × rule pair and level, each pair's levels together.
    pub rows: Vec<InfSupRow>,
}

/// The inf-sup CSV columns: the JSON's fields of the same names (the timings aside).
pub const INFSUP_COLUMNS: [(&str, Cell); 11] = [
    ("level", Cell::Field("/level")),
    ("h", Cell::Field("/h")),
    ("element", Cell::Field("/element")),
    ("rule", Cell::Field("/rule")),
    ("scheme", Cell::Field("/scheme")),
    ("beta", Cell::Field("/beta")),
    ("beta_over_sqrt_h", Cell::Field("/beta_over_sqrt_h")),
    ("beta_bar", Cell::Field("/beta_bar")),
    ("beta_bar_over_sqrt_h", Cell::Field("/beta_bar_over_sqrt_h")),
    ("slope", Cell::Field("/slope")),
    ("kernel", Cell::Field("/kernel")),
];

impl Report for InfSupTable {
    fn csv(&self) -> String {
        csv_table(&self.rows, &INFSUP_COLUMNS)
    }

    fn table(&self) -> String {
        let rows = &self.rows;
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{:<6} {:<15} {:>5} {:>9} {:>11} {:>11} {:>11} {:>11} {:>7} {:>9}",
            "scheme", "pair", "level", "h", "β_h", "β_h/√h", "β̄_h", "β̄_h/√h", "slope", "ms"
        );
        for (i, r) in rows.iter().enumerate() {
            if i > 0 && !rows[i - 1].same_pair(r) {
                s.push('\n');
            }
            let beta = if r.kernel.is_some() {
                "0 (kernel)".to_string()
            } else {
                format!("{:.5}", r.beta)
            };
            let _ = writeln!(
                s,
                "{:<6} {:<15} {:>5} {:>9.6} {:>11} {:>11.5} {:>11.5} {:>11.5} {:>7} {:>9.1}",
                r.scheme.unwrap_or("-"),
                format!("{}+{}", r.element, r.rule),
                r.level,
                r.h,
                beta,
                r.beta_over_sqrt_h,
                r.beta_bar,
                r.beta_bar_over_sqrt_h,
                r.slope.map_or("-".to_string(), |v| format!("{v:.3}")),
                r.mesh_ms + r.rule_ms
            );
        }
        let kernels: Vec<String> = rows
            .iter()
            .filter_map(|r| {
                r.kernel
                    .as_ref()
                    .map(|k| format!("{}+{} level {}: {k}", r.element, r.rule, r.level))
            })
            .collect();
        if let Some(first) = kernels.first() {
            let _ = writeln!(
                s,
                "\nβ_h = 0 where the pressure space has a kernel, e.g. {first}."
            );
        }
        let _ = writeln!(
            s,
            "slope: observed exponent of β_h ∝ h^slope between successive levels (0.5 means β_h/√h is constant)."
        );
        s
    }
}

/// `riplab study`: the reference, the rows and each scheme's least-squares fit; JSON
/// `{ "scenario", "reference", "rows", "fits" }` (docs/design.md §7).
pub struct StudyReport<'a> {
    /// The scenario's name.
    pub scenario: &'a str,
    /// The study: reference, rows and fits.
    pub study: &'a Study,
}

impl StudyReport<'_> {
    /// The JSON of the reference (the study's `reference` object).
    fn reference_json(&self) -> serde_json::Value {
        let reference = &self.study.reference;
        serde_json::json!({
            "element": reference.element.name(), "rule": reference.rule.name(), "epsilon": 0.0,
            "level": reference.level, "refinements": reference.grid.refinements,
            "h_min": reference.grid.h_min(), "n_dofs": reference.n_dofs,
            "load": reference.load, "ms": reference.ms, "source": reference.source,
            "estimate": reference.estimate, "target": reference.target,
            "target_met": reference.target.map(|_| reference.stopped.is_none()), "stopped": reference.stopped,
        })
    }
}

impl Serialize for StudyReport<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        serde_json::json!({
            "scenario": self.scenario,
            "reference": self.reference_json(),
            "rows": self.study.rows,
            "fits": self.study.fits,
        })
        .serialize(s)
    }
}

/// The study's CSV columns. A line is a `row` (a [`crate::study::StudyRow`]'s JSON), a `fit` (a
/// [`crate::study::Fit`]'s: its rates in the `rate_*` columns) or, last, the `reference` (its
/// smallest cell side as `h`, its estimated error in `err_*`, why its refinement stopped in
/// `reason`, and in `source` whether it was `computed` or read from the `cache`).
pub const STUDY_COLUMNS: [(&str, Cell); 32] = [
    ("kind", Cell::Field("/kind")),
    ("scheme", Cell::Field("/scheme")),
    ("element", Cell::Field("/element")),
    ("rule", Cell::Field("/rule")),
    ("level", Cell::Field("/level")),
    ("refinements", Cell::Field("/refinements")),
    ("refine_edges", Cell::Field("/refine_edges")),
    ("h", Cell::First(&["/h", "/h_min"])),
    ("h_min", Cell::Field("/h_min")),
    ("epsilon", Cell::Field("/epsilon")),
    ("method", Cell::Field("/method")),
    ("theta", Cell::Field("/theta")),
    ("gamma0", Cell::Field("/gamma0")),
    ("gamma0_auto", Cell::Field("/gamma0_auto")),
    ("alm_tol", Cell::Field("/alm_tol")),
    ("n_dofs", Cell::Field("/n_dofs")),
    ("status", Cell::Field("/status")),
    ("newton_iterations", Cell::Field("/newton_iterations")),
    ("outer_iterations", Cell::Field("/outer_iterations")),
    ("converged", Cell::Field("/converged")),
    ("solve_ms", Cell::First(&["/solve_ms", "/ms"])),
    ("load", Cell::Field("/load")),
    ("err_p", Cell::First(&["/errors/p", "/estimate/p"])),
    ("err_pbar", Cell::Field("/errors/pbar")),
    ("err_u", Cell::First(&["/errors/u", "/estimate/u"])),
    ("err_load", Cell::First(&["/errors/load", "/estimate/load"])),
    ("rate_p", Cell::Field("/rates/p")),
    ("rate_pbar", Cell::Field("/rates/pbar")),
    ("rate_u", Cell::Field("/rates/u")),
    ("rate_load", Cell::Field("/rates/load")),
    ("reason", Cell::First(&["/reason", "/stopped"])),
    ("source", Cell::Field("/source")),
];

/// `value`, an object, with `kind` first.
fn kind(kind: &str, value: serde_json::Value) -> serde_json::Value {
    let mut record = serde_json::Map::new();
    record.insert("kind".into(), kind.into());
    if let serde_json::Value::Object(fields) = value {
        record.extend(fields);
    }
    serde_json::Value::Object(record)
}

impl Report for StudyReport<'_> {
    fn csv(&self) -> String {
        fn value(v: &impl Serialize) -> serde_json::Value {
            serde_json::to_value(v).expect("a record is plain data")
        }
        let mut records: Vec<serde_json::Value> = Vec::new();
        records.extend(self.study.rows.iter().map(|r| kind("row", value(r))));
        records.extend(self.study.fits.iter().map(|f| kind("fit", value(f))));
        let mut reference = kind("reference", self.reference_json());
        // The reference is the exact method, solved (or read) and certified.
        for (key, v) in [
            ("scheme", "reference".into()),
            ("method", "exact".into()),
            ("status", "ok".into()),
            ("converged", true.into()),
        ] {
            reference[key] = v;
        }
        records.push(reference);
        csv_table(&records, &STUDY_COLUMNS)
    }

    fn table(&self) -> String {
        let (scenario, study) = (self.scenario, self.study);
        let (reference, rows) = (&study.reference, &study.rows);
        let mut s = String::new();
        let rate = |r: &Option<Errors>, f: fn(&Errors) -> f64| {
            r.as_ref().map_or(String::new(), |e| format!("{:.2}", f(e)))
        };
        let _ = writeln!(
            s,
            "{scenario}: reference {}+{}, ε = 0 (exact constraint), level {}{}, {} dofs, load {:.6}",
            reference.element.name(),
            reference.rule.name(),
            reference.level,
            match reference.grid.refinements {
                0 => String::new(),
                1 => " + 1 edge refinement".into(),
                k => format!(" + {k} edge refinements"),
            },
            reference.n_dofs,
            reference.load
        );
        let _ = writeln!(s, "{}", reference_estimate(reference));
        if let Some(why) = &reference.stopped {
            let _ = writeln!(
                s,
                "warning: the reference's refinement stopped short of the target: {why}"
            );
        }
        let mut methods: Vec<String> = rows.iter().map(|r| r.method.setting().label()).collect();
        methods.dedup();
        if !methods.is_empty() {
            let _ = writeln!(s, "method: {}", methods.join(", "));
        }
        let _ = writeln!(
            s,
            "relative errors: p, p̄ in L²(Γ_C); u in H¹ (7); load P; rate = observed order between successive rows; fit = least-squares order over the scheme's rows"
        );
        let _ = writeln!(
            s,
            "{:<14} {:>5} {:>9} {:>8} {:>8} {:>7} {:>9} {:>10} {:>5} {:>10} {:>5} {:>10} {:>5} {:>10} {:>5}",
            "scheme",
            "level",
            "h",
            "ε",
            "dofs",
            "Newton",
            "solve ms",
            "p",
            "rate",
            "p̄",
            "rate",
            "u",
            "rate",
            "load",
            "rate"
        );
        for (i, r) in rows.iter().enumerate() {
            if i > 0 && !rows[i - 1].same_series(r) {
                s.push('\n');
            }
            let head = format!(
                "{:<14} {:>5} {:>9.6} {} {:>8}",
                r.scheme,
                r.level_label(),
                r.h,
                r.method.epsilon_text(r.epsilon, 8),
                r.n_dofs
            );
            let last = rows.get(i + 1).is_none_or(|n| !n.same_series(r));
            let fit = study.fits.iter().find(|f| {
                last && f.scheme == r.scheme
                    && f.method == r.method.setting()
                    && f.refine_edges == r.grading.to_string()
            });
            let (Some(e), Some(iterations), Some(ms)) = (&r.errors, r.newton_iterations, r.solve_ms) else {
                // No result: the reason in place of the numbers.
                let reason = r.reason.as_deref().unwrap_or("");
                let _ = writeln!(s, "{head}  {}: {}", r.status.word(), short_reason(reason));
                if let Some(f) = fit {
                    let _ = writeln!(s, "{}", fit_line(f, &rate));
                }
                continue;
            };
            let flag = if r.status == Status::Ok {
                String::new()
            } else {
                format!("  {}", r.status.word().to_uppercase())
            };
            let _ = writeln!(
                s,
                "{head} {:>7} {:>9.1} {:>10.3e} {:>5} {:>10.3e} {:>5} {:>10.3e} {:>5} {:>10.3e} {:>5}{flag}",
                iterations,
                ms,
                e.p,
                rate(&r.rates, |e| e.p),
                e.pbar,
                rate(&r.rates, |e| e.pbar),
                e.u,
                rate(&r.rates, |e| e.u),
                e.load,
                rate(&r.rates, |e| e.load)
            );
            if let Some(f) = fit {
                let _ = writeln!(s, "{}", fit_line(f, &rate));
            }
        }
        let reasons: Vec<String> = rows
            .iter()
            .filter(|r| r.status != Status::Ok)
            .filter_map(|r| {
                r.reason.as_ref().map(|why| {
                    let setting = if r.method.uses_epsilon() {
                        format!("ε = {:e}", r.epsilon)
                    } else {
                        r.method.label()
                    };
                    format!("{} level {} {setting}: {why}", r.scheme, r.level)
                })
            })
            .collect();
        if !reasons.is_empty() {
            let _ = writeln!(s, "\nrows without a certified result:");
            for why in reasons {
                let _ = writeln!(s, "  {why}");
            }
        }
        s
    }
}

/// The table's lines on the reference's estimated error and what the study asked of it.
fn reference_estimate(reference: &Reference) -> String {
    let Some(e) = &reference.estimate else {
        return "reference's estimated error: none (no coarser reference)".into();
    };
    let u_note = if reference.grid.refinements > 0 {
        " (the uniform level's)"
    } else {
        ""
    };
    let mut line = format!(
        "reference's estimated error (difference from {}): p {:.3e}, u {:.3e}{u_note}, load {:.3e}",
        e.against, e.p, e.u, e.load
    );
    if let Some(t) = &reference.target {
        let _ = write!(
            line,
            "\nreference's target (a tenth of the smallest row errors): p ≤ {:.3e}, u ≤ {:.3e}: {}",
            t.p,
            t.u,
            if reference.stopped.is_none() {
                "met"
            } else {
                "not met"
            }
        );
    }
    line
}

/// Formats one rate of a row's (or a fit's) rates, empty when there are none.
type RateText = dyn Fn(&Option<Errors>, fn(&Errors) -> f64) -> String;

/// The table's `fit` line of a scheme: its least-squares rates in the rate columns.
fn fit_line(f: &crate::study::Fit, rate: &RateText) -> String {
    format!(
        "{:<66} {:>10} {:>5} {:>10} {:>5} {:>10} {:>5} {:>10} {:>5}",
        format!("  fit: least squares over {} rows", f.rows),
        "",
        rate(&f.rates, |e| e.p),
        "",
        rate(&f.rates, |e| e.pbar),
        "",
        rate(&f.rates, |e| e.u),
        "",
        rate(&f.rates, |e| e.load)
    )
}

/// The first clause of a reason, for a table cell (the whole reason follows the table).
fn short_reason(reason: &str) -> &str {
    if reason.contains("multipliers are not unique") {
        return "multipliers not unique";
    }
    reason.split([':', ';']).next().unwrap_or(reason).trim()
}

/// A CSV field, quoted when it holds a comma, a quote or a line break.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Method;
    use crate::mesh::Element;
    use crate::solve::sweep;

    /// A solved and a failed sweep row of the paper's problem at level 0.
    fn rows() -> Vec<SweepRow> {
        let scenario = Scenario::paper();
        let disc = Discretization::of(&scenario, 0, Element::Q1).unwrap();
        let params = ContactParams {
            rule: scenario.rule,
            method: Method::Penalty,
            epsilon: scenario.epsilon,
            obstacle: scenario.obstacle.clone(),
        };
        let sol = sweep(&disc, std::slice::from_ref(&params)).remove(0).unwrap();
        let error = SolveError::Input {
            what: "the method",
            message: "a reason, with a comma".into(),
        };
        vec![
            SweepRow::Solved(Box::new(SolveReport::new(&scenario, 0, &disc, &sol))),
            SweepRow::Failed(SweepFailure::new(&scenario, &disc, &params, &error)),
        ]
    }

    /// Every column names a field of the JSON (a renamed or removed field fails here, not in a
    /// user's script): each of a solved row's cells is present, and a failed row has its
    /// parameters, status and reason.
    #[test]
    fn every_csv_column_is_a_json_field() {
        let rows = rows();
        let solved = serde_json::to_value(&rows[0]).unwrap();
        for (header, cell) in SWEEP_COLUMNS {
            let present = match cell {
                Cell::Field(p) | Cell::Max(p) => solved.pointer(p).is_some(),
                Cell::First(ps) => ps.iter().any(|p| solved.pointer(p).is_some()),
            };
            assert!(present, "sweep column {header}");
        }
        let failed = serde_json::to_value(&rows[1]).unwrap();
        for header in ["epsilon", "method", "depth", "status", "reason"] {
            let (_, cell) = SWEEP_COLUMNS.iter().find(|c| c.0 == header).unwrap();
            assert!(!csv_cell(&failed, *cell).is_empty(), "failed row's {header}");
        }
        let scenario = Scenario::paper();
        let infsup = crate::infsup::table(
            &scenario,
            &[(Element::Q1, crate::contact::Rule::Simpson)],
            &[0, 1],
        )
        .unwrap();
        let json = serde_json::to_value(&infsup[1]).unwrap();
        for (header, cell) in INFSUP_COLUMNS {
            let Cell::Field(p) = cell else { panic!("{header}") };
            assert!(json.pointer(p).is_some(), "infsup column {header}");
        }
    }

    /// CSV cells are the JSON's values: numbers as Rust prints them, null as empty, text
    /// quoted when it holds a comma, the largest of an array for `Max`.
    #[test]
    fn csv_cells_are_the_json_values() {
        let rows = rows();
        let csv = Sweep { rows }.csv();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 3);
        assert_eq!(lines[0], SWEEP_COLUMNS.map(|c| c.0).join(","));
        let solved: Vec<&str> = lines[1].split(',').collect();
        assert_eq!(solved.len(), SWEEP_COLUMNS.len());
        assert_eq!(solved[0], "0.000001", "ε = 1e-6 as Rust prints it");
        assert_eq!(solved[1], "penalty");
        assert_eq!(solved[2], "", "θ is null for the penalty");
        assert_eq!(solved[7], "ok");
        let load: f64 = solved[11].parse().unwrap();
        let max_p: f64 = solved[12].parse().unwrap();
        assert!(load > 0.0 && max_p > 0.0);
        assert!(
            lines[2].ends_with(",\"the method: a reason, with a comma\""),
            "{}",
            lines[2]
        );
        assert!(lines[2].contains(",failed,"), "{}", lines[2]);
    }
}
