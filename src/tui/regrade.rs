//! What a graded solve of the lab did with its grid: after an ε, depth, rule or
//! method change with edge grading on, the lab solves on the graded grid it has and keeps it
//! while the contact edges stay inside its refined band ([`crate::grading::GradedGrid::holds_edges`]);
//! otherwise it grades again from the level's uniform solve. The status line says which.

/// How a graded solve came by its grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Regrade {
    /// Graded from the level's uniform solve (no graded grid of these settings before), in
    /// `passes` passes.
    Graded {
        /// The passes made.
        passes: u32,
    },
    /// Solved on the last graded grid, whose band holds the new contact edges: no new grid,
    /// no new factor.
    Kept,
    /// Solved on the last graded grid first; the contact edges had left its band, so graded
    /// again from the level's uniform solve, in `passes` passes.
    Regraded {
        /// The passes made.
        passes: u32,
    },
}

impl Regrade {
    /// What the status line says: `edges inside the band: kept the graded grid`, `edges
    /// moved: re-graded, 2 passes` or `graded: 2 passes`.
    pub fn text(self) -> String {
        let passes = |n: u32| format!("{n} pass{}", if n == 1 { "" } else { "es" });
        match self {
            Regrade::Graded { passes: n } => format!("graded: {}", passes(n)),
            Regrade::Kept => "edges inside the band: kept the graded grid".into(),
            Regrade::Regraded { passes: n } => format!("edges moved: re-graded, {}", passes(n)),
        }
    }
}
