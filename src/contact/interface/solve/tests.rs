//! The two-body solve on matching meshes, with a coupling built here (identity rows, the
//! trapezoid's tributary weights): the contact patch test's closed form, both slaves alike,
//! an opening interface, and a refused ε.

use super::*;
use crate::fem::{DofMap, Integration, Support};
use crate::material::{Material, Plane};
use crate::mesh::{Element, Mesh};

const DELTA: f64 = 0.01;

fn material(young: f64, poisson: f64) -> Material {
    Material {
        young,
        poisson,
        plane: Plane::Strain,
    }
}

/// A half-model block 1 wide (nx cells) and `height` high on `support`, as its own mesh sees it.
fn block(element: Element, nx: usize, height: f64, m: Material, support: Support) -> Discretization {
    let ny = (height * nx as f64).round() as usize;
    let mesh = Mesh::uniform(element, (0.0, 1.0, nx), (0.0, height, ny.max(1)), true);
    let dofs = DofMap::supported(&mesh, support);
    Discretization::with_dofs(mesh, dofs, m, Integration::Full).unwrap()
}

/// Matching traces of `order`: constraint k at node k of both, weighing ∫φ_k (the trapezoid's
/// tributary length for linear edges, Simpson's h/6, 4h/6, h/6 for quadratic ones).
fn matching(x: &[f64], order: usize) -> Coupling {
    let n = x.len();
    let mut weight = vec![0.0; n];
    for e in 0..(n - 1) / order {
        let h = x[order * (e + 1)] - x[order * e];
        let shares: &[f64] = if order == 1 {
            &[0.5, 0.5]
        } else {
            &[1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0]
        };
        for (j, share) in shares.iter().enumerate() {
            weight[order * e + j] += share * h;
        }
    }
    Coupling {
        x: x.to_vec(),
        weight,
        slave: (0..n).map(|k| vec![(k, 1.0)]).collect(),
        master: (0..n).map(|k| vec![(k, 1.0)]).collect(),
    }
}

/// p = δ/(H_l/E'_l + H_u/E'_u + ε), E' = E/(1 − ν²): two blocks on rollers, uniformly
/// compressed, by hand.
fn patch_pressure(lower: (Material, f64), upper: (Material, f64), epsilon: f64) -> f64 {
    let modulus = |m: &Material| m.young / (1.0 - m.poisson * m.poisson);
    DELTA / (lower.1 / modulus(&lower.0) + upper.1 / modulus(&upper.0) + epsilon)
}

/// The patch test on matching meshes: p uniform at the closed form for the penalty and the
/// exact multipliers, whichever side is the slave; the lower trace at −p H_l/E'_l, the upper
/// at −δ + p H_u/E'_u; P = p · width.
#[test]
fn matching_blocks_pass_the_patch_test() {
    let (ml, mu) = (material(1000.0, 0.3), material(300.0, 0.2));
    let (hl, hu) = (1.0, 0.5);
    for element in [Element::Q1, Element::Q2] {
        let lower = block(element, 4, hl, ml, Support::Roller);
        let upper = block(element, 4, hu, mu, Support::Roller);
        let coupling = matching(&lower.mesh.node_x, element.order());
        let g0 = vec![0.0; coupling.x.len()];
        for slave in [Slave::Upper, Slave::Lower] {
            for epsilon in [0.0, 1e-4] {
                let bodies = Bodies {
                    lower: &lower,
                    upper: &upper,
                    displacement: DELTA,
                    slave,
                };
                let sol = solve(&bodies, &coupling, &g0, epsilon.into(), None).unwrap();
                let p = patch_pressure((ml, hl), (mu, hu), epsilon);
                let what = format!("{element:?} {slave:?} ε = {epsilon}");
                for (k, pk) in sol.p.iter().chain(&sol.pbar).enumerate() {
                    assert!((pk - p).abs() < 1e-10 * p, "{what}: p[{k}] = {pk}, expected {p}");
                }
                assert!((sol.load - p).abs() < 1e-10 * p, "{what}: P = {}", sol.load);
                let e = |m: &Material| m.young / (1.0 - m.poisson * m.poisson);
                let (lower_trace, upper_trace) = match slave {
                    Slave::Upper => (&sol.master, &sol.slave),
                    Slave::Lower => (&sol.slave, &sol.master),
                };
                for &uy in &lower_trace.uy {
                    let want = -p * hl / e(&ml);
                    assert!(
                        (uy - want).abs() < 1e-10 * DELTA,
                        "{what}: lower u_y {uy} against {want}"
                    );
                }
                for &uy in &upper_trace.uy {
                    let want = -DELTA + p * hu / e(&mu);
                    assert!(
                        (uy - want).abs() < 1e-10 * DELTA,
                        "{what}: upper u_y {uy} against {want}"
                    );
                }
                // Free sides: both bodies widen by ν' = ν/(1 − ν) of their shortening.
                let widen = |m: &Material, h: f64| p * h / e(m) * m.poisson / (1.0 - m.poisson) / h;
                let last = lower_trace.ux.len() - 1;
                assert!(
                    (lower_trace.ux[last] - widen(&ml, hl)).abs() < 1e-10 * DELTA,
                    "{what}"
                );
                assert!(
                    (upper_trace.ux[last] - widen(&mu, hu)).abs() < 1e-10 * DELTA,
                    "{what}"
                );
                for (g, pk) in sol.gap.iter().zip(&sol.p) {
                    assert!((g + epsilon * pk).abs() < 1e-12, "{what}: gap {g}");
                }
            }
        }
    }
}

/// A top lifted (δ < 0) opens the interface: no pressure, the gap −δ, the upper body lifted
/// rigidly.
#[test]
fn a_lifted_top_opens_the_interface() {
    let m = material(1000.0, 0.3);
    let lower = block(Element::Q1, 3, 1.0, m, Support::Clamped);
    let upper = block(Element::Q1, 3, 1.0, m, Support::Clamped);
    let coupling = matching(&lower.mesh.node_x, 1);
    let g0 = vec![0.0; coupling.x.len()];
    let bodies = Bodies {
        lower: &lower,
        upper: &upper,
        displacement: -DELTA,
        slave: Slave::Upper,
    };
    for epsilon in [0.0, 1e-3] {
        let sol = solve(&bodies, &coupling, &g0, epsilon.into(), None).unwrap();
        assert!(sol.p.iter().all(|&p| p == 0.0), "{:?}", sol.p);
        assert!(sol.gap.iter().all(|g| (g - DELTA).abs() < 1e-15));
        assert!(sol.slave.uy.iter().all(|u| (u - DELTA).abs() < 1e-15));
        assert!(sol.master.uy.iter().all(|&u| u == 0.0));
    }
}

/// Clamped bodies: no uniform pressure, but equilibrium: the load is the same whichever side
/// is the slave (matching meshes: the same constraints), and the exact multipliers close the
/// gap where they press.
#[test]
fn clamped_bodies_balance_whichever_side_is_the_slave() {
    let m = material(1000.0, 0.3);
    let lower = block(Element::Q1, 4, 1.0, m, Support::Clamped);
    let upper = block(Element::Q1, 4, 0.5, material(2000.0, 0.25), Support::Clamped);
    let coupling = matching(&lower.mesh.node_x, 1);
    let g0 = vec![0.0; coupling.x.len()];
    let load = |slave| {
        let bodies = Bodies {
            lower: &lower,
            upper: &upper,
            displacement: DELTA,
            slave,
        };
        solve(&bodies, &coupling, &g0, 0.0.into(), None).unwrap()
    };
    let (a, b) = (load(Slave::Upper), load(Slave::Lower));
    assert!((a.load - b.load).abs() < 1e-10 * a.load, "{} {}", a.load, b.load);
    let spread =
        a.p.iter().fold(0.0_f64, |m, &p| m.max(p)) - a.p.iter().fold(f64::INFINITY, |m, &p| m.min(p));
    assert!(
        spread > 1e-3 * a.load,
        "clamped ends make p non-uniform: {:?}",
        a.p
    );
    for (g, p) in a.gap.iter().zip(&a.p) {
        assert!(*p >= 0.0 && *g >= -1e-12 * DELTA && (p * g).abs() < 1e-9 * DELTA * a.load);
    }
}

/// Duplicated constraints have no unique exact multipliers (refused, typed); a coupling that
/// names a node beyond the trace is refused, never a panic; an ε below double precision is
/// refused, never a non-finite number nor an overflow taken for convergence.
#[test]
fn refusals_are_typed() {
    let m = material(1000.0, 0.3);
    let lower = block(Element::Q1, 2, 1.0, m, Support::Clamped);
    let upper = block(Element::Q1, 2, 1.0, m, Support::Clamped);
    let bodies = Bodies {
        lower: &lower,
        upper: &upper,
        displacement: DELTA,
        slave: Slave::Upper,
    };
    let one = matching(&lower.mesh.node_x, 1);
    let mut twice = one.clone();
    twice.x.extend(one.x.clone());
    twice.weight.extend(one.weight.clone());
    twice.slave.extend(one.slave.clone());
    twice.master.extend(one.master.clone());
    let g0 = vec![0.0; twice.x.len()];
    assert_eq!(
        solve(&bodies, &twice, &g0, 0.0.into(), None),
        Err(BodiesError::NotUnique { constraints: 6 })
    );
    assert!(solve(&bodies, &twice, &g0, 1e-3.into(), None).is_ok());
    let mut beyond = one.clone();
    beyond.slave[0] = vec![(7, 1.0)];
    assert!(matches!(
        solve(&bodies, &beyond, &[0.0; 3], 1e-3.into(), None),
        Err(BodiesError::Mismatch(_))
    ));
    let (lo, hi) = epsilon_range(&bodies);
    assert_eq!(
        solve(&bodies, &one, &[0.0; 3], 1e-300.into(), None),
        Err(BodiesError::Epsilon {
            epsilon: 1e-300,
            lo,
            hi
        })
    );
}

/// p̄ by hand: constant p stays constant; the trapezoid's points are the vertices themselves.
#[test]
fn smoothing_by_hand() {
    let v = [0.0, 1.0, 3.0];
    // gauss1's points, one per edge: (17), p̄_1 = q_1, p̄_2 = (1·q_1 + 2·q_2)/3, p̄_3 = q_2.
    let pbar = smoothed(&v, &[0.5, 2.0], &[1.0, 2.0], &[3.0, 6.0]);
    assert_eq!(pbar, vec![3.0, 5.0, 6.0]);
    let pbar = smoothed(&v, &v, &[0.5, 1.5, 1.0], &[1.0, 2.0, 4.0]);
    assert_eq!(pbar, vec![1.0, 2.0, 4.0]);
}
