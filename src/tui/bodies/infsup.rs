//! The two-body scene's inf-sup view's numbers (docs/design.md §12, "The inf-sup constant
//! across the interface"; docs/lab.md, "Two bodies"): β_h of each multiplier space of the
//! current rule at levels 0 up to the current one (at least [`LEAST_FINEST`]), the two meshes
//! refined at the current element ratio and offset — one level at a time, as `riplab infsup`
//! computes it ([`interface_table`]). Each level's estimate is kept by its level, ratio,
//! offset and rule, so that going back and forth between the views, ratios or offsets never
//! estimates a level twice (the keys' ratios, offsets, rules and levels are finitely many: a
//! few thousand rows at most); only what the view shows is asked for ([`Estimates::request`]).

use crate::contact::Rule;
use crate::contact::interface::InterfaceMethod;
use crate::contact::interface::solve::BodiesError;
use crate::infsup::interface::Space;
use crate::infsup::interface_table::{InterfaceRow, interface_table};
use crate::scenario::Scenario;

use super::super::bodies_solve::Settings;

/// The inf-sup view shows levels 0 up to the current one, and at least up to this.
pub const LEAST_FINEST: u32 = 3;

/// What an estimate of one level depends on besides the level: the element ratio, the
/// offset and the reduced-integration rule whose spaces are estimated (the element is the
/// scenario's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EstimateKey {
    /// Upper elements : lower elements across the interface.
    pub ratio: (u32, u32),
    /// The upper mesh's offset, a fraction of its element.
    pub offset: f64,
    /// The rule of the point space and its p̄.
    pub rule: Rule,
}

impl EstimateKey {
    /// The key of `settings` on `scenario`: the rule of the method when it is a
    /// reduced-integration one, else the scenario's `contact.rule`.
    pub fn of(settings: &Settings, scenario: &Scenario) -> EstimateKey {
        EstimateKey {
            ratio: settings.ratio,
            offset: settings.offset,
            rule: rule_of(settings.method, scenario),
        }
    }

    /// The spaces estimated: mortar's, mortar-dual's, NTS's, the rule's points and its p̄.
    pub fn spaces(&self) -> Vec<Space> {
        Space::with_rules(&[self.rule])
    }
}

/// The rule whose spaces the view shows: `method`'s when it is a reduced-integration one,
/// else `scenario`'s `contact.rule`.
pub fn rule_of(method: InterfaceMethod, scenario: &Scenario) -> Rule {
    match method {
        InterfaceMethod::Rip(rule) => rule,
        _ => scenario.rule,
    }
}

/// The levels the view shows at `level`: 0 up to it, and at least up to [`LEAST_FINEST`].
pub fn shown_levels(level: u32) -> std::ops::RangeInclusive<u32> {
    0..=level.max(LEAST_FINEST)
}

/// One level's estimate: a row per space in [`EstimateKey::spaces`]' order, or why there is
/// none (a level that does not fit the memory says so, [`crate::infsup::interface_table::fits`]).
pub type LevelEstimate = Result<Vec<InterfaceRow>, BodiesError>;

/// β_h of `key`'s spaces at `level` on `scenario` (the scene's, before its settings apply).
pub fn estimate_level(scenario: &Scenario, key: EstimateKey, level: u32) -> LevelEstimate {
    let mut s = scenario.clone();
    s.level = level;
    if let Some(upper) = s.upper.as_mut() {
        upper.ratio = key.ratio;
        upper.offset = key.offset;
    }
    interface_table(&s, &key.spaces(), &[level])
}

/// Levels to estimate for a key, asked of the worker with the generation that tells it when
/// they are no longer shown.
#[derive(Clone, Debug, PartialEq)]
pub struct EstimateJob {
    /// Bumped at each change of what the view wants: the worker gives a job up between levels
    /// once a newer one is made.
    pub generation: u64,
    /// The ratio, offset and rule.
    pub key: EstimateKey,
    /// The levels not kept yet, ascending.
    pub levels: Vec<u32>,
}

/// The estimates kept, and the job asked for.
#[derive(Debug, Default)]
pub struct Estimates {
    kept: Vec<((EstimateKey, u32), LevelEstimate)>,
    asked: Option<EstimateJob>,
    generation: u64,
}

impl Estimates {
    /// The estimate of `key` at `level`, if kept.
    pub fn get(&self, key: EstimateKey, level: u32) -> Option<&LevelEstimate> {
        self.kept.iter().find(|e| e.0 == (key, level)).map(|e| &e.1)
    }

    /// The newest job's generation (the worker gives up any other between levels).
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The levels asked for and not answered yet, ascending: the first is being estimated.
    pub fn waiting(&self, key: EstimateKey) -> &[u32] {
        match &self.asked {
            Some(job) if job.key == key => &job.levels,
            _ => &[],
        }
    }

    /// The job for what the view wants — `key` at `levels`, None when it is not shown — when
    /// some of it is neither kept nor asked for already; a job no longer wanted is given up
    /// (the generation moves on).
    pub fn request(&mut self, wanted: Option<(EstimateKey, Vec<u32>)>) -> Option<EstimateJob> {
        let missing = wanted.map(|(key, levels)| {
            let levels: Vec<u32> = levels
                .into_iter()
                .filter(|&l| self.get(key, l).is_none())
                .collect();
            (key, levels)
        });
        match (missing, &self.asked) {
            (Some((key, levels)), Some(job))
                if job.key == key && levels.iter().all(|l| job.levels.contains(l)) =>
            {
                None
            }
            (Some((key, levels)), _) if !levels.is_empty() => {
                self.generation += 1;
                let job = EstimateJob {
                    generation: self.generation,
                    key,
                    levels,
                };
                self.asked = Some(job.clone());
                Some(job)
            }
            _ => {
                if self.asked.take().is_some() {
                    self.generation += 1;
                }
                None
            }
        }
    }

    /// Keep the estimate of `key` at `level` (whichever job it answers: it stays true).
    pub fn keep(&mut self, key: EstimateKey, level: u32, estimate: LevelEstimate) {
        if let Some(job) = self.asked.as_mut().filter(|j| j.key == key) {
            job.levels.retain(|&l| l != level);
            if job.levels.is_empty() {
                self.asked = None;
            }
        }
        self.kept.retain(|e| e.0 != (key, level));
        self.kept.push(((key, level), estimate));
    }

    /// Whether a job is asked for and not answered in full.
    pub fn busy(&self) -> bool {
        self.asked.is_some()
    }
}
