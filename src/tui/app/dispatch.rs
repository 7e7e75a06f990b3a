//! What a key does to the lab ([`App::key`]): the action it names ([`super::super::keys`]),
//! applied to the settings, the scene or an overlay, with a notice where it changes nothing.

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

use crate::contact::Rule;
use crate::grading::{Grading, RefineEdges};
use crate::mesh::Element;
use crate::scheme::Scheme;
use crate::stress::Quantity;

use super::super::keys::{ExportKind, LabAction, lab_action};
use super::{App, Command, Compare, DEPTH_STEP, EPSILON_RANGE, MAX_APP_LEVEL, Notice, Scene, shift_decades};

impl App {
    pub(super) fn key(&mut self, key: KeyEvent, commands: &mut Vec<Command>) -> bool {
        if !matches!(key.kind, KeyEventKind::Press | KeyEventKind::Repeat) {
            return false;
        }
        let control = key.modifiers.contains(KeyModifiers::CONTROL);
        let action = lab_action(key.code, control);
        if control {
            match action {
                Some(LabAction::Quit) => self.quit = true,
                Some(LabAction::Suspend) => commands.push(Command::Suspend),
                _ => return false,
            }
            return true;
        }
        self.notice = None;
        if self.show_help || self.overlays.show_log {
            // ↑ ↓ (and the page keys) scroll; any other key closes and does nothing else.
            self.scroll_overlay(key.code);
            return true;
        }
        let Some(action) = action else {
            self.notice = Some(Notice::info(format!(
                "{} does nothing here (? lists the keys)",
                key_name(key.code)
            )));
            return true;
        };
        if self.overlays.too_small && action != LabAction::Quit {
            self.notice = Some(Notice::info(format!(
                "{} ignored: the terminal is too small for the lab (q quits)",
                key_name(key.code)
            )));
            return true;
        }
        let before = self.settings;
        match action {
            LabAction::Quit => self.quit = true,
            // The help and the log were closed above (any key closes them).
            LabAction::Back if self.overlays.projector => {
                self.overlays.projector = false;
                self.notice = Some(Notice::info("projector off"));
            }
            LabAction::Back => {
                self.notice = Some(Notice::info("Esc goes back: nothing is open to close (q quits)"));
            }
            LabAction::Help => {
                self.show_help = true;
                self.overlays.help_scroll = 0;
            }
            LabAction::Log => {
                self.overlays.show_log = true;
                self.overlays.log_scroll = 0;
            }
            LabAction::Cursor | LabAction::CursorLeft | LabAction::CursorRight
                if !matches!(self.scene, Scene::Explore | Scene::Stress) =>
            {
                self.notice = Some(Notice::info(format!(
                    "{} does nothing in the {} scene: the cursor is on explore's pressure chart and the stress map",
                    key_name(key.code),
                    self.scene.name()
                )));
            }
            LabAction::Cursor => self.toggle_cursor(),
            LabAction::CursorLeft => self.move_cursor(-1),
            LabAction::CursorRight => self.move_cursor(1),
            LabAction::Projector => {
                self.overlays.projector = !self.overlays.projector;
                self.notice = Some(Notice::info(if self.overlays.projector {
                    "projector: the chart on the whole screen"
                } else {
                    "projector off"
                }));
            }
            LabAction::Coarser => {
                if self.settings.level == 0 {
                    self.notice = Some(Notice::info("level 0 is the coarsest mesh"));
                }
                self.settings.level = self.settings.level.saturating_sub(1);
            }
            LabAction::Finer => {
                if self.settings.level >= MAX_APP_LEVEL {
                    self.notice = Some(Notice::info(format!(
                        "level {MAX_APP_LEVEL} is the lab's finest: level 8 takes seconds and GiB (riplab solve)"
                    )));
                }
                self.settings.level = (self.settings.level + 1).min(MAX_APP_LEVEL);
            }
            LabAction::Reset => {
                self.settings = App::defaults(&self.scenario);
                self.guides = super::Guides::default();
                self.all_levels = false;
                self.zoom = false;
                self.notice = Some(Notice::info("reset to the scenario's settings"));
            }
            LabAction::NextRule => {
                let i = Rule::ALL
                    .iter()
                    .position(|&r| r == self.settings.rule)
                    .unwrap_or(0);
                self.settings.rule = Rule::ALL[(i + 1) % Rule::ALL.len()];
            }
            LabAction::NextElement => {
                let all = Element::ALL;
                let i = all.iter().position(|&e| e == self.settings.element).unwrap_or(0);
                self.settings.element = all[(i + 1) % all.len()];
            }
            LabAction::Scheme(m) => {
                if let Some(s) = Scheme::paper(m) {
                    self.settings.element = s.element;
                    self.settings.rule = s.rule;
                }
            }
            LabAction::NextMethod => self.settings.method = self.settings.method.next(),
            LabAction::Compare => {
                self.compare = match self.compare {
                    Compare::Schemes => Compare::Methods,
                    Compare::Methods => Compare::Schemes,
                };
                if self.scene != Scene::Convergence {
                    self.notice = Some(Notice::info(match self.compare {
                        Compare::Schemes => "the convergence scene compares M1–M4 (Tab to it)",
                        Compare::Methods => "the convergence scene compares the methods (Tab to it)",
                    }));
                }
            }
            LabAction::EpsilonUp => self.shift_epsilon(1),
            LabAction::EpsilonDown => self.shift_epsilon(-1),
            LabAction::Shallower => self.shift_depth(-DEPTH_STEP),
            LabAction::Deeper => self.shift_depth(DEPTH_STEP),
            LabAction::NextScene => self.scene = self.scene.shifted(1),
            LabAction::PreviousScene => self.scene = self.scene.shifted(Scene::ALL.len() - 1),
            LabAction::Guide(guide) => self.toggle_guide(guide),
            LabAction::Zoom => self.toggle_zoom(),
            LabAction::NextLaw => self.next_law(),
            LabAction::FrictionUp => self.step_friction(true),
            LabAction::FrictionDown => self.step_friction(false),
            LabAction::ShiftUp => self.step_shift(true),
            LabAction::ShiftDown => self.step_shift(false),
            LabAction::Grade => {
                let next = next_grading(self.settings.refine_edges);
                if next.grades() && self.settings.friction.is_on() {
                    // Refused before anything changes: the header keeps the grading it shows.
                    self.notice = Some(Notice::failure(
                        "E: grading (at the edges or over the zone) does not take friction yet; F to friction none first",
                    ));
                } else {
                    self.settings.refine_edges = next;
                    self.notice = Some(Notice::info(grading_notice(next)));
                }
            }
            LabAction::Integration => self.switch_integration(),
            LabAction::AllLevels => self.all_levels_key(),
            LabAction::NextQuantity => {
                self.stress_quantity = self.stress_quantity.next();
                let name = match self.stress_quantity {
                    Quantity::PrincipalShear => "τ₁, the principal shear stress",
                    Quantity::VonMises => "von Mises σ_vM",
                    Quantity::SigmaYy => "σ_yy",
                };
                self.notice = Some(Notice::info(if self.scene == Scene::Stress {
                    format!("the stress map shows {name}")
                } else {
                    format!("the stress scene will show {name} (Tab to it)")
                }));
            }
            LabAction::Export(ExportKind::TourStep) => {
                // The lab's state, solved or not: written by the runtime (a tour file).
                self.export_kind = ExportKind::TourStep;
                commands.push(Command::Export);
            }
            LabAction::Export(kind) => {
                if self.current().is_some() {
                    self.export_kind = kind;
                    commands.push(Command::Export);
                } else {
                    self.notice = Some(Notice::info("nothing to export yet: the solve is not finished"));
                }
            }
            LabAction::NextContact
            | LabAction::RatioDown
            | LabAction::RatioUp
            | LabAction::OffsetDown
            | LabAction::OffsetUp => {
                self.notice = Some(Notice::info(format!(
                    "{} acts on two bodies (a scenario with [upper], e.g. scenarios/patch-two-blocks.toml); this scenario has one body under a rigid obstacle",
                    key_name(key.code)
                )));
            }
            // Only with Ctrl (above).
            LabAction::Suspend => return false,
        }
        if self.settings != before {
            self.generation += 1;
            self.error = None;
        }
        true
    }

    /// `z`: zoom to the contact zone and back (only where there is one to zoom to), in the
    /// scenes that draw Γ_C's zone (explore's pressure chart and contact zone, the stress
    /// map); elsewhere it says so.
    fn toggle_zoom(&mut self) {
        if !matches!(self.scene, Scene::Explore | Scene::Stress) {
            self.notice = Some(Notice::info(format!(
                "z does nothing in the {} scene: it zooms explore's pressure chart and contact zone, and the stress map",
                self.scene.name()
            )));
            return;
        }
        if self.zoom {
            self.zoom = false;
            self.notice = Some(Notice::info("zoom off: all of Γ_C (z zooms in again)"));
            return;
        }
        let in_contact = self
            .current()
            .is_some_and(|s| s.solution.pbar.iter().any(|&p| p > 0.0));
        if in_contact {
            self.zoom = true;
            self.notice = Some(Notice::info(
                "zoomed to the contact zone, p̄ > 0 (z shows all of Γ_C)",
            ));
        } else {
            self.notice = Some(Notice::info("nothing to zoom to: no contact (p̄ = 0)"));
        }
    }

    /// ε times 10^`decades`, kept to the decimal digits of the scenario's ε.
    fn shift_epsilon(&mut self, decades: i32) {
        let next = shift_decades(self.settings.epsilon, decades);
        if (EPSILON_RANGE.0..=EPSILON_RANGE.1).contains(&next) {
            self.settings.epsilon = next;
        } else {
            self.notice = Some(Notice::info(format!(
                "ε stays within {:e} to {:e}",
                EPSILON_RANGE.0, EPSILON_RANGE.1
            )));
        }
    }

    /// The depth plus `delta`, within 0..=min(R, height)/2, rounded to 1e-9.
    fn shift_depth(&mut self, delta: f64) {
        let max = self.max_depth();
        let next = ((self.settings.depth + delta) * 1e9).round() / 1e9;
        if (0.0..=max + 1e-12).contains(&next) {
            self.settings.depth = next;
        } else {
            self.notice = Some(Notice::info(format!("depth stays within 0 to {max}")));
        }
    }

    /// `a`: in explore, the inf-sup estimate at every level up to this one, or at this one
    /// only; in every scene, say what that computes (or why nothing is left to compute).
    fn all_levels_key(&mut self) {
        self.all_levels = !self.all_levels;
        if !matches!(self.scene, Scene::Explore | Scene::InfSup) {
            let state = if self.all_levels { "on" } else { "off" };
            self.notice = Some(Notice::info(format!(
                "inf-sup at every level up to this one: {state} (explore's inf-sup panel)"
            )));
            return;
        }
        let levels = self.infsup_levels();
        let (lo, hi) = (*levels.start(), *levels.end());
        let mut keys = self.infsup_needed();
        keys.sort_by_key(|k| (k.level, k.element.name(), k.rule.name()));
        keys.dedup();
        let total = keys.len();
        let done = keys.iter().filter(|k| self.infsup.contains_key(k)).count();
        let what = if lo == hi {
            format!("inf-sup at level {lo} only")
        } else {
            format!("inf-sup at levels {lo} to {hi}")
        };
        let tail = match total - done {
            0 => "all computed; nothing left to compute".to_string(),
            n => format!("{n} of {total} estimates to compute"),
        };
        let scene_note = if self.scene == Scene::InfSup {
            let state = if self.all_levels { "on" } else { "off" };
            format!(" (this scene shows 0 to 4 or more; explore's every level: {state})")
        } else {
            String::new()
        };
        self.notice = Some(Notice::info(format!("{what}: {tail}{scene_note}")));
    }

    /// ↑ ↓ PageUp PageDown scroll the open help or log; any other key closes it.
    pub(super) fn scroll_overlay(&mut self, code: KeyCode) {
        let step: i32 = match code {
            KeyCode::Up => -1,
            KeyCode::Down => 1,
            KeyCode::PageUp => -10,
            KeyCode::PageDown => 10,
            _ => {
                self.show_help = false;
                self.overlays.show_log = false;
                return;
            }
        };
        // The log scrolls up from its newest line, the help down from its first.
        let (scroll, step) = if self.show_help {
            (&mut self.overlays.help_scroll, step)
        } else {
            (&mut self.overlays.log_scroll, -step)
        };
        *scroll = u16::try_from((i32::from(*scroll) + step).max(0)).unwrap_or(u16::MAX);
    }
}

/// A key as the help writes it, for notices.
pub(in crate::tui) fn key_name(code: KeyCode) -> String {
    match code {
        KeyCode::Char(' ') => "Space".into(),
        KeyCode::Char(c) => crate::text::sanitize(&c.to_string()).into_owned(),
        KeyCode::Tab => "Tab".into(),
        KeyCode::BackTab => "Shift-Tab".into(),
        KeyCode::Enter => "Enter".into(),
        KeyCode::Esc => "Esc".into(),
        KeyCode::Left => "←".into(),
        KeyCode::Right => "→".into(),
        KeyCode::Up => "↑".into(),
        KeyCode::Down => "↓".into(),
        other => format!("{other:?}"),
    }
}

/// The grading after `r` in the cycle of `E`: 0, 1, 2, 3 edge passes, auto, 1z, 2z, 3z zone
/// passes, 0 (a value beyond the cycle, from a scenario or the command line, goes on to the
/// next kind's first).
fn next_grading(r: Grading) -> Grading {
    use Grading::{Edges, Zone};
    match r {
        Edges(RefineEdges::Passes(n)) if n < 3 => Edges(RefineEdges::Passes(n + 1)),
        Edges(RefineEdges::Passes(_)) => Edges(RefineEdges::Auto),
        Edges(RefineEdges::Auto) => Zone(1),
        Zone(n) if n < 3 => Zone(n + 1),
        Zone(_) => Grading::default(),
    }
}

/// What `E` says it did.
fn grading_notice(r: Grading) -> String {
    let passes = |n: u32| format!("{n} pass{}", if n == 1 { "" } else { "es" });
    match r {
        Grading::Edges(RefineEdges::Passes(0)) => "grading off: the uniform level".into(),
        Grading::Edges(RefineEdges::Passes(n)) => format!(
            "edge grading: {} bisecting the lines around each contact edge, each solved again",
            passes(n)
        ),
        Grading::Edges(RefineEdges::Auto) => {
            "edge grading auto: passes until p̄ changes by under 1e-3 (at most 8)".into()
        }
        Grading::Zone(n) => format!(
            "zone grading: {} halving Γ_C's cells over the whole contact zone, each solved again",
            passes(n)
        ),
    }
}
