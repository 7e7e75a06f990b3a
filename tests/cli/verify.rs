//! `riplab verify` as a user runs it (issue 32): its exit codes, `--case`, `--list`, and its
//! refusals of bad values.

use crate::common::riplab;

#[test]
fn verify_runs_a_case_and_lists_the_pack() {
    let (code, out, err) = riplab(&["verify", "--case", "patch"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("M4: max |p − p_exact|/p_exact") && out.contains("source: "),
        "{out}"
    );
    assert!(out.contains("8 of 8 checks OK"), "{out}");
    let (code, out, _) = riplab(&["verify", "--list", "--format", "csv"]);
    assert_eq!(code, 0);
    // A header and at least eight cases, each with its source.
    let rows: Vec<&str> = out.lines().skip(1).collect();
    assert!(rows.len() >= 8, "{out}");
    assert!(rows.iter().all(|r| r.split(',').count() >= 4), "{out}");
    let (code, out, _) = riplab(&["verify", "--case", "circle", "--format", "json"]);
    assert_eq!(code, 0);
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(json["passed"], true);
    assert_eq!(json["checks"][2]["right"], "OK");
}

#[test]
fn verify_refuses_bad_values() {
    let (code, _, err) = riplab(&["verify", "--case", "nope\u{1b}[2J"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("allowed: hertz, circle") && !err.contains('\u{1b}'),
        "{err}"
    );
    let (code, _, err) = riplab(&["verify", "--level", "9"]);
    assert_eq!(code, 2);
    assert!(err.contains("--level") && err.contains("2 to 5"), "{err}");
}
