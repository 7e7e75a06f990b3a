//! The message log (`l`): every notice, failure and solver warning since the lab started,
//! and every change of its state (level, scheme, rule, element, method, ε, depth, grading,
//! integration, friction, scene), each with the time since the lab opened. A message said
//! again while it is among the last few lines is folded into that line (`× 6`), and so is a
//! change of the same setting (`depth 0.8 → 0.2 × 6`).

use std::collections::VecDeque;
use std::time::Instant;

use crate::scheme::Scheme;
use crate::text::num;

use super::super::friction_settings::label;
use super::{Scene, SolveKey};

/// The most lines the log keeps (the oldest go first).
pub const LOG_LEN: usize = 500;

/// How many of the last lines a repeat is folded into.
const FOLD_WINDOW: usize = 4;

/// One line of the log.
#[derive(Clone, Debug, PartialEq)]
pub struct LogEntry {
    /// Something failed.
    pub failure: bool,
    /// What was said (for a change: `depth 0.8 → 0.7`).
    pub text: String,
    /// Seconds since the lab opened, when it was last said.
    pub at: f64,
    /// How many times it was said (repeats folded into it).
    pub count: u32,
    /// A change of state: the setting and its value before the first change folded here.
    change: Option<(&'static str, String)>,
}

/// The log's lines, oldest first (at most [`LOG_LEN`]).
#[derive(Clone, Debug, Default)]
pub struct Log {
    entries: VecDeque<LogEntry>,
    /// When the first line was logged (the lab's opening, to the user: the first key or reply).
    opened: Option<Instant>,
}

impl Log {
    /// The lines, oldest first.
    pub fn iter(&self) -> impl DoubleEndedIterator<Item = &LogEntry> {
        self.entries.iter()
    }

    /// The newest line.
    #[cfg(test)]
    pub fn back(&self) -> Option<&LogEntry> {
        self.entries.back()
    }

    fn now(&mut self) -> f64 {
        self.opened
            .get_or_insert_with(Instant::now)
            .elapsed()
            .as_secs_f64()
    }

    /// Log a message; the same message among the last lines is counted there instead.
    pub fn message(&mut self, failure: bool, text: String) {
        let at = self.now();
        let recent = self.entries.iter_mut().rev().take(FOLD_WINDOW);
        if let Some(same) = recent
            .into_iter()
            .find(|e| e.change.is_none() && e.failure == failure && e.text == text)
        {
            same.count += 1;
            same.at = at;
            return;
        }
        self.push(LogEntry {
            failure,
            text,
            at,
            count: 1,
            change: None,
        });
    }

    /// Log that `what` changed from `from` to `to`; a change of the same setting among the
    /// last lines is folded there (from its first value to this one).
    pub fn change(&mut self, what: &'static str, from: String, to: String) {
        let at = self.now();
        let recent = self.entries.iter_mut().rev().take(FOLD_WINDOW);
        if let Some(same) = recent
            .into_iter()
            .find(|e| e.change.as_ref().is_some_and(|(w, _)| *w == what))
        {
            let first = same.change.as_ref().map(|(_, v)| v.clone()).unwrap_or_default();
            same.text = format!("{what} {first} → {to}");
            same.count += 1;
            same.at = at;
            return;
        }
        self.push(LogEntry {
            failure: false,
            text: format!("{what} {from} → {to}"),
            at,
            count: 1,
            change: Some((what, from)),
        });
    }

    fn push(&mut self, entry: LogEntry) {
        if self.entries.len() == LOG_LEN {
            self.entries.pop_front();
        }
        self.entries.push_back(entry);
    }

    /// Log every setting that differs between `before` and `after`, and the scene's change.
    pub fn changes(&mut self, before: (&SolveKey, Scene), after: (&SolveKey, Scene)) {
        let ((a, scene_a), (b, scene_b)) = (before, after);
        if a.level != b.level {
            self.change("level", a.level.to_string(), b.level.to_string());
        }
        let what = match (a.element != b.element, a.rule != b.rule) {
            (true, true) => Some("scheme"),
            (true, false) => Some("element"),
            (false, true) => Some("rule"),
            (false, false) => None,
        };
        if let Some(what) = what {
            self.change(what, scheme(a), scheme(b));
        }
        if a.method != b.method {
            self.change("method", a.method.name().to_string(), b.method.name().to_string());
        }
        if a.epsilon != b.epsilon {
            self.change("ε", format!("{:e}", a.epsilon), format!("{:e}", b.epsilon));
        }
        if a.depth != b.depth {
            self.change("depth", num(a.depth), num(b.depth));
        }
        if a.refine_edges != b.refine_edges {
            self.change("grading", a.refine_edges.to_string(), b.refine_edges.to_string());
        }
        if a.integration != b.integration {
            self.change(
                "integration",
                format!("{:?}", a.integration).to_lowercase(),
                format!("{:?}", b.integration).to_lowercase(),
            );
        }
        if a.friction != b.friction {
            self.change("friction", label(&a.friction), label(&b.friction));
        }
        if scene_a != scene_b {
            self.change("scene", scene_a.name().to_string(), scene_b.name().to_string());
        }
    }
}

/// `M1 q1+gauss1`, or `q1+simpson` for a pair that is none of the paper's schemes.
fn scheme(key: &SolveKey) -> String {
    let pair = format!("{}+{}", key.element.name(), key.rule.name());
    match Scheme::new(key.element, key.rule).name() {
        Some(m) => format!("{m} {pair}"),
        None => pair,
    }
}

/// `m:ss` of `seconds` (the log's time column).
pub fn clock(seconds: f64) -> String {
    let s = seconds.max(0.0).floor() as u64;
    format!("{}:{:02}", s / 60, s % 60)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A repeated message is counted in its line; so is a run of changes of one setting, from
    /// its first value to its last, across the lines between.
    #[test]
    fn repeats_fold() {
        let mut log = Log::default();
        for d in 1..=6 {
            log.change("depth", format!("0.{}", 9 - d), format!("0.{}", 8 - d));
            log.message(false, "⚠ the obstacle is not resolved".into());
        }
        let lines: Vec<(String, u32)> = log.iter().map(|e| (e.text.clone(), e.count)).collect();
        assert_eq!(
            lines,
            [
                ("depth 0.8 → 0.2".to_string(), 6),
                ("⚠ the obstacle is not resolved".to_string(), 6)
            ]
        );
        log.message(true, "⚠ the obstacle is not resolved".into());
        assert_eq!(log.iter().count(), 3, "a failure is another message");
        assert_eq!(clock(75.4), "1:15");
    }
}
