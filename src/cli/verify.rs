//! `riplab verify`: the verification pack ([`crate::verify`]) graded case by case, as a
//! table, CSV or JSON; exit 1 when a check is NOOK.

use std::process::ExitCode;

use clap::Args;

use crate::output::{Format, output};

use super::choices::{FormatName, choice};
use super::{CliError, print, usage};

/// The arguments of `riplab verify`.
#[derive(Args, Debug)]
pub struct VerifyArgs {
    /// Run only this case (`--list` names them).
    #[arg(long, value_name = "NAME")]
    pub case: Option<String>,
    /// List the cases, their default levels and their references' sources.
    #[arg(long, conflicts_with_all = ["case", "level", "print_stored"])]
    pub list: bool,
    /// Run every case at this level (2 to 5; cattaneo-mindlin alone to 6) instead of its
    /// default; no stored value is compared then.
    #[arg(long, short, allow_negative_numbers = true)]
    pub level: Option<i64>,
    /// Print src/verify/stored.toml anew from this run's values (at the default levels).
    #[arg(long, conflicts_with_all = ["case", "level", "format"])]
    pub print_stored: bool,
    /// Output format (docs/design.md §7).
    #[arg(long, short, value_parser = choice::<FormatName, Format>(), default_value = "table")]
    pub format: Format,
}

/// Run `riplab verify`: exit 0 when every check is OK, 1 otherwise.
pub(super) fn verify(args: &VerifyArgs) -> Result<ExitCode, CliError> {
    let all = crate::verify::cases();
    if args.list {
        print(&output(&crate::output::verify::CaseList::new(&all), args.format))?;
        return Ok(ExitCode::SUCCESS);
    }
    let chosen = crate::verify::select(&all, args.case.as_deref()).map_err(|e| usage("--case", e))?;
    let level = match args.level {
        Some(l) => {
            // The finest level every chosen case accepts.
            let max = chosen
                .iter()
                .map(|c| c.max_level)
                .min()
                .unwrap_or(crate::verify::MAX_VERIFY_LEVEL);
            crate::check::integer(l, i64::from(crate::verify::MIN_VERIFY_LEVEL), i64::from(max))
                .map_err(|m| usage("--level", m))?;
            Some(l as u32)
        }
        None => None,
    };
    let checks = chosen
        .into_iter()
        .flat_map(|c| crate::verify::run(c, level))
        .collect();
    let verification = crate::verify::Verification::new(checks);
    if args.print_stored {
        print(&crate::verify::stored::file(&verification.checks))?;
    } else {
        print(&output(&verification, args.format))?;
    }
    if verification.passed {
        Ok(ExitCode::SUCCESS)
    } else {
        let nook = verification
            .checks
            .iter()
            .filter(|c| c.verdict != crate::verify::Verdict::Ok)
            .count();
        Err(CliError::Failed(format!(
            "{nook} of {} checks are NOOK (the output says which and why)",
            verification.checks.len()
        )))
    }
}
