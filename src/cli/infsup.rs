//! `riplab infsup`: the discrete inf-sup constants of every scheme and level.

use std::process::ExitCode;

use super::args::{InfsupArgs, parse_levels};
use super::{CliError, print, usage};
use crate::contact::Rule;
use crate::mesh::Element;
use crate::output::{InfSupTable, output};
use crate::scheme::Scheme;

pub(super) fn infsup(args: &InfsupArgs) -> Result<ExitCode, CliError> {
    let scenario = args.select.resolve()?;
    // `--level L` alone estimates that level; `--levels` a range (they exclude each other).
    let levels = match (&args.levels, args.select.level) {
        (Some(text), _) => parse_levels(text).map_err(|m| usage("--levels", m))?,
        (None, Some(_)) => vec![scenario.level],
        (None, None) => parse_levels("0..4").expect("the default levels parse"),
    };
    let pairs: Vec<(Element, Rule)> = if args.all {
        Scheme::all().into_iter().map(|s| (s.element, s.rule)).collect()
    } else {
        vec![(scenario.element, scenario.rule)]
    };
    let rows = crate::infsup::table(&scenario, &pairs, &levels)?;
    print(&output(&InfSupTable { rows }, args.format))?;
    Ok(ExitCode::SUCCESS)
}
