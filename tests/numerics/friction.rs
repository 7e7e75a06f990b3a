//! Friction (docs/design.md §11): Tresca and Coulomb under the reduced-integration
//! rules, each check against something independent of the friction solver.

use std::ops::ControlFlow;
use std::path::Path;

use riplab::contact::friction::{Friction, Law, Press, State};
use riplab::contact::newton::NewtonOptions;
use riplab::contact::solution::Solution;
use riplab::contact::{ContactParams, ContactPoints, Method, Rule};
use riplab::discretization::{Discretization, Trace};
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::solve::solve_contact;
use riplab::solve::solve_friction;

fn full() -> Scenario {
    Scenario::load(Path::new("scenarios/hertz-paper-full.toml")).unwrap()
}

fn params(s: &Scenario, rule: Rule, method: Method, epsilon: f64) -> ContactParams {
    ContactParams {
        rule,
        method,
        epsilon,
        obstacle: s.obstacle.clone(),
    }
}

fn with(disc: &Discretization, p: &ContactParams, f: &Friction) -> Solution {
    solve_friction(disc, p, f, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap()
}

fn frictionless(disc: &Discretization, p: &ContactParams) -> Solution {
    solve_contact(disc, p, None, &NewtonOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap()
}

fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    a.iter().zip(b).fold(0.0_f64, |m, (x, y)| m.max((x - y).abs())) / scale
}

/// μ = 0 (Coulomb) and g = 0 (Tresca), shifted, give today's frictionless solve (another
/// solver, on a Normal discretisation's factor) to 1e-12: load, p and p̄; Q = 0.
#[test]
fn mu_zero_is_frictionless() {
    let s = full();
    for element in [Element::Q1, Element::Q2] {
        let disc = s.discretize_traced(1, element, Trace::Full).unwrap();
        let normal = s.discretize(1, element).unwrap();
        let cases: &[(Rule, Method, f64)] = match element {
            Element::Q2 => &[
                (Rule::Simpson, Method::Exact, 0.0),
                (Rule::Gauss1, Method::Penalty, 1e-6),
            ],
            _ => &[
                (Rule::Gauss1, Method::Penalty, 1e-6),
                (Rule::Trapezoid, Method::Exact, 0.0),
                (Rule::Trapezoid, Method::Alm { tolerance: 1e-10 }, 1e-3),
            ],
        };
        for &(rule, method, eps) in cases {
            let p = params(&s, rule, method, eps);
            let reference = frictionless(&normal, &p);
            for law in [Law::Coulomb { mu: 0.0 }, Law::Tresca { threshold: 0.0 }] {
                let f = Friction {
                    law,
                    shift: 0.05,
                    steps: 4,
                    epsilon_t: None,
                    press: Press::WithFriction,
                };
                let sol = with(&disc, &p, &f);
                assert!(
                    sol.newton.converged,
                    "{element:?} {rule:?} {method:?} {law:?}: {:?}",
                    sol.newton.diagnosis
                );
                let what = format!("{element:?} {rule:?} {method:?} {law:?}");
                // The ALM's two solvers stop at the multipliers' relative change 1e-10 by
                // different paths (the frictionless one jumps to the fixed point, friction's
                // is plain Uzawa): equal to the tolerance, not to round-off.
                let tol = if let Method::Alm { .. } = method {
                    1e-9
                } else {
                    1e-12
                };
                assert!(
                    (sol.load - reference.load).abs() <= tol * reference.load,
                    "{what}: {} vs {}",
                    sol.load,
                    reference.load
                );
                assert!(
                    max_rel(&sol.p, &reference.p) <= tol,
                    "{what}: p {}",
                    max_rel(&sol.p, &reference.p)
                );
                assert!(max_rel(&sol.pbar, &reference.pbar) <= tol, "{what}");
                let fr = sol.friction.as_ref().unwrap();
                assert_eq!(fr.tangential_load, 0.0, "{what}");
                assert!(fr.states.iter().all(|&st| st != State::Stick), "{what}");
            }
        }
    }
}

fn coulomb(mu: f64, shift: f64, steps: usize) -> Friction {
    Friction {
        law: Law::Coulomb { mu },
        shift,
        steps,
        epsilon_t: None,
        press: Press::WithFriction,
    }
}

/// The Done-when: on `scenarios/cattaneo-mindlin.toml` at its default level the computed stick
/// half-width is within 5% of Johnson's c = a√(1 − Q/(μP)) for the computed P and Q, and
/// ‖t̄ − q‖₀ within 5% of ‖q‖₀ (q: Cattaneo–Mindlin's closed form, src/contact/mindlin.rs,
/// itself checked by ∫q = Q and the stick zone's rigid motion).
#[test]
fn cattaneo_mindlin_within_five_percent() {
    use riplab::contact::mindlin::{Mindlin, stick_half_width};
    let s = Scenario::load(Path::new("scenarios/cattaneo-mindlin.toml")).unwrap();
    let (_, sol) = riplab::solve::solve_scenario(&s).unwrap();
    assert!(sol.newton.converged, "{:?}", sol.newton.diagnosis);
    let f = sol.friction.as_ref().unwrap();
    let mu = s.friction.law.mu().unwrap();
    let ratio = f.tangential_load / (mu * sol.load);
    assert!(ratio > 0.3 && ratio < 0.7, "Q/(μP) = {ratio}");
    let m = Mindlin::for_loads(&s.obstacle, &s.material, sol.load, f.tangential_load, mu).unwrap();
    let (width, runs) = stick_half_width(&sol.points, &f.states).unwrap();
    assert_eq!(runs, 1);
    assert!(
        (width / m.c - 1.0).abs() <= 0.05,
        "stick half-width {width} against c = {}",
        m.c
    );
    let err = m.relative_error(&sol.points, &f.tbar);
    assert!(err <= 0.05, "‖t̄ − q‖/‖q‖ = {err}");
    // β ≈ 0: eight shift steps give the answer of the default one (no point re-sticks).
    let disc = s.discretize_traced(s.level, s.element, Trace::Full).unwrap();
    let p = params(&s, s.rule, s.method, s.epsilon);
    assert_eq!(s.friction.steps, 1);
    let eight = with(
        &disc,
        &p,
        &Friction {
            steps: 8,
            ..s.friction
        },
    );
    assert!(max_rel(&eight.friction.as_ref().unwrap().tbar, &f.tbar) <= 1e-8);
}

/// A very large μ sticks every contact point: the stick zone is the contact, and the contact
/// nodes move with the obstacle, u_x = ξ, in the displacement of a sparse solve with the
/// nodal forces (not the condensed algebra the solver used).
#[test]
fn large_mu_sticks_everywhere() {
    use riplab::contact::mindlin::stick_half_width;
    let s = full();
    let disc = s.discretize_traced(1, Element::Q1, Trace::Full).unwrap();
    let p = params(&s, Rule::Trapezoid, Method::Exact, 0.0);
    let shift = 0.01;
    let sol = with(&disc, &p, &coulomb(1e6, shift, 2));
    assert!(sol.newton.converged, "{:?}", sol.newton.diagnosis);
    let f = sol.friction.as_ref().unwrap();
    let contact: Vec<usize> = (0..f.states.len())
        .filter(|&q| f.states[q] != State::Open)
        .collect();
    assert!(contact.len() > 4);
    assert!(contact.iter().all(|&q| f.states[q] == State::Stick));
    let (width, runs) = stick_half_width(&sol.points, &f.states).unwrap();
    assert_eq!(runs, 1);
    let x = |q: usize| sol.points.points[q].x;
    let (lo, hi) = (contact[0], *contact.last().unwrap());
    let half = 0.5 * (0.5 * (x(hi) + x(hi + 1)) - 0.5 * (x(lo - 1) + x(lo)));
    assert!((width - half).abs() < 1e-12);
    let u = sol.displacement(&disc);
    let top = disc.mesh().top_nodes();
    for &q in &contact {
        let node = top[q];
        assert!(
            (u[2 * node] - shift).abs() <= 1e-9 * shift,
            "u_x {} at {}",
            u[2 * node],
            x(q)
        );
        assert!(
            (u[2 * node + 1] - s.obstacle.gap(x(q))).abs() <= 1e-9,
            "u_y at {}",
            x(q)
        );
    }
}

/// Q equals minus the sum of the horizontal reactions and P the sum of the vertical ones at
/// the clamped bottom, from K u assembled on every dof (nothing held) with u the solution's
/// displacement (its +Tᵀz included): equilibrium at the assembly's level, not the trace sums.
#[test]
fn tangential_load_is_the_horizontal_reaction() {
    use riplab::fem::{Form, apply};
    let s = full();
    for (element, rule, method, eps) in [
        (Element::Q1, Rule::Gauss1, Method::Penalty, 1e-6),
        (Element::Q1, Rule::Trapezoid, Method::Exact, 0.0),
        (Element::Q2, Rule::Simpson, Method::Exact, 0.0),
    ] {
        let disc = s.discretize_traced(1, element, Trace::Full).unwrap();
        let sol = with(&disc, &params(&s, rule, method, eps), &coulomb(0.3, 0.05, 4));
        assert!(
            sol.newton.converged,
            "{element:?} {rule:?}: {:?}",
            sol.newton.diagnosis
        );
        let q = sol.friction.as_ref().unwrap().tangential_load;
        assert!(q > 0.1 * 0.3 * sol.load, "Q = {q}");
        let mesh = disc.mesh();
        let ku = apply(
            mesh,
            Form::Elasticity(s.material, s.integration),
            &sol.displacement(&disc),
        );
        let nnx = mesh.nnx();
        let (rx, ry): (f64, f64) = (0..nnx).fold((0.0, 0.0), |(a, b), n| (a + ku[2 * n], b + ku[2 * n + 1]));
        assert!(
            (rx + q).abs() <= 1e-9 * sol.load,
            "{element:?} {rule:?}: Σ r_x = {rx}, Q = {q}"
        );
        assert!(
            (ry - sol.load).abs() <= 1e-9 * sol.load,
            "{element:?} {rule:?}: Σ r_y = {ry}, P = {}",
            sol.load
        );
    }
}

/// M1 (Q1 + one-point Gauss, penalty): where the points slip, t = μp exactly, so t's raw
/// values oscillate where p's do; t̄ on the slip zone's vertices does not (it rises to μp's
/// peak and falls, one turn at most).
#[test]
fn m1_t_oscillates_where_p_does() {
    let s = full();
    let disc = s.discretize_traced(1, Element::Q1, Trace::Full).unwrap();
    let p = params(&s, Rule::Gauss1, Method::Penalty, 1e-6);
    let sol = with(&disc, &p, &coulomb(0.3, 0.5, 8));
    assert!(sol.newton.converged, "{:?}", sol.newton.diagnosis);
    let f = sol.friction.as_ref().unwrap();
    let slip: Vec<usize> = (0..f.states.len())
        .filter(|&q| f.states[q] == State::Slip)
        .collect();
    assert!(!slip.is_empty());
    for &q in &slip {
        assert!(
            (f.t[q].abs() - 0.3 * sol.p[q]).abs() <= 1e-12 * sol.p[q],
            "t = μp at slip points"
        );
    }
    // The right slip zone: from the last stick point to the contact's end.
    let last_stick = (0..f.states.len())
        .rfind(|&q| f.states[q] == State::Stick)
        .unwrap_or(slip[0]);
    let right: Vec<usize> = slip.iter().copied().filter(|&q| q > last_stick).collect();
    let (pt, tt): (Vec<f64>, Vec<f64>) = right.iter().map(|&q| (sol.p[q], f.t[q].abs())).unzip();
    assert!(
        crate::common::turns(&pt) >= 2,
        "p does not oscillate here: {pt:?}"
    );
    assert_eq!(crate::common::turns(&tt), crate::common::turns(&pt));
    // t̄ at the vertices strictly inside that zone.
    let xs: Vec<f64> = right.iter().map(|&q| sol.points.points[q].x).collect();
    let (lo, hi) = (xs[0], *xs.last().unwrap());
    let tbar: Vec<f64> = sol
        .points
        .vertex_x
        .iter()
        .zip(&f.tbar)
        .filter(|(x, _)| **x > lo && **x < hi)
        .map(|(_, t)| *t)
        .collect();
    // At most one turn: the peak of μp (at shift 0.5 the zone reaches past it), no
    // oscillation.
    assert!(tbar.len() >= 3);
    assert!(crate::common::turns(&tbar) <= 1, "t̄ {tbar:?}");
}

/// A friction solve that does not converge says so, with the shift where it stopped: never
/// converged, the diagnosis typed (the press, or a shift step after its bisections).
#[test]
fn a_solve_that_does_not_converge_says_where_it_stopped() {
    use riplab::error::Diagnosis;
    let s = full();
    let disc = s.discretize_traced(1, Element::Q1, Trace::Full).unwrap();
    let p = params(&s, Rule::Trapezoid, Method::Exact, 0.0);
    let opts = NewtonOptions {
        max_iterations: 1,
        ..NewtonOptions::default()
    };
    let sol = solve_friction(&disc, &p, &coulomb(0.3, 0.05, 2), None, &opts, &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap();
    assert!(!sol.newton.converged);
    let why = sol.newton.diagnosis.clone().unwrap();
    assert!(
        matches!(why, Diagnosis::Press(_) | Diagnosis::Shift { .. }),
        "{why:?}"
    );
    assert!(why.to_string().contains("shift"), "{why}");
}

/// Tresca with the per-point threshold g_q = μ p_q of a Coulomb step's solution gives that
/// solution back (it satisfies Tresca's conditions, and Tresca's incremental problem has one
/// solution), by another system (Cholesky on the symmetric block, not Coulomb's LU): y and z
/// to 1e-10, for the exact multipliers and the penalty.
#[test]
fn tresca_at_coulombs_pressure_is_coulomb() {
    use riplab::contact::friction::FrictionTrace;
    use riplab::contact::friction::law::{Bound, Imposition, StepProblem};
    use riplab::contact::friction::newton::solve_step;
    let s = full();
    let disc = s.discretize_traced(2, Element::Q1, Trace::Full).unwrap();
    for (rule, imposition) in [
        (Rule::Trapezoid, Imposition::Exact),
        (
            Rule::Gauss1,
            Imposition::Penalty {
                epsilon: 1e-6,
                epsilon_t: 1e-6,
            },
        ),
    ] {
        let points = ContactPoints::on(&disc, rule);
        let couplings = FrictionTrace::of(&disc).unwrap().couplings(&disc, rule, &points);
        let w: Vec<f64> = points.points.iter().map(|q| q.weight).collect();
        let n = w.len();
        let d: Vec<f64> = points.points.iter().map(|q| -s.obstacle.gap(q.x)).collect();
        let zero = vec![0.0; n];
        let step = |bound| StepProblem {
            couplings: &couplings,
            d: &d,
            e: &zero,
            weight: &w,
            bound,
            imposition,
            shift: 0.1,
            anchor: &zero,
        };
        let solve = |pb: &StepProblem| {
            solve_step(
                pb,
                zero.clone(),
                zero.clone(),
                &NewtonOptions::default(),
                &mut |_| ControlFlow::Continue(()),
            )
            .unwrap()
        };
        let mu = 0.3;
        let coulomb = solve(&step(Bound::Coulomb(mu)));
        assert!(coulomb.converged(), "{rule:?}: {:?}", coulomb.diagnosis);
        let slipping = coulomb.states.iter().filter(|&&x| x == State::Slip).count();
        let sticking = coulomb.states.iter().filter(|&&x| x == State::Stick).count();
        assert!(slipping > 0 && sticking > 0, "{rule:?}: partial slip");
        let g: Vec<f64> = (0..n).map(|q| mu * coulomb.y[q] / w[q]).collect();
        let tresca = solve(&step(Bound::Tresca(&g)));
        assert!(tresca.converged(), "{rule:?}");
        assert!(
            max_rel(&tresca.y, &coulomb.y) <= 1e-10,
            "{rule:?}: y {}",
            max_rel(&tresca.y, &coulomb.y)
        );
        assert!(
            max_rel(&tresca.z, &coulomb.z) <= 1e-10,
            "{rule:?}: z {}",
            max_rel(&tresca.z, &coulomb.z)
        );
    }
}

/// Coulomb's step as the fixed point of Tresca's (the issue's "Tresca with g equal to μ times
/// a frozen frictionless pressure equals Coulomb's fixed point started from it"): from the
/// frictionless pressure p⁰, g^k = μ p^k and p^{k+1} = Tresca(g^k)'s pressure. On
/// hertz-paper-full (Dundurs' β ≈ 0.29, so the shear changes p) the first Tresca solve is not
/// Coulomb's, and the iterates contract onto Coulomb's solution, found by the other solver.
#[test]
fn coulomb_is_the_fixed_point_of_tresca_from_the_frictionless_pressure() {
    use riplab::contact::friction::FrictionTrace;
    use riplab::contact::friction::law::{Bound, Imposition, StepProblem};
    use riplab::contact::friction::newton::solve_step;
    let s = full();
    let disc = s.discretize_traced(2, Element::Q1, Trace::Full).unwrap();
    let rule = Rule::Trapezoid;
    let points = ContactPoints::on(&disc, rule);
    let couplings = FrictionTrace::of(&disc).unwrap().couplings(&disc, rule, &points);
    let w: Vec<f64> = points.points.iter().map(|q| q.weight).collect();
    let n = w.len();
    let d: Vec<f64> = points.points.iter().map(|q| -s.obstacle.gap(q.x)).collect();
    let zero = vec![0.0; n];
    let step = |bound| StepProblem {
        couplings: &couplings,
        d: &d,
        e: &zero,
        weight: &w,
        bound,
        imposition: Imposition::Exact,
        shift: 0.1,
        anchor: &zero,
    };
    let solve = |pb: &StepProblem| {
        let out = solve_step(
            pb,
            zero.clone(),
            zero.clone(),
            &NewtonOptions::default(),
            &mut |_| ControlFlow::Continue(()),
        )
        .unwrap();
        assert!(out.converged(), "{:?}", out.diagnosis);
        out
    };
    let mu = 0.3;
    let coulomb = solve(&step(Bound::Coulomb(mu)));
    let frictionless = solve(&step(Bound::Coulomb(0.0)));
    let mut y = frictionless.y;
    let mut distances = Vec::new();
    for _ in 0..30 {
        let g: Vec<f64> = (0..n).map(|q| mu * y[q] / w[q]).collect();
        let tresca = solve(&StepProblem {
            bound: Bound::Tresca(&g),
            ..step(Bound::Coulomb(0.0))
        });
        distances.push(max_rel(&tresca.y, &coulomb.y).max(max_rel(&tresca.z, &coulomb.z)));
        y = tresca.y;
        if distances.last() < Some(&1e-10) {
            break;
        }
    }
    assert!(
        distances[0] > 1e-4,
        "the first Tresca solve differs: {distances:?}"
    );
    assert!(*distances.last().unwrap() < 1e-10, "{distances:?}");
    assert!(distances.windows(2).all(|d| d[1] < d[0]), "{distances:?}");
}

/// Once the contact zone is one point (a press far below the first element's gap), P and Q
/// are linear in the press, with the shift scaled with it (Coulomb's law is positively
/// homogeneous): a press of 1e-300 gives the press of 1e-12's P/λ and Q/λ to 1e-9, with the
/// same states. It gave P = 0 in 0 iterations, Q/(μP) = NaN: the points far out of contact set
/// the round-off floor, and the natural residual's squares of 1e-297 were 0.
#[test]
fn coulomb_scales_with_a_tiny_press() {
    let s = full();
    let disc = s.discretize_traced(1, Element::Q1, Trace::Full).unwrap();
    let at = |depth: f64| {
        let mut p = params(&s, Rule::Trapezoid, Method::Exact, 0.0);
        p.obstacle = s.obstacle.with_depth(depth);
        let sol = with(&disc, &p, &coulomb(0.3, 0.05 * depth, 2));
        assert!(
            sol.newton.converged,
            "depth {depth:e}: {:?}",
            sol.newton.diagnosis
        );
        let f = sol.friction.unwrap();
        (sol.load / depth, f.tangential_load / depth, f.states)
    };
    let small = at(1e-12);
    assert!(small.0 > 0.0 && small.1 != 0.0);
    assert_eq!(small.2.iter().filter(|&&q| q != State::Open).count(), 1);
    for depth in [1e-100, 1e-300] {
        let tiny = at(depth);
        assert!(
            (tiny.0 / small.0 - 1.0).abs() < 1e-9,
            "depth {depth:e}: P/λ {} against {}",
            tiny.0,
            small.0
        );
        assert!(
            (tiny.1 / small.1 - 1.0).abs() < 1e-9,
            "depth {depth:e}: Q/λ {} against {}",
            tiny.1,
            small.1
        );
        assert_eq!(tiny.2, small.2, "depth {depth:e}");
    }
}
