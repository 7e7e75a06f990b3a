//! Helpers shared by the integration tests: [`shared`]'s, and those that run the binary or
//! write under the integration tests' temporary directory.
#![allow(dead_code)]

#[macro_use]
mod shared;
pub use shared::*;

use riplab::scenario::Scenario;

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
    sol: &riplab::contact::solution::Solution,
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
/// A scratch file holding `text` under the test target's temporary directory.
pub fn scratch_file(name: &str, text: &str) -> std::path::PathBuf {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::write(&path, text).unwrap();
    path
}
/// Run riplab ARGS under an address-space limit (`ulimit -v`, the child's alone) of half the
/// peak riplab's own estimate gives a discretisation of `sizes` (`Sizes::peak_bytes`): its
/// memory guard refuses that discretisation before allocating anything, saying so, so any
/// other refusal seen under this limit was made before it was assembled. (Pass the sizes of
/// a level of hundreds of MiB or more: half of that is far more than riplab's start takes.)
/// Exit code, stdout and stderr.
pub fn riplab_under_half_of(sizes: &riplab::fem::memory::Sizes, args: &[&str]) -> (i32, String, String) {
    riplab_under(sizes.peak_bytes() / 2, args)
}
/// Run riplab ARGS under an address-space limit of `bytes` (`ulimit -v`, the child's alone;
/// derive it from riplab's own estimate, never a fixed number). Exit code, stdout and stderr.
pub fn riplab_under(bytes: u64, args: &[&str]) -> (i32, String, String) {
    let kib = bytes / 1024;
    let out = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {kib} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_riplab"))
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
