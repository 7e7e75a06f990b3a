//! Every file one command writes, checked against the others before anything is computed or
//! written: `--plot x.vtu --vtu x.vtu` would have the VTU replace the SVG, and
//! `--plot x.contact.vtu --vtu x.vtu` the Γ_C file replace the plot. Two targets are the same
//! when their absolute paths, with the directory resolved on the filesystem (links, `..`),
//! are equal, or when both exist and are one file (hard links).

use std::path::{Path, PathBuf};

use super::CliError;
use crate::text::sanitize;

/// `path` as the filesystem will resolve it: absolute, its directory canonical when it
/// exists (a missing directory fails the write anyway).
fn resolved(path: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let (Some(dir), Some(name)) = (absolute.parent(), absolute.file_name()) else {
        return absolute;
    };
    match dir.canonicalize() {
        Ok(dir) => dir.join(name),
        Err(_) => absolute,
    }
}

/// Whether two existing paths are one file (device and inode).
#[cfg(unix)]
fn same_file(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(a), Ok(b)) => (a.dev(), a.ino()) == (b.dev(), b.ino()),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(_: &Path, _: &Path) -> bool {
    false
}

/// Refuse (exit 2) when two of `targets` (what names it, the path) are the same file.
pub(super) fn distinct(targets: &[(&str, PathBuf)]) -> Result<(), CliError> {
    let resolved: Vec<PathBuf> = targets.iter().map(|(_, p)| resolved(p)).collect();
    for (i, (what, path)) in targets.iter().enumerate() {
        for (j, (other, other_path)) in targets.iter().enumerate().take(i) {
            if resolved[i] == resolved[j] || same_file(path, other_path) {
                return Err(CliError::Usage(format!(
                    "{what} {} is also {other} ({}): each output needs its own file",
                    sanitize(&path.display().to_string()),
                    sanitize(&other_path.display().to_string())
                )));
            }
        }
    }
    Ok(())
}
