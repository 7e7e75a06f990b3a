//! The refusals `riplab render` shares with `solve`, `infsup` and `study`: a frame
//! whose scene has no answer is refused before anything is built, exit 2, as those commands
//! refuse the same request; a failure found while drawing is reported after the frame.

use super::CliError;
use crate::contact::ContactParams;
use crate::scenario::Scenario;
use crate::solve::checks::check_request;
use crate::tui::app::{App, MAX_APP_LEVEL};

/// The request of a `render` frame of `scene` checked as the command that computes it would
/// check it: the solve's parameters ([`check_request`]) and its memory (graded: from its lines,
/// [`crate::grading::estimate`]), an inf-sup estimate's memory ([`crate::infsup::fits`]), a
/// study's contact ([`crate::study::check_contact`]).
pub(super) fn render_request(scenario: &Scenario, scene: &str, epsilon: Option<f64>) -> Result<(), CliError> {
    let (level, element) = (scenario.level, scenario.element);
    // A level beyond the lab's is refused by the frame's own checks.
    if level > MAX_APP_LEVEL {
        return Ok(());
    }
    let method = scenario.method;
    let params = ContactParams {
        rule: scenario.rule,
        method,
        // The lab's ε: an exact scenario lends the penalty the paper's ([`App::defaults`]).
        epsilon: if method.uses_epsilon() {
            epsilon.unwrap_or(App::defaults(scenario).epsilon)
        } else {
            0.0
        },
        obstacle: scenario.obstacle.clone(),
    };
    check_request(scenario, level, element, &params)?;
    // A grading's estimate holds the uniform level's: it speaks first, naming the grading.
    scenario.graded_fits(level, element, scenario.grading(), |_| 0)?;
    scenario.fits_beside(level, element, 0)?;
    match scene {
        "infsup" => crate::infsup::fits(scenario, level, element)?,
        "convergence" => crate::study::check_contact(scenario)?,
        _ => {}
    }
    Ok(())
}
