//! Tour steps on a scenario of two elastic bodies (docs/lab.md, "Two bodies"; docs/design.md
//! §12): such a step parses with its own keys (`contact`, `ratio`, `offset`, `level`,
//! `epsilon`) and is drawn as the lab's two-body scene above its caption; the patch test's
//! verdict is on its status line (NTS at 2:3 fails it, mortar passes); a key that does not
//! apply to the step's scenario is refused with its place; the player goes back and forth
//! between one-body and two-body steps. The chart of the two-body scene is not asserted on.

use std::path::{Path, PathBuf};

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

use riplab::contact::interface::InterfaceMethod;
use riplab::scenario::Scenario;
use riplab::tui::app::{Command, Msg};
use riplab::tui::bodies::cache::BodiesCache;
use riplab::tui::tour::{Tour, TourApp, TourError, TourMsg, render_step};

/// `scenarios/`, where the tours below are read from.
fn scenarios() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios")
}

/// A step on the contact patch test with `settings` (TOML lines).
fn patch_step(title: &str, settings: &str) -> String {
    format!(
        "\n[[step]]\ntitle = \"{title}\"\nscenario = \"patch-two-blocks.toml\"\n{settings}\ncaption = \"The caption of {title}.\"\n"
    )
}

/// A one-body step at level 0.
const ONE_BODY: &str =
    "\n[[step]]\ntitle = \"One body\"\nlevel = 0\ncaption = \"Under the rigid obstacle.\"\n";

fn tour(steps: &str) -> Tour {
    Tour::parse(&format!("title = \"t\"\n{steps}"), "t.toml", Some(&scenarios()))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The error of a tour of `steps`, read from `scenarios/`.
fn error(steps: &str) -> String {
    Tour::parse(&format!("title = \"t\"\n{steps}"), "t.toml", Some(&scenarios()))
        .map(|_| ())
        .expect_err(steps)
        .to_string()
}

/// The patch error the status line of `frame` prints after `verdict` ("failed: error").
fn patch_error(frame: &str, verdict: &str) -> f64 {
    let at = frame
        .find(&format!("patch test {verdict}"))
        .unwrap_or_else(|| panic!("`patch test {verdict}` in\n{frame}"));
    let rest = frame[at..].split("error ").nth(1).unwrap();
    let number: String = rest
        .trim_start_matches("< ")
        .chars()
        .take_while(|c| c.is_ascii_digit() || matches!(c, '.' | 'e' | '-'))
        .collect();
    number
        .parse()
        .unwrap_or_else(|e| panic!("{number}: {e}\n{frame}"))
}

fn key(code: KeyCode) -> TourMsg {
    TourMsg::Lab(Msg::Key(KeyEvent::new(code, KeyModifiers::NONE)))
}

/// A two-body step parses with its keys and renders at 80×24: the tour's caption panel, the
/// two-body scene's header, and the patch test's verdict on its status line — NTS at 2:3
/// fails it (error above 1e-3), mortar at 2:3 passes (≤ 1e-10), matching meshes give NTS
/// round-off.
#[test]
fn a_two_body_step_renders_its_scene_and_the_patch_verdict_at_80x24() {
    let tour = tour(
        &[
            patch_step("NTS at 2:3", "contact = \"nts\"\nratio = [2, 3]\nlevel = 2"),
            patch_step("Mortar at 2:3", "contact = \"mortar\"\nratio = [2, 3]\nlevel = 2"),
            patch_step(
                "NTS matching",
                "contact = \"nts\"\nratio = [1, 1]\noffset = 0.0\nlevel = 1",
            ),
        ]
        .concat(),
    );
    let bodies = tour.bodies(0).expect("a two-body step");
    assert_eq!(bodies.settings.method, InterfaceMethod::Nts);
    assert_eq!((bodies.settings.ratio, bodies.settings.level), ((2, 3), 2));
    let frames: Vec<String> = (0..3).map(|i| render_step(&tour, i, 80, 24).unwrap()).collect();
    for (i, frame) in frames.iter().enumerate() {
        assert!(frame.contains(&format!("tour {}/3", i + 1)), "{frame}");
        assert!(
            frame.contains(&tour.steps[i].caption),
            "step {}'s caption in\n{frame}",
            i + 1
        );
        let header = frame
            .lines()
            .find(|l| l.starts_with(" riplab · patch-two-blocks · two bodies · "))
            .unwrap_or_else(|| panic!("the two-body header in\n{frame}"));
        let level = tour.bodies(i).unwrap().settings.level;
        assert!(header.contains(&format!("level {level}")), "{header}");
        assert!(frame.lines().all(|l| l.chars().count() <= 80), "{frame}");
    }
    let nts = patch_error(&frames[0], "failed: error");
    assert!(nts > 1e-3, "{nts}\n{}", frames[0]);
    let mortar = patch_error(&frames[1], "passed: error");
    assert!(mortar <= 1e-10, "{mortar}\n{}", frames[1]);
    let matching = patch_error(&frames[2], "passed: error");
    assert!(matching <= 1e-10, "{matching}\n{}", frames[2]);
}

/// A two-body step's `epsilon` sets the penalty (0: the exact multipliers), its `offset`
/// the upper mesh's shift, and a step that leaves them out has its scenario's (mortar).
#[test]
fn a_two_body_step_takes_its_scenario_s_settings_where_it_gives_none() {
    use riplab::contact::interface::solve::Enforcement;
    let tour = tour(
        &[
            patch_step("Own", ""),
            patch_step(
                "Penalty",
                "epsilon = 1e-4\noffset = -0.2\ncontact = \"rip-gauss2\"",
            ),
        ]
        .concat(),
    );
    let own = tour.bodies(0).unwrap();
    let scenario = Scenario::load(&scenarios().join("patch-two-blocks.toml")).unwrap();
    let upper = scenario.upper.as_ref().unwrap();
    assert_eq!(own.settings.method, InterfaceMethod::Mortar);
    assert_eq!(
        (own.settings.ratio, own.settings.offset),
        (upper.ratio, upper.offset)
    );
    assert_eq!(own.settings.enforcement, Enforcement::Exact);
    let penalty = tour.bodies(1).unwrap();
    assert_eq!(penalty.settings.enforcement, Enforcement::Penalty(1e-4));
    assert_eq!(penalty.settings.offset, -0.2);
    assert_eq!(penalty.settings.method.name(), "rip-gauss2");
    assert!(tour.bodies(0).is_some() && tour.app(0).scenario == Scenario::paper());
}

/// Every key of the one-body lab on a two-body step, and every two-body key on a one-body
/// step, is refused with the file, line, column, key and why; a bad value of a two-body key
/// names what is allowed.
#[test]
fn keys_that_do_not_apply_to_the_step_are_refused_with_their_place() {
    // The step's keys start at line 4: `title = "t"`, a blank line, `[[step]]`, its title.
    let at = |settings: &str| patch_step("s", settings);
    for (line, key) in [
        ("scheme = \"M1\"", "scheme"),
        ("rule = \"gauss2\"", "rule"),
        ("depth = 0.1", "depth"),
        ("method = \"alm\"", "method"),
        ("scene = \"infsup\"", "scene"),
        ("overlays = [\"gap\"]", "overlays"),
        ("friction = \"coulomb\"\nmu = 0.3", "friction"),
        ("refine_edges = 1", "refine_edges"),
    ] {
        let e = error(&at(line));
        assert!(
            e.starts_with("t.toml:6:") && e.contains(&format!("step[1].{key}")),
            "{key}: {e}"
        );
        assert!(
            e.contains("does not apply to a two-body step")
                && e.contains("allowed on a two-body step: title, caption, scenario, contact, ratio, offset, level, epsilon"),
            "{key}: {e}"
        );
    }
    // The first in the file's order is named.
    let e = error(&at(
        "contact = \"nts\"\nlevel = 1\nquantity = \"tau1\"\nelement = \"q2\"",
    ));
    assert!(
        e.starts_with("t.toml:8:") && e.contains("step[1].quantity"),
        "{e}"
    );
    for (line, key) in [
        ("contact = \"nts\"", "contact"),
        ("ratio = [2, 3]", "ratio"),
        ("offset = 0.1", "offset"),
    ] {
        let e = error(&format!("\n[[step]]\ntitle = \"s\"\ncaption = \"c\"\n{line}\n"));
        assert!(
            e.starts_with("t.toml:6:")
                && e.contains(&format!("step[1].{key}"))
                && e.contains("applies to a step whose scenario has two elastic bodies"),
            "{key}: {e}"
        );
    }
    let e = error(&at("contact = \"nts3\""));
    assert!(
        e.starts_with("t.toml:6:11:")
            && e.contains("step[1].contact")
            && e.contains(
                "nts, nts2, mortar, mortar-dual, rip-gauss1, rip-gauss2, rip-trapezoid, rip-simpson"
            ),
        "{e}"
    );
    for ratio in ["[0, 3]", "[2]", "[2, 65]", "[2, 3, 4]"] {
        let e = error(&at(&format!("ratio = {ratio}")));
        assert!(
            e.starts_with("t.toml:6:9:") && e.contains("step[1].ratio") && e.contains("each 1 to 64"),
            "{ratio}: {e}"
        );
    }
    let e = error(&at("ratio = [2.5, 3]"));
    assert!(e.starts_with("t.toml:6:") && e.contains("ratio"), "{e}");
    for offset in ["0.5", "-0.7", "nan"] {
        let e = error(&at(&format!("offset = {offset}")));
        assert!(
            e.starts_with("t.toml:6:10:")
                && e.contains("step[1].offset")
                && e.contains("strictly between -0.5 and 0.5"),
            "{offset}: {e}"
        );
    }
    let e = error(&at("level = 8"));
    assert!(e.contains("step[1].level") && e.contains("0 to 7"), "{e}");
    let e = error(&at("epsilon = -1"));
    assert!(e.contains("step[1].epsilon"), "{e}");
}

/// The scenario of the steps that name none may not have two bodies (those steps show the
/// one-body lab): refused when the tour is given it, naming the step.
#[test]
fn a_two_body_scenario_for_the_steps_that_name_none_is_refused() {
    let patch = Scenario::load(&scenarios().join("patch-two-blocks.toml")).unwrap();
    let e = tour(&[patch_step("Two", ""), ONE_BODY.to_string()].concat())
        .with_scenario(patch.clone())
        .unwrap_err();
    assert!(matches!(e, TourError::TwoBodies { step: 2, .. }), "{e}");
    assert!(e.to_string().contains("has two elastic bodies"), "{e}");
    // Every step naming its own: any scenario will do.
    assert!(tour(&patch_step("Two", "")).with_scenario(patch).is_ok());
}

/// The player goes from a one-body step to a two-body one and back: the two-body step asks
/// the tour's two-body solver for its settings (and the lab nothing), is busy until the
/// answer comes, ignores a late answer of a request it no longer makes, keeps its solve for
/// the next visit, takes the two-body scene's keys, and restores the step when left and
/// entered again; the tour's keys and its notices stay the tour's.
#[test]
fn the_player_goes_between_one_body_and_two_body_steps() {
    let tour = tour(
        &[
            ONE_BODY.to_string(),
            patch_step("NTS", "contact = \"nts\"\nlevel = 1"),
            ONE_BODY.to_string(),
        ]
        .concat(),
    );
    let mut player = TourApp::new(tour.clone(), None);
    assert!(player.bodies.is_none());
    let effect = player.update(key(KeyCode::Char(' ')));
    assert!(effect.step_changed && effect.commands.is_empty(), "{effect:?}");
    let (generation, settings) = effect.bodies.expect("the two-body solve is asked for");
    assert_eq!(settings.method, InterfaceMethod::Nts);
    assert!(player.is_busy() && player.is_pristine());
    let mut cache = BodiesCache::new(tour.scenario_of(1).clone());
    let solved = cache.solve(&settings, &|| false);
    assert!(
        !player.bodies_reply(generation + 1, cache.solve(&settings, &|| false)),
        "a reply nobody asked for"
    );
    assert!(player.bodies_reply(generation, solved));
    assert!(!player.is_busy());
    // The scene's keys: `n` the next discretisation, solved anew.
    let effect = player.update(key(KeyCode::Char('n')));
    let (newer, next) = effect.bodies.expect("a new solve");
    assert!(newer > generation && next.method == InterfaceMethod::Nts2);
    assert!(!player.is_pristine() && player.is_busy());
    // The old answer arrives late: not the scene's.
    assert!(!player.bodies_reply(generation, cache.solve(&settings, &|| false)));
    // A one-body step: the lab asks for its solve, the two-body scene is gone.
    let effect = player.update(key(KeyCode::Char(' ')));
    assert!(player.bodies.is_none() && effect.bodies.is_none());
    assert!(effect.commands.iter().any(|c| matches!(c, Command::Solve(_))));
    assert_eq!(player.app.settings, tour.app(2).settings);
    // Back: the step's own settings, its solve kept and shown at once.
    let effect = player.update(key(KeyCode::Left));
    assert!(effect.bodies.is_none(), "the kept solve needs none: {effect:?}");
    assert!(player.is_pristine() && !player.is_busy());
    let bodies = player.bodies.as_ref().unwrap();
    assert!(bodies.solved.as_ref().is_some_and(|s| s.settings == settings));
    // The tour's keys stay the tour's, its notices on the two-body scene's status line.
    player.update(key(KeyCode::Char('q')));
    assert!(!player.should_quit());
    let said = player
        .bodies
        .as_ref()
        .and_then(|b| b.notice.clone())
        .map(|n| n.text)
        .unwrap_or_default();
    assert!(said.contains("q again ends the tour"), "{said}");
    player.update(key(KeyCode::Char('?')));
    assert!(player.show_help);
    player.update(key(KeyCode::Esc));
    player.update(key(KeyCode::Home));
    assert!(player.bodies.is_none() && player.index() == 0);
}

/// The embedded tour ends on the contact patch test (docs/design.md §12): NTS on matching
/// meshes passes, NTS at 2:3 fails (error above 1e-3), mortar at 2:3 passes (≤ 1e-10), and a
/// reduced-integration rule at 2:3 follows with p̄ by (17) — each verdict read from the status
/// line at 80×24.
#[test]
fn the_paper_tour_ends_on_the_contact_patch_test() {
    let tour = Tour::paper();
    let first = (0..tour.steps.len())
        .find(|&i| tour.bodies(i).is_some())
        .expect("two-body steps");
    assert!(
        (first..tour.steps.len()).all(|i| tour.bodies(i).is_some()),
        "at the end"
    );
    let shown: Vec<(String, (u32, u32), f64, String)> = (first..tour.steps.len())
        .map(|i| {
            let s = tour.bodies(i).unwrap().settings;
            assert!(s.level <= 3, "step {}: level {} solves fast", i + 1, s.level);
            (
                s.method.name().to_string(),
                s.ratio,
                s.offset,
                render_step(&tour, i, 80, 24).unwrap(),
            )
        })
        .collect();
    let [nts_matching, nts, mortar, rip, ..] = &shown[..] else {
        panic!("four two-body steps at least");
    };
    assert_eq!(
        (nts_matching.0.as_str(), nts_matching.1, nts_matching.2),
        ("nts", (1, 1), 0.0)
    );
    assert!(
        patch_error(&nts_matching.3, "passed: error") <= 1e-10,
        "{}",
        nts_matching.3
    );
    assert_eq!((nts.0.as_str(), nts.1), ("nts", (2, 3)));
    assert!(patch_error(&nts.3, "failed: error") > 1e-3, "{}", nts.3);
    assert_eq!((mortar.0.as_str(), mortar.1), ("mortar", (2, 3)));
    assert!(patch_error(&mortar.3, "passed: error") <= 1e-10, "{}", mortar.3);
    assert!(
        rip.0.starts_with("rip-") && rip.1 == (2, 3),
        "{:?}",
        (&rip.0, rip.1)
    );
    assert!(rip.3.contains("patch test "), "{}", rip.3);
}

/// `--check`'s listing names a two-body step's scene, level, element with the ratio and its
/// discretisation; a handout writes its screen (with its caption and the two-body header), no
/// chart, and an index line of its settings.
#[test]
fn listing_and_handout_include_two_body_steps() {
    use riplab::tui::tour::handout::write_handout;
    use riplab::tui::tour::listing::listing;
    let tour = tour(
        &[
            ONE_BODY.to_string(),
            patch_step(
                "NTS",
                "contact = \"nts\"\nratio = [2, 3]\nlevel = 1\nepsilon = 1e-4",
            ),
        ]
        .concat(),
    );
    let list = listing(&tour);
    let row: Vec<&str> = list
        .lines()
        .find(|l| l.contains("two-bodies"))
        .unwrap_or_else(|| panic!("{list}"))
        .split_whitespace()
        .collect();
    assert_eq!(row[..6], ["2", "two-bodies", "1", "q1", "2:3", "nts"], "{list}");
    let dir = std::env::temp_dir().join(format!("riplab-tour-bodies-handout-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let files = write_handout(&tour, &dir, 80, 24, |_, _| {}).unwrap();
    let names: Vec<String> = files
        .iter()
        .map(|f| f.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["step-01.txt", "step-01.svg", "step-02.txt", "index.md"]);
    let screen = std::fs::read_to_string(dir.join("step-02.txt")).unwrap();
    assert!(
        screen.contains(" riplab · patch-two-blocks · two bodies · q1 level 1 · ε = 1e-4")
            && screen.contains("The caption of NTS."),
        "{screen}"
    );
    let index = std::fs::read_to_string(dir.join("index.md")).unwrap();
    assert!(
        index.contains(
            "Scene two bodies · patch-two-blocks · q1 at level 1 · nts · ratio 2:3 · offset 0 · penalty, ε = 0.0001"
        ) && index.contains("- chart: none: the two-body scene's interface pressure is on its screen"),
        "{index}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The refusal's words, as `tour --check` prints them (STABILITY.md quotes them).
#[test]
fn a_one_body_key_on_a_two_body_step_is_refused_in_these_words() {
    let e = error(&patch_step("s", "scheme = \"M1\""));
    assert_eq!(
        e,
        "t.toml:6:10: `step[1].scheme`: does not apply to a two-body step (its scenario has an elastic [upper] body): the bodies' element is their scenario's ([mesh] element), and a rip rule is chosen by contact (rip-gauss1, rip-gauss2, rip-trapezoid, rip-simpson); allowed on a two-body step: title, caption, scenario, contact, ratio, offset, level, epsilon\n    6 | scheme = \"M1\"\n      |          ^"
    );
}

/// Tab on a two-body step keeps the step's pressure view and says where the inf-sup view is:
/// the tour's worker solves steps, it does not estimate (the view would wait for ever).
#[test]
fn tab_on_a_two_body_step_stays_on_the_pressure() {
    let tour = tour(
        &[
            ONE_BODY.to_string(),
            patch_step("NTS", "contact = \"nts\"\nlevel = 1"),
        ]
        .concat(),
    );
    let mut player = TourApp::new(tour, None);
    player.update(key(KeyCode::Char(' ')));
    for code in [KeyCode::Tab, KeyCode::BackTab] {
        let effect = player.update(key(code));
        assert!(
            effect.bodies.is_none() && effect.commands.is_empty(),
            "{effect:?}"
        );
        let bodies = player.bodies.as_ref().expect("the two-body step");
        assert_eq!(bodies.shown, riplab::tui::bodies::BodiesView::Pressure);
        let said = &bodies.notice.as_ref().expect("a notice").text;
        assert!(said.contains("inf-sup view"), "{said}");
    }
}

/// A two-body step at 80×24 keeps the pressure chart's rows for its reference line: the
/// applied pressure is drawn (not "no room"), the meshes' panel left out when the caption takes
/// its rows.
#[test]
fn a_two_body_step_at_80x24_draws_the_applied_pressure() {
    let tour = riplab::tui::tour::Tour::paper();
    let last = tour.steps.len() - 1;
    for index in last - 3..=last {
        let text = riplab::tui::tour::render_step(&tour, index, 80, 24).unwrap();
        assert!(
            text.contains("─ applied 5.348") && !text.contains("no room"),
            "step {index}:\n{text}"
        );
    }
}
