//! What a study says of its own rows: the rows whose errors the penalty may account
//! for are marked in JSON and CSV, not only noted on stderr, and a fit of fewer than two rows
//! (no rates) has no line in the table.

use crate::common::riplab;

/// The paper's problem at ε = 1e-6 (κ = εE/h = 4e-3 at level 2, a load bound of 1.2e-3 against
/// M3's load error of 1.4e-3: dominated); with the exact constraint no row has a penalty.
#[test]
fn rows_dominated_by_the_penalty_are_marked_in_json_and_csv() {
    let (code, out, err) = riplab(&[
        "study",
        "--levels",
        "0..2",
        "--schemes",
        "M3",
        "--epsilon",
        "1e-6",
        "--format",
        "json",
    ]);
    assert_eq!(code, 0, "{err}");
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    let rows = json["rows"].as_array().expect("rows");
    let marked: Vec<u64> = rows
        .iter()
        .filter(|r| r["epsilon_dominated"] == serde_json::Value::Bool(true))
        .map(|r| r["level"].as_u64().unwrap())
        .collect();
    assert!(marked.contains(&2), "{marked:?}");
    assert!(err.contains("M3 level 2: the load's error"), "{err}");
    let (code, out, _) = riplab(&[
        "study",
        "--levels",
        "0..2",
        "--schemes",
        "M3",
        "--method",
        "exact",
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0);
    let mut lines = out.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = header
        .iter()
        .position(|&h| h == "epsilon_dominated")
        .expect("a CSV column");
    let values: Vec<&str> = lines
        .filter(|l| l.starts_with("row,"))
        .map(|l| l.split(',').nth(column).unwrap())
        .collect();
    assert_eq!(values, ["false"; 3]);
}

/// A study of one level fits one row: the JSON keeps the fit (rates null), the table drops its
/// line (it read "fit: least squares over 1 rows" with no rate).
#[test]
fn a_fit_of_one_row_has_no_table_line() {
    let args = [
        "study",
        "--levels",
        "3",
        "--schemes",
        "M4",
        "--reference-level",
        "4",
    ];
    let (code, out, err) = riplab(&args);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("M4                 3"), "{out}");
    assert!(!out.contains("fit:"), "{out}");
    let (code, out, _) = riplab(&[&args[..], &["--format", "json"]].concat());
    assert_eq!(code, 0);
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(json["fits"][0]["rows"], 1);
}
