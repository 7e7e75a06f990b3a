//! The interactive loop: the terminal (raw mode, alternate screen, restored on exit and on
//! panic by ratatui), an input thread and the worker feeding one channel, and a redraw only
//! when an update says the screen changed, inside synchronized-output brackets.

use std::io;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use crossterm::event::Event;
use crossterm::terminal::{BeginSynchronizedUpdate, EndSynchronizedUpdate};
use ratatui::{DefaultTerminal, Frame};

use crate::scenario::Scenario;

use super::app::{App, Command, ExportKind, Msg, Response};
use super::export::{export_csv, export_svg, export_vtu};
use super::view::{Look, view};
use super::worker::Worker;

/// Everything the loop waits for.
enum Input {
    Terminal(Event),
    Worker(Response),
    /// Reading the terminal failed: the loop ends with this error.
    Broken(io::Error),
}

/// Forward the terminal's events to `tx` from a thread of their own, as `event(e)`; a failed
/// read is sent as `broken(err)` and ends the thread (so does a closed channel).
pub(super) fn forward_terminal<T: Send + 'static>(
    tx: mpsc::Sender<T>,
    event: fn(Event) -> T,
    broken: fn(io::Error) -> T,
) -> io::Result<()> {
    std::thread::Builder::new()
        .name("riplab-input".into())
        .spawn(move || {
            loop {
                let (input, end) = match crossterm::event::read() {
                    Ok(e) => (event(e), false),
                    Err(e) => (broken(e), true),
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

/// Run the lab on `scenario` until the user quits, exporting into `dir` (absolute); the
/// terminal is restored in every case.
pub fn run(scenario: Scenario, look: Look, dir: PathBuf) -> io::Result<()> {
    let mut terminal = ratatui::try_init()?;
    let result = event_loop(&mut terminal, scenario, &look, &dir);
    ratatui::restore();
    result
}

/// Wait for the next input: for ever, or at most one [`TICK`] when `tick` (then None).
pub(super) fn next<T>(rx: &mpsc::Receiver<T>, tick: bool) -> Result<Option<T>, ()> {
    if tick {
        match rx.recv_timeout(TICK) {
            Ok(input) => Ok(Some(input)),
            Err(RecvTimeoutError::Timeout) => Ok(None),
            Err(RecvTimeoutError::Disconnected) => Err(()),
        }
    } else {
        rx.recv().map(Some).map_err(|_| ())
    }
}

fn event_loop(terminal: &mut DefaultTerminal, scenario: Scenario, look: &Look, dir: &Path) -> io::Result<()> {
    let (tx, rx) = mpsc::channel::<Input>();
    let to_app = tx.clone();
    let worker = Worker::spawn(scenario.clone(), move |r| to_app.send(Input::Worker(r)).is_ok());
    forward_terminal(tx, Input::Terminal, Input::Broken)?;

    let mut app = App::new(scenario);
    let mut redraw = apply(terminal, &mut app, &worker, Msg::Resize, dir)?;
    while !app.should_quit() {
        if redraw {
            draw(terminal, &app, look)?;
        }
        // Block for one input (or a tick while a long job runs), then take whatever else is
        // queued before drawing again.
        let Ok(first) = next(&rx, app.wants_tick()) else {
            break;
        };
        redraw = false;
        if first.is_none() {
            redraw |= apply(terminal, &mut app, &worker, Msg::Tick, dir)?;
        }
        for input in first.into_iter().chain(std::iter::from_fn(|| rx.try_recv().ok())) {
            let msg = match input {
                Input::Terminal(Event::Key(key)) => Msg::Key(key),
                Input::Terminal(Event::Resize(..)) => Msg::Resize,
                Input::Terminal(_) => continue,
                Input::Worker(r) => Msg::Worker(r),
                Input::Broken(e) => return Err(e),
            };
            redraw |= apply(terminal, &mut app, &worker, msg, dir)?;
            if app.should_quit() {
                break;
            }
        }
    }
    Ok(())
}

/// Update the app and carry out its commands; returns whether to redraw.
fn apply(
    terminal: &mut DefaultTerminal,
    app: &mut App,
    worker: &Worker,
    msg: Msg,
    dir: &Path,
) -> io::Result<bool> {
    let effect = app.update(msg);
    let mut redraw = effect.redraw;
    for command in effect.commands {
        match command {
            Command::Export => redraw |= apply(terminal, app, worker, export(app, dir), dir)?,
            Command::Suspend => {
                suspend(terminal)?;
                redraw = true;
            }
            other => worker.send(&other),
        }
    }
    Ok(redraw)
}

/// Ctrl-Z: restore the terminal, stop the process as the shell's Ctrl-Z would (SIGTSTP,
/// sent by `kill`, std having no call for it), and take the terminal again once resumed.
pub(super) fn suspend(terminal: &mut DefaultTerminal) -> io::Result<()> {
    ratatui::restore();
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
    terminal.swap_buffers();
    stopped.map(|_| ())
}

/// Carry out [`Command::Export`] into `dir`: the reply for the app.
pub(super) fn export(app: &App, dir: &Path) -> Msg {
    let result = match app.current() {
        Some(solved) => match app.export_kind {
            ExportKind::Csv => export_csv(&app.scenario, solved, dir),
            ExportKind::Svg => export_svg(&app.scenario, solved, dir),
            ExportKind::Vtu => export_vtu(&app.scenario, solved, dir),
        }
        .map(|p| p.display().to_string()),
        None => Err("no solution to export".into()),
    };
    Msg::Exported(result)
}

/// One frame of the lab inside synchronized-output brackets (no tearing over SSH).
fn draw(terminal: &mut DefaultTerminal, app: &App, look: &Look) -> io::Result<()> {
    draw_with(terminal, |frame| view(app, frame, look))
}

/// What `render` draws, as one frame inside synchronized-output brackets.
pub(super) fn draw_with(terminal: &mut DefaultTerminal, render: impl FnOnce(&mut Frame)) -> io::Result<()> {
    crossterm::execute!(terminal.backend_mut(), BeginSynchronizedUpdate)?;
    let drawn = terminal.draw(render).map(|_| ());
    crossterm::execute!(terminal.backend_mut(), EndSynchronizedUpdate)?;
    drawn
}
