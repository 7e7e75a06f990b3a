//! `s`: the displayed solution as CSV (the CLI's `--format csv`) in a new file of the current
//! directory. Never overwrites: the name is fresh, the file is written to a temporary name and
//! then linked into place, which fails if the name was taken meanwhile.

use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use crate::report::SolveReport;
use crate::scenario::Scenario;

use super::worker::Solved;

/// How many numbered names to try before giving up.
const MAX_TRIES: u32 = 1000;

/// Write `solved` to `<scenario>-<element>-<rule>-L<level>[-N].csv` in `dir`; returns the path.
pub fn export_csv(scenario: &Scenario, solved: &Solved, dir: &Path) -> Result<PathBuf, String> {
    let report = SolveReport::new(scenario, solved.key.level, &solved.disc, &solved.solution);
    let text = report.csv();
    let stem = format!(
        "{}-{}-{}-L{}",
        sanitize(&scenario.name),
        report.element,
        report.rule,
        solved.key.level
    );
    let tmp = dir.join(format!(".{stem}.{}.tmp", std::process::id()));
    let write = || -> std::io::Result<()> {
        let mut f = fs::File::create_new(&tmp)?;
        f.write_all(text.as_bytes())?;
        f.sync_all()
    };
    write().map_err(|e| format!("{}: {e}", tmp.display()))?;
    let result = claim(&tmp, dir, &stem);
    let _ = fs::remove_file(&tmp);
    result
}

/// Link `tmp` to the first free name `stem.csv`, `stem-1.csv`, …: a hard link fails when the
/// target exists, so nothing is overwritten even under a race. Where hard links are not
/// supported, fall back to a rename onto a name that does not exist.
fn claim(tmp: &Path, dir: &Path, stem: &str) -> Result<PathBuf, String> {
    for n in 0..MAX_TRIES {
        let path = dir.join(if n == 0 {
            format!("{stem}.csv")
        } else {
            format!("{stem}-{n}.csv")
        });
        match fs::hard_link(tmp, &path) {
            Ok(()) => return Ok(path),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(_) if !path.exists() => {
                return fs::rename(tmp, &path)
                    .map(|()| path.clone())
                    .map_err(|e| format!("{}: {e}", path.display()));
            }
            Err(_) => continue,
        }
    }
    Err(format!("no free file name for {stem}.csv in {}", dir.display()))
}

/// The scenario name reduced to characters safe in a file name.
fn sanitize(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}
