//! riplab run in a pseudo-terminal as a person runs it: what it writes is gathered by a
//! thread, its end by another, keys and mouse reports are written to it, and every wait is
//! woken by what it shows or by its end, with a generous deadline — never a sleep or a poll.

use std::io::{Read, Write};
use std::os::fd::OwnedFd;
use std::os::unix::process::ExitStatusExt as _;
use std::process::{Command, ExitStatus, Stdio};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long a wait may take before the test fails (a loaded host included).
pub const DEADLINE: Duration = Duration::from_secs(240);

/// The alternate screen entered (`?1049h`).
pub const ENTERED: &[u8] = b"\x1b[?1049h";

/// Whether `hay` holds `needle`.
pub fn contains(hay: &[u8], needle: &[u8]) -> bool {
    find(hay, needle).is_some()
}

/// Where `needle` first is in `hay`.
pub fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

/// The riplab binary with `args`, the tests' cache and a terminal type that draws.
pub fn riplab(args: &[&str]) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_riplab"));
    command
        .args(args)
        .env("TERM", "xterm-256color")
        .env_remove("NO_COLOR")
        .env("XDG_CACHE_HOME", crate::common::test_cache());
    command
}

/// What the reader and the waiter threads gather: everything written, and the status once the
/// child has ended; each change is announced on the condition variable.
#[derive(Default)]
struct Seen {
    output: Vec<u8>,
    status: Option<ExitStatus>,
}

type Shared = Arc<(Mutex<Seen>, Condvar)>;

/// A child on a pseudo-terminal.
pub struct Pty {
    pid: u32,
    keys: std::fs::File,
    /// The terminal's side, kept open to read its settings after the child ends.
    user: Option<OwnedFd>,
    seen: Shared,
    reader: Option<JoinHandle<()>>,
    waiter: Option<JoinHandle<()>>,
}

/// How a run ended: its status, everything it wrote, and whether the terminal was left in
/// canonical mode with echo (not raw).
pub struct Ended {
    pub status: ExitStatus,
    pub output: Vec<u8>,
    pub cooked: bool,
}

impl Ended {
    /// The signal that ended the process, if one did.
    pub fn signal(&self) -> Option<i32> {
        self.status.signal()
    }
}

/// Run `change` on what is seen and announce it.
fn announce(seen: &Shared, change: impl FnOnce(&mut Seen)) {
    let (lock, changed) = &**seen;
    change(&mut lock.lock().unwrap());
    changed.notify_all();
}

impl Pty {
    /// Run `command` with its standard streams on the terminal's side of a new pseudo-terminal
    /// of `size` (columns, rows).
    pub fn spawn(size: (u16, u16), mut command: Command) -> Pty {
        use rustix::pty::{OpenptFlags, grantpt, openpt, ptsname, unlockpt};
        let controller = openpt(OpenptFlags::RDWR | OpenptFlags::NOCTTY | OpenptFlags::CLOEXEC).unwrap();
        grantpt(&controller).unwrap();
        unlockpt(&controller).unwrap();
        let name = ptsname(&controller, Vec::new()).unwrap();
        let user: OwnedFd = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .open(name.to_str().unwrap())
            .unwrap()
            .into();
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
        command
            .stdin(Stdio::from(user.try_clone().unwrap()))
            .stdout(Stdio::from(user.try_clone().unwrap()))
            .stderr(Stdio::from(user.try_clone().unwrap()));
        let mut child = command.spawn().unwrap();
        // The command holds the terminal's side until dropped.
        drop(command);
        let pid = child.id();
        let seen = Shared::default();
        let reader = {
            let seen = seen.clone();
            let mut from = std::fs::File::from(controller.try_clone().unwrap());
            std::thread::spawn(move || {
                let mut buf = vec![0u8; 1 << 16];
                while let Ok(n) = from.read(&mut buf) {
                    if n == 0 {
                        break;
                    }
                    announce(&seen, |s| s.output.extend_from_slice(&buf[..n]));
                }
            })
        };
        let waiter = {
            let seen = seen.clone();
            std::thread::spawn(move || {
                let status = child.wait().unwrap();
                announce(&seen, |s| s.status = Some(status));
            })
        };
        Pty {
            pid,
            keys: std::fs::File::from(controller),
            user: Some(user),
            seen,
            reader: Some(reader),
            waiter: Some(waiter),
        }
    }

    /// The child's process id.
    pub fn pid(&self) -> u32 {
        self.pid
    }

    /// Everything written so far.
    pub fn output(&self) -> Vec<u8> {
        self.seen.0.lock().unwrap().output.clone()
    }

    /// Wait, woken by each write and by the end, until `stop` holds of what is seen; the test
    /// fails if the deadline passes first.
    fn wait_until<T>(&self, what: &str, mut stop: impl FnMut(&Seen) -> Option<T>) -> T {
        let deadline = Instant::now() + DEADLINE;
        let (lock, changed) = &*self.seen;
        let mut seen = lock.lock().unwrap();
        loop {
            if let Some(answer) = stop(&seen) {
                return answer;
            }
            let left = deadline.saturating_duration_since(Instant::now());
            assert!(!left.is_zero(), "no {what} within {DEADLINE:?}");
            seen = changed.wait_timeout(seen, left).unwrap().0;
        }
    }

    /// Wait until `done` holds of the output (true) or the child ends first (false); the test
    /// fails if the deadline passes.
    pub fn holds_before_the_end(&mut self, what: &str, done: impl Fn(&[u8]) -> bool) -> bool {
        self.wait_until(what, |seen| {
            if done(&seen.output) {
                Some(true)
            } else {
                seen.status.map(|_| false)
            }
        })
    }

    /// Wait until `done` holds of the output; the test fails if the child ends first or the
    /// deadline passes.
    pub fn wait_for(&mut self, what: &str, done: impl Fn(&[u8]) -> bool) {
        if !self.holds_before_the_end(what, done) {
            let status = self.seen.0.lock().unwrap().status;
            let out = self.output();
            let tail = &out[out.len().saturating_sub(2000)..];
            panic!(
                "ended ({status:?}) before {what}: {:?}",
                String::from_utf8_lossy(tail)
            );
        }
    }

    /// Wait until the screen of a terminal of `size` shows `text` (the output fed to a
    /// terminal emulator as it comes); the test fails if the child ends first or the
    /// deadline passes.
    pub fn wait_for_text(&mut self, size: (u16, u16), text: &str) {
        let n = |v: u16| std::num::NonZeroU16::new(v).unwrap();
        let parser = Mutex::new((vt100::Parser::new(n(size.1), n(size.0), 0), 0usize));
        self.wait_for(&format!("`{text}` on the screen"), |out| {
            let mut guard = parser.lock().unwrap();
            let (parser, seen) = &mut *guard;
            parser.process(&out[*seen..]);
            *seen = out.len();
            parser.screen().contents().contains(text)
        });
    }

    /// Wait until the alternate screen is entered and a frame with the lab's title is drawn
    /// in it.
    pub fn wait_for_frame(&mut self) {
        self.wait_for("a frame on the alternate screen", |out| {
            find(out, ENTERED).is_some_and(|at| contains(&out[at..], b" riplab "))
        });
    }

    /// Write `bytes` as if typed.
    pub fn send(&mut self, bytes: &[u8]) {
        self.keys.write_all(bytes).unwrap();
    }

    /// Send the signal `name` (`TERM`, `HUP`, `ABRT`…) to the child.
    pub fn signal(&self, name: &str) {
        let status = Command::new("kill")
            .arg(format!("-{name}"))
            .arg(self.pid().to_string())
            .status()
            .unwrap();
        assert!(status.success(), "kill -{name}");
    }

    /// Wait for the end (within the deadline), then everything written and the terminal's
    /// mode.
    pub fn finish(mut self) -> Ended {
        let status = self.wait_until("end", |seen| seen.status);
        use rustix::termios::LocalModes;
        let user = self.user.take().expect("the terminal's side");
        let modes = rustix::termios::tcgetattr(&user).unwrap().local_modes;
        let cooked = modes.contains(LocalModes::ICANON | LocalModes::ECHO);
        // The terminal's side closed everywhere, the reader reads what is left, then ends.
        drop(user);
        if let Some(reader) = self.reader.take() {
            reader.join().unwrap();
        }
        Ended {
            status,
            output: self.output(),
            cooked,
        }
    }
}

impl Drop for Pty {
    /// A child still running is killed, and the waiter reaps it.
    fn drop(&mut self) {
        if self.seen.0.lock().map(|s| s.status.is_none()).unwrap_or(false) {
            let _ = Command::new("kill")
                .arg("-KILL")
                .arg(self.pid.to_string())
                .status();
        }
        if let Some(waiter) = self.waiter.take() {
            let _ = waiter.join();
        }
    }
}

/// The screen after `output`, as a terminal of `size` shows it.
pub fn screen(size: (u16, u16), output: &[u8]) -> vt100::Screen {
    let n = |v: u16| std::num::NonZeroU16::new(v).unwrap();
    let mut parser = vt100::Parser::new(n(size.1), n(size.0), 0);
    parser.process(output);
    parser.screen().clone()
}

/// The terminal as it was before riplab: the main screen, the cursor shown, no mouse reports.
pub fn assert_restored(screen: &vt100::Screen, what: &str) {
    assert!(
        !screen.alternate_screen(),
        "{what}: still on the alternate screen"
    );
    assert!(!screen.hide_cursor(), "{what}: the cursor is hidden");
    assert_eq!(
        screen.mouse_protocol_mode(),
        vt100::MouseProtocolMode::None,
        "{what}: mouse reports still on"
    );
}
