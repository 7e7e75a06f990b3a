//! What a key does in the two-body scene ([`BodiesApp::dispatch`]): the action the lab's key
//! table names ([`crate::tui::keys::lab_action`]), applied to the level, the discretisation,
//! the element ratio or the offset, or to the view shown (Tab, Shift-Tab: the pressure or the
//! inf-sup view); a key whose action has no meaning for two bodies is refused with the reason
//! on the status line, never ignored in silence.

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use super::super::app::{MAX_APP_LEVEL, key_name};
use super::super::bodies_solve::{MAX_OFFSET, OFFSET_STEP, ratios};
use super::super::keys::{LabAction, lab_action};
use super::super::protocol::Notice;
use super::{BodiesApp, BodiesView};
use crate::contact::interface::InterfaceMethod;

impl BodiesApp {
    /// Apply `key`; whether the screen changed.
    pub(super) fn dispatch(&mut self, key: KeyEvent) -> bool {
        if !matches!(key.kind, KeyEventKind::Press | KeyEventKind::Repeat) {
            return false;
        }
        let control = key.modifiers.contains(KeyModifiers::CONTROL);
        let action = lab_action(key.code, control);
        if control {
            // Ctrl-Z is the runtime's (it reads the key before the scene does).
            if action == Some(LabAction::Quit) {
                self.quit = true;
            }
            return action.is_some();
        }
        self.notice = None;
        if self.show_help {
            match key.code {
                KeyCode::Up => self.help_scroll = self.help_scroll.saturating_sub(1),
                KeyCode::Down => self.help_scroll = self.help_scroll.saturating_add(1),
                _ => self.show_help = false,
            }
            return true;
        }
        let name = key_name(key.code);
        let Some(action) = action else {
            self.notice = Some(Notice::info(format!(
                "{name} does nothing here (? lists the keys)"
            )));
            return true;
        };
        if self.too_small && action != LabAction::Quit {
            self.notice = Some(Notice::info(format!(
                "{name} ignored: the terminal is too small for the lab (q quits)"
            )));
            return true;
        }
        match action {
            LabAction::Quit => self.quit = true,
            LabAction::Help => {
                self.show_help = true;
                self.help_scroll = 0;
            }
            LabAction::Back => {
                self.notice = Some(Notice::info("Esc goes back: nothing is open to close (q quits)"));
            }
            LabAction::Coarser if self.settings.level == 0 => {
                self.notice = Some(Notice::info("level 0 is the coarsest mesh"));
            }
            LabAction::Coarser => self.settings.level -= 1,
            LabAction::Finer if self.settings.level >= MAX_APP_LEVEL => {
                self.notice = Some(Notice::info(format!(
                    "level {MAX_APP_LEVEL} is the lab's finest (riplab solve goes further)"
                )));
            }
            LabAction::Finer => self.settings.level += 1,
            LabAction::NextContact => {
                let all = InterfaceMethod::ALL;
                let i = all.iter().position(|&m| m == self.settings.method).unwrap_or(0);
                let at = (i + 1) % all.len();
                self.settings.method = all[at];
                self.notice = Some(Notice::info(format!(
                    "contact {} ({}/{}: n cycles nts … mortar-dual, rip-gauss1 … rip-simpson)",
                    self.settings.method.name(),
                    at + 1,
                    all.len()
                )));
            }
            LabAction::RatioDown | LabAction::RatioUp => self.step_ratio(action == LabAction::RatioUp),
            LabAction::OffsetDown | LabAction::OffsetUp => self.step_offset(action == LabAction::OffsetUp),
            LabAction::Reset => {
                self.settings = self.initial;
                self.notice = Some(Notice::info("reset to the scenario's settings"));
            }
            LabAction::NextScene | LabAction::PreviousScene => self.next_view(),
            LabAction::Suspend => return false,
            other => self.notice = Some(Notice::info(format!("{name}: {}", refusal(other)))),
        }
        true
    }

    /// The other view: the inf-sup view after the pressure's, and back (two views: Tab and
    /// Shift-Tab alike).
    fn next_view(&mut self) {
        self.shown = match self.shown {
            BodiesView::Pressure => BodiesView::InfSup,
            BodiesView::InfSup => BodiesView::Pressure,
        };
        self.notice = Some(Notice::info(match self.shown {
            BodiesView::InfSup => "inf-sup view: β_h as both meshes are refined (Tab: the pressure)",
            BodiesView::Pressure => "the interface pressure (Tab: the inf-sup view)",
        }));
    }

    /// The next (or previous) element ratio of [`ratios`], the scenario's own among them.
    fn step_ratio(&mut self, up: bool) {
        let list = ratios(self.initial.ratio);
        let n = list.len();
        let next = match list.iter().position(|&r| r == self.settings.ratio) {
            Some(i) if up => (i + 1) % n,
            Some(i) => (i + n - 1) % n,
            None => 0,
        };
        self.settings.ratio = list[next];
        let names: Vec<String> = list.iter().map(|(a, b)| format!("{a}:{b}")).collect();
        self.notice = Some(Notice::info(format!(
            "ratio {} upper : lower elements across the interface (k K: {})",
            self.settings.ratio_text(),
            names.join(" ")
        )));
    }

    /// The offset a step up or down, within ±[`MAX_OFFSET`].
    fn step_offset(&mut self, up: bool) {
        let step = if up { OFFSET_STEP } else { -OFFSET_STEP };
        // On the grid of tenths, so that repeated steps land on 0 again.
        let next = ((self.settings.offset + step) / OFFSET_STEP).round() * OFFSET_STEP;
        if next.abs() > MAX_OFFSET + 1e-9 {
            self.notice = Some(Notice::info(format!(
                "offset {} is the end: |offset| < 1/2 of an element (j J step by {OFFSET_STEP})",
                self.settings.offset
            )));
            return;
        }
        self.settings.offset = if next.abs() < 1e-9 { 0.0 } else { next };
        self.notice = Some(Notice::info(format!(
            "offset {} of an upper element: its interior lines shifted (j J)",
            self.settings.offset
        )));
    }
}

/// Why `action` does nothing on two bodies.
fn refusal(action: LabAction) -> &'static str {
    use LabAction as L;
    match action {
        L::Scheme(_) | L::NextRule | L::NextElement => {
            "the one-body scheme, rule and element; on two bodies both meshes take the scenario's element, and n cycles the interface's discretisation (rip's rules among them)"
        }
        L::EpsilonUp | L::EpsilonDown | L::NextMethod => {
            "the two-body scene solves with the scenario's ε (0: the exact multipliers); riplab render --epsilon or riplab solve --epsilon sets another"
        }
        L::Shallower | L::Deeper => {
            "the depth is the rigid obstacle's; two bodies are pressed by the upper body's [upper] displacement"
        }
        L::Compare | L::NextQuantity => {
            "the mesh, convergence and stress scenes need one body under a rigid obstacle; two bodies have the pressure and the inf-sup views (Tab)"
        }
        L::AllLevels => "the two-body inf-sup view (Tab) estimates every level up to the current one already",
        L::Guide(_) => {
            "the overlays (gap, Hertz, circle, Mindlin) are the one-body chart's; the patch test's applied pressure is drawn here as its reference line"
        }
        L::NextLaw | L::FrictionUp | L::FrictionDown | L::ShiftUp | L::ShiftDown => {
            "friction is not available on two bodies yet"
        }
        L::Grade => "grading is not available on two bodies yet",
        L::Integration => "the two-body scene keeps the scenario's volumetric integration",
        L::Export(_) => {
            "no exports from the two-body scene yet: riplab solve --format json writes its numbers"
        }
        L::Zoom | L::Cursor | L::CursorLeft | L::CursorRight | L::Projector | L::Log => {
            "not in the two-body scene yet (the one-body scenes have it)"
        }
        // Acted on by the scene itself.
        L::Quit
        | L::Back
        | L::Help
        | L::Coarser
        | L::Finer
        | L::NextContact
        | L::RatioDown
        | L::RatioUp
        | L::OffsetDown
        | L::OffsetUp
        | L::Reset
        | L::NextScene
        | L::PreviousScene
        | L::Suspend => "",
    }
}
