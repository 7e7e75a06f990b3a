//! A study's edge grading (issue 35): with the lab's `E` on, the convergence scene's study
//! solves each scheme and method at every level twice, on the uniform level and graded at the
//! contact edges ([`crate::grading`]), the two series drawn side by side.

use crate::refine_edges::RefineEdges;

use super::protocol::StudyKey;

impl StudyKey {
    /// The gradings of its series: the uniform levels, and the key's grading when it grades.
    pub fn gradings(&self) -> Vec<RefineEdges> {
        let mut out = vec![RefineEdges::default()];
        if self.refine_edges.grades() {
            out.push(self.refine_edges);
        }
        out
    }

    /// This study without its graded series (the uniform rows it shares with `self`).
    pub fn ungraded(&self) -> StudyKey {
        StudyKey {
            refine_edges: RefineEdges::default(),
            ..self.clone()
        }
    }

    /// What its graded series are called after the scheme or method: `+2e`, `+auto` (None when
    /// it does not grade).
    pub fn graded_suffix(&self) -> Option<String> {
        graded_suffix(self.refine_edges)
    }
}

/// `+2e` after two passes' grading, `+auto` for `auto` (as a level reads `4+2e`); None for the
/// uniform levels.
pub fn graded_suffix(refine: RefineEdges) -> Option<String> {
    match refine {
        RefineEdges::Passes(0) => None,
        RefineEdges::Passes(n) => Some(format!("+{n}e")),
        other => Some(format!("+{other}")),
    }
}
