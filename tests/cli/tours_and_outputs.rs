//! Tours checked as they are played and outputs bounded, on the command line: a tour step's
//! friction on a half model refused by `tour --check` and before a handout is begun; a tour
//! of many steps naming one scenario file reads it once; a handout beyond its limit refused
//! before anything is written, with the estimate and the limit; `render` refuses what `solve`
//! refuses with the same exit code; a link planted at the temporary name `--plot` used is
//! neither blamed on the target nor removed.

use std::path::PathBuf;

use crate::common::{no_panic, riplab, test_cache};

/// A fresh directory under the test target's temporary one.
fn scratch(name: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("tours-outputs-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A step whose friction the lab refuses (a half model) passed `--check` and failed the
/// handout halfway, blaming "shift = 0 moves the obstacle's centre to x = 0" (exit 1): now
/// `--check`, `--tour` and `--handout` refuse it as the lab does, exit 2, nothing written.
#[test]
fn friction_on_a_half_model_is_refused_by_the_check() {
    let dir = scratch("half-friction");
    let tour = dir.join("t.toml");
    std::fs::write(
        &tour,
        "title = \"t\"\n[[step]]\ntitle = \"s\"\ncaption = \"c\"\nlevel = 0\nfriction = \"coulomb\"\nmu = 0.3\n",
    )
    .unwrap();
    let tour = tour.to_str().unwrap();
    let (code, out, err) = riplab(&["tour", "--check", tour]);
    no_panic(&err);
    assert_eq!(code, 2, "{out}{err}");
    assert!(out.is_empty(), "{out}");
    assert!(
        err.contains("step 1") && err.contains("friction needs the full model"),
        "{err}"
    );
    let handout = dir.join("handout");
    let (code, _, err) = riplab(&["tour", "--tour", tour, "--handout", handout.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(!err.contains("shift = 0"), "{err}");
    assert!(!handout.exists(), "nothing written");
}

/// 200 steps naming one scenario file: `--check` reads it once (it read and parsed it 200
/// times) and says so.
#[test]
fn many_steps_on_one_scenario_file_read_it_once() {
    let dir = scratch("read-once");
    std::fs::write(dir.join("s.toml"), riplab::scenario::DEFAULT_SCENARIO).unwrap();
    let mut text = String::from("title = \"many\"\n");
    for i in 0..200 {
        text.push_str(&format!(
            "\n[[step]]\ntitle = \"{i}\"\ncaption = \"c\"\nscenario = \"s.toml\"\nlevel = 0\n"
        ));
    }
    let tour = dir.join("many.toml");
    std::fs::write(&tour, text).unwrap();
    let (code, out, err) = riplab(&["tour", "--check", tour.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("a valid tour of 200 steps"), "{out}");
    assert!(out.contains("scenario files: 1 (each read once"), "{out}");
}

/// A handout of more steps at 1000×500 than its limit allows is refused before anything is
/// solved or written (a 120-step handout wrote 65 MB from a 4 kB tour; nothing bounded it),
/// exit 2, naming the estimate, the limit and `--size`.
#[test]
fn a_handout_beyond_its_limit_is_refused_before_writing() {
    let dir = scratch("handout-limit");
    // Each step's screen is counted at 4 bytes a cell: enough steps to pass the limit (256 MiB,
    // the library's `MAX_HANDOUT_BYTES`) on screens alone.
    let screen = 500 * (4 * 1000 + 1);
    let steps = (256 << 20) / screen + 1;
    let mut text = String::from("title = \"long\"\n");
    for i in 0..steps {
        text.push_str(&format!(
            "\n[[step]]\ntitle = \"{i}\"\ncaption = \"c\"\nlevel = 0\n"
        ));
    }
    let tour = dir.join("long.toml");
    std::fs::write(&tour, text).unwrap();
    let handout = dir.join("out");
    let (code, out, err) = riplab(&[
        "tour",
        "--tour",
        tour.to_str().unwrap(),
        "--handout",
        handout.to_str().unwrap(),
        "--size",
        "1000x500",
    ]);
    no_panic(&err);
    assert_eq!(code, 2, "{out}{err}");
    assert!(
        err.contains(&format!("{steps} steps at 1000×500"))
            && err.contains("256.0 MiB")
            && err.contains("--size"),
        "{err}"
    );
    assert!(!err.contains("written"), "{err}");
    assert!(!handout.exists(), "nothing written");
}

/// `render` of a request that `solve` refuses as bad input after assembly (Nitsche's γ₀ below
/// its stability threshold) exits 2 with `solve`'s message and no frame, as `solve` does (it
/// printed the frame and exited 1).
#[test]
fn render_exits_as_solve_on_a_gamma0_below_the_threshold() {
    let args = ["--method", "nitsche", "--gamma0", "1"];
    let (solve_code, _, solve_err) = riplab(&[&["solve"][..], &args].concat());
    let (code, out, err) = riplab(&[&["render", "--size", "100x30"][..], &args].concat());
    no_panic(&err);
    assert_eq!((solve_code, code), (2, 2), "{solve_err}\n{err}");
    assert!(out.is_empty(), "{out}");
    let first = |s: &str| s.lines().next().unwrap_or_default().to_string();
    assert_eq!(first(&err), first(&solve_err));
    assert!(err.contains("γ₀: 1 is too small"), "{err}");
}

/// A link planted at `.a.svg.<pid>-0.tmp` (the shell's pid, which `exec` gives riplab): `solve
/// --plot a.svg` said "a.svg: exists" (it did not), exit 1, and deleted the link. Now the
/// chart is written, and the link and its target are untouched.
#[test]
fn a_link_planted_at_a_predictable_temporary_is_left_alone() {
    let dir = scratch("planted-plot");
    std::fs::write(dir.join("victim"), "keep").unwrap();
    let out = std::process::Command::new("sh")
        .current_dir(&dir)
        .arg("-c")
        .arg("ln -s victim .a.svg.$$-0.tmp && exec \"$0\" solve --level 0 --plot a.svg")
        .arg(env!("CARGO_BIN_EXE_riplab"))
        .env("XDG_CACHE_HOME", test_cache())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    no_panic(&err);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        std::fs::read_to_string(dir.join("a.svg"))
            .unwrap()
            .contains("<svg")
    );
    assert_eq!(std::fs::read_to_string(dir.join("victim")).unwrap(), "keep");
    let links: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.file_type().unwrap().is_symlink())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(links.len(), 1, "{links:?}");
    assert!(
        links[0].starts_with(".a.svg.") && links[0].ends_with("-0.tmp"),
        "{links:?}"
    );
}

/// An integer beyond 64 bits in a tour step was "invalid type: integer … as i128, expected
/// i64", with no step: now the step's key, the value and the allowed range, exit 2.
#[test]
fn an_oversized_level_in_a_step_is_said_in_the_users_words() {
    let dir = scratch("oversized-level");
    let tour = dir.join("t.toml");
    std::fs::write(
        &tour,
        "title = \"t\"\n[[step]]\ntitle = \"a\"\ncaption = \"c\"\nlevel = 0\n[[step]]\ntitle = \"b\"\ncaption = \"c\"\nlevel = 99999999999999999999\n",
    )
    .unwrap();
    let (code, stdout, stderr) = riplab(&["tour", "--check", tour.to_str().unwrap()]);
    no_panic(&stderr);
    assert_eq!(code, 2, "{stdout}{stderr}");
    assert!(!stderr.contains("i128"), "{stderr}");
    assert!(
        stderr.contains("99999999999999999999")
            && stderr.contains("step[2].level")
            && stderr.contains("0 to 7"),
        "{stderr}"
    );
}
