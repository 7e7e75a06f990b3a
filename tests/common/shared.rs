//! Helpers shared by the integration tests and the lab's unit tests (`src/tui/tests`): nothing
//! here runs the binary or needs the integration tests' temporary directory.
#![allow(dead_code)]

use riplab::scenario::Scenario;

/// Snapshot `text` as `snapshots/<name>.snap` (the top-level directory, no module prefix).
#[macro_export]
macro_rules! snap {
    ($name:expr, $text:expr) => {
        insta::with_settings!({
            snapshot_path => concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"),
            prepend_module_to_snapshot => false,
            omit_expression => true,
        }, {
            insta::assert_snapshot!($name, $text);
        })
    };
}
/// The default scenario's text with some lines replaced: each `(old, new)` replaces the
/// whole line that starts with `old`.
pub fn paper_text(edits: &[(&str, &str)]) -> String {
    let mut text = riplab::scenario::DEFAULT_SCENARIO.to_string();
    for (old, new) in edits {
        let line = text
            .lines()
            .find(|l| l.trim_start().starts_with(old))
            .unwrap_or_else(|| panic!("no line {old}"))
            .to_string();
        text = text.replace(&line, new);
    }
    text
}
/// The default scenario with some TOML lines replaced (see [`paper_text`]).
pub fn paper_with(edits: &[(&str, &str)]) -> Scenario {
    Scenario::parse(&paper_text(edits), "test.toml").expect("valid test scenario")
}
/// A deterministic pseudo-random sequence in [−1, 1) (no dependency needed for tests).
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}
/// Relative difference |a − b| / max(|b|, floor).
pub fn rel(a: f64, b: f64, floor: f64) -> f64 {
    (a - b).abs() / b.abs().max(floor)
}
/// Whatever a command failed with, it did not panic.
pub fn no_panic(stderr: &str) {
    assert!(!stderr.contains("panicked"), "panicked: {stderr}");
}

/// Number of sign changes of successive differences above 1e-9: an oscillating sequence has
/// many.
pub fn turns(v: &[f64]) -> usize {
    let d: Vec<f64> = v
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| d.abs() > 1e-9)
        .collect();
    d.windows(2).filter(|w| w[0] * w[1] < 0.0).count()
}
