//! The sliding patch test (docs/design.md §11): a flat rigid plane pressed into a
//! block and then slid over it. With the sides loaded by the tractions of the uniform state —
//! σ_yy = −p, σ_xx = −λp/(λ + 2μ), σ_xy = τ — the linear field u = (τy/μ, −py/(λ + 2μ)) is in
//! every element's space, so it is the exact discrete solution: p uniform (by hand:
//! p = kd, k = (λ + 2μ)/H; the penalty's kd/(1 + εk)), every point slipping, t = μ_f p
//! (Coulomb) or t = g (Tresca), Q = I(t, 1), no oscillation under any rule.

use std::ops::ControlFlow;
use std::sync::Arc;

use riplab::contact::friction::{Free, solve_with};
use riplab::contact::friction::{Friction, Law, Press, State};
use riplab::contact::newton::NewtonOptions;
use riplab::contact::{ContactParams, ContactPoints, Method, Obstacle, Outline, Rule};
use riplab::discretization::{Discretization, Trace};
use riplab::fem::Integration;
use riplab::fem::basis::evaluate;
use riplab::fem::dofs::DofMap;
use riplab::material::{Material, Plane};
use riplab::mesh::{Element, Mesh};

const YOUNG: f64 = 1000.0;
const POISSON: f64 = 0.3;
const HEIGHT: f64 = 1.0;
const DEPTH: f64 = 0.01;
const MU_F: f64 = 0.3;
/// Far beyond the top's elastic shift τH/μ (about 0.01): every point slips.
const SHIFT: f64 = 0.2;

/// The flat plane η = 0.
struct Plane0;
impl Outline for Plane0 {
    fn outline(&self, _: f64) -> f64 {
        0.0
    }
}

/// The consistent nodal loads of the constant tractions `left` and `right` on the block's
/// sides (free dofs), each side edge integrated exactly (Simpson's weights on Q2's).
fn side_loads(disc: &Discretization, left: [f64; 2], right: [f64; 2]) -> Vec<f64> {
    let mesh = disc.mesh();
    let dofs = disc.dofs();
    let (nnx, nny) = (mesh.nnx(), mesh.node_y.len());
    let order = mesh.element.order();
    let weights: &[f64] = if order == 2 {
        &[1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0]
    } else {
        &[0.5, 0.5]
    };
    let mut f = vec![0.0; dofs.n_free()];
    for (column, traction) in [(0, left), (nnx - 1, right)] {
        for start in (0..nny - 1).step_by(order) {
            let h = mesh.node_y[start + order] - mesh.node_y[start];
            for (k, w) in weights.iter().enumerate() {
                let node = (start + k) * nnx + column;
                for (comp, t) in traction.iter().enumerate() {
                    if let Some(i) = dofs.free_index(2 * node + comp) {
                        f[i] += w * h * t;
                    }
                }
            }
        }
    }
    f
}

#[test]
fn a_plane_slid_over_a_block_gives_uniform_p_and_t_equal_mu_p() {
    let material = Material {
        young: YOUNG,
        poisson: POISSON,
        plane: Plane::Strain,
    };
    let lame = YOUNG * POISSON / ((1.0 + POISSON) * (1.0 - 2.0 * POISSON));
    let shear = YOUNG / (2.0 * (1.0 + POISSON));
    let k = (lame + 2.0 * shear) / HEIGHT;
    // A flat plane whose lowest point (where the shift is checked to stay over the body) is
    // the block's middle.
    let flat = Obstacle::Custom {
        outline: Arc::new(Plane0),
        depth: DEPTH,
    };
    let eps = 1e-4;
    // (method, ε, the factor on p = kd).
    let methods = [
        (Method::Exact, 0.0, 1.0),
        (Method::Penalty, eps, 1.0 / (1.0 + eps * k)),
        // The friction ALM's Uzawa updates contract linearly, more slowly as κ = εE/h grows
        // (docs/design.md §11: no jump to the exact multipliers): at ε = 1e-5 every case
        // takes 15–46 updates; at 1e-3 q2+gauss2 did not converge in 500.
        (Method::Alm { tolerance: 1e-12 }, 1e-5, 1.0),
    ];
    let cases = [
        (Element::Q1, Rule::Gauss1),
        (Element::Q1, Rule::Trapezoid),
        (Element::Q1, Rule::Gauss2),
        (Element::Q1, Rule::Simpson),
        (Element::Q2, Rule::Gauss2),
        (Element::Q2, Rule::Simpson),
        (Element::P1, Rule::Gauss1),
        (Element::P1, Rule::Trapezoid),
    ];
    for (element, rule) in cases {
        let mesh = Mesh::uniform(element, (-1.0, 1.0, 4), (0.0, HEIGHT, 3), false);
        let dofs = DofMap::model(&mesh);
        let disc = Discretization::with_trace(mesh, dofs, material, Integration::Full, Trace::Full).unwrap();
        let points = ContactPoints::on(&disc, rule);
        let unique = points.len() <= disc.contact_dofs().len();
        for &(method, epsilon, factor) in &methods {
            if method == Method::Exact && !unique {
                continue;
            }
            let p = factor * k * DEPTH;
            for (law, t_expect) in [
                (Law::Coulomb { mu: MU_F }, MU_F * p),
                (
                    Law::Tresca {
                        threshold: 0.5 * MU_F * p,
                    },
                    0.5 * MU_F * p,
                ),
            ] {
                let what = format!(
                    "{} {} {}+{}",
                    law.name(),
                    method.name(),
                    element.name(),
                    rule.name()
                );
                // The sides carry σ·n of the uniform state: σ_xx = −λp/(λ + 2μ), σ_xy = t.
                let sxx = -lame * p / (lame + 2.0 * shear);
                let mut u0 = side_loads(&disc, [-sxx, -t_expect], [sxx, t_expect]);
                disc.factor().solve_in_place(&mut u0, 1);
                let u0 = disc.dofs().expand(&u0, |_| 0.0);
                let (d, e): (Vec<f64>, Vec<f64>) = points
                    .points
                    .iter()
                    .map(|q| {
                        let ([ux, uy], _) = evaluate(disc.mesh(), &u0, q.x, HEIGHT);
                        (uy - flat.gap(q.x), ux)
                    })
                    .unzip();
                let params = ContactParams {
                    rule,
                    method,
                    epsilon,
                    obstacle: flat.clone(),
                };
                let friction = Friction {
                    law,
                    shift: SHIFT,
                    steps: 1,
                    epsilon_t: None,
                    press: Press::WithFriction,
                };
                let sol = solve_with(
                    &disc,
                    &params,
                    &friction,
                    Free { d: &d, e: &e },
                    None,
                    &NewtonOptions::default(),
                    &mut |_| ControlFlow::Continue(()),
                )
                .unwrap_or_else(|err| panic!("{what}: {err}"));
                assert!(
                    sol.newton.converged,
                    "{what}: {:?} {:?}",
                    sol.newton.iterations, sol.outer_iterations
                );
                let fr = &sol.friction;
                let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
                for q in 0..points.len() {
                    assert!(close(sol.p[q], p), "{what}: p at {q} = {} against {p}", sol.p[q]);
                    assert!(
                        close(fr.t[q], t_expect),
                        "{what}: t at {q} = {} against {t_expect}",
                        fr.t[q]
                    );
                    assert_eq!(fr.states[q], State::Slip, "{what}: point {q}");
                }
                for (i, (pb, tb)) in sol.pbar.iter().zip(&fr.tbar).enumerate() {
                    assert!(
                        close(*pb, p) && close(*tb, t_expect),
                        "{what}: p̄, t̄ at {i}: {pb}, {tb}"
                    );
                }
                // Q = I(t, 1) over the top's width 2, beside P.
                assert!(
                    close(fr.tangential_load, 2.0 * t_expect),
                    "{what}: Q {}",
                    fr.tangential_load
                );
                assert!(close(sol.load, 2.0 * p), "{what}: P {}", sol.load);
            }
        }
    }
}
