//! The one call into the library's inf-sup estimate (docs/design.md §5), kept behind this adapter so
//! that the app does not depend on how the library organises the computation.

use crate::contact::Rule;
use crate::discretization::Discretization;
use crate::error::SolveError;

pub use crate::infsup::InfSup;

/// β_h and β̄_h for `rule` on `disc` (costs about one factorisation).
pub fn estimate(disc: &Discretization, rule: Rule) -> Result<InfSup, SolveError> {
    crate::infsup::inf_sup(disc, rule)
}
