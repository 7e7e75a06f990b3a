//! `riplab render` and the lab on a two-body scenario (docs/lab.md, "Two bodies"): the
//! two-body scene drawn with `--contact`, what it refuses (exit 2), and the lab in a terminal
//! answering its keys and giving the terminal back on `q`.

use crate::common::riplab as run;
use crate::pty::{Pty, assert_restored, riplab, screen};

const PATCH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/patch-two-blocks.toml");
const HERTZ: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-two-bodies.toml");

/// `render PATCH --contact M --size 80x24`: the frame fits 80×24, names the method and the
/// ratio, and states the patch test's verdict: mortar passes, NTS fails; `--keys` steps the
/// ratio to 1:1, where NTS passes. On the Hertz scenario the status line gives the load.
#[test]
fn render_draws_the_two_body_scene() {
    for (contact, keys, said) in [
        ("mortar", "", "patch test passed: error < 1e-12 (≤ 1e-10)"),
        ("nts", "", "patch test failed: error 0.1 (> 1e-3)"),
        ("nts", "k", "patch test passed"),
        ("rip", "", "p̄ smoothed (17)"),
    ] {
        let args = [
            "render",
            PATCH,
            "--contact",
            contact,
            "--size",
            "80x24",
            "--keys",
            keys,
        ];
        let (code, out, err) = run(&args);
        assert_eq!(code, 0, "{args:?}: {err}");
        assert_eq!(out.lines().count(), 24, "{out}");
        // Columns: p̄'s combining macron takes none.
        let columns = |l: &str| l.chars().filter(|&c| c != '\u{304}').count();
        assert!(out.lines().all(|l| columns(l) <= 80), "{out}");
        assert!(out.contains(said), "{args:?}: {out}");
        assert!(out.contains(" · ratio "), "{out}");
    }
    let (code, out, err) = run(&[
        "render",
        HERTZ,
        "--contact",
        "nts2",
        "--epsilon",
        "1e-5",
        "--size",
        "80x24",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("nts2: load P = ") && out.contains("ε = 1e-5"),
        "{out}"
    );
    // The ALM across the interface: mortar's updates reach the exact uniform pressure.
    let (code, out, err) = run(&[
        "render",
        PATCH,
        "--contact",
        "mortar",
        "--method",
        "alm",
        "--epsilon",
        "1e-4",
        "--size",
        "80x24",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("ALM ε = 1e-4") && out.contains("patch test passed"),
        "{out}"
    );
}

/// `render PATCH --keys "<tab>"` and `--scene infsup` draw the inf-sup view at 80×24: β_h of
/// every space of the rule at levels 0–3, their slope, the ratio and offset in the header.
#[test]
fn render_draws_the_inf_sup_view() {
    for way in [&["--keys", "<tab>"][..], &["--scene", "infsup"][..]] {
        let mut args = vec!["render", PATCH, "--size", "80x24"];
        args.extend(way);
        let (code, out, err) = run(&args);
        assert_eq!(code, 0, "{args:?}: {err}");
        assert_eq!(out.lines().count(), 24, "{out}");
        for said in [
            "inf-sup at ratio 2:3 · offset 0",
            "mortar-dual",
            "rip-gauss1-pbar",
            "slope",
            "β_h at ratio 2:3",
        ] {
            assert!(out.contains(said), "{args:?}: {said}:\n{out}");
        }
    }
}

/// What the two-body scene does not take is refused before any work, naming why (exit 2):
/// a one-body scene, grading, a one-body method, `--contact` on one body (render's and the
/// lab's), the lab's `--contact` before a command.
#[test]
fn render_refuses_what_two_bodies_do_not_take() {
    for (args, said) in [
        (&["--scene", "convergence"][..], "needs one body"),
        (&["--refine-edges", "1"][..], "grading"),
        (
            &["--method", "nitsche"][..],
            "does not apply to a two-body scenario",
        ),
    ] {
        let mut all = vec!["render", PATCH];
        all.extend_from_slice(args);
        let (code, _, err) = run(&all);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(said), "{args:?}: {err}");
    }
    // --contact on one body: render's, and the lab's (refused before the terminal is taken).
    for args in [&["render", "--contact", "nts"][..], &["--contact", "nts"]] {
        let (code, _, err) = run(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(
            err.contains("--contact") && err.contains("[upper]"),
            "{args:?}: {err}"
        );
    }
    // The lab's --contact is not a command's.
    let (code, _, err) = run(&["--contact", "nts", "solve", PATCH]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--contact before the command is the lab's"), "{err}");
}

/// The lab on the patch scenario in an 80×24 terminal, monochrome: it opens on mortar, `n`
/// goes to mortar-dual, `k` to 1:1, a one-body key says why not; `q` gives the terminal back.
#[test]
fn the_lab_opens_the_two_body_scene_and_q_restores_the_terminal() {
    const SIZE: (u16, u16) = (80, 24);
    let mut command = riplab(&[PATCH]);
    command.env("NO_COLOR", "1");
    let mut pty = Pty::spawn(SIZE, command);
    pty.wait_for_frame();
    pty.wait_for_text(SIZE, "patch test passed");
    pty.send(b"n");
    pty.wait_for_text(SIZE, "mortar-dual · ratio 2:3");
    pty.send(b"k");
    pty.wait_for_text(SIZE, "mortar-dual · ratio 1:1");
    pty.send(b"F");
    pty.wait_for_text(SIZE, "friction is not available on two bodies");
    pty.send(b"q");
    let ended = pty.finish();
    assert!(ended.status.success(), "{}", ended.status);
    assert!(ended.cooked, "the terminal is left in raw mode");
    assert_restored(&screen(SIZE, &ended.output), "q in the two-body scene");
}

/// Off the patch test the status line counts the active-set iterations in the singular for
/// one: a narrow block (`[upper] width`) settles at once, and read "1 iterations".
#[test]
fn one_iteration_is_singular_in_the_status_line() {
    let text =
        std::fs::read_to_string(PATCH)
            .unwrap()
            .replacen("height = 0.5", "height = 0.5\nwidth = 1.0", 1);
    let path = crate::common::scratch_file("lab-bodies-narrow.toml", &text);
    let args = [
        "render",
        path.to_str().unwrap(),
        "--contact",
        "mortar",
        "--size",
        "80x24",
    ];
    let (code, out, err) = run(&args);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("· 1 iteration\n") || out.contains("· 1 iteration "),
        "{out}"
    );
}

/// A status line wider than the frame breaks between its items, not inside one: a narrow
/// block pressed 1e-300 under rip-trapezoid read "… · contact 0 to 0.5 · 1" and "iteration"
/// on the next row.
#[test]
fn a_long_status_line_breaks_between_its_items() {
    let text = std::fs::read_to_string(PATCH)
        .unwrap()
        .replacen("height = 0.5", "height = 0.5\nwidth = 1.0", 1)
        .replacen("displacement = 0.01", "displacement = 1e-300", 1)
        .replacen("rule = \"gauss1\"", "rule = \"trapezoid\"", 1);
    let path = crate::common::scratch_file("lab-bodies-long-status.toml", &text);
    let args = [
        "render",
        path.to_str().unwrap(),
        "--contact",
        "rip",
        "--size",
        "80x24",
    ];
    let (code, out, err) = run(&args);
    assert_eq!(code, 0, "{err}");
    let rows: Vec<&str> = out.lines().collect();
    let at = rows
        .iter()
        .position(|l| l.contains("load P = "))
        .expect("the status line");
    assert!(rows[at].trim_end().ends_with("contact 0 to 0.5"), "{out}");
    assert_eq!(rows[at + 1].trim(), "1 iteration", "{out}");
}
