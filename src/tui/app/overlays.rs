//! What the lab shows over or instead of its scenes: the help's and the log's scroll, the
//! message log itself (every notice, failure and solver warning since the lab started), the
//! cursor on the pressure chart and the stress map (`x`, moved with `,` and `.`), the
//! projector view (`f`) and whether the terminal is too small for the lab (keys other than
//! `q` ignored then, each saying so).

use std::cell::Cell;
use std::sync::Arc;

use ratatui::layout::Rect;

use super::super::lab_error::LabError;
use super::log::Log;
use super::{App, Notice};

/// The overlays' state ([`App::overlays`]).
#[derive(Clone, Debug, Default)]
pub struct Overlays {
    /// The first line of the help overlay shown (↑ ↓ scroll it).
    pub help_scroll: u16,
    /// The message log is open (`l`).
    pub show_log: bool,
    /// Every message and change of state since the lab started, oldest first, repeats
    /// folded ([`Log`]).
    pub log: Log,
    /// How many lines the log is scrolled up from its newest line.
    pub log_scroll: u16,
    /// The contact point (a vertex of Γ_C, mirrored for a half model: an index into
    /// [`crate::tui::shown::Shown::pbar`]) under the cursor; None when the cursor is hidden.
    pub cursor: Option<usize>,
    /// The projector view: the scene's main chart on the whole screen (`f`).
    pub projector: bool,
    /// The terminal is smaller than the lab's minimum (set by the runtime, and by `render`).
    pub too_small: bool,
    /// The lab is a step of the guided tour: no key bar (the caption panel has the tour's
    /// keys).
    pub in_tour: bool,
    /// Where the last frame put what the mouse can click (set by the view as it draws).
    pub drawn: Cell<Drawn>,
}

/// Where the last frame drew the parts a click acts on, in the frame's cells.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Drawn {
    /// The scene tabs of the header (each ` name `, in [`super::Scene::ALL`]'s order).
    pub tabs: Option<Rect>,
    /// The pressure chart's graph and the x range it spans.
    pub chart: Option<(Rect, [f64; 2])>,
}

impl App {
    /// Append the notice, the failure and the solver's first warning that are new since
    /// `before` (the notice and error then) to the log.
    pub(super) fn log_new_messages(
        &mut self,
        before: (Option<Notice>, Option<LabError>),
        solved_before: bool,
    ) {
        let (notice, error) = before;
        let mut new = Vec::new();
        if let Some(n) = self.notice.as_ref().filter(|n| Some(*n) != notice.as_ref()) {
            new.push((n.failure, n.text.clone()));
        }
        if let Some(e) = self.error.as_ref().filter(|e| Some(*e) != error.as_ref()) {
            new.push((true, e.to_string()));
        }
        if !solved_before && let Some(solved) = &self.solved {
            let key = solved.key;
            new.extend(solved.solution.warnings.iter().map(|w| {
                (
                    false,
                    format!(
                        "⚠ level {} {}+{}: {w}",
                        key.level,
                        key.element.name(),
                        key.rule.name()
                    ),
                )
            }));
        }
        for (failure, text) in new {
            self.overlays.log.message(failure, text);
        }
    }

    /// Whether `solved` is the solution now shown (for [`App::log_new_messages`]).
    pub(super) fn shows(&self, solved: Option<&Arc<super::Solved>>) -> bool {
        match (solved, &self.solved) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (None, None) => true,
            _ => false,
        }
    }

    /// The contact point under the cursor, as (x, p̄) of the solution shown, if the cursor is.
    pub fn cursor_point(&self) -> Option<(f64, f64)> {
        let i = self.overlays.cursor?;
        self.solved.as_ref()?.shown.pbar.get(i).copied()
    }

    /// `x`: show the cursor at p̄'s largest value, or hide it.
    pub(super) fn toggle_cursor(&mut self) {
        if self.overlays.cursor.take().is_some() {
            self.notice = Some(Notice::info("cursor hidden"));
            return;
        }
        let Some(solved) = &self.solved else {
            self.notice = Some(Notice::info("no cursor yet: the solve is not finished"));
            return;
        };
        let pbar = &solved.shown.pbar;
        let peak = (0..pbar.len()).max_by(|&a, &b| pbar[a].1.total_cmp(&pbar[b].1));
        self.overlays.cursor = peak;
        self.notice = Some(Notice::info(
            ", and . move the cursor one contact point; x hides it",
        ));
    }

    /// `,` and `.`: the cursor `by` contact points on (saying why not where it cannot move).
    pub(super) fn move_cursor(&mut self, by: isize) {
        let Some(i) = self.overlays.cursor else {
            self.notice = Some(Notice::info(", and . move the cursor: x shows it first"));
            return;
        };
        let pbar: &[(f64, f64)] = self.solved.as_ref().map_or(&[], |s| &s.shown.pbar);
        // A half model's mirrored points hold x = 0 twice: a step moves to another x.
        let mut next = i.checked_add_signed(by).filter(|&j| j < pbar.len());
        while let Some(j) = next.filter(|&j| pbar[j].0 == pbar[i].0) {
            next = j.checked_add_signed(by).filter(|&k| k < pbar.len());
        }
        match next {
            Some(j) => self.overlays.cursor = Some(j),
            None => {
                self.notice = Some(Notice::info(if by < 0 {
                    "the cursor is at the first contact point"
                } else {
                    "the cursor is at the last contact point"
                }))
            }
        }
    }

    /// Keep the cursor on the solution shown (another mesh has other points): the point
    /// nearest the cursor's x before.
    pub(super) fn follow_cursor(&mut self, x: Option<f64>) {
        let (Some(x), Some(solved)) = (x, &self.solved) else {
            return;
        };
        let pbar = &solved.shown.pbar;
        self.overlays.cursor =
            (0..pbar.len()).min_by(|&a, &b| (pbar[a].0 - x).abs().total_cmp(&(pbar[b].0 - x).abs()));
    }
}
