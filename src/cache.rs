//! The study's reference, kept between runs (issue 13): the exact-constraint Q2 solution of a
//! scenario at a level costs seconds to minutes (12 s at level 6, 67 s at level 7), and it
//! depends only on the body, the material, the obstacle and the level. It is stored in the
//! user's cache directory (`$XDG_CACHE_HOME/riplab`, `~/.cache/riplab`; the platform's
//! convention elsewhere), one file per reference, named by a hash of its key.
//!
//! The key is the text of everything the reference depends on, with riplab's version: a new
//! version never reads an old entry. A file is written to a temporary name and renamed into
//! place, so concurrent runs never see half a file (two that compute the same entry write the
//! same bytes). A file is read only when its size is exactly what its key implies, its key
//! text equals the one asked for (no hash collision can mix two entries) and its checksum
//! matches; anything else is recomputed and replaced.
//!
//! A reference refined at its contact edges ([`crate::study::ReferenceMesh::refined`]) is kept
//! step by step, each keyed by its refinement count and its vertex lines too, so that a refined
//! entry can never be read as another grid's.

use std::fs;
use std::io::{self, Write as _};
use std::path::{Path, PathBuf};

use crate::error::SolveError;
use crate::scenario::Scenario;
use crate::study::{REFERENCE_SCHEME, Reference, ReferenceFields, ReferenceMesh};

const MAGIC: &[u8; 8] = b"RIPREF01";

/// Where the reference came from.
#[derive(Clone, Debug, PartialEq)]
pub enum Provenance {
    /// Read from this file.
    Cached(PathBuf),
    /// Computed now and stored in this file.
    Stored(PathBuf),
    /// Computed now; not stored (no cache asked for, or the store failed: why).
    Computed(Option<String>),
}

/// The user's cache directory for riplab, if the platform has one.
pub fn default_dir() -> Option<PathBuf> {
    dirs::cache_dir().map(|d| d.join("riplab"))
}

/// The reference of `scenario` at the uniform `level`: from `dir` when an entry is there and
/// sound, otherwise computed (and stored in `dir`). `dir` None computes without the cache.
pub fn reference(
    scenario: &Scenario,
    level: u32,
    dir: Option<&Path>,
) -> Result<(Reference, Provenance), SolveError> {
    crate::study::check_contact(scenario)?;
    let grid = ReferenceMesh::uniform(scenario, level);
    let (fields, provenance) = fields(scenario, &grid, dir)?;
    let reference = Reference::from_fields(scenario, &grid, &fields);
    reference.check_meaningful()?;
    Ok((reference, provenance))
}

/// The reference's fields on `grid`: from `dir` when an entry is there and sound, otherwise
/// computed (and stored in `dir`). `dir` None computes without the cache.
pub fn fields(
    scenario: &Scenario,
    grid: &ReferenceMesh,
    dir: Option<&Path>,
) -> Result<(ReferenceFields, Provenance), SolveError> {
    // A custom outline has no text that identifies it: never cached.
    let dir = dir.filter(|_| !matches!(scenario.obstacle, crate::contact::Obstacle::Custom { .. }));
    let Some(dir) = dir else {
        return Ok((
            ReferenceFields::solve_on(scenario, grid)?,
            Provenance::Computed(None),
        ));
    };
    let key = key(scenario, grid);
    let path = dir.join(format!("reference-{:016x}.bin", fnv1a(key.as_bytes())));
    let (n_u, n_p) = grid.lengths();
    if let Some(fields) = read(&path, &key, n_u, n_p) {
        return Ok((fields, Provenance::Cached(path)));
    }
    let fields = ReferenceFields::solve_on(scenario, grid)?;
    let provenance = match write(dir, &path, &key, &fields) {
        Ok(()) => Provenance::Stored(path),
        Err(e) => Provenance::Computed(Some(format!("not stored in {}: {e}", dir.display()))),
    };
    Ok((fields, provenance))
}

/// Everything the reference depends on, as text (f64's Debug form round-trips exactly); a
/// refined grid adds its refinement count and its vertex lines.
fn key(s: &Scenario, grid: &ReferenceMesh) -> String {
    let mut key = format!(
        "riplab {} reference {:?} level {}\nbody {:?} x {:?} y {:?} half {}\nmaterial {:?}\nintegration {:?}\nobstacle {:?}",
        env!("CARGO_PKG_VERSION"),
        REFERENCE_SCHEME,
        grid.level,
        (s.width, s.height),
        s.x_lines,
        s.y_lines,
        s.half_model,
        s.material,
        s.integration,
        s.obstacle
    );
    if grid.refinements > 0 {
        key.push_str(&format!(
            "\nrefinements {}\nxs {:?}\nys {:?}",
            grid.refinements, grid.xs, grid.ys
        ));
    }
    key
}

/// FNV-1a, 64 bits: the file name's hash and the payload's checksum (stable across builds,
/// unlike the standard library's hasher).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

fn encode(key: &str, f: &ReferenceFields) -> Vec<u8> {
    let mut out = Vec::with_capacity(64 + key.len() + 8 * (f.u.len() + f.p.len()));
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&(key.len() as u64).to_le_bytes());
    out.extend_from_slice(key.as_bytes());
    for n in [f.u.len(), f.p.len(), f.n_dofs] {
        out.extend_from_slice(&(n as u64).to_le_bytes());
    }
    for v in [f.load, f.ms].iter().chain(&f.u).chain(&f.p) {
        out.extend_from_slice(&v.to_le_bytes());
    }
    let sum = fnv1a(&out);
    out.extend_from_slice(&sum.to_le_bytes());
    out
}

/// The entry at `path` if it is exactly the one asked for; None for anything else.
fn read(path: &Path, key: &str, n_u: usize, n_p: usize) -> Option<ReferenceFields> {
    let size = 8 + 8 + key.len() + 3 * 8 + 8 * (2 + n_u + n_p) + 8;
    let meta = fs::metadata(path).ok()?;
    if !meta.is_file() || meta.len() != size as u64 {
        return None;
    }
    let bytes = fs::read(path).ok()?;
    if bytes.len() != size {
        return None;
    }
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
    let mut float = || f64::from_le_bytes(take(8).try_into().expect("8 bytes"));
    let (load, ms) = (float(), float());
    let u: Vec<f64> = (0..n_u).map(|_| float()).collect();
    let p: Vec<f64> = (0..n_p).map(|_| float()).collect();
    let finite = load.is_finite() && u.iter().chain(&p).all(|v| v.is_finite());
    finite.then_some(ReferenceFields {
        u,
        p,
        load,
        n_dofs: n_dofs as usize,
        ms,
    })
}

/// Store `fields` at `path`: written to a temporary file in `dir`, then renamed into place.
fn write(dir: &Path, path: &Path, key: &str, fields: &ReferenceFields) -> io::Result<()> {
    fs::create_dir_all(dir)?;
    let tmp = dir.join(format!(
        ".{}.{}.tmp",
        path.file_name()
            .map_or_else(Default::default, |n| n.to_string_lossy()),
        std::process::id()
    ));
    let result = (|| {
        let mut f = fs::File::create(&tmp)?;
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
            load: 643.0075,
            n_dofs: 3,
            ms: 12.5,
        }
    }

    #[test]
    fn an_entry_reads_back_exactly_and_only_as_itself() {
        let dir = std::env::temp_dir().join(format!("riplab-cache-unit-{}", std::process::id()));
        let path = dir.join("entry.bin");
        write(&dir, &path, "key A", &fields()).unwrap();
        assert_eq!(read(&path, "key A", 4, 3), Some(fields()));
        // Another key of the same length, other lengths: not this entry.
        assert_eq!(read(&path, "key B", 4, 3), None);
        assert_eq!(read(&path, "key A", 5, 3), None);
        // One flipped byte anywhere: refused by the checksum (or the header).
        let good = fs::read(&path).unwrap();
        for i in [0, 9, 20, good.len() / 2, good.len() - 1] {
            let mut bad = good.clone();
            bad[i] ^= 0x10;
            fs::write(&path, &bad).unwrap();
            assert_eq!(read(&path, "key A", 4, 3), None, "byte {i}");
        }
        // Truncated: refused.
        fs::write(&path, &good[..good.len() - 3]).unwrap();
        assert_eq!(read(&path, "key A", 4, 3), None);
        fs::remove_dir_all(&dir).unwrap();
    }

    /// A uniform level keeps the key it always had; a refined grid's key names its refinement
    /// count and every line, so two refinements (or two grids with the same count) never share
    /// an entry.
    #[test]
    fn a_refined_reference_is_keyed_by_its_lines() {
        let s = Scenario::paper();
        let uniform = ReferenceMesh::uniform(&s, 1);
        assert!(!key(&s, &uniform).contains("refinements"));
        assert!(key(&s, &uniform).contains("level 1\nbody"));
        let mut once = uniform.clone();
        once.refinements = 1;
        once.xs.insert(1, 0.25);
        let mut moved = once.clone();
        moved.xs[1] = 0.125;
        let (a, b) = (key(&s, &once), key(&s, &moved));
        assert!(a.contains("refinements 1") && a.contains("0.25"), "{a}");
        assert_ne!(a, b);
        assert_ne!(a, key(&s, &uniform));
        // Its lengths follow its lines (one more x-interval: two more Q2 node columns).
        let ((u0, p0), (u1, p1)) = (uniform.lengths(), once.lengths());
        assert_eq!((u1 - u0, p1 - p0), (2 * 2 * (2 * 4 * 2 + 1), 2));
    }

    #[test]
    fn fnv1a_matches_its_published_test_vectors() {
        assert_eq!(fnv1a(b""), 0xcbf29ce484222325);
        assert_eq!(fnv1a(b"a"), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a(b"foobar"), 0x85944171f73967e8);
    }
}
