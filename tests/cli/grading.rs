//! `--refine-edges` and `[mesh] refine_edges`: bad values are refused naming the
//! key (file, line) and the allowed range, exit 2; a graded solve reports its passes and its
//! smallest cell in JSON, CSV and the table.

use crate::common::{no_panic, paper_text, riplab, scratch_file};

/// A bad `[mesh] refine_edges` names the file, line, key and what is allowed; a bad flag names
/// the flag.
#[test]
fn bad_refine_edges_exit_2_naming_the_key_and_the_range() {
    for (name, value, fragments) in [
        (
            "refine-nine.toml",
            "refine_edges = 9",
            &["`mesh.refine_edges`", "`9`", "0 to 8, or auto"][..],
        ),
        (
            "refine-text.toml",
            "refine_edges = \"most\"",
            &["`mesh.refine_edges`", "`most`", "0 to 8, or auto"],
        ),
        (
            "refine-float.toml",
            "refine_edges = 1.5",
            &["refine_edges", "a number of passes 0 to 8"],
        ),
    ] {
        let text = paper_text(&[("level = 0", &format!("level = 0\n{value}"))]);
        let path = scratch_file(name, &text);
        let (code, stdout, stderr) = riplab(&["solve", path.to_str().unwrap()]);
        assert_eq!(code, 2, "{name}: {stderr}");
        assert!(stdout.is_empty());
        no_panic(&stderr);
        assert!(stderr.contains(&format!("{name}:")), "{name}: {stderr}");
        for f in fragments {
            assert!(stderr.contains(f), "{name}: lacks {f:?}: {stderr}");
        }
    }
    for args in [
        &["solve", "--refine-edges", "-1"][..],
        &["solve", "--refine-edges", "nine"],
        &["study", "--levels", "0..1", "--refine-edges", "0,9"],
    ] {
        let (code, stdout, stderr) = riplab(args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stdout.is_empty());
        no_panic(&stderr);
        assert!(
            stderr.contains("--refine-edges") && stderr.contains("0 to 8, or auto"),
            "{stderr}"
        );
    }
}

/// A graded solve's JSON carries its passes and smallest cell (the scenario's key and the flag
/// alike; the flag wins), its table header says `level 1+2e`, and a sweep's CSV has both
/// columns; the uniform level reports 0 passes and h_min = h.
#[test]
fn a_graded_solve_reports_its_passes_and_smallest_cell() {
    let json = |args: &[&str]| -> serde_json::Value {
        let (code, stdout, stderr) = riplab(args);
        assert_eq!(code, 0, "{stderr}");
        serde_json::from_str(&stdout).unwrap()
    };
    let uniform = json(&["solve", "-l", "1", "-f", "json"]);
    assert_eq!(uniform["refine_edges"], 0);
    assert_eq!(uniform["h_min"], uniform["h"]);
    let graded = json(&["solve", "-l", "1", "--refine-edges", "2", "-f", "json"]);
    assert_eq!(graded["refine_edges"], 2);
    assert_eq!(graded["h_min"], 0.125);
    assert!(graded["n_dofs"].as_u64() > uniform["n_dofs"].as_u64());
    let text = paper_text(&[("level = 0", "level = 1\nrefine_edges = 2")]);
    let path = scratch_file("refine-two.toml", &text);
    let from_file = json(&["solve", path.to_str().unwrap(), "-f", "json"]);
    assert_eq!(from_file["refine_edges"], 2);
    assert_eq!(from_file["nodes"], graded["nodes"]);
    let overridden = json(&[
        "solve",
        path.to_str().unwrap(),
        "--refine-edges",
        "0",
        "-f",
        "json",
    ]);
    assert_eq!(overridden["refine_edges"], 0);

    let (code, table, _) = riplab(&["solve", "-l", "1", "--refine-edges", "2"]);
    assert_eq!(code, 0);
    assert!(table.contains("level 1+2e (h = 0.5, h_min = 0.125)"), "{table}");

    let (code, csv, stderr) = riplab(&[
        "solve",
        "-l",
        "1",
        "--refine-edges",
        "1",
        "--depth",
        "0.6,0.8",
        "-f",
        "csv",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let lines: Vec<&str> = csv.lines().collect();
    let header: Vec<&str> = lines[0].split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for row in &lines[1..] {
        let cells: Vec<&str> = row.split(',').collect();
        assert_eq!(cells[col("refine_edges")], "1", "{row}");
        assert_eq!(cells[col("h_min")], "0.25", "{row}");
    }
}

/// `study --refine-edges 0,1` gives a graded series beside the uniform one: its rows name
/// their passes and smallest cell, its fit is against n^(−1/2), the table shows `1+1e`, and
/// the CSV has both columns.
#[test]
fn a_study_sweeps_the_grading_as_an_axis() {
    let args = [
        "study",
        "--levels",
        "0..1",
        "--schemes",
        "M1",
        "--refine-edges",
        "0,1",
        "--no-cache",
    ];
    let (code, stdout, stderr) = riplab(&[&args[..], &["--format", "json"]].concat());
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let rows = v["rows"].as_array().unwrap();
    let passes: Vec<u64> = rows.iter().map(|r| r["refine_edges"].as_u64().unwrap()).collect();
    assert_eq!(passes, [0, 0, 1, 1]);
    for r in &rows[2..] {
        assert!(r["h_min"].as_f64() < r["h"].as_f64(), "{r}");
        assert!(r["n_dofs"].as_u64() > rows[0]["n_dofs"].as_u64());
    }
    let fits = v["fits"].as_array().unwrap();
    assert_eq!(fits.len(), 2);
    assert_eq!(
        (fits[0]["abscissa"].as_str(), fits[0]["refine_edges"].as_str()),
        (Some("h"), Some("0"))
    );
    assert_eq!(
        (fits[1]["abscissa"].as_str(), fits[1]["refine_edges"].as_str()),
        (Some("n^-1/2"), Some("1"))
    );
    let (code, table, _) = riplab(&args);
    assert_eq!(code, 0);
    assert!(table.contains("M1              1+1e "), "{table}");
    let (code, csv, _) = riplab(&[&args[..], &["--format", "csv"]].concat());
    assert_eq!(code, 0);
    let header = csv.lines().next().unwrap();
    assert!(
        header.contains(",refine_edges,") && header.contains(",h_min,"),
        "{header}"
    );
}
