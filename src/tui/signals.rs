//! The terminal given back when a signal ends the lab or the tour (docs/design.md §8: the
//! terminal is always restored).
//!
//! SIGTERM, SIGHUP and SIGINT are turned into an input of the event loop: the handler writes
//! the signal's number into a pipe, a thread reading it calls back the loop's channel, and
//! the loop ends as on `q` — the terminal restored through its writer (so that a recording
//! ends as the terminal does) and the recording's file finished — after which
//! [`Guard::finish`] ends the process as the signal asked (the shell sees "terminated", not
//! a success). A second such signal (a loop that does not answer) restores the terminal
//! at once and ends the process.
//!
//! An abort (a failed allocation: `memory allocation of N bytes failed`, or any
//! `std::process::abort`) runs no hook and no destructor: its SIGABRT handler writes the
//! sequences that end a synchronized update, leave the alternate screen, stop the mouse
//! reports and show the cursor, puts back the terminal's settings saved before raw mode, and
//! lets the abort go on. Handlers make only async-signal-safe calls (`write`, `tcsetattr`,
//! `sigaction`, `raise`) and touch only atomics and statics written before they are
//! installed. The real fix of an abort is a refusal before the allocation (the memory guard,
//! [`crate::fem::memory`]); this is the last line for whatever the estimate did not foresee.

/// Restores the terminal on the signals above while it lives (Linux; elsewhere it does
/// nothing and [`Guard::finish`] returns).
pub(super) struct Guard {
    #[cfg(target_os = "linux")]
    inner: imp::Installed,
}

#[cfg(target_os = "linux")]
mod imp {
    use std::sync::OnceLock;
    use std::sync::atomic::{AtomicI32, Ordering};

    /// Standard input's terminal settings before raw mode (the lab's first start).
    static SAVED: OnceLock<libc::termios> = OnceLock::new();
    /// The write end of the pipe the handler of [`ENDING`] writes to (-1: none).
    static PIPE: AtomicI32 = AtomicI32::new(-1);
    /// The first ending signal received (0: none).
    static RECEIVED: AtomicI32 = AtomicI32::new(0);

    /// The signals that end the loop as `q` does.
    pub(super) const ENDING: [libc::c_int; 3] = [libc::SIGTERM, libc::SIGHUP, libc::SIGINT];

    /// End a synchronized update, leave the alternate screen, stop every mouse report the
    /// lab may have asked for, show the cursor, new line.
    const RESTORE: &[u8] =
        b"\x1b[?2026l\x1b[?1049l\x1b[?1006l\x1b[?1015l\x1b[?1003l\x1b[?1002l\x1b[?1000l\x1b[?25h\r\n";

    /// The terminal as it was before the lab, written from a handler.
    fn restore_now() {
        // SAFETY: write and tcsetattr are async-signal-safe; RESTORE is a static and the
        // termios was written once before any handler was installed.
        unsafe {
            libc::write(libc::STDOUT_FILENO, RESTORE.as_ptr().cast(), RESTORE.len());
            if let Some(t) = SAVED.get() {
                libc::tcsetattr(libc::STDIN_FILENO, libc::TCSANOW, t);
            }
        }
    }

    /// The default action of `signal`, taken now.
    fn die_of(signal: libc::c_int) {
        // SAFETY: sigaction and raise are async-signal-safe; the action is zeroed (no flags,
        // an empty mask) with the default handler.
        unsafe {
            let mut action: libc::sigaction = std::mem::zeroed();
            action.sa_sigaction = libc::SIG_DFL;
            libc::sigaction(signal, &action, std::ptr::null_mut());
            libc::raise(signal);
        }
    }

    extern "C" fn on_abort(_: libc::c_int) {
        restore_now();
        die_of(libc::SIGABRT);
    }

    extern "C" fn on_ending(signal: libc::c_int) {
        if RECEIVED.swap(signal, Ordering::SeqCst) != 0 {
            // The second: the loop did not end in time.
            restore_now();
            die_of(signal);
            return;
        }
        let byte = signal as u8;
        // SAFETY: write is async-signal-safe; a closed or invalid descriptor only fails.
        unsafe {
            libc::write(PIPE.load(Ordering::SeqCst), (&raw const byte).cast(), 1);
        }
    }

    /// The handlers installed: the ones they replaced, and the pipe's write end (its read
    /// end belongs to the thread that reads it).
    pub(super) struct Installed {
        previous: Vec<(libc::c_int, libc::sigaction)>,
        write: libc::c_int,
    }

    /// Install `handler` for `signal` (restarting interrupted calls), returning the action
    /// it replaced.
    fn install(signal: libc::c_int, handler: extern "C" fn(libc::c_int)) -> libc::sigaction {
        // SAFETY: both actions are valid zeroed structs; the handler is async-signal-safe.
        unsafe {
            let mut action: libc::sigaction = std::mem::zeroed();
            action.sa_sigaction = handler as libc::sighandler_t;
            action.sa_flags = libc::SA_RESTART;
            libc::sigemptyset(&mut action.sa_mask);
            let mut previous: libc::sigaction = std::mem::zeroed();
            libc::sigaction(signal, &action, &mut previous);
            previous
        }
    }

    impl Installed {
        /// Save the terminal's settings and install the handlers; `on_signal` is called from
        /// a thread of its own with the first ending signal.
        pub(super) fn new(on_signal: Box<dyn FnOnce(i32) + Send>) -> Installed {
            let mut fds = [-1; 2];
            // SAFETY: tcgetattr writes a termios it is given; pipe2 writes two descriptors.
            unsafe {
                let mut t: libc::termios = std::mem::zeroed();
                if libc::tcgetattr(libc::STDIN_FILENO, &mut t) == 0 {
                    let _ = SAVED.set(t);
                }
                if libc::pipe2(fds.as_mut_ptr(), libc::O_CLOEXEC) != 0 {
                    fds = [-1; 2];
                }
            }
            let [read, write] = fds;
            RECEIVED.store(0, Ordering::SeqCst);
            PIPE.store(write, Ordering::SeqCst);
            if read >= 0 {
                let spawned = std::thread::Builder::new()
                    .name("riplab-signals".into())
                    .spawn(move || {
                        let mut byte = 0u8;
                        // SAFETY: reads one byte into a local; the descriptor stays open
                        // until this thread has seen its end (Installed::drop closes only the
                        // write end, then this end after the read returns 0).
                        let n = unsafe { libc::read(read, (&raw mut byte).cast(), 1) };
                        if n == 1 {
                            on_signal(i32::from(byte));
                        }
                        // SAFETY: this thread owns the read end.
                        unsafe { libc::close(read) };
                    });
                if spawned.is_err() {
                    // SAFETY: nothing reads it.
                    unsafe { libc::close(read) };
                }
            }
            let mut previous = vec![(libc::SIGABRT, install(libc::SIGABRT, on_abort))];
            previous.extend(ENDING.iter().map(|&s| (s, install(s, on_ending))));
            Installed { previous, write }
        }

        /// The first ending signal received, if any.
        pub(super) fn received(&self) -> Option<i32> {
            Some(RECEIVED.load(Ordering::SeqCst)).filter(|&s| s != 0)
        }
    }

    impl Drop for Installed {
        fn drop(&mut self) {
            // SAFETY: puts back the actions that were there before, then closes the pipe's
            // write end (its reader then ends).
            unsafe {
                for (signal, action) in &self.previous {
                    libc::sigaction(*signal, action, std::ptr::null_mut());
                }
                PIPE.store(-1, Ordering::SeqCst);
                if self.write >= 0 {
                    libc::close(self.write);
                }
            }
        }
    }

    /// End the process with `signal`'s default action.
    pub(super) fn end_with(signal: i32) {
        die_of(signal);
    }
}

impl Guard {
    /// Save the terminal's settings (call before raw mode) and install the handlers;
    /// `on_signal` is told of the first SIGTERM, SIGHUP or SIGINT (from a thread of its own).
    pub(super) fn install(on_signal: impl FnOnce(i32) + Send + 'static) -> Self {
        #[cfg(target_os = "linux")]
        {
            Guard {
                inner: imp::Installed::new(Box::new(on_signal)),
            }
        }
        #[cfg(not(target_os = "linux"))]
        {
            let _ = on_signal;
            Guard {}
        }
    }

    /// Put the previous handlers back; then, if a signal asked the loop to end, end the
    /// process as that signal does by default (call once the terminal is restored and the
    /// recording finished).
    pub(super) fn finish(self) {
        #[cfg(target_os = "linux")]
        {
            let received = self.inner.received();
            drop(self);
            if let Some(signal) = received {
                imp::end_with(signal);
            }
        }
    }
}
