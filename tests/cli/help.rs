//! The command line's own conventions: help documents the exit codes; completions and the man
//! page are generated from the same definition.

use crate::common::riplab;

#[test]
fn help_documents_exit_codes() {
    for args in [
        &["--help"][..],
        &["solve", "--help"],
        &["infsup", "--help"],
        &["study", "--help"],
        &["render", "--help"],
    ] {
        let (code, out, _) = riplab(args);
        assert_eq!(code, 0);
        assert!(
            out.contains("Exit codes:") && out.contains("2  bad input"),
            "{args:?}"
        );
    }
}

#[test]
fn completions_and_man_page() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let (code, out, _) = riplab(&["completions", shell]);
        assert_eq!(code, 0, "{shell}");
        assert!(out.contains("riplab") && out.contains("infsup"), "{shell}");
    }
    let (code, man, _) = riplab(&["man"]);
    assert_eq!(code, 0);
    assert!(man.starts_with(".ie") && man.contains(".TH riplab 1") && man.contains("Exit codes"));
}

#[test]
fn render_prints_a_frame_without_a_terminal() {
    let (code, out, _) = riplab(&["render", "--size", "80x24", "--scene", "infsup"]);
    assert_eq!(code, 0);
    assert_eq!(out.lines().count(), 24);
    assert!(out.contains("β"));
}
