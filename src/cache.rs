//! The study's reference, kept between runs: the exact-constraint Q2 solution of a
//! scenario at a level costs seconds to minutes (12 s at level 6, 67 s at level 7), and it
//! depends only on the body, the material, the obstacle and the level. It is stored in the
//! user's cache directory (`$XDG_CACHE_HOME/riplab`, `~/.cache/riplab`; the platform's
//! convention elsewhere), one file per reference, named by a hash of its key.
//!
//! The key is the text of everything the reference depends on, with riplab's version and the
//! build's numerics identity (build.rs: a hash of the sources, Cargo.lock, the compiler and
//! the target), so that another build never reads an entry it did not write. The file I/O is
//! [`mod@file`]'s: written to a fresh, unpredictable temporary name created exclusively (never
//! through a link) and renamed into place, so concurrent runs never see half a file; read
//! through one handle opened without following links and without blocking, a regular file of
//! exactly the size its key implies, whose key text equals the one asked for (no hash
//! collision can mix two entries) and whose checksum matches. What it holds is then checked
//! for meaning ([`meaning`]: finite, its sizes the mesh's, its load the integral of its
//! pressure and the reaction of its displacement); anything else is recomputed and replaced.
//!
//! A reference refined at its contact edges ([`crate::study::ReferenceMesh::refined`]) is kept
//! step by step, each keyed by its refinement count and its vertex lines too, so that a refined
//! entry can never be read as another grid's.

use std::path::{Path, PathBuf};

use crate::error::SolveError;
use crate::scenario::Scenario;
use crate::study::{REFERENCE_SCHEME, Reference, ReferenceFields, ReferenceMesh, ReferenceSource};

pub mod file;
pub mod meaning;

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
    let n_t = if scenario.friction.is_on() { n_p } else { 0 };
    let read = file::read(&path, &key, n_u, n_p, n_t)
        .filter(|fields| meaning::check(scenario, grid, fields).is_ok());
    if let Some(mut fields) = read {
        fields.source = ReferenceSource::Cache;
        return Ok((fields, Provenance::Cached(path)));
    }
    let fields = ReferenceFields::solve_on(scenario, grid)?;
    let provenance = match file::write(dir, &path, &key, &fields) {
        Ok(()) => Provenance::Stored(path),
        Err(e) => Provenance::Computed(Some(format!("not stored in {}: {e}", dir.display()))),
    };
    Ok((fields, provenance))
}

/// Everything the reference depends on, as text (f64's Debug form round-trips exactly); a
/// refined grid adds its refinement count and its vertex lines, friction its law, shift and
/// steps ([`crate::study::reference_friction`]), so that a frictionless reference is never
/// read for a study with friction, nor the other way round.
fn key(s: &Scenario, grid: &ReferenceMesh) -> String {
    let mut key = format!(
        "riplab {} numerics {} reference {:?} level {}\nbody {:?} x {:?} y {:?} half {}\nmaterial {:?}\nintegration {:?}\nobstacle {:?}",
        env!("CARGO_PKG_VERSION"),
        NUMERICS_ID,
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
    let friction = crate::study::reference_friction(s);
    if friction.is_on() {
        key.push_str(&format!("\nfriction {friction:?}"));
    }
    if grid.refinements > 0 {
        key.push_str(&format!(
            "\nrefinements {}\nxs {:?}\nys {:?}",
            grid.refinements, grid.xs, grid.ys
        ));
    }
    key
}

/// The build's numerics identity (build.rs): a hash of src/, Cargo.lock, rustc's version and
/// the target.
pub const NUMERICS_ID: &str = env!("RIPLAB_NUMERICS_ID");

/// FNV-1a, 64 bits: the file name's hash and the payload's checksum (stable across builds,
/// unlike the standard library's hasher).
pub(crate) fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

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

    /// The key names the build's numerics identity: another build's entry is another key.
    #[test]
    fn the_key_holds_the_build_identity() {
        let s = Scenario::paper();
        let key = key(&s, &ReferenceMesh::uniform(&s, 1));
        assert_eq!(NUMERICS_ID.len(), 16);
        assert!(NUMERICS_ID.bytes().all(|b| b.is_ascii_hexdigit()));
        assert!(key.contains(&format!("numerics {NUMERICS_ID} ")), "{key}");
    }

    /// A frictionless reference is never read for a study with friction, nor the other way
    /// round, nor one μ's for another's: each has its own key and entry, and each is read
    /// back as stored (t with friction, none without).
    #[test]
    fn friction_and_frictionless_references_are_kept_apart() {
        use crate::contact::friction::{Friction, Law, Press};
        let dir = std::env::temp_dir().join(format!("riplab-cache-friction-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-paper-full.toml");
        let plain = Scenario::load(Path::new(path)).unwrap();
        let with = |mu: f64, epsilon_t: Option<f64>| {
            let mut s = plain.clone();
            s.friction = Friction {
                law: Law::Coulomb { mu },
                shift: 0.05,
                steps: 2,
                epsilon_t,
                press: Press::WithFriction,
            };
            s
        };
        let grid = ReferenceMesh::uniform(&plain, 0);
        let stored = |s: &Scenario| match fields(s, &grid, Some(&dir)).unwrap() {
            (f, Provenance::Stored(p)) => (f, p),
            other => panic!("not computed and stored: {:?}", other.1),
        };
        let cached = |s: &Scenario| match fields(s, &grid, Some(&dir)).unwrap() {
            (f, Provenance::Cached(p)) => (f, p),
            other => panic!("not read: {:?}", other.1),
        };
        let (f0, p0) = stored(&plain);
        let (f3, p3) = stored(&with(0.3, None));
        let (f6, p6) = stored(&with(0.6, None));
        assert!(p0 != p3 && p3 != p6 && p0 != p6);
        assert!(f0.t.is_empty() && !f3.t.is_empty() && f3.t != f6.t);
        let same = |a: &ReferenceFields, b: &ReferenceFields| {
            (&a.u, &a.p, &a.t, a.load) == (&b.u, &b.p, &b.t, b.load)
        };
        assert!(same(&cached(&plain).0, &f0));
        assert!(same(&cached(&with(0.3, None)).0, &f3));
        // The rows' ε_t is not the reference's (it imposes friction exactly): the same entry.
        assert_eq!(cached(&with(0.3, Some(1e-6))).1, p3);
        // A frictionless entry planted at a friction entry's path is not believed.
        std::fs::copy(&p0, &p3).unwrap();
        let (again, _) = stored(&with(0.3, None));
        assert!(same(&again, &f3));
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn fnv1a_matches_its_published_test_vectors() {
        assert_eq!(fnv1a(b""), 0xcbf29ce484222325);
        assert_eq!(fnv1a(b"a"), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a(b"foobar"), 0x85944171f73967e8);
    }
}
