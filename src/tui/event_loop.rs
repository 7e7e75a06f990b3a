//! The one event loop of the lab and the tour ([`run_program`], driving a [`Program`]): the
//! terminal (raw mode, alternate screen, mouse reports unless `--no-mouse`; restored on exit,
//! on panic by ratatui's hook, on a signal or an abort by [`super::signals`]), an input thread
//! and the workers feeding one channel, and a redraw only when an update says the screen
//! changed, inside synchronized-output brackets. The frame is at most [`super::MAX_SIZE`]
//! whatever the terminal's size ([`super::drawn_area`]).

use std::io;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use crossterm::event::{DisableMouseCapture, EnableMouseCapture, Event};
use crossterm::terminal::{BeginSynchronizedUpdate, EndSynchronizedUpdate};
use ratatui::backend::CrosstermBackend;
use ratatui::layout::Size;
use ratatui::{Frame, Terminal, TerminalOptions, Viewport};

use super::app::{Notice, Response};
use super::record::cast::Event as CastEvent;
use super::record::{CastFile, Chapter, Recorder, Screen, Tap};
use super::{RunError, drawn_area};

/// The terminal of the lab and the tour: crossterm on standard output, through the writer
/// that records it when asked ([`Screen`]).
pub(super) type Term = Terminal<CrosstermBackend<Screen>>;

/// A recording to make: the file, created, and the title its header gives.
pub(super) type Recording = Option<(CastFile, String)>;

/// Everything the loop waits for.
pub(super) enum Input {
    Terminal(Event),
    /// A reply of the worker of the given epoch (a program that replaces its worker drops
    /// the replies of the old one; the lab's worker is epoch 0).
    Worker(u64, Response),
    /// A solve of the two-body scene, for the settings of the given generation
    /// ([`super::bodies`], [`super::bodies_solve`]).
    Bodies(
        u64,
        Box<Result<super::bodies_solve::Solved, crate::contact::interface::solve::BodiesError>>,
    ),
    /// Reading the terminal failed: the loop ends with this error.
    Broken(io::Error),
    /// The recording failed (the loop shows why on the status line).
    RecordingFailed,
    /// SIGTERM, SIGHUP or SIGINT: the loop ends as on `q` ([`super::signals`]).
    Signal,
}

/// What an update asks of the loop.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Flow {
    /// The screen changed.
    pub redraw: bool,
    /// Ctrl-Z: give the terminal back until resumed.
    pub suspend: bool,
}

impl std::ops::BitOrAssign for Flow {
    fn bitor_assign(&mut self, other: Flow) {
        self.redraw |= other.redraw;
        self.suspend |= other.suspend;
    }
}

/// What the one event loop ([`run_program`]) drives: the lab ([`Lab`]) or the tour.
pub(super) trait Program {
    /// The first update, before the first frame.
    fn start(&mut self) -> Flow;
    /// One input from the terminal or a worker (never [`Input::Broken`],
    /// [`Input::RecordingFailed`] nor [`Input::Signal`]).
    fn input(&mut self, input: Input) -> Flow;
    /// The wait of [`Program::wait`] is over with no input.
    fn tick(&mut self) -> Flow;
    /// After a batch of inputs (the tour's auto-advance).
    fn after_inputs(&mut self) -> Flow {
        Flow::default()
    }
    /// How long to wait for input before [`Program::tick`]; None: for ever.
    fn wait(&self) -> Option<Duration>;
    fn should_quit(&self) -> bool;
    fn draw(&self, frame: &mut Frame);
    /// Where a recording is: the tour's step and the scene shown; None while the tour's step
    /// is still computing (its marker waits for the finished frame).
    fn chapter(&self) -> Option<Chapter>;
    /// Show `notice` on the status line (a recording that failed).
    fn notice(&mut self, notice: Notice) -> Flow;
    /// The frame just drawn is on the screen, and its marker, if any, in the recording.
    fn shown(&mut self) {}
}

/// Forward the terminal's events to `tx` from a thread of their own; a failed read is sent
/// as [`Input::Broken`] and ends the thread (so does a closed channel).
fn forward_terminal(tx: mpsc::Sender<Input>) -> io::Result<()> {
    std::thread::Builder::new()
        .name("riplab-input".into())
        .spawn(move || {
            loop {
                let (input, end) = match crossterm::event::read() {
                    Ok(e) => (Input::Terminal(e), false),
                    Err(e) => (Input::Broken(e), true),
                };
                if tx.send(input).is_err() || end {
                    return;
                }
            }
        })?;
    Ok(())
}

/// How often the screen is redrawn while a long job shows its time left.
pub(super) const TICK: Duration = Duration::from_millis(250);

/// The one event loop of the lab and the tour: the terminal (raw mode, alternate screen, the
/// mouse's reports if `mouse`), restored on every path — a panic included, by ratatui's hook;
/// SIGTERM, SIGHUP and SIGINT by ending the loop as `q` does, then the process as the signal
/// asks; an abort by [`super::signals`]' handler —, an input thread and the program's workers
/// feeding one channel, and a redraw only when an update says the screen changed, inside
/// synchronized-output brackets. `start` makes the program from the channel's sender (for its
/// workers) and the terminal's size. With a recording, everything the terminal is sent goes
/// to it as well (the terminal's restoring included), with the resizes and a marker at each
/// new chapter ([`Chapter::marker`]); a recording that failed is an error at the end. The
/// frame, its buffers and the recording's size are the terminal's, at most
/// [`super::MAX_SIZE`] ([`drawn_area`]).
pub(super) fn run_program<P: Program>(
    recording: Recording,
    mouse: bool,
    start: impl FnOnce(mpsc::Sender<Input>, Size) -> io::Result<P>,
) -> Result<(), RunError> {
    let (tx, rx) = mpsc::channel::<Input>();
    let signals = {
        let tx = tx.clone();
        super::signals::Guard::install(move |_| {
            let _ = tx.send(Input::Signal);
        })
    };
    let drawn = drawn_area(crossterm::terminal::size()?);
    let mut recorder = recording.map(|(file, title)| {
        let tx = tx.clone();
        let wake = move || {
            let _ = tx.send(Input::RecordingFailed);
        };
        Recorder::start(file, (drawn.width, drawn.height), &title, wake)
    });
    let mut terminal = take_terminal(recorder.as_ref().map(Recorder::tap), mouse)?;
    let result = event_loop(&mut terminal, recorder.as_mut(), mouse, (tx, rx), start);
    // Restored through the terminal's writer, so that a recording ends as the terminal does.
    let restored = give_back(&mut terminal);
    if restored.is_err() {
        ratatui::restore();
        let _ = crossterm::execute!(io::stdout(), DisableMouseCapture);
    }
    drop(terminal);
    let recorded = match recorder {
        Some(recorder) => recorder.finish().map_err(RunError::Recording),
        None => Ok(()),
    };
    // After a signal the process ends here, the terminal and the recording finished.
    signals.finish();
    result.map_err(RunError::Terminal).and(recorded)
}

/// Raw mode, the alternate screen and (with `mouse`) the mouse's reports, on a terminal
/// writing through [`Screen`] whose buffers are the size of [`drawn_area`]; a panic restores
/// the terminal first (as `ratatui::init` does).
fn take_terminal(tap: Option<Tap>, mouse: bool) -> io::Result<Term> {
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        ratatui::restore();
        let _ = crossterm::execute!(io::stdout(), DisableMouseCapture);
        hook(info);
    }));
    crossterm::terminal::enable_raw_mode()?;
    let mut screen = Screen::new(tap);
    crossterm::execute!(screen, crossterm::terminal::EnterAlternateScreen)?;
    if mouse {
        crossterm::execute!(screen, EnableMouseCapture)?;
    }
    // A fixed viewport: ratatui sizes its two buffers to it, where a fullscreen one follows
    // the terminal to any size; the loop resizes it ([`resize_to`]).
    let viewport = Viewport::Fixed(drawn_area(crossterm::terminal::size()?));
    Terminal::with_options(CrosstermBackend::new(screen), TerminalOptions { viewport })
}

/// The terminal is now `(columns, rows)`: the frame follows it, within [`super::MAX_SIZE`].
fn resize_to(terminal: &mut Term, size: (u16, u16)) -> io::Result<()> {
    let area = drawn_area(size);
    if area != terminal.get_frame().area() {
        terminal.resize(area)?;
    }
    Ok(())
}

/// The mouse's reports stopped, the cursor shown, raw mode off, the alternate screen left.
fn give_back(terminal: &mut Term) -> io::Result<()> {
    crossterm::execute!(terminal.backend_mut(), DisableMouseCapture)?;
    terminal.show_cursor()?;
    crossterm::terminal::disable_raw_mode()?;
    crossterm::execute!(terminal.backend_mut(), crossterm::terminal::LeaveAlternateScreen)
}

fn event_loop<P: Program>(
    terminal: &mut Term,
    mut recorder: Option<&mut Recorder>,
    mouse: bool,
    (tx, rx): (mpsc::Sender<Input>, mpsc::Receiver<Input>),
    start: impl FnOnce(mpsc::Sender<Input>, Size) -> io::Result<P>,
) -> io::Result<()> {
    forward_terminal(tx.clone())?;
    let mut program = start(tx, terminal.size()?)?;
    let mut flow = program.start();
    let mut chapter: Option<Chapter> = None;
    while !program.should_quit() {
        if let Some(recorder) = recorder.as_deref_mut()
            && let Some(failure) = recorder.new_failure()
        {
            flow |= program.notice(Notice::failure(failure.to_string()));
        }
        if flow.suspend {
            suspend(terminal, mouse)?;
            flow.redraw = true;
        }
        // Where the recording is, as of the frame about to be drawn (a worker may finish
        // more meanwhile, which the next frame shows): marked only with a frame drawn.
        let drawn = recorder
            .as_ref()
            .filter(|_| flow.redraw)
            .and_then(|_| program.chapter());
        if flow.redraw {
            draw_with(terminal, |frame| program.draw(frame))?;
        }
        // The marker after the frame it marks: replayed to a marker, a recording shows it.
        if let Some(recorder) = recorder.as_deref_mut()
            && let Some(now) = drawn
        {
            if let Some(marker) = now.marker(chapter.as_ref()) {
                recorder.record(CastEvent::Marker(marker));
            }
            chapter = Some(now);
        }
        if flow.redraw {
            program.shown();
        }
        // Block for one input (or until the program's wait is over), then take whatever else
        // is queued before drawing again.
        let first = match program.wait() {
            Some(timeout) => match rx.recv_timeout(timeout) {
                Ok(input) => Some(input),
                Err(RecvTimeoutError::Timeout) => None,
                Err(RecvTimeoutError::Disconnected) => break,
            },
            None => match rx.recv() {
                Ok(input) => Some(input),
                Err(_) => break,
            },
        };
        flow = Flow::default();
        if first.is_none() {
            flow |= program.tick();
        }
        for input in first.into_iter().chain(std::iter::from_fn(|| rx.try_recv().ok())) {
            let input = match input {
                Input::Broken(e) => return Err(e),
                Input::Signal => return Ok(()),
                // Shown by the check above the next draw.
                Input::RecordingFailed => continue,
                input => input,
            };
            if let Input::Terminal(Event::Resize(w, h)) = input {
                resize_to(terminal, (w, h))?;
                if let Some(recorder) = recorder.as_deref() {
                    let drawn = drawn_area((w, h));
                    recorder.record(CastEvent::Resize(drawn.width, drawn.height));
                }
            }
            flow |= program.input(input);
            if program.should_quit() {
                return Ok(());
            }
        }
        flow |= program.after_inputs();
    }
    Ok(())
}

/// Ctrl-Z: restore the terminal, stop the process as the shell's Ctrl-Z would (SIGTSTP,
/// sent by `kill`, std having no call for it), and take the terminal again once resumed (the
/// mouse's reports too, with `mouse`).
pub(super) fn suspend(terminal: &mut Term, mouse: bool) -> io::Result<()> {
    if give_back(terminal).is_err() {
        ratatui::restore();
    }
    let stopped = std::process::Command::new("kill")
        .args(["-TSTP", &std::process::id().to_string()])
        .status();
    // Resumed: raw mode and the alternate screen again, on the same terminal (a new one, or
    // `Terminal::clear`, would ask for the cursor position, whose reply the input thread would
    // take); the screen is blank, so the next draw is diffed against a blank buffer.
    crossterm::terminal::enable_raw_mode()?;
    crossterm::execute!(
        terminal.backend_mut(),
        crossterm::terminal::EnterAlternateScreen,
        crossterm::terminal::Clear(crossterm::terminal::ClearType::All)
    )?;
    if mouse {
        crossterm::execute!(terminal.backend_mut(), EnableMouseCapture)?;
    }
    terminal.swap_buffers();
    stopped.map(|_| ())
}

/// What `render` draws, as one frame inside synchronized-output brackets.
pub(super) fn draw_with(terminal: &mut Term, render: impl FnOnce(&mut Frame)) -> io::Result<()> {
    crossterm::execute!(terminal.backend_mut(), BeginSynchronizedUpdate)?;
    let drawn = terminal.draw(render).map(|_| ());
    crossterm::execute!(terminal.backend_mut(), EndSynchronizedUpdate)?;
    drawn
}
