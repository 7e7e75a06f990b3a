//! `riplab tour --check FILE`: a validated tour's steps as a table, one line each: the scene,
//! the level, the scheme and the method each step shows (a setting the step leaves out is its
//! scenario's, as [`Tour::app`] makes it), and the title — a two-body step's scene
//! `two-bodies`, its element with the ratio for the scheme and its discretisation across the
//! interface for the method ([`Tour::bodies`]); above it, how many scenario files the steps
//! name (each read once).

use std::fmt::Write as _;

use crate::scheme::Scheme;

use super::Tour;

/// The tour's title, file and steps, as `riplab tour --check` prints them.
pub fn listing(tour: &Tour) -> String {
    let mut out = format!(
        "{}: a valid tour of {} step{}\ntitle: {}\n",
        tour.source,
        tour.steps.len(),
        if tour.steps.len() == 1 { "" } else { "s" },
        tour.title
    );
    if tour.scenario_reads > 0 {
        let _ = writeln!(
            out,
            "scenario files: {} (each read once, however many steps name it)",
            tour.scenario_reads
        );
    }
    out.push('\n');
    let _ = writeln!(
        out,
        "{:>4}  {:<11}  {:>5}  {:<14}  {:<8}  title",
        "step", "scene", "level", "scheme", "method"
    );
    for (i, step) in tour.steps.iter().enumerate() {
        if let Some(bodies) = tour.bodies(i) {
            // The two-body scene: the element and the ratio, the discretisation.
            let s = &bodies.settings;
            let mesh = format!("{} {}", bodies.scenario.element.name(), s.ratio_text());
            let _ = writeln!(
                out,
                "{:>4}  {:<11}  {:>5}  {:<14}  {:<8}  {}",
                i + 1,
                "two-bodies",
                s.level,
                mesh,
                s.method.name(),
                step.title
            );
            continue;
        }
        let app = tour.app(i);
        let s = &app.settings;
        let _ = writeln!(
            out,
            "{:>4}  {:<11}  {:>5}  {:<14}  {:<8}  {}",
            i + 1,
            app.scene.name(),
            s.level,
            Scheme::new(s.element, s.rule).label(),
            s.method.name(),
            step.title
        );
    }
    out
}
