//! Two elastic bodies on meshes that need not match (docs/design.md §12), judged by the
//! contact patch test of scenarios/patch-two-blocks.toml: its exact pressure is uniform,
//! p = δ/(H_l/E'_l + H_u/E'_u + ε) (E' = E/(1 − ν²), plane strain), by hand.

use std::path::Path;

use riplab::contact::Rule;
use riplab::contact::interface::InterfaceMethod;
use riplab::mesh::Element;
use riplab::scenario::Scenario;

fn patch() -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/patch-two-blocks.toml");
    Scenario::load(&path).unwrap()
}

/// `patch` at `ratio` and `offset`, solved at `level` by `method` with ε: its patch error.
fn patch_error(ratio: (u32, u32), offset: f64, level: u32, method: InterfaceMethod, epsilon: f64) -> f64 {
    patch_error_with(Element::Q1, ratio, offset, level, method, epsilon)
}

/// [`patch_error`] with `element` in both bodies.
fn patch_error_with(
    element: Element,
    ratio: (u32, u32),
    offset: f64,
    level: u32,
    method: InterfaceMethod,
    epsilon: f64,
) -> f64 {
    let mut s = patch();
    s.element = element;
    let upper = s.upper.as_mut().unwrap();
    (upper.ratio, upper.offset) = (ratio, offset);
    let solved = s.solve_bodies(level, method, epsilon).unwrap();
    let (exact, error) = solved.patch.unwrap();
    assert!(error.is_finite() && exact > 0.0);
    // The load carried is the exact pressure over the half width (1.5) whenever p is uniform.
    if error < 1e-10 {
        assert!(
            (solved.solution.load - 1.5 * exact).abs() < 1e-9 * exact,
            "P = {}",
            solved.solution.load
        );
    }
    error
}

/// The scenario's closed form by hand: 0.01/(1/1098.90… + 0.5/520.833…) = 5.347593…
#[test]
fn the_patch_scenarios_pressure_by_hand() {
    let s = patch();
    let e_lower = 1000.0 / (1.0 - 0.3 * 0.3);
    let e_upper = 500.0 / (1.0 - 0.2 * 0.2);
    let p = 0.01 / (1.0 / e_lower + 0.5 / e_upper);
    assert!((s.patch_pressure(0.0).unwrap() - p).abs() < 1e-12 * p);
    assert!((p - 5.347_593_582_887_7).abs() < 1e-9);
    let eps = 1e-4;
    assert!((s.patch_pressure(eps).unwrap() - 0.01 / (1.0 / e_lower + 0.5 / e_upper + eps)).abs() < 1e-12);
}

/// Mortar, standard and dual, passes the patch test to round-off at 1:1 with an offset, 2:3
/// and 5:7, levels 0–4, with the exact multipliers and with the penalty.
#[test]
fn mortar_passes_the_patch_test() {
    for method in [InterfaceMethod::Mortar, InterfaceMethod::MortarDual] {
        for (ratio, offset) in [((1, 1), 0.3), ((2, 3), 0.0), ((5, 7), 0.2)] {
            for level in 0..=4 {
                let e = patch_error(ratio, offset, level, method, 0.0);
                assert!(
                    e <= 1e-10,
                    "{} {ratio:?} offset {offset} level {level}: {e:e}",
                    method.name()
                );
            }
            let e = patch_error(ratio, offset, 2, method, 1e-4);
            assert!(e <= 1e-10, "{} {ratio:?} penalty: {e:e}", method.name());
        }
    }
}

/// So do the other elements: Q2 (quadratic edges, Simpson's weights) and P1, at levels 0–2.
#[test]
fn mortar_passes_the_patch_test_with_q2_and_p1() {
    for element in [Element::Q2, Element::P1] {
        for method in [InterfaceMethod::Mortar, InterfaceMethod::MortarDual] {
            for (ratio, offset) in [((1, 1), 0.3), ((2, 3), 0.0), ((5, 7), 0.2)] {
                for level in 0..=2 {
                    let e = patch_error_with(element, ratio, offset, level, method, 1e-5);
                    let what = format!("{element:?} {} {ratio:?} level {level}", method.name());
                    assert!(e <= 1e-10, "{what}: {e:e}");
                }
            }
        }
    }
}

/// One-pass node-to-segment fails it on non-matching meshes (its master sees the slave's
/// nodal forces, not a uniform pressure); two-pass NTS and the reduced-integration rules are
/// reported (finite), not graded.
#[test]
fn node_to_segment_fails_the_patch_test() {
    for ratio in [(2, 3), (5, 7)] {
        for level in 0..=2 {
            let e = patch_error(ratio, 0.0, level, InterfaceMethod::Nts, 0.0);
            assert!(e > 1e-3, "nts {ratio:?} level {level}: {e:e}");
        }
        let others = [
            (InterfaceMethod::Nts2, 1e-4),
            (InterfaceMethod::Rip(Rule::Gauss1), 1e-4),
            (InterfaceMethod::Rip(Rule::Gauss2), 1e-4),
            (InterfaceMethod::Rip(Rule::Trapezoid), 1e-4),
            (InterfaceMethod::Rip(Rule::Simpson), 1e-4),
        ];
        for (method, epsilon) in others {
            let e = patch_error(ratio, 0.0, 1, method, epsilon);
            eprintln!(
                "{} {ratio:?} level 1, ε = {epsilon:e}: patch error {e:.3e}",
                method.name()
            );
        }
    }
}

/// scenarios/hertz-two-bodies.toml: an elastic cylinder (R = 10) on an elastic block, meshes
/// 3:2 across the contact, the exact multipliers at level 2 (lower h = 1/8, upper 1/12):
/// against two-body Hertz of the computed load (Johnson §4.2: 1/E* = (1 − ν₁²)/E₁ +
/// (1 − ν₂²)/E₂, a² = 4PR/(πE*), p₀ = 2P/(πa), P the full load, twice the half model's),
/// mortar's peak pressure is within 1% of p₀ (measured 0.20%, dual 0.10%) and its contact
/// ends within one upper cell of a; one-pass NTS's peak is printed (2.5% high).
#[test]
fn two_body_hertz_at_level_2() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hertz-two-bodies.toml");
    let s = Scenario::load(&path).unwrap();
    let upper = s.upper.as_ref().unwrap();
    let radius = upper.shape.radius().unwrap();
    let e_star = 1.0
        / ((1.0 - s.material.poisson.powi(2)) / s.material.young
            + (1.0 - upper.material.poisson.powi(2)) / upper.material.young);
    for method in [
        InterfaceMethod::Mortar,
        InterfaceMethod::MortarDual,
        InterfaceMethod::Nts,
    ] {
        let solved = s.solve_bodies(2, method, 0.0).unwrap();
        let sol = &solved.solution;
        let load = 2.0 * sol.load;
        let a = (4.0 * load * radius / (std::f64::consts::PI * e_star)).sqrt();
        let p0 = 2.0 * load / (std::f64::consts::PI * a);
        let peak = sol.p.iter().fold(0.0_f64, |m, &p| m.max(p));
        let last = (0..sol.p.len()).rev().find(|&k| sol.p[k] > 0.0).unwrap();
        let (inside, outside) = (sol.x[last], sol.x[last + 1]);
        eprintln!(
            "{}: P = {load:.4}, a = {a:.4} (contact ends in [{inside:.4}, {outside:.4}]), p0 = {p0:.4}, peak {peak:.4} ({:+.2}%)",
            method.name(),
            100.0 * (peak / p0 - 1.0)
        );
        if method != InterfaceMethod::Nts {
            assert!(
                (peak / p0 - 1.0).abs() < 0.01,
                "{}: peak {peak} against p0 {p0}",
                method.name()
            );
            let cell = solved.upper.mesh().h();
            assert!(
                inside < a + cell && outside > a - cell,
                "{}: a = {a}, [{inside}, {outside}]",
                method.name()
            );
        }
    }
}

/// A small press is answered as a large one, scaled: at δ = 1e-12 (and 1e-30) the exact
/// multipliers carry the patch test's uniform pressure to 1e-10 (before, the exact solver
/// took zero forces as converged whenever the penetration's forces were below its tolerance
/// in force units: P = 0, patch error 1). A lifted top (δ < 0) is no patch test: no
/// p_applied, no patch error (it printed p_applied = −5.35, patch error 0).
#[test]
fn a_small_press_is_solved_and_a_lift_is_no_patch_test() {
    for delta in [1e-12, 1e-30] {
        let mut s = patch();
        s.upper.as_mut().unwrap().displacement = delta;
        let solved = s.solve_bodies(1, InterfaceMethod::Mortar, 0.0).unwrap();
        let (exact, error) = solved.patch.unwrap();
        assert!(error < 1e-10, "δ = {delta}: patch error {error}");
        assert!(
            (solved.solution.load - 1.5 * exact).abs() < 1e-9 * exact,
            "δ = {delta}"
        );
    }
    let mut s = patch();
    s.upper.as_mut().unwrap().displacement = -0.01;
    assert_eq!(s.patch_pressure(0.0), None);
    let solved = s.solve_bodies(1, InterfaceMethod::Mortar, 0.0).unwrap();
    assert!(solved.patch.is_none() && solved.solution.load == 0.0);
}

/// The ALM across the interface reaches the exact multipliers' answer: at ε = 1e-4 (a
/// penalty whose patch pressure is 0.1 % soft) mortar's updates carry the exact uniform p at
/// 2:3 to 1e-9, where the penalty alone stays soft by its closed form; NTS's multipliers
/// equal the exact ones to 1e-8 (its own answer, not a uniform one).
#[test]
fn the_alm_across_the_interface_reaches_the_exact_multipliers() {
    use riplab::contact::interface::solve::Enforcement;
    let mut s = patch();
    s.upper.as_mut().unwrap().ratio = (2, 3);
    let alm = Enforcement::Alm {
        epsilon: 1e-4,
        tolerance: 1e-12,
    };
    let solved = s.solve_bodies(2, InterfaceMethod::Mortar, alm).unwrap();
    let (exact, error) = solved.patch.unwrap();
    assert!((exact - 5.347_593_582_887_7).abs() < 1e-9, "{exact}");
    assert!(error < 1e-9, "patch error {error:e}");
    let updates = solved.solution.outer_iterations.unwrap();
    assert!((2..=20).contains(&updates), "{updates} updates");
    // The penalty at the same ε: soft by ε against H_l/E'_l + H_u/E'_u = 1.87e-3, to round-off.
    let penalty = s.solve_bodies(2, InterfaceMethod::Mortar, 1e-4).unwrap();
    let soft = s.patch_pressure(1e-4).unwrap();
    assert!(penalty.solution.p.iter().all(|p| (p - soft).abs() < 1e-10 * soft));
    assert!((soft / exact - 1.0).abs() > 1e-2);
    let nts_exact = s.solve_bodies(2, InterfaceMethod::Nts, 0.0).unwrap().solution;
    let nts_alm = s.solve_bodies(2, InterfaceMethod::Nts, alm).unwrap().solution;
    for (a, b) in nts_alm.p.iter().zip(&nts_exact.p) {
        assert!((a - b).abs() < 1e-8 * exact, "{a} vs {b}");
    }
}

/// An upper block narrower than the lower one (`[upper] width`, docs/design.md §12) on a
/// foundation 10⁶ times stiffer: between its rollers the block is compressed uniformly, so
/// p = δ E'_u / H_u at every row (by hand: δ = 0.01, E'_u = 500/0.96, H_u = 0.5), to the
/// foundation's compliance — for mortar at 2:3 with the upper's 5 elements over the lower's
/// 8 under it, and on the lower's mesh left whole (its 12 elements). The load is that p over
/// the upper's half width.
#[test]
fn a_narrow_block_on_a_stiff_foundation_is_compressed_uniformly() {
    let mut s = patch();
    s.material.young *= 1e6;
    let upper = s.upper.as_mut().unwrap();
    upper.width = 2.0;
    assert_eq!(s.patch_pressure(0.0), None, "a punch is no patch test");
    let upper_mesh = s.upper_mesh(1, Element::Q1).unwrap();
    assert_eq!(upper_mesh.node_x.first(), Some(&0.0));
    assert!((upper_mesh.node_x.last().unwrap() - 1.0).abs() < 1e-15);
    assert_eq!(upper_mesh.nx(), 5, "2:3 of the 8 lower elements under it");
    let by_hand = 0.01 * (500.0 / 0.96) / 0.5;
    for method in [InterfaceMethod::Mortar, InterfaceMethod::MortarDual] {
        let solved = s.solve_bodies(1, method, 0.0).unwrap();
        assert_eq!(solved.lower.mesh().nx(), 12);
        let sol = &solved.solution;
        assert!(sol.x.iter().all(|&x| (0.0..=1.0 + 1e-12).contains(&x)));
        for p in &sol.p {
            assert!(
                (p / by_hand - 1.0).abs() < 1e-4,
                "{method:?}: p {p} against {by_hand}"
            );
        }
        assert!(
            (sol.load / (by_hand * 1.0) - 1.0).abs() < 1e-4,
            "{method:?}: P {}",
            sol.load
        );
    }
}

/// A narrow elastic block on a wider elastic body is a punch: mortar's and one-pass NTS's
/// pressure is highest at its corner (the last row), above 1.3 times the middle's, and
/// every discretisation carries the same load to 5 % (two-pass NTS, over-constrained, with
/// rows lifted off between its others).
#[test]
fn a_narrow_block_on_an_elastic_body_presses_hardest_at_its_corner() {
    let mut s = patch();
    s.upper.as_mut().unwrap().width = 1.0;
    let mut loads = Vec::new();
    for method in [
        InterfaceMethod::Mortar,
        InterfaceMethod::Nts,
        InterfaceMethod::Nts2,
    ] {
        let sol = s.solve_bodies(2, method, 0.0).unwrap().solution;
        assert!(sol.load > 0.0 && sol.p.iter().all(|p| p.is_finite() && *p >= 0.0));
        loads.push(sol.load);
        if method != InterfaceMethod::Nts2 {
            let last = *sol.p.last().unwrap();
            assert!(sol.p.iter().all(|&p| p <= last), "{method:?}: {:?}", sol.p);
            assert!(last > 1.3 * sol.p[0], "{method:?}: {:?}", sol.p);
        }
    }
    for load in &loads {
        assert!((load / loads[0] - 1.0).abs() < 0.05, "{loads:?}");
    }
}

/// The patch scenario with its upper body's top under a uniform pressure q instead of a
/// prescribed displacement.
fn pressed(q: f64) -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/patch-two-blocks.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let from = "support = \"roller\"\ndisplacement = 0.01";
    assert!(text.contains(from));
    let text = text.replace(from, &format!("pressure = {q:?}"));
    Scenario::parse(&text, "pressed-two-blocks.toml").unwrap()
}

/// The contact patch test as the issue of two bodies states it: a uniform pressure q on the
/// upper block's top (docs/design.md §12, "A pressure on the top") is carried across the
/// non-matching interface as p = q by mortar (standard and dual, 2:3 and 5:7, either side the
/// slave), for the exact multipliers and for the penalty alike; the pin's descent is the two
/// blocks' shortening, δ = q (H_l/E'_l + H_u/E'_u + ε), by hand; the lower trace sinks by the
/// lower block's shortening q H_l/E'_l, the upper one (which includes u_q) by εq more. NTS
/// does not carry it uniformly.
#[test]
fn a_pressure_on_the_top_is_carried_across_as_it_is() {
    use riplab::contact::interface::solve::Slave;
    let q = 5.0;
    let (lower, upper) = (1.0 / (1000.0 / 0.91), 0.5 / (500.0 / 0.96));
    for (ratio, slave, epsilon) in [
        ((2, 3), Slave::Upper, 0.0),
        ((5, 7), Slave::Upper, 0.0),
        ((2, 3), Slave::Lower, 0.0),
        ((2, 3), Slave::Upper, 1e-4),
    ] {
        let mut s = pressed(q);
        let body = s.upper.as_mut().unwrap();
        (body.ratio, body.slave) = (ratio, slave);
        assert_eq!(s.patch_pressure(epsilon), Some(q));
        for method in [InterfaceMethod::Mortar, InterfaceMethod::MortarDual] {
            let solved = s.solve_bodies(1, method, epsilon).unwrap();
            let case = format!("{method:?} {ratio:?} {slave:?} ε {epsilon}");
            let (exact, error) = solved.patch.unwrap();
            assert_eq!(exact, q);
            assert!(error < 1e-10, "{case}: patch error {error:e}");
            assert!((solved.solution.load / (1.5 * q) - 1.0).abs() < 1e-11, "{case}");
            let delta = q * (lower + upper + epsilon);
            assert!(
                (solved.descent / delta - 1.0).abs() < 1e-9,
                "{case}: δ {} against {delta}",
                solved.descent
            );
            let sol = &solved.solution;
            // The upper trace sinks by the penalty's penetration εq more.
            let (upper_trace, lower_trace) = match slave {
                Slave::Upper => (&sol.slave, &sol.master),
                _ => (&sol.master, &sol.slave),
            };
            for (trace, sinks) in [(upper_trace, q * (lower + epsilon)), (lower_trace, q * lower)] {
                for uy in &trace.uy {
                    assert!(
                        (uy / -sinks - 1.0).abs() < 1e-9,
                        "{case}: u_y {uy} against {}",
                        -sinks
                    );
                }
            }
        }
    }
    let mut s = pressed(q);
    s.upper.as_mut().unwrap().ratio = (2, 3);
    let (_, nts) = s
        .solve_bodies(1, InterfaceMethod::Nts, 0.0)
        .unwrap()
        .patch
        .unwrap();
    assert!(nts > 1e-3, "NTS's patch error {nts}");
}

/// A pressure of 1e-200 on the top is balanced like one of 5 (P = q·w, the patch error
/// round-off), and so is 1e-300: seen failing before, regula falsi's step fb·(b − a)
/// underflowed to 0 and the search stayed on one δ for its 200 tries.
#[test]
fn a_tiny_pressure_is_balanced() {
    for q in [1e-200, 1e-300] {
        let solved = pressed(q).solve_bodies(1, InterfaceMethod::Mortar, 0.0).unwrap();
        assert!((solved.solution.load / (1.5 * q) - 1.0).abs() < 1e-11, "q {q:e}");
        let (_, error) = solved.patch.unwrap();
        assert!(error < 1e-10, "q {q:e}: patch error {error:e}");
    }
}
