//! A work–precision study taken from the engine, to run on a thread of its own.

use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

use crate::grading::{Grading, RefineEdges};
use crate::scenario::Scenario;
use crate::scheme::Scheme;
use crate::study::{StudyRow, convergence_graded};

use super::super::lab_error::LabError;
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
    /// that say why. With the key's grading on, each level's rows graded so follow its uniform
    /// ones ([`convergence_graded`], as `riplab study --refine-edges 0,N`), timed likewise.
    pub fn run(self, report: &mut dyn FnMut(Progress)) -> Result<Arc<Study>, LabError> {
        self.run_shown(report, &mut |_| {})
    }

    /// [`Studying::run`], each finished level's rows (with those before it) also handed to
    /// `partial` as a study of the levels so far, so that the points appear as computed (a
    /// graded study hands its uniform rows of a level over before its graded ones).
    pub fn run_shown(
        self,
        report: &mut dyn FnMut(Progress),
        partial: &mut dyn FnMut(Arc<Study>),
    ) -> Result<Arc<Study>, LabError> {
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
        let (reference, _) = crate::cache::reference(&self.scenario, key.reference_level(), dir.as_deref())?;
        // The uniform rows of the last study, when it differs from this one only in its
        // grading (an `E` press on the convergence scene): kept, only the graded rows solved.
        let uniform_of = kept().clone().filter(|s| s.key.ungraded() == key.ungraded());
        let gradings = key.gradings();
        let mut rows = Vec::new();
        for (level, &estimate_ms) in (0..=key.max_level).zip(&self.estimates_ms[1..]) {
            report(Progress::Study {
                level: Some(level),
                started: Instant::now(),
                estimate_ms,
            });
            for (g, &grading) in gradings.iter().enumerate() {
                let kept_rows = uniform_of.as_ref().filter(|_| !grading.grades()).map(|s| {
                    s.rows
                        .iter()
                        .filter(|r| r.level == level && !r.grading.grades())
                        .cloned()
                        .collect::<Vec<_>>()
                });
                match kept_rows {
                    Some(kept_rows) => rows.extend(kept_rows),
                    None => {
                        for &method in &key.methods {
                            let solve = || {
                                convergence_graded(
                                    &self.scenario,
                                    &reference,
                                    &key.schemes,
                                    &[level],
                                    (Some(method), key.epsilon),
                                    grading,
                                )
                            };
                            let runs: Vec<Vec<StudyRow>> = (0..TIMED_RUNS).map(|_| solve()).collect();
                            rows.extend(median_times(runs));
                        }
                    }
                }
                if level < key.max_level || g + 1 < gradings.len() {
                    partial(Arc::new(self.ordered(rows.clone())));
                }
            }
        }
        let study = Arc::new(self.ordered(rows));
        *kept() = Some(study.clone());
        Ok(study)
    }
}

impl Studying {
    /// A study of `rows` in the key's order: by scheme, then method, the uniform series before
    /// the graded one, then ascending level.
    fn ordered(&self, mut rows: Vec<StudyRow>) -> Study {
        let key = &self.key;
        let scheme_index = |r: &StudyRow| {
            key.schemes
                .iter()
                .position(|&(e, rule)| Scheme::new(e, rule).label() == r.scheme)
        };
        let method_index = |r: &StudyRow| key.methods.iter().position(|m| m.name() == r.method.method);
        rows.sort_by_key(|r| (scheme_index(r), method_index(r), r.grading.grades(), r.level));
        Study {
            key: key.clone(),
            rows,
        }
    }
}

/// What a level of a study with the grading `refine` costs against its uniform rows alone:
/// a graded row solves the uniform level and then each pass on a finer grid (`auto` counted as
/// three passes; a zone pass as an edge pass), a rough estimate for the time left.
pub(super) fn cost_factor(refine: Grading) -> f64 {
    match refine {
        Grading::Edges(RefineEdges::Passes(n)) | Grading::Zone(n) => 1.0 + f64::from(n + u32::from(n > 0)),
        Grading::Edges(RefineEdges::Auto) => 5.0,
    }
}

/// How many times each row of a study is solved: its time is the median (the chart says
/// so), so that one slow or fast measurement does not reorder the methods.
pub const TIMED_RUNS: usize = 3;

/// The rows of the first run, each with the median of the runs' solve times (the runs solve
/// the same problems: their rows correspond one to one).
fn median_times(mut runs: Vec<Vec<StudyRow>>) -> Vec<StudyRow> {
    let mut rows = runs.remove(0);
    for (i, row) in rows.iter_mut().enumerate() {
        let mut times: Vec<f64> = row.solve_ms.into_iter().collect();
        times.extend(runs.iter().filter_map(|run| run.get(i).and_then(|r| r.solve_ms)));
        times.sort_by(f64::total_cmp);
        row.solve_ms = times
            .get(times.len() / 2)
            .copied()
            .filter(|_| row.solve_ms.is_some());
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Method;
    use crate::study::Status;

    fn row(level: u32, solve_ms: Option<f64>) -> StudyRow {
        StudyRow {
            scheme: "M1".into(),
            element: crate::mesh::Element::Q1,
            rule: "gauss1",
            level,
            h: 1.0,
            epsilon: 1e-6,
            method: Method::Penalty.into(),
            n_dofs: 68,
            refine_edges: 0,
            h_min: 1.0,
            grading: Default::default(),
            status: Status::Ok,
            reason: None,
            epsilon_dominated: false,
            newton_iterations: Some(1),
            outer_iterations: None,
            converged: true,
            solve_ms,
            load: Some(1.0),
            errors: None,
            rates: None,
            warnings: Vec::new(),
        }
    }

    /// Each row's time is the median of its runs' (not the first run's); a row without a
    /// time (not solved) stays without one.
    #[test]
    fn a_rows_time_is_the_median_of_its_runs() {
        let runs = vec![
            vec![row(0, Some(6.75)), row(1, None)],
            vec![row(0, Some(0.62)), row(1, Some(3.0))],
            vec![row(0, Some(1.45)), row(1, Some(4.0))],
        ];
        let rows = median_times(runs);
        assert_eq!(rows[0].solve_ms, Some(1.45));
        assert_eq!(rows[1].solve_ms, None);
    }
}
