//! `riplab sweep`'s report: one row per scheme and level, or why its solve failed.

use std::fmt::Write as _;

use serde::Serialize;

use super::Report;
use super::csv::{Cell, csv_table};
use super::solve::SolveReport;
use super::study::short_reason;
use crate::contact::ContactParams;
use crate::contact::method::MethodFields;
use crate::discretization::Discretization;
use crate::error::SolveError;
use crate::scenario::Scenario;
use crate::study::Status;

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
pub const SWEEP_COLUMNS: [(&str, Cell); 19] = [
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
    ("grading", Cell::Field("/grading")),
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

#[cfg(test)]
mod tests {
    use super::super::INFSUP_COLUMNS;
    use super::super::csv::csv_cell;
    use super::*;
    use crate::contact::Method;
    use crate::error::InputFault;
    use crate::mesh::Element;
    use crate::solve::sweep;

    /// A solved and a failed sweep row of the paper's problem at level 0.
    fn rows() -> Vec<SweepRow> {
        let scenario = Scenario::paper();
        let disc = scenario.discretize(0, Element::Q1).unwrap();
        let params = ContactParams {
            rule: scenario.rule,
            method: Method::Penalty,
            epsilon: scenario.epsilon,
            obstacle: scenario.obstacle.clone(),
        };
        let sol = sweep(&disc, std::slice::from_ref(&params)).remove(0).unwrap();
        let error = SolveError::Input(InputFault::Theta { theta: 2.0 });
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
            lines[2].ends_with(
                ",\"Nitsche's θ: 2 is outside [−1, 1] (1 symmetric, 0 incomplete, −1 skew-symmetric)\""
            ),
            "{}",
            lines[2]
        );
        assert!(lines[2].contains(",failed,"), "{}", lines[2]);
    }
}
