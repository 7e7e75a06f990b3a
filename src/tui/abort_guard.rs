//! The terminal restored when the process aborts (issue 37). A panic is ratatui's hook's
//! business; an abort (a failed allocation: `memory allocation of N bytes failed`, or any
//! `std::process::abort`) runs no hook and no destructor, so the lab would leave the terminal
//! in raw mode, in the alternate screen, with the cursor hidden. While a [`Guard`] lives, a
//! SIGABRT handler writes the sequences that leave the alternate screen and show the cursor,
//! puts back the terminal's settings saved before raw mode, and lets the abort go on (only
//! async-signal-safe calls: `write`, `tcsetattr`, `signal`, `raise`).
//!
//! The real fix is a refusal before the allocation (the memory guard, [`crate::fem::memory`]);
//! this is the last line for whatever the estimate did not foresee.

/// Restores the terminal on SIGABRT while it lives (Linux; elsewhere it does nothing).
pub(super) struct Guard {
    #[cfg(target_os = "linux")]
    previous: libc::sighandler_t,
}

#[cfg(target_os = "linux")]
mod imp {
    use std::sync::OnceLock;

    /// Standard input's terminal settings before raw mode (the lab's first start).
    pub(super) static SAVED: OnceLock<libc::termios> = OnceLock::new();

    /// End a synchronized update, leave the alternate screen, show the cursor, new line.
    const RESTORE: &[u8] = b"\x1b[?2026l\x1b[?1049l\x1b[?25h\r\n";

    pub(super) extern "C" fn on_abort(_: libc::c_int) {
        // SAFETY: write, tcsetattr, signal and raise are async-signal-safe; the buffers are
        // statics, the termios was written once before the handler was installed.
        unsafe {
            libc::write(libc::STDOUT_FILENO, RESTORE.as_ptr().cast(), RESTORE.len());
            if let Some(t) = SAVED.get() {
                libc::tcsetattr(libc::STDIN_FILENO, libc::TCSANOW, t);
            }
            libc::signal(libc::SIGABRT, libc::SIG_DFL);
            libc::raise(libc::SIGABRT);
        }
    }
}

impl Guard {
    /// Save the terminal's settings (call before raw mode) and install the handler.
    pub(super) fn install() -> Self {
        #[cfg(target_os = "linux")]
        {
            // SAFETY: tcgetattr writes a termios it is given; signal installs a handler whose
            // body is async-signal-safe (above).
            unsafe {
                let mut t: libc::termios = std::mem::zeroed();
                if libc::tcgetattr(libc::STDIN_FILENO, &mut t) == 0 {
                    let _ = imp::SAVED.set(t);
                }
                let handler = imp::on_abort as extern "C" fn(libc::c_int);
                let previous = libc::signal(libc::SIGABRT, handler as libc::sighandler_t);
                Guard { previous }
            }
        }
        #[cfg(not(target_os = "linux"))]
        Guard {}
    }
}

impl Drop for Guard {
    fn drop(&mut self) {
        // SAFETY: puts back the handler that was there before.
        #[cfg(target_os = "linux")]
        unsafe {
            libc::signal(libc::SIGABRT, self.previous);
        }
    }
}
