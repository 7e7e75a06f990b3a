//! The two-body scene's discretisations kept between solves (docs/lab.md, "Two bodies"):
//! each body's [`Discretization`] (its mesh, K factorised and the trace compliance) by what
//! it depends on — the lower body by the level alone, the upper body by the level, the
//! element ratio and the offset — so that a change of the discretisation across the
//! interface (`n`) or of the enforcement solves on both bodies as they are, and a change of
//! the ratio or the offset builds the upper body only.
//!
//! While the scene is idle the cache builds what the next keys are likely to ask for
//! ([`BodiesCache::prefetch_ratios`], [`BodiesCache::prefetch_finer`]).
//!
//! Bounded twice: at most [`KEPT`] of each body, and never more than the memory guard allows
//! (docs/design.md §12's bodies are built after [`crate::fem::memory::Sizes::peak_bytes`] is
//! checked against what the process may use: a build refused for its memory drops the least
//! recently used bodies, those the solve needs kept, and tries again).

use std::rc::Rc;

use super::super::app::MAX_APP_LEVEL;
use super::super::bodies_solve::{Settings, Solved, ratios};
use crate::contact::interface::solve::BodiesError;
use crate::discretization::Discretization;
use crate::error::SolveError;
use crate::scenario::Scenario;

/// How many discretisations of each body are kept at most.
pub const KEPT: usize = 4;

/// What the upper body's discretisation depends on: the level, the ratio and the offset.
#[derive(Clone, Copy, Debug, PartialEq)]
struct UpperKey {
    level: u32,
    ratio: (u32, u32),
    offset: f64,
}

impl UpperKey {
    fn of(settings: &Settings) -> UpperKey {
        UpperKey {
            level: settings.level,
            ratio: settings.ratio,
            offset: settings.offset,
        }
    }
}

/// How many discretisations of each body the cache has built (the seam its tests count).
#[cfg(test)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Built {
    /// The lower body's.
    pub lower: usize,
    /// The upper body's.
    pub upper: usize,
}

/// Discretisations by key, the least recently used first.
struct Kept<K> {
    entries: Vec<(K, Rc<Discretization>)>,
}

impl<K: Copy + PartialEq> Kept<K> {
    fn new() -> Self {
        Kept { entries: Vec::new() }
    }

    fn contains(&self, key: K) -> bool {
        self.entries.iter().any(|e| e.0 == key)
    }

    /// The discretisation of `key`, now the most recently used.
    fn take(&mut self, key: K) -> Option<Rc<Discretization>> {
        let i = self.entries.iter().position(|e| e.0 == key)?;
        let entry = self.entries.remove(i);
        let disc = entry.1.clone();
        self.entries.push(entry);
        Some(disc)
    }

    /// Keep `disc` as the most recently used, the least recently used dropped beyond [`KEPT`].
    fn keep(&mut self, key: K, disc: Rc<Discretization>) {
        self.entries.retain(|e| e.0 != key);
        self.entries.push((key, disc));
        if self.entries.len() > KEPT {
            self.entries.remove(0);
        }
    }

    /// Drop the least recently used discretisation other than `pinned`'s; whether there was one.
    fn drop_oldest(&mut self, pinned: Option<K>) -> bool {
        match self.entries.iter().position(|e| Some(e.0) != pinned) {
            Some(i) => {
                self.entries.remove(i);
                true
            }
            None => false,
        }
    }
}

/// The two bodies' discretisations of one two-body scenario, kept between solves.
pub struct BodiesCache {
    scenario: Scenario,
    lower: Kept<u32>,
    upper: Kept<UpperKey>,
    #[cfg(test)]
    built: Built,
}

impl BodiesCache {
    /// An empty cache for the two-body `scenario` (the scene's, before its settings apply).
    pub fn new(scenario: Scenario) -> BodiesCache {
        BodiesCache {
            scenario,
            lower: Kept::new(),
            upper: Kept::new(),
            #[cfg(test)]
            built: Built::default(),
        }
    }

    /// How many discretisations of each body this cache has built.
    #[cfg(test)]
    pub fn built(&self) -> Built {
        self.built
    }

    /// Solve the scene with `settings`, on the bodies kept when they are, building the others;
    /// given up as soon as `cancelled` says so (asked before each body is built — a
    /// factorisation cannot be interrupted, and a body built is kept — and through the
    /// interface's solve, [`Scenario::solve_discretized`]).
    ///
    /// # Errors
    ///
    /// As [`Scenario::discretize_bodies`] and [`Scenario::solve_discretized`], and
    /// [`SolveError::Cancelled`].
    pub fn solve(
        &mut self,
        settings: &Settings,
        cancelled: &dyn Fn() -> bool,
    ) -> Result<Solved, BodiesError> {
        let go_on = || {
            if cancelled() {
                Err(BodiesError::Solve(SolveError::Cancelled))
            } else {
                Ok(())
            }
        };
        let scenario = settings.apply(&self.scenario);
        scenario.upper.as_ref().ok_or(BodiesError::OneBody)?;
        go_on()?;
        let lower = self.lower_body(&scenario, settings)?;
        go_on()?;
        let upper = self.upper_body(&scenario, settings)?;
        let interface =
            scenario.solve_discretized(&lower, &upper, settings.method, settings.enforcement, cancelled)?;
        Ok(Solved::of(settings, &scenario, &lower, &upper, interface))
    }

    /// The lower body at `settings`' level, kept or built.
    fn lower_body(
        &mut self,
        scenario: &Scenario,
        settings: &Settings,
    ) -> Result<Rc<Discretization>, BodiesError> {
        let level = settings.level;
        if let Some(disc) = self.lower.take(level) {
            return Ok(disc);
        }
        let disc = loop {
            match scenario.discretize(level, scenario.element) {
                Err(SolveError::TooLarge { .. }) if self.free(settings) => {}
                built => break built?,
            }
        };
        Ok(self.keep_lower(level, disc))
    }

    /// The upper body at `settings`' level, ratio and offset, kept or built.
    fn upper_body(
        &mut self,
        scenario: &Scenario,
        settings: &Settings,
    ) -> Result<Rc<Discretization>, BodiesError> {
        let key = UpperKey::of(settings);
        if let Some(disc) = self.upper.take(key) {
            return Ok(disc);
        }
        let disc = loop {
            match scenario.discretize_upper(settings.level, scenario.element, 0) {
                Err(SolveError::TooLarge { .. }) if self.free(settings) => {}
                built => break built?.ok_or(BodiesError::OneBody)?,
            }
        };
        Ok(self.keep_upper(key, disc))
    }

    /// Keep `disc`, the lower body at `level`, built just now.
    fn keep_lower(&mut self, level: u32, disc: Discretization) -> Rc<Discretization> {
        #[cfg(test)]
        {
            self.built.lower += 1;
        }
        let disc = Rc::new(disc);
        self.lower.keep(level, disc.clone());
        disc
    }

    /// Keep `disc`, the upper body of `key`, built just now.
    fn keep_upper(&mut self, key: UpperKey, disc: Discretization) -> Rc<Discretization> {
        #[cfg(test)]
        {
            self.built.upper += 1;
        }
        let disc = Rc::new(disc);
        self.upper.keep(key, disc.clone());
        disc
    }

    /// While the scene is idle after a solve of `settings`: build the upper bodies at the
    /// ratios `k` and `K` step to (at this offset), what its next keys are likely to ask for
    /// ([`BodiesCache::build_ahead`]).
    pub fn prefetch_ratios(&mut self, settings: &Settings, stop: &dyn Fn() -> bool) {
        let Some(own) = self.scenario.upper.as_ref().map(|u| u.ratio) else {
            return;
        };
        let list = ratios(own);
        let n = list.len();
        let at = list.iter().position(|&r| r == settings.ratio).unwrap_or(0);
        let ratio = |i: usize| Settings {
            ratio: list[i % n],
            ..*settings
        };
        self.build_ahead(settings, &[ratio(at + n - 1), ratio(at + 1)], stop);
    }

    /// While the scene is idle after a solve of `settings`: build both bodies a level finer
    /// (`→`, up to [`MAX_APP_LEVEL`]; [`BodiesCache::build_ahead`]).
    pub fn prefetch_finer(&mut self, settings: &Settings, stop: &dyn Fn() -> bool) {
        let finer = Settings {
            level: settings.level + 1,
            ..*settings
        };
        if finer.level <= MAX_APP_LEVEL {
            self.build_ahead(settings, &[finer], stop);
        }
    }

    /// Build the bodies of each of `ahead` not kept yet, each only when the memory guard
    /// holds it beside another build of the bodies of `settings`, the current ones
    /// ([`crate::fem::memory::Sizes::peak_bytes`] of both reserved); abandoned as soon as
    /// `stop` says so, asked before each body (a factorisation cannot be interrupted).
    fn build_ahead(&mut self, settings: &Settings, ahead: &[Settings], stop: &dyn Fn() -> bool) {
        let (level, element) = (settings.level, self.scenario.element);
        let current = settings.apply(&self.scenario);
        let reserved = current
            .sizes(level, element)
            .peak_bytes()
            .saturating_add(current.upper_sizes(level, element).map_or(0, |s| s.peak_bytes()));
        for next in ahead {
            let scenario = next.apply(&self.scenario);
            if !self.lower.contains(next.level) {
                if stop() {
                    return;
                }
                let Ok(disc) = scenario.discretize_beside(next.level, element, reserved) else {
                    continue;
                };
                self.keep_lower(next.level, disc);
            }
            let key = UpperKey::of(next);
            if !self.upper.contains(key) {
                if stop() {
                    return;
                }
                if let Ok(Some(disc)) = scenario.discretize_upper(next.level, element, reserved) {
                    self.keep_upper(key, disc);
                }
            }
        }
    }

    /// Drop the least recently used body that a solve of `settings` does not use (the upper
    /// bodies first); whether there was one.
    fn free(&mut self, settings: &Settings) -> bool {
        self.upper.drop_oldest(Some(UpperKey::of(settings))) || self.lower.drop_oldest(Some(settings.level))
    }
}
