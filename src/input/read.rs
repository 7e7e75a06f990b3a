//! Bounded reading: a scenario or tour file read as UTF-8 text, only from a regular file and
//! never more than [`MAX_FILE_BYTES`].

use std::path::Path;

use super::locate::{Locator, ScenarioError};

/// The largest scenario or tour file riplab reads.
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// Read a TOML file of at most [`MAX_FILE_BYTES`] as UTF-8 text: (its name for errors, its
/// text). `what` names the kind of file in the errors ("a scenario", "a tour").
///
/// Only regular files are read (a FIFO would block, a device such as `/dev/zero` never
/// ends), and never more than the cap plus one byte, whatever size the file claims: a file
/// that grows while it is read is refused like one that was too large from the start.
pub fn read_toml(path: &Path, what: &str) -> Result<(String, String), ScenarioError> {
    use std::io::Read as _;
    let file = path.display().to_string();
    let plain = |message: String| ScenarioError {
        file: file.clone(),
        location: None,
        key: None,
        message,
        source_line: None,
    };
    let not_regular = |meta: &std::fs::Metadata| {
        plain(format!(
            "is not a regular file ({}); {what} is read from a regular file of at most 1 MiB",
            file_kind(meta)
        ))
    };
    // Ask before opening: opening a FIFO for reading blocks until a writer comes.
    let meta = std::fs::metadata(path).map_err(|e| plain(format!("cannot read: {e}")))?;
    if !meta.is_file() {
        return Err(not_regular(&meta));
    }
    let handle = std::fs::File::open(path).map_err(|e| plain(format!("cannot read: {e}")))?;
    // The file opened may not be the one asked about (a rename in between): ask again.
    let meta = handle
        .metadata()
        .map_err(|e| plain(format!("cannot read: {e}")))?;
    if !meta.is_file() {
        return Err(not_regular(&meta));
    }
    let mut bytes = Vec::with_capacity(meta.len().min(MAX_FILE_BYTES) as usize + 1);
    handle
        .take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| plain(format!("cannot read: {e}")))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(plain(format!(
            "is larger than 1 MiB ({} bytes or more); {what} is at most 1 MiB",
            bytes.len()
        )));
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        let offset = e.utf8_error().valid_up_to();
        let text = String::from_utf8_lossy(e.as_bytes()).into_owned();
        Locator {
            file: &file,
            text: &text,
        }
        .error(Some(offset..offset), None, "is not valid UTF-8".into())
    })?;
    Ok((file, text))
}

/// What kind of file system object `meta` describes, for an error message.
fn file_kind(meta: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt as _;
        let t = meta.file_type();
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if meta.is_dir() {
        "a directory"
    } else {
        "not a regular file"
    }
}
