//! The cache's file I/O, as a careful program does it:
//!
//! - an entry is written to a temporary file in the cache directory whose name holds the
//!   process id and a random number (unpredictable: a name cannot be planted in advance),
//!   created exclusively (`O_CREAT | O_EXCL`, and `O_NOFOLLOW`: never through a link, never
//!   onto a FIFO or another file), private to the user, then renamed into place;
//! - temporaries older than [`STALE`] (left by killed runs) are removed when an entry is
//!   written, regular files only;
//! - an entry is read through one handle, opened without following a link and without
//!   blocking (`O_NOFOLLOW | O_NONBLOCK`: a FIFO or a device there cannot stall the study), a
//!   regular file checked on that handle (`fstat`, so it cannot be swapped between the check
//!   and the read), of exactly the size its key implies, and read to at most that size.

use std::fs;
use std::io::{self, Read as _, Write as _};
use std::path::Path;
use std::time::Duration;

use super::fnv1a;
use crate::study::{ReferenceFields, ReferenceSource};

const MAGIC: &[u8; 8] = b"RIPREF01";

/// A temporary file older than this is a killed run's, and removed (a live run holds its
/// temporary for the seconds of one write).
pub const STALE: Duration = Duration::from_secs(3600);

/// The prefix and suffix of every temporary file of the cache.
const TMP_PREFIX: &str = ".reference-";
const TMP_SUFFIX: &str = ".tmp";

fn encode(key: &str, f: &ReferenceFields) -> Vec<u8> {
    let mut out = Vec::with_capacity(64 + key.len() + 8 * (f.u.len() + f.p.len() + f.t.len()));
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&(key.len() as u64).to_le_bytes());
    out.extend_from_slice(key.as_bytes());
    for n in [f.u.len(), f.p.len(), f.n_dofs] {
        out.extend_from_slice(&(n as u64).to_le_bytes());
    }
    for v in [f.load, f.ms].iter().chain(&f.u).chain(&f.p).chain(&f.t) {
        out.extend_from_slice(&v.to_le_bytes());
    }
    let sum = fnv1a(&out);
    out.extend_from_slice(&sum.to_le_bytes());
    out
}

/// The size of the entry of `key` with `n_u` displacements, `n_p` pressures and `n_t`
/// tangential tractions (0 without friction; its key says whether it has friction).
fn entry_size(key: &str, n_u: usize, n_p: usize, n_t: usize) -> usize {
    8 + 8 + key.len() + 3 * 8 + 8 * (2 + n_u + n_p + n_t) + 8
}

/// Open `path` for reading without following a link and without blocking on a FIFO.
fn open_entry(path: &Path) -> io::Result<fs::File> {
    let mut options = fs::OpenOptions::new();
    options.read(true);
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::fs::OpenOptionsExt as _;
        options.custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK);
    }
    options.open(path)
}

/// The bytes of the entry at `path` if it is a regular file of exactly `size` bytes (checked
/// on the open handle), read to at most that size.
fn read_bytes(path: &Path, size: usize) -> Option<Vec<u8>> {
    let file = open_entry(path).ok()?;
    let meta = file.metadata().ok()?;
    if !meta.is_file() || meta.len() != size as u64 {
        return None;
    }
    let mut bytes = Vec::with_capacity(size);
    file.take(size as u64 + 1).read_to_end(&mut bytes).ok()?;
    (bytes.len() == size).then_some(bytes)
}

/// The entry at `path` if it is exactly the one asked for (`n_t` tangential tractions after
/// its pressures: 0 without friction); None for anything else.
pub fn read(path: &Path, key: &str, n_u: usize, n_p: usize, n_t: usize) -> Option<ReferenceFields> {
    let size = entry_size(key, n_u, n_p, n_t);
    let bytes = read_bytes(path, size)?;
    let (body, sum) = bytes.split_at(size - 8);
    if fnv1a(body) != u64::from_le_bytes(sum.try_into().ok()?) {
        return None;
    }
    let mut at = 0;
    let mut take = |n: usize| {
        let s = &body[at..at + n];
        at += n;
        s
    };
    let word = |b: &[u8]| u64::from_le_bytes(b.try_into().expect("8 bytes"));
    if take(8) != MAGIC || word(take(8)) != key.len() as u64 || take(key.len()) != key.as_bytes() {
        return None;
    }
    let (u_len, p_len, n_dofs) = (word(take(8)), word(take(8)), word(take(8)));
    if (u_len, p_len) != (n_u as u64, n_p as u64) {
        return None;
    }
    let n_dofs = usize::try_from(n_dofs).ok()?;
    let mut float = || f64::from_le_bytes(take(8).try_into().expect("8 bytes"));
    let (load, ms) = (float(), float());
    let u: Vec<f64> = (0..n_u).map(|_| float()).collect();
    let p: Vec<f64> = (0..n_p).map(|_| float()).collect();
    let t: Vec<f64> = (0..n_t).map(|_| float()).collect();
    Some(ReferenceFields {
        u,
        p,
        t,
        load,
        n_dofs,
        ms,
        source: ReferenceSource::Cache,
    })
}

/// A fresh temporary file beside `path` in `dir`: an unpredictable name, created exclusively,
/// never through a link, readable by the user only.
fn create_temporary(dir: &Path, path: &Path) -> io::Result<(fs::File, std::path::PathBuf)> {
    use std::hash::{BuildHasher as _, Hasher as _};
    let name = path
        .file_name()
        .map_or_else(Default::default, |n| n.to_string_lossy());
    let stem = name.strip_prefix("reference-").unwrap_or(&name);
    for _ in 0..8 {
        // RandomState is seeded from the operating system's entropy in every process.
        let mut h = std::collections::hash_map::RandomState::new().build_hasher();
        h.write_u64(u64::from(std::process::id()));
        let tmp = dir.join(format!(
            "{TMP_PREFIX}{stem}.{}.{:016x}{TMP_SUFFIX}",
            std::process::id(),
            h.finish()
        ));
        let mut options = fs::OpenOptions::new();
        options.write(true).create_new(true);
        #[cfg(unix)]
        {
            use std::os::unix::fs::OpenOptionsExt as _;
            options.mode(0o600);
            #[cfg(target_os = "linux")]
            options.custom_flags(libc::O_NOFOLLOW);
        }
        match options.open(&tmp) {
            Ok(f) => return Ok((f, tmp)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
    Err(io::Error::new(
        io::ErrorKind::AlreadyExists,
        "no fresh temporary name after 8 tries",
    ))
}

/// Remove the cache's temporary files in `dir` older than [`STALE`] (regular files only: a
/// link or anything else there is left alone).
pub fn clean_stale(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if !(name.starts_with(TMP_PREFIX) && name.ends_with(TMP_SUFFIX)) {
            continue;
        }
        let Ok(meta) = fs::symlink_metadata(entry.path()) else {
            continue;
        };
        let old = meta
            .modified()
            .ok()
            .and_then(|t| t.elapsed().ok())
            .is_some_and(|age| age > STALE);
        if meta.file_type().is_file() && old {
            let _ = fs::remove_file(entry.path());
        }
    }
}

/// Store `fields` at `path`: written to a fresh temporary file in `dir`, then renamed into
/// place; stale temporaries of killed runs are removed first.
pub fn write(dir: &Path, path: &Path, key: &str, fields: &ReferenceFields) -> io::Result<()> {
    fs::create_dir_all(dir)?;
    clean_stale(dir);
    let (mut f, tmp) = create_temporary(dir, path)?;
    let result = (|| {
        f.write_all(&encode(key, fields))?;
        f.sync_all()?;
        fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fields() -> ReferenceFields {
        ReferenceFields {
            u: vec![0.0, -1.5, 2.25e-300, 7.0],
            p: vec![1.0, 2.0, 3.0],
            t: Vec::new(),
            load: 643.0075,
            n_dofs: 3,
            ms: 12.5,
            source: ReferenceSource::Cache,
        }
    }

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("riplab-cache-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn an_entry_reads_back_exactly_and_only_as_itself() {
        let dir = scratch("unit");
        let path = dir.join("entry.bin");
        write(&dir, &path, "key A", &fields()).unwrap();
        assert_eq!(read(&path, "key A", 4, 3, 0), Some(fields()));
        // Another key of the same length, other lengths: not this entry.
        assert_eq!(read(&path, "key B", 4, 3, 0), None);
        assert_eq!(read(&path, "key A", 5, 3, 0), None);
        // One flipped byte anywhere: refused by the checksum (or the header).
        let good = fs::read(&path).unwrap();
        for i in [0, 9, 20, good.len() / 2, good.len() - 1] {
            let mut bad = good.clone();
            bad[i] ^= 0x10;
            fs::write(&path, &bad).unwrap();
            assert_eq!(read(&path, "key A", 4, 3, 0), None, "byte {i}");
        }
        // Truncated: refused.
        fs::write(&path, &good[..good.len() - 3]).unwrap();
        assert_eq!(read(&path, "key A", 4, 3, 0), None);
        // Nothing but the entry is left: no temporary.
        let names: Vec<_> = fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("entry.bin")]);
        fs::remove_dir_all(&dir).unwrap();
    }

    /// The old temporary name (`.<entry>.<pid>.tmp`) planted as a link to a victim, or as a
    /// FIFO, is neither followed nor blocked on: the write goes to a fresh name.
    #[cfg(target_os = "linux")]
    #[test]
    fn a_planted_temporary_is_never_followed_or_blocked_on() {
        let dir = scratch("planted");
        let path = dir.join("reference-0123.bin");
        let victim = dir.join("victim");
        fs::write(&victim, b"precious").unwrap();
        let pid = std::process::id();
        std::os::unix::fs::symlink(&victim, dir.join(format!(".reference-0123.bin.{pid}.tmp"))).unwrap();
        let fifo =
            std::ffi::CString::new(dir.join(format!(".reference-0123.{pid}.tmp")).to_str().unwrap()).unwrap();
        // SAFETY: mkfifo with a valid C string.
        assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o600) }, 0);
        write(&dir, &path, "key", &fields()).unwrap();
        assert_eq!(fs::read(&victim).unwrap(), b"precious");
        assert_eq!(read(&path, "key", 4, 3, 0), Some(fields()));
        fs::remove_dir_all(&dir).unwrap();
    }

    /// An entry that is a link (to /dev/zero, or to a good entry), a FIFO or a directory is not
    /// read, and nothing blocks or reads without bound.
    #[cfg(target_os = "linux")]
    #[test]
    fn an_entry_is_read_only_as_a_regular_file_through_one_handle() {
        let dir = scratch("special");
        let good = dir.join("good.bin");
        write(&dir, &good, "key", &fields()).unwrap();
        let link = dir.join("link.bin");
        std::os::unix::fs::symlink(&good, &link).unwrap();
        assert_eq!(read(&link, "key", 4, 3, 0), None, "a link is not followed");
        let zero = dir.join("zero.bin");
        std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
        assert_eq!(read(&zero, "key", 4, 3, 0), None);
        let fifo = dir.join("fifo.bin");
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: mkfifo with a valid C string.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        assert_eq!(read(&fifo, "key", 4, 3, 0), None, "a FIFO is not waited on");
        fs::create_dir(dir.join("dir.bin")).unwrap();
        assert_eq!(read(&dir.join("dir.bin"), "key", 4, 3, 0), None);
        fs::remove_dir_all(&dir).unwrap();
    }

    /// Temporaries older than an hour are removed; fresh ones, links and other files stay.
    #[cfg(target_os = "linux")]
    #[test]
    fn stale_temporaries_are_cleaned() {
        let dir = scratch("stale");
        let old = dir.join(".reference-1.bin.1.tmp");
        let fresh = dir.join(".reference-2.bin.2.tmp");
        let other = dir.join("reference-3.bin");
        for f in [&old, &fresh, &other] {
            fs::write(f, b"x").unwrap();
        }
        let link = dir.join(".reference-4.bin.4.tmp");
        std::os::unix::fs::symlink(&other, &link).unwrap();
        let two_hours_ago = std::time::SystemTime::now() - Duration::from_secs(7200);
        fs::File::options()
            .write(true)
            .open(&old)
            .unwrap()
            .set_modified(two_hours_ago)
            .unwrap();
        clean_stale(&dir);
        assert!(!old.exists());
        assert!(fresh.exists() && other.exists() && fs::symlink_metadata(&link).is_ok());
        fs::remove_dir_all(&dir).unwrap();
    }
}
