//! Fuzz the scenario parser and validator: any bytes give a scenario whose values are in range
//! or an error naming the file — never a panic, never a control character in the message.
#![no_main]

use libfuzzer_sys::fuzz_target;
use riplab::Scenario;
use riplab::fuzzing::{LENGTH, YOUNG};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match Scenario::parse(text, "fuzz.toml") {
        Ok(s) => {
            let (lo, hi) = YOUNG;
            assert!(s.material.young >= lo && s.material.young <= hi);
            assert!(s.material.poisson > -1.0 && s.material.poisson < 0.5);
            let (lo, hi) = LENGTH;
            assert!(s.width >= lo && s.width <= hi && s.height >= lo && s.height <= hi);
            assert!(s.level <= 8);
            assert!(s.obstacle.depth().abs() < s.height);
            assert!(s.x_lines.windows(2).all(|w| w[0] < w[1]));
            assert!(s.y_lines.windows(2).all(|w| w[0] < w[1]));
            let (elo, ehi) = s.epsilon_range(s.level);
            assert!(s.epsilon == 0.0 || (s.epsilon >= elo && s.epsilon <= ehi));
            assert!(!s.name.chars().any(char::is_control));
            assert!(
                !s.name
                    .chars()
                    .any(|c| matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}'))
            );
            // The unknown count used by the memory check must not overflow or panic either.
            let _ = s.n_dofs(s.level, s.element);
        }
        Err(e) => {
            let message = e.to_string();
            assert!(message.starts_with("fuzz.toml"));
            assert!(!message.chars().any(|c| c.is_control() && c != '\n'));
        }
    }
});
