//! A work–precision study taken from the engine, to run on a thread of its own.

use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::study::{StudyRow, convergence};

use super::super::protocol::{Progress, Study, StudyKey};

/// A work–precision study taken from the engine ([`super::Engine::studying`]), to run anywhere.
pub struct Studying {
    pub(super) scenario: Scenario,
    pub(super) key: StudyKey,
    /// The estimated time of each stage, ms: the reference, then each level.
    pub(super) estimates_ms: Vec<f64>,
    /// The engine's last study: reused if it is this one, replaced by this one when it ends.
    pub(super) kept: Arc<Mutex<Option<Arc<Study>>>>,
}

impl Studying {
    /// Each of the key's schemes with each of its methods at levels 0..=max against the Q2
    /// reference one level finer, at the key's ε (fresh solves, so the timings are
    /// comparable); each stage (the reference, then each level) is announced to `report` with
    /// its estimate. A method a scheme cannot run (`exact` on a rule with a kernel) gives rows
    /// that say why.
    pub fn run(self, report: &mut dyn FnMut(Progress)) -> Result<Arc<Study>, String> {
        let kept = || self.kept.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(study) = kept().as_ref().filter(|s| s.key == self.key) {
            return Ok(study.clone());
        }
        let key = &self.key;
        report(Progress::Study {
            level: None,
            started: Instant::now(),
            estimate_ms: self.estimates_ms[0],
        });
        let dir = crate::cache::default_dir();
        let (reference, _) = crate::cache::reference(&self.scenario, key.reference_level(), dir.as_deref())
            .map_err(|e| e.to_string())?;
        let mut rows = Vec::new();
        for (level, &estimate_ms) in (0..=key.max_level).zip(&self.estimates_ms[1..]) {
            report(Progress::Study {
                level: Some(level),
                started: Instant::now(),
                estimate_ms,
            });
            for &method in &key.methods {
                rows.extend(convergence(
                    &self.scenario,
                    &reference,
                    &key.schemes,
                    &[level],
                    Some(method),
                    key.epsilon,
                ));
            }
        }
        // The key's order: by scheme, then method, then ascending level.
        let scheme_index = |r: &StudyRow| {
            key.schemes
                .iter()
                .position(|&(e, rule)| Scheme::new(e, rule).label() == r.scheme)
        };
        let method_index = |r: &StudyRow| key.methods.iter().position(|m| m.name() == r.method.method);
        rows.sort_by_key(|r| (scheme_index(r), method_index(r), r.level));
        let study = Arc::new(Study {
            key: self.key.clone(),
            rows,
        });
        *kept() = Some(study.clone());
        Ok(study)
    }
}
