//! Scenario files refused where they say it and in the user's words: friction with what the
//! rest of the file asks and it cannot take (Nitsche's method, ε_t with the exact method, a
//! grading) at the key that asks it; a grading from the file never blamed on a flag;
//! decimals that underflow to 0 and integers beyond 64 bits at their key with the range; the
//! help's defaults those of the code.

use crate::common::{riplab, scratch_file};

/// The full model with `[friction]` (Coulomb, μ = 0.3) and `extra` lines in it, each
/// `(line start, replacement)` as [`crate::common::paper_text`] takes them.
fn full_with_friction(edits: &[(&str, &str)]) -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-paper-full.toml");
    let mut text = std::fs::read_to_string(path).unwrap() + "\n[friction]\nlaw = \"coulomb\"\nmu = 0.3\n";
    for (old, new) in edits {
        let line = text
            .lines()
            .find(|l| l.trim_start().starts_with(old))
            .unwrap_or_else(|| panic!("no line {old}"))
            .to_string();
        text = text.replace(&line, new);
    }
    text
}

/// `file:line:col` of the first line of `text` that starts with `start`, its value's column.
fn at(file: &std::path::Path, text: &str, start: &str) -> String {
    let (n, line) = text
        .lines()
        .enumerate()
        .find(|(_, l)| l.starts_with(start))
        .unwrap_or_else(|| panic!("no line {start}"));
    let col = line.find('=').unwrap() + 3;
    format!("{}:{}:{col}", file.display(), n + 1)
}

/// `riplab ARGS`: exit 2, nothing on stdout, every fragment in stderr, none of `absent`.
fn refused(args: &[&str], fragments: &[&str], absent: &[&str]) {
    let (code, stdout, stderr) = riplab(args);
    assert_eq!(code, 2, "{args:?}: {stderr}");
    assert!(stdout.is_empty(), "{args:?}: {stdout}");
    for f in fragments {
        assert!(stderr.contains(f), "{args:?}: lacks {f:?}: {stderr}");
    }
    for a in absent {
        assert!(!stderr.contains(a), "{args:?}: names {a:?}: {stderr}");
    }
}

/// Friction with Nitsche, ε_t with the exact method and friction on a graded mesh, all in one
/// file, are refused at the key that asks them (no file, line or key before); a file's
/// grading with friction from the flags blames `--friction`, never `--refine-edges`.
#[test]
fn friction_conflicts_in_a_file_are_located() {
    let nitsche = full_with_friction(&[("epsilon", "epsilon = 1e-6\nmethod = \"nitsche\"")]);
    let file = scratch_file("friction-nitsche.toml", &nitsche);
    let path = file.to_str().unwrap();
    refused(
        &["solve", path],
        &[
            &at(&file, &nitsche, "law")[..],
            "`friction.law`",
            "not by contact.method = \"nitsche\"",
        ],
        &[],
    );
    let exact = full_with_friction(&[("epsilon", "epsilon = 0.0"), ("mu", "mu = 0.3\nepsilon_t = 1e-6")]);
    let file = scratch_file("friction-exact-epsilon-t.toml", &exact);
    refused(
        &["solve", file.to_str().unwrap()],
        &[
            &at(&file, &exact, "epsilon_t")[..],
            "`friction.epsilon_t`",
            "the method here is exact",
        ],
        &[],
    );
    let graded = full_with_friction(&[("level", "level = 1\nrefine_edges = \"2z\"")]);
    let file = scratch_file("friction-graded.toml", &graded);
    refused(
        &["solve", file.to_str().unwrap()],
        &[
            &at(&file, &graded, "refine_edges")[..],
            "`mesh.refine_edges`",
            "not available with friction",
        ],
        &["--refine-edges"],
    );
    let plain = scratch_file(
        "full-graded.toml",
        &full_with_friction(&[
            ("level", "level = 1\nrefine_edges = 2"),
            ("[friction]", ""),
            ("law", ""),
            ("mu", ""),
        ]),
    );
    for command in ["solve", "study"] {
        refused(
            &[
                command,
                plain.to_str().unwrap(),
                "--friction",
                "coulomb",
                "--mu",
                "0.3",
            ],
            &["invalid value for --friction", "`[mesh] refine_edges = 2`"],
            &["--refine-edges:"],
        );
    }
}

/// `mu = 1e-400` and `epsilon = 1e-400` became 0 (the latter selecting the exact method)
/// where the command line refuses both; an integer beyond 64 bits said "invalid type: integer
/// … as i128, expected i64". Each is refused at its key with what is allowed.
#[test]
fn underflows_and_oversized_integers_in_a_file_are_refused_at_their_key() {
    for (name, edits, key, words) in [
        (
            "mu-underflow.toml",
            vec![("mu", "mu = 1e-400")],
            "friction.mu",
            "`1e-400` is not 0 but underflows to 0",
        ),
        (
            "epsilon-underflow.toml",
            vec![
                ("epsilon", "epsilon = 1e-400"),
                ("[friction]", ""),
                ("law", ""),
                ("mu", ""),
            ],
            "contact.epsilon",
            "`1e-400` is not 0 but underflows to 0",
        ),
        (
            "level-oversized.toml",
            vec![("level", "level = 99999999999999999999")],
            "mesh.level",
            "99999999999999999999 is out of range; allowed: 0 to 8",
        ),
        (
            "steps-oversized.toml",
            vec![("mu", "mu = 0.3\nsteps = -170141183460469231731687303715884105729")],
            "friction.steps",
            "-170141183460469231731687303715884105729 is out of range; allowed: 1 to 1000",
        ),
    ] {
        let text = full_with_friction(&edits);
        let file = scratch_file(name, &text);
        let line = key.rsplit('.').next().unwrap();
        refused(
            &["solve", file.to_str().unwrap()],
            &[&at(&file, &text, line)[..], &format!("`{key}`: {words}")[..]],
            &["i128", "i64"],
        );
    }
}

/// `solve --help` gave the `--shift-steps` default as 8 where it is 1: the help's range and
/// default are the constants'.
#[test]
fn the_shift_steps_help_states_the_constants() {
    use riplab::contact::friction::{DEFAULT_STEPS, MAX_STEPS};
    let (code, stdout, _) = riplab(&["solve", "--help"]);
    assert_eq!(code, 0);
    let said = format!("1 to {MAX_STEPS} [default: the scenario's, else {DEFAULT_STEPS}]");
    assert!(stdout.contains(&said), "{stdout}");
}
