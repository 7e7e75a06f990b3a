//! The second hostile pass: a study that has nothing to measure against, the
//! inf-sup estimate under a memory limit, outputs that would replace each other, global options
//! before the subcommand, terminal text from the command line and the environment, and the
//! smaller holes. Each case fails on the code before the change.

use std::path::Path;

use crate::common::{no_panic, paper_text, riplab, scratch_file as scratch};

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

// 2. The inf-sup estimate under a memory limit (the lab's terminal on an abort: terminal.rs).

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

/// `needs about X GiB` and `has Y GiB available` of a memory refusal, in bytes (one decimal:
/// each ±0.05 GiB).
fn need_and_available(stderr: &str) -> Option<(f64, f64)> {
    let gib_after = |key: &str| -> Option<f64> {
        let rest = &stderr[stderr.find(key)? + key.len()..];
        let number = rest.split_whitespace().next()?;
        Some(number.parse::<f64>().ok()? * f64::from(1u32 << 30))
    };
    Some((gib_after("needs about")?, gib_after("this process has")?))
}

/// Under address-space limits around what Q2 level 5 needs, `infsup` either answers or is
/// refused with exit 2 and a message about memory: never an abort, never "not positive
/// definite" (a factorisation that ran out of memory used to say so).
///
/// The limits are derived from riplab's own estimate, never fixed: what the process maps
/// before the check (the gemm kernels' reservation, thread stacks) depends on the CPU and its
/// caches, so a first run under a small limit reads the estimate and what was left of the
/// limit, and the limits tried are that mapping plus fractions of the estimate. Below the
/// estimate the refusal is certain on every host; above it the estimate promises the work
/// fits, so the largest limit must answer.
#[test]
fn the_inf_sup_estimate_is_refused_before_it_runs_out_of_memory() {
    let args = ["infsup", "--levels", "5", "--element", "q2", "--threads", "1"];
    const MIB: f64 = (1u64 << 20) as f64;
    // A probe: the smallest of these limits that leaves the process some room to start, and
    // is refused, gives the estimate and the mapping (the limit less what was available).
    // The probes climb past what the dense product kernel reserves on the first product (960
    // MiB where the L3 is reported as 480 MiB; src/fem/memory/kernel.rs).
    let (need, mapped) = [512u64, 768, 1024, 1280, 1536, 1792, 2048, 2560, 3072, 4096]
        .into_iter()
        .find_map(|mib| {
            let (code, stderr) = riplab_limited(mib, &args);
            let (need, available) = need_and_available(&stderr)?;
            (code == 2 && available >= 0.1 * f64::from(1u32 << 30))
                .then_some((need, mib as f64 * MIB - available))
        })
        .expect("a probe under 512–4096 MiB is refused with the estimate and what is available");
    // One decimal of GiB on each figure: ±0.1 GiB on the sum, far inside the 25% below.
    let limit = |fraction: f64| ((mapped + fraction * need) / MIB).ceil() as u64;
    for fraction in [0.75, 0.95, 1.1, 1.3, 1.6] {
        let mib = limit(fraction);
        let (code, stderr) = riplab_limited(mib, &args);
        no_panic(&stderr);
        let at = format!("{fraction} of the estimate ({mib} MiB)");
        assert!(code == 0 || code == 2, "{at}: exit {code}: {stderr}");
        assert!(!stderr.contains("positive definite"), "{at}: {stderr}");
        if code == 2 {
            assert!(
                stderr.contains("choose a coarser level") && stderr.contains("available"),
                "{at}: {stderr}"
            );
        }
        if fraction < 0.8 {
            assert_eq!(code, 2, "{at}: below the estimate and not refused: {stderr}");
        }
        if fraction > 1.5 {
            assert_eq!(code, 0, "{at}: the estimate said it fits: {stderr}");
        }
    }
}

/// A solve under address-space limits around what the process maps and the dense product
/// kernel reserves on a thread's first product (twice its figure for the L3 cache: 960 MiB on
/// a host whose two cores share a 480 MiB L3, 4 MiB on a small one) is refused with exit 2 or
/// answers: never aborted inside the kernel (`memory allocation of 1006632960 bytes failed`,
/// the guard's estimate fitting). On two threads every thread that multiplies has its own:
/// the inf-sup scene's dense work on Γ_C at level 4 runs on rayon's pool, and aborted under
/// 2500 MiB.
#[test]
fn a_solve_under_a_tight_address_space_is_refused_never_aborted() {
    let q2 = |threads| ["solve", "--level", "5", "--element", "q2", "--threads", threads].to_vec();
    let scene = ["render", "--scene", "infsup", "--size", "80x24", "--threads", "2"].to_vec();
    for (mib, args) in [
        (700u64, q2("1")),
        (1000, q2("1")),
        (1400, q2("1")),
        (2500, q2("2")),
        (2500, scene),
    ] {
        let (code, stderr) = riplab_limited(mib, &args);
        no_panic(&stderr);
        let at = format!("{mib} MiB, {}", args.join(" "));
        assert!(code == 0 || code == 2, "{at}: exit {code}: {stderr}");
        if code == 2 {
            assert!(
                stderr.contains("choose a coarser level") && stderr.contains("available"),
                "{at}: {stderr}"
            );
        }
    }
}

// 6. One requested output replacing another.

#[test]
fn outputs_of_one_command_never_replace_each_other() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("clashing-outputs");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    let at = |name: &str| dir.join(name).to_str().unwrap().to_string();
    for (plot, vtu) in [
        (at("x.vtu"), at("x.vtu")),
        (at("x.contact.vtu"), at("x.vtu")),
        (at("sub/../x.vtu"), at("x.vtu")),
    ] {
        for force in [false, true] {
            let mut args = vec!["solve", "--level", "0", "--plot", &plot, "--vtu", &vtu];
            if force {
                args.push("--force");
            }
            let (code, stdout, stderr) = riplab(&args);
            no_panic(&stderr);
            assert_eq!(code, 2, "{args:?}: {stderr}");
            assert!(stdout.is_empty(), "{args:?}: {stdout}");
            assert!(
                stderr.contains("each output needs its own file"),
                "{args:?}: {stderr}"
            );
            let left: Vec<_> = std::fs::read_dir(&dir)
                .unwrap()
                .map(|e| e.unwrap().file_name())
                .collect();
            assert_eq!(
                left,
                vec![std::ffi::OsString::from("sub")],
                "{args:?} wrote something"
            );
        }
    }
    // Distinct names still work.
    let (code, _, stderr) = riplab(&[
        "solve",
        "--level",
        "0",
        "--plot",
        &at("p.svg"),
        "--vtu",
        &at("b.vtu"),
    ]);
    assert_eq!(code, 0, "{stderr}");
}

// 7. Global options before the subcommand.

#[test]
fn global_options_go_before_or_after_the_command() {
    for args in [
        &["--threads", "2", "solve", "--level", "0"][..],
        &["--no-color", "solve", "--level", "0"],
        &["solve", "--level", "0", "--threads", "2", "--no-color"],
        &[
            "--marker",
            "dot",
            "--threads",
            "1",
            "render",
            "--level",
            "0",
            "--size",
            "80x24",
        ],
    ] {
        let (code, stdout, stderr) = riplab(args);
        assert_eq!(code, 0, "{args:?}: {stderr}");
        assert!(!stdout.is_empty(), "{args:?}");
    }
    // A scenario file alone is still the lab's (which needs a terminal).
    let (code, _, stderr) = riplab(&["scenarios/hertz-paper.toml"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("the lab needs a terminal"), "{stderr}");
    // A scenario before a command is refused, saying where it goes.
    let (code, _, stderr) = riplab(&["scenarios/hertz-paper.toml", "solve"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("riplab solve FILE"), "{stderr}");
}

// 8. Escape sequences and bidi controls from the command line and the environment.

fn clean(stderr: &str) {
    assert!(
        !stderr.contains('\u{1b}'),
        "an escape reached the terminal: {stderr:?}"
    );
    assert!(
        !stderr.contains('\u{202e}'),
        "a bidi override reached the terminal: {stderr:?}"
    );
}

#[test]
fn command_line_and_environment_text_is_sanitised() {
    let (code, _, stderr) = riplab(&["solve", "--level", "0", "--method", "pen\u{1b}]0;X\u{7}alty"]);
    assert_eq!(code, 2, "{stderr}");
    clean(&stderr);
    let (code, _, stderr) = riplab(&["solve", "--level", "x\u{1b}[2J"]);
    assert_eq!(code, 2, "{stderr}");
    clean(&stderr);
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("esc\u{1b}[31mdir\u{202e}");
    std::fs::create_dir_all(&dir).unwrap();
    let vtu = dir.join("out.vtu");
    let _ = std::fs::remove_file(&vtu);
    let _ = std::fs::remove_file(dir.join("out.contact.vtu"));
    let (code, _, stderr) = riplab(&["solve", "--level", "0", "--vtu", vtu.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.contains("wrote "), "{stderr}");
    clean(&stderr);
    // The cache directory from the environment, in the "read from" note.
    let cache = dir.join("cache");
    for _ in 0..2 {
        let (code, _, stderr) = crate::hostile_cache::study(&cache, "table");
        assert_eq!(code, 0, "{stderr}");
        clean(&stderr);
    }
    // A scenario name with a bidi override.
    let path = scratch(
        "bidi-name.toml",
        &paper_text(&[("name", "name = \"evil\u{202e}txt.exe\"")]),
    );
    let (code, stdout, stderr) = riplab(&["solve", path.to_str().unwrap(), "--level", "0"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(!stdout.contains('\u{202e}'), "{stdout}");
}

#[test]
fn a_tour_value_cannot_forge_a_line() {
    let tour = scratch(
        "forged-scene.toml",
        "title = \"t\"\n[[step]]\ntitle = \"s\"\ncaption = \"c\"\nscene = \"x\\nerror: forged\"\n",
    );
    let (code, _, stderr) = riplab(&["tour", "--tour", tour.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        !stderr.lines().any(|l| l.starts_with("error: forged")),
        "{stderr}"
    );
}

// 9. Smaller holes.

#[test]
fn penalties_that_underflow_to_zero_are_refused() {
    for args in [
        &["solve", "--level", "0", "--epsilon", "1e-400"][..],
        &["solve", "--level", "0", "--kappa", "1e-400"],
        &["study", "--levels", "0", "--epsilon", "1e-400"],
        &["study", "--level", "0", "--sweep-epsilon", "1e-6,1e-400"],
        &["render", "--level", "0", "--epsilon", "1e-400"],
    ] {
        let (code, stdout, stderr) = riplab(args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stdout.is_empty(), "{args:?}: {stdout}");
        assert!(stderr.contains("underflows to 0"), "{args:?}: {stderr}");
    }
}

#[test]
fn negative_values_start_a_list() {
    let (code, stdout, stderr) = riplab(&["solve", "--level", "0", "--depth", "-0.5,0.5", "--format", "csv"]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(
        stdout.lines().filter(|l| l.contains("0.5")).count(),
        2,
        "{stdout}"
    );
}

#[test]
fn deep_keys_and_huge_lines_give_a_short_located_error() {
    let deep = scratch(
        "deep-key.toml",
        &format!("{} = 1\n", vec!["a"; 150_000].join(".")),
    );
    let (code, _, stderr) = riplab(&["solve", deep.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("deep-key.toml:1:1") && stderr.contains("nested deeper"),
        "{stderr}"
    );
    assert!(stderr.len() < 1000, "{} bytes", stderr.len());
    let huge = scratch(
        "huge-line.toml",
        &format!(
            "{}\nx = [{}\n",
            riplab::scenario::DEFAULT_SCENARIO,
            "1, ".repeat(300_000)
        ),
    );
    let (code, _, stderr) = riplab(&["solve", huge.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.len() < 2000, "{} bytes echoed", stderr.len());
    // The caret stands under the excerpt, not 900,000 columns to the right.
    assert!(stderr.lines().all(|l| l.chars().count() < 400), "{stderr}");
}

#[test]
fn tour_steps_are_checked_as_fully_as_when_played() {
    let tour = scratch(
        "tiny-epsilon-tour.toml",
        "title = \"t\"\n[[step]]\ntitle = \"s\"\ncaption = \"c\"\nlevel = 2\nepsilon = 1e-300\n",
    );
    let (code, _, stderr) = riplab(&["tour", "--tour", tour.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("step 1") && stderr.contains("level 2") && stderr.contains("out of range"),
        "{stderr}"
    );
}

#[test]
fn render_exits_2_on_a_refusal_like_solve() {
    // ε = 0 with gauss2 on Q1: the multipliers are not unique (a kernel), refused by solve.
    let args = ["--level", "1", "--scheme", "M2", "--method", "exact"];
    let (solve_code, _, _) = riplab(&[&["solve"][..], &args].concat());
    let (code, stdout, stderr) = riplab(&[&["render"][..], &args].concat());
    assert_eq!((solve_code, code), (2, 2), "{stderr}");
    assert!(stdout.is_empty(), "{stdout}");
    assert!(
        stderr.contains("kernel") || stderr.contains("not unique"),
        "{stderr}"
    );
}

#[test]
fn nitsche_sweeps_over_epsilon_are_refused() {
    for args in [
        &[
            "solve",
            "--level",
            "0",
            "--method",
            "nitsche",
            "--epsilon",
            "1e-6,1e-5",
        ][..],
        &[
            "study",
            "--level",
            "0",
            "--method",
            "nitsche",
            "--sweep-epsilon",
            "1e-6,1e-5",
        ],
    ] {
        let (code, stdout, stderr) = riplab(args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stdout.is_empty(), "{stdout}");
        assert!(stderr.contains("nitsche does not use ε"), "{args:?}: {stderr}");
    }
}
