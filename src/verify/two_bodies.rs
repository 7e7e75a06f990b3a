//! The contact patch test of two elastic bodies on meshes that do not match (docs/design.md
//! §12): `scenarios/patch-two-blocks.toml`, two blocks on rollers pressed together, whose exact
//! pressure is uniform, p = δ/(H_l/E'_l + H_u/E'_u + ε). Mortar, with standard and dual
//! multipliers, transmits it to round-off at 1:1 with an offset, 2:3 and 5:7; one-pass
//! node-to-segment does not on the non-matching ratios (its master sees the slave's nodal
//! forces, not a uniform pressure), which the case reports as the method's known failure.
//! The same blocks under a uniform pressure q on the upper's top, its descent found so that
//! the interface carries it, give p = q: the patch test as Taylor and Papadopoulos pose it.

use super::{Case, Kind, MAX_VERIFY_LEVEL, Measured};
use crate::contact::interface::InterfaceMethod;
use crate::contact::interface::solve::BodiesError;
use crate::error::{Diagnosis, SolveError};
use crate::fem::Support;
use crate::scenario::Scenario;

/// The case.
pub const CASE: Case = Case {
    name: "patch-two-bodies",
    description: "two blocks on rollers, meshes 1:1 offset, 2:3, 5:7 across the interface, exact multipliers, the upper's top pressed down or under a pressure: mortar and mortar-dual transmit the uniform p, one-pass NTS fails (its known failure)",
    source: "two blocks on rollers carry the uniform σ_yy = −p: p = δ/(H_l/E'_l + H_u/E'_u + ε), E' = E/(1 − ν²) (the contact patch test, Taylor & Papadopoulos 1991; mortar passes it, Puso & Laursen 2004)",
    kind: Kind::ClosedForm,
    default_level: 2,
    max_level: MAX_VERIFY_LEVEL,
    run,
};

/// Where one-pass NTS's failure is documented.
const NTS_SOURCE: &str = "node-to-segment's known failure of the patch test on non-matching meshes (Taylor & Papadopoulos 1991; Zavarise & De Lorenzis 2009): 1 when its patch error exceeds 1e-3";

/// The scenario, embedded.
const PATCH: &str = include_str!("../../scenarios/patch-two-blocks.toml");

/// The pressure on the upper body's top in the case's second form (units of E).
const PRESSURE: f64 = 5.0;

/// The meshes across the interface: (upper, lower) elements and the offset.
const MESHES: [((u32, u32), f64); 3] = [((1, 1), 0.3), ((2, 3), 0.0), ((5, 7), 0.2)];

/// The solver's error of a two-body solve that failed.
pub(super) fn failed(e: BodiesError) -> SolveError {
    match e {
        BodiesError::Solve(e) => e,
        other => SolveError::NotConverged {
            what: "the two-body patch test's solve",
            iterations: 0,
            residual: f64::NAN,
            diagnosis: match other {
                BodiesError::NotConverged(d) => d,
                _ => Diagnosis::Stalled {
                    iterations: 0,
                    residual: f64::NAN,
                },
            },
        },
    }
}

fn run(level: u32) -> Result<Vec<Measured>, SolveError> {
    let base =
        Scenario::parse(PATCH, "<embedded patch-two-blocks.toml>").expect("the embedded scenario is valid");
    let mut out = Vec::new();
    for (ratio, offset) in MESHES {
        let mut scenario = base.clone();
        if let Some(upper) = scenario.upper.as_mut() {
            (upper.ratio, upper.offset) = (ratio, offset);
        }
        let at = if offset == 0.0 {
            format!("{}:{}", ratio.0, ratio.1)
        } else {
            format!("{}:{} offset {offset}", ratio.0, ratio.1)
        };
        let error = |method| -> Result<f64, SolveError> {
            let solved = scenario.solve_bodies(level, method, 0.0).map_err(failed)?;
            Ok(solved.patch.map_or(f64::NAN, |p| p.1))
        };
        for method in [InterfaceMethod::Mortar, InterfaceMethod::MortarDual] {
            out.push(Measured::absolute(
                format!("{} {at}: max |p − p_applied|/p_applied", method.name()),
                error(method)?,
                0.0,
                1e-9,
            ));
        }
        // The same blocks under a pressure on the upper's top (its descent found): p = q.
        let pressed = pressed(&scenario);
        for method in [InterfaceMethod::Mortar, InterfaceMethod::MortarDual] {
            let solved = pressed.solve_bodies(level, method, 0.0).map_err(failed)?;
            out.push(Measured::absolute(
                format!("{} {at}, a pressure on the top: max |p − q|/q", method.name()),
                solved.patch.map_or(f64::NAN, |p| p.1),
                0.0,
                1e-9,
            ));
        }
        if ratio.0 != ratio.1 {
            let nts = error(InterfaceMethod::Nts)?;
            out.push(
                Measured::absolute(
                    format!("nts {at}: fails the patch test (1: its error exceeds 1e-3)"),
                    if nts > 1e-3 { 1.0 } else { 0.0 },
                    1.0,
                    0.0,
                )
                .against(Kind::ClosedForm, NTS_SOURCE),
            );
        }
    }
    Ok(out)
}

/// `scenario` with its upper body's top under the pressure [`PRESSURE`] instead of its
/// displacement: free but for the pin (docs/design.md §12, "A pressure on the top").
fn pressed(scenario: &Scenario) -> Scenario {
    let mut pressed = scenario.clone();
    if let Some(upper) = pressed.upper.as_mut() {
        (upper.pressure, upper.displacement, upper.support) = (Some(PRESSURE), 0.0, Support::Free);
    }
    pressed
}
