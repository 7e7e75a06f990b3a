//! `riplab study`: every scheme against a refined reference, with its rates and fits
//! (docs/design.md §6); on a two-body scenario every discretisation of the interface against
//! the scenario's closed form (§12).

use std::process::ExitCode;

use clap::ValueEnum as _;

use super::args::{Select, StudyArgs, method_at, parse_levels};
use super::choices::ContactName;
use super::{CliError, grading, note, print, shown, usage};
use crate::check;
use crate::contact::Method;
use crate::contact::interface::InterfaceMethod;
use crate::contact::interface::solve::Enforcement;
use crate::output::{Format, InterfaceStudyReport, StudyReport, output};
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::study::interface::{ClosedForm, study_interface};
use crate::study::{Plan, ReferenceLevelError, all_ok};

/// The reference's refinements when `--reference-refinements` is not given.
const REFERENCE_REFINEMENTS: i64 = 4;

pub(super) fn study(args: &StudyArgs) -> Result<ExitCode, CliError> {
    let mut scenario = Select {
        scenario: args.scenario.clone(),
        ..Select::default()
    }
    .resolve()?;
    if scenario.upper.is_some() {
        return two_bodies(args, &scenario);
    }
    if !args.contact.is_empty() {
        return Err(usage(
            "--contact",
            format!(
                "{} has one body (a rigid obstacle): --contact chooses the discretisation across the interface of a two-body scenario ([upper])",
                scenario.source
            ),
        ));
    }
    scenario.friction = study_friction(args, &scenario)?;
    let schemes = if args.schemes.is_empty() {
        Scheme::PAPER.iter().map(|s| (s.element, s.rule)).collect()
    } else {
        args.schemes
            .iter()
            .map(|s| Scheme::parse(s).map(|s| (s.element, s.rule)))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|m| usage("--schemes", m))?
    };
    let reference_refinements = args.reference_refinements.unwrap_or(REFERENCE_REFINEMENTS);
    let method = args.method.resolve(&scenario)?;
    if let Some(m) = method.filter(|m| !m.uses_epsilon() && !args.sweep_epsilon.is_empty()) {
        return Err(usage(
            "--sweep-epsilon",
            format!(
                "{} does not use ε: its rows would not change and no rate against ε exists",
                m.name()
            ),
        ));
    }
    let levels = match args.level {
        Some(l) => {
            check::level(l).map_err(|m| usage("--level", m))?;
            vec![l as u32]
        }
        None => parse_levels(&args.levels).map_err(|m| usage("--levels", m))?,
    };
    // A penalty refinement study's default ε keeps the penalty's error below the mesh's.
    let penalty = matches!(method, None | Some(Method::Penalty)) && args.sweep_epsilon.is_empty();
    let epsilon = match args.epsilon {
        Some(e) => e,
        None if penalty => crate::study::penalty_error::default_epsilon(&scenario, levels[levels.len() - 1]),
        None => scenario.epsilon,
    };
    if args.epsilon.is_none() && epsilon != scenario.epsilon {
        note(&format!(
            "note: ε = {epsilon:.3e} (κ = εE/h = {:e} at level {}), not the scenario's {:e}, so that the penalty's error stays well below the mesh's (--epsilon sets it)",
            crate::study::penalty_error::STUDY_KAPPA,
            levels[levels.len() - 1],
            scenario.epsilon
        ));
    }
    if args.sweep_epsilon.is_empty() {
        method_at(method, epsilon, "--epsilon")?;
    }
    // ε's range depends on h: check it at the coarsest and the finest level studied.
    for &level in [levels[0], levels[levels.len() - 1]].iter() {
        let range = scenario.epsilon_range(level);
        check::epsilon_in(epsilon, range)
            .map_err(|m| usage("--epsilon", format!("at level {level}: {m}")))?;
        for &e in &args.sweep_epsilon {
            check::epsilon_in(e, range).map_err(|m| usage("--sweep-epsilon", m))?;
        }
    }
    let requested = match args.reference_level {
        Some(l) => {
            check::level(l).map_err(|m| usage("--reference-level", m))?;
            Some(l as u32)
        }
        None => None,
    };
    let reference_level = crate::study::reference_level(&levels, requested).map_err(|e| match e {
        ReferenceLevelError::NotFiner { .. } => usage("--reference-level", e),
        ReferenceLevelError::NoFinerLevel { .. } => usage("--levels", e),
    })?;
    check::integer(reference_refinements, 0, i64::from(crate::study::MAX_REFINEMENTS))
        .map_err(|m| usage("--reference-refinements", m))?;
    let dir = (!args.no_cache).then(crate::cache::default_dir).flatten();
    let mut fetch = |grid: &crate::study::ReferenceMesh| {
        let (fields, provenance) = crate::cache::fields(&scenario, grid, dir.as_deref())?;
        let what = match grid.refinements {
            0 => format!("reference level {}", grid.level),
            k => format!("reference level {} refinement {k}", grid.level),
        };
        match provenance {
            crate::cache::Provenance::Cached(path) => note(&format!(
                "{what} read from {} (computed in {:.1} s; --no-cache recomputes it)",
                shown(&path),
                fields.ms / 1e3
            )),
            other => {
                note(&format!(
                    "{what} done in {:.1} s ({} dofs)",
                    fields.ms / 1e3,
                    fields.n_dofs
                ));
                if let crate::cache::Provenance::Computed(Some(why)) = other {
                    note(&format!("warning: the reference is {why}"));
                }
            }
        }
        Ok(fields)
    };
    let refine = grading::refine_axis(&args.refine_edges, &scenario)?;
    if scenario.friction.is_on() && refine.iter().any(|r| r.grades()) {
        // A scenario with both is refused where it asks them (crate::input): the friction
        // here is the flags'.
        return Err(if args.refine_edges.is_empty() {
            usage(
                "--friction",
                format!(
                    "friction is not available on graded meshes yet, and the scenario's `[mesh] refine_edges = {}` grades them; give --refine-edges 0",
                    scenario.grading()
                ),
            )
        } else {
            usage(
                "--refine-edges",
                "grading (at the edges or over the zone) is not available with friction yet; study uniform levels (--refine-edges 0)",
            )
        });
    }
    // Every graded row's memory, estimated from its lines (Scenario::graded_fits) before
    // the reference or any row is assembled: one that cannot fit refuses the whole study.
    if args.sweep_epsilon.is_empty() {
        for &grading in &refine {
            for &(element, _) in &schemes {
                for &level in &levels {
                    scenario.graded_fits(level, element, grading, |_| 0)?;
                }
            }
        }
    }
    let with = match scenario.friction.is_on() {
        true => format!(", with {} friction imposed exactly", scenario.friction.law.name()),
        false => String::new(),
    };
    note(&format!(
        "the reference: q2 + simpson, ε = 0 (exact constraint){with}, level {reference_level} and, for its estimated error, level {} …",
        reference_level - 1
    ));
    let plan = if args.sweep_epsilon.is_empty() {
        Plan::Levels {
            levels: &levels,
            epsilon,
            refine: &refine,
        }
    } else {
        Plan::Sweep {
            level: levels[0],
            epsilons: &args.sweep_epsilon,
        }
    };
    let mut study = crate::study::study(
        &scenario,
        &schemes,
        method,
        plan,
        (reference_level, reference_refinements as u32),
        &mut fetch,
    )?;
    // Rows whose errors the penalty may account for: a field of the row (JSON, CSV) and a note
    // (a refinement's; in an ε sweep the penalty's share is what is measured).
    let mut notes = Vec::new();
    if args.sweep_epsilon.is_empty() {
        for row in &mut study.rows {
            if let Some(why) = crate::study::penalty_error::dominated(row, scenario.material.young) {
                row.epsilon_dominated = true;
                notes.push(why);
            }
        }
    }
    // The table says it in its own lines; JSON and CSV carry it in a field.
    if let (Some(why), false) = (&study.reference.stopped, args.format == Format::Table) {
        note(&format!(
            "warning: the reference's estimated error is above a tenth of the smallest row error; its refinement stopped at {}: {why}",
            study.reference.grid.refinements
        ));
    }
    print(&output(
        &StudyReport {
            scenario: &scenario.name,
            study: &study,
        },
        args.format,
    ))?;
    for why in notes {
        note(&format!("note: {why}"));
    }
    let rows = study.rows;
    if all_ok(&rows) {
        Ok(ExitCode::SUCCESS)
    } else {
        let n = rows
            .iter()
            .filter(|r| r.status != crate::study::Status::Ok)
            .count();
        Err(CliError::Failed(format!(
            "{n} of {} rows have no certified result (their status and reason are in the output)",
            rows.len()
        )))
    }
}

/// The friction of every row and of the reference: the scenario's `[friction]` with the
/// options applied ([`super::FrictionArgs::resolve`]); one loading history only (a list of
/// --shift-steps is `solve`'s sweep).
fn study_friction(
    args: &StudyArgs,
    scenario: &crate::scenario::Scenario,
) -> Result<crate::contact::friction::Friction, CliError> {
    let frictions = args.friction.resolve(scenario)?;
    match frictions[..] {
        [one] => Ok(one),
        _ => Err(usage(
            "--shift-steps",
            "a study takes one number of steps (a list sweeps them in `riplab solve`)",
        )),
    }
}

/// `riplab study` on a two-body scenario (docs/design.md §12, "The study across the
/// interface"): each `--contact` discretisation at each level of `--levels`, against the
/// scenario's closed form ([`crate::study::interface`]). The one-body study's options are
/// refused, and every level's memory is checked before any solve (exit 2); a row without a
/// result exits 1 after the output.
fn two_bodies(args: &StudyArgs, scenario: &Scenario) -> Result<ExitCode, CliError> {
    refuse_one_body_options(args, scenario)?;
    let levels = parse_levels(&args.levels).map_err(|m| usage("--levels", m))?;
    let method = args.method.resolve(scenario)?;
    let flag = match args.epsilon {
        Some(_) => "--epsilon",
        None => "the scenario's contact.epsilon",
    };
    let epsilon = args.epsilon.unwrap_or(scenario.epsilon);
    let enforcement = super::two_bodies::enforcement(method, epsilon, flag, scenario)?;
    if epsilon > 0.0 {
        for level in [levels[0], levels[levels.len() - 1]] {
            check::epsilon_in(epsilon, scenario.epsilon_range(level))
                .map_err(|m| usage(flag, format!("at level {level}: {m}")))?;
        }
    }
    let element = scenario.element;
    for &level in &levels {
        let upper = scenario.upper_sizes(level, element).map_or(0, |s| s.peak_bytes());
        scenario.fits_beside(level, element, upper)?;
    }
    let names = match args.contact.is_empty() {
        true => ContactName::value_variants(),
        false => &args.contact[..],
    };
    let mut methods: Vec<InterfaceMethod> = Vec::new();
    for &name in names {
        let m = super::two_bodies::method_of(name, scenario);
        if !methods.contains(&m) {
            methods.push(m);
        }
    }
    let rows = study_interface(scenario, &methods, &levels, enforcement)
        .map_err(|e| super::two_bodies::cli_error(e, flag))?;
    let upper = scenario.upper.as_ref().expect("a two-body scenario");
    let report = InterfaceStudyReport {
        scenario: &scenario.name,
        element: element.name(),
        ratio: [upper.ratio.0, upper.ratio.1],
        offset: upper.offset,
        slave: upper.slave.name(),
        method: match enforcement {
            Enforcement::Exact => "exact",
            Enforcement::Penalty(_) => "penalty",
            Enforcement::Alm { .. } => "alm",
        },
        epsilon: enforcement.epsilon(),
        closed_form: ClosedForm::of(scenario),
        rows: &rows,
    };
    print(&output(&report, args.format))?;
    match rows.iter().filter(|r| !r.ok()).count() {
        0 => Ok(ExitCode::SUCCESS),
        n => Err(CliError::Failed(format!(
            "{n} of {} rows have no result (their status and reason are in the output)",
            rows.len()
        ))),
    }
}

/// Refuse the one-body study's options on a two-body scenario: its schemes, gradings, ε
/// sweep, reference and friction.
fn refuse_one_body_options(args: &StudyArgs, scenario: &Scenario) -> Result<(), CliError> {
    let given: [(&str, bool); 7] = [
        ("--schemes", !args.schemes.is_empty()),
        ("--refine-edges", !args.refine_edges.is_empty()),
        ("--sweep-epsilon", !args.sweep_epsilon.is_empty()),
        ("--level", args.level.is_some()),
        ("--reference-level", args.reference_level.is_some()),
        ("--reference-refinements", args.reference_refinements.is_some()),
        ("--no-cache", args.no_cache),
    ];
    if let Some((flag, _)) = given.iter().find(|g| g.1) {
        return Err(usage(
            flag,
            "does not apply to a two-body scenario ([upper]): its study compares the interface's discretisations (--contact) over --levels against the scenario's closed form, with --method and --epsilon",
        ));
    }
    let frictions = args.friction.resolve(scenario)?;
    if frictions.len() > 1 || frictions[0].is_on() {
        return Err(usage(
            "--friction",
            "friction is not available on a two-body scenario ([upper]) yet",
        ));
    }
    Ok(())
}
