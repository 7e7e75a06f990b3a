//! The lab and the tour in a pseudo-terminal ([`crate::pty`]): the terminal given back on a
//! signal and on an abort, the recording finished; memory that follows the drawn frame, not
//! the terminal; `TERM=dumb` refused before any escape sequence; the mouse.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::pty::{ENTERED, Pty, assert_restored, contains, riplab, screen};

/// The size of the ordinary runs.
const SIZE: (u16, u16) = (100, 30);

/// A fresh directory for one test's files.
fn fresh_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The output events of an asciicast file, each line checked to be JSON (a header, then
/// `[time, code, data]` events).
fn cast_output(path: &Path) -> Vec<u8> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: serde_json::Value = serde_json::from_str(lines.next().expect("a header")).unwrap();
    assert_eq!(header["version"], 2, "{path:?}");
    let mut out = Vec::new();
    for line in lines {
        let event: serde_json::Value =
            serde_json::from_str(line).unwrap_or_else(|e| panic!("{path:?}: {e}: {line}"));
        if event[1] == "o" {
            out.extend_from_slice(event[2].as_str().unwrap().as_bytes());
        }
    }
    out
}

/// SIGTERM and SIGHUP, sent once the first frame is on the alternate screen, to the lab, the
/// tour and either while recording: the terminal is given back (the main screen, the cursor
/// shown, no mouse reports, canonical mode with echo), the process ends by that signal, and
/// the recording is a valid asciicast that ends with the terminal restored.
#[test]
fn a_signal_restores_the_terminal_and_finishes_the_recording() {
    let dir = fresh_dir("signalled");
    for (args, signal, number) in [
        (&[][..], "TERM", 15),
        (&[][..], "HUP", 1),
        (&["tour"][..], "TERM", 15),
        (&["tour"][..], "HUP", 1),
        (&["--record"][..], "TERM", 15),
        (&["tour", "--record"][..], "HUP", 1),
    ] {
        let what = format!("riplab {} ← SIG{signal}", args.join(" "));
        let cast = dir.join(format!("{}-{signal}.cast", args.join("-")));
        let mut command = riplab(args);
        if args.contains(&"--record") {
            command.arg(&cast);
        }
        let mut pty = Pty::spawn(SIZE, command);
        pty.wait_for_frame();
        pty.signal(signal);
        let ended = pty.finish();
        assert_eq!(ended.signal(), Some(number), "{what}: {}", ended.status);
        assert!(ended.cooked, "{what}: the terminal is left in raw mode");
        assert_restored(&screen(SIZE, &ended.output), &what);
        if args.contains(&"--record") {
            let replayed = cast_output(&cast);
            assert!(contains(&replayed, ENTERED), "{what}: the recording has frames");
            assert_restored(&screen(SIZE, &replayed), &format!("{what}, replayed"));
        }
    }
}

/// The lab aborted (SIGABRT, as a failed allocation does) once its first frame is drawn
/// leaves the alternate screen, shows the cursor and puts the terminal's settings back.
#[test]
fn an_aborted_lab_restores_the_terminal() {
    let mut pty = Pty::spawn(SIZE, riplab(&["--no-color"]));
    pty.wait_for_frame();
    pty.signal("ABRT");
    let ended = pty.finish();
    assert_eq!(ended.signal(), Some(6), "{}", ended.status);
    assert!(ended.cooked, "the terminal is left in raw mode");
    assert_restored(&screen(SIZE, &ended.output), "aborted");
}

/// The peak address space (VmPeak, bytes) of process `pid`.
fn vm_peak(pid: u32) -> u64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap();
    let line = status.lines().find(|l| l.starts_with("VmPeak:")).expect("VmPeak");
    let kb: u64 = line
        .split_whitespace()
        .nth(1)
        .and_then(|v| v.parse().ok())
        .expect("a number of kB");
    kb * 1024
}

/// The largest frame, as `render --help` states it ("from 80x24 to WxH").
fn largest_frame() -> (u16, u16) {
    let (code, help, err) = crate::common::riplab(&["render", "--help"]);
    assert_eq!(code, 0, "{err}");
    let at = help.find("80x24 to ").expect("render --help states the sizes") + "80x24 to ".len();
    let size: String = help[at..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == 'x')
        .collect();
    let (w, h) = size.split_once('x').expect("WxH");
    (w.parse().unwrap(), h.parse().unwrap())
}

/// The lab in a 30000×20000 terminal draws its largest frame (1000×500) within twice the
/// address space a run in a terminal of exactly that size needs, measured here: its buffers
/// follow the frame, not the terminal (they took 28.8 GB there, an abort).
#[test]
fn a_huge_terminal_needs_no_more_memory_than_the_largest_frame() {
    let largest = largest_frame();
    let mut normal = Pty::spawn(largest, riplab(&[]));
    normal.wait_for_frame();
    normal.wait_for_text(largest, "converged");
    let peak = vm_peak(normal.pid());
    normal.signal("TERM");
    let ended = normal.finish();
    assert_eq!(ended.signal(), Some(15), "{}", ended.status);

    let limit = 2 * peak;
    let mut command = Command::new("prlimit");
    command.arg(format!("--as={limit}"));
    command.arg(env!("CARGO_BIN_EXE_riplab"));
    command
        .env("TERM", "xterm-256color")
        .env("XDG_CACHE_HOME", crate::common::test_cache());
    let mut huge = Pty::spawn((30_000, 20_000), command);
    huge.wait_for_frame();
    huge.signal("TERM");
    let ended = huge.finish();
    let tail = String::from_utf8_lossy(&ended.output[ended.output.len().saturating_sub(500)..]).into_owned();
    assert_eq!(
        ended.signal(),
        Some(15),
        "under {limit} bytes (twice the {peak} of a {}x{} run): {} {tail:?}",
        largest.0,
        largest.1,
        ended.status
    );
    assert!(!tail.contains("memory allocation"), "{tail:?}");
}

/// `TERM=dumb` (a terminal that cannot move its cursor): the lab, the tour and a recording are
/// refused with exit 2 before any escape sequence is written (and no recording is left),
/// the message naming TERM=dumb and `riplab render`.
#[test]
fn term_dumb_is_refused_before_any_escape_sequence() {
    let dir = fresh_dir("dumb");
    let cast = dir.join("dumb.cast");
    let cast = cast.to_str().unwrap();
    for args in [&[][..], &["tour"], &["--record", cast]] {
        let mut command = riplab(args);
        command.env("TERM", "dumb");
        let mut pty = Pty::spawn(SIZE, command);
        let entered = pty.holds_before_the_end("the alternate screen", |out| contains(out, ENTERED));
        let out = pty.output();
        assert!(
            !entered && !contains(&out, b"\x1b["),
            "{args:?}: {:?}",
            String::from_utf8_lossy(&out)
        );
        let ended = pty.finish();
        let text = String::from_utf8_lossy(&ended.output);
        assert_eq!(ended.status.code(), Some(2), "{args:?}: {text}");
        assert!(
            text.contains("TERM=dumb") && text.contains("riplab render"),
            "{args:?}: {text}"
        );
        assert!(!Path::new(cast).exists(), "the recording is left");
    }
}

/// The mouse in the lab: a click on the `infsup` tab (an SGR mouse report written to the
/// terminal, as a terminal sends it) shows the inf-sup scene; the lab asks for mouse reports
/// and stops them when it ends. With `--no-mouse` it never asks.
#[test]
fn a_click_on_a_tab_changes_the_scene() {
    let mut pty = Pty::spawn(SIZE, riplab(&[]));
    pty.wait_for_frame();
    assert!(
        contains(&pty.output(), b"\x1b[?1006h"),
        "SGR mouse reports asked for"
    );
    // The tabs are right-aligned on the first row: ` explore  infsup  mesh  convergence
    // stress `; find `infsup` on the screen drawn so far.
    let shown = screen(SIZE, &pty.output());
    let header = shown.rows(0, SIZE.0).next().unwrap();
    let at = header.find("infsup").expect("the tabs");
    let column = header[..at].chars().count() + 3;
    // Press and release, 1-based column and row.
    let report = format!("\x1b[<0;{};1M\x1b[<0;{};1m", column + 1, column + 1);
    pty.send(report.as_bytes());
    pty.wait_for_text(SIZE, "β_h/√h against h");
    pty.send(b"q");
    let ended = pty.finish();
    assert!(ended.status.success(), "{}", ended.status);
    assert!(ended.cooked);
    assert_restored(&screen(SIZE, &ended.output), "after the click");

    let mut pty = Pty::spawn(SIZE, riplab(&["--no-mouse"]));
    pty.wait_for_frame();
    pty.send(b"q");
    let ended = pty.finish();
    assert!(ended.status.success(), "{}", ended.status);
    assert!(
        !contains(&ended.output, b"\x1b[?1000h"),
        "--no-mouse asked for mouse reports"
    );
}
