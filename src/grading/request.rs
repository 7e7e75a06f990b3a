//! The grading request's words: how a solve grades its mesh, the value of `--refine-edges
//! N|Nz|auto` and of a scenario's `[mesh] refine_edges`, at the contact edges ([`RefineEdges`])
//! or over the contact zone ([`Grading::Zone`]), read and written as on the command line.

use std::fmt;

/// The most edge-grading passes `--refine-edges` and `[mesh] refine_edges` accept (and the cap
/// of `auto`).
pub const MAX_PASSES: u32 = 8;

/// `auto` grades until the relative change of p̄ in L²(Γ_C) between two passes is below this.
pub const AUTO_TOLERANCE: f64 = 1e-3;

/// How many times a solve grades its mesh at the contact edges: `--refine-edges N|auto` and
/// the scenario's `[mesh] refine_edges`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RefineEdges {
    /// Exactly this many passes (0: the uniform level), fewer only when no contact edge is left
    /// to grade.
    Passes(u32),
    /// Until p̄ changes by less than [`AUTO_TOLERANCE`] between passes, at most [`MAX_PASSES`].
    Auto,
}

impl Default for RefineEdges {
    /// No grading: the uniform level.
    fn default() -> Self {
        RefineEdges::Passes(0)
    }
}

/// A refine-edges value that is neither `auto`, a pass count in range, nor a zone's (`Nz`).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "`{given}` is not a grading; allowed: 0 to {MAX_PASSES}, or auto (passes at the contact edges), or 1z to {MAX_PASSES}z (passes over the contact zone)"
)]
pub struct RefineEdgesError {
    /// The text given (sanitised by the caller before it reaches a terminal).
    pub given: String,
}

impl RefineEdges {
    /// `auto`, or a whole number of passes 0 ..= [`MAX_PASSES`].
    ///
    /// # Errors
    ///
    /// Text that is neither `auto` nor a whole number 0 ..= [`MAX_PASSES`].
    pub fn parse(text: &str) -> Result<Self, RefineEdgesError> {
        let text = text.trim();
        if text.eq_ignore_ascii_case("auto") {
            return Ok(RefineEdges::Auto);
        }
        match text.parse::<i64>() {
            Ok(n) => Self::of_count(n),
            Err(_) => Err(RefineEdgesError {
                given: crate::text::sanitize(text).into_owned(),
            }),
        }
    }

    /// `n` passes, when 0 ..= [`MAX_PASSES`].
    ///
    /// # Errors
    ///
    /// `n` below 0 or above [`MAX_PASSES`].
    pub fn of_count(n: i64) -> Result<Self, RefineEdgesError> {
        match u32::try_from(n) {
            Ok(n) if n <= MAX_PASSES => Ok(RefineEdges::Passes(n)),
            _ => Err(RefineEdgesError { given: n.to_string() }),
        }
    }

    /// Whether a solve with this setting grades at all.
    pub fn grades(self) -> bool {
        self != RefineEdges::Passes(0)
    }

    /// Whether another pass is wanted after `done` passes, the last having changed p̄ by
    /// `change` (relative, L²(Γ_C); None before the first pass).
    pub fn wants_pass(self, done: u32, change: Option<f64>) -> bool {
        match self {
            RefineEdges::Passes(n) => done < n,
            RefineEdges::Auto => done < MAX_PASSES && change.is_none_or(|c| c >= AUTO_TOLERANCE),
        }
    }
}

impl fmt::Display for RefineEdges {
    /// `auto` or the pass count, as written on the command line.
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            RefineEdges::Passes(n) => write!(f, "{n}"),
            RefineEdges::Auto => f.write_str("auto"),
        }
    }
}

/// How a solve grades its mesh: at the contact edges (`N`, `Ne`, `auto`: [`RefineEdges`]) or
/// over the whole contact zone (`Nz`: [`super::zone`]). Written as on the command
/// line (`3`, `auto`, `3z`), and so in JSON and CSV.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Grading {
    /// Passes at the contact edges (`Passes(0)`: the uniform level).
    Edges(RefineEdges),
    /// This many passes over the contact zone (at least 1).
    Zone(u32),
}

impl Default for Grading {
    /// No grading: the uniform level.
    fn default() -> Self {
        Grading::Edges(RefineEdges::default())
    }
}

impl From<RefineEdges> for Grading {
    fn from(r: RefineEdges) -> Self {
        Grading::Edges(r)
    }
}

impl Grading {
    /// `N` or `Ne` (edge passes), `auto`, or `Nz` (zone passes; `0z` is the uniform level).
    ///
    /// # Errors
    ///
    /// Text that is none of `N`, `Ne`, `auto`, `Nz`, or passes beyond [`MAX_PASSES`].
    pub fn parse(text: &str) -> Result<Self, RefineEdgesError> {
        let text = text.trim();
        let refused = || RefineEdgesError {
            given: crate::text::sanitize(text).into_owned(),
        };
        let zone = text.strip_suffix(['z', 'Z']);
        let count = zone.or_else(|| text.strip_suffix(['e', 'E']));
        match count {
            Some(n) if !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()) => {
                let passes = RefineEdges::parse(n).map_err(|_| refused())?;
                Ok(match (zone, passes) {
                    (Some(_), RefineEdges::Passes(n)) if n > 0 => Grading::Zone(n),
                    _ => Grading::Edges(passes),
                })
            }
            Some(_) => Err(refused()),
            None => RefineEdges::parse(text).map(Grading::Edges),
        }
    }

    /// `n` passes of the kind of `self` (edges for `auto`).
    pub fn with_passes(self, n: u32) -> Self {
        match self {
            Grading::Zone(_) if n > 0 => Grading::Zone(n),
            _ => Grading::Edges(RefineEdges::Passes(n)),
        }
    }

    /// Whether a solve with this setting grades at all.
    pub fn grades(self) -> bool {
        self != Grading::default()
    }

    /// The letter of a graded level's label (`4+3e`, `4+3z`).
    pub fn letter(self) -> char {
        match self {
            Grading::Edges(_) => 'e',
            Grading::Zone(_) => 'z',
        }
    }

    /// The label of `level` after `passes` passes of this grading: `4`, `4+3e` or `4+3z`.
    pub fn level_label(self, level: u32, passes: u32) -> String {
        match passes {
            0 => level.to_string(),
            n => format!("{level}+{n}{}", self.letter()),
        }
    }

    /// Whether another pass is wanted after `done` passes ([`RefineEdges::wants_pass`]).
    pub fn wants_pass(self, done: u32, change: Option<f64>) -> bool {
        match self {
            Grading::Edges(r) => r.wants_pass(done, change),
            Grading::Zone(n) => done < n,
        }
    }

    /// The grading in words, for messages: where it grades, its passes, and its text (`graded
    /// over the contact zone, 8 passes (8z)`).
    pub fn described(self) -> String {
        let passes = |n: u32| match n {
            1 => "1 pass".to_string(),
            n => format!("{n} passes"),
        };
        match self {
            Grading::Edges(RefineEdges::Passes(0)) => "not graded (0)".into(),
            Grading::Edges(RefineEdges::Passes(n)) => {
                format!("graded at the contact edges, {} ({n})", passes(n))
            }
            Grading::Edges(RefineEdges::Auto) => format!(
                "graded at the contact edges until p̄ settles, at most {} (auto)",
                passes(MAX_PASSES)
            ),
            Grading::Zone(n) => format!("graded over the contact zone, {} ({n}z)", passes(n)),
        }
    }
}

impl fmt::Display for Grading {
    /// As written on the command line: `3`, `auto` or `3z`.
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            Grading::Edges(r) => r.fmt(f),
            Grading::Zone(n) => write!(f, "{n}z"),
        }
    }
}

/// JSON carries the text of [`fmt::Display`] (`"3"`, `"auto"`, `"3z"`).
impl serde::Serialize for Grading {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `auto`, 0 … MAX_PASSES; anything else names what is allowed.
    #[test]
    fn refine_edges_parses_auto_and_counts_in_range() {
        assert_eq!(RefineEdges::parse("auto"), Ok(RefineEdges::Auto));
        assert_eq!(RefineEdges::parse("0"), Ok(RefineEdges::default()));
        assert_eq!(RefineEdges::parse(" 3"), Ok(RefineEdges::Passes(3)));
        for bad in ["9", "-1", "two", "1.5"] {
            let e = RefineEdges::parse(bad).unwrap_err().to_string();
            assert!(e.contains("allowed: 0 to 8, or auto"), "{e}");
        }
        assert!(!RefineEdges::default().grades() && RefineEdges::Auto.grades());
        assert!(RefineEdges::Auto.wants_pass(0, None) && !RefineEdges::Auto.wants_pass(1, Some(1e-4)));
        assert!(!RefineEdges::Auto.wants_pass(MAX_PASSES, Some(1.0)));
        assert!(
            RefineEdges::Passes(2).wants_pass(1, Some(0.0)) && !RefineEdges::Passes(2).wants_pass(2, None)
        );
    }

    /// `Nz` is a zone grading, `N`/`Ne`/`auto` an edge grading, `0z` the uniform level; the
    /// text reads back; anything else names what is allowed.
    #[test]
    fn grading_parses_edges_and_zones() {
        use Grading::{Edges, Zone};
        assert_eq!(Grading::parse("3z"), Ok(Zone(3)));
        assert_eq!(Grading::parse(" 2Z"), Ok(Zone(2)));
        assert_eq!(Grading::parse("0z"), Ok(Grading::default()));
        assert_eq!(Grading::parse("2e"), Ok(Edges(RefineEdges::Passes(2))));
        assert_eq!(Grading::parse("2"), Ok(Edges(RefineEdges::Passes(2))));
        assert_eq!(Grading::parse("auto"), Ok(Edges(RefineEdges::Auto)));
        for g in [Zone(3), Edges(RefineEdges::Passes(2)), Edges(RefineEdges::Auto)] {
            assert_eq!(Grading::parse(&g.to_string()), Ok(g));
        }
        for bad in ["9z", "z", "-1z", "2ze", "autoz", "1.5z", "ze"] {
            let e = Grading::parse(bad).unwrap_err().to_string();
            assert!(
                e.contains("or 1z to 8z (passes over the contact zone)"),
                "{bad}: {e}"
            );
        }
        assert_eq!(Zone(3).level_label(4, 3), "4+3z");
        assert_eq!(Zone(3).level_label(4, 0), "4");
        assert_eq!(Edges(RefineEdges::Auto).level_label(4, 2), "4+2e");
        assert!(Zone(2).wants_pass(1, Some(0.0)) && !Zone(2).wants_pass(2, Some(1.0)));
        assert!(Zone(1).grades() && !Grading::default().grades());
    }
}
