//! `--refine-edges Nz` and `[mesh] refine_edges = "Nz"`: grading over the contact
//! zone. Bad values name the flag or the key and what is allowed, exit 2; a zone-graded solve
//! and a study's zone series report `refine_edges` (passes made), `grading` (the value asked)
//! and the smallest cell in JSON, CSV and the table (`1+2z`); `render` (the lab) draws it.

use crate::common::{no_panic, paper_text, riplab, scratch_file};

/// The text of what a refusal must name.
const ALLOWED: &str =
    "0 to 8, or auto (passes at the contact edges), or 1z to 8z (passes over the contact zone)";

/// `9z`, `z`, `-1z` and a study's `0,9z` name the flag and the range; a scenario's
/// `refine_edges = "9z"` names the file, line and key.
#[test]
fn bad_zone_gradings_exit_2_naming_what_is_allowed() {
    for args in [
        &["solve", "--refine-edges", "9z"][..],
        &["solve", "--refine-edges", "z"],
        &["solve", "--refine-edges", "-1z"],
        &["infsup", "--refine-edges", "2zz"],
        &["study", "--levels", "0..1", "--refine-edges", "0,9z"],
    ] {
        let (code, stdout, stderr) = riplab(args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stdout.is_empty());
        no_panic(&stderr);
        assert!(
            stderr.contains("--refine-edges") && stderr.contains(ALLOWED),
            "{args:?}: {stderr}"
        );
    }
    let text = paper_text(&[("level = 0", "level = 0\nrefine_edges = \"9z\"")]);
    let path = scratch_file("refine-nine-zones.toml", &text);
    let (code, stdout, stderr) = riplab(&["solve", path.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stdout.is_empty());
    for f in ["refine-nine-zones.toml:", "`mesh.refine_edges`", "`9z`", ALLOWED] {
        assert!(stderr.contains(f), "lacks {f:?}: {stderr}");
    }
}

/// A zone-graded solve's JSON carries its passes, the grading asked and its smallest cell (the
/// key and the flag alike), its table says `level 1+2z` (h the largest cell side: 0.25, every
/// cell within eight sides of the zone or of Γ_C being halved), a sweep's CSV has the `grading`
/// column; Γ_C's vertices are uniform across the contact zone (p̄ > 0) at the smallest side.
#[test]
fn a_zone_graded_solve_reports_its_grading() {
    let json = |args: &[&str]| -> serde_json::Value {
        let (code, stdout, stderr) = riplab(args);
        assert_eq!(code, 0, "{stderr}");
        serde_json::from_str(&stdout).unwrap()
    };
    let graded = json(&["solve", "-l", "1", "--refine-edges", "2z", "-f", "json"]);
    assert_eq!(
        (&graded["refine_edges"], &graded["grading"], &graded["h_min"]),
        (&2.into(), &"2z".into(), &0.125.into())
    );
    let x: Vec<f64> = serde_json::from_value(graded["nodes"]["x"].clone()).unwrap();
    let pbar: Vec<f64> = serde_json::from_value(graded["nodes"]["pbar"].clone()).unwrap();
    let pressed = pbar.iter().rposition(|&p| p > 0.0).unwrap();
    assert!(pressed > 4, "{pbar:?}");
    assert!(
        x[..=pressed + 1].windows(2).all(|w| w[1] - w[0] == 0.125),
        "{x:?}"
    );
    let edges = json(&["solve", "-l", "1", "--refine-edges", "2", "-f", "json"]);
    assert_eq!(edges["grading"], "2");
    assert_ne!(edges["nodes"], graded["nodes"]);

    let text = paper_text(&[("level = 0", "level = 1\nrefine_edges = \"2z\"")]);
    let path = scratch_file("refine-two-zones.toml", &text);
    let from_file = json(&["solve", path.to_str().unwrap(), "-f", "json"]);
    assert_eq!(
        (&from_file["grading"], &from_file["nodes"]),
        (&graded["grading"], &graded["nodes"])
    );

    let (code, table, _) = riplab(&["solve", "-l", "1", "--refine-edges", "2z"]);
    assert_eq!(code, 0);
    assert!(table.contains("level 1+2z (h = 0.25, h_min = 0.125)"), "{table}");

    let args = [
        "solve",
        "-l",
        "1",
        "--refine-edges",
        "1z",
        "--depth",
        "0.6,0.8",
        "-f",
        "csv",
    ];
    let (code, csv, stderr) = riplab(&args);
    assert_eq!(code, 0, "{stderr}");
    let lines: Vec<&str> = csv.lines().collect();
    let header: Vec<&str> = lines[0].split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for row in &lines[1..] {
        let cells: Vec<&str> = row.split(',').collect();
        let (passes, grading, h_min) = (
            cells[col("refine_edges")],
            cells[col("grading")],
            cells[col("h_min")],
        );
        assert_eq!((passes, grading, h_min), ("1", "1z", "0.25"), "{row}");
    }
}

/// `study --refine-edges 0,1z`: the zone series' rows say `1+1z` in the table and `grading`
/// `1z` in JSON and CSV, its fit is named `1z` and taken against n^(−1/2).
#[test]
fn a_study_sweeps_zone_gradings() {
    let args = [
        "study",
        "--levels",
        "0..1",
        "--schemes",
        "M1",
        "--refine-edges",
        "0,1z",
        "--no-cache",
    ];
    let (code, stdout, stderr) = riplab(&[&args[..], &["--format", "json"]].concat());
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let rows = v["rows"].as_array().unwrap();
    let gradings: Vec<(&str, u64)> = rows
        .iter()
        .map(|r| {
            (
                r["grading"].as_str().unwrap(),
                r["refine_edges"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(gradings, [("0", 0), ("0", 0), ("1z", 1), ("1z", 1)]);
    let fits = v["fits"].as_array().unwrap();
    assert_eq!(
        (fits[1]["abscissa"].as_str(), fits[1]["refine_edges"].as_str()),
        (Some("n^-1/2"), Some("1z"))
    );
    let (code, table, _) = riplab(&args);
    assert_eq!(code, 0);
    assert!(table.contains("M1              1+1z "), "{table}");
    let (code, csv, _) = riplab(&[&args[..], &["--format", "csv"]].concat());
    assert_eq!(code, 0);
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == "grading").unwrap();
    let zone_rows = csv
        .lines()
        .filter(|l| l.starts_with("row,") && l.split(',').nth(col) == Some("1z"));
    assert_eq!(zone_rows.count(), 2, "{csv}");
}

/// The lab grades over the zone too: `render --refine-edges 3z` and a scenario whose
/// `refine_edges` is `"3z"` draw the zone-graded solve (the header says `level 1+3z`, the
/// graded mesh's unknowns, more than the level's); `render --refine-edges 9z` names the flag
/// and the range, exit 2.
#[test]
fn render_draws_a_zone_graded_solve() {
    let text = paper_text(&[("level = 0", "level = 1\nrefine_edges = \"3z\"")]);
    let path = scratch_file("lab-three-zones.toml", &text);
    let (code, uniform, stderr) = riplab(&["render", "-l", "1", "--size", "80x24"]);
    assert_eq!(code, 0, "{stderr}");
    let dofs = |frame: &str| -> usize {
        let at = frame.find(" el ").expect("the counts");
        let n = frame[at + 4..].split(' ').next().unwrap();
        n.parse().unwrap()
    };
    let mut frames = Vec::new();
    for args in [
        &["render", "-l", "1", "--size", "80x24", "--refine-edges", "3z"][..],
        &["render", path.to_str().unwrap(), "--size", "80x24"],
    ] {
        let (code, frame, stderr) = riplab(args);
        assert_eq!(code, 0, "{args:?}: {stderr}");
        no_panic(&stderr);
        assert!(frame.contains("level 1+3z"), "{args:?}\n{frame}");
        assert!(dofs(&frame) > dofs(&uniform), "{frame}\n{uniform}");
        frames.push(frame);
    }
    assert_eq!(frames[0], frames[1], "the flag and the key alike");
    let (code, stdout, stderr) = riplab(&["render", "--size", "80x24", "--refine-edges", "9z"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stdout.is_empty());
    assert!(
        stderr.contains("--refine-edges") && stderr.contains(ALLOWED),
        "{stderr}"
    );
}

/// `infsup --refine-edges 2z`: two levels whose zone-graded meshes have the same widest cell
/// (0.25 at levels 0 and 1) get no slope, never an infinite one (it printed `-inf`); every
/// number in the JSON is finite, and the note says what h is.
#[test]
fn infsup_over_the_zone_reports_no_infinite_slope() {
    let args = ["infsup", "--levels", "0..1", "--refine-edges", "2z"];
    let (code, table, stderr) = riplab(&args);
    assert_eq!(code, 0, "{stderr}");
    assert!(!table.contains("inf") && !table.contains("NaN"), "{table}");
    assert!(
        stderr.contains("graded over the contact zone") && stderr.contains("graded mesh's widest cell"),
        "{stderr}"
    );
    let (code, json, _) = riplab(&[&args[..], &["--format", "json"]].concat());
    assert_eq!(code, 0);
    let rows: Vec<serde_json::Value> = serde_json::from_str(&json).unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!((&rows[0]["h"], &rows[1]["h"]), (&0.25.into(), &0.25.into()));
    assert!(rows[1]["slope"].is_null(), "{}", rows[1]);
    for r in &rows {
        assert!(
            r["beta"].as_f64().is_some_and(|b| b.is_finite() && b > 0.0),
            "{r}"
        );
    }
}

/// Friction with a zone grading is refused as with an edge grading, naming both: `solve` and
/// `study` on the full model with Coulomb friction, exit 2.
#[test]
fn friction_with_a_zone_grading_is_refused() {
    let friction = [
        "scenarios/hertz-paper-full.toml",
        "--friction",
        "coulomb",
        "--mu",
        "0.3",
    ];
    for args in [
        [&["solve", "-l", "1", "--refine-edges", "2z"][..], &friction].concat(),
        [
            &["study", "--levels", "0..1", "--refine-edges", "0,1z"][..],
            &friction,
        ]
        .concat(),
    ] {
        let (code, stdout, stderr) = riplab(&args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stdout.is_empty());
        no_panic(&stderr);
        let named = "--refine-edges: grading (at the edges or over the zone) is not available with friction";
        assert!(stderr.contains(named), "{args:?}: {stderr}");
    }
}
