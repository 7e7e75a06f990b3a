//! `riplab tour --check FILE` lists a tour's steps without a
//! terminal (exit 2 with the file, line and key of an error); `--handout DIR` writes a frame
//! and a chart per step and an index, refusing a directory that is not empty; `--record`
//! refuses an existing file and a bad path before anything else, and leaves no file behind
//! when there is no terminal to record.

use std::path::PathBuf;

use crate::common::riplab;

/// A fresh directory under the system's temporary one.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("riplab-tour-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

const TWO_STEPS: &str = "title = \"Two\"

[[step]]
title = \"The mesh\"
caption = \"First.\"
scene = \"mesh\"
scheme = \"M1\"
level = 0

[[step]]
title = \"M4 with Nitsche\"
caption = \"Second.\"
scheme = \"M4\"
level = 1
method = \"nitsche\"
gamma0 = 50
";

#[test]
fn check_lists_the_steps_without_a_terminal() {
    let dir = scratch("check");
    let file = dir.join("two.toml");
    std::fs::write(&file, TWO_STEPS).unwrap();
    let (code, out, err) = riplab(&["tour", "--check", file.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("a valid tour of 2 steps") && out.contains("title: Two"),
        "{out}"
    );
    let rows: Vec<Vec<&str>> = out
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("step"))
        .skip(1)
        .map(|l| l.split_whitespace().collect())
        .collect();
    assert_eq!(rows.len(), 2, "{out}");
    assert_eq!(rows[0][..5], ["1", "mesh", "0", "M1", "penalty"]);
    assert_eq!(rows[1][..5], ["2", "explore", "1", "M4", "nitsche"]);
    assert!(out.contains("M4 with Nitsche"));
    // The embedded tour's file checks too.
    let paper = concat!(env!("CARGO_MANIFEST_DIR"), "/tours/paper.toml");
    let (code, out, _) = riplab(&["tour", "--check", paper]);
    assert_eq!(code, 0);
    assert!(out.contains("a valid tour of 19 steps"), "{out}");
    // Its two-body steps: the scene, the level, the element with the ratio, the discretisation.
    let two: Vec<Vec<&str>> = out
        .lines()
        .filter(|l| l.contains(" two-bodies "))
        .map(|l| l.split_whitespace().collect())
        .collect();
    assert_eq!(two.len(), 4, "{out}");
    assert_eq!(
        two[1][..6],
        ["17", "two-bodies", "2", "q1", "2:3", "nts"],
        "{out}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn check_names_the_file_line_and_key_of_an_error() {
    let dir = scratch("check-bad");
    let file = dir.join("bad.toml");
    // (text replaced, its replacement, the key named); the offending line is the
    // replacement's last.
    for (edit, replacement, key) in [
        ("gamma0 = 50", "gamma0 = 1e9", "step[2].gamma0"),
        ("gamma0 = 50", "theta = 2", "step[2].theta"),
        (
            "method = \"nitsche\"\ngamma0 = 50",
            "gamma0 = 50",
            "step[2].gamma0",
        ),
        ("level = 1", "level = 1\nquantity = \"tau9\"", "step[2].quantity"),
        (
            "level = 1",
            "level = 1\noverlays = [\"zoom\", \"blur\"]",
            "step[2].overlays",
        ),
    ] {
        let written = TWO_STEPS.replace(edit, replacement);
        std::fs::write(&file, &written).unwrap();
        let (code, out, err) = riplab(&["tour", "--check", file.to_str().unwrap()]);
        assert_eq!(code, 2, "{replacement}: {err}");
        assert!(out.is_empty());
        let bad = replacement.lines().last().unwrap();
        let n = written.lines().position(|l| l == bad).unwrap() + 1;
        let at = format!("{}:{n}:", file.display());
        assert!(
            err.contains(&at) && err.contains(key),
            "{replacement}: {at} {key}: {err}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn handout_writes_a_frame_and_a_chart_per_step() {
    let dir = scratch("handout");
    let file = dir.join("two.toml");
    std::fs::write(&file, TWO_STEPS).unwrap();
    let out_dir = dir.join("out");
    let args = [
        "tour",
        "--tour",
        file.to_str().unwrap(),
        "--handout",
        out_dir.to_str().unwrap(),
    ];
    let (code, out, err) = riplab(&args);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("index.md") && out.contains("4 step files"), "{out}");
    for name in [
        "index.md",
        "step-01.txt",
        "step-01.svg",
        "step-02.txt",
        "step-02.svg",
    ] {
        assert!(out_dir.join(name).is_file(), "{name}");
    }
    // The default size is 100×30, as the tour's snapshots.
    let frame = std::fs::read_to_string(out_dir.join("step-02.txt")).unwrap();
    assert_eq!(frame.lines().count(), 30);
    assert!(frame.contains("tour 2/2") && frame.contains("Second."), "{frame}");
    // Not into a directory that holds files: exit 2, nothing replaced.
    let (code, _, err) = riplab(&args);
    assert_eq!(code, 2);
    assert!(err.contains("--handout") && err.contains("not empty"), "{err}");
    assert_eq!(
        std::fs::read_to_string(out_dir.join("step-02.txt")).unwrap(),
        frame
    );
    // A size out of range is said before anything is solved.
    let (code, _, err) = riplab(&[
        "tour",
        "--handout",
        dir.join("x").to_str().unwrap(),
        "--size",
        "60x20",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("--size") && err.contains("80x24"), "{err}");
    assert!(!dir.join("x").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn record_refuses_an_existing_file_and_a_bad_path() {
    let dir = scratch("record");
    let existing = dir.join("old.cast");
    std::fs::write(&existing, "keep me").unwrap();
    for args in [
        vec!["tour", "--record", existing.to_str().unwrap()],
        vec!["--record", existing.to_str().unwrap()],
    ] {
        let (code, _, err) = riplab(&args);
        assert_eq!(code, 2, "{args:?}");
        assert!(
            err.contains("--record") && err.contains("exists") && err.contains("never replaces"),
            "{err}"
        );
        assert_eq!(std::fs::read_to_string(&existing).unwrap(), "keep me");
    }
    let missing = dir.join("no/such/dir/t.cast");
    let (code, _, err) = riplab(&["tour", "--record", missing.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("cannot create the recording"), "{err}");
    // Without a terminal: the usual error, and the new file is not left behind.
    let fresh = dir.join("new.cast");
    let (code, _, err) = riplab(&["tour", "--record", fresh.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("needs a terminal"), "{err}");
    assert!(!fresh.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
