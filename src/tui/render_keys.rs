//! `riplab render --keys KEYS`: a key sequence applied to the lab before its settled frame is
//! printed, so that every state a user can reach (a level stepped to, the cursor moved, the
//! projector view, the log) can be rendered in docs and tests. Each character is its key;
//! `<tab>`, `<backtab>`, `<esc>`, `<enter>`, `<space>`, `<left>`, `<right>`, `<up>`, `<down>`,
//! `<pageup>`, `<pagedown>` and `<lt>` (a literal `<`) name the others.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};

use crate::text;

/// The most keys one `--keys` may hold (each may start a solve).
pub const MAX_KEYS: usize = 200;

/// The named keys of [`parse_keys`].
const NAMED: &[(&str, KeyCode)] = &[
    ("tab", KeyCode::Tab),
    ("backtab", KeyCode::BackTab),
    ("esc", KeyCode::Esc),
    ("enter", KeyCode::Enter),
    ("space", KeyCode::Char(' ')),
    ("left", KeyCode::Left),
    ("right", KeyCode::Right),
    ("up", KeyCode::Up),
    ("down", KeyCode::Down),
    ("pageup", KeyCode::PageUp),
    ("pagedown", KeyCode::PageDown),
    ("lt", KeyCode::Char('<')),
];

/// Why a key sequence was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum KeysError {
    /// A `<name>` that names no key.
    #[error("--keys: `<{0}>` names no key; allowed names: {names}", names = names())]
    UnknownName(String),
    /// A `<` without its `>`.
    #[error("--keys: `<` at character {0} has no closing `>` (write <lt> for the key <)")]
    Unclosed(usize),
    /// More keys than [`MAX_KEYS`].
    #[error("--keys: {0} keys; allowed: at most {MAX_KEYS}")]
    TooMany(usize),
}

fn names() -> String {
    NAMED
        .iter()
        .map(|(n, _)| format!("<{n}>"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The keys of `spec`, in order (see the module's doc).
pub fn parse_keys(spec: &str) -> Result<Vec<KeyEvent>, KeysError> {
    let mut keys = Vec::new();
    let mut chars = spec.char_indices();
    while let Some((at, c)) = chars.next() {
        let code = if c == '<' {
            let rest = &spec[at + 1..];
            let end = rest.find('>').ok_or(KeysError::Unclosed(at + 1))?;
            let name = &rest[..end];
            let code = NAMED
                .iter()
                .find(|(n, _)| n.eq_ignore_ascii_case(name))
                .map(|&(_, k)| k)
                .ok_or_else(|| KeysError::UnknownName(text::sanitize(name).into_owned()))?;
            for _ in 0..name.chars().count() + 1 {
                chars.next();
            }
            code
        } else {
            KeyCode::Char(c)
        };
        let modifiers = match code {
            KeyCode::Char(c) if c.is_uppercase() => KeyModifiers::SHIFT,
            KeyCode::BackTab => KeyModifiers::SHIFT,
            _ => KeyModifiers::NONE,
        };
        keys.push(KeyEvent::new(code, modifiers));
        if keys.len() > MAX_KEYS {
            return Err(KeysError::TooMany(spec.chars().count()));
        }
    }
    Ok(keys)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_and_names_parse() {
        let keys = parse_keys("]x.<tab><lt>").unwrap();
        let codes: Vec<KeyCode> = keys.iter().map(|k| k.code).collect();
        assert_eq!(
            codes,
            [
                KeyCode::Char(']'),
                KeyCode::Char('x'),
                KeyCode::Char('.'),
                KeyCode::Tab,
                KeyCode::Char('<')
            ]
        );
        assert_eq!(parse_keys("<tab"), Err(KeysError::Unclosed(1)));
        assert!(matches!(parse_keys("<ctrl-c>"), Err(KeysError::UnknownName(n)) if n == "ctrl-c"));
        assert!(matches!(
            parse_keys(&"]".repeat(MAX_KEYS + 1)),
            Err(KeysError::TooMany(_))
        ));
        assert_eq!(parse_keys(&"]".repeat(MAX_KEYS)).unwrap().len(), MAX_KEYS);
    }
}
