//! The lab's two-body scene (docs/design.md §12, docs/lab.md "Two bodies"): a scenario with
//! an elastic `[upper]` body instead of the rigid obstacle, the interface pressure of the
//! chosen discretisation (node-to-segment, mortar, the reduced-integration rules) drawn live
//! as the method, the element ratio and the offset change, so that NTS's pressure starts to
//! oscillate the moment the meshes stop matching while mortar's stays flat (the contact
//! patch test), both meshes drawn deformed under it; Tab shows its inf-sup view instead, β_h of
//! each multiplier space as both meshes are refined at the current ratio and offset
//! ([`infsup`], drawn by [`infsup_view`]). Its state is [`BodiesApp`]; its keys are the lab's table's
//! ([`super::keys::LAB`]), those that have no meaning for two bodies refused with the reason;
//! [`view`] draws it, [`runtime`] runs it with its solves and estimates on a worker thread (the
//! bodies' discretisations kept between solves by [`cache`]), and [`render_bodies`] draws one
//! frame as text for `riplab render`.

pub mod cache;
mod dispatch;
pub mod infsup;
pub mod infsup_view;
mod meshes;
pub mod runtime;

pub mod view;

use crossterm::event::KeyEvent;

use super::RenderError;
use super::app::MAX_APP_LEVEL;
use super::bodies_solve::{Settings, Solved};
use super::protocol::Notice;
use crate::contact::interface::InterfaceMethod;
use crate::contact::interface::solve::BodiesError;
use crate::scenario::Scenario;

/// Which view of the two-body scene is shown (Tab, Shift-Tab).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BodiesView {
    /// The interface pressure over both meshes.
    Pressure,
    /// β_h of each multiplier space against h ([`infsup`]).
    InfSup,
}

/// The two-body scene's state.
#[derive(Debug)]
pub struct BodiesApp {
    /// The scenario as read (two bodies).
    pub scenario: Scenario,
    /// What is asked for now.
    pub settings: Settings,
    /// The scenario's own settings (`0` goes back to them).
    pub initial: Settings,
    /// The newest solve that finished (perhaps of earlier settings while a newer one runs).
    pub solved: Option<Solved>,
    /// Why the solve of the current settings failed.
    pub error: Option<BodiesError>,
    /// The answer to the last key.
    pub notice: Option<Notice>,
    /// The help overlay is open.
    pub show_help: bool,
    /// The help's first line shown.
    pub help_scroll: u16,
    /// The terminal is below the lab's 80×24: only `q` acts.
    pub too_small: bool,
    /// `q` was pressed.
    pub quit: bool,
    /// Bumped at every change of the settings: a reply of an older one is stale.
    pub generation: u64,
    /// The view shown.
    pub shown: BodiesView,
    /// The inf-sup view's estimates, kept, and the job asked for.
    pub infsup: infsup::Estimates,
}

/// A solve for the worker: the generation it answers and the settings.
pub type Request = (u64, Settings);

impl BodiesApp {
    /// The scene on two-body `scenario` with `method` at the scenario's own level, ratio,
    /// offset and ε (None for a one-body scenario). `level` overrides the scenario's, at most
    /// [`MAX_APP_LEVEL`].
    pub fn new(scenario: Scenario, method: InterfaceMethod) -> Option<BodiesApp> {
        let mut settings = Settings::of(&scenario, method)?;
        settings.level = settings.level.min(MAX_APP_LEVEL);
        Some(BodiesApp {
            scenario,
            settings,
            initial: settings,
            solved: None,
            error: None,
            notice: None,
            show_help: false,
            help_scroll: 0,
            too_small: false,
            quit: false,
            generation: 0,
            shown: BodiesView::Pressure,
            infsup: infsup::Estimates::default(),
        })
    }

    /// The first request: the scene's settings.
    pub fn start(&self) -> Request {
        (self.generation, self.settings)
    }

    /// Whether the solve shown is of the current settings (or failed for them).
    pub fn settled(&self) -> bool {
        self.error.is_some() || self.solved.as_ref().is_some_and(|s| s.settings == self.settings)
    }

    /// The worker's answer for `generation`: kept if it is the newest request's.
    pub fn reply(&mut self, generation: u64, result: Result<Solved, BodiesError>) -> bool {
        if generation != self.generation {
            return false;
        }
        match result {
            Ok(solved) => {
                self.solved = Some(solved);
                self.error = None;
            }
            Err(e) => self.error = Some(e),
        }
        true
    }

    /// A key: what it changes, and the solve to ask for — while the pressure is shown, when
    /// the settings changed or the pressure view came back to settings not solved (the
    /// inf-sup view asks for its estimates by [`BodiesApp::infsup_request`]).
    pub fn key(&mut self, key: KeyEvent) -> (bool, Option<Request>) {
        let (before, shown) = (self.settings, self.shown);
        let redraw = self.dispatch(key);
        let changed = self.settings != before;
        if changed {
            self.generation += 1;
            self.error = None;
        }
        if !changed && self.shown == shown {
            return (redraw, None);
        }
        let solve = self.shown == BodiesView::Pressure && (changed || !self.settled());
        (true, solve.then_some((self.generation, self.settings)))
    }

    /// The inf-sup view's key: the current ratio, offset and rule.
    pub fn estimate_key(&self) -> infsup::EstimateKey {
        infsup::EstimateKey::of(&self.settings, &self.scenario)
    }

    /// The estimates to ask for: the levels the inf-sup view shows and has not got, when it is
    /// shown; a job it no longer shows is given up ([`infsup::Estimates::request`]).
    pub fn infsup_request(&mut self) -> Option<infsup::EstimateJob> {
        let wanted = (self.shown == BodiesView::InfSup).then(|| {
            (
                self.estimate_key(),
                infsup::shown_levels(self.settings.level).collect(),
            )
        });
        self.infsup.request(wanted)
    }
}

/// `app` solved synchronously, then `keys` applied one by one, each solved (or, in the
/// inf-sup view, estimated) before the next (what `riplab render` and the tests draw).
///
/// # Errors
///
/// A key that quits.
pub fn settle_bodies(app: &mut BodiesApp, keys: &[KeyEvent]) -> Result<(), RenderError> {
    let mut cache = cache::BodiesCache::new(app.scenario.clone());
    let mut settle = |app: &mut BodiesApp, (generation, settings): Request| {
        let result = cache.solve(&settings, &|| false);
        app.reply(generation, result);
    };
    let estimate = |app: &mut BodiesApp| {
        if let Some(job) = app.infsup_request() {
            for level in job.levels {
                let estimate = infsup::estimate_level(&app.scenario, job.key, level);
                app.infsup.keep(job.key, level, estimate);
            }
        }
    };
    let first = app.start();
    settle(app, first);
    estimate(app);
    for (i, &key) in keys.iter().enumerate() {
        let (_, request) = app.key(key);
        if app.quit {
            return Err(RenderError::Quits { at: i + 1 });
        }
        if let Some(request) = request {
            settle(app, request);
        }
        estimate(app);
    }
    Ok(())
}

/// One frame of the two-body scene as text: `app` settled with `keys` ([`settle_bodies`]),
/// drawn on a `width`×`height` test terminal in `look`; with the failure the frame shows, if
/// any.
///
/// # Errors
///
/// A key that quits.
pub fn render_bodies(
    mut app: BodiesApp,
    keys: &[KeyEvent],
    width: u16,
    height: u16,
    look: &super::view::Look,
) -> Result<(String, Option<BodiesError>), RenderError> {
    settle_bodies(&mut app, keys)?;
    let text = super::render_frame(width, height, |frame| view::view(&app, frame, look));
    Ok((text, app.error))
}
