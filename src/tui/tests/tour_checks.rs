//! A tour's steps checked as the lab plays them, and what the lab's `T` writes: a step's
//! friction refused on its scenario's half model, with Nitsche's method, on a graded mesh or
//! shifted out of the body, when the tour is read (not when its handout is half written); the
//! lab's grading carried by the step `T` writes; an append that would pass the size a tour
//! file may have refused, the file unchanged; each scenario file read once however many steps
//! name it; a handout's names taken mid-run refused in words that name no option it lacks; a
//! step's overlay its scenario has no curve for refused when the tour is read.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

use riplab::grading::{Grading, RefineEdges};
use riplab::scenario::Scenario;
use riplab::tui::app::{App, Msg};
use riplab::tui::tour::Tour;
use riplab::tui::tour::author::{LabSource, save_step};
use riplab::tui::tour::handout::{HandoutError, MAX_HANDOUT_BYTES, estimate, write_handout};

/// A fresh directory under the system's temporary one.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("riplab-tour-checks-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A tour of one step with `settings` (TOML lines).
fn one_step(settings: &str) -> String {
    format!("title = \"t\"\n\n[[step]]\ntitle = \"s\"\ncaption = \"c\"\n{settings}\n")
}

/// `scenarios/cattaneo-mindlin.toml`: a full model with Coulomb friction.
fn cattaneo() -> Scenario {
    Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/cattaneo-mindlin.toml")).unwrap()
}

/// Why the tour of one step with `settings`, played on `scenario`, is refused.
fn refused(settings: &str, scenario: Scenario) -> String {
    Tour::parse(&one_step(settings), "t.toml", None)
        .unwrap_or_else(|e| panic!("{e}"))
        .with_scenario(scenario)
        .map(|_| ())
        .expect_err(settings)
        .to_string()
}

fn press(app: &mut App, keys: &str) {
    for c in keys.chars() {
        app.update(Msg::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE)));
    }
}

/// The friction the lab refuses to solve is refused when the tour is read (`tour --check`,
/// `--tour`, `--handout` all read it so), naming the step and the reason: on a half model (it
/// passed, and the handout then failed blaming a shift of 0), with Nitsche, on a graded mesh,
/// shifted out of the body. Friction the lab solves passes.
#[test]
fn friction_the_lab_refuses_is_refused_when_the_tour_is_read() {
    let half = refused("level = 0\nfriction = \"coulomb\"\nmu = 0.3", Scenario::paper());
    assert!(
        half.starts_with("t.toml: step 1 (`s`)") && half.contains("friction needs the full model"),
        "{half}"
    );
    assert!(!half.contains("shift = 0"), "{half}");
    for (settings, why) in [
        ("method = \"nitsche\"", "not nitsche"),
        ("refine_edges = \"2z\"", "refine_edges = \"2z\""),
        ("refine_edges = 1", "does not take friction"),
        ("shift = 1000.0", "shift = 1000 moves the obstacle's centre"),
    ] {
        let e = refused(&format!("level = 1\n{settings}"), cattaneo());
        assert!(e.contains("step 1") && e.contains(why), "{settings}: {e}");
    }
    let tour = Tour::parse(&one_step("level = 1\nshift = 0.05"), "t.toml", None).unwrap();
    assert!(tour.with_scenario(cattaneo()).is_ok());
}

/// A step's overlay its scenario has no curve for is refused when the tour is read, in the
/// words the lab's key says it with (Mindlin's traction on the frictionless paper was
/// accepted by `tour --check` and drew nothing; Hertz's on a flat punch the same). The
/// curves the scenario has pass.
#[test]
fn an_overlay_the_scenario_has_no_curve_for_is_refused_when_the_tour_is_read() {
    let punch =
        Scenario::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/flat-punch.toml")).unwrap();
    for (settings, scenario, why) in [
        (
            "overlays = [\"mindlin\"]",
            Scenario::paper(),
            "no Mindlin traction here",
        ),
        (
            "overlays = [\"gap\", \"hertz\"]",
            punch.clone(),
            "no Hertz solution",
        ),
        ("overlays = [\"circle\"]", punch.clone(), "no Hertz solution"),
    ] {
        let e = refused(&format!("level = 0\n{settings}"), scenario);
        let overlay = settings.rsplit('"').nth(1).unwrap();
        assert!(
            e.starts_with("t.toml: step 1 (`s`)")
                && e.contains(&format!("[\"{overlay}\"]"))
                && e.contains(why),
            "{settings}: {e}"
        );
    }
    for (settings, scenario) in [
        ("overlays = [\"gap\"]", punch),
        ("overlays = [\"hertz\", \"circle\", \"gap\"]", Scenario::paper()),
        ("overlays = [\"mindlin\", \"hertz\"]", cattaneo()),
    ] {
        let tour = Tour::parse(&one_step(&format!("level = 0\n{settings}")), "t.toml", None).unwrap();
        assert!(tour.with_scenario(scenario).is_ok(), "{settings}");
    }
}

/// A step naming a scenario of two elastic bodies is a two-body step (the lab's two-body
/// scene, not the rigid limit played as one body); a one-body scenario's step is not.
#[test]
fn a_two_body_scenario_makes_a_two_body_step() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    for file in ["patch-two-blocks.toml", "hertz-two-bodies.toml"] {
        let text = one_step(&format!("scenario = \"{file}\""));
        let tour = Tour::parse(&text, "t.toml", Some(&dir)).unwrap_or_else(|e| panic!("{file}: {e}"));
        let bodies = tour
            .bodies(0)
            .unwrap_or_else(|| panic!("{file}: a two-body step"));
        assert!(bodies.scenario.upper.is_some(), "{file}");
    }
    let text = one_step("scenario = \"flat-punch.toml\"");
    assert!(
        Tour::parse(&text, "t.toml", Some(&dir))
            .unwrap()
            .bodies(0)
            .is_none()
    );
}

/// `]` `E` `E` `T`: the step holds the lab's two passes of edge grading (it held none, and
/// played the uniform mesh), and zone grading too; the tour plays it back at the lab's
/// settings.
#[test]
fn t_writes_the_lab_grading() {
    let dir = scratch("grading");
    let source = LabSource {
        tour_out: dir.join("t.toml"),
        scenario_file: None,
    };
    let mut app = App::new(Scenario::paper());
    press(&mut app, "]EE");
    assert_eq!(app.settings.refine_edges, Grading::Edges(RefineEdges::Passes(2)));
    let notice = save_step(&app, &source);
    assert!(
        !notice.failure && notice.text.contains("added step 1"),
        "{}",
        notice.text
    );
    let mut zone = App::new(Scenario::paper());
    press(&mut zone, "EEEEE");
    assert_eq!(zone.settings.refine_edges, Grading::Zone(1));
    assert!(!save_step(&zone, &source).failure);
    let written = std::fs::read_to_string(&source.tour_out).unwrap();
    assert!(written.contains("\nrefine_edges = 2\n"), "{written}");
    assert!(written.contains("\nrefine_edges = \"1z\"\n"), "{written}");
    let tour = Tour::load(&source.tour_out)
        .unwrap()
        .with_scenario(Scenario::paper())
        .unwrap();
    assert_eq!(tour.app(0).settings, app.settings);
    assert_eq!(tour.app(1).settings, zone.settings);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `T` on a screen whose friction a step would not play (graded friction) writes nothing and
/// says why: the tour stays valid.
#[test]
fn t_writes_no_step_the_tour_would_refuse() {
    let dir = scratch("graded-friction");
    let source = LabSource {
        tour_out: dir.join("t.toml"),
        scenario_file: None,
    };
    let mut app = App::new(cattaneo());
    // The keys refuse it (`E` with friction on): set as it would stand.
    app.settings.refine_edges = Grading::Edges(RefineEdges::Passes(1));
    let notice = save_step(&app, &source);
    assert!(notice.failure, "{}", notice.text);
    assert!(notice.text.contains("does not take friction"), "{}", notice.text);
    assert!(!source.tour_out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `T` onto a valid tour 9 bytes under the limit (1 MiB) refuses the step, which would make
/// the file one that no command reads (it appended, and `--check`, `--tour` and `T` then all
/// refused the file); the file is unchanged and still valid.
#[test]
fn t_refuses_an_append_past_the_size_limit() {
    let dir = scratch("size");
    let file = dir.join("big.toml");
    let limit = riplab::input::read::MAX_FILE_BYTES as usize;
    let mut text = one_step("level = 0");
    let pad = limit - 9 - text.len();
    // A comment line of `pad` bytes (with its `#` and line break).
    text.push('#');
    text.push_str(&"x".repeat(pad - 2));
    text.push('\n');
    assert_eq!(text.len(), limit - 9);
    std::fs::write(&file, &text).unwrap();
    assert!(Tour::load(&file).is_ok());
    let notice = save_step(
        &App::new(Scenario::paper()),
        &LabSource {
            tour_out: file.clone(),
            scenario_file: None,
        },
    );
    assert!(notice.failure, "{}", notice.text);
    assert!(
        notice.text.contains("1048567 bytes") && notice.text.contains("1 MiB"),
        "{}",
        notice.text
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), text, "unchanged");
    assert!(Tour::load(&file).is_ok());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// 200 steps naming one scenario file read it once, and share one scenario (it was read,
/// parsed and held 200 times: 21–28 s and 286 MB for a 1 MB scenario).
#[test]
fn a_scenario_named_by_many_steps_is_read_once() {
    let dir = scratch("read-once");
    std::fs::write(dir.join("s.toml"), riplab::scenario::DEFAULT_SCENARIO).unwrap();
    std::fs::write(dir.join("other.toml"), riplab::scenario::DEFAULT_SCENARIO).unwrap();
    let mut text = String::from("title = \"many\"\n");
    for i in 0..200 {
        let file = if i == 100 { "other.toml" } else { "s.toml" };
        text.push_str(&format!(
            "\n[[step]]\ntitle = \"{i}\"\ncaption = \"c\"\nscenario = \"{file}\"\nlevel = 0\n"
        ));
    }
    std::fs::write(dir.join("many.toml"), text).unwrap();
    let tour = Tour::load(&dir.join("many.toml")).unwrap();
    assert_eq!(tour.scenario_reads, 2);
    let first = tour.steps[0].scenario.as_ref().unwrap();
    assert!(
        tour.steps
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != 100)
            .all(|(_, s)| Arc::ptr_eq(s.scenario.as_ref().unwrap(), first))
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A link planted at a handout's next file while it is written is refused, untouched, and the
/// message names no option (`--force`, which `tour --handout` does not have).
#[test]
fn a_link_planted_in_a_handout_is_refused_in_its_own_words() {
    let dir = scratch("planted");
    let out = dir.join("lesson");
    let victim = dir.join("victim.txt");
    std::fs::write(&victim, "keep").unwrap();
    let tour = Tour::parse(
        &format!(
            "{}\n{}",
            one_step("level = 0"),
            "[[step]]\ntitle = \"u\"\ncaption = \"d\"\nlevel = 0\n"
        ),
        "t.toml",
        None,
    )
    .unwrap();
    let planted = out.join("step-02.txt");
    let e = write_handout(&tour, &out, 100, 30, |done, _| {
        if done == 1 {
            std::os::unix::fs::symlink(&victim, &planted).unwrap();
        }
    })
    .unwrap_err();
    let message = e.to_string();
    assert!(!message.contains("--force"), "{message}");
    assert!(
        message.contains("step-02.txt") && message.contains("never replaces"),
        "{message}"
    );
    assert!(
        std::fs::symlink_metadata(&planted)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The handout's estimate bounds what it writes (every step's screen, chart and the index),
/// for each rule at a level whose charts are larger than the screens; a tour whose estimate
/// passes the limit is refused before the directory is made.
#[test]
fn the_handout_estimate_bounds_what_it_writes() {
    let dir = scratch("estimate");
    let steps: String = ["M1", "M2", "M3", "M4"]
        .iter()
        .map(|m| format!("\n[[step]]\ntitle = \"{m}\"\ncaption = \"c\"\nscheme = \"{m}\"\nlevel = 4\n"))
        .collect();
    let tour = Tour::parse(&format!("title = \"four\"\n{steps}"), "t.toml", None).unwrap();
    let out = dir.join("lesson");
    let files = write_handout(&tour, &out, 80, 24, |_, _| {}).unwrap();
    let written: u64 = files.iter().map(|f| std::fs::metadata(f).unwrap().len()).sum();
    let bound = estimate(&tour, 80, 24);
    assert!(written <= bound, "{written} > {bound}");
    // Enough copies of a step at the largest frame to pass the limit: refused, nothing made.
    let one = Tour::parse(&one_step("scheme = \"M1\"\nlevel = 4"), "t.toml", None).unwrap();
    let n = (MAX_HANDOUT_BYTES / estimate(&one, 1000, 500) + 2) as usize;
    let many: String = (0..n)
        .map(|i| format!("\n[[step]]\ntitle = \"{i}\"\ncaption = \"c\"\nscheme = \"M1\"\nlevel = 4\n"))
        .collect();
    let big = Tour::parse(&format!("title = \"many\"\n{many}"), "t.toml", None).unwrap();
    let refused = dir.join("big");
    let e = write_handout(&big, &refused, 1000, 500, |_, _| panic!("a step was written")).unwrap_err();
    assert!(matches!(e, HandoutError::TooLarge { .. }), "{e}");
    assert!(
        e.to_string().contains("256.0 MiB") && e.to_string().contains("--size"),
        "{e}"
    );
    assert!(!refused.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An integer beyond 64 bits as a step's `refine_edges` is refused at the step's key with the
/// passes allowed (0 to 8), as `mesh.refine_edges` is in a scenario; it named i64's range.
#[test]
fn an_oversized_step_grading_names_the_passes_allowed() {
    let e = Tour::parse(&one_step("refine_edges = 99999999999999999999"), "t.toml", None).unwrap_err();
    let said = e.to_string();
    assert!(
        said.contains("`step[1].refine_edges`: 99999999999999999999 is out of range; allowed: 0 to 8"),
        "{said}"
    );
}

/// A value of the wrong type in a step is refused at the step's own key (`step[2].level`,
/// the second `[[step]]`), in the user's words: it said `step.level` and "expected i64".
#[test]
fn a_wrong_type_in_a_step_names_the_step_in_the_users_words() {
    let two = |setting: &str| {
        format!(
            "{}\n[[step]]\ntitle = \"u\"\ncaption = \"d\"\n{setting}\n",
            one_step("level = 0")
        )
    };
    for (setting, said) in [
        (
            "level = \"x\"",
            "`step[2].level`: invalid type: string \"x\", expected a whole number",
        ),
        (
            "depth = true",
            "`step[2].depth`: invalid type: boolean `true`, expected a number",
        ),
        (
            "refine_edges = 1.5",
            "`step[2].refine_edges`: invalid type: floating point `1.5`",
        ),
    ] {
        let e = Tour::parse(&two(setting), "t.toml", None)
            .unwrap_err()
            .to_string();
        assert!(e.contains(said), "{setting}: {e}");
    }
}
