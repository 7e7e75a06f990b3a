//! Bad scenarios and bad command lines: a clear message naming the file, line and key with
//! the allowed range, exit code 2, no panic.

mod common;

use common::riplab;

/// (file, expected fragments of the message)
const CASES: &[(&str, &[&str])] = &[
    (
        "poisson-half.toml",
        &[
            ":19:11",
            "`material.poisson`",
            "0.5 is out of range",
            "−1 < ν < 0.5",
        ],
    ),
    (
        "young-negative.toml",
        &[":18:9", "`material.young`", "-5", "from 1e-6 to 1e12"],
    ),
    (
        "young-nan.toml",
        &[":18:9", "`material.young`", "not a finite number"],
    ),
    (
        "level-negative.toml",
        &[":32:9", "`mesh.level`", "-1 is out of range", "0 to 8"],
    ),
    (
        "unknown-key.toml",
        &[":25:1", "unknown field `radus`", "expected one of"],
    ),
    ("malformed.toml", &[":34:", "unclosed table"]),
    ("wrong-type.toml", &[":36:11", "`contact.epsilon`", "string"]),
    (
        "zero-cells.toml",
        &[":30:6", "`mesh.nx`", "0 is out of range", "1 to 4096"],
    ),
    ("truncated.toml", &[":12:", "missing field `height`"]),
    ("not-utf8.toml", &[":37:", "not valid UTF-8"]),
    (
        "negative-width.toml",
        &[":13:9", "`body.width`", "-16 is out of range", "from 1e-6 to 1e6"],
    ),
];

#[test]
fn bad_scenarios_exit_2_with_a_located_message() {
    for (file, fragments) in CASES {
        let path = format!("{}/tests/bad/{file}", env!("CARGO_MANIFEST_DIR"));
        let (code, stdout, stderr) = riplab(&["solve", &path]);
        assert_eq!(code, 2, "{file}: exit code {code}, stderr: {stderr}");
        assert!(stdout.is_empty(), "{file}: printed a result");
        assert!(!stderr.contains("panicked"), "{file}: panicked: {stderr}");
        assert!(
            stderr.contains(file),
            "{file}: message does not name the file: {stderr}"
        );
        for f in *fragments {
            assert!(stderr.contains(f), "{file}: message lacks {f:?}:\n{stderr}");
        }
    }
}

#[test]
fn bad_command_line_values_exit_2() {
    for (args, fragment) in [
        (&["solve", "--epsilon=-1e-6"][..], "--epsilon"),
        (&["solve", "--epsilon", "0", "--scheme", "M2"][..], "not unique"),
        (&["solve", "--epsilon", "inf"][..], "not a finite number"),
        (&["solve", "--level", "9"][..], "0 to 8"),
        (&["solve", "--scheme", "M7"][..], "M1, M2, M3, M4 or element+rule"),
        (&["solve", "--rule", "gauss3"][..], "gauss1"),
        (&["infsup", "--levels", "3..1"][..], "--levels"),
        (&["solve", "no-such-file.toml"][..], "cannot read"),
    ] {
        let (code, stdout, stderr) = riplab(args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(
            stdout.is_empty() && stderr.contains(fragment),
            "{args:?}: {stderr}"
        );
    }
}

#[test]
fn solve_json_is_the_design_object() {
    let (code, stdout, _) = riplab(&["solve", "--level", "1", "--rule", "gauss1", "--format", "json"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["scenario"], "hertz-paper");
    assert_eq!(
        (v["element"].as_str(), v["rule"].as_str(), v["level"].as_u64()),
        (Some("q1"), Some("gauss1"), Some(1))
    );
    assert_eq!(
        (v["h"].as_f64(), v["epsilon"].as_f64(), v["depth"].as_f64()),
        (Some(0.5), Some(1e-6), Some(0.8))
    );
    assert_eq!(
        (
            v["half_model"].as_bool(),
            v["n_elements"].as_u64(),
            v["converged"].as_bool()
        ),
        (Some(true), Some(128), Some(true))
    );
    assert!(v["n_dofs"].as_u64().unwrap() > 0 && v["newton_iterations"].as_u64().is_some());
    let xs: Vec<f64> = v["nodes"]["x"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(xs.len(), 17);
    assert!(xs.windows(2).all(|w| w[0] < w[1]));
    assert_eq!(v["nodes"]["uy"].as_array().unwrap().len(), 17);
    assert_eq!(v["nodes"]["pbar"].as_array().unwrap().len(), 17);
    assert_eq!(v["points"]["x"].as_array().unwrap().len(), 16);
    assert_eq!(v["points"]["p"].as_array().unwrap().len(), 16);
    assert!(v["timing_ms"]["total"].as_f64().unwrap() >= 0.0);
    assert!(v["load"].as_f64().unwrap() > 0.0);
}

#[test]
fn an_epsilon_sweep_prints_one_object_per_value() {
    let (code, stdout, _) = riplab(&[
        "solve",
        "--level",
        "2",
        "--epsilon",
        "1e-5,1e-6,1e-7",
        "--format",
        "json",
    ]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let eps: Vec<f64> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|o| o["epsilon"].as_f64().unwrap())
        .collect();
    assert_eq!(eps, vec![1e-5, 1e-6, 1e-7]);
    // The mesh's work is paid once: only the first solve reports assembly time.
    let assembly: Vec<f64> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|o| o["timing_ms"]["assembly"].as_f64().unwrap())
        .collect();
    assert!(assembly[1] == 0.0 && assembly[2] == 0.0);
}

/// A 100 MB file is refused from its size, before it is read (a sparse file: no disk used).
#[test]
fn a_huge_file_is_refused_unread() {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("huge-scenario.toml");
    std::fs::File::create(&path).unwrap().set_len(100 << 20).unwrap();
    let (code, stdout, stderr) = riplab(&["solve", path.to_str().unwrap()]);
    std::fs::remove_file(&path).unwrap();
    assert_eq!(code, 2);
    assert!(
        stdout.is_empty() && stderr.contains("huge-scenario.toml") && stderr.contains("at most 1 MiB"),
        "{stderr}"
    );
}
