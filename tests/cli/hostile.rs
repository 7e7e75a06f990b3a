//! Hostile and careless input: every case a hostile test found, each refused with a
//! clear message and exit 2, or answered honestly (never a non-finite number called
//! converged), never a panic, an unbounded read or a hang.

use std::io::Read as _;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use riplab::mesh::Element;
use riplab::scenario::Scenario;

use crate::common::{no_panic, paper_text, riplab, riplab_under_half_of, scratch_file as scratch};

/// How long a refusal may take before it counts as a hang: the refusals are immediate, and a
/// hang (an open() of a FIFO with no writer) is for ever, so the limit is generous enough for
/// any host however loaded.
const HANG: Duration = Duration::from_secs(120);

/// Run riplab with a time limit ([`HANG`]): (exit code, stdout, stderr); a hang fails the test.
fn riplab_within(args: &[&str]) -> (i32, String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_riplab"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Each output read to its end on a thread of its own (riplab's end closes both; a full
    // pipe would block it), the test waiting for both at most [`HANG`].
    let (done, ended) = std::sync::mpsc::channel();
    let pipes: [Box<dyn std::io::Read + Send>; 2] = [
        Box::new(child.stdout.take().unwrap()),
        Box::new(child.stderr.take().unwrap()),
    ];
    for (which, mut pipe) in pipes.into_iter().enumerate() {
        let done = done.clone();
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let read = pipe.read_to_end(&mut bytes).map(|_| bytes);
            let _ = done.send((which, read));
        });
    }
    let deadline = Instant::now() + HANG;
    let mut outputs = [String::new(), String::new()];
    for _ in 0..2 {
        let Ok((which, read)) = ended.recv_timeout(deadline.saturating_duration_since(Instant::now())) else {
            let _ = child.kill();
            let _ = child.wait();
            panic!("riplab {args:?} still running after {HANG:?}");
        };
        outputs[which] = String::from_utf8(read.unwrap()).unwrap();
    }
    let status = child.wait().unwrap();
    let [out, err] = outputs;
    (status.code().unwrap_or(-1), out, err)
}

// 1. Wrong answers reported as success.

#[test]
fn penalties_whose_products_overflow_are_refused_with_the_range() {
    for args in [
        &["solve", "--level", "1", "--epsilon", "1e-200"][..],
        &["solve", "--level", "1", "--epsilon", "1e-308", "--format", "json"],
        &["solve", "--level", "1", "--epsilon", "1e-155"],
        &["solve", "--level", "1", "--kappa", "1e-200"],
        &["solve", "--level", "1", "--epsilon", "1e300"],
        &["study", "--levels", "0..1", "--epsilon", "1e-200"],
        &["study", "--level", "1", "--sweep-epsilon", "1e-6,1e-200"],
        &["render", "--level", "1", "--epsilon", "1e-200"],
    ] {
        let (code, stdout, stderr) = riplab(args);
        no_panic(&stderr);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stdout.is_empty(), "{args:?} printed a result: {stdout}");
        assert!(
            stderr.contains("out of range") && stderr.contains("allowed: 0 (the exact constraint) or"),
            "{args:?}: {stderr}"
        );
        // Numbers in messages are short (no 300-digit decimals).
        assert!(!stderr.contains("00000000000"), "{args:?}: {stderr}");
    }
    let path = scratch(
        "tiny-epsilon.toml",
        &paper_text(&[("epsilon", "epsilon = 1e-200")]),
    );
    let (code, _, stderr) = riplab(&["solve", path.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("`contact.epsilon`") && stderr.contains("1e-200"),
        "{stderr}"
    );
}

#[test]
fn depths_beyond_the_body_are_refused() {
    for d in ["100", "1.7e308", "4", "-4"] {
        let (code, stdout, stderr) = riplab(&["solve", "--level", "1", &format!("--depth={d}")]);
        assert_eq!(code, 2, "depth {d}: {stderr}");
        assert!(
            stdout.is_empty() && stderr.contains("the body is 4 high"),
            "{stderr}"
        );
    }
    let path = scratch("deep.toml", &paper_text(&[("depth", "depth = 100.0")]));
    let (code, _, stderr) = riplab(&["solve", path.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("`obstacle.depth`") && stderr.contains(":25:9"),
        "{stderr}"
    );
}

/// The library refuses the same parameters when it is called directly (the lab, the tour
/// and library users do not pass through the CLI's checks).
#[test]
fn the_library_refuses_unrepresentable_parameters() {
    use riplab::contact::ContactParams;
    use riplab::contact::newton::NewtonOptions;
    use riplab::error::SolveError;
    use riplab::solve::solve_contact;
    let s = riplab::scenario::Scenario::paper();
    let disc = s.discretize(1, s.element).unwrap();
    for (epsilon, depth) in [(1e-200, 0.8), (1e300, 0.8), (1e-6, 1.7e308), (1e-6, f64::NAN)] {
        let params = ContactParams::by_epsilon(s.rule, epsilon, s.obstacle.with_depth(depth));
        let r = solve_contact(&disc, &params, None, &NewtonOptions::default(), &mut |_| {
            std::ops::ControlFlow::Continue(())
        });
        match r {
            Err(e @ SolveError::Range { .. }) => assert!(e.is_input(), "{e}"),
            other => panic!("ε = {epsilon}, depth = {depth}: {other:?}"),
        }
    }
}

/// Whatever a library user builds, a non-finite number is never reported as converged.
#[test]
fn a_stiffness_that_overflows_is_never_converged() {
    use riplab::contact::ContactParams;
    use riplab::contact::newton::NewtonOptions;
    use riplab::discretization::Discretization;
    use riplab::material::{Material, Plane};
    use riplab::solve::solve_contact;
    let s = riplab::scenario::Scenario::paper();
    for young in [1.7e308, 1e300] {
        let material = Material {
            young,
            poisson: 0.3,
            plane: Plane::Strain,
        };
        let Ok(disc) = Discretization::new(s.mesh(0, s.element), material, s.integration) else {
            continue; // refused: fine
        };
        let (lo, _) = disc.epsilon_range();
        let params = ContactParams::by_epsilon(s.rule, lo * 10.0, s.obstacle.clone());
        if let Ok(sol) = solve_contact(&disc, &params, None, &NewtonOptions::default(), &mut |_| {
            std::ops::ControlFlow::Continue(())
        }) {
            let finite = sol.load.is_finite()
                && sol.newton.residual.is_finite()
                && sol
                    .p
                    .iter()
                    .chain(&sol.pbar)
                    .chain(&sol.vertex_uy)
                    .all(|v| v.is_finite());
            assert!(
                !sol.newton.converged || finite,
                "E = {young}: converged with load {} residual {}",
                sol.load,
                sol.newton.residual
            );
        }
    }
}

// 2. Physically poor answers are warned about.

#[test]
fn locking_and_unresolved_obstacles_are_warned_about() {
    let locking = scratch("locking.toml", &paper_text(&[("poisson", "poisson = 0.4999999")]));
    let (code, stdout, stderr) = riplab(&["solve", locking.to_str().unwrap(), "--format", "json"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stderr.contains("warning:") && stderr.contains("locks"),
        "{stderr}"
    );
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let warnings = v["warnings"].as_array().unwrap();
    assert!(
        warnings.iter().any(|w| w.as_str().unwrap().contains("selective")),
        "{warnings:?}"
    );
    // Selective integration cures it: no warning.
    let cured = scratch(
        "locking-cured.toml",
        &paper_text(&[
            ("poisson", "poisson = 0.4999999"),
            ("level", "level = 0\nintegration = \"selective\""),
        ]),
    );
    let (code, stdout, stderr) = riplab(&["solve", cured.to_str().unwrap(), "--format", "json"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(!stderr.contains("warning:"), "{stderr}");
    assert_eq!(
        serde_json::from_str::<serde_json::Value>(&stdout).unwrap()["warnings"],
        serde_json::json!([])
    );

    // A cylinder of radius 0.5 falls between the level-0 points: load 0 with a warning.
    let narrow = scratch(
        "narrow.toml",
        &paper_text(&[("radius", "radius = 0.5"), ("depth", "depth = 3.0")]),
    );
    let (code, stdout, stderr) = riplab(&["solve", narrow.to_str().unwrap(), "--format", "json"]);
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["load"].as_f64(), Some(0.0));
    assert!(stderr.contains("does not resolve it"), "{stderr}");
    // At a level that resolves it, a narrow contact zone is still said to be narrow.
    let (code, _, stderr) = riplab(&["solve", narrow.to_str().unwrap(), "--level", "1"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.contains("contact zone spans only"), "{stderr}");
    // The paper's problem at level 1 has no warning.
    let (code, _, stderr) = riplab(&["solve", "--level", "1"]);
    assert_eq!(code, 0);
    assert!(!stderr.contains("warning"), "{stderr}");
}

// 3. Exit codes of the study.

#[test]
fn a_study_with_unconverged_rows_exits_1_and_shows_them() {
    // κ = ε·E/h = 1e-16 at level 0: round-off swamps the forces, the rows are not certified.
    let (code, stdout, stderr) = riplab(&[
        "study",
        "--levels",
        "0..1",
        "--schemes",
        "M1,M3",
        "--epsilon",
        "1e-19",
    ]);
    no_panic(&stderr);
    assert_eq!(code, 1, "{stderr}");
    assert!(stdout.contains("NOT CONVERGED"), "{stdout}");
    assert!(stdout.contains("rows without a certified result"), "{stdout}");
}

#[test]
fn a_sweep_reports_rows_it_cannot_solve_in_place() {
    let (code, stdout, stderr) = riplab(&[
        "solve",
        "--scheme",
        "M2",
        "--level",
        "1",
        "--epsilon",
        "1e-6,0",
        "--format",
        "json",
    ]);
    assert_eq!(code, 1, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let rows = v.as_array().unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0]["status"], "ok");
    assert!(rows[0]["load"].as_f64().unwrap() > 0.0);
    assert_eq!(rows[1]["status"], "kernel");
    assert!(rows[1]["reason"].as_str().unwrap().contains("not unique"));
}

// 4. Unbounded reads.

#[test]
fn special_files_are_refused_without_reading_them() {
    for path in ["/dev/zero", "/dev/urandom", "/dev/stdin", "/dev/null", "/"] {
        if !Path::new(path).exists() {
            continue;
        }
        let (code, stdout, stderr) = riplab_within(&["solve", path]);
        assert_eq!(code, 2, "{path}: {stderr}");
        assert!(
            stdout.is_empty() && stderr.contains("not a regular file"),
            "{path}: {stderr}"
        );
    }
    // A FIFO with no writer would block an open() for ever.
    let fifo = Path::new(env!("CARGO_TARGET_TMPDIR")).join("scenario.fifo");
    let _ = std::fs::remove_file(&fifo);
    let made = Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        let (code, _, stderr) = riplab_within(&["solve", fifo.to_str().unwrap()]);
        assert_eq!(code, 2, "{stderr}");
        assert!(stderr.contains("a FIFO"), "{stderr}");
        std::fs::remove_file(&fifo).unwrap();
    }
    // A tour that names a device as its scenario.
    let tour = scratch(
        "device-tour.toml",
        "title = \"t\"\n[[step]]\ntitle = \"s\"\ncaption = \"c\"\nscenario = \"/dev/zero\"\n",
    );
    let (code, _, stderr) = riplab_within(&["tour", "--tour", tour.to_str().unwrap()]);
    no_panic(&stderr);
    assert_eq!(code, 2, "{stderr}");
}

// 7, 8. Output that cannot be written.

#[test]
fn a_closed_stderr_is_not_a_crash() {
    for args in [
        &["solve", "--level", "99"][..],
        &["study", "--levels", "0..1", "--schemes", "M1"],
    ] {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let status = Command::new(env!("CARGO_BIN_EXE_riplab"))
            .args(args)
            .env("XDG_CACHE_HOME", crate::common::test_cache())
            .stdout(Stdio::null())
            .stderr(writer)
            .status()
            .unwrap();
        assert_ne!(status.code(), Some(101), "{args:?} panicked");
        assert!(status.code().is_some(), "{args:?} died of a signal");
    }
}

#[test]
fn a_closed_stdout_pipe_is_not_a_crash() {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(env!("CARGO_BIN_EXE_riplab"))
        .args(["solve", "--level", "1"])
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    no_panic(&stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
}

#[test]
fn a_full_disk_is_an_error() {
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else {
        return;
    };
    let out = Command::new(env!("CARGO_BIN_EXE_riplab"))
        .args(["solve", "--format", "json"])
        .stdout(full)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("cannot write the output"), "{stderr}");
}

// 9. Text from files is sanitised.

#[test]
fn escape_sequences_from_files_never_reach_the_terminal() {
    let hostile = scratch(
        "escapes.toml",
        &paper_text(&[("name", "name = \"\\u001b]0;PWNED\\u0007\\u001b[2J\"")]),
    );
    let (code, stdout, stderr) = riplab(&["solve", hostile.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        !stdout.contains('\u{1b}') && !stdout.contains('\u{7}'),
        "{stdout:?}"
    );
    assert!(stdout.contains("]0;PWNED"), "the name is shown, defanged");
    // A malformed file with raw control bytes: the error snippet is defanged too.
    let raw = scratch(
        "raw-escapes.toml",
        "name = \"x\"\n\u{1b}[2J\u{1b}]0;PWNED\u{7} = = =\n",
    );
    let (code, _, stderr) = riplab(&["solve", raw.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(
        !stderr.contains('\u{1b}') && !stderr.contains('\u{7}'),
        "{stderr:?}"
    );
}

// 10. --force replaces regular files only, and the check comes before the solve.

#[test]
fn force_never_replaces_links_fifos_or_devices() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("force-targets");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let target = dir.join("real.svg");
    std::fs::write(&target, "keep").unwrap();
    let link = dir.join("link.svg");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let (code, _, stderr) = riplab(&["solve", "--plot", link.to_str().unwrap(), "--force"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("not a regular file"), "{stderr}");
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
    let fifo = dir.join("pipe.svg");
    if Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        let (code, _, stderr) = riplab_within(&["solve", "--plot", fifo.to_str().unwrap(), "--force"]);
        assert_eq!(code, 2, "{stderr}");
        use std::os::unix::fs::FileTypeExt as _;
        assert!(std::fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
    }
    // An existing file is refused before a solve that would take long: under half the
    // memory of level 7 (whose guard would refuse it in other words) it is still "exists".
    let level7 = Scenario::paper().sizes(7, Element::Q1);
    let (code, stdout, stderr) = riplab_under_half_of(
        &level7,
        &["solve", "--level", "7", "--plot", target.to_str().unwrap()],
    );
    assert_eq!(code, 2, "{stderr}");
    assert!(stdout.is_empty() && stderr.contains("exists"), "{stderr}");
    assert!(
        !stderr.contains("choose a coarser level"),
        "the check came after the solve's"
    );
    // A regular file is replaced with --force.
    let (code, _, stderr) = riplab(&["solve", "--plot", target.to_str().unwrap(), "--force"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(std::fs::read_to_string(&target).unwrap().contains("<svg"));
}

// 11. Degenerate geometry is bad input naming the key.

#[test]
fn degenerate_geometry_names_the_key() {
    for (edit, key) in [
        (("width", "width = 1e-300"), "`body.width`"),
        (("height", "height = 1e300"), "`body.height`"),
        (("young", "young = 1.8e308"), "`material.young`"),
        (("nx", "x_lines = [0.0, 1e-300, 8.0]"), "`mesh.x_lines`"),
    ] {
        let text = paper_text(&[edit]);
        let path = scratch("degenerate.toml", &text);
        let (code, stdout, stderr) = riplab(&["solve", path.to_str().unwrap()]);
        no_panic(&stderr);
        assert_eq!(code, 2, "{edit:?}: {stderr}");
        assert!(stdout.is_empty() && stderr.contains(key), "{edit:?}: {stderr}");
        assert!(!stderr.contains("rigid motion"), "{edit:?}: {stderr}");
    }
}

// 12. Smaller things.

#[test]
fn smaller_holes_are_closed() {
    // A polyline point with three coordinates.
    let poly = paper_text(&[
        (
            "shape",
            "shape = \"polyline\"\npoints = [[-8.0, 1.0], [0.0, 0.0, 5.0], [8.0, 1.0]]",
        ),
        ("radius", ""),
        ("center", ""),
    ]);
    let path = scratch("poly3.toml", &poly);
    let (code, _, stderr) = riplab(&["solve", path.to_str().unwrap()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("`obstacle.points`") && stderr.contains("3 coordinates"),
        "{stderr}"
    );
    // `--scheme` takes pairs as `study --schemes` does.
    let (code, stdout, stderr) = riplab(&["solve", "--scheme", "q2+gauss1", "--format", "json"]);
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(
        (v["element"].as_str(), v["rule"].as_str()),
        (Some("q2"), Some("gauss1"))
    );
    // `infsup --level L` estimates level L; `study --level` needs a sweep.
    let (code, stdout, stderr) = riplab(&["infsup", "--level", "2", "--format", "json"]);
    assert_eq!(code, 0, "{stderr}");
    let rows: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(rows.as_array().unwrap().len(), 1);
    assert_eq!(rows[0]["level"], 2);
    let (code, _, stderr) = riplab(&["study", "--level", "2"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("--sweep-epsilon"), "{stderr}");
    // ε = 0 with a kernel rule is refused before the (here expensive) assembly: under half the
    // memory of level 8, whose guard would refuse it in other words.
    let level8 = Scenario::paper().sizes(8, Element::Q1);
    let (code, _, stderr) = riplab_under_half_of(
        &level8,
        &["solve", "--scheme", "M2", "--epsilon", "0", "--level", "8"],
    );
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("not unique"), "{stderr}");
    assert!(
        !stderr.contains("choose a coarser level"),
        "refused only after assembly"
    );
}

/// Errors inside nested tables (arrays of inline tables) name the line and the dotted key.
#[test]
fn nested_table_errors_have_a_line_and_a_key() {
    let bumps =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/two-bumps.toml")).unwrap();
    let second = "{ center = 3.0, radius = 3.0, lift = 0.1 }";
    assert!(bumps.contains(second));
    let line = bumps.lines().position(|l| l.contains(second)).unwrap() + 1;
    for (replacement, key, fragment) in [
        (
            "{ center = 3.0 }",
            "`obstacle.bumps.radius`",
            "missing field `radius`",
        ),
        (
            "{ center = 3.0, radius = 3.0, lift = 0.1, foo = 1 }",
            "`obstacle.bumps`",
            "unknown field `foo`",
        ),
        (
            "{ center = 3.0, radius = -3.0 }",
            "`obstacle.bumps.radius`",
            "-3 is out of range",
        ),
    ] {
        let path = scratch("nested.toml", &bumps.replace(second, replacement));
        let (code, _, stderr) = riplab(&["solve", path.to_str().unwrap()]);
        assert_eq!(code, 2, "{stderr}");
        assert!(
            stderr.contains(&format!("nested.toml:{line}:"))
                && stderr.contains(key)
                && stderr.contains(fragment),
            "{replacement}: {stderr}"
        );
    }
}

/// A row's status is the same token in CSV as in JSON (`not_converged`, not `not converged`).
#[test]
fn csv_and_json_agree_on_a_rows_status() {
    let args = [
        "study",
        "--levels",
        "0..0",
        "--schemes",
        "M1",
        "--epsilon",
        "1e-19",
    ];
    let (code, csv, _) = riplab(&[&args[..], &["--format", "csv"]].concat());
    assert_eq!(code, 1);
    let (_, json, _) = riplab(&[&args[..], &["--format", "json"]].concat());
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let token = v["rows"][0]["status"].as_str().unwrap().to_string();
    assert_eq!(token, "not_converged");
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = header.iter().position(|h| *h == "status").unwrap();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(row[column], token);
}
