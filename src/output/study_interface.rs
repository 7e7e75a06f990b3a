//! `riplab study`'s report on a two-body scenario (docs/design.md §7, §12): each interface
//! discretisation's rows, their errors against the closed form and the observed rates.

use std::fmt::Write as _;

use serde::Serialize;

use super::Report;
use super::csv::{Cell, csv_table};
use super::study::short_reason;
use crate::study::interface::{ClosedForm, InterfaceStudyRow, ROUND_OFF};

/// `riplab study` on a two-body scenario; JSON `{ "scenario", "element", "ratio", "offset",
/// "slave", "method", "epsilon", "closed_form", "rows" }`.
#[derive(Serialize)]
pub struct InterfaceStudyReport<'a> {
    /// The scenario's name.
    pub scenario: &'a str,
    /// The element of both bodies.
    pub element: &'static str,
    /// The upper body's elements for every `ratio[1]` of the lower's across the interface.
    pub ratio: [u32; 2],
    /// The upper body's interior vertex lines shifted by this fraction of its element.
    pub offset: f64,
    /// `upper` or `lower`.
    pub slave: &'static str,
    /// How the constraint is enforced: `penalty`, `exact` or `alm`.
    pub method: &'static str,
    /// ε (0: the exact multipliers).
    pub epsilon: f64,
    /// What the rows are measured against: `patch`, `hertz` or `none`.
    pub closed_form: ClosedForm,
    /// A row per discretisation and level, each discretisation's levels together.
    pub rows: &'a [InterfaceStudyRow],
}

/// The CSV columns: a row per line, each cell a field of the row's JSON.
pub const INTERFACE_STUDY_COLUMNS: [(&str, Cell); 19] = [
    ("contact", Cell::Field("/contact")),
    ("level", Cell::Field("/level")),
    ("h", Cell::Field("/h")),
    ("dofs_lower", Cell::Field("/dofs_lower")),
    ("dofs_upper", Cell::Field("/dofs_upper")),
    ("status", Cell::Field("/status")),
    ("newton_iterations", Cell::Field("/newton_iterations")),
    ("outer_iterations", Cell::Field("/outer_iterations")),
    ("solve_ms", Cell::Field("/solve_ms")),
    ("P", Cell::Field("/P")),
    ("zone_from", Cell::Field("/contact_zone/from")),
    ("zone_to", Cell::Field("/contact_zone/to")),
    ("err_patch", Cell::Field("/errors/patch")),
    ("err_a", Cell::Field("/errors/a")),
    ("err_p0", Cell::Field("/errors/p0")),
    ("rate_patch", Cell::Field("/rates/patch")),
    ("rate_a", Cell::Field("/rates/a")),
    ("rate_p0", Cell::Field("/rates/p0")),
    ("reason", Cell::Field("/reason")),
];

/// An error, or `—` where there is none.
fn error(v: Option<f64>) -> String {
    v.map_or("—".into(), |v| format!("{v:.3e}"))
}

/// A rate, or `—` where there is none (a first level, a round-off error, no result).
fn rate(v: Option<f64>) -> String {
    v.map_or("—".into(), |v| format!("{v:.2}"))
}

impl InterfaceStudyReport<'_> {
    /// The table's first lines: the problem, the enforcement and what the rows measure.
    fn heading(&self) -> String {
        let mut s = String::new();
        let enforcement = match self.method {
            "exact" => "exact multipliers (ε = 0)".to_string(),
            "alm" => format!("ALM at ε = {:e}", self.epsilon),
            _ => format!("penalty ε = {:e}", self.epsilon),
        };
        let offset = match self.offset {
            0.0 => String::new(),
            o => format!(" offset {o}"),
        };
        let _ = writeln!(
            s,
            "{}: two bodies, {}, meshes {}:{}{offset} across the interface ({} slave), {enforcement}",
            self.scenario, self.element, self.ratio[0], self.ratio[1], self.slave
        );
        let measured = match self.closed_form {
            ClosedForm::Patch => "the contact patch test: patch error max |p − p_applied|/p_applied",
            ClosedForm::Hertz => {
                "two-body Hertz (Johnson §4.2): relative errors of a (from the pressure's moments) and p₀"
            }
            ClosedForm::None => {
                "no closed form for this scenario: each row gives the load P and the contact zone, no error"
            }
        };
        let _ = writeln!(s, "against {measured}");
        if self.closed_form != ClosedForm::None {
            let _ = writeln!(
                s,
                "rate = log(e₀/e₁)/log(h₀/h₁) from the level before; — where an error is below round-off ({ROUND_OFF:e})"
            );
        }
        s
    }

    /// A row's cells after its head: its result, or its status and short reason.
    fn cells(&self, r: &InterfaceStudyRow) -> String {
        let (Some(iterations), Some(ms)) = (r.newton_iterations, r.solve_ms) else {
            let why = r.reason.as_deref().unwrap_or("");
            return format!("  {}: {}", r.status.replace('_', " "), short_reason(why));
        };
        let (e, k) = (&r.errors, &r.rates);
        let results = match self.closed_form {
            ClosedForm::Patch => format!(" {:>10} {:>6}", error(e.patch), rate(k.patch)),
            ClosedForm::Hertz => format!(
                " {:>10} {:>6} {:>10} {:>6}",
                error(e.a),
                rate(k.a),
                error(e.p0),
                rate(k.p0)
            ),
            ClosedForm::None => format!(
                " {:>13} {:>21}",
                r.load.map_or("—".into(), |p| format!("{p:.6e}")),
                r.contact_zone
                    .map_or("none".into(), |z| format!("{:.4} to {:.4}", z.from, z.to))
            ),
        };
        format!(" {iterations:>6} {ms:>9.1}{results}")
    }
}

impl Report for InterfaceStudyReport<'_> {
    fn csv(&self) -> String {
        csv_table(self.rows, &INTERFACE_STUDY_COLUMNS)
    }

    fn table(&self) -> String {
        let mut s = self.heading();
        let results = match self.closed_form {
            ClosedForm::Patch => format!(" {:>10} {:>6}", "patch", "rate"),
            ClosedForm::Hertz => format!(" {:>10} {:>6} {:>10} {:>6}", "a", "rate", "p₀", "rate"),
            ClosedForm::None => format!(" {:>13} {:>21}", "P", "contact zone (x)"),
        };
        let _ = writeln!(
            s,
            "{:<14} {:>5} {:>9} {:>8} {:>8} {:>6} {:>9}{results}",
            "contact", "level", "h", "dofs lo", "dofs up", "Newton", "solve ms"
        );
        for (i, r) in self.rows.iter().enumerate() {
            if i > 0 && self.rows[i - 1].contact != r.contact {
                s.push('\n');
            }
            let _ = writeln!(
                s,
                "{:<14} {:>5} {:>9.6} {:>8} {:>8}{}",
                r.contact,
                r.level,
                r.h,
                r.dofs_lower,
                r.dofs_upper,
                self.cells(r)
            );
        }
        let reasons: Vec<String> = self
            .rows
            .iter()
            .filter_map(|r| {
                r.reason
                    .as_ref()
                    .map(|why| format!("{} level {}: {why}", r.contact, r.level))
            })
            .collect();
        if !reasons.is_empty() {
            let _ = writeln!(s, "\nrows without a result:");
            for why in reasons {
                let _ = writeln!(s, "  {why}");
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::interface::{InterfaceErrors, Zone};

    fn row(contact: &'static str, level: u32, patch: Option<f64>, rate: Option<f64>) -> InterfaceStudyRow {
        InterfaceStudyRow {
            contact,
            level,
            h: 0.5 / f64::from(1 << level),
            dofs_lower: 10,
            dofs_upper: 8,
            status: "ok",
            reason: None,
            newton_iterations: Some(1),
            outer_iterations: None,
            solve_ms: Some(1.5),
            load: Some(8.0),
            contact_zone: Some(Zone { from: 0.0, to: 1.5 }),
            errors: InterfaceErrors {
                patch,
                ..InterfaceErrors::default()
            },
            rates: InterfaceErrors {
                patch: rate,
                ..InterfaceErrors::default()
            },
        }
    }

    fn report(rows: &[InterfaceStudyRow], closed_form: ClosedForm) -> InterfaceStudyReport<'_> {
        InterfaceStudyReport {
            scenario: "s",
            element: "q1",
            ratio: [2, 3],
            offset: 0.0,
            slave: "upper",
            method: "exact",
            epsilon: 0.0,
            closed_form,
            rows,
        }
    }

    /// A round-off error's rate is `—` in the table and null in the JSON, an empty CSV cell;
    /// a failed row says its status and reason, in the table and after it.
    #[test]
    fn absent_rates_and_failed_rows() {
        let mut failed = row("nts", 1, None, None);
        (failed.status, failed.reason) = ("not_converged", Some("it stalled: 40 iterations".into()));
        (failed.newton_iterations, failed.solve_ms) = (None, None);
        let rows = [
            row("mortar", 0, Some(3e-15), None),
            row("mortar", 1, Some(5e-15), None),
            row("nts", 0, Some(0.1), None),
            failed,
        ];
        let r = report(&rows, ClosedForm::Patch);
        let table = r.table();
        let line = table.lines().filter(|l| l.starts_with("mortar")).nth(1).unwrap();
        assert!(line.ends_with('—'), "{table}");
        assert!(table.contains("not converged: it stalled"), "{table}");
        assert!(
            table.contains("nts level 1: it stalled: 40 iterations"),
            "{table}"
        );
        assert!(!table.contains("NaN"), "{table}");
        let json: serde_json::Value = serde_json::from_str(&r.json()).unwrap();
        assert!(json["rows"][1]["rates"]["patch"].is_null());
        assert_eq!(json["closed_form"], "patch");
        let csv = r.csv();
        let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        let at = header.iter().position(|h| *h == "rate_patch").unwrap();
        assert_eq!(csv.lines().nth(2).unwrap().split(',').nth(at), Some(""));
        // No closed form: the load and the zone, no error column.
        let table = report(&rows[..1], ClosedForm::None).table();
        assert!(
            table.contains("8.000000e0") && table.contains("0.0000 to 1.5000"),
            "{table}"
        );
        assert!(!table.contains("patch error"), "{table}");
    }

    /// Every CSV column names a field of a full row's JSON.
    #[test]
    fn every_column_is_a_field() {
        let rows = [row("mortar", 0, Some(1e-3), Some(1.0))];
        let json = serde_json::to_value(&rows[0]).unwrap();
        for (name, cell) in INTERFACE_STUDY_COLUMNS {
            let Cell::Field(pointer) = cell else {
                panic!("{name}")
            };
            assert!(json.pointer(pointer).is_some(), "{name}: {pointer}");
        }
    }
}
