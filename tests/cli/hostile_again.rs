//! The second hostile pass (issue 37): a study that has nothing to measure against, the
//! inf-sup estimate under a memory limit, outputs that would replace each other, global options
//! before the subcommand, terminal text from the command line and the environment, and the
//! smaller holes. Each case fails on the code before the change.

use std::path::{Path, PathBuf};

use crate::common::{paper_text, riplab};

/// A scratch file under the test target's temporary directory.
fn scratch(name: &str, text: &str) -> PathBuf {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn no_panic(stderr: &str) {
    assert!(!stderr.contains("panicked"), "panicked: {stderr}");
}

// 1. A reference without contact: relative errors divide by its zero norms.

#[test]
fn a_study_without_contact_is_refused_never_ok_with_nan() {
    let path = scratch("no-contact-study.toml", &paper_text(&[("depth", "depth = -0.5")]));
    let path = path.to_str().unwrap();
    for format in ["table", "json", "csv"] {
        let (code, stdout, stderr) = riplab(&[
            "study",
            path,
            "--levels",
            "0..1",
            "--schemes",
            "M1,M3",
            "--format",
            format,
            "--no-cache",
        ]);
        no_panic(&stderr);
        assert_eq!(code, 2, "{format}: {stdout}{stderr}");
        assert!(
            !stdout.contains("\"ok\"") && !stdout.contains("NaN"),
            "{format}: {stdout}"
        );
        assert!(
            stderr.contains("the reference has no contact") && stderr.contains("relative errors"),
            "{format}: {stderr}"
        );
    }
    // The lab's convergence scene says the same inside its frame, and exits 2.
    let (code, stdout, stderr) = riplab(&["render", path, "--scene", "convergence", "--size", "100x30"]);
    no_panic(&stderr);
    assert!(!stdout.contains("NaN"), "{stdout}");
    assert!(
        format!("{stdout}{stderr}").contains("the reference has no contact"),
        "{stdout}{stderr}"
    );
    assert_eq!(code, 2, "{stdout}{stderr}");
}

// 2. The inf-sup estimate under a memory limit; the lab's terminal on an abort.

/// Run riplab under an address-space limit of `mib` MiB (prlimit): (exit code, stderr).
fn riplab_limited(mib: u64, args: &[&str]) -> (i32, String) {
    let out = std::process::Command::new("prlimit")
        .arg(format!("--as={}", mib << 20))
        .arg(env!("CARGO_BIN_EXE_riplab"))
        .args(args)
        .env("XDG_CACHE_HOME", crate::common::test_cache())
        .output()
        .expect("prlimit runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// Under address-space limits around what Q2 level 5 needs, `infsup` either answers or is
/// refused with exit 2 and a message about memory: never an abort, never "not positive
/// definite" (a factorisation that ran out of memory used to say so).
#[test]
fn the_inf_sup_estimate_is_refused_before_it_runs_out_of_memory() {
    let args = ["infsup", "--levels", "5", "--element", "q2", "--threads", "1"];
    let mut refused = 0;
    for mib in [1300, 1400, 1500, 1600] {
        let (code, stderr) = riplab_limited(mib, &args);
        no_panic(&stderr);
        assert!(code == 0 || code == 2, "{mib} MiB: exit {code}: {stderr}");
        assert!(!stderr.contains("positive definite"), "{mib} MiB: {stderr}");
        if code == 2 {
            refused += 1;
            assert!(
                stderr.contains("choose a coarser level") && stderr.contains("available"),
                "{mib} MiB: {stderr}"
            );
        }
    }
    assert!(refused > 0, "no limit was tight enough to test the refusal");
}

/// The lab aborted (SIGABRT, as a failed allocation does) leaves the alternate screen and
/// shows the cursor again.
#[test]
fn an_aborted_lab_restores_the_terminal() {
    let log = Path::new(env!("CARGO_TARGET_TMPDIR")).join("aborted-lab.log");
    let lab = format!(
        "{} --no-color </dev/tty & pid=$!; sleep 2; kill -ABRT $pid; wait $pid",
        env!("CARGO_BIN_EXE_riplab")
    );
    let status = std::process::Command::new("script")
        .args(["-qec", &format!("sh -c '{lab}'")])
        .arg(&log)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .status()
        .expect("script runs");
    let bytes = std::fs::read(&log).unwrap();
    let find = |pat: &[u8]| bytes.windows(pat.len()).rposition(|w| w == pat);
    let entered = find(b"\x1b[?1049h").unwrap_or_else(|| panic!("never entered: {status:?}"));
    let left = find(b"\x1b[?1049l").expect("the alternate screen is left");
    let shown = find(b"\x1b[?25h").expect("the cursor is shown");
    assert!(
        left > entered && shown > entered,
        "{:?}",
        String::from_utf8_lossy(&bytes)
    );
}
