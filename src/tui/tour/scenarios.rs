//! The scenario files a tour's steps name, each read and validated once however many steps
//! name it, and shared by those steps: a tour of 200 steps on one 1 MiB scenario reads 1 MiB,
//! not 200, and holds one scenario, not 200 copies. A path is relative to the tour file's
//! directory; a tour read from no file (the embedded one) may name only the scenario files
//! embedded with it ([`super::embedded`]). A scenario of two bodies makes its steps two-body
//! steps ([`super::bodies_step`]).

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use crate::input::ScenarioError;
use crate::scenario::Scenario;

use super::embedded;

/// Why a step's scenario has no answer.
pub(super) enum Unloaded {
    /// The file could not be read or is not a valid scenario.
    Invalid(ScenarioError),
    /// A path in a tour read from no file, naming no embedded scenario.
    NoDirectory,
}

/// The scenarios a tour's steps have named so far, by the path as written.
pub(super) struct StepScenarios<'a> {
    /// Where the paths are relative to (None: the tour was read from no file).
    dir: Option<&'a Path>,
    /// Each path's scenario, validated.
    loaded: HashMap<String, Arc<Scenario>>,
    /// How many scenario files were read and validated.
    reads: usize,
}

impl<'a> StepScenarios<'a> {
    /// None loaded yet; paths relative to `dir`.
    pub(super) fn new(dir: Option<&'a Path>) -> Self {
        StepScenarios {
            dir,
            loaded: HashMap::new(),
            reads: 0,
        }
    }

    /// The scenario at `path`: read and validated the first time it is named, shared after.
    pub(super) fn get(&mut self, path: &str) -> Result<Arc<Scenario>, Unloaded> {
        if let Some(scenario) = self.loaded.get(path) {
            return Ok(Arc::clone(scenario));
        }
        let scenario = match (self.dir, embedded::scenario_text(path)) {
            (Some(dir), _) => Scenario::load(&dir.join(path)),
            (None, Some(text)) => Scenario::parse(text, path),
            (None, None) => return Err(Unloaded::NoDirectory),
        };
        self.reads += 1;
        let scenario = Arc::new(scenario.map_err(Unloaded::Invalid)?);
        self.loaded.insert(path.to_string(), Arc::clone(&scenario));
        Ok(scenario)
    }

    /// How many scenario files were read and validated.
    pub(super) fn reads(&self) -> usize {
        self.reads
    }
}
