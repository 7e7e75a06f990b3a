//! The friction keys (docs/design.md §11, "The lab"): `F` cycles the law none → coulomb →
//! tresca, `u`/`U` step μ through [`MU_STEPS`] (or g by 1.25), `<`/`>` the shift ξ by 1.25.
//! Each says what it did, or why it did nothing: a half model holds Γ_C's u_x (friction needs
//! the full model, `body.model = "full"`), a step at its bound, friction off.

use crate::contact::Method;
use crate::contact::friction::Law;

use super::super::friction_settings::{
    DEFAULT_MU, MU_STEPS, SHIFT_RANGE, THRESHOLD_RANGE, default_shift, label, round3, step_mu, step_scaled,
};
use super::{App, Notice};

/// How a friction key's notice ends while its solve runs.
const RE_SOLVING: &str = " — re-solving";

/// Why a half model takes no friction, and where to find a full one.
pub const HALF_MODEL: &str = "friction needs the full model (body.model = \"full\"): this half model holds u_x = 0 on its symmetry line; open scenarios/cattaneo-mindlin.toml or hertz-paper-full.toml";

impl App {
    /// `F`: the next law; a scenario without `[friction]` switches on with μ =
    /// [`DEFAULT_MU`], g = μ × the shown p̄'s peak, and the shift ξ₀ ([`default_shift`]).
    pub(super) fn next_law(&mut self) {
        if self.scenario.half_model {
            self.notice = Some(Notice::failure(format!("F: {HALF_MODEL}")));
            return;
        }
        let own = self.scenario.friction.law;
        let law = match self.settings.friction.law {
            Law::None => Law::Coulomb {
                mu: own.mu().unwrap_or(DEFAULT_MU),
            },
            Law::Coulomb { mu } => {
                let peak = self.solved.as_ref().map(|s| s.shown.peak).filter(|&p| p > 0.0);
                match own.threshold().or(peak.map(|p| round3(mu.max(DEFAULT_MU) * p))) {
                    Some(threshold) => Law::Tresca { threshold },
                    None => {
                        self.notice = Some(Notice::info(
                            "F: tresca's g is set from the shown pressure's peak: no solve with contact yet",
                        ));
                        return;
                    }
                }
            }
            Law::Tresca { .. } => Law::None,
        };
        if law != Law::None && self.settings.refine_edges.grades() {
            // Refused before anything changes (the solve would refuse it).
            self.notice = Some(Notice::failure(
                "F: friction does not take a graded mesh yet; E back to 0 passes first",
            ));
            return;
        }
        self.settings.friction.law = law;
        if law != Law::None && self.settings.friction.shift == 0.0 {
            let own = self.scenario.friction.shift;
            self.settings.friction.shift = if own != 0.0 { own } else { self.shift_unit() };
        }
        self.say_friction();
    }

    /// `u`/`U`: μ one step of [`MU_STEPS`] down or up, or g ÷ or × 1.25.
    pub(super) fn step_friction(&mut self, up: bool) {
        let key = if up { "U" } else { "u" };
        let young = self.scenario.material.young;
        let law = match self.settings.friction.law {
            Law::None => {
                self.notice = Some(Notice::info(format!(
                    "{key} steps μ (coulomb) or g (tresca): friction is off (F switches it on)"
                )));
                return;
            }
            Law::Coulomb { mu } => match step_mu(mu, up) {
                Some(mu) => Law::Coulomb { mu },
                None => {
                    let end = if up {
                        MU_STEPS[MU_STEPS.len() - 1]
                    } else {
                        MU_STEPS[0]
                    };
                    self.notice = Some(Notice::info(format!(
                        "{key}: μ = {end} ends the lab's list (riplab solve --mu takes any μ ≥ 0)"
                    )));
                    return;
                }
            },
            Law::Tresca { threshold } => {
                let (lo, hi) = (THRESHOLD_RANGE.0 * young, THRESHOLD_RANGE.1 * young);
                match step_scaled(threshold, up, (lo, hi)) {
                    Some(threshold) => Law::Tresca { threshold },
                    None => {
                        self.notice = Some(Notice::info(format!(
                            "{key}: g = {} is at the lab's bound (g from {} to {}, 1e-4 E to E)",
                            crate::text::num(threshold),
                            crate::text::num(lo),
                            crate::text::num(hi)
                        )));
                        return;
                    }
                }
            }
        };
        self.settings.friction.law = law;
        self.say_friction();
    }

    /// `<`/`>`: the shift ξ ÷ or × 1.25 (from 0, `>` sets ξ₀), |ξ| within
    /// [`SHIFT_RANGE`] × ξ₀.
    pub(super) fn step_shift(&mut self, up: bool) {
        let key = if up { ">" } else { "<" };
        if !self.settings.friction.is_on() {
            self.notice = Some(Notice::info(format!(
                "{key} steps the shift after the press: friction is off (F switches it on)"
            )));
            return;
        }
        let unit = self.shift_unit();
        let shift = self.settings.friction.shift;
        let next = if shift == 0.0 {
            up.then_some(unit)
        } else {
            step_scaled(shift, up, (SHIFT_RANGE.0 * unit, SHIFT_RANGE.1 * unit))
        };
        let Some(next) = next else {
            self.notice = Some(Notice::info(format!(
                "{key}: ξ = {} is at the lab's bound (|ξ| from {} to {}: ξ₀/100 to 20 ξ₀)",
                crate::text::num(shift),
                crate::text::num(round3(SHIFT_RANGE.0 * unit)),
                crate::text::num(round3(SHIFT_RANGE.1 * unit))
            )));
            return;
        };
        self.settings.friction.shift = next;
        self.say_friction();
    }

    /// ξ₀ at the lab's depth ([`default_shift`]); with no contact at that depth, 2% of h.
    fn shift_unit(&self) -> f64 {
        default_shift(&self.scenario, self.settings.depth)
            .unwrap_or_else(|| round3(0.02 * self.scenario.h(self.settings.level)))
    }

    /// A friction key's "— re-solving" gives way to the solve's own readout (Q, Q/(μP), the
    /// stick zone) once it arrives; the log keeps it.
    pub(super) fn solved_friction(&mut self) {
        if self.notice.as_ref().is_some_and(|n| n.text.ends_with(RE_SOLVING)) {
            self.notice = None;
        }
    }

    /// What the friction keys set, and what the solve will say of it.
    fn say_friction(&mut self) {
        let f = self.settings.friction;
        let mut text = format!("friction: {}{RE_SOLVING}", label(&f));
        if f.is_on() && matches!(self.settings.method, Method::Nitsche { .. }) {
            text = format!(
                "friction: {} — nitsche takes no friction (m: another method)",
                label(&f)
            );
        } else if !f.is_on() {
            text = format!("friction off{RE_SOLVING}");
        }
        self.notice = Some(Notice::info(text));
    }
}
