//! The pressure chart's overlays (docs/lab.md, "Overlays"): the gap −g, Hertz's parabola,
//! the exact circular indenter's pressure and Cattaneo–Mindlin's traction q, each toggled on
//! its own (`g`, `h`, `o`, `M`). The chart draws them under p̄ and as many as its rows hold
//! ([`crate::tui::view::plot::Plot::overlays`]); its legend names the others.

use super::super::keys::Guide;
use super::{App, Notice, Scene};

/// Which overlays are on ([`App::guides`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Guides {
    /// −g (`g`).
    pub gap: bool,
    /// Hertz's pressure (`h`).
    pub hertz: bool,
    /// The exact circle's pressure (`o`).
    pub circle: bool,
    /// Mindlin's q (`M`).
    pub mindlin: bool,
}

impl Guides {
    /// Every overlay on (the tests that draw them all).
    #[cfg(test)]
    pub const ALL: Guides = Guides {
        gap: true,
        hertz: true,
        circle: true,
        mindlin: true,
    };

    /// Whether `guide` is on.
    pub fn on(&self, guide: Guide) -> bool {
        let mut copy = *self;
        *copy.flag(guide)
    }

    fn flag(&mut self, guide: Guide) -> &mut bool {
        match guide {
            Guide::Gap => &mut self.gap,
            Guide::Hertz => &mut self.hertz,
            Guide::Circle => &mut self.circle,
            Guide::Mindlin => &mut self.mindlin,
        }
    }
}

impl Guide {
    /// Its name in the notices.
    pub fn name(self) -> &'static str {
        match self {
            Guide::Gap => "the gap −g",
            Guide::Hertz => "Hertz's pressure (+)",
            Guide::Circle => "the exact circle's pressure (o)",
            Guide::Mindlin => "Mindlin's traction q (*)",
        }
    }
}

impl App {
    /// Why `guide` has no curve on this screen (the obstacle is no cylinder, or, for
    /// Mindlin's traction, there is no friction), if it has none: the lab's keys and a tour's
    /// `overlays` are refused with it.
    pub fn guide_refusal(&self, guide: Guide) -> Option<&'static str> {
        let cylinder = self.scenario.obstacle.hertz_radius().is_some();
        match guide {
            Guide::Hertz | Guide::Circle if !cylinder => {
                Some("no Hertz solution for this obstacle: it needs a cylinder (a radius)")
            }
            Guide::Mindlin if !cylinder || !self.settings.friction.is_on() => {
                Some("no Mindlin traction here: it needs a cylinder and friction (F; a full model)")
            }
            _ => None,
        }
    }

    /// `g`, `h`, `o`, `M`: `guide` on or off, saying so; refused (and said) where the
    /// obstacle or the friction has no such curve. Off always works.
    pub(super) fn toggle_guide(&mut self, guide: Guide) {
        let refusal = if self.guides.on(guide) {
            None
        } else {
            self.guide_refusal(guide)
        };
        if let Some(why) = refusal {
            self.notice = Some(Notice::info(why));
            return;
        }
        let flag = self.guides.flag(guide);
        *flag = !*flag;
        let state = if *flag { "on" } else { "off" };
        let place = if self.scene == Scene::Explore {
            ""
        } else {
            " (drawn on explore's pressure chart)"
        };
        self.notice = Some(Notice::info(format!("{} {state}{place}", guide.name())));
    }
}
