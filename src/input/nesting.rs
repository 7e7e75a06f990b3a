//! A pre-scan of a TOML text for nesting deeper than any scenario or tour has:
//! the TOML reader stops arrays and inline tables nested too deep with a located error, but a
//! dotted key of 150,000 parts (`a.b.c… = 1`, `[a.b.c…]`) reaches serde's recursion limit,
//! whose message has no line and no key. A key of more than [`MAX_KEY_PARTS`] parts is refused
//! here, before the reader, with its line and the start of the key.

use super::locate::{Locator, ScenarioError};

/// The most parts a dotted key may have (the deepest key of a scenario has 3).
pub const MAX_KEY_PARTS: usize = 32;

/// Where the scanner is: in plain TOML, or inside a string of this kind.
#[derive(Clone, Copy, PartialEq)]
enum In {
    Plain,
    Comment,
    Basic,
    Literal,
    MultiBasic,
    MultiLiteral,
}

impl Locator<'_> {
    /// Refuse a dotted key of more than 32 parts (`MAX_KEY_PARTS`), at its first character.
    pub fn check_nesting(&self) -> Result<(), ScenarioError> {
        let bytes = self.text.as_bytes();
        let (mut state, mut i) = (In::Plain, 0);
        // The dots of the current chain of key parts and where the chain began.
        let (mut dots, mut start) = (0usize, None::<usize>);
        let starts = |i: usize, s: &[u8]| bytes[i..].starts_with(s);
        while i < bytes.len() {
            let b = bytes[i];
            match state {
                In::Comment if b == b'\n' => state = In::Plain,
                In::Basic if b == b'\\' => i += 1,
                In::Basic if b == b'"' || b == b'\n' => state = In::Plain,
                In::Literal if b == b'\'' || b == b'\n' => state = In::Plain,
                In::MultiBasic if b == b'\\' => i += 1,
                In::MultiBasic if starts(i, b"\"\"\"") => (state, i) = (In::Plain, i + 2),
                In::MultiLiteral if starts(i, b"'''") => (state, i) = (In::Plain, i + 2),
                In::Plain => {
                    let part = b.is_ascii_alphanumeric() || b == b'_' || b == b'-' || b == b'"' || b == b'\'';
                    if b == b'.' {
                        dots += 1;
                        if dots >= MAX_KEY_PARTS {
                            return Err(self.too_deep(start.unwrap_or(i)));
                        }
                    } else if part {
                        start.get_or_insert(i);
                    } else if b != b' ' && b != b'\t' {
                        (dots, start) = (0, None);
                    }
                    if starts(i, b"\"\"\"") {
                        (state, i) = (In::MultiBasic, i + 2);
                    } else if starts(i, b"'''") {
                        (state, i) = (In::MultiLiteral, i + 2);
                    } else {
                        match b {
                            b'"' => state = In::Basic,
                            b'\'' => state = In::Literal,
                            b'#' => state = In::Comment,
                            _ => {}
                        }
                    }
                }
                _ => {}
            }
            i += 1;
        }
        Ok(())
    }

    fn too_deep(&self, at: usize) -> ScenarioError {
        let key: String = self.text[at..]
            .chars()
            .take(40)
            .take_while(|c| *c != '\n')
            .collect();
        self.error(
            Some(at..at),
            Some(format!("{key}…")),
            format!(
                "a key nested deeper than {MAX_KEY_PARTS} levels; allowed: the keys of docs/design.md §1"
            ),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str) -> Result<(), ScenarioError> {
        Locator { file: "t.toml", text }.check_nesting()
    }

    #[test]
    fn deep_dotted_keys_are_refused_with_their_line() {
        let deep = format!("x = 1\n{} = 1\n", vec!["a"; 150_000].join("."));
        let e = check(&deep).unwrap_err();
        assert_eq!(e.location, Some((2, 1)));
        assert!(e.key.as_deref().unwrap().starts_with("a.a.a"));
        let header = format!("[{}]\n", vec!["b"; 100].join("."));
        assert_eq!(check(&header).unwrap_err().location, Some((1, 2)));
        // Dots in strings, comments, numbers and ordinary keys are not nesting.
        let fine = format!(
            "[material]\nyoung = 1.5e3\nname = \"{}\"\n# {}\ns = '''\n{}\n'''\na.b.c = 1\n",
            ".".repeat(100),
            ".".repeat(100),
            "x.".repeat(100)
        );
        assert_eq!(check(&fine), Ok(()));
        assert_eq!(check(riplab_default()), Ok(()));
    }

    fn riplab_default() -> &'static str {
        crate::scenario::DEFAULT_SCENARIO
    }
}
