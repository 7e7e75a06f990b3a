//! What the command line's help, the README and the tour files say about the lab, read in
//! process (clap's help as `riplab --help` prints it). Unit tests of the command line.

use clap::CommandFactory as _;

use riplab::tui::app::{MAX_APP_LEVEL, Scene};

/// `riplab --help`, or `riplab SUBCOMMAND --help` with `sub`.
fn long_help(sub: Option<&str>) -> String {
    let mut cli = super::Cli::command();
    match sub {
        Some(name) => cli
            .find_subcommand_mut(name)
            .expect("a subcommand")
            .render_long_help(),
        None => cli.render_long_help(),
    }
    .to_string()
}

/// `render --help` lists every key of the lab's table (the help overlay
/// and the README's table are read from the same table, `riplab::tui::keys::LAB`).
#[test]
fn render_help_lists_the_labs_keys() {
    let help = long_help(Some("render"));
    for row in riplab::tui::keys::LAB {
        let line = format!("  {:<16}{}", row.keys, row.what.join(" "));
        assert!(help.contains(&line), "`{line}` in\n{help}");
    }
    assert!(help.contains("Exit codes:"), "the notes follow");
}

/// `render`'s help names every scene and the lab's levels; `riplab --help` says where exports
/// go and names `v`; the tour file's header gives the lab's levels; hertz-block's comment names
/// the stress scene's key.
#[test]
fn helps_and_files_agree_with_the_lab() {
    let help = long_help(Some("render"));
    for scene in Scene::ALL {
        assert!(help.contains(scene.name()), "{scene:?} in\n{help}");
    }
    let range = format!("0 to {MAX_APP_LEVEL}");
    assert!(
        help.contains(&range) && help.contains(&format!("Mesh level {range}")),
        "{help}"
    );
    let help = long_help(None);
    assert!(
        help.contains("--export-dir") && help.contains("`v` (VTU)"),
        "{help}"
    );
    let root = env!("CARGO_MANIFEST_DIR");
    let tour = std::fs::read_to_string(format!("{root}/tours/paper.toml")).unwrap();
    assert!(
        tour.contains(&format!("level    = 0..={MAX_APP_LEVEL} ")),
        "the tour's header"
    );
    let block = std::fs::read_to_string(format!("{root}/scenarios/hertz-block.toml")).unwrap();
    assert!(block.contains("`c` cycles") && !block.contains("stress scene (`s`)"));
}

/// docs/lab.md's key table is the lab's key table (`riplab::tui::keys`), row for row.
#[test]
fn the_documented_key_table_is_the_labs() {
    let docs = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/lab.md")).unwrap();
    let table = riplab::tui::keys::readme_table();
    assert!(
        docs.contains(&table),
        "docs/lab.md's key table differs from the lab's; it should read:\n{table}"
    );
}

/// A tour file's title and captions are text from a file: defanged before the terminal.
#[test]
fn tour_text_is_sanitised() {
    let tour = riplab::tui::tour::Tour::parse(
        r#"title = "t\u001b]0;PWNED\u0007"
[[step]]
title = "s\u001b[2J"
caption = """
line one\u001b[31m
line two"""
"#,
        "hostile-tour.toml",
        None,
    )
    .expect("a valid tour");
    assert!(!tour.title.chars().any(char::is_control), "{:?}", tour.title);
    let step = &tour.steps[0];
    assert!(!step.title.chars().any(char::is_control), "{:?}", step.title);
    assert!(
        !step.caption.chars().any(|c| c.is_control() && c != '\n'),
        "{:?}",
        step.caption
    );
    assert!(step.caption.contains("line one") && step.caption.contains('\n'));
}
