//! Helpers shared by the integration tests.
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

/// Run the riplab binary: (exit code, stdout, stderr).
pub fn riplab(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_riplab"))
        .args(args)
        .env("XDG_CACHE_HOME", test_cache())
        .output()
        .expect("runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// Σ over the clamped bottom of (K u)_y: the vertical reaction of the support.
pub fn bottom_reaction(
    scenario: &Scenario,
    disc: &riplab::discretization::Discretization,
    sol: &riplab::solution::Solution,
) -> f64 {
    use riplab::fem::{Form, apply};
    let ku = apply(
        disc.mesh(),
        Form::Elasticity(scenario.material, scenario.integration),
        &sol.displacement(disc),
    );
    (0..disc.mesh().nnx())
        .map(|i| ku[2 * disc.mesh().node(i, 0) + 1])
        .sum()
}

/// The cache directory of the tests' riplab runs (never the user's own).
pub fn test_cache() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("xdg-cache")
}

/// The paper's lab at `level`, solved synchronously, with `scene` shown, timings hidden.
pub fn settled(level: u32, scene: riplab::tui::app::Scene) -> riplab::tui::app::App {
    use riplab::tui::engine::Engine;
    use riplab::tui::settle::settle;
    let mut app = riplab::tui::app::App::new(Scenario::paper());
    app.show_timing = false;
    app.settings.level = level;
    app.scene = scene;
    settle(&mut app, &mut Engine::new(Scenario::paper()));
    app
}

/// A scratch file holding `text` under the test target's temporary directory.
pub fn scratch_file(name: &str, text: &str) -> std::path::PathBuf {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Whatever a command failed with, it did not panic.
pub fn no_panic(stderr: &str) {
    assert!(!stderr.contains("panicked"), "panicked: {stderr}");
}
