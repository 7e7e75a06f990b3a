//! riplab run in a pseudo-terminal as a person runs it: what it writes is gathered by a
//! thread, keys and mouse reports are written to it, and every wait is for what it shows or
//! for its end, with a generous deadline — never for a time.

use std::io::{Read, Write};
use std::os::fd::OwnedFd;
use std::os::unix::process::ExitStatusExt as _;
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::{Arc, Mutex};
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

/// A child on a pseudo-terminal.
pub struct Pty {
    child: Child,
    keys: std::fs::File,
    /// The terminal's side, kept open to read its settings after the child ends.
    user: Option<OwnedFd>,
    output: Arc<Mutex<Vec<u8>>>,
    reader: Option<JoinHandle<()>>,
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
        let child = command.spawn().unwrap();
        // The command holds the terminal's side until dropped.
        drop(command);
        let output = Arc::new(Mutex::new(Vec::new()));
        let reader = {
            let output = output.clone();
            let mut from = std::fs::File::from(controller.try_clone().unwrap());
            std::thread::spawn(move || {
                let mut buf = vec![0u8; 1 << 16];
                while let Ok(n) = from.read(&mut buf) {
                    if n == 0 {
                        break;
                    }
                    output.lock().unwrap().extend_from_slice(&buf[..n]);
                }
            })
        };
        Pty {
            child,
            keys: std::fs::File::from(controller),
            user: Some(user),
            output,
            reader: Some(reader),
        }
    }

    /// The child's process id.
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// Everything written so far.
    pub fn output(&self) -> Vec<u8> {
        self.output.lock().unwrap().clone()
    }

    /// Wait until `done` holds of the output (true) or the child ends first (false); the test
    /// fails if the deadline passes.
    pub fn holds_before_the_end(&mut self, what: &str, done: impl Fn(&[u8]) -> bool) -> bool {
        let deadline = Instant::now() + DEADLINE;
        loop {
            if done(&self.output.lock().unwrap()) {
                return true;
            }
            if self.child.try_wait().unwrap().is_some() {
                return false;
            }
            assert!(Instant::now() < deadline, "no {what} within {DEADLINE:?}");
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Wait until `done` holds of the output; the test fails if the child ends first or the
    /// deadline passes.
    pub fn wait_for(&mut self, what: &str, done: impl Fn(&[u8]) -> bool) {
        if !self.holds_before_the_end(what, done) {
            let status = self.child.try_wait().unwrap();
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
        let deadline = Instant::now() + DEADLINE;
        let status = loop {
            if let Some(status) = self.child.try_wait().unwrap() {
                break status;
            }
            assert!(Instant::now() < deadline, "did not end within {DEADLINE:?}");
            std::thread::sleep(Duration::from_millis(20));
        };
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
    fn drop(&mut self) {
        if self.child.try_wait().ok().flatten().is_none() {
            let _ = self.child.kill();
            let _ = self.child.wait();
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
