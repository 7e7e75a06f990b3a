//! The convergence study's machinery: errors of the reference against itself vanish, and
//! the observed behaviour matches Theorem 2 (26) and the paper's claim about p and p̄.

use crate::common::paper_with;
use riplab::contact::{Method, Rule};
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::study::{
    Errors, Plan, Reference, ReferenceFields, ReferenceMesh, Status, StudyRow, Target, convergence, fits,
    least_squares_slope, refine_reference, study, uniform_reference,
};

#[test]
fn errors_rates_and_the_smoothing_claim() {
    let scenario = paper_with(&[]);
    let reference = Reference::compute(&scenario, 4).unwrap();
    // The reference scheme at the reference level against itself: zero (checks evaluation and
    // integration on nested meshes).
    let itself = convergence(
        &scenario,
        &reference,
        &[(Element::Q2, Rule::Simpson)],
        &[4],
        None,
        0.0,
    );
    let e = itself[0].errors.unwrap();
    assert!(
        e.p < 1e-12 && e.pbar < 0.1 && e.u < 1e-12 && e.load < 1e-12,
        "{e:?}"
    );
    let rows = convergence(
        &scenario,
        &reference,
        &[(Element::Q1, Rule::Gauss1), (Element::Q1, Rule::Trapezoid)],
        &[1, 2, 3],
        None,
        1e-10,
    );
    for r in &rows {
        assert!(r.converged && r.status == Status::Ok, "{r:?}");
    }
    // H¹ error of Q1 at rate 1 (the h term of (26); ε is too small to matter).
    for r in rows.iter().filter(|r| r.level > 1) {
        let u_rate = r.rates.unwrap().u;
        assert!(
            (0.85..1.2).contains(&u_rate),
            "{} level {}: u rate {u_rate}",
            r.scheme,
            r.level
        );
    }
    // M1 on the finest level: the smoothed pressure is much closer to the truth than the raw one.
    let m1 = rows.iter().find(|r| r.scheme == "M1" && r.level == 3).unwrap();
    let e = m1.errors.unwrap();
    assert!(e.pbar < 0.6 * e.p, "M1: p̄ error {} vs p error {}", e.pbar, e.p);
}

/// The reference is kept in the cache directory: the second study reads it and reports the
/// same errors; a damaged entry is recomputed; `--no-cache` neither reads nor writes; two
/// studies at once both succeed.
#[test]
fn the_reference_is_cached_between_runs() {
    use std::process::Command;
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("cache-test");
    let _ = std::fs::remove_dir_all(&dir);
    let run = |extra: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_riplab"))
            .args([
                "study",
                "--levels",
                "0..1",
                "--schemes",
                "M1,M3",
                "--format",
                "json",
            ])
            .args(extra)
            .env("XDG_CACHE_HOME", &dir)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(0));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let errors: Vec<serde_json::Value> = v["rows"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r["errors"].clone())
            .collect();
        (errors, String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (none, stderr) = run(&["--no-cache"]);
    assert!(stderr.contains(" done in ") && !dir.exists(), "{stderr}");
    let (first, stderr) = run(&[]);
    assert!(stderr.contains(" done in "), "{stderr}");
    let (second, stderr) = run(&[]);
    assert!(stderr.contains(" read from "), "{stderr}");
    assert_eq!(first, second);
    assert_eq!(first, none);
    // Damage the entry: it is recomputed (and replaced).
    let entry = std::fs::read_dir(dir.join("riplab"))
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    let mut bytes = std::fs::read(&entry).unwrap();
    let mid = bytes.len() / 2;
    bytes[mid] ^= 1;
    std::fs::write(&entry, &bytes).unwrap();
    let (third, stderr) = run(&[]);
    assert!(stderr.contains(" done in "), "{stderr}");
    assert_eq!(first, third);
    // Two runs at once on an empty cache.
    std::fs::remove_dir_all(&dir).unwrap();
    let spawn = || {
        Command::new(env!("CARGO_BIN_EXE_riplab"))
            .args(["study", "--levels", "0..1", "--schemes", "M1", "--format", "json"])
            .env("XDG_CACHE_HOME", &dir)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap()
    };
    let (a, b) = (spawn(), spawn());
    let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
    assert!(a.status.success() && b.status.success());
    assert!(!a.stdout.is_empty() && !b.stdout.is_empty());
    let (after, stderr) = run(&[]);
    assert!(stderr.contains(" read from "), "{stderr}");
    assert_eq!(after[0], first[0]);
}

/// Rows of one scheme with hand-made errors for the least-squares fit.
fn made_row(level: u32, h: f64, errors: Option<Errors>, status: Status) -> StudyRow {
    StudyRow {
        scheme: "M1".into(),
        element: riplab::mesh::Element::Q1,
        rule: "gauss1",
        level,
        h,
        epsilon: 1e-6,
        method: Method::Penalty.into(),
        n_dofs: 10,
        refine_edges: 0,
        h_min: h,
        grading: Default::default(),
        status,
        reason: None,
        epsilon_dominated: false,
        newton_iterations: Some(1),
        outer_iterations: None,
        converged: status == Status::Ok,
        solve_ms: Some(1.0),
        load: Some(1.0),
        errors,
        rates: None,
        warnings: Vec::new(),
    }
}

/// Errors C·h^r over the levels give a least-squares rate of exactly r for each quantity, and
/// rows without a result (or without errors) are left out of the fit, even when their numbers
/// would pull it off.
#[test]
fn the_least_squares_rate_recovers_a_known_slope_and_ignores_rows_without_results() {
    let law = |h: f64| Errors {
        p: 3.0 * h.powf(0.5),
        pbar: 0.7 * h.powf(1.5),
        u: 2.0 * h,
        load: 0.1 * h * h,
        tbar: Some(0.4 * h.powf(0.75)),
        tangential_load: Some(0.2 * h.powi(3)),
    };
    let mut rows: Vec<StudyRow> = (0..4)
        .map(|l| {
            let h = 0.5_f64.powi(l);
            made_row(l as u32, h, Some(law(h)), Status::Ok)
        })
        .collect();
    // A failed row and a not-converged row with wild numbers: not fitted.
    rows.insert(2, made_row(9, 0.3, None, Status::Failed));
    let mut wild = law(0.01);
    wild.p = 1e3;
    rows.push(made_row(5, 0.01, Some(wild), Status::NotConverged));
    let fitted = fits(&rows, false);
    assert_eq!(fitted.len(), 1);
    assert_eq!(fitted[0].rows, 4);
    let r = fitted[0].rates.unwrap();
    let (tbar, q) = (r.tbar.unwrap(), r.tangential_load.unwrap());
    for (got, want) in [
        (r.p, 0.5),
        (r.pbar, 1.5),
        (r.u, 1.0),
        (r.load, 2.0),
        (tbar, 0.75),
        (q, 3.0),
    ] {
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }
    // Noisy errors: the fit is the slope of the regression line, here by hand:
    // x = ln h = (0, −ln 2, −2 ln 2), y = (0, −ln 2, −3 ln 2) → slope 1.5.
    let pts = [0.0, -2f64.ln(), -2.0 * 2f64.ln()]
        .iter()
        .zip([0.0, -2f64.ln(), -3.0 * 2f64.ln()])
        .map(|(x, y)| (*x, y))
        .collect::<Vec<_>>();
    assert!((least_squares_slope(&pts).unwrap() - 1.5).abs() < 1e-12);
    // One usable row: no fit.
    let single = fits(&rows[..2], false);
    assert_eq!((single[0].rows, single[0].rates), (2, fits_of_two(&rows[..2])));
    let one = fits(&rows[..1], false);
    assert_eq!((one[0].rows, one[0].rates), (1, None));
}

/// Nitsche's `auto` γ₀ is chosen on each level's mesh (γ₀* differs in its last digits): the
/// rows are still one method, fitted together (each was its own fit, "least squares over 1
/// rows"), and the fit carries the setting, not one level's γ₀.
#[test]
fn auto_gamma0_rows_are_fitted_together() {
    use riplab::contact::method::{Gamma0, MethodFields};
    let auto = Method::Nitsche {
        theta: 1,
        gamma0: Gamma0::Auto,
    };
    let rows: Vec<StudyRow> = (0..3)
        .map(|l| {
            let h = 0.5_f64.powi(l);
            let mut row = made_row(
                l as u32,
                h,
                Some(Errors {
                    p: h,
                    pbar: h,
                    u: h,
                    load: h,
                    tbar: None,
                    tangential_load: None,
                }),
                Status::Ok,
            );
            row.method = MethodFields::used(auto, Some(15.6899 + 1e-6 * f64::from(l)));
            row
        })
        .collect();
    let fitted = fits(&rows, false);
    assert_eq!(fitted.len(), 1);
    assert_eq!(fitted[0].rows, 3);
    assert_eq!(
        (fitted[0].method.gamma0, fitted[0].method.gamma0_auto),
        (None, Some(true))
    );
    assert!((fitted[0].rates.unwrap().u - 1.0).abs() < 1e-12);
}

/// The fit of two rows is their row-to-row rate.
fn fits_of_two(rows: &[StudyRow]) -> Option<Errors> {
    let (a, b) = (rows[0].errors.unwrap(), rows[1].errors.unwrap());
    let s = (rows[1].h / rows[0].h).ln();
    let r = |x: f64, y: f64| (y / x).ln() / s;
    let e = Errors {
        p: r(a.p, b.p),
        pbar: r(a.pbar, b.pbar),
        u: r(a.u, b.u),
        load: r(a.load, b.load),
        tbar: None,
        tangential_load: None,
    };
    // Round to the fit's own round-off.
    let got = fits(rows, false)[0].rates.unwrap();
    assert!((got.p - e.p).abs() < 1e-12 && (got.load - e.load).abs() < 1e-12);
    Some(got)
}

/// The uniform reference's estimated error is its difference from level − 1, which is what a
/// study row of the reference scheme at level − 1 reports against it (two independent paths:
/// the row is solved by the study, the estimate read from the coarser reference's fields); a
/// refined reference keeps every uniform line (nested) and refines only near the one contact
/// edge of the half model and next to Γ_C.
#[test]
fn the_reference_estimates_its_error_and_refines_at_the_contact_edge() {
    let scenario = Scenario::paper();
    let mut fetch = |g: &ReferenceMesh| ReferenceFields::solve_on(&scenario, g);
    let (uniform, fields) = uniform_reference(&scenario, 3, &mut fetch).unwrap();
    let estimate = uniform.estimate.clone().unwrap();
    assert_eq!(estimate.against, "level 2");
    let row = convergence(
        &scenario,
        &uniform,
        &[(Element::Q2, Rule::Simpson)],
        &[2],
        None,
        0.0,
    );
    let e = row[0].errors.unwrap();
    assert!(
        (e.p - estimate.p).abs() < 1e-9 * e.p && (e.u - estimate.u).abs() < 1e-9 * e.u,
        "{e:?} vs {estimate:?}"
    );
    // The half model has one contact edge: one place to refine.
    let edges = uniform.grid.contact_edges(&fields.p);
    assert_eq!(edges.len(), 1, "{edges:?}");
    let once = uniform.grid.refined(&fields.p).unwrap();
    assert_eq!(once.refinements, 1);
    for x in &uniform.grid.xs {
        assert!(once.xs.contains(x), "line x = {x} lost");
    }
    for y in &uniform.grid.ys {
        assert!(once.ys.contains(y), "line y = {y} lost");
    }
    // 2·EDGE_WIDTH + 1 x-intervals and EDGE_WIDTH y-intervals bisected.
    assert_eq!(once.xs.len(), uniform.grid.xs.len() + 5);
    assert_eq!(once.ys.len(), uniform.grid.ys.len() + 2);
    let edge_x = 0.5 * (uniform.grid.xs[edges[0]] + uniform.grid.xs[edges[0] + 1]);
    let new: Vec<f64> = once
        .xs
        .iter()
        .filter(|x| !uniform.grid.xs.contains(x))
        .copied()
        .collect();
    let h = uniform.grid.h_min();
    assert!(
        new.iter().all(|x| (x - edge_x).abs() < 3.0 * h),
        "{new:?} around {edge_x}"
    );
    // A target the uniform reference meets: nothing refined, nothing to warn about.
    let loose = Target { p: 1.0, u: 1.0 };
    let (same, fields) = refine_reference(&scenario, (uniform, fields), Some(loose), 4, &mut fetch);
    assert_eq!((same.grid.refinements, same.stopped.as_deref()), (0, None));
    // p met, u not: edge refinements cannot lower u's estimate; it stops and says why.
    let u_only = Target { p: 1.0, u: 1e-12 };
    let (same, _) = refine_reference(&scenario, (same, fields), Some(u_only), 4, &mut fetch);
    assert_eq!(same.grid.refinements, 0);
    assert!(
        same.stopped
            .as_deref()
            .unwrap()
            .contains("finer --reference-level"),
        "{:?}",
        same.stopped
    );
}

/// Refinement at the contact edges helps where it should: two edge refinements of
/// the level-3 reference cut its estimated p error well below the uniform level 3's, at a
/// fraction of level 4's unknowns, and the refined reference is truly closer to a level-5
/// reference than the uniform level 3 is.
#[test]
fn edge_refinement_beats_the_uniform_reference_of_the_same_level() {
    let scenario = Scenario::paper();
    let mut fetch = |g: &ReferenceMesh| ReferenceFields::solve_on(&scenario, g);
    let start = uniform_reference(&scenario, 3, &mut fetch).unwrap();
    let (uniform_p, uniform_u) = start.0.estimate.clone().map(|e| (e.p, e.u)).unwrap();
    let uniform_dofs = start.0.n_dofs;
    let tiny = Target { p: 1e-12, u: 1e-12 };
    let once_grid = start.0.grid.refined(&start.1.p).unwrap();
    let (refined, _) = refine_reference(&scenario, start, Some(tiny), 2, &mut fetch);
    let once_fields = ReferenceFields::solve_on(&scenario, &once_grid).unwrap();
    assert!(uniform_dofs < refined.n_dofs);
    assert_eq!(refined.grid.refinements, 2);
    assert!(
        refined.stopped.as_deref().unwrap_or("").contains("cap of 2"),
        "{:?}",
        refined.stopped
    );
    let e = refined.estimate.clone().unwrap();
    assert_eq!(e.against, "refinement 1");
    let level4 = scenario.n_dofs(4, Element::Q2);
    let truth = Reference::compute(&scenario, 5).unwrap();
    let true_uniform = truth.estimate_against(
        &scenario,
        &ReferenceMesh::uniform(&scenario, 3),
        &ReferenceFields::solve(&scenario, 3).unwrap(),
    );
    let true_refined = truth.estimate_against(
        &scenario,
        &refined.grid,
        &ReferenceFields::solve_on(&scenario, &refined.grid).unwrap(),
    );
    let true_level4 = truth.estimate_against(
        &scenario,
        &ReferenceMesh::uniform(&scenario, 4),
        &ReferenceFields::solve(&scenario, 4).unwrap(),
    );
    // Measured (docs/convergence.md): estimated p 1.38e-2 (uniform 3) → 3.43e-3 (refined 2,
    // a ratio of 0.25) with 21 384 unknowns, 0.33 of level 4's 65 664; against level 5 the
    // true p error goes 4.50e-3 → 1.74e-4 (level 4: 3.43e-3) and u's 1.06e-3 → 5.96e-4.
    assert!(
        e.p < 0.35 * uniform_p,
        "estimated p {} vs uniform {uniform_p}",
        e.p
    );
    assert!(refined.n_dofs < level4 * 2 / 5, "{} vs {level4}", refined.n_dofs);
    assert!(
        true_refined.p < 0.1 * true_uniform.p,
        "{true_refined:?} vs {true_uniform:?}"
    );
    assert!(
        true_refined.p < 0.2 * true_level4.p,
        "{true_refined:?} vs {true_level4:?}"
    );
    assert!(
        true_refined.u < 0.7 * true_uniform.u,
        "{true_refined:?} vs {true_uniform:?}"
    );
    // The estimate bounds the true error from above (docs/design.md §6): for p the difference
    // from refinement 1 is about refinement 1's error; u keeps the uniform level's estimate,
    // since the difference of two edge refinements would miss the body's error away from the
    // edges (measured: 3.97e-4 < 5.96e-4, the true one).
    assert!(true_refined.p < e.p && true_uniform.p < uniform_p);
    assert_eq!(e.u, uniform_u);
    assert!(
        true_refined.u < e.u && true_uniform.u < uniform_u,
        "{true_refined:?} vs {e:?}"
    );
    let step = refined.estimate_against(&scenario, &once_grid, &once_fields);
    assert!(step.u < true_refined.u, "{step:?} vs {true_refined:?}");
    assert_eq!((step.p, step.load), (e.p, e.load));
}

/// `--reference-refinements` outside 0..=8: a clear message and exit 2, before any solve.
#[test]
fn reference_refinements_out_of_range_is_refused() {
    for bad in ["9", "-1"] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_riplab"))
            .args([
                "study",
                "--levels",
                "0",
                "--no-cache",
                "--reference-refinements",
                bad,
            ])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains("--reference-refinements") && stderr.contains("allowed: 0 to 8"),
            "{stderr}"
        );
        assert!(!stderr.contains("the reference: q2"), "{stderr}");
    }
}

/// The whole study: after the reference is refined, every row's errors are what a fresh solve
/// measures against the final reference (the rows are re-measured from what they kept, not
/// solved again), the target is a tenth of the smallest final errors, and each scheme has a fit.
#[test]
fn a_refined_study_measures_its_rows_against_the_final_reference() {
    let scenario = Scenario::paper();
    let schemes = [(Element::Q1, Rule::Trapezoid), (Element::Q2, Rule::Simpson)];
    let levels = [0, 1];
    let mut fetch = |g: &ReferenceMesh| ReferenceFields::solve_on(&scenario, g);
    let plan = Plan::Levels {
        levels: &levels,
        epsilon: 1e-8,
        refine: &[Default::default()],
    };
    let s = study(&scenario, &schemes, None, plan, (2, 2), &mut fetch).unwrap();
    assert_eq!(s.reference.grid.refinements, 2, "{:?}", s.reference.stopped);
    let fresh = convergence(&scenario, &s.reference, &schemes, &levels, None, 1e-8);
    for (a, b) in s.rows.iter().zip(&fresh) {
        let (ea, eb) = (a.errors.unwrap(), b.errors.unwrap());
        for (x, y) in [(ea.p, eb.p), (ea.pbar, eb.pbar), (ea.u, eb.u), (ea.load, eb.load)] {
            assert!(
                (x - y).abs() <= 1e-9 * y,
                "{} level {}: {ea:?} vs {eb:?}",
                a.scheme,
                a.level
            );
        }
        assert_eq!(a.rates.is_some(), a.level > 0);
    }
    let target = s.reference.target.unwrap();
    assert_eq!(Some(target), Target::of(&s.rows));
    assert_eq!(s.fits.len(), 2);
    assert!(s.fits.iter().all(|f| f.rows == 2 && f.rates.is_some()));
    study_csv_is_its_json(&s);
}

/// The study's CSV (`riplab study --format csv`) is its JSON, line by line: a row per row, a
/// fit per fit, the reference last; each error, rate and estimate is the JSON's number.
fn study_csv_is_its_json(s: &riplab::study::Study) {
    use riplab::output::{Report, STUDY_COLUMNS, StudyReport};
    let report = StudyReport {
        scenario: "paper",
        study: s,
    };
    // The value itself (serde_json's text parser may round the last digit).
    let json = serde_json::to_value(&report).unwrap();
    let csv = report.csv();
    let lines: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    let header = &lines[0];
    assert_eq!(header, &STUDY_COLUMNS.map(|c| c.0).to_vec());
    assert_eq!(lines.len(), 1 + s.rows.len() + s.fits.len() + 1);
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let num = |text: &str| text.parse::<f64>().unwrap();
    for (i, row) in json["rows"].as_array().unwrap().iter().enumerate() {
        let line = &lines[1 + i];
        assert_eq!(line[col("kind")], "row");
        assert_eq!(num(line[col("err_p")]), row["errors"]["p"].as_f64().unwrap());
        assert_eq!(num(line[col("err_u")]), row["errors"]["u"].as_f64().unwrap());
        assert_eq!(line[col("scheme")], row["scheme"].as_str().unwrap());
    }
    for (i, fit) in json["fits"].as_array().unwrap().iter().enumerate() {
        let line = &lines[1 + s.rows.len() + i];
        assert_eq!(line[col("kind")], "fit");
        assert_eq!(num(line[col("rate_p")]), fit["rates"]["p"].as_f64().unwrap());
    }
    let reference = lines.last().unwrap();
    assert_eq!(reference[col("kind")], "reference");
    assert_eq!(num(reference[col("refinements")]), 2.0);
    assert_eq!(
        num(reference[col("err_p")]),
        json["reference"]["estimate"]["p"].as_f64().unwrap()
    );
    assert_eq!(
        num(reference[col("h")]),
        json["reference"]["h_min"].as_f64().unwrap()
    );
}
