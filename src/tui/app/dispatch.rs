//! What a key does to the lab ([`App::key`]): the action it names ([`super::super::keys`]),
//! applied to the settings, the scene or an overlay, with a notice where it changes nothing.

use crossterm::event::{KeyEvent, KeyEventKind, KeyModifiers};

use crate::contact::Rule;
use crate::mesh::Element;
use crate::scheme::Scheme;

use super::super::keys::{ExportKind, LabAction, lab_action};
use super::{
    App, Command, Compare, DEPTH_STEP, EPSILON_RANGE, MAX_APP_LEVEL, Notice, Scene, level_8_cost,
    shift_decades,
};

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
        if self.show_help {
            // Any key closes the help and does nothing else.
            self.show_help = false;
            return true;
        }
        let Some(action) = action else {
            return false;
        };
        let before = self.settings;
        match action {
            LabAction::Quit => self.quit = true,
            LabAction::Help => self.show_help = true,
            LabAction::Coarser => {
                if self.settings.level == 0 {
                    self.notice = Some(Notice::info("level 0 is the coarsest mesh"));
                }
                self.settings.level = self.settings.level.saturating_sub(1);
            }
            LabAction::Finer => {
                if self.settings.level >= MAX_APP_LEVEL {
                    self.notice = Some(Notice::info(format!(
                        concat!(
                            "level {} is the lab's finest: ",
                            level_8_cost!(),
                            " (riplab solve)"
                        ),
                        MAX_APP_LEVEL
                    )));
                }
                self.settings.level = (self.settings.level + 1).min(MAX_APP_LEVEL);
            }
            LabAction::Reset => {
                self.settings = App::defaults(&self.scenario);
                self.show_gap = false;
                self.show_hertz = false;
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
            LabAction::Gap => self.show_gap = !self.show_gap,
            LabAction::Hertz => {
                if self.scenario.obstacle.hertz_radius().is_some() || self.show_hertz {
                    self.show_hertz = !self.show_hertz;
                } else {
                    self.notice = Some(Notice::info(
                        "no Hertz solution for this obstacle: it needs a cylinder (a radius)",
                    ));
                }
            }
            LabAction::Zoom => self.toggle_zoom(),
            LabAction::AllLevels => self.all_levels = !self.all_levels,
            LabAction::NextQuantity => self.stress_quantity = self.stress_quantity.next(),
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
            // Only with Ctrl (above).
            LabAction::Suspend => return false,
        }
        if self.settings != before {
            self.generation += 1;
            self.error = None;
        }
        true
    }

    /// `z`: zoom to the contact zone and back (only where there is one to zoom to).
    fn toggle_zoom(&mut self) {
        if self.zoom {
            self.zoom = false;
            return;
        }
        if !matches!(self.scene, Scene::Explore | Scene::Mesh | Scene::Stress) {
            self.notice = Some(Notice::info(
                "z zooms the pressure chart, the contact zone and the stress map: explore, mesh and stress scenes",
            ));
            return;
        }
        let in_contact = self
            .current()
            .is_some_and(|s| s.solution.pbar.iter().any(|&p| p > 0.0));
        if in_contact {
            self.zoom = true;
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
}
