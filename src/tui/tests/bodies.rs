//! The lab's two-body scene (docs/lab.md, "Two bodies"; docs/design.md §12): on the contact
//! patch test at a ratio where the meshes do not match, mortar's pressure drawn flat and
//! node-to-segment's oscillating; the keys for the discretisation, the ratio and the offset;
//! the one-body keys refused with their reason, and the two-body keys in a one-body lab.

use std::collections::BTreeSet;
use std::path::Path;

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::symbols::Marker;
use riplab::contact::interface::InterfaceMethod;
use riplab::scenario::Scenario;
use riplab::tui::bodies::view::{FAILS, PASSES};
use riplab::tui::bodies::{BodiesApp, settle_bodies, view};
use riplab::tui::bodies_solve::Settings;
use riplab::tui::theme::Theme;
use riplab::tui::view::Look;

const PATCH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/patch-two-blocks.toml");

const LOOK: Look = Look {
    theme: Theme { color: false },
    marker: Marker::Braille,
};

/// The patch scenario's scene with `method`, settled after `keys` (characters).
fn patch(method: InterfaceMethod, keys: &str) -> BodiesApp {
    let scenario = Scenario::load(Path::new(PATCH)).unwrap();
    let mut app = BodiesApp::new(scenario, method).expect("two bodies");
    settle_bodies(&mut app, &keys.chars().map(key).collect::<Vec<_>>()).unwrap();
    app
}

fn key(c: char) -> KeyEvent {
    KeyEvent::new(KeyCode::Char(c), KeyModifiers::NONE)
}

/// The frame at 80×24, monochrome.
fn frame(app: &BodiesApp) -> String {
    riplab::tui::render_frame(80, 24, |f| view::view(app, f, &LOOK))
}

/// The patch error the scene solved.
fn patch_error(app: &BodiesApp) -> f64 {
    app.solved
        .as_ref()
        .expect("solved")
        .patch
        .expect("the patch test")
        .1
}

/// The rows of the chart's graph (right of its y axis: not the legend) on which p's `•`
/// marks are drawn.
fn marked_rows(frame: &str) -> BTreeSet<usize> {
    frame
        .lines()
        .enumerate()
        .filter(|(_, line)| {
            let inner = line.strip_prefix('│').unwrap_or("");
            let label = inner.trim_start_matches(|c: char| c.is_ascii_digit() || ".-e ".contains(c));
            label.starts_with(['┤', '│']) && label.contains('•')
        })
        .map(|(i, _)| i)
        .collect()
}

/// Switching from mortar to one-pass NTS (`n` six times) at the patch scenario's 2:3 changes
/// the drawn pressure from flat (every p mark on one row; patch error ≤ 1e-10, stated on the
/// status line) to oscillating (marks on several rows; patch error > 1e-3, stated). At 1:1
/// (`k`) NTS is flat again, and the offset (`J`) breaks it.
#[test]
fn mortar_draws_flat_and_nts_oscillates_on_non_matching_meshes() {
    let mortar = patch(InterfaceMethod::Mortar, "");
    assert_eq!(mortar.settings.ratio, (2, 3));
    assert!(patch_error(&mortar) <= PASSES, "{}", patch_error(&mortar));
    let flat = frame(&mortar);
    assert!(
        flat.contains("patch test passed: error < 1e-12 (≤ 1e-10)"),
        "{flat}"
    );
    assert_eq!(marked_rows(&flat).len(), 1, "{flat}");
    snap!("bodies_patch_mortar_2_3_80x24", &flat);

    let nts = patch(InterfaceMethod::Mortar, "nnnnnn");
    assert_eq!(nts.settings.method, InterfaceMethod::Nts);
    assert!(patch_error(&nts) > FAILS, "{}", patch_error(&nts));
    let wavy = frame(&nts);
    assert!(wavy.contains("patch test failed: error 0.1 (> 1e-3)"), "{wavy}");
    assert!(marked_rows(&wavy).len() >= 2, "{wavy}");
    snap!("bodies_patch_nts_2_3_80x24", &wavy);

    let matching = patch(InterfaceMethod::Nts, "k");
    assert_eq!(matching.settings.ratio, (1, 1));
    assert!(patch_error(&matching) <= PASSES, "{}", patch_error(&matching));
    assert_eq!(marked_rows(&frame(&matching)).len(), 1);
    let shifted = patch(InterfaceMethod::Nts, "kJ");
    assert_eq!((shifted.settings.ratio, shifted.settings.offset), ((1, 1), 0.1));
    assert!(patch_error(&shifted) > FAILS, "{}", patch_error(&shifted));
    assert!(marked_rows(&frame(&shifted)).len() >= 2);
}

/// p̄ is drawn for the reduced-integration rules (a solid line, named in the legend) and the
/// applied pressure as the reference line on every method.
#[test]
fn rip_draws_p_bar_beside_p() {
    let rip = patch(InterfaceMethod::Rip(riplab::contact::Rule::Gauss2), "");
    let text = frame(&rip);
    assert!(
        text.contains("p̄ smoothed (17)") && text.contains("p rip-gauss2"),
        "{text}"
    );
    assert!(text.contains("─ applied 5.348"), "{text}");
    let mortar = frame(&patch(InterfaceMethod::Mortar, ""));
    assert!(
        !mortar.contains("p̄") && mortar.contains("─ applied 5.348"),
        "{mortar}"
    );
    // The applied line the legend names stands on the chart, beside p and p̄: gauss1's p̄,
    // 0.87 % under it, covered it cell for cell at ±25 % (under a row apart).
    for text in [
        frame(&patch(InterfaceMethod::Rip(riplab::contact::Rule::Gauss1), "")),
        mortar,
    ] {
        // A graph row: the frame's `│`, a tick label (digits) or none, the y axis (`│`, `┤`).
        let graph = |l: &str| -> Option<String> {
            let rest = l.strip_prefix('│')?;
            let axis = rest.find(['│', '┤'])?;
            let label = &rest[..axis];
            label
                .chars()
                .all(|c| c.is_ascii_digit() || " .-e".contains(c))
                .then(|| rest[axis..].chars().skip(1).collect())
        };
        let drawn = text.lines().filter_map(graph).any(|row| row.contains('─'));
        assert!(drawn, "no applied line on the chart:\n{text}");
    }
}

/// `n` cycles every discretisation, `k`/`K` the ratios (the scenario's among them), `j`/`J`
/// the offset by tenths within ±0.4, `←`/`→` the level, `0` resets; each change asks for a
/// solve of the new settings, with a new generation.
#[test]
fn the_two_body_keys_change_what_is_solved() {
    let scenario = Scenario::load(Path::new(PATCH)).unwrap();
    let mut app = BodiesApp::new(scenario, InterfaceMethod::Mortar).unwrap();
    let mut seen = Vec::new();
    for _ in InterfaceMethod::ALL {
        let (_, request) = app.key(key('n'));
        seen.push(request.expect("a solve").1.method);
    }
    assert_eq!(seen.last(), Some(&InterfaceMethod::Mortar));
    assert!(InterfaceMethod::ALL.iter().all(|m| seen.contains(m)), "{seen:?}");
    let ratios: Vec<(u32, u32)> = (0..4).map(|_| app.key(key('K')).1.unwrap().1.ratio).collect();
    assert_eq!(ratios, [(3, 4), (5, 7), (1, 1), (2, 3)]);
    assert_eq!(app.key(key('k')).1.unwrap().1.ratio, (1, 1));
    for _ in 0..4 {
        app.key(key('J'));
    }
    assert!((app.settings.offset - 0.4).abs() < 1e-12);
    let (_, request) = app.key(key('J'));
    assert!(request.is_none(), "0.5 is out of range");
    assert!(app.notice.as_ref().unwrap().text.contains("|offset| < 1/2"));
    for _ in 0..8 {
        app.key(key('j'));
    }
    assert!((app.settings.offset + 0.4).abs() < 1e-12);
    let right = KeyEvent::new(KeyCode::Right, KeyModifiers::NONE);
    let (_, request) = app.key(right);
    assert_eq!(request.unwrap().1.level, 2);
    let generation = app.generation;
    let (_, request) = app.key(key('0'));
    let (g, settings): (u64, Settings) = request.unwrap();
    assert_eq!((g, settings), (generation + 1, app.initial));
    // A reply of an older generation is not shown.
    assert!(!app.reply(
        generation,
        Err(riplab::contact::interface::solve::BodiesError::OneBody)
    ));
    assert!(app.error.is_none());
}

/// Every one-body key says why it does not act on two bodies and changes nothing: the rule,
/// ε, the method, the depth, the one-body scenes, the overlays, friction, grading, exports,
/// the cursor.
#[test]
fn one_body_keys_are_refused_with_their_reason() {
    let scenario = Scenario::load(Path::new(PATCH)).unwrap();
    let mut app = BodiesApp::new(scenario, InterfaceMethod::Mortar).unwrap();
    let before = app.settings;
    for (c, reason) in [
        ('r', "n cycles the interface's discretisation"),
        ('1', "n cycles"),
        ('e', "scenario's element"),
        ('+', "scenario's ε"),
        ('m', "scenario's ε"),
        ('d', "[upper] displacement"),
        ('w', "need one body"),
        ('a', "every level up to the current one"),
        ('g', "reference line"),
        ('F', "friction"),
        ('E', "grading"),
        ('s', "riplab solve --format json"),
        ('T', "riplab solve --format json"),
        ('x', "not in the two-body scene"),
        ('f', "not in the two-body scene"),
        ('l', "not in the two-body scene"),
    ] {
        let (redraw, request) = app.key(key(c));
        assert!(redraw && request.is_none(), "{c}");
        let said = &app.notice.as_ref().expect("a notice").text;
        assert!(
            said.starts_with(&format!("{c}: ")) && said.contains(reason),
            "{c}: {said}"
        );
    }
    assert_eq!(app.settings, before);
}

/// The scene's key bar and help are read from the lab's key table: the bar's keys fit 80
/// columns, and the help lists the scene's rows first.
#[test]
fn the_bar_and_help_come_from_the_key_table() {
    let bar = riplab::tui::key_bar::bodies_bar();
    let words: Vec<&str> = bar.iter().map(|e| e.1).collect();
    assert_eq!(
        words,
        [
            "level", "contact", "ratio", "offset", "inf-sup", "reset", "help", "quit"
        ]
    );
    assert_eq!((bar[1].0.as_str(), bar[4].0.as_str()), ("n", "Tab"));
    let help = riplab::tui::key_bar::bodies_help();
    let every = help.iter().position(|l| l.1.starts_with("every key")).unwrap();
    for keys in ["n", "k  K", "j  J", "Tab  Shift-Tab", "0"] {
        assert!(help[..every].iter().any(|l| l.0 == keys), "{keys}: {help:?}");
    }
    let mut app = patch(InterfaceMethod::Mortar, "?");
    let text = frame(&app);
    assert!(text.contains("two bodies: next contact (nts … rip)"), "{text}");
    app.key(key('x'));
    assert!(!app.show_help, "any other key closes the help");
}

/// The lab on one body says that the two-body keys act on two bodies, naming a scenario.
#[test]
fn a_one_body_lab_refuses_the_two_body_keys() {
    let mut app = super::settled(0, riplab::tui::app::Scene::Explore);
    for c in ['n', 'k', 'K', 'j', 'J'] {
        let _ = app.update(riplab::tui::app::Msg::Key(key(c)));
        let said = &app.notice.as_ref().expect("a notice").text;
        assert!(
            said.contains("acts on two bodies") && said.contains("patch-two-blocks"),
            "{said}"
        );
    }
}

/// The key table drives the two-body scene's dispatch too: every key it binds acts there or
/// says why not (a notice, the help, a change of settings, quitting), none in silence.
#[test]
fn every_key_of_the_table_answers_in_the_two_body_scene() {
    let scenario = Scenario::load(Path::new(PATCH)).unwrap();
    for row in riplab::tui::keys::LAB {
        for &(code, action) in row.bindings {
            let mut app = BodiesApp::new(scenario.clone(), InterfaceMethod::Mortar).unwrap();
            let before = app.settings;
            let (redraw, _) = app.key(KeyEvent::new(code, KeyModifiers::NONE));
            let answered = app.notice.is_some() || app.show_help || app.quit || app.settings != before;
            assert!(redraw && answered, "{code:?} ({action:?}) answers nothing");
        }
    }
}

/// Off the patch test (two-body Hertz, a zone of a few per cent of the interface) the chart is
/// drawn over the contact zone widened by half its width, and the status line gives the load,
/// the peak and the zone; the patch test's chart spans the whole interface.
#[test]
fn a_hertz_contact_is_drawn_over_its_zone() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-two-bodies.toml");
    let scenario = Scenario::load(Path::new(path)).unwrap();
    let mut app = BodiesApp::new(scenario, InterfaceMethod::Mortar).unwrap();
    settle_bodies(&mut app, &[]).unwrap();
    let solved = app.solved.as_ref().expect("solved");
    let [a, b] = solved.zone().expect("in contact");
    let drawn = view::x_bounds(solved);
    assert_eq!(drawn[0], solved.x_range[0]);
    assert!(
        drawn[1] >= b && drawn[1] < 0.5 * solved.x_range[1],
        "{drawn:?}, zone {a}..{b}"
    );
    let text = frame(&app);
    assert!(
        text.contains("mortar: load P = ") && text.contains("· contact 0 to "),
        "{text}"
    );
    let patch = patch(InterfaceMethod::Nts, "");
    let solved = patch.solved.as_ref().unwrap();
    assert_eq!(view::x_bounds(solved), solved.x_range);
}
