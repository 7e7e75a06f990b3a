//! Fuzz the command line's own parsers (level ranges, schemes): any text gives a valid value or
//! an error that says what is allowed — never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use riplab::cli::parse_levels;
use riplab::scheme::Scheme;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    match parse_levels(text) {
        Ok(levels) => {
            assert!(!levels.is_empty() && levels.len() <= 9);
            assert!(levels.windows(2).all(|w| w[1] == w[0] + 1) && levels[levels.len() - 1] <= 8);
        }
        Err(m) => assert!(m.contains("allowed")),
    }
    if let Err(m) = Scheme::parse(text) {
        assert!(m.contains("allowed"));
    }
});
