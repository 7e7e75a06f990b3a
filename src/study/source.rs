//! Where a study's reference came from: the JSON's and CSV's `reference.source`,
//! so that a reader of the output (not only of stderr) knows whether its numbers were solved
//! by this run or read from the cache ([`crate::cache`]).

use serde::Serialize;

/// Where the reference's fields came from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ReferenceSource {
    /// Solved by this run.
    #[default]
    Computed,
    /// Read from the cache, checked for meaning ([`crate::cache`]).
    Cache,
}
