//! With edge grading on (`E`), the convergence scene's study
//! computes each scheme's graded series beside its uniform one — the numbers `riplab study
//! --refine-edges 0,N` gives — level by level as the uniform rows, and the chart draws every
//! series (the graded ones marked `a`–`d`) near each of its values at every size.

use std::sync::{Arc, OnceLock};

use riplab::contact::Rule;
use riplab::grading::{Grading, RefineEdges};
use riplab::scenario::Scenario;
use riplab::study::Errors;
use riplab::study::{Plan, Status, StudyRow};
use riplab::tui::app::{App, Compare, Msg, Scene, Study, StudyKey};
use riplab::tui::engine::Engine;
use riplab::tui::render_app;
use riplab::tui::theme::Theme;
use riplab::tui::view::Look;

const LOOK: Look = Look {
    theme: Theme { color: false },
    marker: ratatui::symbols::Marker::Braille,
};

/// The paper's app on the convergence scene with `refine` set (timings hidden).
fn graded_app(refine: impl Into<Grading>) -> App {
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.scene = Scene::Convergence;
    app.settings.refine_edges = refine.into();
    app
}

/// The study the app's key asks for at `refine`, on the real engine, with `max_level`.
fn key_of(refine: impl Into<Grading>, max_level: u32) -> StudyKey {
    let mut key = graded_app(refine).study_key();
    key.max_level = max_level;
    key
}

/// The rows of `rows` of one series (scheme, method, grading) in level order.
fn series<'a>(rows: &'a [StudyRow], of: &StudyRow) -> Vec<&'a StudyRow> {
    rows.iter().filter(|r| r.same_series(of)).collect()
}

/// The lab's graded study at levels 0 to 2 equals `riplab study --levels 0..2 --refine-edges
/// 0,2 --reference-level 3 --reference-refinements 0` (the library call the command makes) at
/// the lab's ε and method: the same rows, each error to 1e-12 (times are not compared), the
/// graded rows labelled `2+2e` with the graded mesh's unknowns; the lab orders them per scheme,
/// uniform then graded, and hands over each level's uniform rows, then its graded rows.
#[test]
fn the_labs_graded_study_is_riplab_studys() {
    let scenario = Scenario::paper();
    let key = key_of(RefineEdges::Passes(2), 2);
    assert_eq!(
        key.gradings(),
        [Grading::default(), RefineEdges::Passes(2).into()]
    );
    assert_eq!(key.label(), "M1–M4 (penalty), uniform and +2e");
    let mut partials: Vec<Arc<Study>> = Vec::new();
    let lab = Engine::new(scenario.clone())
        .studying(&key)
        .unwrap()
        .run_shown(&mut |_| {}, &mut |s| partials.push(s))
        .unwrap();
    let dir = riplab::cache::default_dir();
    let mut fetch = |g: &riplab::study::ReferenceMesh| {
        riplab::cache::fields(&scenario, g, dir.as_deref()).map(|(f, _)| f)
    };
    let cli = riplab::study::study(
        &scenario,
        &key.schemes,
        Some(key.methods[0]),
        Plan::Levels {
            levels: &[0, 1, 2],
            epsilon: key.epsilon,
            refine: &[RefineEdges::Passes(0).into(), RefineEdges::Passes(2).into()],
        },
        (3, 0),
        &mut fetch,
    )
    .unwrap();
    assert_eq!(lab.rows.len(), cli.rows.len());
    assert_eq!(
        lab.rows.len(),
        4 * 3 * 2,
        "M1–M4, levels 0 to 2, uniform and graded"
    );
    for (a, b) in lab.rows.iter().zip(&cli.rows) {
        let what = format!("{} {}", a.scheme, a.level_label());
        assert_eq!(
            (&a.scheme, a.level_label(), a.n_dofs, a.status),
            (&b.scheme, b.level_label(), b.n_dofs, b.status),
            "{what}"
        );
        assert_eq!(a.status, Status::Ok, "{what}: {:?}", a.reason);
        let (e, f) = (a.errors.unwrap(), b.errors.unwrap());
        for (x, y, name) in [
            (e.p, f.p, "p"),
            (e.pbar, f.pbar, "p̄"),
            (e.u, f.u, "u"),
            (e.load, f.load, "load"),
        ] {
            assert!((x - y).abs() <= 1e-12 * y.abs(), "{what}: {name} {x} against {y}");
        }
    }
    // Graded: two passes at every level, on more unknowns than the uniform level.
    let m1 = &lab.rows[0];
    let graded = series(&lab.rows, &lab.rows[3]);
    assert!(
        graded
            .iter()
            .all(|r| r.grading == RefineEdges::Passes(2).into() && r.refine_edges == 2)
    );
    assert_eq!(graded[2].level_label(), "2+2e");
    let uniform = series(&lab.rows, m1);
    assert!(
        uniform
            .iter()
            .zip(&graded)
            .all(|(u, g)| g.n_dofs > u.n_dofs && g.h_min == u.h_min / 4.0)
    );
    // Progressively: level 0's uniform rows, then its graded ones, and so on.
    let counts: Vec<(usize, usize)> = partials
        .iter()
        .map(|s| {
            let graded = s.rows.iter().filter(|r| r.grading.grades()).count();
            (s.rows.len() - graded, graded)
        })
        .collect();
    assert_eq!(counts, [(4, 0), (4, 4), (8, 4), (8, 8), (12, 8)]);
}

/// The cells right of the y axis in the rows of the chart whose title starts with `title`
/// (the graph, without legend, tick labels or borders).
fn graph_rows(frame: &str, title: &str) -> Vec<String> {
    let lines: Vec<&str> = frame.lines().collect();
    let top = lines
        .iter()
        .position(|l| l.starts_with(&format!("┌ {title}")))
        .unwrap_or_else(|| panic!("no chart `{title}` in\n{frame}"));
    let mut out = Vec::new();
    for line in &lines[top + 1..] {
        if line.starts_with('└') {
            break;
        }
        let chars: Vec<char> = line.chars().collect();
        let Some(axis) = chars[1..]
            .iter()
            .position(|&c| c == '┤' || c == '│')
            .map(|i| i + 1)
        else {
            continue;
        };
        if axis + 1 < chars.len() && !chars[axis + 1..].contains(&'└') {
            out.push(chars[axis + 1..chars.len() - 1].iter().collect());
        }
    }
    out
}

/// The paper's lab with one edge-grading pass on the convergence scene, its study (levels 0 to
/// 4, uniform and +1e) run once on the real engine for every test that draws it.
fn settled_graded() -> App {
    static STUDY: OnceLock<Arc<Study>> = OnceLock::new();
    let mut app = graded_app(RefineEdges::Passes(1));
    let key = app.study_key();
    let study = STUDY.get_or_init(|| Engine::new(Scenario::paper()).study(&key, &mut |_| {}).unwrap());
    app.studies.insert(key, Ok(study.clone()));
    app
}

/// Every series the legend names — M1–M4 uniform (`1`–`4`) and graded (`a`–`d`) —
/// has a mark near each of its five levels at every size from 80×24 to 200×60, without colour;
/// the legend names the graded ones `M1+1e p̄` …, and the table pairs each uniform row with
/// its graded row (`4` beside `4+1e`).
#[test]
fn every_graded_series_is_drawn_at_every_size() {
    let mut app = settled_graded();
    crate::tui::tests::steady_times(&mut app);
    assert!(
        app.clone().update(Msg::Resize).commands.is_empty(),
        "the study is there"
    );
    for (w, h) in [(80, 24), (100, 30), (120, 40), (200, 60)] {
        let frame = render_app(&app, &LOOK, w, h);
        let graph = graph_rows(&frame, "work–precision");
        for glyph in ['1', '2', '3', '4', 'a', 'b', 'c', 'd'] {
            let n = graph
                .iter()
                .flat_map(|r| r.chars())
                .filter(|&c| c == glyph)
                .count();
            assert!(n >= 5, "{glyph} {n} times at {w}×{h}\n{frame}");
        }
        for name in ["M1 p̄", "a M1+1e p̄", "b M2+1e p̄", "c M3+1e p̄", "d M4+1e p̄"] {
            assert!(frame.contains(name), "legend `{name}` at {w}×{h}\n{frame}");
        }
        assert!(frame.contains("uniform and +1e"), "{frame}");
        let paired = frame.lines().find(|l| l.contains(" M4 ") && l.contains(" 4+1e "));
        assert!(paired.is_some(), "M4's level 4 beside 4+1e at {w}×{h}\n{frame}");
    }
}

/// A made-up row (fixed numbers, so that frames are deterministic): `scheme` with `method` at
/// `level`, graded by `refine` (`passes` made), its p̄ error `pbar` in `ms`.
fn row(
    scheme: &str,
    method: riplab::contact::Method,
    level: u32,
    refine: Grading,
    ms: f64,
    pbar: f64,
) -> StudyRow {
    let passes = match refine {
        Grading::Edges(RefineEdges::Passes(n)) | Grading::Zone(n) => n,
        Grading::Edges(RefineEdges::Auto) => 3,
    };
    let h = 1.0 / f64::from(1 << level);
    StudyRow {
        scheme: scheme.into(),
        element: riplab::mesh::Element::Q1,
        rule: "gauss1",
        level,
        h,
        epsilon: 1e-6,
        method: method.into(),
        n_dofs: [90, 306, 1122][level as usize] + 40 * passes as usize,
        refine_edges: passes,
        h_min: h / f64::from(1 << passes),
        grading: refine,
        status: Status::Ok,
        reason: None,
        epsilon_dominated: false,
        newton_iterations: Some(3),
        outer_iterations: None,
        converged: true,
        solve_ms: Some(ms),
        load: Some(1.0),
        errors: Some(Errors {
            p: 2.0 * pbar,
            pbar,
            u: pbar / 2.0,
            load: pbar,
            tbar: None,
            tangential_load: None,
        }),
        rates: None,
        warnings: Vec::new(),
    }
}

/// The app on the convergence scene at level 2 with a made-up study of `key`'s schemes (or
/// methods) at levels 0 to 2, uniform and graded as `refine`; `kernel` names a method without
/// an answer.
fn made_up(compare: Compare, refine: impl Into<Grading>, kernel: Option<&str>) -> App {
    let mut app = graded_app(refine);
    app.compare = compare;
    app.settings.level = 2;
    if compare == Compare::Methods {
        app.settings.rule = Rule::Gauss2;
    }
    let key = app.study_key();
    let mut rows = Vec::new();
    let names: Vec<(String, riplab::contact::Method)> = match compare {
        Compare::Schemes => ["M1", "M2", "M3", "M4"]
            .iter()
            .map(|s| (s.to_string(), key.methods[0]))
            .collect(),
        Compare::Methods => key.methods.iter().map(|&m| ("M2".to_string(), m)).collect(),
    };
    for (i, (scheme, method)) in names.iter().enumerate() {
        for grading in key.gradings() {
            for level in 0..=2u32 {
                let f = f64::from(1 << level) * (1.0 + 0.15 * i as f64);
                let (ms, pbar) = match grading.grades() {
                    false => (2.0 * f * f, 0.2 / f),
                    true => (3.0 * f * f, 0.08 / f),
                };
                let mut r = row(scheme, *method, level, grading, ms, pbar);
                if kernel == Some(method.name()) {
                    r.status = Status::Kernel;
                    r.reason = Some(
                        "ε = 0 imposes the constraint exactly at more points than normal displacements"
                            .into(),
                    );
                    r.errors = None;
                    r.solve_ms = None;
                }
                rows.push(r);
            }
        }
    }
    app.studies.insert(key.clone(), Ok(Arc::new(Study { key, rows })));
    app
}

/// The graded chart and table at 80×24, schemes with `E` at two passes and the methods on M2
/// with `auto`: the legend keeps to its two rows (every entry whole); `exact` has no answer on
/// gauss2 and says so once in the legend (its graded series adds no entry) and in both halves
/// of the table.
#[test]
fn graded_convergence_80x24() {
    let schemes = made_up(Compare::Schemes, RefineEdges::Passes(2), None);
    let text = render_app(&schemes, &LOOK, 80, 24);
    for name in ["M1 p (raw)", "⠒1⠒ M1 p̄", "a M1+2e p̄", "⠒4⠒ M4 p̄", "d M4+2e p̄"] {
        assert!(text.contains(name), "`{name}` in\n{text}");
    }
    snap!("tui__convergence_graded_80x24", text);
    let methods = made_up(Compare::Methods, RefineEdges::Auto, Some("exact"));
    let text = render_app(&methods, &LOOK, 80, 24);
    for name in [
        "P⠒ penalty p̄",
        "p penalty+auto p̄",
        "e exact+auto",
        "⠒E⠒ exact: kernel",
    ] {
        assert_eq!(text.contains(name), name != "e exact+auto", "`{name}` in\n{text}");
    }
    assert!(text.contains("kernel            │ 2+3e"), "{text}");
    snap!("tui__convergence_graded_methods_80x24", text);
}

/// With zone grading (`3z`) the graded series read `M1+3z p̄` in the legend and `2+3z` in the
/// table.
#[test]
fn zone_graded_convergence_80x24() {
    let app = made_up(Compare::Schemes, Grading::Zone(3), None);
    let text = render_app(&app, &LOOK, 80, 24);
    for name in ["a M1+3z p̄", "d M4+3z p̄", "2+3z"] {
        assert!(text.contains(name), "`{name}` in\n{text}");
    }
    assert!(!text.contains("+3e"), "{text}");
}

/// `E` on the convergence scene asks for a study that differs from the last only in its
/// grading: the engine keeps the uniform rows (their very times) and solves the graded ones.
#[test]
fn an_e_press_on_the_convergence_scene_solves_only_the_graded_rows() {
    let engine = Engine::new(Scenario::paper());
    let uniform = engine
        .study(&key_of(RefineEdges::default(), 1), &mut |_| {})
        .unwrap();
    assert!(uniform.rows.iter().all(|r| !r.grading.grades()));
    let graded = engine
        .study(&key_of(RefineEdges::Passes(1), 1), &mut |_| {})
        .unwrap();
    let kept: Vec<&StudyRow> = graded.rows.iter().filter(|r| !r.grading.grades()).collect();
    assert_eq!(kept.len(), uniform.rows.len());
    for (a, b) in kept.iter().zip(&uniform.rows) {
        assert_eq!((a.level, &a.scheme, a.solve_ms), (b.level, &b.scheme, b.solve_ms));
    }
    assert_eq!(graded.rows.len(), 2 * uniform.rows.len());
}

/// `E` on the convergence scene asks for the study with the new grading (its uniform rows the
/// engine keeps, above), and the scene says what it computes.
#[test]
fn e_on_the_convergence_scene_asks_for_the_graded_study() {
    use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
    use riplab::tui::app::Command;
    let mut app = graded_app(RefineEdges::default());
    let studies = |commands: Vec<Command>| -> Vec<StudyKey> {
        commands
            .into_iter()
            .filter_map(|c| match c {
                Command::Study(r) => Some(r.key),
                _ => None,
            })
            .collect()
    };
    let first = studies(app.update(Msg::Resize).commands);
    assert_eq!(first.len(), 1);
    assert_eq!(first[0].refine_edges, Grading::default());
    let e = Msg::Key(KeyEvent::new(KeyCode::Char('E'), KeyModifiers::NONE));
    let graded = studies(app.update(e).commands);
    assert_eq!(graded.len(), 1, "{graded:?}");
    assert_eq!(graded[0].refine_edges, RefineEdges::Passes(1).into());
    assert_eq!(graded[0].ungraded(), first[0]);
    app.notice = None;
    let text = render_app(&app, &LOOK, 80, 24);
    assert!(
        text.contains("then M1–M4 (penalty), uniform and +1e") && text.contains("at levels 0 to 4…"),
        "{text}"
    );
}
