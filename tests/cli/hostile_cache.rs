//! The study's reference cache under attack (issue 37): the JSON and CSV say where the
//! reference came from, and an entry with a valid checksum but a meaning that does not hold
//! (its pressures scaled) is recomputed, never believed.

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
