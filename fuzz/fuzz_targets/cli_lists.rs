//! Fuzz the command line's own parsers (level ranges, schemes, the numbers of ε, κ and the
//! depth): any text gives a valid value or an error that says what is allowed — never a panic,
//! never a non-zero number read as 0.
#![no_main]

use libfuzzer_sys::fuzz_target;
use riplab::fuzzing::{number, parse_levels};
use riplab::scheme::Scheme;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match parse_levels(text) {
        Ok(levels) => {
            assert!(!levels.is_empty() && levels.len() <= 9);
            assert!(levels.windows(2).all(|w| w[1] == w[0] + 1) && levels[levels.len() - 1] <= 8);
        }
        Err(m) => assert!(m.to_string().contains("allowed")),
    }
    if let Err(m) = Scheme::parse(text) {
        assert!(m.to_string().contains("allowed"));
    }
    match number(text) {
        Ok(v) if v == 0.0 => {
            let mantissa = text.trim().split(['e', 'E']).next().unwrap_or("");
            assert!(
                !mantissa.bytes().any(|b| (b'1'..=b'9').contains(&b)),
                "{text:?} read as 0"
            );
        }
        Ok(_) => {}
        Err(m) => {
            assert!(m.to_string().contains("not a number") || m.to_string().contains("underflows to 0"))
        }
    }
});
