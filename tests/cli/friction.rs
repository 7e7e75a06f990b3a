//! Friction on the command line: bad `[friction]` tables and flags exit 2 naming
//! the file, line and key (or the flag) and the range; a friction solve's JSON carries the
//! `friction`, `mindlin`, `nodes.ux/tbar` and `points.t/state` fields.

use crate::common::riplab;

/// (file, expected fragments of the message)
const CASES: &[(&str, &[&str])] = &[
    (
        "friction-negative-mu.toml",
        &[":36:6", "`friction.mu`", "-0.3 is out of range", "finite μ ≥ 0"],
    ),
    (
        "friction-nan-mu.toml",
        &[":36:6", "`friction.mu`", "NaN is out of range", "finite μ ≥ 0"],
    ),
    (
        "friction-half.toml",
        &[":39:7", "`friction.law`", "body.model = \"full\""],
    ),
    (
        "friction-shift-beyond.toml",
        &[":37:9", "`friction.shift`", "beyond the body", "(-8, 8)"],
    ),
    (
        "friction-mu-with-tresca.toml",
        &[":37:6", "`friction.mu`", "does not apply to law tresca"],
    ),
    ("friction-steps.toml", &[":37:9", "`friction.steps`", "1 to 1000"]),
];

#[test]
fn bad_friction_tables_exit_2_with_a_located_message() {
    for (file, fragments) in CASES {
        let path = format!("{}/tests/bad/{file}", env!("CARGO_MANIFEST_DIR"));
        let (code, stdout, stderr) = riplab(&["solve", &path]);
        assert_eq!(code, 2, "{file}: exit code {code}, stderr: {stderr}");
        assert!(stdout.is_empty(), "{file}: printed a result");
        assert!(!stderr.contains("panicked"), "{file}: {stderr}");
        for f in *fragments {
            assert!(stderr.contains(f), "{file}: message lacks {f:?}:\n{stderr}");
        }
    }
}

#[test]
fn bad_friction_flags_exit_2() {
    let full = format!("{}/scenarios/hertz-paper-full.toml", env!("CARGO_MANIFEST_DIR"));
    let full = full.as_str();
    for (args, fragments) in [
        (
            &["solve", full, "--friction", "coulomb", "--mu", "-1"][..],
            &["--mu", "finite μ ≥ 0"][..],
        ),
        (
            &["solve", full, "--friction", "coulomb", "--mu", "nan"][..],
            &["--mu", "NaN"][..],
        ),
        (
            &["solve", "--friction", "coulomb", "--mu", "0.3"][..],
            &["--friction", "body.model = \"half\""][..],
        ),
        (
            &[
                "solve",
                full,
                "--friction",
                "coulomb",
                "--mu",
                "0.3",
                "--shift",
                "100",
            ][..],
            &["--shift", "beyond the body"][..],
        ),
        (
            &["solve", full, "--mu", "0.3"][..],
            &["--mu", "--friction coulomb"][..],
        ),
        (
            &["solve", full, "--shift", "0.1"][..],
            &["--shift", "with friction only"][..],
        ),
        (
            &[
                "solve",
                full,
                "--friction",
                "tresca",
                "--mu",
                "0.3",
                "--threshold",
                "1",
            ][..],
            &["--mu", "does not apply"][..],
        ),
        (
            &[
                "solve",
                full,
                "--friction",
                "coulomb",
                "--mu",
                "0.3",
                "--shift-steps",
                "0",
            ][..],
            &["--shift-steps", "1 to 1000"][..],
        ),
        (
            &["solve", full, "--friction", "stiction"][..],
            &["--friction", "none, coulomb, tresca"][..],
        ),
    ] {
        let (code, stdout, stderr) = riplab(args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stdout.is_empty(), "{args:?}");
        for f in fragments {
            assert!(stderr.contains(f), "{args:?}: lacks {f:?}: {stderr}");
        }
    }
}

/// The JSON of a friction solve: the law and its loading, Q, the states, t and t̄, and
/// Cattaneo–Mindlin's block; Q equals the sum of the points' t weighted as P sums p (checked
/// here from the printed numbers: Q/(μP) as printed).
#[test]
fn friction_json_fields() {
    let path = format!("{}/scenarios/cattaneo-mindlin.toml", env!("CARGO_MANIFEST_DIR"));
    let (code, stdout, stderr) = riplab(&["solve", &path, "--level", "1", "--format", "json"]);
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let f = &v["friction"];
    assert_eq!(f["law"], "coulomb");
    assert_eq!(
        (f["mu"].as_f64(), f["shift"].as_f64(), f["steps"].as_u64()),
        (Some(0.3), Some(0.0815), Some(1))
    );
    let (q, p) = (
        f["tangential_load"].as_f64().unwrap(),
        v["load"].as_f64().unwrap(),
    );
    assert!((f["load_ratio"].as_f64().unwrap() - q / (0.3 * p)).abs() < 1e-12);
    let n = v["points"]["x"].as_array().unwrap().len();
    assert_eq!(v["points"]["t"].as_array().unwrap().len(), n);
    let states = v["points"]["state"].as_array().unwrap();
    assert_eq!(states.len(), n);
    let count = |s: &str| states.iter().filter(|x| *x == s).count() as u64;
    assert_eq!(f["stick"].as_u64(), Some(count("stick")));
    assert_eq!(f["slip"].as_u64(), Some(count("slip")));
    assert_eq!(f["open"].as_u64(), Some(count("open")));
    assert_eq!(f["step_iterations"].as_array().unwrap().len(), 2);
    let m = v["nodes"]["x"].as_array().unwrap().len();
    assert_eq!(v["nodes"]["ux"].as_array().unwrap().len(), m);
    assert_eq!(v["nodes"]["tbar"].as_array().unwrap().len(), m);
    let mindlin = &v["mindlin"];
    assert!(mindlin["c"].as_f64().unwrap() > 0.0);
    assert!(mindlin["relative_error"].as_f64().unwrap() < 0.2);
    // Without friction: law none, nulls.
    let (code, stdout, _) = riplab(&["solve", "--level", "0", "--format", "json"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["friction"]["law"], "none");
    assert!(v["nodes"]["ux"].is_null() && v["points"]["state"].is_null() && v["mindlin"].is_null());
}

/// `--shift-steps 1,4` sweeps the steps on one mesh: one row each, with its own history.
#[test]
fn a_shift_steps_sweep_gives_each_row_its_steps() {
    let path = format!("{}/scenarios/hertz-paper-full.toml", env!("CARGO_MANIFEST_DIR"));
    let (code, stdout, stderr) = riplab(&[
        "solve",
        &path,
        "--friction",
        "coulomb",
        "--mu",
        "0.3",
        "--shift",
        "0.05",
        "--shift-steps",
        "1,4",
        "--format",
        "json",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let rows = v
        .as_array()
        .or_else(|| v["rows"].as_array())
        .expect("a sweep's rows");
    assert_eq!(rows.len(), 2);
    let steps: Vec<u64> = rows
        .iter()
        .map(|r| r["friction"]["steps"].as_u64().unwrap())
        .collect();
    assert_eq!(steps, [1, 4]);
}

/// Tiny and huge friction parameters are printed in scientific notation, not as hundreds of
/// digits (`μ = 1e-300` was written out as 0.000… to 300 places); the study's first line too.
#[test]
fn extreme_friction_parameters_print_short() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/cattaneo-mindlin.toml");
    for (args, said) in [
        (vec!["--mu", "1e-300"], "(μ = 1e-300), shift 0.0815"),
        (vec!["--shift", "1e-300"], "(μ = 0.3), shift 1e-300 in"),
        (
            vec!["--friction", "tresca", "--threshold", "1e300"],
            "(g = 1e300)",
        ),
    ] {
        let mut all = vec!["solve", file, "--level", "0"];
        all.extend(args);
        let (code, out, err) = crate::common::riplab(&all);
        assert_eq!(code, 0, "{all:?}: {err}");
        let line = out
            .lines()
            .find(|l| l.starts_with("friction "))
            .expect("the friction line");
        assert!(line.contains(said) && line.chars().count() < 200, "{line}");
    }
}

/// An obstacle lifted off the body presses nothing: Q/(μP) is undefined and absent (it was
/// printed as NaN in the table and null in JSON), Q = 0 and every point open.
#[test]
fn a_lifted_obstacle_has_no_load_ratio() {
    let args = [
        "solve",
        "scenarios/hertz-paper-full.toml",
        "-l",
        "1",
        "--scheme",
        "M3",
        "--friction",
        "coulomb",
        "--mu",
        "0.3",
        "--shift",
        "0.01",
        "--depth",
        "-0.1",
    ];
    let (code, out, err) = crate::common::riplab(&args);
    assert_eq!(code, 0, "{err}");
    let line = out
        .lines()
        .find(|l| l.starts_with("friction "))
        .expect("the friction line");
    assert!(!line.contains("NaN") && !line.contains("Q/(μP)"), "{line}");
    assert!(
        line.contains("Q = 0.000000; 0 stick, 0 slip, 33 open points"),
        "{line}"
    );
}

/// Cattaneo–Mindlin's q assumes Dundurs' β = 0: `solve` names the body's β beside it (0.286 for
/// ν = 0.3 in plane strain, (1 − 2ν)/(2(1 − ν)) by hand), and the lab's status line does when
/// it is far from 0 (hertz-paper-full) but not on cattaneo-mindlin (ν = 0.499: 0.002).
#[test]
fn mindlin_names_the_bodys_dundurs_beta() {
    let (code, out, err) = crate::common::riplab(&[
        "solve",
        "scenarios/hertz-paper-full.toml",
        "-l",
        "1",
        "--friction",
        "coulomb",
        "--mu",
        "0.3",
        "--shift",
        "0.14",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("(β = 0; this body's β = 0.286,"), "{out}");
    let render = |scenario: &str, keys: &str| {
        let (code, out, err) =
            crate::common::riplab(&["render", scenario, "--keys", keys, "--size", "80x24"]);
        assert_eq!(code, 0, "{err}");
        out.split_whitespace().collect::<Vec<_>>().join(" ")
    };
    let full = render("scenarios/hertz-paper-full.toml", "F");
    assert!(full.contains("Mindlin (β=0; here 0.29) c="), "{full}");
    let decoupled = render("scenarios/cattaneo-mindlin.toml", "1");
    assert!(
        decoupled.contains("Mindlin c=") && !decoupled.contains("here 0."),
        "{decoupled}"
    );
}
