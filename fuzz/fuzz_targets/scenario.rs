//! Fuzz the scenario parser and validator: any bytes give a scenario whose values are in range
//! or an error naming the file — never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use riplab::scenario::Scenario;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    match Scenario::parse(text, "fuzz.toml") {
        Ok(s) => {
            assert!(s.material.young > 0.0 && s.material.young.is_finite());
            assert!(s.material.poisson > -1.0 && s.material.poisson < 0.5);
            assert!(s.width > 0.0 && s.height > 0.0 && s.level <= 8);
            assert!(s.x_lines.windows(2).all(|w| w[0] < w[1]));
            // The unknown count used by the memory check must not overflow or panic either.
            let _ = s.n_dofs(s.level, s.element);
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.toml")),
    }
});
