//! The "did it change" tier's stored values (`src/verify/stored.toml`): per case, the value of
//! each quantity at the case's default level, as the numerics gave it when the file was
//! written. `riplab verify --print-stored` writes the file anew from a run at the default
//! levels, after a change of the numerics that was meant.

use std::collections::{BTreeMap, BTreeSet};
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
/// levels), a table per case, each quantity once (a run checks it against its reference and
/// again against its stored value: written twice, the keys repeated and TOML refused the file).
pub fn file(checks: &[Check]) -> String {
    let mut s = String::from(
        "# riplab verify's stored values: each case's quantities at its default level, the\n\
         # \"did it change\" tier (src/verify/mod.rs). Written by `riplab verify --print-stored`.\n",
    );
    let mut case = "";
    let mut written = BTreeSet::new();
    for c in checks {
        if c.case != case {
            case = c.case;
            let _ = write!(s, "\n[{case}]\n");
        }
        if !written.insert((c.case, c.quantity.as_str())) {
            continue;
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

    /// A quantity checked twice (against its reference, then its stored value) is written
    /// once, and the file parses.
    #[test]
    fn a_quantity_checked_twice_is_stored_once() {
        let check = |kind, computed| Check {
            case: "hertz",
            kind,
            quantity: "peak p̄ against p₀".into(),
            level: 2,
            computed: Some(computed),
            reference: None,
            measure: super::super::Measure::Relative,
            error: None,
            tolerance: None,
            verdict: super::super::Verdict::Ok,
            reason: None,
            source: "",
        };
        use super::super::Kind;
        let text = file(&[check(Kind::ClosedForm, 61.0), check(Kind::Unchanged, 61.0)]);
        let all: BTreeMap<String, BTreeMap<String, f64>> = toml::from_str(&text).unwrap();
        assert_eq!(all["hertz"]["peak p̄ against p₀"], 61.0);
        assert_eq!(text.matches("peak").count(), 1, "{text}");
    }

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
