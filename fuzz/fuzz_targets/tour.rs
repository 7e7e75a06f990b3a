//! Fuzz the tour parser: any bytes give a tour or an error naming the file — never a panic,
//! never a control character in the message.
#![no_main]

use libfuzzer_sys::fuzz_target;
use riplab::tui::tour::Tour;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Err(e) = Tour::parse(text, "fuzz.toml", None) {
        let message = e.to_string();
        assert!(message.starts_with("fuzz.toml"));
        assert!(!message.chars().any(|c| c.is_control() && c != '\n'));
    }
});
