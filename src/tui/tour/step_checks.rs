//! A tour's step checked against its scenario when the tour is read
//! ([`super::Tour::with_scenario`]), as the lab refuses the same settings when the step is
//! played: its friction ([`super::friction_step::check`]), its overlays
//! ([`App::guide_refusal`]), its ε against its level's range, its depth against its scenario's.
//! A two-body step has no friction, overlay or depth (refused when it is parsed,
//! [`super::bodies_step`]): its ε alone is checked.

use crate::check;
use crate::text::sanitize;

use super::super::app::{App, MAX_APP_LEVEL};
use super::super::keys::Guide;
use super::errors::TourError;
use super::{OVERLAYS, Tour, friction_step};

/// Step `i` of `tour` (0-based) checked against its scenario.
pub(super) fn check(tour: &Tour, i: usize) -> Result<(), TourError> {
    let step = &tour.steps[i];
    let file = || sanitize(&tour.source).into_owned();
    let title = || step.title.clone();
    if step.bodies.is_none() {
        one_body(tour, i)?;
    }
    let scenario = tour.scenario_of(i);
    if let Some(epsilon) = step.epsilon.filter(|e| *e > 0.0) {
        let level = step.level.unwrap_or(scenario.level).min(MAX_APP_LEVEL);
        check::epsilon_in(epsilon, scenario.epsilon_range(level)).map_err(|source| TourError::Epsilon {
            file: file(),
            step: i + 1,
            title: title(),
            level,
            source: Box::new(source),
        })?;
    }
    Ok(())
}

/// One-body step `i` of `tour`: its friction, overlays and depth against its scenario.
fn one_body(tour: &Tour, i: usize) -> Result<(), TourError> {
    let step = &tour.steps[i];
    let file = || sanitize(&tour.source).into_owned();
    let title = || step.title.clone();
    let app = tour.app(i);
    friction_step::check(&app).map_err(|source| TourError::Friction {
        file: file(),
        step: i + 1,
        title: title(),
        source,
    })?;
    let guides = [Guide::Gap, Guide::Hertz, Guide::Circle, Guide::Mindlin];
    for (guide, overlay) in guides.into_iter().zip(OVERLAYS) {
        if let Some(why) = app.guide_refusal(guide).filter(|_| step.guides.on(guide)) {
            return Err(TourError::Overlay {
                file: file(),
                step: i + 1,
                title: title(),
                overlay,
                why,
            });
        }
    }
    if let Some(depth) = step.depth {
        let max = App::new(tour.scenario_of(i).clone()).max_depth();
        if depth > max + 1e-12 {
            return Err(TourError::Depth {
                file: file(),
                step: i + 1,
                title: title(),
                depth,
                max,
            });
        }
    }
    Ok(())
}
