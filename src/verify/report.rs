//! `riplab verify`'s output in the CLI's formats ([`crate::output::Report`]): a table with
//! each case's source under its rows, CSV (a row per check, read from the JSON), and JSON.

use std::fmt::Write as _;

use serde::Serialize;

use super::{Case, Verdict, Verification};
use crate::output::{Cell, Report, csv_table};

/// The CSV columns of `riplab verify`.
const COLUMNS: [(&str, Cell); 16] = [
    ("case", Cell::Field("/case")),
    ("quantity", Cell::Field("/quantity")),
    ("level", Cell::Field("/level")),
    ("computed", Cell::Field("/computed")),
    ("reference", Cell::Field("/reference")),
    ("measure", Cell::Field("/measure")),
    ("error", Cell::Field("/error")),
    ("tolerance", Cell::Field("/tolerance")),
    ("right", Cell::Field("/right")),
    ("stored", Cell::Field("/stored")),
    ("change", Cell::Field("/change")),
    ("change_tolerance", Cell::Field("/change_tolerance")),
    ("unchanged", Cell::Field("/unchanged")),
    ("verdict", Cell::Field("/verdict")),
    ("reason", Cell::Field("/reason")),
    ("source", Cell::Field("/source")),
];

/// `text` padded with spaces to `width` columns on a terminal: combining marks (U+0300 to
/// U+036F, the bar of p̄) take none.
fn pad(text: &str, width: usize) -> String {
    let shown = text
        .chars()
        .filter(|c| !('\u{300}'..='\u{36f}').contains(c))
        .count();
    format!("{text}{}", " ".repeat(width.saturating_sub(shown)))
}

/// A number of the table, or `-` for none.
fn cell(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |v| format!("{v:.4e}"))
}

impl Report for Verification {
    fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{:<16} {:<38} {:>2} {:>11} {:>11} {:>10} {:>10} {:>5} {:>10} {:>5}",
            "case", "quantity", "L", "computed", "reference", "error", "tolerance", "right", "change", "same"
        );
        for (i, c) in self.checks.iter().enumerate() {
            let same = c.unchanged.map_or("-", Verdict::name);
            let _ = writeln!(
                s,
                "{:<16} {} {:>2} {:>11} {:>11} {:>10} {:>10} {:>5} {:>10} {:>5}",
                c.case,
                pad(&c.quantity, 38),
                c.level,
                cell(c.computed),
                cell(c.reference),
                cell(c.error),
                cell(c.tolerance),
                c.right.name(),
                cell(c.change),
                same
            );
            if let Some(why) = &c.reason {
                let _ = writeln!(s, "{:<16} failed: {why}", "");
            }
            let last_of_case = self.checks.get(i + 1).is_none_or(|n| n.case != c.case);
            if last_of_case {
                let _ = writeln!(s, "{:<16} source: {}", "", c.source);
            }
        }
        let ok = self.checks.iter().filter(|c| c.verdict == Verdict::Ok).count();
        let _ = writeln!(
            s,
            "\n{ok} of {} checks OK (right: error ≤ tolerance against the reference; same: within {:e} relative of the stored value at the default level, - at other levels)",
            self.checks.len(),
            super::CHANGE_RELATIVE
        );
        s
    }

    fn csv(&self) -> String {
        csv_table(&self.checks, &COLUMNS)
    }
}

/// `riplab verify --list`: the cases, their default levels, what they check and their sources.
#[derive(Serialize)]
#[serde(transparent)]
pub struct CaseList {
    /// A row per case.
    pub cases: Vec<CaseEntry>,
}

/// One case of [`CaseList`].
#[derive(Serialize)]
pub struct CaseEntry {
    /// The case's name.
    pub name: &'static str,
    /// Its default level.
    pub default_level: u32,
    /// What it checks.
    pub description: &'static str,
    /// Where its reference comes from.
    pub source: &'static str,
}

impl CaseList {
    /// The list of `cases`.
    pub fn new(cases: &[Case]) -> Self {
        CaseList {
            cases: cases
                .iter()
                .map(|c| CaseEntry {
                    name: c.name,
                    default_level: c.default_level,
                    description: c.description,
                    source: c.source,
                })
                .collect(),
        }
    }
}

impl Report for CaseList {
    fn table(&self) -> String {
        let mut s = String::new();
        for c in &self.cases {
            let _ = writeln!(s, "{:<16} level {}  {}", c.name, c.default_level, c.description);
            let _ = writeln!(s, "{:<16} source: {}", "", c.source);
        }
        s
    }

    fn csv(&self) -> String {
        csv_table(
            &self.cases,
            &[
                ("name", Cell::Field("/name")),
                ("default_level", Cell::Field("/default_level")),
                ("description", Cell::Field("/description")),
                ("source", Cell::Field("/source")),
            ],
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every CSV column names a field of a check's JSON.
    #[test]
    fn the_csv_columns_are_fields() {
        let checks = super::super::run(&super::super::manufactured::CASE, Some(2));
        let json = serde_json::to_value(&checks[0]).unwrap();
        for (name, cell) in COLUMNS {
            let Cell::Field(pointer) = cell else {
                unreachable!()
            };
            assert!(json.pointer(pointer).is_some(), "{name}");
        }
    }
}
