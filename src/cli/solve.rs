//! `riplab solve`: one solve, or a sweep of levels, in the CLI's formats, with its plots and VTU.

use std::process::ExitCode;

use super::args::{SolveArgs, method_at};
use super::{CliError, grading, note, outputs, print, shown, usage};
use crate::contact::ContactParams;
use crate::contact::Method;
use crate::discretization::Trace;
use crate::output::{SolveReport, Sweep, SweepFailure, SweepRow, output};
use crate::solve::checks::check_request;
use crate::text::num;
use crate::{check, vtu};

pub(super) fn solve(args: &SolveArgs) -> Result<ExitCode, CliError> {
    let mut scenario = args.select.resolve()?;
    if scenario.upper.is_some() {
        return super::two_bodies::solve(args, &scenario);
    }
    if args.contact.is_some() {
        return Err(usage(
            "--contact",
            "discretises the interface of two elastic bodies; this scenario has one (give a scenario with [upper], e.g. scenarios/patch-two-blocks.toml)",
        ));
    }
    scenario.set_grading(grading::refine_edges(args.refine_edges.as_deref(), &scenario)?);
    let method = args.method.resolve(&scenario)?;
    let frictions = args.friction.resolve(&scenario)?;
    let friction_on = frictions[0].is_on();
    if friction_on && scenario.grading().grades() {
        return Err(graded_friction(args.refine_edges.is_some(), &scenario));
    }
    let level = scenario.level;
    let range = scenario.epsilon_range(level);
    for &e in &args.epsilon {
        check::epsilon_in(e, range).map_err(|m| usage("--epsilon", m))?;
    }
    // ε = κ·h/E: the κ range is KAPPA_RANGE whatever the level.
    let scale = scenario.h(level) / scenario.material.young;
    for &k in &args.kappa {
        check::epsilon_in(k * scale, range)
            .map_err(|m| usage("--kappa", format!("κ = {}: {m}", crate::text::num(k))))?;
    }
    for &d in &args.depth {
        check::depth(d, scenario.height).map_err(|m| usage("--depth", m))?;
    }
    if args.epsilon.len().max(args.kappa.len()) > 1 && args.depth.len() > 1 {
        return Err(CliError::Usage(
            "sweep one of --epsilon (or --kappa) and --depth at a time".into(),
        ));
    }
    let epsilons = match (args.epsilon.is_empty(), args.kappa.is_empty()) {
        (false, _) => args.epsilon.clone(),
        (true, false) => args.kappa.iter().map(|k| k * scale).collect(),
        // The scenario's ε, or for a method that needs one where the scenario has none
        // (ε = 0), an error that says so.
        (true, true) => vec![scenario.epsilon],
    };
    // Every ε with the method: `penalty` and `alm` refuse ε = 0 (before any work).
    let flag = if args.kappa.is_empty() {
        "--epsilon"
    } else {
        "--kappa"
    };
    for &e in &epsilons {
        let (m, _) = method_at(method, e, flag)?;
        if friction_on {
            let named = if args.method.method.is_some() {
                "--method"
            } else {
                flag
            };
            args.friction.check_method(m, &frictions, named)?;
        }
    }
    let depths = if args.depth.is_empty() {
        vec![scenario.obstacle.depth()]
    } else {
        args.depth.clone()
    };
    if frictions.len() > 1 && (epsilons.len() > 1 || depths.len() > 1) {
        return Err(CliError::Usage(
            "sweep one of --epsilon (or --kappa), --depth and --shift-steps at a time".into(),
        ));
    }
    let many = epsilons.len() > 1 || depths.len() > 1 || frictions.len() > 1;
    if let Some(m) = method.filter(|m| !m.uses_epsilon() && epsilons.len() > 1) {
        return Err(usage(
            flag,
            format!(
                "{} does not use ε: every row of a sweep over ε would be the same solve; sweep --depth instead",
                m.name()
            ),
        ));
    }
    let mut targets = Vec::new();
    if let Some(path) = &args.plot {
        targets.push(("--plot", path.clone()));
    }
    if let Some(path) = &args.vtu {
        targets.push(("--vtu", path.clone()));
        targets.push(("--vtu's Γ_C file", vtu::contact_path(path)));
    }
    outputs::distinct(&targets)?;
    if let Some(path) = &args.plot {
        if many {
            return Err(usage("--plot", "plots one solve; a sweep has several"));
        }
        crate::plot::check_target(path, args.force).map_err(|e| plot_error(path, &e))?;
    }
    let params = |epsilon: f64, depth: f64| {
        let (method, epsilon) = Method::resolve(method, epsilon).expect("checked above");
        ContactParams {
            rule: scenario.rule,
            method,
            epsilon,
            obstacle: scenario.obstacle.with_depth(depth),
        }
    };
    // A single solve's request with no answer is refused before any assembly; in a sweep each
    // row says for itself.
    if !many {
        check_request(
            &scenario,
            level,
            scenario.element,
            &params(epsilons[0], depths[0]),
        )?;
    }
    if many && args.vtu.is_some() {
        return Err(usage("--vtu", "exports one solve; a sweep has several"));
    }
    // Before any work: an existing file is refused unless --force, and then only a regular one.
    if let Some(path) = &args.vtu {
        vtu::check_targets(path, args.force).map_err(|e| usage("--vtu", e.to_string()))?;
    }

    // A graded solve's memory, from its lines, before the uniform level is built.
    scenario.graded_fits(level, scenario.element, scenario.grading(), |_| 0)?;
    let trace = if friction_on { Trace::Full } else { Trace::Normal };
    let disc = scenario.discretize_traced(level, scenario.element, trace)?;
    let mut instances: Vec<ContactParams> = epsilons
        .iter()
        .flat_map(|&e| depths.iter().map(move |&d| (e, d)))
        .map(|(e, d)| params(e, d))
        .collect();
    let mut rows: Vec<SweepRow> = Vec::new();
    // A sweep over the friction's rows solves the one instance once per row.
    if frictions.len() > 1 {
        instances = vec![instances[0].clone(); frictions.len()];
    }
    let outcomes = grading::solve_all(&scenario, &disc, &instances, &frictions, scenario.grading());
    for (params, (solved, graded, passes)) in instances.iter().zip(outcomes) {
        let disc = graded.as_ref().unwrap_or(&disc);
        let sol = match solved {
            Ok(sol) => sol,
            Err(e) if many => {
                rows.push(SweepRow::Failed(SweepFailure::new(&scenario, disc, params, &e)));
                continue;
            }
            Err(e) => return Err(e.into()),
        };
        // The setting that tells the sweep's rows apart: ε where the method uses it.
        let setting = if params.method.uses_epsilon() {
            format!("ε = {:e}", params.epsilon)
        } else {
            sol.method_fields().label()
        };
        for w in &sol.warnings {
            note(&format!(
                "warning: {setting}, depth = {}: {w}",
                num(params.obstacle.depth())
            ));
        }
        let mut report = SolveReport::new(&scenario, level, disc, &sol);
        (report.refine_edges, report.grading) = (passes, scenario.grading());
        rows.push(SweepRow::Solved(Box::new(report)));
        if let Some(path) = &args.plot {
            let title = crate::plot::chart_title(&scenario.name, disc.mesh.element, level, &sol);
            crate::plot::pressure_svg(path, &title, &sol, scenario.half_model, args.force)
                .map_err(|e| CliError::Failed(format!("--plot {e}")))?;
        }
        if let Some(path) = &args.vtu {
            let field = sol
                .stress_field(disc)
                .map_err(|e| CliError::Failed(format!("the stress field: {e}")))?;
            let [body, contact] = vtu::write(path, disc, &sol, &field, args.force)
                .map_err(|e| CliError::Failed(format!("--vtu {e}")))?;
            note(&format!("wrote {} and {}", shown(&body), shown(&contact)));
        }
    }
    let sweep = Sweep { rows };
    let out = match &sweep.rows[..] {
        [SweepRow::Solved(report)] if !many => output(report.as_ref(), args.format),
        _ => output(&sweep, args.format),
    };
    print(&out)?;
    let failed: Vec<String> = sweep
        .rows
        .iter()
        .filter_map(|row| match row {
            SweepRow::Solved(r) if !r.converged => Some(format!(
                "ε = {:e}, depth = {}: {}",
                r.epsilon,
                num(r.depth),
                r.diagnosis.as_deref().unwrap_or("not converged")
            )),
            SweepRow::Solved(_) => None,
            SweepRow::Failed(f) => Some(format!(
                "ε = {:e}, depth = {}: {}",
                f.epsilon,
                num(f.depth),
                f.reason
            )),
        })
        .collect();
    if failed.is_empty() {
        Ok(ExitCode::SUCCESS)
    } else {
        Err(CliError::Failed(format!(
            "no certified result for {}",
            failed.join("; ")
        )))
    }
}

/// The refusal of friction on a graded mesh, naming what asked for each: `--refine-edges`
/// when given, else the friction flags over the scenario's `[mesh] refine_edges` (a scenario
/// file with both is refused where it asks them, [`crate::input`]).
fn graded_friction(flag_given: bool, scenario: &crate::scenario::Scenario) -> CliError {
    if flag_given {
        return usage(
            "--refine-edges",
            "grading (at the edges or over the zone) is not available with friction yet; use a finer level",
        );
    }
    usage(
        "--friction",
        format!(
            "friction is not available on a graded mesh yet, and the scenario's `[mesh] refine_edges = {}` grades it; give --refine-edges 0, or use a finer level",
            scenario.grading()
        ),
    )
}

pub(super) fn plot_error(path: &std::path::Path, e: &std::io::Error) -> CliError {
    let what = match e.kind() {
        std::io::ErrorKind::AlreadyExists => "exists; not overwritten (--force replaces it)".to_string(),
        std::io::ErrorKind::InvalidInput => format!("{e} (--force replaces regular files only)"),
        _ => e.to_string(),
    };
    usage("--plot", format!("{}: {what}", shown(path)))
}
