//! Numbers as the file writes them, checked before serde reads them (scenarios and tours): a
//! decimal that is not zero but underflows to 0 in double precision (`mu = 1e-400`) would
//! silently become 0 (`epsilon = 1e-400` would select the exact method), and an integer
//! beyond 64 bits reached the user as serde's "invalid type: integer … as i128, expected
//! i64". Each is refused at its value with its dotted key (`mesh.level`, `step[3].level`) and,
//! for an integer, the range its key allows, as the command line refuses them.

use std::ops::Range;

use toml::de::{DeTable, DeValue};

use super::locate::{Locator, ScenarioError};
use crate::text::sanitize;

/// Whether `text`, read as `value`, names a non-zero decimal that underflows to 0.
pub fn underflows(text: &str, value: f64) -> bool {
    let mantissa = text.split(['e', 'E']).next().unwrap_or("");
    value == 0.0 && mantissa.bytes().any(|b| (b'1'..=b'9').contains(&b))
}

/// A number of the file refused, where, and why.
struct Fault {
    span: Range<usize>,
    key: String,
    message: String,
}

impl Locator<'_> {
    /// Refuse the first (in the file's order) float literal that underflows to 0 and integer
    /// beyond i64, each at its value; `allowed(key)` gives the range of an integer key (its
    /// dotted key, array elements numbered from 1: `step[3].level`). A text that is not TOML
    /// passes: the reader's own error says where.
    pub fn check_numbers(&self, allowed: impl Fn(&str) -> Option<(i64, i64)>) -> Result<(), ScenarioError> {
        let Ok(root) = DeTable::parse(self.text) else {
            return Ok(());
        };
        let mut faults = Vec::new();
        for (key, value) in root.get_ref().iter() {
            walk(
                key.get_ref(),
                value.get_ref(),
                value.span(),
                &allowed,
                &mut faults,
            );
        }
        match faults.into_iter().min_by_key(|f| f.span.start) {
            Some(f) => Err(self.error(Some(f.span), Some(f.key), f.message)),
            None => Ok(()),
        }
    }
}

/// Collect the faults of `value` (at `span`, under the dotted `key`) and of everything in it.
fn walk(
    key: &str,
    value: &DeValue,
    span: Range<usize>,
    allowed: &dyn Fn(&str) -> Option<(i64, i64)>,
    faults: &mut Vec<Fault>,
) {
    match value {
        DeValue::Float(f) => {
            let text = f.as_str();
            if text.parse::<f64>().is_ok_and(|v| underflows(text, v)) {
                faults.push(Fault {
                    span,
                    key: key.to_string(),
                    message: format!(
                        "`{}` is not 0 but underflows to 0 in double precision (the smallest is about 5e-324); write 0 if 0 is meant",
                        sanitize(text)
                    ),
                });
            }
        }
        DeValue::Integer(i) if i64::from_str_radix(i.as_str(), i.radix()).is_err() => {
            let range = match allowed(key) {
                Some((lo, hi)) => format!("{lo} to {hi}"),
                None => format!("a whole number from {} to {}", i64::MIN, i64::MAX),
            };
            faults.push(Fault {
                span,
                key: key.to_string(),
                message: format!("{} is out of range; allowed: {range}", sanitize(&i.to_string())),
            });
        }
        DeValue::Array(items) => {
            for (n, item) in items.iter().enumerate() {
                let key = format!("{key}[{}]", n + 1);
                walk(&key, item.get_ref(), item.span(), allowed, faults);
            }
        }
        DeValue::Table(table) => {
            for (k, v) in table.iter() {
                walk(
                    &format!("{key}.{}", k.get_ref()),
                    v.get_ref(),
                    v.span(),
                    allowed,
                    faults,
                );
            }
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str) -> Result<(), ScenarioError> {
        let allowed = |key: &str| (key == "mesh.level").then_some((0, 8));
        Locator { file: "t.toml", text }.check_numbers(allowed)
    }

    /// `1e-400` is refused where it stands (in a table, an array, an inline table); `0`, `0.0e5`
    /// and the smallest subnormal pass; an integer beyond i64 is refused in the user's words
    /// with its key's range (or i64's), in the file's order; a text that is not TOML passes.
    #[test]
    fn underflows_and_oversized_integers_are_refused_at_their_key() {
        let e = check("[friction]\nlaw = \"coulomb\"\nmu = 1e-400\n").unwrap_err();
        assert_eq!(
            (e.location, e.key.as_deref()),
            (Some((3, 6)), Some("friction.mu"))
        );
        assert!(
            e.message.contains("`1e-400` is not 0 but underflows to 0"),
            "{}",
            e.message
        );
        let e = check("[mesh]\nx_lines = [0.0, 1e-999, 1.0]\n").unwrap_err();
        assert_eq!(e.key.as_deref(), Some("mesh.x_lines[2]"));
        let e = check("[[step]]\ntitle = \"a\"\n[[step]]\nb = { c = -0.5e-330 }\n").unwrap_err();
        assert_eq!(
            (e.location, e.key.as_deref()),
            (Some((4, 11)), Some("step[2].b.c"))
        );
        assert_eq!(check("a = 0\nb = 0.0e5\nc = 5e-324\nd = -0.0\ne = nan\n"), Ok(()));
        let e = check("[mesh]\nlevel = 99999999999999999999\nnx = 1e-400\n").unwrap_err();
        assert_eq!(e.key.as_deref(), Some("mesh.level"));
        assert_eq!(e.message, "99999999999999999999 is out of range; allowed: 0 to 8");
        let huge = format!("[mesh]\nny = -{}\n", "9".repeat(50));
        let e = check(&huge).unwrap_err();
        assert!(
            e.message.ends_with(
                "is out of range; allowed: a whole number from -9223372036854775808 to 9223372036854775807"
            ),
            "{}",
            e.message
        );
        assert_eq!(check("x = 0x7fffffffffffffff\n"), Ok(()));
        assert!(check("x = 0x8000000000000000\n").is_err());
        assert_eq!(check("[mesh\nlevel = 1e-400"), Ok(()));
    }
}
