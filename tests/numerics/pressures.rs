//! Numeric snapshots of the pressures of the paper's problem (docs/design.md §1) at levels 0 and 1
//! for M1–M4, and the oscillation claim of its Figure 4 as an assertion.

use crate::common::paper_with;
use riplab::scheme::Scheme;
use riplab::solve::solve_scenario;

fn table(scheme: &str, level: u32) -> (String, Vec<f64>, Vec<f64>) {
    let Scheme { element, rule } = Scheme::parse(scheme).unwrap();
    let mut s = paper_with(&[]);
    (s.element, s.rule, s.level) = (element, rule, level);
    let (_, sol) = solve_scenario(&s).unwrap();
    assert!(sol.newton.converged);
    let mut text = format!(
        "{scheme} level {level}: load P = {:.6e}\nvertices: x, u_y, pbar\n",
        sol.load
    );
    for ((x, uy), pb) in sol.points.vertex_x.iter().zip(&sol.vertex_uy).zip(&sol.pbar) {
        text += &format!("{x:>9.5} {uy:>14.5e} {pb:>12.5e}\n");
    }
    text += "points: x, p\n";
    for (q, p) in sol.points.points.iter().zip(&sol.p) {
        text += &format!("{:>9.5} {p:>12.5e}\n", q.x);
    }
    (text, sol.p.clone(), sol.pbar.clone())
}

#[test]
fn snapshots_of_p_and_pbar() {
    for scheme in ["M1", "M2", "M3", "M4"] {
        for level in [0, 1] {
            let (text, _, _) = table(scheme, level);
            snap!(format!("pressures_{scheme}_level{level}"), text);
        }
    }
}

/// Figure 4: on the paper's 128-element mesh the raw M1 pressure oscillates inside the
/// contact zone while the smoothed one decreases monotonically from the centre.
#[test]
fn m1_oscillates_and_smoothing_does_not() {
    let (_, p, pbar) = table("M1", 1);
    let contact_p: Vec<f64> = p.iter().cloned().take_while(|&v| v > 0.0).collect();
    let contact_pbar: Vec<f64> = pbar.iter().cloned().take_while(|&v| v > 0.0).collect();
    assert!(
        crate::common::turns(&contact_p) >= 3,
        "raw p should zig-zag: {contact_p:?}"
    );
    assert_eq!(
        crate::common::turns(&contact_pbar),
        0,
        "p̄ should be monotone: {contact_pbar:?}"
    );
}
