//! Text that reaches a terminal: sanitised when it came from a file, and numbers written the
//! way a reader checks them.

use std::borrow::Cow;

/// `text` with every control character (C0, DEL, C1: escape sequences, bells, carriage
/// returns, line feeds) and every bidirectional control replaced by `�`, so that text read
/// from a file, the command line or the environment cannot move the cursor, retitle the
/// window, clear the screen, start a line of its own or reorder what follows it when it is
/// printed.
pub fn sanitize(text: &str) -> Cow<'_, str> {
    if text.chars().any(unsafe_char) {
        Cow::Owned(
            text.chars()
                .map(|c| if unsafe_char(c) { '\u{fffd}' } else { c })
                .collect(),
        )
    } else {
        Cow::Borrowed(text)
    }
}

/// A control character, or a bidirectional control of Unicode's Bidi_Control property: the
/// embeddings and overrides U+202A–U+202E, the isolates U+2066–U+2069, the marks U+200E,
/// U+200F and the Arabic letter mark U+061C.
fn unsafe_char(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' | '\u{200e}' | '\u{200f}' | '\u{061c}')
}

/// [`sanitize`] for several lines: each line sanitised, the line breaks kept.
pub fn sanitize_lines(text: &str) -> String {
    text.split('\n')
        .map(|l| sanitize(l.strip_suffix('\r').unwrap_or(l)).into_owned())
        .collect::<Vec<_>>()
        .join("\n")
}

/// A number as a person reads it in a message: plain between 1e-4 and 1e6, scientific
/// otherwise (never a 300-digit decimal), `NaN`, `inf` and `-inf` as themselves.
pub fn num(value: f64) -> String {
    let a = value.abs();
    if !value.is_finite() || a == 0.0 || (1e-4..1e6).contains(&a) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

/// A value with `digits` decimals (`{:.6}`) when that shows at least three significant
/// digits of it, in scientific notation with `digits` decimals otherwise (a load of 2e-7 is
/// not `0.000000`, nor 1e300 a decimal of 300 digits); `NaN`, `inf` and `-inf` as themselves.
pub fn fixed(value: f64, digits: usize) -> String {
    let a = value.abs();
    let least = 10f64.powi(2 - digits as i32);
    if !value.is_finite() || a == 0.0 || (least..1e9).contains(&a) {
        format!("{value:.digits$}")
    } else {
        format!("{value:.digits$e}")
    }
}

/// A result in scientific notation with `digits` decimals (`{:.3e}`), or, when it is not a
/// finite number, `n/a: ` and `why` (what makes it undefined): a table never shows `inf` or
/// `NaN` as a value.
pub fn sci(value: f64, digits: usize, why: &str) -> String {
    if value.is_finite() {
        format!("{value:.digits$e}")
    } else {
        format!("n/a: {why}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_keeps_three_digits_or_turns_scientific() {
        assert_eq!(fixed(7.962_108, 6), "7.962108");
        assert_eq!(fixed(1.5e-4, 6), "0.000150");
        assert_eq!(fixed(2e-7, 6), "2.000000e-7");
        assert_eq!(fixed(-2e-7, 5), "-2.00000e-7");
        assert_eq!(fixed(0.0, 6), "0.000000");
        assert_eq!(fixed(3e12, 2), "3.00e12");
        assert_eq!(fixed(f64::NAN, 6), "NaN");
    }

    #[test]
    fn control_characters_are_replaced() {
        let hostile = "a\u{1b}]0;PWNED\u{7}\u{1b}[2Jb\u{9b}c\r\n";
        let clean = sanitize(hostile);
        assert_eq!(
            clean,
            "a\u{fffd}]0;PWNED\u{fffd}\u{fffd}[2Jb\u{fffd}c\u{fffd}\u{fffd}"
        );
        assert!(!clean.chars().any(char::is_control));
        assert!(matches!(sanitize("plain ε = 1e-6"), Cow::Borrowed(_)));
        assert_eq!(sanitize_lines("x\u{1b}\r\ny"), "x\u{fffd}\ny");
    }

    #[test]
    fn bidi_controls_are_replaced() {
        for c in [
            '\u{202a}', '\u{202e}', '\u{2066}', '\u{2069}', '\u{200e}', '\u{200f}', '\u{061c}',
        ] {
            assert_eq!(sanitize(&format!("a{c}b")), "a\u{fffd}b", "{:x}", c as u32);
        }
        // Letters of right-to-left scripts stay: only the controls go.
        assert_eq!(sanitize("שלום مرحبا"), "שלום مرحبا");
    }

    #[test]
    fn numbers_are_short() {
        assert_eq!(num(1e300), "1e300");
        assert_eq!(num(-1.7e308), "-1.7e308");
        assert_eq!(num(1e-200), "1e-200");
        assert_eq!(num(0.8), "0.8");
        assert_eq!(num(1000.0), "1000");
        assert_eq!(num(0.0), "0");
        assert_eq!(num(f64::NAN), "NaN");
        assert_eq!(num(f64::NEG_INFINITY), "-inf");
    }
}
