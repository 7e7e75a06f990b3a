//! What the CLI prints (docs/design.md §7): every result is a [`Report`], printed by one
//! function per format — a human table, CSV, or JSON — chosen once by [`output`]. CSV cells are
//! read from the JSON of the same struct ([`csv_table`]), so the two cannot drift apart.

use serde::Serialize;

mod csv;
mod friction;
mod graded;
mod infsup;
mod interface;
mod solve;
mod study;
mod study_interface;
mod sweep;
pub mod verify;
pub use csv::{Cell, csv_table};
pub use friction::{FrictionReport, MindlinReport};
pub use infsup::{INFSUP_COLUMNS, INTERFACE_INFSUP_COLUMNS, InfSupTable, InterfaceInfSupTable};
pub use interface::{INTERFACE_COLUMNS, InterfaceReport};
pub use solve::{CircleReport, HertzReport, Nodes, Points, SolveReport};
pub use study::{STUDY_COLUMNS, StudyReport};
pub use study_interface::{INTERFACE_STUDY_COLUMNS, InterfaceStudyReport};
pub use sweep::{SWEEP_COLUMNS, Sweep, SweepFailure, SweepRow};

/// Output format of the CLI.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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
