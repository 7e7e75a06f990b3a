//! A study's grading: with the lab's `E` on, the convergence scene's study solves
//! each scheme and method at every level twice, on the uniform level and graded at the
//! contact edges or over the contact zone ([`crate::grading`]), the two series drawn side by
//! side.

use crate::grading::{Grading, RefineEdges};

use super::protocol::StudyKey;

impl StudyKey {
    /// The gradings of its series: the uniform levels, and the key's grading when it grades.
    pub fn gradings(&self) -> Vec<Grading> {
        let mut out = vec![Grading::default()];
        if self.refine_edges.grades() {
            out.push(self.refine_edges);
        }
        out
    }

    /// This study without its graded series (the uniform rows it shares with `self`).
    pub fn ungraded(&self) -> StudyKey {
        StudyKey {
            refine_edges: Grading::default(),
            ..self.clone()
        }
    }

    /// What its graded series are called after the scheme or method: `+2e`, `+auto`, `+3z`
    /// (None when it does not grade).
    pub fn graded_suffix(&self) -> Option<String> {
        graded_suffix(self.refine_edges)
    }
}

/// `+2e` after two passes' grading at the edges, `+3z` after three over the zone, `+auto` for
/// `auto` (as a level reads `4+2e`, `4+3z`); None for the uniform levels.
pub fn graded_suffix(refine: Grading) -> Option<String> {
    match refine {
        Grading::Edges(RefineEdges::Passes(0)) => None,
        Grading::Edges(RefineEdges::Auto) => Some("+auto".into()),
        Grading::Edges(RefineEdges::Passes(n)) | Grading::Zone(n) => Some(format!("+{n}{}", refine.letter())),
    }
}
