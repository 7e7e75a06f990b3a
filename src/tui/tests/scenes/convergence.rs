//! The convergence scene: studies of the schemes and of the methods.

use super::*;

// ---- convergence scene -----------------------------------------------------------------

/// A row of a made-up study (fixed timings, so that frames are deterministic).
#[allow(clippy::too_many_arguments)]
fn row(scheme: &str, level: u32, n_dofs: usize, ms: f64, p: f64, pbar: f64, u: f64) -> StudyRow {
    StudyRow {
        scheme: scheme.into(),
        element: riplab::mesh::Element::Q1,
        rule: "gauss1",
        level,
        h: 1.0 / f64::from(1 << level),
        epsilon: 1e-6,
        method: riplab::contact::Method::Penalty.into(),
        n_dofs,
        refine_edges: 0,
        h_min: 1.0 / f64::from(1 << level),
        grading: Default::default(),
        status: Status::Ok,
        reason: None,
        epsilon_dominated: false,
        newton_iterations: Some(3),
        outer_iterations: None,
        converged: true,
        solve_ms: Some(ms),
        load: Some(1.0),
        errors: Some(Errors {
            p,
            pbar,
            u,
            load: pbar,
            tbar: None,
            tangential_load: None,
        }),
        rates: None,
        warnings: Vec::new(),
    }
}

/// The paper's app on the convergence scene at level 2 with a made-up study of levels 0..=2.
pub(super) fn convergence_app() -> App {
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.scene = Scene::Convergence;
    app.settings.level = 2;
    let key = app.study_key();
    // Levels 0 to 4 from the first look (this made-up study holds 0 to 2).
    assert_eq!(key.max_level, 4);
    let rows = vec![
        row("M1", 0, 90, 2.0, 0.42, 0.12, 0.05),
        row("M1", 1, 306, 6.5, 0.31, 0.045, 0.025),
        row("M1", 2, 1122, 24.0, 0.22, 0.016, 0.0123),
        row("M2", 0, 90, 2.4, 0.9, 0.2, 0.05),
        row("M2", 1, 306, 7.1, 1.3, 0.15, 0.026),
        row("M2", 2, 1122, 27.0, 1.8, 0.11, 0.0125),
        row("M3", 0, 90, 1.8, 0.15, 0.1, 0.048),
        row("M3", 1, 306, 6.0, 0.07, 0.04, 0.024),
        row("M3", 2, 1122, 22.0, 0.0345, 0.0149, 0.012),
        row("M4", 0, 306, 5.2, 0.05, 0.03, 0.01),
        row("M4", 1, 1122, 19.0, 0.018, 0.01, 0.0025),
        row("M4", 2, 4290, 80.0, 0.0065, 0.0035, 0.000612),
    ];
    app.studies.insert(key.clone(), Ok(Arc::new(Study { key, rows })));
    app
}

#[test]
fn convergence_80x24() {
    let app = convergence_app();
    assert!(
        app.clone().update(Msg::Resize).commands.is_empty(),
        "a cached study asks for nothing more"
    );
    snap!("tui__convergence_80x24", frame(&app, 80, 24));
}

#[test]
fn convergence_120x40() {
    snap!("tui__convergence_120x40", frame(&convergence_app(), 120, 40));
}

fn studies(commands: &[Command]) -> Vec<StudyRequest> {
    commands
        .iter()
        .filter_map(|c| match c {
            Command::Study(r) => Some(r.clone()),
            _ => None,
        })
        .collect()
}

#[test]
fn convergence_asks_for_one_study_and_caches_it() {
    let mut app = App::new(Scenario::paper());
    app.update(Msg::Resize);
    app.update(key(KeyCode::Tab));
    app.update(key(KeyCode::Tab));
    let cmds = app.update(key(KeyCode::Tab)).commands;
    assert_eq!(app.scene, Scene::Convergence);
    let asked = studies(&cmds);
    assert_eq!(cmds.len(), 1, "only the study: {cmds:?}");
    assert_eq!(asked.len(), 1);
    let req = asked[0].clone();
    assert_eq!(req.key.scenario, app.scenario.name);
    // Levels 0 to 4 from the first look.
    assert_eq!(req.key.max_level, 4);
    assert_eq!(req.key.reference_level(), 5);
    let text = frame(&app, 80, 24);
    assert!(text.contains("computing the reference (q2, level 5)…"), "{text}");
    // Away and back while it runs: not asked again.
    app.update(key(KeyCode::Tab));
    assert!(studies(&app.update(key(KeyCode::BackTab)).commands).is_empty());
    // The study finishes (on the real engine: levels 0 to 4 against the q2 reference at level 5).
    let engine = Engine::new(Scenario::paper());
    let reply = Response::Study {
        generation: req.generation,
        result: Some(engine.study(&req.key, &mut |_| {})),
        key: req.key.clone(),
    };
    assert!(app.update(Msg::Worker(reply)).redraw);
    let Some(Ok(study)) = app.studies.get(&req.key) else {
        panic!("the study is cached: {:?}", app.studies);
    };
    let mut schemes: Vec<&str> = study.rows.iter().map(|r| r.scheme.as_str()).collect();
    assert_eq!(study.rows.len(), 4 * 5, "M1–M4 at levels 0 to 4");
    schemes.dedup();
    assert_eq!(schemes, ["M1", "M2", "M3", "M4"]);
    assert!(
        study
            .rows
            .iter()
            .all(|r| r.errors.is_some_and(|e| e.pbar > 0.0 && e.pbar.is_finite()))
    );
    assert!(!frame(&app, 80, 24).contains("computing"));
    // Cached: coming back asks for nothing.
    app.update(key(KeyCode::Tab));
    let back = app.update(key(KeyCode::BackTab)).commands;
    assert_eq!(app.scene, Scene::Convergence);
    assert!(back.is_empty(), "{back:?}");
}

#[test]
fn newer_studies_supersede_older_ones() {
    let mut app = App::new(Scenario::paper());
    app.scene = Scene::Convergence;
    let old = studies(&app.update(Msg::Resize).commands).remove(0);
    // A level step keeps the study (levels 0 to 4 whatever the level); `w` asks for another.
    assert!(studies(&app.update(key(KeyCode::Right)).commands).is_empty());
    let new = studies(&app.update(ch('w')).commands).remove(0);
    assert!(new.generation > old.generation);
    assert_ne!(old.key, new.key);
    // The old study's reply is dropped: a newer one was asked for.
    let reply = Response::Study {
        generation: old.generation,
        key: old.key.clone(),
        result: Some(Err(SolveError::Cancelled.into())),
    };
    assert!(!app.update(Msg::Worker(reply)).redraw);
    assert!(app.studies.is_empty());
    // A study dropped unstarted by the worker is asked for again while still wanted.
    let dropped = Response::Study {
        generation: new.generation,
        key: new.key.clone(),
        result: None,
    };
    let again = studies(&app.update(Msg::Worker(dropped)).commands);
    assert_eq!(again.len(), 1);
    assert_eq!(again[0].key, new.key);
    // Levels above the study's cap share the capped study.
    app.settings.level = MAX_APP_LEVEL;
    assert_eq!(app.study_key().max_level, MAX_APP_LEVEL.min(MAX_STUDY_LEVEL));
}

// ---- the convergence scene compares the methods -------------------------------

/// The methods' names in the rows of `study`, in order.
fn methods_of(study: &Study) -> Vec<&'static str> {
    study.rows.iter().map(|r| r.method.method).collect()
}

/// `w` turns the study of M1–M4 with the lab's method into a study of the methods on the
/// lab's scheme; its rows carry each method (checked on the real engine: the ALM gives the
/// exact load where the penalty misses it by its ε term), and the chart has one series per
/// method, each with its own glyph (legible without colour).
#[test]
fn w_makes_a_study_of_the_methods() {
    let mut app = App::new(Scenario::paper());
    app.scene = Scene::Convergence;
    let schemes = studies(&app.update(Msg::Resize).commands).remove(0);
    assert_eq!(schemes.key.compare, Compare::Schemes);
    assert_eq!(schemes.key.methods, [app.settings.method]);
    assert_eq!(schemes.key.schemes.len(), 4, "M1–M4");
    let asked = studies(&app.update(ch('w')).commands);
    assert_eq!(asked.len(), 1, "one study: {asked:?}");
    let req = asked[0].clone();
    assert_eq!(req.key.compare, Compare::Methods);
    let names: Vec<&str> = req.key.methods.iter().map(|m| m.name()).collect();
    assert_eq!(names, ["penalty", "alm", "nitsche", "exact"]);
    assert_eq!(req.key.schemes, [(app.settings.element, app.settings.rule)]);
    let text = frame(&app, 120, 40);
    assert!(text.contains("then the methods on M1 at levels 0 to 4"), "{text}");
    // The study runs on the real engine: levels 0 to 4 against the q2 reference at level 5.
    let engine = Engine::new(Scenario::paper());
    let reply = Response::Study {
        generation: req.generation,
        result: Some(engine.study(&req.key, &mut |_| {})),
        key: req.key.clone(),
    };
    assert!(app.update(Msg::Worker(reply)).redraw);
    let Some(Ok(study)) = app.studies.get(&req.key) else {
        panic!("the study is cached: {:?}", app.studies);
    };
    let mut methods = methods_of(study);
    methods.dedup();
    assert_eq!(methods, ["penalty", "alm", "nitsche", "exact"]);
    assert!(
        study
            .rows
            .iter()
            .all(|r| r.scheme == "M1" && r.status == Status::Ok)
    );
    let load = |name: &str| {
        study
            .rows
            .iter()
            .find(|r| r.method.method == name)
            .unwrap()
            .load
            .unwrap()
    };
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    // The ALM has no penalty error: its load is the exact one; the penalty's is not.
    assert!(
        rel(load("alm"), load("exact")) < 1e-9,
        "{} {}",
        load("alm"),
        load("exact")
    );
    assert!(
        rel(load("penalty"), load("exact")) > 1e-6,
        "{} {}",
        load("penalty"),
        load("exact")
    );
    // Only the ALM updates a multiplier.
    assert!(
        study
            .rows
            .iter()
            .all(|r| r.outer_iterations.is_some() == (r.method.method == "alm"))
    );
    // One series per method, each with its glyph in the legend; no raw-p curve here.
    let text = render_app(&app, &MONO, 120, 40);
    for entry in ["⠒P⠒ penalty p̄", "⠒A⠒ alm p̄", "⠒N⠒ nitsche p̄", "⠒E⠒ exact p̄"] {
        assert!(text.contains(entry), "legend entry `{entry}` in\n{text}");
    }
    assert!(!text.contains("M1 p (raw)"), "{text}");
    assert!(text.contains("work–precision of the methods on M1"), "{text}");
    assert!(text.contains("w compares M1–M4"), "{text}");
    // Back to the schemes: that study is asked for again (the first was never answered).
    let back = studies(&app.update(ch('w')).commands);
    assert_eq!(back.len(), 1);
    assert_eq!(back[0].key, schemes.key);
}

/// `m` changes the method of the schemes' study, which is a study of its own.
#[test]
fn the_schemes_study_runs_the_labs_method() {
    let mut app = App::new(Scenario::paper());
    app.scene = Scene::Convergence;
    let penalty = studies(&app.update(Msg::Resize).commands).remove(0);
    let alm = studies(&app.update(ch('m')).commands);
    assert_eq!(alm.len(), 1);
    assert_ne!(alm[0].key, penalty.key);
    assert_eq!(alm[0].key.methods, [app.settings.method]);
    assert_eq!(alm[0].key.label(), "M1–M4 (exact)");
    // ε: the methods' study runs at the lab's (the penalty's error depends on it), the
    // schemes' at the scenario's.
    app.update(ch('w'));
    assert_eq!(app.study_key().epsilon, 1e-6);
    app.update(ch('+'));
    assert_eq!(app.study_key().epsilon, 1e-5);
    app.update(ch('w'));
    assert_eq!(app.study_key().epsilon, 1e-6);
}

/// A made-up study of the methods on M2 at levels 0..=2 (fixed timings): `exact` has no
/// answer on a rule with a kernel, and says so.
fn methods_app() -> App {
    let mut app = App::new(Scenario::paper());
    app.show_timing = false;
    app.scene = Scene::Convergence;
    app.compare = Compare::Methods;
    app.settings.level = 2;
    app.settings.rule = Rule::Gauss2;
    let key = app.study_key();
    let mut rows = Vec::new();
    for (i, &method) in key.methods.iter().enumerate() {
        for level in 0..=2u32 {
            let f = f64::from(1 << level);
            let mut r = row(
                "M2",
                level,
                [90, 306, 1122][level as usize],
                2.0 * f * f * (1.0 + i as f64),
                0.5 / f,
                0.2 / f,
                0.05 / f,
            );
            r.rule = "gauss2";
            r.method = method.into();
            r.outer_iterations = (method.name() == "alm").then_some(3);
            if method.name() == "exact" {
                r.status = Status::Kernel;
                r.reason = Some("ε = 0 imposes the constraint exactly at the 8 points of gauss2, more than the 5 normal displacements on Γ_C".into());
                r.errors = None;
                r.solve_ms = None;
                r.newton_iterations = None;
            }
            rows.push(r);
        }
    }
    app.studies.insert(key.clone(), Ok(Arc::new(Study { key, rows })));
    app
}

/// The methods' chart and table at 80×24, with colour and without: `exact` says why it has
/// no curve, in the legend and in the table.
#[test]
fn convergence_methods_80x24() {
    let app = methods_app();
    assert!(
        app.clone().update(Msg::Resize).commands.is_empty(),
        "a cached study asks for nothing more"
    );
    let text = frame(&app, 80, 24);
    assert!(text.contains("exact: kernel"), "{text}");
    let mono = render_app(&app, &MONO, 80, 24);
    for entry in ["⠒P⠒ penalty p̄", "⠒A⠒ alm p̄", "⠒N⠒ nitsche p̄", "⠒E⠒ exact: kernel"] {
        assert!(mono.contains(entry), "legend entry `{entry}` in\n{mono}");
    }
    assert!(
        mono.contains("kernel: ε = 0 imposes"),
        "the table says why:\n{mono}"
    );
    snap!("tui__convergence_methods_80x24", text);
}
