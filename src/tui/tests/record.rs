//! The tour's recorder alone, on a writer that fails and on one that keeps what it is given
//! (the recording of a whole tour in a pseudo-terminal is tested on the binary, in
//! tests/cli/record.rs).

use std::io::Write;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use riplab::tui::record::cast::{Event, Header};
use riplab::tui::record::{Recorder, RecordingFailure};

/// A writer that fails as a full disk does.
struct Full;

impl Write for Full {
    fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
        Err(std::io::Error::from_raw_os_error(28))
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// A recording that cannot be written says so, once, and at the end.
#[test]
fn a_failed_recording_is_reported() {
    let (tx, rx) = std::sync::mpsc::channel();
    let wake = move || tx.send(()).unwrap();
    let mut recorder = Recorder::with_writer(Full, "full.cast".into(), &Header::new(80, 24, "t"), wake);
    recorder.record(Event::Output(b"x".to_vec()));
    // The loop is woken as soon as the write fails (a deadline only against a hang).
    rx.recv_timeout(Duration::from_secs(120)).expect("woken");
    let full = |failure: &RecordingFailure| {
        matches!(failure, RecordingFailure::Write { name, source }
            if name == "full.cast" && source.raw_os_error() == Some(28))
    };
    let failure = recorder.new_failure().expect("the failure");
    assert!(full(&failure), "{failure:?}");
    // The status line's text, as before the failure was typed.
    let disk = std::io::Error::from_raw_os_error(28);
    assert_eq!(failure.to_string(), format!("recording full.cast failed: {disk}"));
    assert!(
        recorder.new_failure().is_none(),
        "reported once on the status line"
    );
    let end = recorder.finish().unwrap_err();
    assert!(full(&end), "{end:?}");
}

/// The recorder's file holds every event in order, the header first.
#[test]
fn a_recorder_writes_its_events_in_order() {
    #[derive(Clone, Default)]
    struct Shared(Arc<Mutex<Vec<u8>>>);
    impl Write for Shared {
        fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
            self.0.lock().unwrap().extend_from_slice(b);
            Ok(b.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let out = Shared::default();
    let recorder = Recorder::with_writer(out.clone(), "mem".into(), &Header::new(80, 24, "t"), || {
        panic!("no failure")
    });
    let tap = recorder.tap();
    recorder.record(Event::Marker("a".into()));
    tap.record(Event::Output("é".as_bytes().to_vec()));
    recorder.record(Event::Resize(90, 25));
    recorder.finish().unwrap();
    let text = String::from_utf8(out.0.lock().unwrap().clone()).unwrap();
    let lines: Vec<serde_json::Value> = text.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines[0]["version"], 2);
    let kinds: Vec<(&str, &str)> = lines[1..]
        .iter()
        .map(|e| (e[1].as_str().unwrap(), e[2].as_str().unwrap()))
        .collect();
    assert_eq!(kinds, [("m", "a"), ("o", "é"), ("r", "90x25")]);
}
