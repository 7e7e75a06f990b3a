//! `riplab study` with friction: the friction options and `[friction]` reach every
//! row and the reference; the JSON, CSV and table carry t̄'s and Q's errors; the cache keeps a
//! frictionless reference and a friction one apart; a refused row is reported in its row
//! (exit 1); a list of shift steps and edge grading are refused (exit 2).

use std::path::{Path, PathBuf};
use std::process::Command;

/// `riplab study` of `hertz-paper-full` at levels 0..1 with M3 and the given options, its
/// cache under `cache`: exit code, stdout, stderr.
fn study(cache: &Path, options: &[&str]) -> (i32, String, String) {
    let scenario = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-paper-full.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_riplab"))
        .args([
            "study",
            scenario,
            "--schemes",
            "M3",
            "--reference-refinements",
            "0",
        ])
        .args(options)
        .env("XDG_CACHE_HOME", cache)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn fresh_cache(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("study-friction-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

const COULOMB: &[&str] = &["--friction", "coulomb", "--mu", "0.3", "--shift", "0.05"];

fn json(options: &[&str], cache: &Path) -> serde_json::Value {
    let mut all = vec!["--levels", "0..1", "--epsilon", "1e-6", "-f", "json"];
    all.extend(options);
    let (code, stdout, stderr) = study(cache, &all);
    assert_eq!(code, 0, "{stderr}");
    serde_json::from_str(&stdout).unwrap()
}

/// A study with friction (once refused) reports t̄'s and Q's errors in every row
/// and the friction it solved with; the cache serves each reference only to its own kind.
#[test]
fn a_friction_study_reports_tbar_and_keeps_its_reference_apart() {
    let cache = fresh_cache("apart");
    let with = json(COULOMB, &cache);
    assert_eq!(with["reference"]["source"], "computed");
    assert_eq!(with["friction"]["law"], "coulomb");
    assert_eq!(with["friction"]["mu"], 0.3);
    let q = with["reference"]["tangential_load"].as_f64().unwrap();
    assert!(q > 0.0 && q < 0.3 * with["reference"]["load"].as_f64().unwrap());
    let rows = with["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    for row in rows {
        assert_eq!(row["status"], "ok");
        assert!(row["errors"]["tbar"].as_f64().unwrap() > 0.0, "{row}");
        assert!(row["errors"]["tangential_load"].as_f64().unwrap() > 0.0, "{row}");
    }
    // The frictionless study in the same cache solves its own reference, with no t̄ at all.
    let plain = json(&[], &cache);
    assert_eq!(plain["reference"]["source"], "computed");
    assert!(plain.get("friction").is_none());
    assert!(plain["reference"].get("tangential_load").is_none());
    assert!(plain["rows"][0]["errors"].get("tbar").is_none());
    // Each is then read back for its own kind, with the same numbers.
    let again = json(COULOMB, &cache);
    assert_eq!(again["reference"]["source"], "cache");
    let errors = |v: &serde_json::Value| -> Vec<serde_json::Value> {
        v["rows"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r["errors"].clone())
            .collect()
    };
    assert_eq!(errors(&again), errors(&with));
    assert_eq!(json(&[], &cache)["reference"]["source"], "cache");
    // Another μ is another reference.
    let other = json(
        &["--friction", "coulomb", "--mu", "0.6", "--shift", "0.05"],
        &cache,
    );
    assert_eq!(other["reference"]["source"], "computed");
    let _ = std::fs::remove_dir_all(&cache);
}

/// The CSV has the t̄ and Q columns, filled with friction; the table a t̄ and a Q column.
#[test]
fn csv_and_table_carry_the_tangential_errors() {
    let cache = fresh_cache("csv");
    let mut options = vec!["--levels", "0..1", "--epsilon", "1e-6", "-f", "csv"];
    options.extend(COULOMB);
    let (code, stdout, stderr) = study(&cache, &options);
    assert_eq!(code, 0, "{stderr}");
    let mut lines = stdout.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (tbar, rate) = (column("err_tbar"), column("rate_tbar"));
    let rows: Vec<Vec<&str>> = lines
        .map(|l| l.split(',').collect())
        .filter(|r: &Vec<&str>| r[0] == "row")
        .collect();
    assert_eq!(rows.len(), 2);
    assert!(rows.iter().all(|r| r[tbar].parse::<f64>().unwrap() > 0.0));
    assert!(rows[1][rate].parse::<f64>().is_ok());
    let (code, table, stderr) = study(
        &cache,
        &[&["--levels", "0..1", "--epsilon", "1e-6"], COULOMB].concat(),
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(table.contains("coulomb μ = 0.3"), "{table}");
    assert!(
        table
            .lines()
            .any(|l| l.starts_with("scheme") && l.contains("t̄") && l.contains(" Q ")),
        "{table}"
    );
    let _ = std::fs::remove_dir_all(&cache);
}

/// An ε sweep with ε_t: the ε = 0 row (exact, which takes no ε_t) is refused in its row and
/// the penalty row stands; exit 1.
#[test]
fn a_refused_friction_row_is_reported_per_row() {
    let cache = fresh_cache("refused");
    let mut options = vec![
        "--level",
        "1",
        "--sweep-epsilon",
        "0,1e-6",
        "--epsilon-t",
        "1e-6",
        "-f",
        "json",
    ];
    options.extend(COULOMB);
    let (code, stdout, stderr) = study(&cache, &options);
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("1 of 2 rows"), "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows[0]["status"], "failed");
    assert!(
        rows[0]["reason"].as_str().unwrap().contains("exact takes none"),
        "{}",
        rows[0]
    );
    assert_eq!(rows[1]["status"], "ok");
    assert!(rows[1]["errors"]["tbar"].as_f64().unwrap() > 0.0);
    let _ = std::fs::remove_dir_all(&cache);
}

/// A list of shift steps, edge grading, and friction on a half model are usage errors.
#[test]
fn friction_options_a_study_cannot_take_are_refused() {
    let cache = fresh_cache("usage");
    let cases: &[(&[&str], &str)] = &[
        (&["--shift-steps", "1,4"], "--shift-steps"),
        (&["--refine-edges", "0,1"], "--refine-edges"),
        (&["--mu", "-1"], "--mu"),
    ];
    for (extra, flag) in cases {
        let (code, stdout, stderr) = study(&cache, &[&["--levels", "0"], COULOMB, extra].concat());
        assert_eq!(code, 2, "{extra:?}: {stderr}");
        assert!(stdout.is_empty());
        assert!(stderr.contains(flag), "{extra:?}: {stderr}");
    }
    let half = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-paper.toml");
    let (code, _, stderr) = crate::common::riplab(&[
        "study",
        half,
        "--levels",
        "0",
        "--friction",
        "coulomb",
        "--mu",
        "0.3",
    ]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("full model"), "{stderr}");
}
