//! How reports show a mesh graded at the contact edges or over the contact zone
//! ([`crate::grading`]).

impl super::SolveReport {
    /// The level as the report shows it: `4`, or `4+3e` after three edge-grading passes
    /// (`4+3z` over the contact zone).
    pub fn level_label(&self) -> String {
        self.grading.level_label(self.level, self.refine_edges)
    }

    /// `, h_min = …` for a graded mesh (empty on a uniform level).
    pub fn h_min_note(&self) -> String {
        match self.refine_edges {
            0 => String::new(),
            _ => format!(", h_min = {}", self.h_min),
        }
    }
}
