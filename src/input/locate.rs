//! The error locator: a byte span of a TOML text turned into the file, the 1-based line and
//! column, the dotted key and the offending line, in a [`ScenarioError`] (used for scenarios
//! and tours).

use std::fmt::{self, Display};
use std::ops::Range;

use toml::Spanned;

use crate::text::{sanitize, sanitize_lines};

/// What went wrong in a scenario, and where.
#[derive(Clone, Debug, PartialEq)]
pub struct ScenarioError {
    /// The file's name as given (or [`crate::scenario::DEFAULT_SOURCE`]).
    pub file: String,
    /// 1-based (line, column), when known.
    pub location: Option<(usize, usize)>,
    /// Dotted key, e.g. `material.poisson`, when known.
    pub key: Option<String>,
    /// What is wrong, and what is allowed.
    pub message: String,
    /// The offending source line for display (an excerpt of a long one),
    /// with the 1-based column of the caret in it.
    /// (Boxed: the error travels in every `Result` of the command line.)
    pub source_line: Option<Box<(String, usize)>>,
}

impl std::error::Error for ScenarioError {}

/// Every piece of text that came from the file (its name, keys, the message that may quote
/// the file, the source line) is sanitised: an error must not replay escape sequences.
impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", sanitize(&self.file))?;
        if let Some((line, col)) = self.location {
            write!(f, ":{line}:{col}")?;
        }
        write!(f, ": ")?;
        if let Some(key) = &self.key {
            write!(f, "`{}`: ", sanitize(key))?;
        }
        write!(f, "{}", sanitize_lines(&self.message))?;
        if let (Some((line, _)), Some((text, col))) = (self.location, self.source_line.as_deref()) {
            write!(f, "\n {line:>4} | {}\n      | {:>col$}", sanitize(text), "^")?;
        }
        Ok(())
    }
}

/// The most characters of a line (or a key) an error echoes.
pub const EXCERPT_CHARS: usize = 120;

/// `text` cut to at most `max` characters, `…` marking the cut.
fn bounded(text: &str, max: usize) -> String {
    match text.char_indices().nth(max) {
        Some((at, _)) => format!("{}…", &text[..at]),
        None => text.to_string(),
    }
}

/// The part of a line an error shows, and the caret's 1-based column in it: the whole line
/// when it is short, else at most [`EXCERPT_CHARS`] characters from a little before the
/// 1-based `column`, `…` marking the cuts.
fn excerpt(line: &str, column: usize) -> (String, usize) {
    if line.chars().count() <= EXCERPT_CHARS {
        return (line.to_string(), column);
    }
    let from = column.saturating_sub(EXCERPT_CHARS / 4 + 1);
    let tail: String = line.chars().skip(from).take(EXCERPT_CHARS + 1).collect();
    let cut = bounded(&tail, EXCERPT_CHARS);
    if from > 0 {
        (format!("…{cut}"), column - from + 1)
    } else {
        (cut, column)
    }
}

/// Turns byte spans of a TOML text into located errors (used for scenarios and tours).
pub struct Locator<'a> {
    /// The file's name, for the errors.
    pub file: &'a str,
    /// The file's text, into which the spans point.
    pub text: &'a str,
}

impl Locator<'_> {
    /// An error at `span` about `key` (inferred from the line's `key = value` when None).
    pub fn error(&self, span: Option<Range<usize>>, key: Option<String>, message: String) -> ScenarioError {
        let (location, source_line) = match span {
            Some(span) => {
                let start = span.start.min(self.text.len());
                let start = (0..=start)
                    .rev()
                    .find(|&i| self.text.is_char_boundary(i))
                    .unwrap_or(0);
                let before = &self.text[..start];
                let line = before.matches('\n').count() + 1;
                let line_start = before.rfind('\n').map_or(0, |i| i + 1);
                let column = self.text[line_start..start].chars().count() + 1;
                let text = self.text[line_start..].lines().next().unwrap_or("");
                (Some((line, column)), Some(Box::new(excerpt(text, column))))
            }
            None => (None, None),
        };
        // serde names the reader's types; the user's words instead.
        let message = message
            .replace(", expected i64", ", expected a whole number")
            .replace(", expected f64", ", expected a number");
        // A missing field is reported at the table that lacks it: name the field.
        let missing = message
            .strip_prefix("missing field `")
            .and_then(|rest| rest.split('`').next())
            .map(str::to_string);
        let key = key.or_else(|| {
            let at = location.and_then(|(l, _)| self.key_at(l));
            match (missing, at) {
                (Some(field), Some(at)) if location.is_some_and(|(l, c)| l > 1 || c > 1) => {
                    Some(format!("{at}.{field}"))
                }
                (Some(field), _) => Some(field),
                (None, at) => at,
            }
        });
        ScenarioError {
            file: self.file.to_string(),
            location,
            key: key.map(|k| bounded(&k, EXCERPT_CHARS)),
            message,
            source_line,
        }
    }

    /// The dotted key assigned on 1-based `line` (`table.key`), found from the text; inside
    /// an array of inline tables (`bumps = [ { … }, … ]`), the array's key.
    fn key_at(&self, line: usize) -> Option<String> {
        let lines: Vec<&str> = self.text.lines().collect();
        let here = lines.get(line - 1)?.trim();
        let name = |l: &str| l.trim_matches(|c| c == '[' || c == ']').trim().to_string();
        // The table a header on line index `i` opens: `step[3]` for the third `[[step]]`.
        let header = |i: usize| {
            let l = lines[i].trim();
            let table = name(l);
            if !l.starts_with("[[") {
                return table;
            }
            let same = lines[..=i]
                .iter()
                .filter(|h| h.trim().starts_with("[[") && name(h) == table)
                .count();
            format!("{table}[{same}]")
        };
        if here.starts_with('[') {
            return Some(header(line - 1));
        }
        let above = &lines[..line - 1];
        let start = above
            .iter()
            .rposition(|l| l.trim().starts_with('['))
            .map_or(0, |i| i + 1);
        let table = start.checked_sub(1).map(header);
        let join = |key: &str| match &table {
            Some(t) => format!("{t}.{key}"),
            None => key.to_string(),
        };
        let bare = |k: &str| !k.is_empty() && k.chars().all(|c| c.is_alphanumeric() || "_-.".contains(c));
        let key = here
            .split('=')
            .next()
            .map(str::trim)
            .filter(|k| bare(k) && here.contains('='));
        if let Some(key) = key {
            return Some(join(key));
        }
        // Inside a multi-line array: the key of the line that opened it.
        let opened = above[start..]
            .iter()
            .rev()
            .find_map(|l| l.split_once('=').filter(|(_, v)| v.trim_start().starts_with('[')));
        match opened {
            Some((key, _)) if bare(key.trim()) => Some(join(key.trim())),
            _ => table,
        }
    }

    /// `test` of a spanned value, failing with an error at the value about `key`.
    pub fn check<T, E: Display>(
        &self,
        key: &str,
        value: &Spanned<T>,
        test: impl Fn(&T) -> Result<(), E>,
    ) -> Result<(), ScenarioError> {
        test(value.get_ref())
            .map_err(|e| self.error(Some(value.span()), Some(key.to_string()), e.to_string()))
    }
}
