//! Issue 31, item 5, for near-incompressible: the header shows ν and the volumetric
//! integration where locking is the lesson (a selective integration, or ν from 0.495 with the
//! full one), at 80 and 120 columns; the paper's ν = 0.3 with full integration does not.

use riplab::fem::Integration;
use riplab::scenario::Scenario;
use riplab::tui::app::App;
use riplab::tui::render_app;

const LOOK: riplab::tui::view::Look = riplab::tui::view::Look {
    theme: riplab::tui::theme::Theme { color: false },
    marker: ratatui::symbols::Marker::Braille,
};

fn header(scenario: Scenario, width: u16) -> String {
    let frame = render_app(&App::new(scenario), &LOOK, width, 24);
    frame.lines().nth(1).unwrap().to_string()
}

#[test]
fn the_header_shows_nu_and_the_integration_where_locking_is_the_lesson() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios/near-incompressible.toml");
    let scenario = Scenario::load(std::path::Path::new(path)).unwrap();
    assert_eq!(scenario.integration, Integration::Selective);
    for width in [80, 120] {
        let line = header(scenario.clone(), width);
        assert!(line.ends_with("│ ν=0.49 selective"), "{line}");
        assert!(line.chars().count() <= usize::from(width), "{line}");
    }
    let mut locking = Scenario::paper();
    locking.material.poisson = 0.4999999;
    assert!(header(locking, 80).ends_with("│ ν=0.4999999 full"));
    let paper = header(Scenario::paper(), 120);
    assert!(!paper.contains('ν'), "{paper}");
}
