//! How many times a solve grades its mesh at the contact edges (issue 35): the value of
//! `--refine-edges N|auto` and of a scenario's `[mesh] refine_edges`, the grading itself being
//! [`crate::grading`]'s.

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

/// A refine-edges value that is neither `auto` nor a pass count in range.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("`{given}` is not a number of edge-grading passes; allowed: 0 to {MAX_PASSES}, or auto")]
pub struct RefineEdgesError {
    /// The text given (sanitised by the caller before it reaches a terminal).
    pub given: String,
}

impl RefineEdges {
    /// `auto`, or a whole number of passes 0 ..= [`MAX_PASSES`].
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
}
