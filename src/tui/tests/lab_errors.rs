//! The worker's failures, the tour's refusals and a
//! recording's end are typed errors that keep their sources, and say what users read before
//! (each message checked against the text the code wrote before it was typed).

use std::error::Error as _;
use std::time::Duration;

use riplab::error::SolveError;
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::tui::lab_error::LabError;
use riplab::tui::tour::errors::{StepError, TextError};
use riplab::tui::tour::{AutoIntervalError, Tour, TourError, auto_interval, render_step};

/// The failures the worker makes up itself read as they did; a solve's keeps its source.
#[test]
fn the_workers_failures_keep_their_messages_and_sources() {
    let built = LabError::BuildEnded {
        level: 3,
        element: Element::Q2,
    };
    assert_eq!(
        built.to_string(),
        "the build of level 3 with q2 ended without a result"
    );
    assert_eq!(
        LabError::EstimateEnded.to_string(),
        "the estimate ended without a result"
    );
    let other = LabError::OtherScenario {
        runs: "paper".into(),
        asked: "hertz-paper".into(),
    };
    assert_eq!(other.to_string(), "the worker runs paper, not hertz-paper");
    let solve = SolveError::Factorization {
        matrix: "stiffness",
        pivot: 4,
    };
    let lab = LabError::from(solve.clone());
    assert_eq!(
        lab.to_string(),
        solve.to_string(),
        "shown as the solve's own message"
    );
    assert_eq!(lab, LabError::Solve(solve));
}

/// A study asked of an engine on another scenario is refused with both names.
#[test]
fn a_study_of_another_scenario_is_refused_by_name() {
    use riplab::tui::engine::Engine;
    let engine = Engine::new(Scenario::paper());
    let mut app = riplab::tui::app::App::new(Scenario::paper());
    app.scenario.name = "elsewhere".into();
    let key = app.study_key();
    let Err(e) = engine.studying(&key) else {
        panic!("a study of another scenario ran");
    };
    assert_eq!(
        e,
        LabError::OtherScenario {
            runs: Scenario::paper().name,
            asked: "elsewhere".into()
        }
    );
}

/// `--auto` out of range names the seconds given.
#[test]
fn an_auto_interval_out_of_range_says_so() {
    assert_eq!(auto_interval(2.0), Ok(Duration::from_secs(2)));
    assert_eq!(auto_interval(0.1), Err(AutoIntervalError { seconds: 0.1 }));
    assert_eq!(
        auto_interval(0.1).unwrap_err().to_string(),
        "0.1 is out of range; allowed: 0.5 to 3600 seconds"
    );
}

/// A caption line too long, and a blank title, are refused with the old wording.
#[test]
fn titles_and_captions_that_do_not_fit_are_refused_with_their_variant() {
    assert_eq!(
        TextError::CaptionWidth { line: 2, chars: 97 }.to_string(),
        "line 2 has 97 characters; allowed: 1 to 4 lines of at most 96 characters"
    );
    assert_eq!(
        TextError::EmptyLine { width: 60 }.to_string(),
        "is empty; allowed: one line of 1 to 60 characters"
    );
    let long = "x".repeat(97);
    let text = format!("title = \"t\"\n[[step]]\ntitle = \"s\"\ncaption = \"a\\n{long}\"\n");
    let e = Tour::parse(&text, "bad.toml", None).unwrap_err().to_string();
    assert!(
        e.contains("line 2 has 97 characters; allowed: 1 to 4 lines of at most 96 characters"),
        "{e}"
    );
}

/// A step's ε outside its level's range is refused with the check's error as its source.
#[test]
fn a_steps_epsilon_out_of_range_keeps_the_checks_error() {
    let text = "title = \"t\"\n[[step]]\ntitle = \"s\"\ncaption = \"c\"\nlevel = 0\nepsilon = 1e8\n";
    let tour = Tour::parse(text, "eps.toml", None).unwrap();
    let e = tour.with_scenario(Scenario::paper()).unwrap_err();
    assert!(
        matches!(&e, TourError::Epsilon { step: 1, level: 0, file, .. } if file == "eps.toml"),
        "{e:?}"
    );
    assert!(e.source().is_some(), "the range check is its source");
    assert!(
        e.to_string()
            .starts_with("eps.toml: step 1 (`s`): ε at level 0: "),
        "{e}"
    );
}

/// A step beyond the tour is refused by number.
#[test]
fn a_step_beyond_the_tour_is_refused_by_number() {
    let tour = Tour::paper();
    let steps = tour.steps.len();
    let e = render_step(&tour, steps, 80, 24).unwrap_err();
    assert!(
        matches!(e, StepError::NoSuchStep { step, steps: s } if step == steps + 1 && s == steps),
        "{e:?}"
    );
    assert_eq!(
        e.to_string(),
        format!("step {} does not exist; the tour has {steps} steps", steps + 1)
    );
}
