//! The asciicast v2 format (asciinema's newline-delimited JSON): a header line
//! `{"version": 2, "width", "height", "timestamp", "title"}`, then one event per line,
//! `[t, "o", data]` for output, `[t, "m", label]` for a marker, `[t, "r", "COLSxROWS"]` for a
//! resize, t in seconds from the start. Every string goes through serde_json, so that escape
//! sequences, quotes and control characters are escaped as JSON requires; output bytes that
//! end inside a UTF-8 sequence are held back until the rest arrives.

use std::io::{self, Write};

use serde::Serialize;

/// The header line of an asciicast v2 file.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Header {
    /// Always 2.
    pub version: u8,
    /// The terminal's columns at the start.
    pub width: u16,
    /// The terminal's rows at the start.
    pub height: u16,
    /// When the recording started (Unix seconds).
    pub timestamp: u64,
    /// What was recorded (shown by players).
    pub title: String,
}

impl Header {
    /// A version-2 header for a `width`×`height` terminal, stamped now.
    pub fn new(width: u16, height: u16, title: &str) -> Header {
        let timestamp = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs());
        Header {
            version: 2,
            width,
            height,
            timestamp,
            title: title.to_string(),
        }
    }
}

/// One event of a recording.
#[derive(Clone, Debug, PartialEq)]
pub enum Event {
    /// Bytes sent to the terminal.
    Output(Vec<u8>),
    /// A chapter: a tour's step (its title) or a scene.
    Marker(String),
    /// The terminal's new size (columns, rows).
    Resize(u16, u16),
}

/// An asciicast v2 stream being written to `out`.
pub struct Cast<W: Write> {
    out: W,
    /// Output bytes that end inside a UTF-8 sequence, waiting for the rest.
    pending: Vec<u8>,
    /// The time of the last event written (events never go back in time).
    last: f64,
}

impl<W: Write> Cast<W> {
    /// Start a stream: the header line first.
    pub fn new(mut out: W, header: &Header) -> io::Result<Cast<W>> {
        serde_json::to_writer(&mut out, header)?;
        out.write_all(b"\n")?;
        Ok(Cast {
            out,
            pending: Vec::new(),
            last: 0.0,
        })
    }

    /// Write `event` at `seconds` from the start (rounded to microseconds, never before the
    /// previous event).
    pub fn event(&mut self, seconds: f64, event: &Event) -> io::Result<()> {
        let t = ((seconds * 1e6).round() / 1e6).max(self.last);
        self.last = t;
        match event {
            Event::Output(bytes) => {
                self.pending.extend_from_slice(bytes);
                let text = take_text(&mut self.pending);
                if text.is_empty() {
                    return Ok(());
                }
                self.line(t, "o", &text)
            }
            Event::Marker(label) => self.line(t, "m", label),
            Event::Resize(w, h) => self.line(t, "r", &format!("{w}x{h}")),
        }
    }

    /// End the stream: output still held back (an incomplete UTF-8 sequence) is written with
    /// U+FFFD for its bytes, and the writer flushed and returned.
    pub fn finish(mut self) -> io::Result<W> {
        if !self.pending.is_empty() {
            let text = String::from_utf8_lossy(&self.pending).into_owned();
            self.pending.clear();
            self.line(self.last, "o", &text)?;
        }
        self.out.flush()?;
        Ok(self.out)
    }

    /// Flush what is written so far.
    pub fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }

    fn line(&mut self, t: f64, code: &str, data: &str) -> io::Result<()> {
        serde_json::to_writer(&mut self.out, &(t, code, data))?;
        self.out.write_all(b"\n")
    }
}

/// The text of `bytes` up to the last complete UTF-8 sequence (invalid bytes as U+FFFD); an
/// incomplete sequence at the end stays in `bytes` for the next call.
fn take_text(bytes: &mut Vec<u8>) -> String {
    let mut text = String::new();
    let mut rest: &[u8] = bytes;
    loop {
        match std::str::from_utf8(rest) {
            Ok(s) => {
                text.push_str(s);
                rest = &[];
                break;
            }
            Err(e) => {
                let (valid, after) = rest.split_at(e.valid_up_to());
                text.push_str(std::str::from_utf8(valid).unwrap_or_default());
                match e.error_len() {
                    Some(n) => {
                        text.push('\u{fffd}');
                        rest = &after[n..];
                    }
                    // The sequence is cut off at the end: wait for its rest.
                    None => {
                        rest = after;
                        break;
                    }
                }
            }
        }
    }
    let keep = rest.len();
    bytes.drain(..bytes.len() - keep);
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(bytes: &[u8]) -> Vec<serde_json::Value> {
        std::str::from_utf8(bytes)
            .expect("the stream is UTF-8")
            .lines()
            .map(|l| serde_json::from_str(l).expect("every line is JSON"))
            .collect()
    }

    /// The header comes first; escapes and quotes are JSON-escaped; a UTF-8 sequence split
    /// across writes is written whole, once its rest arrives.
    #[test]
    fn events_are_json_lines_and_split_utf8_waits() {
        let mut cast = Cast::new(Vec::new(), &Header::new(100, 30, "a \"tour\"")).unwrap();
        let braille = "⣿".as_bytes();
        cast.event(0.1, &Event::Output(b"\x1b[2J\"x\"".to_vec())).unwrap();
        cast.event(0.2, &Event::Output(braille[..1].to_vec())).unwrap();
        cast.event(0.3, &Event::Output(braille[1..].to_vec())).unwrap();
        cast.event(0.35, &Event::Marker("M1 at 32 elements".into()))
            .unwrap();
        cast.event(0.4, &Event::Resize(80, 24)).unwrap();
        // A clock that goes back is held at the last time.
        cast.event(0.39, &Event::Output(vec![0xff, b'a'])).unwrap();
        let out = lines(&cast.finish().unwrap());
        assert_eq!(out[0]["version"], 2);
        assert_eq!(
            (out[0]["width"].as_u64(), out[0]["height"].as_u64()),
            (Some(100), Some(30))
        );
        assert_eq!(out[0]["title"], "a \"tour\"");
        let events: Vec<(f64, &str, &str)> = out[1..]
            .iter()
            .map(|e| {
                (
                    e[0].as_f64().unwrap(),
                    e[1].as_str().unwrap(),
                    e[2].as_str().unwrap(),
                )
            })
            .collect();
        assert_eq!(
            events,
            [
                (0.1, "o", "\x1b[2J\"x\""),
                (0.3, "o", "⣿"),
                (0.35, "m", "M1 at 32 elements"),
                (0.4, "r", "80x24"),
                (0.4, "o", "\u{fffd}a"),
            ]
        );
    }

    /// A stream that ends inside a UTF-8 sequence ends with U+FFFD, still valid JSON.
    #[test]
    fn a_cut_sequence_at_the_end_is_replaced() {
        let mut cast = Cast::new(Vec::new(), &Header::new(80, 24, "t")).unwrap();
        cast.event(0.0, &Event::Output(vec![b'a', 0xe2, 0xa3])).unwrap();
        let out = lines(&cast.finish().unwrap());
        assert_eq!(out[1][2], "a");
        assert_eq!(out[2][2], "\u{fffd}");
    }
}
