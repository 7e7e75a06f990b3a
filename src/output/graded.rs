//! How reports show a mesh graded at the contact edges ([`crate::grading`]).

impl super::SolveReport {
    /// The level as the report shows it: `4`, or `4+3e` after three edge-grading passes.
    pub fn level_label(&self) -> String {
        match self.refine_edges {
            0 => self.level.to_string(),
            n => format!("{}+{n}e", self.level),
        }
    }

    /// `, h_min = …` for a graded mesh (empty on a uniform level).
    pub fn h_min_note(&self) -> String {
        match self.refine_edges {
            0 => String::new(),
            _ => format!(", h_min = {}", self.h_min),
        }
    }
}
