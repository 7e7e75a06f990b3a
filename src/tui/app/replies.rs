//! What the worker's replies do to the lab ([`App::worker`]): a solve, its stresses or
//! displacement, an inf-sup estimate or a study stored where the scenes read them, or its
//! failure shown.

use super::{App, Response, Scene};

impl App {
    pub(super) fn worker(&mut self, response: Response) -> bool {
        match response {
            Response::Progress { generation, progress } => {
                if self.pending_solve != Some(generation) {
                    return false;
                }
                self.progress = Some(progress);
            }
            Response::Solved { generation, result } => {
                if self.pending_solve != Some(generation) {
                    return false;
                }
                self.pending_solve = None;
                self.progress = None;
                match result {
                    // The user came back to the settings on screen meanwhile: keep them.
                    Ok(solved) if solved.key != self.settings && self.current().is_some() => {}
                    Ok(solved) => {
                        self.solved = Some(solved);
                        self.error = None;
                        self.solved_friction();
                    }
                    Err(e) => {
                        self.failed = Some(self.settings);
                        self.error = Some(e);
                    }
                }
            }
            Response::Displaced { key } => {
                return self.scene.needs_solution() && self.current().is_some_and(|s| s.key == key);
            }
            Response::Stresses { key } => {
                if self.stress_pending == Some(key) {
                    self.stress_pending = None;
                }
                return self.scene == Scene::Stress && self.current().is_some_and(|s| s.key == key);
            }
            Response::StudyPartial { generation, study } => {
                if self.study_pending.as_ref().map(|(g, _)| *g) != Some(generation) {
                    return false;
                }
                self.study_partial = Some(study);
                return self.scene == Scene::Convergence;
            }
            Response::StudyProgress { generation, progress } => {
                if self.study_pending.as_ref().map(|(g, _)| *g) != Some(generation) {
                    return false;
                }
                self.study_progress = Some(progress);
                return self.scene == Scene::Convergence;
            }
            Response::Cancelled { generation } => {
                if self.pending_solve != Some(generation) {
                    return false;
                }
                self.pending_solve = None;
                self.progress = None;
            }
            Response::InfSupProgress { key, progress } => {
                if !self.infsup_pending.contains(&key) {
                    return false;
                }
                self.infsup_progress = Some((key, progress));
                return self.scene == Scene::InfSup;
            }
            Response::InfSup { key, result } => {
                self.infsup_pending.remove(&key);
                if self.infsup_progress.is_some_and(|(k, _)| k == key) {
                    self.infsup_progress = None;
                }
                match result {
                    Some(result) => {
                        self.infsup.insert(key, result);
                    }
                    None => return false,
                }
            }
            Response::Study {
                generation,
                key,
                result,
            } => {
                if self.study_pending.as_ref() != Some(&(generation, key.clone())) {
                    // Superseded by a newer study request: dropped.
                    return false;
                }
                self.study_pending = None;
                self.study_progress = None;
                self.study_partial = None;
                if let Some(result) = result {
                    self.studies.insert(key, result);
                }
            }
        }
        true
    }
}
