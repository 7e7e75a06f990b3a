//! The study's reference cache under attack: the JSON and CSV say where the reference came
//! from, and an entry with a valid checksum but a meaning that does not hold (its pressures
//! scaled; everything scaled alike; another depth's true solution under this depth's key) is
//! recomputed, never believed.

use std::path::{Path, PathBuf};
use std::process::Command;

/// `riplab study --levels 0 --schemes M1` on the uniform reference with its cache under
/// `cache`: exit code, stdout and stderr.
pub(crate) fn study(cache: &Path, format: &str) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_riplab"))
        .args([
            "study",
            "--levels",
            "0",
            "--schemes",
            "M1",
            "--reference-refinements",
            "0",
        ])
        .args(["--format", format])
        .env("XDG_CACHE_HOME", cache)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text).unwrap()
}

/// The entries of the cache directory.
fn entries(cache: &Path) -> Vec<PathBuf> {
    let dir = cache.join("riplab");
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

#[test]
fn the_output_says_where_the_reference_came_from_and_a_wrong_entry_is_not_believed() {
    let cache = Path::new(env!("CARGO_TARGET_TMPDIR")).join("hostile-cache");
    let _ = std::fs::remove_dir_all(&cache);
    let (code, first, stderr) = study(&cache, "json");
    assert_eq!(code, 0, "{stderr}");
    let first = json(&first);
    assert_eq!(first["reference"]["source"], "computed");
    let (code, second, stderr) = study(&cache, "json");
    assert_eq!(code, 0, "{stderr}");
    let second = json(&second);
    assert_eq!(second["reference"]["source"], "cache");
    assert_eq!(first["rows"][0]["errors"], second["rows"][0]["errors"]);
    let (_, csv, _) = study(&cache, "csv");
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let column = header
        .iter()
        .position(|c| *c == "source")
        .expect("a source column");
    let last: Vec<&str> = csv.lines().last().unwrap().split(',').collect();
    assert_eq!((last[0], last[column]), ("reference", "cache"), "{csv}");

    // Every entry's pressures ×1.5, its checksum made valid again: recomputed, not used.
    for path in entries(&cache) {
        let mut bytes = std::fs::read(&path).unwrap();
        let word = |b: &[u8], at: usize| u64::from_le_bytes(b[at..at + 8].try_into().unwrap()) as usize;
        let key_len = word(&bytes, 8);
        let at = 16 + key_len;
        let (n_u, n_p) = (word(&bytes, at), word(&bytes, at + 8));
        let p_start = at + 24 + 16 + 8 * n_u;
        for k in 0..n_p {
            let o = p_start + 8 * k;
            let v = f64::from_le_bytes(bytes[o..o + 8].try_into().unwrap()) * 1.5;
            bytes[o..o + 8].copy_from_slice(&v.to_le_bytes());
        }
        let n = bytes.len() - 8;
        let sum = fnv1a(&bytes[..n]);
        bytes[n..].copy_from_slice(&sum.to_le_bytes());
        std::fs::write(&path, &bytes).unwrap();
    }
    let (code, third, stderr) = study(&cache, "json");
    assert_eq!(code, 0, "{stderr}");
    let third = json(&third);
    assert_eq!(third["reference"]["source"], "computed", "{stderr}");
    assert_eq!(first["rows"][0]["errors"], third["rows"][0]["errors"]);
    assert_eq!(first["reference"]["load"], third["reference"]["load"]);
}

/// `riplab study --levels 0..1 --schemes M1,M3 --reference-refinements 0 --format json` on
/// `scenario` (the paper's, depth 0.8, when None) with its cache under `cache`: exit code, the
/// JSON, stderr.
fn study_levels(cache: &Path, scenario: Option<&Path>) -> (i32, serde_json::Value, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_riplab"));
    cmd.arg("study");
    if let Some(s) = scenario {
        cmd.arg(s);
    }
    let out = cmd
        .args([
            "--levels",
            "0..1",
            "--schemes",
            "M1,M3",
            "--reference-refinements",
            "0",
        ])
        .args(["--format", "json"])
        .env("XDG_CACHE_HOME", cache)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let v = serde_json::from_slice(&out.stdout).unwrap_or(serde_json::Value::Null);
    (out.status.code().unwrap_or(-1), v, stderr)
}

/// An entry's parts: its key and its numbers (load, time, u, p, t in the file's order).
struct Entry {
    key: String,
    counts: [u64; 3],
    numbers: Vec<f64>,
}

impl Entry {
    fn read(path: &Path) -> Entry {
        let bytes = std::fs::read(path).unwrap();
        let word = |at: usize| u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap());
        let key_len = word(8) as usize;
        let key = String::from_utf8(bytes[16..16 + key_len].to_vec()).unwrap();
        let at = 16 + key_len;
        let counts = [word(at), word(at + 8), word(at + 16)];
        let numbers = bytes[at + 24..bytes.len() - 8]
            .chunks(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect();
        Entry { key, counts, numbers }
    }

    /// Written to `dir` under its key's name, its checksum valid.
    fn write(&self, dir: &Path) -> PathBuf {
        let mut bytes = b"RIPREF01".to_vec();
        bytes.extend_from_slice(&(self.key.len() as u64).to_le_bytes());
        bytes.extend_from_slice(self.key.as_bytes());
        for c in self.counts {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
        for v in &self.numbers {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let sum = fnv1a(&bytes);
        bytes.extend_from_slice(&sum.to_le_bytes());
        let path = dir.join(format!("reference-{:016x}.bin", fnv1a(self.key.as_bytes())));
        std::fs::write(&path, bytes).unwrap();
        path
    }
}

/// Two forgeries with valid checksums and consistent numbers, each recomputed: every entry's
/// u, p and load ×1.5 (its load still I(p, 1), its displacement's reaction still its load), and
/// the true depth-0.7 entries written under the depth-0.8 keys (they read 531 for 643). Both
/// fail their own obstacle's contact conditions on Γ_C; the study says "computed" and reports
/// the true reference's load and errors.
#[test]
fn consistent_entries_that_are_not_the_problems_are_recomputed() {
    let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("hostile-cache-meaning");
    let _ = std::fs::remove_dir_all(&root);
    let (deep, shallow) = (root.join("deep"), root.join("shallow"));
    let (code, truth, stderr) = study_levels(&deep, None);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(truth["reference"]["source"], "computed");
    let names = entries(&deep);
    assert!(!names.is_empty());

    for path in &names {
        let mut entry = Entry::read(path);
        // The time (the second number) stays; the load, u, p (and t) are scaled.
        for (i, v) in entry.numbers.iter_mut().enumerate() {
            if i != 1 {
                *v *= 1.5;
            }
        }
        assert_eq!(&entry.write(path.parent().unwrap()), path);
    }
    let (code, scaled, stderr) = study_levels(&deep, None);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(scaled["reference"]["source"], "computed", "{stderr}");
    assert_eq!(scaled["reference"]["load"], truth["reference"]["load"]);
    assert_eq!(scaled["rows"][0]["errors"], truth["rows"][0]["errors"]);

    let text = riplab::scenario::DEFAULT_SCENARIO.replace("depth = 0.8 ", "depth = 0.7 ");
    let file = root.join("depth-0.7.toml");
    std::fs::write(&file, text).unwrap();
    let (code, other, stderr) = study_levels(&shallow, Some(&file));
    assert_eq!(code, 0, "{stderr}");
    assert_ne!(other["reference"]["load"], truth["reference"]["load"]);
    std::fs::remove_dir_all(deep.join("riplab")).unwrap();
    std::fs::create_dir_all(deep.join("riplab")).unwrap();
    let mut planted: Vec<PathBuf> = entries(&shallow)
        .iter()
        .map(|path| {
            let mut entry = Entry::read(path);
            assert!(entry.key.contains("depth: 0.7,"), "{}", entry.key);
            entry.key = entry.key.replace("depth: 0.7,", "depth: 0.8,");
            entry.write(&deep.join("riplab"))
        })
        .collect();
    planted.sort();
    assert_eq!(planted, names, "the forgeries sit where the true entries were");
    let (code, transplanted, stderr) = study_levels(&deep, None);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(transplanted["reference"]["source"], "computed", "{stderr}");
    assert_eq!(transplanted["reference"]["load"], truth["reference"]["load"]);
    assert_eq!(transplanted["rows"][0]["errors"], truth["rows"][0]["errors"]);
}
