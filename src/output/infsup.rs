//! `riplab infsup`'s report: the discrete inf-sup constants β and β̄ of every scheme and level;
//! on a two-body scenario β of every multiplier space across the interface and level.

use std::fmt::Write as _;

use serde::Serialize;

use super::Report;
use super::csv::{Cell, csv_table};
use crate::infsup::InfSupRow;
use crate::infsup::interface_table::InterfaceRow;

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

/// `riplab infsup` on a two-body scenario: a row per multiplier space and level
/// ([`crate::infsup::interface_table::interface_table`]); JSON the array of its rows.
#[derive(Serialize)]
#[serde(transparent)]
pub struct InterfaceInfSupTable {
    /// A row per space and level, each space's levels together.
    pub rows: Vec<InterfaceRow>,
}

/// The two-body inf-sup CSV columns: the JSON's fields of the same names (the timings aside).
pub const INTERFACE_INFSUP_COLUMNS: [(&str, Cell); 11] = [
    ("level", Cell::Field("/level")),
    ("h", Cell::Field("/h")),
    ("h_master", Cell::Field("/h_master")),
    ("element", Cell::Field("/element")),
    ("rule", Cell::Field("/rule")),
    ("space", Cell::Field("/space")),
    ("multipliers", Cell::Field("/multipliers")),
    ("beta", Cell::Field("/beta")),
    ("beta_over_sqrt_h", Cell::Field("/beta_over_sqrt_h")),
    ("slope", Cell::Field("/slope")),
    ("kernel", Cell::Field("/kernel")),
];

impl Report for InterfaceInfSupTable {
    fn csv(&self) -> String {
        csv_table(&self.rows, &INTERFACE_INFSUP_COLUMNS)
    }

    fn table(&self) -> String {
        let rows = &self.rows;
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{:<18} {:>5} {:>9} {:>9} {:>6} {:>11} {:>11} {:>7} {:>9}",
            "space", "level", "h", "h_master", "mult", "β_h", "β_h/√h", "slope", "ms"
        );
        for (i, r) in rows.iter().enumerate() {
            if i > 0 && rows[i - 1].space != r.space {
                s.push('\n');
            }
            let beta = if r.kernel.is_some() {
                "0 (kernel)".to_string()
            } else {
                format!("{:.5}", r.beta)
            };
            let _ = writeln!(
                s,
                "{:<18} {:>5} {:>9.6} {:>9.6} {:>6} {:>11} {:>11.5} {:>7} {:>9.1}",
                r.space,
                r.level,
                r.h,
                r.h_master,
                r.multipliers,
                beta,
                r.beta_over_sqrt_h,
                r.slope.map_or("-".to_string(), |v| format!("{v:.3}")),
                r.mesh_ms + r.space_ms
            );
        }
        if let Some(r) = rows.iter().find(|r| r.kernel.is_some()) {
            let k = r.kernel.as_deref().unwrap_or_default();
            let _ = writeln!(
                s,
                "\nβ_h = 0 where the multipliers are not unique, e.g. {} level {}: {k}.",
                r.space, r.level
            );
        }
        let _ = writeln!(
            s,
            "h, h_master: the slave's and the master's widest edge on the interface; mult: the multipliers."
        );
        let _ = writeln!(
            s,
            "slope: observed exponent of β_h ∝ h^slope between successive levels (0.5 means β_h/√h is constant)."
        );
        s
    }
}
