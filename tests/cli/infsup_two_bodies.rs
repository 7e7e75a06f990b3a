//! `riplab infsup` on a two-body scenario (docs/design.md §12, "The inf-sup constant across
//! the interface"): every multiplier space at every level with finite numbers, the slope its
//! rows print against the log-ratio of their β_h, the three formats, and the bad input.

use crate::common::{no_panic, riplab, riplab_under_half_of};

const PATCH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/patch-two-blocks.toml");
const HERTZ: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-two-bodies.toml");

/// The rows of `riplab infsup ARGS --format json`, which must exit 0.
fn rows(args: &[&str]) -> Vec<serde_json::Value> {
    let mut all = vec!["infsup", "--format", "json"];
    all.extend_from_slice(args);
    let (code, out, err) = riplab(&all);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str::<serde_json::Value>(&out)
        .unwrap()
        .as_array()
        .unwrap()
        .clone()
}

fn num(row: &serde_json::Value, key: &str) -> f64 {
    row[key].as_f64().unwrap_or_else(|| panic!("{key} in {row}"))
}

/// Every space of `spaces` has one row per level of `levels`, in that order, with finite
/// h, β_h ≥ 0 and β_h/√h.
fn check_spaces(rows: &[serde_json::Value], spaces: &[&str], levels: &[u64]) {
    let got: Vec<(String, u64)> = rows
        .iter()
        .map(|r| {
            (
                r["space"].as_str().unwrap().to_string(),
                r["level"].as_u64().unwrap(),
            )
        })
        .collect();
    let want: Vec<(String, u64)> = spaces
        .iter()
        .flat_map(|s| levels.iter().map(move |&l| (s.to_string(), l)))
        .collect();
    assert_eq!(got, want);
    for r in rows {
        for key in ["h", "h_master", "beta", "beta_over_sqrt_h"] {
            assert!(num(r, key).is_finite() && num(r, key) >= 0.0, "{key}: {r}");
        }
        assert_eq!(r["kernel"].is_null(), num(r, "beta") > 0.0, "{r}");
    }
}

/// The patch scenario (2:3) at levels 0–3: mortar's, mortar-dual's, NTS's, gauss1's points
/// and p̄'s rows; each slope is ln(β_h/β_h')/ln(h/h') of its row and the one before, computed
/// here from the printed β_h and h; the stable spaces' slopes are near ½ at level 3 (β_h ∝ √h).
#[test]
fn infsup_on_the_patch_scenario() {
    let rows = rows(&[PATCH, "--levels", "0..3"]);
    let spaces = ["mortar", "mortar-dual", "nts", "rip-gauss1", "rip-gauss1-pbar"];
    check_spaces(&rows, &spaces, &[0, 1, 2, 3]);
    for pair in rows.windows(2) {
        let (prev, row) = (&pair[0], &pair[1]);
        if prev["space"] != row["space"] {
            assert!(row["slope"].is_null(), "{row}");
            continue;
        }
        let log_ratio = (num(row, "beta") / num(prev, "beta")).ln() / (num(row, "h") / num(prev, "h")).ln();
        let slope = num(row, "slope");
        assert!(
            (slope - log_ratio).abs() <= 1e-12,
            "{slope} against {log_ratio}: {row}"
        );
        if row["level"] == 3 {
            assert!((slope - 0.5).abs() < 0.05, "{row}");
        }
    }
    assert!(rows[0]["slope"].is_null());
    // The upper body is the slave, two of its edges for three of the lower's (6 at level 0).
    assert_eq!(num(&rows[0], "h") / num(&rows[0], "h_master"), 1.5);
    assert_eq!(rows[0]["rule"], serde_json::Value::Null);
    assert_eq!(rows[3 * 4]["rule"], "gauss1");
}

/// The Hertz scenario (3:2, the trapezoid) answers too; `--all` lists every rule's spaces.
#[test]
fn infsup_on_hertz_and_every_rule() {
    let rows = rows(&[HERTZ, "--levels", "0..1"]);
    let spaces = [
        "mortar",
        "mortar-dual",
        "nts",
        "rip-trapezoid",
        "rip-trapezoid-pbar",
    ];
    check_spaces(&rows, &spaces, &[0, 1]);
    let all = self::rows(&[PATCH, "--levels", "0..1", "--all"]);
    let mut spaces = vec!["mortar".to_string(), "mortar-dual".into(), "nts".into()];
    for rule in ["gauss1", "gauss2", "trapezoid", "simpson"] {
        spaces.extend([format!("rip-{rule}"), format!("rip-{rule}-pbar")]);
    }
    let spaces: Vec<&str> = spaces.iter().map(String::as_str).collect();
    check_spaces(&all, &spaces, &[0, 1]);
}

/// The table names every space and the slope; the CSV has the JSON's fields, one line a row.
#[test]
fn infsup_two_bodies_table_and_csv() {
    let (code, out, err) = riplab(&["infsup", PATCH, "--levels", "0..1", "--rule", "simpson"]);
    assert_eq!(code, 0, "{err}");
    for word in [
        "mortar-dual",
        "nts",
        "rip-simpson-pbar",
        "β_h/√h",
        "slope",
        "h_master",
    ] {
        assert!(out.contains(word), "{word}: {out}");
    }
    let (code, out, err) = riplab(&["infsup", PATCH, "--levels", "0..1", "--format", "csv"]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(
        lines[0],
        "level,h,h_master,element,rule,space,multipliers,beta,beta_over_sqrt_h,slope,kernel"
    );
    assert_eq!(lines.len(), 1 + 5 * 2);
    let json = rows(&[PATCH, "--levels", "0..1"]);
    for (line, row) in lines[1..].iter().zip(&json) {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells[5], row["space"].as_str().unwrap());
        // serde_json's reading may round the last bit differently from str::parse.
        let (csv, json) = (cells[7].parse::<f64>().unwrap(), num(row, "beta"));
        assert!((csv - json).abs() <= 4.0 * f64::EPSILON * json, "{csv} {json}");
    }
}

/// Bad input exits 2 and says what: a range that runs down, a level out of range, grading.
#[test]
fn infsup_two_bodies_bad_input() {
    for (args, said) in [
        (&["--levels", "3..1"][..], "--levels"),
        (&["--levels", "0..9"][..], "--levels"),
        (&["--refine-edges", "1"][..], "--refine-edges"),
    ] {
        let mut all = vec!["infsup", PATCH];
        all.extend_from_slice(args);
        let (code, out, err) = riplab(&all);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty() && err.contains(said), "{args:?}: {err}");
    }
}

/// A level whose two bodies do not fit is refused before anything is built (exit 2, the
/// memory named), under an address-space limit of half riplab's own estimate of the upper
/// body's discretisation alone, with the levels before it asked too: nothing is printed.
#[test]
fn infsup_two_bodies_refused_before_it_runs_out_of_memory() {
    let scenario = riplab::scenario::Scenario::load(std::path::Path::new(HERTZ)).unwrap();
    let sizes = scenario.upper_sizes(5, scenario.element).unwrap();
    let (code, out, err) = riplab_under_half_of(&sizes, &["infsup", HERTZ, "--levels", "0..5"]);
    no_panic(&err);
    assert_eq!(code, 2, "{err}");
    assert!(out.is_empty(), "{out}");
    assert!(
        err.contains("across the interface at level") && err.contains("choose a coarser level"),
        "{err}"
    );
}
