//! A scheme: an element with a contact rule. The paper's four (docs/design.md §2) have names,
//! M1–M4; every other pair is written `element+rule` (e.g. `q2+gauss1`). This is the one place
//! that names, labels and parses them.

use std::fmt;
use std::str::FromStr;

use crate::contact::Rule;
use crate::mesh::Element;

/// An element and the contact rule of the penalty term.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Scheme {
    /// The element of the displacement.
    pub element: Element,
    /// The contact rule on Γ_C.
    pub rule: Rule,
}

impl Scheme {
    /// The scheme of `element` with `rule`.
    pub const fn new(element: Element, rule: Rule) -> Self {
        Scheme { element, rule }
    }

    /// The paper's schemes M1–M4, in order.
    pub const PAPER: [Scheme; 4] = [
        Scheme::new(Element::Q1, Rule::Gauss1),
        Scheme::new(Element::Q1, Rule::Gauss2),
        Scheme::new(Element::Q1, Rule::Trapezoid),
        Scheme::new(Element::Q2, Rule::Simpson),
    ];

    /// The paper's scheme M`m` (1–4).
    pub fn paper(m: u8) -> Option<Scheme> {
        Scheme::PAPER.get(usize::from(m).checked_sub(1)?).copied()
    }

    /// Every element × rule pair: the paper's four first, then the others.
    pub fn all() -> Vec<Scheme> {
        let mut all = Scheme::PAPER.to_vec();
        for element in Element::ALL {
            for rule in Rule::ALL {
                let s = Scheme::new(element, rule);
                if !all.contains(&s) {
                    all.push(s);
                }
            }
        }
        all
    }

    /// The paper's name (M1–M4), if it has one.
    pub fn name(self) -> Option<&'static str> {
        const NAMES: [&str; 4] = ["M1", "M2", "M3", "M4"];
        Scheme::PAPER.iter().position(|&s| s == self).map(|i| NAMES[i])
    }

    /// The paper's name or `element+rule`: what [`Scheme::parse`] reads back.
    pub fn label(self) -> String {
        self.name().map_or_else(
            || format!("{}+{}", self.element.name(), self.rule.name()),
            str::to_string,
        )
    }

    /// A scheme as written: M1–M4 or `element+rule`, any case.
    ///
    /// # Errors
    ///
    /// Text that is neither M1–M4 nor `element+rule`, with the allowed names.
    pub fn parse(text: &str) -> Result<Scheme, SchemeError> {
        let bad = || SchemeError {
            text: text.to_string(),
        };
        let t = text.trim();
        if let Some(m) = t.strip_prefix(['M', 'm']) {
            return m.parse().ok().and_then(Scheme::paper).ok_or_else(bad);
        }
        let (e, r) = t.split_once('+').ok_or_else(bad)?;
        let element = Element::ALL
            .into_iter()
            .find(|x| x.name().eq_ignore_ascii_case(e.trim()));
        let rule = Rule::ALL
            .into_iter()
            .find(|x| x.name().eq_ignore_ascii_case(r.trim()));
        Ok(Scheme::new(element.ok_or_else(bad)?, rule.ok_or_else(bad)?))
    }
}

/// A scheme's name that is neither M1–M4 nor `element+rule`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("`{text}`; allowed: M1, M2, M3, M4 or element+rule, e.g. q2+gauss1")]
pub struct SchemeError {
    /// The text as written.
    pub text: String,
}

impl FromStr for Scheme {
    type Err = SchemeError;
    fn from_str(s: &str) -> Result<Self, SchemeError> {
        Scheme::parse(s)
    }
}

impl fmt::Display for Scheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.label())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every label parses back to its scheme; the paper's names are docs/design.md §2's.
    #[test]
    fn labels_parse_back() {
        for s in Scheme::all() {
            assert_eq!(Scheme::parse(&s.label()), Ok(s));
            assert_eq!(Scheme::parse(&s.label().to_lowercase()), Ok(s));
        }
        assert_eq!(Scheme::all().len(), Element::ALL.len() * Rule::ALL.len());
        assert_eq!(Scheme::parse("m4"), Ok(Scheme::new(Element::Q2, Rule::Simpson)));
        assert_eq!(
            Scheme::parse(" Q2 + Gauss1 ").map(Scheme::label),
            Ok("q2+gauss1".into())
        );
        assert!(
            SchemeError { text: "M5".into() }
                .to_string()
                .contains("allowed: M1")
        );
        for bad in ["M0", "M5", "M", "q3+gauss1", "q1+gauss3", "q1", ""] {
            assert_eq!(Scheme::parse(bad), Err(SchemeError { text: bad.into() }), "{bad}");
        }
    }
}
