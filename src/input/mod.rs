//! Scenario files: everything between a TOML file and the model [`Scenario`] (docs/design.md
//! §1). Data flows one way, from here to the model: [`crate::scenario`] knows nothing of TOML.
//!
//! - [`read`]: bounded reading of a scenario or tour file;
//! - `schema`: the TOML schema serde reads;
//! - [`locate`]: the error locator (file, line, column, key, the offending line);
//! - `nesting`: keys nested too deep, refused with their line before the TOML reader;
//! - [`literals`]: numbers as written (underflowing decimals, integers beyond 64 bits),
//!   refused at their key before serde reads them;
//! - `validate`: the schema checked and turned into the model (`upper`: the upper body).
//!
//! Every value is checked against its allowed range ([`crate::check`]); an error names the
//! file, the line and column, the key, the value, and what is allowed.

use std::path::Path;

use crate::scenario::{DEFAULT_SCENARIO, DEFAULT_SOURCE, Scenario};

mod friction;
pub mod literals;
pub mod locate;
mod nesting;
pub mod read;
mod schema;
mod upper;
mod validate;

#[cfg(feature = "tui")]
pub use locate::Locator;
pub use locate::ScenarioError;
pub use read::read_toml;
/// γ₀ as written, read by tour steps too.
#[cfg(feature = "tui")]
pub(crate) use schema::RawGamma0;
/// `refine_edges` as written, read by tour steps too.
#[cfg(feature = "tui")]
pub(crate) use schema::RawRefineEdges;

/// Reading a scenario: from the embedded default, a file or a text.
impl Scenario {
    /// The embedded default: the paper's problem.
    pub fn paper() -> Scenario {
        Scenario::parse(DEFAULT_SCENARIO, DEFAULT_SOURCE).expect("the embedded scenario is valid")
    }

    /// Read and validate a scenario file.
    ///
    /// # Errors
    ///
    /// The file cannot be read or is too large, or as [`Scenario::parse`]'s.
    pub fn load(path: &Path) -> Result<Scenario, ScenarioError> {
        let (file, text) = read_toml(path, "a scenario")?;
        Scenario::parse(&text, &file)
    }

    /// Parse and validate scenario text; `file` names it in errors.
    ///
    /// # Errors
    ///
    /// TOML that does not parse, an unknown key, a value of the wrong type or out of its range:
    /// [`ScenarioError`] names the file, the line, the column and the key.
    pub fn parse(text: &str, file: &str) -> Result<Scenario, ScenarioError> {
        validate::scenario(text, file)
    }
}
