//! Fuzz the tour parser: any bytes give a tour or an error naming the file — never a panic,
//! never a control character in the message; a valid tour's steps checked against the paper's
//! scenario as when it is played.
#![no_main]

use libfuzzer_sys::fuzz_target;
use riplab::Scenario;
use riplab::fuzzing::Tour;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match Tour::parse(text, "fuzz.toml", None) {
        // Every step checked against the scenario it is played with (depth, ε at its level).
        Ok(tour) => {
            if let Err(e) = tour.with_scenario(Scenario::paper()) {
                let m = e.to_string();
                assert!(
                    m.starts_with("fuzz.toml") && !m.chars().any(char::is_control),
                    "{m:?}"
                );
            }
        }
        Err(e) => {
            let message = e.to_string();
            assert!(message.starts_with("fuzz.toml"));
            assert!(!message.chars().any(|c| c.is_control() && c != '\n'));
        }
    }
});
