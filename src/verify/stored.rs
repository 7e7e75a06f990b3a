//! The "did it change" tier's stored values (`src/verify/stored.toml`): per case, the value of
//! each quantity at the case's default level, as the numerics gave it when the file was
//! written. `riplab verify --print-stored` writes the file anew from a run at the default
//! levels, after a change of the numerics that was meant.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::Check;

/// The stored values, embedded at build time.
const STORED: &str = include_str!("stored.toml");

/// The stored values of `case`'s quantities (empty for a case with none).
pub fn values(case: &str) -> BTreeMap<String, f64> {
    let all: BTreeMap<String, BTreeMap<String, f64>> =
        toml::from_str(STORED).expect("src/verify/stored.toml is riplab's own, checked by its tests");
    all.get(case).cloned().unwrap_or_default()
}

/// The file `src/verify/stored.toml` holding `checks`' computed values (a run at the default
/// levels), a table per case.
pub fn file(checks: &[Check]) -> String {
    let mut s = String::from(
        "# riplab verify's stored values: each case's quantities at its default level, the\n\
         # \"did it change\" tier (src/verify/mod.rs). Written by `riplab verify --print-stored`.\n",
    );
    let mut case = "";
    for c in checks {
        if c.case != case {
            case = c.case;
            let _ = write!(s, "\n[{case}]\n");
        }
        if let Some(v) = c.computed {
            // A TOML basic string: the quantities are riplab's own, without control characters.
            let key = c.quantity.replace('\\', "\\\\").replace('"', "\\\"");
            let _ = writeln!(s, "\"{key}\" = {v:e}");
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The embedded file parses, and names only cases and quantities that exist.
    #[test]
    fn the_stored_file_names_the_packs_cases() {
        let all: BTreeMap<String, BTreeMap<String, f64>> = toml::from_str(STORED).unwrap();
        let names: Vec<&str> = super::super::cases().iter().map(|c| c.name).collect();
        for case in all.keys() {
            assert!(names.contains(&case.as_str()), "{case} is not a case");
        }
        assert!(!values("circle").is_empty());
    }
}
