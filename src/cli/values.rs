//! Numbers of the command line read as the user meant them: a decimal that is not
//! zero but underflows to 0 in double precision (`1e-400`) would silently select the exact
//! constraint (ε = 0); it is refused, saying why, where a plain `0` is accepted.

use crate::text::sanitize;

/// A number of the command line that is not one, or not the one meant.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum NumberError {
    /// Not a number at all.
    #[error("`{}` is not a number", sanitize(text))]
    NotANumber {
        /// The text as given (trimmed).
        text: String,
    },
    /// A non-zero decimal that underflows to 0.
    #[error(
        "`{}` is not 0 but underflows to 0 in double precision (the smallest is about 5e-324); write 0 for the exact constraint",
        sanitize(text)
    )]
    Underflow {
        /// The text as given (trimmed).
        text: String,
    },
}

/// `text` as a finite-or-not f64 (the ranges are checked later, per option), refused when it
/// names a non-zero number that underflows to 0.
///
/// # Errors
///
/// Text that is not a number, or a non-zero number that underflows to 0.
pub fn number(text: &str) -> Result<f64, NumberError> {
    let trimmed = text.trim();
    let value: f64 = trimmed.parse().map_err(|_| NumberError::NotANumber {
        text: trimmed.to_string(),
    })?;
    if crate::input::literals::underflows(trimmed, value) {
        return Err(NumberError::Underflow {
            text: trimmed.to_string(),
        });
    }
    Ok(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_that_underflow_to_zero_are_refused() {
        assert_eq!(number("1e-6"), Ok(1e-6));
        assert_eq!(number("0"), Ok(0.0));
        assert_eq!(number("0.000e5"), Ok(0.0));
        assert_eq!(number("-0"), Ok(-0.0));
        assert_eq!(number(" 2.5 "), Ok(2.5));
        for tiny in ["1e-400", "-3.5E-999", "0.001e-330"] {
            let e = number(tiny).unwrap_err();
            assert_eq!(e, NumberError::Underflow { text: tiny.into() });
            assert!(e.to_string().contains("underflows to 0"), "{tiny}: {e}");
        }
        let escape = number("x\u{1b}[2J").unwrap_err();
        assert!(matches!(escape, NumberError::NotANumber { .. }));
        assert!(escape.to_string().contains('\u{fffd}'));
    }
}
