//! `--record FILE.cast`: the lab or the tour recorded as an asciicast v2 file ([`cast`]) of
//! exactly what the terminal was sent, with its timing, the terminal's resizes, and a marker
//! at every step of a tour (its title) and every change of scene.
//!
//! The terminal's writer ([`Screen`]) holds a frame's bytes until the backend flushes, writes
//! them to the terminal, and hands a copy to a [`Recorder`], whose thread turns them into JSON
//! lines in a buffered file: the drawing thread never waits for the disk. The file is created
//! before the terminal is taken ([`CastFile::create`]: a bad path is a clear error, an
//! existing file is never replaced); a failed write (a full disk) stops the recording and is
//! reported on the status line and at exit.

pub mod cast;

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Instant;

use cast::{Cast, Event, Header};

use super::app::Scene;

/// Why a recording cannot start.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// The file exists: riplab never replaces a file.
    #[error("{0}: the file exists; a recording never replaces a file (choose another name)")]
    Exists(String),
    /// The file cannot be created (no such directory, no permission…).
    #[error("{path}: cannot create the recording: {source}")]
    Create {
        /// The path asked for.
        path: String,
        /// What the system said.
        source: io::Error,
    },
}

/// Why a recording stopped (shown on the status line and at exit).
#[derive(Clone, Debug, thiserror::Error)]
pub enum RecordingFailure {
    /// A write failed (a full disk), or the writer's thread could not be started.
    #[error("recording {name} failed: {source}")]
    Write {
        /// The file (sanitised).
        name: String,
        /// What the system said (shared: the writer's thread keeps it for the loop).
        source: Arc<io::Error>,
    },
    /// The writer's thread stopped without finishing (it panicked).
    #[error("recording {name}: the writer stopped")]
    WriterStopped {
        /// The file (sanitised).
        name: String,
    },
}

/// A new, empty asciicast file, created before the terminal is taken.
#[derive(Debug)]
pub struct CastFile {
    path: PathBuf,
    file: File,
}

impl CastFile {
    /// Create `path` (never replacing a file: an existing name is refused).
    pub fn create(path: &Path) -> Result<CastFile, RecordError> {
        let name = crate::text::sanitize(&path.display().to_string()).into_owned();
        match File::create_new(path) {
            Ok(file) => Ok(CastFile {
                path: path.to_path_buf(),
                file,
            }),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => Err(RecordError::Exists(name)),
            Err(source) => Err(RecordError::Create { path: name, source }),
        }
    }

    /// Where the recording goes.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// What the recorder's thread is sent.
enum Job {
    Event(f64, Event),
    Finish,
}

/// A recording in progress: events are timed here and written by a thread of their own.
pub struct Recorder {
    tap: Tap,
    /// The first write error (the thread stops writing after it).
    failure: Arc<Mutex<Option<Arc<io::Error>>>>,
    /// Whether the failure was already shown.
    reported: bool,
    thread: Option<JoinHandle<()>>,
    /// What the file is called, for messages.
    name: String,
}

impl Recorder {
    /// Start recording into `file` a terminal of `size` (columns, rows): the header is written
    /// first. `wake` is called once if a write fails (so that the failure is shown at once).
    pub fn start(
        file: CastFile,
        size: (u16, u16),
        title: &str,
        wake: impl FnOnce() + Send + 'static,
    ) -> Recorder {
        let name = crate::text::sanitize(&file.path.display().to_string()).into_owned();
        let header = Header::new(size.0, size.1, title);
        Recorder::with_writer(BufWriter::new(file.file), name, &header, wake)
    }

    /// Start recording into `out` (named `name` in messages); `wake` as for [`Recorder::start`].
    pub fn with_writer<W: Write + Send + 'static>(
        out: W,
        name: String,
        header: &Header,
        wake: impl FnOnce() + Send + 'static,
    ) -> Recorder {
        let (tx, rx) = mpsc::channel();
        let failure = Arc::new(Mutex::new(None));
        let shared = failure.clone();
        let header = header.clone();
        let thread = std::thread::Builder::new()
            .name("riplab-record".into())
            .spawn(move || {
                if let Err(e) = write_events(out, &header, &rx) {
                    *shared.lock().unwrap_or_else(|p| p.into_inner()) = Some(Arc::new(e));
                    wake();
                }
            });
        let (thread, failure) = match thread {
            Ok(t) => (Some(t), failure),
            Err(e) => (None, Arc::new(Mutex::new(Some(Arc::new(e))))),
        };
        Recorder {
            tap: Tap {
                tx,
                start: Instant::now(),
            },
            failure,
            reported: false,
            thread,
            name,
        }
    }

    /// Record `event` now.
    pub fn record(&self, event: Event) {
        self.tap.record(event);
    }

    /// A handle that records into this recording (for the terminal's writer).
    pub fn tap(&self) -> Tap {
        self.tap.clone()
    }

    /// The recording's failure, the first time it is asked for after it happened.
    pub fn new_failure(&mut self) -> Option<RecordingFailure> {
        if self.reported {
            return None;
        }
        let failure = self.failure()?;
        self.reported = true;
        Some(failure)
    }

    fn failure(&self) -> Option<RecordingFailure> {
        let source = self.failure.lock().unwrap_or_else(|p| p.into_inner()).clone()?;
        Some(RecordingFailure::Write {
            name: self.name.clone(),
            source,
        })
    }

    /// Write what is left and close the file; the recording's failure, if any.
    pub fn finish(mut self) -> Result<(), RecordingFailure> {
        let _ = self.tap.tx.send(Job::Finish);
        if let Some(thread) = self.thread.take()
            && thread.join().is_err()
        {
            return Err(RecordingFailure::WriterStopped {
                name: self.name.clone(),
            });
        }
        match self.failure() {
            Some(f) => Err(f),
            None => Ok(()),
        }
    }
}

/// A handle on a recording: events sent through it are timed from the recording's start.
#[derive(Clone)]
pub struct Tap {
    tx: Sender<Job>,
    start: Instant,
}

impl Tap {
    /// Record `event` now.
    pub fn record(&self, event: Event) {
        let t = self.start.elapsed().as_secs_f64();
        // A stopped thread has its failure stored: the send's own error adds nothing.
        let _ = self.tx.send(Job::Event(t, event));
    }
}

/// The recorder's thread: the header, then the events as they come, the file flushed whenever
/// no event waits.
fn write_events<W: Write>(out: W, header: &Header, rx: &Receiver<Job>) -> io::Result<()> {
    let mut cast = Cast::new(out, header)?;
    cast.flush()?;
    'recording: while let Ok(first) = rx.recv() {
        for job in std::iter::once(first).chain(std::iter::from_fn(|| rx.try_recv().ok())) {
            match job {
                Job::Event(t, event) => cast.event(t, &event)?,
                Job::Finish => break 'recording,
            }
        }
        cast.flush()?;
    }
    cast.finish().map(|_| ())
}

/// The terminal's writer: a frame's bytes are held until the backend flushes, then written to
/// the terminal and, when recording, copied to the [`Recorder`].
pub struct Screen {
    out: io::Stdout,
    frame: Vec<u8>,
    tap: Option<Tap>,
}

impl Screen {
    /// The process's standard output, recorded through `tap` if given.
    pub fn new(tap: Option<Tap>) -> Screen {
        Screen {
            out: io::stdout(),
            frame: Vec::new(),
            tap,
        }
    }
}

impl Write for Screen {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.frame.extend_from_slice(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        if self.frame.is_empty() {
            return self.out.flush();
        }
        let frame = std::mem::take(&mut self.frame);
        let written = self.out.write_all(&frame).and_then(|()| self.out.flush());
        if let Some(tap) = &self.tap {
            tap.record(Event::Output(frame));
        }
        written
    }
}

impl Drop for Screen {
    fn drop(&mut self) {
        let _ = self.flush();
    }
}

/// Where a recording marks a chapter: the tour's step (index and title) and the scene shown.
#[derive(Clone, Debug, PartialEq)]
pub struct Chapter {
    /// The tour's step (None in the lab).
    pub step: Option<(usize, String)>,
    /// The scene shown.
    pub scene: Scene,
}

impl Chapter {
    /// The marker on the way from `before` (None: the start) to `self`: the step's title when
    /// the step changed, else `scene: NAME` when the scene did, else none.
    pub fn marker(&self, before: Option<&Chapter>) -> Option<String> {
        let step_changed = before.is_none_or(|b| b.step != self.step);
        match &self.step {
            Some((_, title)) if step_changed => Some(title.clone()),
            _ if step_changed || before.is_some_and(|b| b.scene != self.scene) => {
                Some(format!("scene: {}", self.scene.name()))
            }
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A marker at the start, at each new step (its title, even when the scene changes with
    /// it), and at each change of scene within a step or in the lab; none otherwise.
    #[test]
    fn markers_name_steps_and_scenes() {
        let at = |step: Option<usize>, scene| Chapter {
            step: step.map(|i| (i, format!("Step {i}"))),
            scene,
        };
        let tour = at(Some(0), Scene::Explore);
        assert_eq!(tour.marker(None).as_deref(), Some("Step 0"));
        assert_eq!(tour.marker(Some(&tour)), None);
        let next = at(Some(1), Scene::InfSup);
        assert_eq!(next.marker(Some(&tour)).as_deref(), Some("Step 1"));
        let tabbed = at(Some(1), Scene::Mesh);
        assert_eq!(tabbed.marker(Some(&next)).as_deref(), Some("scene: mesh"));
        let lab = at(None, Scene::Explore);
        assert_eq!(lab.marker(None).as_deref(), Some("scene: explore"));
        assert_eq!(lab.marker(Some(&lab)), None);
        let stress = at(None, Scene::Stress);
        assert_eq!(stress.marker(Some(&lab)).as_deref(), Some("scene: stress"));
    }
}
