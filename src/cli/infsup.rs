//! `riplab infsup`: the discrete inf-sup constants of every scheme and level, on the uniform
//! levels or (`--refine-edges`) on meshes graded at the contact edges; on a two-body scenario
//! those of every multiplier space across the interface (docs/design.md §12).

use std::ops::ControlFlow;
use std::process::ExitCode;
use std::time::Instant;

use super::args::{InfsupArgs, parse_levels};
use super::two_bodies::cli_error;
use super::{CliError, grading, note, print, usage};
use crate::contact::newton::NewtonOptions;
use crate::contact::{ContactParams, Rule};
use crate::error::SolveError;
use crate::fem::memory::Sizes;
use crate::grading::Grading;
use crate::infsup::interface::Space;
use crate::infsup::interface_table::{self, interface_table};
use crate::infsup::{InfSupRow, TraceCompliance, estimate, fits, fits_beside, slope};
use crate::mesh::Element;
use crate::output::{InfSupTable, InterfaceInfSupTable, output};
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::solve::{Request, solve};

pub(super) fn infsup(args: &InfsupArgs) -> Result<ExitCode, CliError> {
    let scenario = args.select.resolve()?;
    let levels = levels(args, &scenario)?;
    if scenario.upper.is_some() {
        return two_bodies(args, &scenario, &levels);
    }
    let refine = grading::refine_edges(args.refine_edges.as_deref(), &scenario)?;
    let pairs: Vec<(Element, Rule)> = if args.all {
        Scheme::all().into_iter().map(|s| (s.element, s.rule)).collect()
    } else {
        vec![(scenario.element, scenario.rule)]
    };
    // Every level's memory, from its lines, before anything is assembled.
    for &(element, _) in &pairs {
        for &level in &levels {
            if refine.grades() {
                scenario.graded_fits(level, element, refine, Sizes::infsup_extra_bytes)?;
            } else {
                fits(&scenario, level, element)?;
            }
        }
    }
    let rows = if refine.grades() {
        let (graded, h) = match refine {
            Grading::Zone(_) => (
                "over the contact zone",
                "graded mesh's widest cell (a slope only between different h)",
            ),
            Grading::Edges(_) => ("at the contact edges", "level's widest cell"),
        };
        note(&format!(
            "riplab: --refine-edges {refine}: β_h on meshes graded {graded}, each scheme's by its \
             own solve at ε = {}; h is the {h}",
            crate::text::num(scenario.epsilon)
        ));
        graded_table(&scenario, &pairs, &levels, refine)?
    } else {
        crate::infsup::table(&scenario, &pairs, &levels)?
    };
    print(&output(&InfSupTable { rows }, args.format))?;
    Ok(ExitCode::SUCCESS)
}

/// The levels asked: `--level L` alone estimates that level; `--levels` a range (they
/// exclude each other); 0..4 by default.
fn levels(args: &InfsupArgs, scenario: &Scenario) -> Result<Vec<u32>, CliError> {
    Ok(match (&args.levels, args.select.level) {
        (Some(text), _) => parse_levels(text).map_err(|m| usage("--levels", m))?,
        (None, Some(_)) => vec![scenario.level],
        (None, None) => parse_levels("0..4").expect("the default levels parse"),
    })
}

/// `riplab infsup` on a two-body scenario: β_h of mortar's, mortar-dual's, NTS's spaces and
/// of the rule's points and p̄ (every rule's with `--all`) across the interface, the element
/// the scenario's (or --element's). Every level's memory is checked before anything is built.
fn two_bodies(args: &InfsupArgs, scenario: &Scenario, levels: &[u32]) -> Result<ExitCode, CliError> {
    if args.refine_edges.is_some() {
        return Err(usage(
            "--refine-edges",
            "does not apply to a two-body scenario ([upper]): grading is not available yet",
        ));
    }
    let rules = if args.all {
        Rule::ALL.to_vec()
    } else {
        vec![scenario.rule]
    };
    let spaces = Space::with_rules(&rules);
    // No ε enters the estimate: the flag a two-body solve's ε error would name never shows.
    let error = |e| cli_error(e, "--epsilon");
    for &level in levels {
        interface_table::fits(scenario, level, scenario.element).map_err(error)?;
    }
    let rows = interface_table(scenario, &spaces, levels).map_err(error)?;
    print(&output(&InterfaceInfSupTable { rows }, args.format))?;
    Ok(ExitCode::SUCCESS)
}

/// The table of [`crate::infsup::table`] on graded meshes: for each pair and level, the
/// scheme's solve graded at its contact edges as `refine` asks ([`solve`]: the edges
/// are where its own pressure leaves contact), then β_h and β̄_h on the final mesh; grouped
/// per pair by ascending level, each row with its slope from the one before. The mesh time
/// of a row is its graded solve's and its trace compliance's.
fn graded_table(
    scenario: &Scenario,
    pairs: &[(Element, Rule)],
    levels: &[u32],
    refine: Grading,
) -> Result<Vec<InfSupRow>, SolveError> {
    let mut rows: Vec<InfSupRow> = Vec::new();
    for &(element, rule) in pairs {
        for &level in levels {
            fits(scenario, level, element)?;
            let t = Instant::now();
            let uniform = scenario.discretize(level, element)?;
            let params = ContactParams::by_epsilon(rule, scenario.epsilon, scenario.obstacle.clone());
            let request = Request::new(params).with_grading(scenario, level, refine);
            let graded = solve(&uniform, &request, &NewtonOptions::default(), &mut |_| {
                ControlFlow::Continue(())
            })?;
            let disc = graded.disc(&uniform);
            fits_beside(disc)?;
            let compliance = TraceCompliance::new(disc)?;
            let mesh_ms = t.elapsed().as_secs_f64() * 1e3;
            let t = Instant::now();
            let est = estimate(disc, &compliance, rule)?;
            let mut row = InfSupRow::new(
                level,
                element,
                rule,
                est,
                mesh_ms,
                t.elapsed().as_secs_f64() * 1e3,
            );
            if let Some(prev) = rows.last().filter(|p| p.same_pair(&row)) {
                row.slope = slope(prev, &row);
            }
            rows.push(row);
        }
    }
    Ok(rows)
}
