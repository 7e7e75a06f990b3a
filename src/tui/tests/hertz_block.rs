//! The lab opens zoomed in on a contact zone too narrow to
//! see on the whole of Γ_C (it opened on a spike at x = 0) and says so; the Hertz overlay reads
//! out a, p₀ and p̄'s relative L² distance from Hertz, a and p₀ checked against Hertz's
//! formulas for the computed load.

use riplab::scenario::Scenario;
use riplab::tui::app::App;
use riplab::tui::engine::Engine;
use riplab::tui::render_app;
use riplab::tui::settle::settle;

const LOOK: riplab::tui::view::Look = riplab::tui::view::Look {
    theme: riplab::tui::theme::Theme { color: false },
    marker: ratatui::symbols::Marker::Braille,
};

fn block() -> Scenario {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/hertz-block.toml");
    Scenario::load(std::path::Path::new(path)).unwrap()
}

#[test]
fn a_narrow_contact_opens_zoomed_and_says_so() {
    let app = App::new(block());
    assert!(app.zoom);
    let notice = app.notice.as_ref().expect("a notice").text.clone();
    assert!(
        notice.contains("opened zoomed in") && notice.contains("z shows all"),
        "{notice}"
    );
    // The paper's contact zone is nearly half of Γ_C: no zoom, no notice.
    let paper = App::new(Scenario::paper());
    assert!(!paper.zoom && paper.notice.is_none());
}

#[test]
fn the_hertz_overlay_reads_out_a_p0_and_the_error() {
    let scenario = block();
    let mut app = App::new(scenario.clone());
    app.show_timing = false;
    app.guides.hertz = true;
    settle(&mut app, &mut Engine::new(scenario.clone()));
    let solved = app.solved.clone().expect("solved");
    // Hertz (plane strain): a² = 4PR(1 − ν²)/(πE), p₀ = 2P/(πa), P the whole body's load.
    let load = 2.0 * solved.solution.load;
    let (e, nu) = (scenario.material.young, scenario.material.poisson);
    let radius = 10.0;
    let a = (4.0 * load * radius * (1.0 - nu * nu) / (std::f64::consts::PI * e)).sqrt();
    let p0 = 2.0 * load / (std::f64::consts::PI * a);
    let frame = render_app(&app, &LOOK, 100, 30);
    let sig = riplab::tui::view::fmt::sig;
    let error = solved.shown.hertz_error.expect("an error against Hertz");
    let legend = format!(
        "Hertz a={} p₀={}, p̄ off {}%",
        sig(a, 3),
        sig(p0, 3),
        sig(100.0 * error, 2)
    );
    assert!(frame.contains(&legend), "`{legend}` in\n{frame}");
    assert!(error > 0.0 && error < 0.02, "{error}");
}
