//! Tour steps written by the lab's `T` play back to the screens the lab showed, a
//! file that is not a tour is never added to, and a handout has each step's screen (equal to
//! `render_step`), its pressure chart and an index.

use std::path::{Path, PathBuf};

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

use riplab::scenario::Scenario;
use riplab::tui::app::{App, Command, ExportKind, Msg, Scene};
use riplab::tui::engine::Engine;
use riplab::tui::render_app;
use riplab::tui::settle::{carry_out, settle};
use riplab::tui::tour::author::{CAPTION_PLACEHOLDER, LabSource, save_step};
use riplab::tui::tour::handout::{HandoutError, write_handout};
use riplab::tui::tour::{Tour, render_step};

const LOOK: riplab::tui::view::Look = riplab::tui::view::Look {
    theme: riplab::tui::theme::Theme { color: true },
    marker: ratatui::symbols::Marker::Braille,
};

/// A fresh directory under the system's temporary one.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("riplab-authoring-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Press `keys` in the lab: the commands they ask for.
fn press(app: &mut App, keys: &[KeyCode]) -> Vec<Command> {
    keys.iter()
        .flat_map(|&code| {
            app.update(Msg::Key(KeyEvent::new(code, KeyModifiers::NONE)))
                .commands
        })
        .collect()
}

/// What the lab shows once `commands` are done: the solves of settings left behind dropped (as
/// the lab's worker cancels them), the rest carried out on a fresh engine (as `render_step`
/// solves a step: no warm start), timings hidden, drawn at the size the tour leaves the lab
/// above a one-line caption (two rows).
fn lab_frame(app: &mut App, commands: Vec<Command>) -> String {
    app.show_timing = false;
    let generation = app.generation;
    let commands = commands
        .into_iter()
        .filter(|c| !matches!(c, Command::Solve(r) if r.generation != generation))
        .collect();
    let mut engine = Engine::new(app.scenario.clone());
    carry_out(app, &mut engine, commands);
    // The estimates computed so far are the lab's history, which a step does not carry (the
    // inf-sup scene computes levels 0 to 4): only those this screen asks for.
    app.infsup.clear();
    settle(app, &mut engine);
    // What the last key said (every key says what it did) is the lab's, not the
    // step's.
    app.notice = None;
    // Drawn as a step's lab is: without the key bar (the tour's panel has its keys).
    app.overlays.in_tour = true;
    let frame = render_app(app, &LOOK, 100, 28);
    app.overlays.in_tour = false;
    frame
}

/// `T` asks for the tour step whether or not a solution is on screen.
#[test]
fn t_asks_for_a_tour_step() {
    let mut app = App::new(Scenario::paper());
    app.scene = Scene::InfSup;
    let effect = app.update(Msg::Key(KeyEvent::new(KeyCode::Char('T'), KeyModifiers::NONE)));
    assert!(effect.commands.contains(&Command::Export));
    assert_eq!(app.export_kind, ExportKind::TourStep);
}

/// The test: a tour written by `T` from a sequence of lab states plays back to the same
/// frames (render_step of each step, whose top 28 rows are the lab, against the lab's frame
/// when `T` was pressed), and `riplab tour --check`'s reading accepts it.
#[test]
fn steps_written_by_t_play_back_to_the_lab_frames() {
    use KeyCode::{BackTab, Char, Tab};
    let dir = scratch("playback");
    let source = LabSource {
        tour_out: dir.join("lesson.toml"),
        scenario_file: None,
    };
    let mut app = App::new(Scenario::paper());
    let states: [&[KeyCode]; 4] = [
        // The "Done when": `]]2` gives level 2 with M2.
        &[Char(']'), Char(']'), Char('2')],
        // The inf-sup scene at every level, for M3 (no solve of M3 yet: the header shows no
        // dofs, as the step's playback shows none; what the lab shows from its history, the
        // dofs of a solve at the same settings, a step does not carry).
        &[Tab, Char('3'), Char('a')],
        // Back to explore: the ALM at ε = 1e-7, the overlays, a shallower obstacle.
        &[
            BackTab,
            Char('m'),
            Char('m'),
            Char('-'),
            Char('g'),
            Char('h'),
            Char('d'),
        ],
        // M4 with Nitsche, in the stress scene showing von Mises.
        &[Char('4'), Char('m'), BackTab, Char('c')],
    ];
    let mut frames = Vec::new();
    for (i, keys) in states.iter().enumerate() {
        let mut commands = press(&mut app, keys);
        if i == 2 {
            // Zoom needs the contact zone on screen.
            lab_frame(&mut app, commands);
            commands = press(&mut app, &[Char('z')]);
            assert!(app.zoom, "{:?}", app.notice);
        }
        frames.push(lab_frame(&mut app, commands));
        let notice = save_step(&app, &source);
        assert!(!notice.failure, "{}", notice.text);
        assert!(
            notice.text.contains(&format!("added step {}", i + 1)) && notice.text.contains("lesson.toml"),
            "{}",
            notice.text
        );
    }
    let written = std::fs::read_to_string(&source.tour_out).unwrap();
    for expected in [
        "scheme = \"M2\"\nlevel = 2\n",
        "epsilon = 1e-7\nmethod = \"alm\"\nalm_tol = 1e-10\n",
        "depth = 0.7\n",
        "overlays = [\"gap\", \"hertz\", \"all-levels\", \"zoom\"]",
        "method = \"nitsche\"\ntheta = 1\ngamma0 = \"auto\"\n",
        "scene = \"stress\"",
        "quantity = \"von_mises\"",
    ] {
        assert!(written.contains(expected), "{expected:?} in\n{written}");
    }
    let tour = Tour::load(&source.tour_out)
        .unwrap_or_else(|e| panic!("{e}"))
        .with_scenario(Scenario::paper())
        .unwrap();
    assert_eq!(tour.steps.len(), 4);
    assert!(tour.steps.iter().all(|s| s.caption == CAPTION_PLACEHOLDER));
    // The first step is M2 at level 2 (q1 + gauss2), as the issue asks.
    let first = tour.app(0);
    assert_eq!((first.settings.level, first.scene), (2, Scene::Explore));
    assert_eq!(
        riplab::scheme::Scheme::new(first.settings.element, first.settings.rule).name(),
        Some("M2")
    );
    for (i, lab) in frames.iter().enumerate() {
        let step = render_step(&tour, i, 100, 30).unwrap();
        let top: Vec<&str> = step.lines().take(28).collect();
        let lab: Vec<&str> = lab.lines().collect();
        assert_eq!(
            top,
            lab,
            "step {}:\n{step}\nthe lab showed:\n{}",
            i + 1,
            lab.join("\n")
        );
        assert!(step.contains(&format!("tour {}/4", i + 1)));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A lab opened on a scenario file names it in the step, relative to the tour file when it
/// lies beside it: the step plays back on that scenario.
#[test]
fn a_scenario_file_is_named_relative_to_the_tour() {
    let dir = scratch("scenario");
    let scenario_file = dir.join("deep.toml");
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hertz-paper.toml"))
            .unwrap()
            .replace("name = \"hertz-paper\"", "name = \"deep-one\"");
    assert!(text.contains("deep-one"));
    std::fs::write(&scenario_file, text).unwrap();
    let scenario = Scenario::load(&scenario_file).unwrap();
    let source = LabSource {
        tour_out: dir.join("t.toml"),
        scenario_file: Some(scenario_file.clone()),
    };
    let notice = save_step(&App::new(scenario), &source);
    assert!(!notice.failure, "{}", notice.text);
    let written = std::fs::read_to_string(&source.tour_out).unwrap();
    assert!(written.contains("scenario = \"deep.toml\""), "{written}");
    let tour = Tour::load(&source.tour_out).unwrap();
    assert_eq!(tour.scenario_of(0).name, "deep-one");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `T` never changes a file that is not a valid tour: it says so and leaves the file as it was.
#[test]
fn t_never_adds_to_another_kind_of_file() {
    let dir = scratch("refuse");
    let app = App::new(Scenario::paper());
    for text in ["name = \"a scenario, say\"\n", "not toml at all [", ""] {
        let file = dir.join("other.toml");
        std::fs::write(&file, text).unwrap();
        let notice = save_step(
            &app,
            &LabSource {
                tour_out: file.clone(),
                scenario_file: None,
            },
        );
        assert!(notice.failure, "{text:?}: {}", notice.text);
        assert!(notice.text.contains("valid tour file only"), "{}", notice.text);
        assert_eq!(std::fs::read_to_string(&file).unwrap(), text, "unchanged");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A small tour: explore with M1 at level 0, then the inf-sup scene (whose chart is solved
/// for the handout alone).
const SMALL: &str = "title = \"Small\"

[[step]]
title = \"First\"
caption = \"One line.\"
scheme = \"M1\"
level = 0

[[step]]
title = \"Second\"
caption = \"\"\"
Two lines,
the second.\"\"\"
scene = \"infsup\"
scheme = \"M3\"
level = 0
";

/// The test: a handout has one text file and one SVG per step, the text equal to
/// `render_step`, and an index that lists the steps, their captions and files; a directory
/// that is not empty is refused.
#[test]
fn a_handout_has_each_steps_frame_chart_and_index() {
    let dir = scratch("handout");
    let tour = Tour::parse(SMALL, "small.toml", None).unwrap();
    let out = dir.join("lesson");
    let mut done = Vec::new();
    let files = write_handout(&tour, &out, 100, 30, |d, n| done.push((d, n))).unwrap();
    assert_eq!(done, [(1, 2), (2, 2)]);
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "index.md",
            "step-01.svg",
            "step-01.txt",
            "step-02.svg",
            "step-02.txt"
        ]
    );
    assert_eq!(files.len(), 5);
    for (i, scheme) in [(0, "M1 (q1 + gauss1)"), (1, "M3 (q1 + trapezoid)")] {
        let stem = format!("step-{:02}", i + 1);
        let text = std::fs::read_to_string(out.join(format!("{stem}.txt"))).unwrap();
        assert_eq!(text, render_step(&tour, i, 100, 30).unwrap(), "{stem}");
        let svg = std::fs::read_to_string(out.join(format!("{stem}.svg"))).unwrap();
        assert!(
            svg.contains("<svg") && svg.trim_end().ends_with("</svg>"),
            "{stem}"
        );
        // The second step shows the inf-sup scene: its SVG is the inf-sup chart.
        let title = match i {
            0 => format!("hertz-paper: {scheme}, level 0"),
            _ => "hertz-paper: β_h/√h against h".into(),
        };
        assert!(svg.contains(&title), "{stem}: {title}");
    }
    let index = std::fs::read_to_string(out.join("index.md")).unwrap();
    for expected in [
        "# Small",
        "## 1. First",
        "> One line.",
        "## 2. Second",
        "> Two lines,\n> the second.",
        "[step-01.txt](step-01.txt)",
        "[step-02.svg](step-02.svg)",
        "Scene infsup · hertz-paper · M3 at level 0",
    ] {
        assert!(index.contains(expected), "{expected:?} in\n{index}");
    }
    // Again into the same directory: refused, nothing replaced.
    let again = write_handout(&tour, &out, 100, 30, |_, _| {}).unwrap_err();
    assert!(matches!(again, HandoutError::Directory { .. }), "{again}");
    assert!(again.to_string().contains("not empty"), "{again}");
    assert_eq!(std::fs::read_to_string(out.join("index.md")).unwrap(), index);
    std::fs::remove_dir_all(&dir).unwrap();
}
