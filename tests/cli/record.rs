//! `riplab tour --auto --record FILE.cast` run in a pseudo-terminal gives a valid asciicast v2
//! file: the header first, events in non-decreasing time, a marker per step (its title), and
//! output that, replayed through a terminal emulator (vt100), ends on the last step's frame as
//! the tour's handout draws it (`riplab tour --handout`); and the lab's `T` writes a tour step
//! that `tour --check` accepts. (The recorder alone is tested beside it, in src/tui/tests.)

use std::io::{Read, Write};
use std::os::fd::OwnedFd;
use std::path::PathBuf;
use std::process::{Child, Stdio};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

const SIZE: (u16, u16) = (100, 30);

/// Three cheap steps (level 0); the last shows the mesh scene, which has no inf-sup panel to
/// fill after its solve.
const TOUR: &str = "title = \"Recorded\"

[[step]]
title = \"One: M1\"
caption = \"The first step.\"
scheme = \"M1\"
level = 0

[[step]]
title = \"Two: M3\"
caption = \"The second step.\"
scheme = \"M3\"
level = 0

[[step]]
title = \"Three: the mesh\"
caption = \"The last step.\"
scene = \"mesh\"
scheme = \"M1\"
level = 0
";

/// A pseudo-terminal of `SIZE`: (controller, the terminal's side).
fn pty() -> (OwnedFd, OwnedFd) {
    pty_of(SIZE)
}

/// A pseudo-terminal of `size` (columns, rows): (controller, the terminal's side).
pub(crate) fn pty_of(size: (u16, u16)) -> (OwnedFd, OwnedFd) {
    use rustix::pty::{OpenptFlags, grantpt, openpt, ptsname, unlockpt};
    let controller = openpt(OpenptFlags::RDWR | OpenptFlags::NOCTTY | OpenptFlags::CLOEXEC).unwrap();
    grantpt(&controller).unwrap();
    unlockpt(&controller).unwrap();
    let name = ptsname(&controller, Vec::new()).unwrap();
    let user = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .open(name.to_str().unwrap())
        .unwrap();
    rustix::termios::tcsetwinsize(
        &user,
        rustix::termios::Winsize {
            ws_row: size.1,
            ws_col: size.0,
            ws_xpixel: 0,
            ws_ypixel: 0,
        },
    )
    .unwrap();
    (controller, user.into())
}

/// A terminal emulator of `SIZE`.
fn parser() -> vt100::Parser {
    parser_of(SIZE)
}

/// A terminal emulator of `size` (columns, rows).
pub(crate) fn parser_of(size: (u16, u16)) -> vt100::Parser {
    let n = |v: u16| std::num::NonZeroU16::new(v).unwrap();
    vt100::Parser::new(n(size.1), n(size.0), 0)
}

/// The screen as vt100 shows it, one trimmed line per row.
pub(crate) fn rows(screen: &vt100::Screen) -> Vec<String> {
    let (_, columns) = screen.size();
    screen
        .rows(0, columns.get())
        .map(|r| r.trim_end().to_string())
        .collect()
}

/// A line as compared: the status line and the caption's title line without what the live
/// tour shows and `render_step` leaves out (the solve's time, the auto-advance's state), with
/// runs of blanks made one (their keys are right-aligned); every other line exactly.
fn comparable(line: &str) -> String {
    if !line.contains("Newton step") && !line.contains(" tour 3/3 ") {
        return line.to_string();
    }
    let line = line.replace(" auto: done ", " ");
    let mut parts = line.split(" · ");
    let mut kept = vec![parts.next().unwrap_or_default().to_string()];
    for part in parts {
        let time = part.split_once(" ms").is_some_and(|(number, _)| {
            !number.is_empty() && number.chars().all(|c| c.is_ascii_digit() || ".e+-".contains(c))
        });
        match part.split_once(" ms") {
            // The time alone, or the time then the keys: the keys kept.
            Some((_, rest)) if time => kept.last_mut().unwrap().push_str(rest),
            _ => kept.push(part.to_string()),
        }
    }
    kept.join(" · ").split_whitespace().collect::<Vec<_>>().join(" ")
}

/// What the terminal shows, as read from the controller so far.
pub(crate) struct Live {
    terminal: vt100::Parser,
    /// The reads so far.
    reads: u64,
    /// Whether riplab's side has closed (riplab ended).
    closed: bool,
}

/// The terminal kept up to date by a thread that reads the controller, each read signalled:
/// the tests wait on it for what they expect, never for a fixed time.
pub(crate) struct Screen {
    live: Mutex<Live>,
    changed: Condvar,
}

impl Screen {
    /// Read `controller` on a thread of its own (the child blocks if nobody reads) until
    /// riplab's side closes.
    fn read(controller: &OwnedFd) -> (Arc<Screen>, JoinHandle<()>) {
        Screen::read_into(controller, parser())
    }

    /// [`Screen::read`] into `terminal` (of the pseudo-terminal's size).
    pub(crate) fn read_into(controller: &OwnedFd, terminal: vt100::Parser) -> (Arc<Screen>, JoinHandle<()>) {
        let screen = Arc::new(Screen {
            live: Mutex::new(Live {
                terminal,
                reads: 0,
                closed: false,
            }),
            changed: Condvar::new(),
        });
        let mut from = std::fs::File::from(controller.try_clone().unwrap());
        let reading = screen.clone();
        let reader = std::thread::spawn(move || {
            let mut buf = [0u8; 65536];
            loop {
                let n = from.read(&mut buf).unwrap_or(0);
                let mut live = reading.live.lock().unwrap();
                if n == 0 {
                    live.closed = true;
                } else {
                    live.terminal.process(&buf[..n]);
                    live.reads += 1;
                }
                reading.changed.notify_all();
                if n == 0 {
                    break;
                }
            }
        });
        (screen, reader)
    }

    /// Wait until the screen's text holds all of `what` or riplab ended, at most until
    /// `deadline`.
    pub(crate) fn wait_for(&self, what: &[&str], deadline: Instant) -> MutexGuard<'_, Live> {
        let shows = |live: &Live| {
            let text = live.terminal.screen().contents();
            what.iter().all(|w| text.contains(w))
        };
        let live = self.live.lock().unwrap();
        let timeout = deadline.saturating_duration_since(Instant::now());
        let (live, _) = self
            .changed
            .wait_timeout_while(live, timeout, |l| !l.closed && !shows(l))
            .unwrap();
        assert!(
            shows(&live),
            "waiting for {what:?} (riplab ended: {}):\n{}",
            live.closed,
            rows(live.terminal.screen()).join("\n")
        );
        live
    }

    /// From `live` on, wait until the screen has not changed for 700 ms (its last frame
    /// drawn), riplab still running, at most until `deadline`.
    pub(crate) fn wait_quiet(&self, mut live: MutexGuard<'_, Live>, deadline: Instant) {
        loop {
            let reads = live.reads;
            let (now, quiet) = self
                .changed
                .wait_timeout_while(live, Duration::from_millis(700), |l| {
                    l.reads == reads && !l.closed
                })
                .unwrap();
            assert!(
                !now.closed,
                "riplab ended early:\n{}",
                rows(now.terminal.screen()).join("\n")
            );
            if quiet.timed_out() {
                return;
            }
            assert!(Instant::now() < deadline, "the screen never stays quiet");
            live = now;
        }
    }

    /// Wait until riplab has ended, at most until `deadline`.
    pub(crate) fn wait_for_end(&self, deadline: Instant) {
        let live = self.live.lock().unwrap();
        let timeout = deadline.saturating_duration_since(Instant::now());
        let (live, _) = self
            .changed
            .wait_timeout_while(live, timeout, |l| !l.closed)
            .unwrap();
        assert!(live.closed, "riplab did not quit");
    }
}

/// Kill the child if the test fails before it ends.
pub(crate) struct Reap(pub(crate) Child);

impl Drop for Reap {
    fn drop(&mut self) {
        if self.0.try_wait().ok().flatten().is_none() {
            let _ = self.0.kill();
            let _ = self.0.wait();
        }
    }
}

#[test]
fn a_recorded_tour_is_a_valid_asciicast_ending_on_the_last_frame() {
    let dir = std::env::temp_dir().join(format!("riplab-record-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let tour_file = dir.join("t.toml");
    std::fs::write(&tour_file, TOUR).unwrap();
    let cast: PathBuf = dir.join("t.cast");
    let (controller, user) = pty();
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_riplab"))
        .args(["tour", "--tour"])
        .arg(&tour_file)
        .args(["--auto", "0.5", "--record"])
        .arg(&cast)
        .env("TERM", "xterm-256color")
        .env("XDG_CACHE_HOME", crate::common::test_cache())
        .stdin(Stdio::from(user.try_clone().unwrap()))
        .stdout(Stdio::from(user.try_clone().unwrap()))
        .stderr(Stdio::from(user))
        .spawn()
        .unwrap();
    let mut child = Reap(child);
    let (screen, reader) = Screen::read(&controller);
    // Wait for the last step solved and the screen quiet for a while (its last frame drawn),
    // then quit.
    let deadline = Instant::now() + Duration::from_secs(120);
    screen.wait_quiet(screen.wait_for(&["tour 3/3", "✓ converged"], deadline), deadline);
    std::fs::File::from(controller).write_all(b"q").unwrap();
    screen.wait_for_end(deadline);
    let status = child.0.wait().unwrap();
    assert!(status.success(), "{status}");
    drop(child);
    let _ = reader.join();

    // The file: a header line, then events.
    let text = std::fs::read_to_string(&cast).unwrap();
    let mut lines = text.lines();
    let header: serde_json::Value = serde_json::from_str(lines.next().unwrap()).unwrap();
    assert_eq!(header["version"], 2);
    assert_eq!(header["width"], SIZE.0);
    assert_eq!(header["height"], SIZE.1);
    assert!(header["timestamp"].as_u64().unwrap() > 1_600_000_000);
    assert_eq!(header["title"], "riplab tour: Recorded");
    let events: Vec<(f64, String, String)> = lines
        .map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}"));
            let e = v.as_array().unwrap();
            assert_eq!(e.len(), 3, "{l}");
            (
                e[0].as_f64().unwrap(),
                e[1].as_str().unwrap().to_string(),
                e[2].as_str().unwrap().to_string(),
            )
        })
        .collect();
    assert!(events.windows(2).all(|w| w[0].0 <= w[1].0), "time goes back");
    assert!(events.iter().all(|e| ["o", "m", "r"].contains(&e.1.as_str())));
    let markers: Vec<&str> = events
        .iter()
        .filter(|e| e.1 == "m")
        .map(|e| e.2.as_str())
        .collect();
    assert_eq!(markers, ["One: M1", "Two: M3", "Three: the mesh"]);
    // The steps' markers come about the auto interval (0.5 s) apart, or more while a solve
    // runs (each is stamped when the loop draws, the interval counted from the step's change).
    let times: Vec<f64> = events.iter().filter(|e| e.1 == "m").map(|e| e.0).collect();
    assert!(times.windows(2).all(|w| w[1] - w[0] >= 0.45), "{times:?}");

    // Replayed: the last screen shown before the alternate screen is left is the last step's.
    let mut replay = parser();
    let mut last = None;
    for (_, code, data) in &events {
        if code == "o" {
            replay.process(data.as_bytes());
            if replay.screen().alternate_screen() {
                last = Some(rows(replay.screen()));
            }
        }
    }
    assert!(
        !replay.screen().alternate_screen(),
        "the recording ends with the terminal restored"
    );
    let last = last.expect("frames on the alternate screen");
    let handout = dir.join("handout");
    let size = format!("{}x{}", SIZE.0, SIZE.1);
    let (code, _, err) = crate::common::riplab(&[
        "tour",
        "--tour",
        tour_file.to_str().unwrap(),
        "--handout",
        handout.to_str().unwrap(),
        "--size",
        &size,
    ]);
    assert_eq!(code, 0, "{err}");
    let expected = std::fs::read_to_string(handout.join("step-03.txt")).unwrap();
    let expected: Vec<String> = expected.lines().map(comparable).collect();
    let last: Vec<String> = last.iter().map(|l| comparable(l)).collect();
    assert_eq!(last, expected, "replayed:\n{}", last.join("\n"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The issue's "Done when" in the lab itself: `]]2` then `T` writes a step that `tour --check`
/// accepts at level 2 with M2, the status line says where, and the lab's recording marks the
/// change of scene.
#[test]
fn the_lab_records_and_writes_a_tour_step_on_t() {
    let dir = std::env::temp_dir().join(format!("riplab-record-lab-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let cast = dir.join("lab.cast");
    let tour = dir.join("lesson.toml");
    let (controller, user) = pty();
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_riplab"))
        .arg("--record")
        .arg(&cast)
        .arg("--tour-out")
        .arg(&tour)
        .env("TERM", "xterm-256color")
        .env("XDG_CACHE_HOME", crate::common::test_cache())
        .stdin(Stdio::from(user.try_clone().unwrap()))
        .stdout(Stdio::from(user.try_clone().unwrap()))
        .stderr(Stdio::from(user))
        .spawn()
        .unwrap();
    let mut child = Reap(child);
    let (screen, reader) = Screen::read(&controller);
    let mut keys = std::fs::File::from(controller);
    let deadline = Instant::now() + Duration::from_secs(120);
    let wait_for = |what: &[&str]| drop(screen.wait_for(what, deadline));
    // The lab opens at level 1 (the paper's mesh); one level finer and M2.
    wait_for(&["level 1", "✓ converged"]);
    keys.write_all(b"]2").unwrap();
    wait_for(&["M2 q1+gauss2", "level 2", "✓ converged"]);
    keys.write_all(b"T").unwrap();
    wait_for(&["added step 1 to", "lesson.toml"]);
    keys.write_all(b"\t").unwrap();
    wait_for(&["β_h/√h against h"]);
    keys.write_all(b"q").unwrap();
    screen.wait_for_end(deadline);
    let status = child.0.wait().unwrap();
    assert!(status.success(), "{status}");
    drop(child);
    let _ = reader.join();
    // The step: M2 at level 2, and `tour --check` accepts the file.
    let (code, out, err) = crate::common::riplab(&["tour", "--check", tour.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let row: Vec<&str> = out.lines().last().unwrap().split_whitespace().collect();
    assert_eq!(row[..5], ["1", "explore", "2", "M2", "penalty"], "{out}");
    // The recording: the lab's scenes as markers.
    let text = std::fs::read_to_string(&cast).unwrap();
    let markers: Vec<String> = text
        .lines()
        .skip(1)
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .filter(|e| e[1] == "m")
        .map(|e| e[2].as_str().unwrap().to_string())
        .collect();
    assert_eq!(markers, ["scene: explore", "scene: infsup"]);
    assert!(
        text.lines()
            .next()
            .unwrap()
            .contains("\"title\":\"riplab lab: hertz-paper\"")
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
