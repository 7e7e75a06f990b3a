//! Property-based test of the scenario parser and validator: any value of any key gives a
//! valid scenario or an error that names the file, the key and what is allowed — never a
//! panic, never an out-of-range value let through.

use proptest::prelude::*;
use riplab::scenario::{DEFAULT_SCENARIO, Scenario};

/// Keys of the default scenario whose values the test replaces, with their line prefixes.
const KEYS: &[(&str, &str)] = &[
    ("body.width", "width ="),
    ("body.height", "height ="),
    ("material.young", "young ="),
    ("material.poisson", "poisson ="),
    ("obstacle.radius", "radius ="),
    ("obstacle.depth", "depth ="),
    ("obstacle.center", "center ="),
    ("mesh.nx", "nx ="),
    ("mesh.ny", "ny ="),
    ("mesh.level", "level ="),
    ("contact.epsilon", "epsilon ="),
];

/// A TOML value of any kind and size, including what TOML allows and riplab must reject.
fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f64>().prop_map(|v| if v.is_nan() {
            "nan".into()
        } else if v.is_infinite() {
            if v > 0.0 { "inf".into() } else { "-inf".into() }
        } else {
            format!("{v:e}")
        }),
        (-1.0e3..1.0e3f64).prop_map(|v| format!("{v}")),
        any::<i64>().prop_map(|v| v.to_string()),
        (-3i64..12).prop_map(|v| v.to_string()),
        "[a-z]{0,6}".prop_map(|s| format!("\"{s}\"")),
        Just("true".to_string()),
        Just("[1.0, 2.0]".to_string()),
        Just("".to_string()),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn any_value_is_accepted_in_range_or_rejected_with_its_key(k in 0..KEYS.len(), v in value()) {
        let (key, prefix) = KEYS[k];
        let line = DEFAULT_SCENARIO.lines().find(|l| l.starts_with(prefix)).unwrap();
        let text = DEFAULT_SCENARIO.replace(line, &format!("{prefix} {v}"));
        match Scenario::parse(&text, "prop.toml") {
            Ok(s) => {
                prop_assert!(s.width > 0.0 && s.width.is_finite() && s.height > 0.0 && s.height.is_finite());
                prop_assert!(s.material.young > 0.0 && s.material.young.is_finite());
                prop_assert!(s.material.poisson > -1.0 && s.material.poisson < 0.5);
                prop_assert!(s.obstacle.depth().is_finite() && s.epsilon >= 0.0 && s.epsilon.is_finite());
                prop_assert!(s.level <= 8 && s.x_lines.len() >= 2 && s.y_lines.len() >= 2);
            }
            Err(e) => {
                let msg = e.to_string();
                prop_assert!(msg.starts_with("prop.toml:"), "no file/line: {}", msg);
                let leaf = key.rsplit('.').next().unwrap();
                prop_assert!(msg.contains(leaf), "key {} not named: {}", key, msg);
            }
        }
    }
}
