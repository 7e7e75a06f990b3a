//! The paper's tour recorded at 80×24 with `--auto 0.5`: each step's marker is written once
//! the step's computations (the solve, the inf-sup rows, the study and its reference) have
//! finished, so that the recording replayed to any marker shows a finished frame — nothing
//! `computing`, no `⟳`, no two-body `solving` — with the step's whole caption on screen (no
//! `↓ more`).

use std::io::Write;
use std::process::Stdio;
use std::time::{Duration, Instant};

use super::record::{Reap, Screen, parser_of, pty_of, rows};

const SIZE: (u16, u16) = (80, 24);

#[test]
fn a_recorded_tour_marks_each_step_on_its_finished_frame() {
    let dir = std::env::temp_dir().join(format!("riplab-record-tour-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let cast = dir.join("t.cast");
    let (controller, user) = pty_of(SIZE);
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_riplab"))
        .args(["tour", "--auto", "0.5", "--record"])
        .arg(&cast)
        .env("TERM", "xterm-256color")
        .env("NO_COLOR", "1")
        .env("XDG_CACHE_HOME", crate::common::test_cache())
        .stdin(Stdio::from(user.try_clone().unwrap()))
        .stdout(Stdio::from(user.try_clone().unwrap()))
        .stderr(Stdio::from(user))
        .spawn()
        .unwrap();
    let mut child = Reap(child);
    let (screen, reader) = Screen::read_into(&controller, parser_of(SIZE));
    // The whole tour computes (the reference of step 13 too): a generous deadline.
    let deadline = Instant::now() + Duration::from_secs(900);
    screen.wait_quiet(
        screen.wait_for(&["tour 19/19", "auto: done", "patch test failed"], deadline),
        deadline,
    );
    std::fs::File::from(controller).write_all(b"q").unwrap();
    screen.wait_for_end(deadline);
    assert!(child.0.wait().unwrap().success());
    drop(child);
    let _ = reader.join();

    let text = std::fs::read_to_string(&cast).unwrap();
    let mut replay = parser_of(SIZE);
    let mut markers = Vec::new();
    for line in text.lines().skip(1) {
        let event: serde_json::Value = serde_json::from_str(line).unwrap();
        let data = event[2].as_str().unwrap();
        match event[1].as_str().unwrap() {
            "o" => replay.process(data.as_bytes()),
            "m" => {
                let frame = rows(replay.screen()).join("\n");
                for busy in ["computing", "⟳", "↓ more", "estimate(s) running", "solving"] {
                    assert!(!frame.contains(busy), "`{busy}` at the marker `{data}`:\n{frame}");
                }
                assert!(
                    frame.contains(&format!("tour {}/19", markers.len() + 1)),
                    "{data}:\n{frame}"
                );
                markers.push(data.to_string());
            }
            _ => {}
        }
    }
    assert_eq!(markers.len(), 19, "{markers:?}");
    assert_eq!(markers[0], "The problem");
    assert_eq!(markers[14], "Beyond the paper: friction, Cattaneo–Mindlin");
    // The two-body steps' markers too, each on its solved scene (no `solving`).
    assert_eq!(markers[18], "Kikuchi's reduced integration across the interface");
    // Each step was shown at least the interval after its marker: the auto-advance counts
    // from the finished frame shown, so that however long a frame takes to come on a loaded
    // host, no step is cut short (a millisecond's margin for the times' floating point).
    let times: Vec<f64> = text
        .lines()
        .skip(1)
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .filter(|e| e[1] == "m")
        .map(|e| e[0].as_f64().unwrap())
        .collect();
    assert!(times.windows(2).all(|w| w[1] - w[0] >= 0.5 - 1e-3), "{times:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The live tour goes between one-body and two-body steps with its keys: End shows the last
/// step (two bodies, solved on the tour's thread), `n` there changes its discretisation and it
/// is solved again, ← shows the step before (mortar), Home the first (one body, its solve
/// kept); `q` `q` quits with exit 0.
#[test]
fn the_live_tour_goes_between_one_body_and_two_body_steps() {
    let (controller, user) = pty_of(SIZE);
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_riplab"))
        .arg("tour")
        .env("TERM", "xterm-256color")
        .env("NO_COLOR", "1")
        .env("XDG_CACHE_HOME", crate::common::test_cache())
        .stdin(Stdio::from(user.try_clone().unwrap()))
        .stdout(Stdio::from(user.try_clone().unwrap()))
        .stderr(Stdio::from(user))
        .spawn()
        .unwrap();
    let mut child = Reap(child);
    let (screen, reader) = Screen::read_into(&controller, parser_of(SIZE));
    let mut keys = std::fs::File::from(controller.try_clone().unwrap());
    // A generous deadline, not a timing: each step solves in well under a second.
    let deadline = Instant::now() + Duration::from_secs(300);
    drop(screen.wait_for(&["tour 1/19", "✓ converged"], deadline));
    for (key, shown) in [
        (
            &b"\x1b[F"[..],
            &["tour 19/19", "patch test failed: error 0.0077"][..],
        ),
        (
            b"n",
            &["rip-gauss2", "patch test failed: error 0.096", "(changed)"],
        ),
        (b"\x1b[D", &["tour 18/19", "patch test passed"]),
        (b"\x1b[H", &["tour 1/19", "✓ converged"]),
    ] {
        keys.write_all(key).unwrap();
        drop(screen.wait_for(shown, deadline));
    }
    keys.write_all(b"qq").unwrap();
    screen.wait_for_end(deadline);
    assert!(child.0.wait().unwrap().success());
    drop(child);
    let _ = reader.join();
}
