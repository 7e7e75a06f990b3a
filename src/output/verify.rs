//! `riplab verify`'s output in the CLI's formats ([`crate::output::Report`]): a table in
//! [`WIDTH`] columns, a section per [`Kind`] and each case's source under its name; CSV (a row
//! per check, every field of the JSON); and JSON.

use std::fmt::Write as _;

use serde::Serialize;

use crate::output::{Cell, Report, csv_table};
use crate::verify::{Case, Check, Kind, Verdict, Verification};

/// The CSV columns of `riplab verify`.
const COLUMNS: [(&str, Cell); 12] = [
    ("case", Cell::Field("/case")),
    ("kind", Cell::Field("/kind")),
    ("quantity", Cell::Field("/quantity")),
    ("level", Cell::Field("/level")),
    ("computed", Cell::Field("/computed")),
    ("reference", Cell::Field("/reference")),
    ("measure", Cell::Field("/measure")),
    ("error", Cell::Field("/error")),
    ("tolerance", Cell::Field("/tolerance")),
    ("verdict", Cell::Field("/verdict")),
    ("reason", Cell::Field("/reason")),
    ("source", Cell::Field("/source")),
];

/// The table's width: a terminal of 80 columns (SSH at 80×24) shows it unwrapped.
pub const WIDTH: usize = 80;
/// The quantity's column, its two-space indent included; a longer quantity takes a line of
/// its own above its numbers.
const NAME: usize = 30;
/// The computed value's and the reference's columns.
const VALUE: usize = 10;
/// The error's and the tolerance's columns.
const ERROR: usize = 9;

/// Columns `text` takes on a terminal: combining marks (U+0300 to U+036F, the bar of p̄)
/// take none.
fn shown(text: &str) -> usize {
    text.chars()
        .filter(|c| !('\u{300}'..='\u{36f}').contains(c))
        .count()
}

/// `text` padded with spaces to `width` columns on a terminal.
fn pad(text: &str, width: usize) -> String {
    format!("{text}{}", " ".repeat(width.saturating_sub(shown(text))))
}

/// `v` in scientific notation with the most digits (up to `digits`) that fit `width`, or `-`
/// for none.
fn sci(v: Option<f64>, digits: usize, width: usize) -> String {
    let Some(v) = v else { return "-".into() };
    (0..=digits)
        .rev()
        .map(|d| format!("{v:.d$e}"))
        .find(|t| t.len() <= width)
        .unwrap_or_else(|| format!("{v:.0e}"))
}

/// `text` in lines of at most [`WIDTH`] columns, each starting with `indent` (words longer
/// than a line are cut).
fn wrap(text: &str, indent: &str) -> String {
    let room = WIDTH - shown(indent);
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        let mut word = word.to_string();
        while shown(&word) > room {
            let cut: String = word.chars().take(room).collect();
            word = word.chars().skip(room).collect();
            if !line.is_empty() {
                lines.push(std::mem::take(&mut line));
            }
            lines.push(cut);
        }
        if !line.is_empty() && shown(&line) + 1 + shown(&word) > room {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(&word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines.iter().map(|l| format!("{indent}{l}\n")).collect()
}

/// A check's row: its quantity, then its numbers and verdict (the numbers on a line of their
/// own when the quantity is longer than its column).
fn row(c: &Check) -> String {
    let numbers = format!(
        " {:>VALUE$} {:>VALUE$} {:>ERROR$} {:>ERROR$} {:>4}",
        sci(c.computed, 4, VALUE),
        sci(c.reference, 4, VALUE),
        sci(c.error, 2, ERROR),
        sci(c.tolerance, 2, ERROR),
        c.verdict.name()
    );
    let name = format!("  {}", c.quantity);
    let mut s = if shown(&name) <= NAME {
        format!("{}{numbers}\n", pad(&name, NAME))
    } else {
        format!("{}{}{numbers}\n", wrap(&c.quantity, "  "), " ".repeat(NAME))
    };
    if let Some(why) = &c.reason {
        s.push_str(&wrap(&format!("failed: {why}"), "    "));
    }
    s
}

impl Report for Verification {
    fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{}{:>w$} {:>w$} {:>e$} {:>e$} {:>4}",
            pad("quantity", NAME),
            "computed",
            "reference",
            "error",
            "tolerance",
            "",
            w = VALUE + 1,
            e = ERROR,
        );
        for kind in Kind::ALL {
            let rows: Vec<&Check> = self.checks.iter().filter(|c| c.kind == kind).collect();
            if rows.is_empty() {
                continue;
            }
            let _ = write!(
                s,
                "\n{}",
                wrap(&format!("{}: {}", kind.name().to_uppercase(), kind.meaning()), "")
            );
            let mut last: Option<(&str, u32)> = None;
            for c in rows {
                if last != Some((c.case, c.level)) {
                    last = Some((c.case, c.level));
                    let _ = writeln!(s, "{} (level {})", c.case, c.level);
                    if kind != Kind::Unchanged {
                        s.push_str(&wrap(&format!("source: {}", c.source), "    "));
                    }
                }
                s.push_str(&row(c));
            }
        }
        let ok = self.checks.iter().filter(|c| c.verdict == Verdict::Ok).count();
        let _ = write!(
            s,
            "\n{}",
            wrap(
                &format!(
                    "{ok} of {} checks OK (OK: error ≤ tolerance against the reference; unchanged: within {:e} relative of the value stored at the default level, no row at other levels)",
                    self.checks.len(),
                    crate::verify::CHANGE_RELATIVE
                ),
                ""
            )
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
    /// What its quantities compare.
    pub kind: Kind,
    /// Its default level.
    pub default_level: u32,
    /// The finest level it accepts.
    pub max_level: u32,
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
                    kind: c.kind,
                    default_level: c.default_level,
                    max_level: c.max_level,
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
            let _ = writeln!(
                s,
                "{} ({}, level {} by default, {} to {})",
                c.name,
                c.kind.name(),
                c.default_level,
                crate::verify::MIN_VERIFY_LEVEL,
                c.max_level
            );
            s.push_str(&wrap(c.description, "    "));
            s.push_str(&wrap(&format!("source: {}", c.source), "    "));
        }
        s
    }

    fn csv(&self) -> String {
        csv_table(
            &self.cases,
            &[
                ("name", Cell::Field("/name")),
                ("kind", Cell::Field("/kind")),
                ("default_level", Cell::Field("/default_level")),
                ("max_level", Cell::Field("/max_level")),
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
        let checks = crate::verify::run(&crate::verify::manufactured::CASE, Some(2));
        let json = serde_json::to_value(&checks[0]).unwrap();
        for (name, cell) in COLUMNS {
            let Cell::Field(pointer) = cell else {
                unreachable!()
            };
            assert!(json.pointer(pointer).is_some(), "{name}");
        }
    }
}
