//! The convergence study's machinery: errors of the reference against itself vanish, and
//! the observed behaviour matches Theorem 2 (26) and the paper's claim about p and p̄.

use crate::common::paper_with;
use riplab::contact::Rule;
use riplab::mesh::Element;
use riplab::study::{Reference, Status, convergence};

#[test]
fn errors_rates_and_the_smoothing_claim() {
    let scenario = paper_with(&[]);
    let reference = Reference::compute(&scenario, 4).unwrap();
    // The reference scheme at the reference level against itself: zero (checks evaluation and
    // integration on nested meshes).
    let itself = convergence(
        &scenario,
        &reference,
        &[(Element::Q2, Rule::Simpson)],
        &[4],
        None,
        0.0,
    );
    let e = itself[0].errors.unwrap();
    assert!(
        e.p < 1e-12 && e.pbar < 0.1 && e.u < 1e-12 && e.load < 1e-12,
        "{e:?}"
    );
    let rows = convergence(
        &scenario,
        &reference,
        &[(Element::Q1, Rule::Gauss1), (Element::Q1, Rule::Trapezoid)],
        &[1, 2, 3],
        None,
        1e-10,
    );
    for r in &rows {
        assert!(r.converged && r.status == Status::Ok, "{r:?}");
    }
    // H¹ error of Q1 at rate 1 (the h term of (26); ε is too small to matter).
    for r in rows.iter().filter(|r| r.level > 1) {
        let u_rate = r.rates.unwrap().u;
        assert!(
            (0.85..1.2).contains(&u_rate),
            "{} level {}: u rate {u_rate}",
            r.scheme,
            r.level
        );
    }
    // M1 on the finest level: the smoothed pressure is much closer to the truth than the raw one.
    let m1 = rows.iter().find(|r| r.scheme == "M1" && r.level == 3).unwrap();
    let e = m1.errors.unwrap();
    assert!(e.pbar < 0.6 * e.p, "M1: p̄ error {} vs p error {}", e.pbar, e.p);
}

/// The reference is kept in the cache directory: the second study reads it and reports the
/// same errors; a damaged entry is recomputed; `--no-cache` neither reads nor writes; two
/// studies at once both succeed (issue 13, item 5).
#[test]
fn the_reference_is_cached_between_runs() {
    use std::process::Command;
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("cache-test");
    let _ = std::fs::remove_dir_all(&dir);
    let run = |extra: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_riplab"))
            .args([
                "study",
                "--levels",
                "0..1",
                "--schemes",
                "M1,M3",
                "--format",
                "json",
            ])
            .args(extra)
            .env("XDG_CACHE_HOME", &dir)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(0));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let errors: Vec<serde_json::Value> = v["rows"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r["errors"].clone())
            .collect();
        (errors, String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (none, stderr) = run(&["--no-cache"]);
    assert!(stderr.contains("reference done") && !dir.exists(), "{stderr}");
    let (first, stderr) = run(&[]);
    assert!(stderr.contains("reference done"), "{stderr}");
    let (second, stderr) = run(&[]);
    assert!(stderr.contains("reference read from"), "{stderr}");
    assert_eq!(first, second);
    assert_eq!(first, none);
    // Damage the entry: it is recomputed (and replaced).
    let entry = std::fs::read_dir(dir.join("riplab"))
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    let mut bytes = std::fs::read(&entry).unwrap();
    let mid = bytes.len() / 2;
    bytes[mid] ^= 1;
    std::fs::write(&entry, &bytes).unwrap();
    let (third, stderr) = run(&[]);
    assert!(stderr.contains("reference done"), "{stderr}");
    assert_eq!(first, third);
    // Two runs at once on an empty cache.
    std::fs::remove_dir_all(&dir).unwrap();
    let spawn = || {
        Command::new(env!("CARGO_BIN_EXE_riplab"))
            .args(["study", "--levels", "0..1", "--schemes", "M1", "--format", "json"])
            .env("XDG_CACHE_HOME", &dir)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap()
    };
    let (a, b) = (spawn(), spawn());
    let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
    assert!(a.status.success() && b.status.success());
    assert!(!a.stdout.is_empty() && !b.stdout.is_empty());
    let (after, stderr) = run(&[]);
    assert!(stderr.contains("reference read from"), "{stderr}");
    assert_eq!(after[0], first[0]);
}
