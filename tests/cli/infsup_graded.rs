//! `riplab infsup --refine-edges N`, the inf-sup estimate on
//! meshes graded at the contact edges. Checked against the plain estimate on a scenario whose
//! level-0 lines are the graded grid's (the grading is only a choice of lines), against the
//! uniform table at N = 0, and for its bad input.

use riplab::contact::newton::NewtonOptions;
use riplab::contact::{ContactParams, Rule};
use riplab::grading::RefineEdges;
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::solve::solve_graded;

/// The rows of `riplab infsup ARGS --format json`: (level, β_h, β̄_h).
fn rows(args: &[&str]) -> (Vec<(u64, f64, f64)>, String) {
    let mut all = vec!["infsup", "--format", "json"];
    all.extend(args);
    let (code, out, err) = crate::common::riplab(&all);
    assert_eq!(code, 0, "{args:?}: {err}");
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    let rows = json
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            (
                r["level"].as_u64().unwrap(),
                r["beta"].as_f64().unwrap(),
                r["beta_bar"].as_f64().unwrap(),
            )
        })
        .collect();
    (rows, err)
}

/// M1 at level 1 graded twice: β_h and β̄_h are the plain estimate's on the paper's problem
/// with the graded grid's lines as its level-0 lines, to 1e-12; grading lowers M1's β_h (its
/// smallest cells are a quarter of h).
#[test]
fn a_graded_estimate_is_the_estimate_on_the_graded_lines() {
    let (graded, note) = rows(&["--level", "1", "--refine-edges", "2"]);
    assert!(note.contains("graded at the contact edges"), "{note}");
    let scenario = Scenario::paper();
    let uniform = scenario.discretize(1, Element::Q1).unwrap();
    let params = ContactParams::by_epsilon(Rule::Gauss1, scenario.epsilon, scenario.obstacle.clone());
    let g = solve_graded(
        &scenario,
        (1, &uniform),
        &params,
        RefineEdges::Passes(2),
        &NewtonOptions::default(),
    )
    .unwrap();
    assert_eq!(g.grid.passes, 2);
    let mut lines = scenario.clone();
    (lines.x_lines, lines.y_lines) = (g.grid.xs.clone(), g.grid.ys.clone());
    let plain = riplab::infsup::table(&lines, &[(Element::Q1, Rule::Gauss1)], &[0]).unwrap();
    let (_, beta, beta_bar) = graded[0];
    assert!(
        (beta - plain[0].beta).abs() <= 1e-12 * plain[0].beta,
        "{beta} {}",
        plain[0].beta
    );
    assert!((beta_bar - plain[0].beta_bar).abs() <= 1e-12 * plain[0].beta_bar);
    let (uniform_rows, _) = rows(&["--level", "1"]);
    assert!(
        beta < 0.9 * uniform_rows[0].1,
        "{beta} against {}",
        uniform_rows[0].1
    );
}

/// `--refine-edges 0` is the uniform table; a count out of range is refused with the range.
#[test]
fn zero_passes_is_the_uniform_table_and_bad_counts_are_refused() {
    let (zero, note) = rows(&["--levels", "0..2", "--refine-edges", "0"]);
    assert!(!note.contains("graded"), "{note}");
    let (uniform, _) = rows(&["--levels", "0..2"]);
    assert_eq!(zero, uniform);
    for bad in ["9", "-1", "two"] {
        let flag = format!("--refine-edges={bad}");
        let (code, _, err) = crate::common::riplab(&["infsup", &flag]);
        assert_eq!(code, 2, "{bad}: {err}");
        assert!(err.contains("allowed: 0 to 8, or auto"), "{err}");
    }
}
