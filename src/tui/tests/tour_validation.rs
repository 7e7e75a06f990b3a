//! The validation of tour files: a bad tour names the file, the line, the key and what is
//! allowed; a tour's scenario paths are relative to its file.

use std::path::Path;

use riplab::scenario::Scenario;
use riplab::tui::tour::{Tour, TourError};

/// The error of parsing `text` as a tour.
fn error(text: &str) -> String {
    Tour::parse(text, "bad.toml", None).unwrap_err().to_string()
}

const STEP: &str = "title = \"t\"\n[[step]]\ntitle = \"s\"\ncaption = \"c\"\n";

#[test]
fn bad_tours_name_the_file_line_key_and_allowed_values() {
    let e = error(&format!("{STEP}colour = 1\n"));
    assert!(e.starts_with("bad.toml:5:"), "{e}");
    assert!(e.contains("colour") && e.contains("caption"), "{e}");
    let e = error(&format!("{STEP}level = 9\n"));
    assert!(
        e.starts_with("bad.toml:5:9:") && e.contains("step[1].level") && e.contains("0 to 7"),
        "{e}"
    );
    let e = error(&format!("{STEP}scene = \"plot\"\n"));
    assert!(
        e.contains("step[1].scene") && e.contains("explore, infsup, mesh"),
        "{e}"
    );
    let e = error(&format!("{STEP}overlays = [\"gap\", \"grid\"]\n"));
    assert!(
        e.contains("step[1].overlays") && e.contains("gap, hertz, circle, mindlin, all-levels"),
        "{e}"
    );
    let e = error(&format!("{STEP}scheme = \"M9\"\n"));
    assert!(
        e.contains("step[1].scheme") && e.contains("M1, M2, M3, M4"),
        "{e}"
    );
    let e = error(&format!("{STEP}scheme = \"M1\"\nrule = \"simpson\"\n"));
    assert!(e.contains("not both"), "{e}");
    let e = error(&format!("{STEP}element = \"q3\"\n"));
    assert!(e.contains("q3") && e.contains("q1"), "{e}");
    let e = error(&format!("{STEP}epsilon = -1e-6\n"));
    assert!(
        e.contains("step[1].epsilon") && e.contains("exact constraint"),
        "{e}"
    );
    let e = error(&format!("{STEP}depth = -0.1\n"));
    assert!(e.contains("step[1].depth"), "{e}");
    let e = error("title = \"t\"\n[[step]]\ntitle = \"s\"\ncaption = \"\"\"\n1\n2\n3\n4\n5\"\"\"\n");
    assert!(e.contains("step[1].caption") && e.contains("5 lines"), "{e}");
    let e = error(&format!(
        "title = \"t\"\n[[step]]\ntitle = \"s\"\ncaption = \"{}\"\n",
        "x".repeat(97)
    ));
    assert!(e.contains("97 characters"), "{e}");
    let e = error("title = \"t\"\nstep = []\n");
    assert!(e.contains("at least one"), "{e}");
    let e = error(&format!("{STEP}scenario = \"x.toml\"\n"));
    assert!(e.contains("step[1].scenario") && e.contains("tour file"), "{e}");
    assert!(error("title = ").starts_with("bad.toml:1:"));
}

#[test]
fn scenario_paths_are_relative_to_the_tour_file() {
    let dir = std::env::temp_dir().join(format!("riplab-tour-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scenario = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hertz-paper.toml");
    std::fs::copy(&scenario, dir.join("mine.toml")).unwrap();
    let file = dir.join("t.toml");
    std::fs::write(&file, format!("{STEP}scenario = \"mine.toml\"\ndepth = 0.5\n")).unwrap();
    let tour = Tour::load(&file).unwrap();
    assert_eq!(tour.scenario_of(0).name, "hertz-paper");
    assert_eq!(tour.app(0).settings.depth, 0.5);
    std::fs::write(&file, format!("{STEP}scenario = \"missing.toml\"\n")).unwrap();
    let e = Tour::load(&file).unwrap_err().to_string();
    assert!(e.contains("t.toml:5:") && e.contains("missing.toml"), "{e}");
    // A depth beyond the scenario's limit is refused for the scenario given at run time.
    std::fs::write(&file, format!("{STEP}depth = 2.5\n")).unwrap();
    let tour = Tour::load(&file).unwrap();
    let e = tour.with_scenario(Scenario::paper()).unwrap_err();
    assert!(
        matches!(
            e,
            TourError::Depth {
                step: 1,
                depth: 2.5,
                ..
            }
        ),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

// ---- the tour at 80×24 ---------------------------------------------------------
