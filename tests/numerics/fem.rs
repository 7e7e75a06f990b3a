//! The finite element layer checked against exact solutions: the patch test and a
//! manufactured elasticity solution with the expected H¹ convergence rates.

use riplab::fem::condense::{TraceFactor, TraceOrdering};
use riplab::fem::split::{SplitFactor, SplitOrdering};
use riplab::fem::{DofMap, Form, Integration, SymCsc, apply, assemble};
use riplab::material::{Material, Plane};
use riplab::mesh::{Element, Mesh};
use riplab::verify::manufactured;

const STEEL_LIKE: Material = Material {
    young: 1000.0,
    poisson: 0.3,
    plane: Plane::Strain,
};

/// Solve a(u, v) = ∫ f·v with u = `boundary` on every boundary node; returns u on all dofs.
fn dirichlet_solve(
    mesh: &Mesh,
    material: Material,
    f: &[f64],
    boundary: impl Fn(f64, f64) -> [f64; 2],
) -> Vec<f64> {
    dirichlet_solve_with(mesh, Form::Elasticity(material, Integration::Full), f, boundary)
}

/// The same for any form.
fn dirichlet_solve_with(
    mesh: &Mesh,
    form: Form,
    f: &[f64],
    boundary: impl Fn(f64, f64) -> [f64; 2],
) -> Vec<f64> {
    let (nnx, nny) = (mesh.nnx(), mesh.node_y.len());
    let on_boundary = |n: usize| {
        let (i, j) = (n % nnx, n / nnx);
        i == 0 || j == 0 || i == nnx - 1 || j == nny - 1
    };
    let dofs = DofMap::new(mesh.n_nodes(), |n, _| on_boundary(n));
    let lifted: Vec<f64> = (0..2 * mesh.n_nodes())
        .map(|g| {
            if on_boundary(g / 2) {
                let (x, y) = mesh.node_coords(g / 2);
                boundary(x, y)[g % 2]
            } else {
                0.0
            }
        })
        .collect();
    // K_ff u_f = f_f − K_fd u_d.
    let k_lift = apply(mesh, form, &lifted);
    let rhs: Vec<f64> = f.iter().zip(&k_lift).map(|(a, b)| a - b).collect();
    let mut uf = dofs.restrict(&rhs);
    let k = assemble(mesh, &dofs, form);
    let factor = TraceFactor::new(&TraceOrdering::new(&k, &[]).unwrap(), &k).unwrap();
    factor.solve_in_place(&mut uf, 1);
    dofs.expand(&uf, |g| lifted[g])
}

fn nonuniform_mesh(element: Element) -> Mesh {
    Mesh::from_lines(
        element,
        vec![-1.0, -0.3, 0.1, 0.8, 2.0],
        vec![0.0, 0.25, 1.1, 1.5],
        false,
    )
}

#[test]
fn patch_test_reproduces_a_linear_field() {
    let linear = |x: f64, y: f64| [0.3 + 1.2 * x - 0.7 * y, -0.4 + 0.5 * x + 0.9 * y];
    for (element, integration) in Element::ALL
        .iter()
        .flat_map(|&e| [(e, Integration::Full), (e, Integration::Selective)])
    {
        let mesh = nonuniform_mesh(element);
        let nearly_incompressible = Material {
            poisson: 0.4999,
            ..STEEL_LIKE
        };
        let form = Form::Elasticity(nearly_incompressible, integration);
        let u = dirichlet_solve_with(&mesh, form, &vec![0.0; 2 * mesh.n_nodes()], linear);
        let worst = (0..mesh.n_nodes())
            .map(|n| {
                let (x, y) = mesh.node_coords(n);
                let e = linear(x, y);
                (u[2 * n] - e[0]).abs().max((u[2 * n + 1] - e[1]).abs())
            })
            .fold(0.0, f64::max);
        assert!(
            worst < 1e-10,
            "{element:?} {integration:?}: linear field off by {worst:e}"
        );
    }
}

#[test]
fn patch_test_gives_the_uniform_stress_reactions() {
    // Uniaxial strain ε_xx = 1e-3 on [−1, 2] × [0, 1.5]: the reaction on the right side is
    // σ_xx · height = (λ + 2μ) ε_xx · 1.5, checked by summing K u over the right-side nodes.
    let (lambda, mu) = STEEL_LIKE.lame();
    for element in Element::ALL {
        let mesh = nonuniform_mesh(element);
        let u = dirichlet_solve(&mesh, STEEL_LIKE, &vec![0.0; 2 * mesh.n_nodes()], |x, _| {
            [1e-3 * x, 0.0]
        });
        let ku = apply(&mesh, Form::Elasticity(STEEL_LIKE, Integration::Full), &u);
        let nnx = mesh.nnx();
        let right: f64 = (0..mesh.node_y.len()).map(|j| ku[2 * (j * nnx + nnx - 1)]).sum();
        let expect = (lambda + 2.0 * mu) * 1e-3 * 1.5;
        assert!(
            (right - expect).abs() < 1e-10 * expect,
            "{element:?}: {right} vs {expect}"
        );
    }
}

/// The H¹ rates of the manufactured solution u = (sin πx sin πy, sin πx sin πy) on the unit
/// square ([`manufactured::h1_relative_error`]) from 4 to 32 cells across.
fn manufactured_rates(element: Element) -> Vec<f64> {
    let errors: Vec<f64> = [4, 8, 16, 32]
        .iter()
        .map(|&n| manufactured::h1_relative_error(element, n).unwrap())
        .collect();
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

#[test]
fn manufactured_solution_converges_at_rate_one_for_q1_and_p1() {
    for element in [Element::Q1, Element::P1] {
        let rates = manufactured_rates(element);
        let last = *rates.last().unwrap();
        assert!((0.95..1.1).contains(&last), "{element:?}: H¹ rates {rates:?}");
    }
}

#[test]
fn manufactured_solution_converges_at_rate_two_for_q2() {
    let rates = manufactured_rates(Element::Q2);
    let last = *rates.last().unwrap();
    assert!((1.9..2.15).contains(&last), "Q2: H¹ rates {rates:?}");
}

/// The stiffness of a body of the paper's kind (bottom clamped, Γ_C on top; a half model when
/// `symmetric`) with `nx` × `ny` cells, its dofs and Γ_C's normal dofs.
fn contact_body(
    element: Element,
    nx: usize,
    ny: usize,
    symmetric: bool,
) -> (Mesh, DofMap, SymCsc, Vec<usize>) {
    let mesh = Mesh::uniform(element, (0.0, 8.0, nx), (0.0, 4.0, ny), symmetric);
    let dofs = DofMap::model(&mesh);
    let k = assemble(&mesh, &dofs, Form::Elasticity(STEEL_LIKE, Integration::Full));
    let trace = mesh
        .top_nodes()
        .iter()
        .map(|&t| dofs.free_index(2 * t + 1).unwrap())
        .collect();
    (mesh, dofs, k, trace)
}

/// Every element, half and full models, even and odd numbers of cells across (Q2's middle
/// column is a vertex line, so its halves differ by a cell when the count is odd), wider and
/// higher than wide.
fn split_cases() -> impl Iterator<Item = (Element, usize, usize, bool)> {
    Element::ALL.into_iter().flat_map(|element| {
        [(16, 4), (13, 5), (6, 9)]
            .into_iter()
            .flat_map(move |(nx, ny)| [true, false].map(|symmetric| (element, nx, ny, symmetric)))
    })
}

/// The largest absolute entry.
fn max_abs(values: impl IntoIterator<Item = f64>) -> f64 {
    values.into_iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// The two-subdomain factor, and the whole grid as one part, give faer's single factor's
/// trace compliance C = E K⁻¹ Eᵀ and Schur complement factor; the one part also on
/// grids without a middle column.
#[test]
fn the_split_factor_has_the_single_factors_compliance() {
    let narrow = [
        (Element::Q2, 1, 3, true),
        (Element::Q1, 1, 4, false),
        (Element::P1, 1, 2, true),
    ];
    for (element, nx, ny, symmetric) in split_cases().chain(narrow) {
        let (mesh, dofs, k, trace) = contact_body(element, nx, ny, symmetric);
        let single = TraceFactor::new(&TraceOrdering::grid(&k, &mesh, &dofs, &trace).unwrap(), &k).unwrap();
        let orderings = SplitOrdering::new(&k, &mesh, &dofs, &trace)
            .unwrap()
            .into_iter()
            .chain([SplitOrdering::whole(&k, &mesh, &dofs, &trace).unwrap()]);
        for split in orderings {
            let split = SplitFactor::new(&split, &k).unwrap();
            assert_the_same_trace_blocks(&single, &split, trace.len(), (element, nx, ny, symmetric));
        }
    }
}

/// `single` and `split` have the same C and L_T (of order `m`) to 10⁻¹² relative.
fn assert_the_same_trace_blocks(
    single: &TraceFactor,
    split: &SplitFactor,
    m: usize,
    (element, nx, ny, symmetric): (Element, usize, usize, bool),
) {
    let parts = split.parts();
    for (name, a, b) in [
        ("C", single.compliance(), split.compliance()),
        ("L_T", single.schur_factor(), split.schur_factor()),
    ] {
        assert_eq!((a.nrows(), a.ncols()), (m, m));
        let scale = max_abs(a.col_iter().flat_map(|c| c.iter().copied().collect::<Vec<_>>()));
        let diff = max_abs(
            (0..a.ncols())
                .flat_map(|j| (0..a.nrows()).map(move |i| (i, j)))
                .map(|(i, j)| a[(i, j)] - b[(i, j)]),
        );
        assert!(
            diff <= 1e-12 * scale,
            "{element:?} {nx}×{ny} symmetric={symmetric}, {parts} parts: {name} differs by {diff:e} (scale {scale:e})"
        );
    }
}

/// A factor grown in K's own arrays (its values and row indices, given up to the factor to
/// save fresh memory) has the same bits as one in fresh memory: nothing of K's contents stays
/// in it.
#[test]
fn a_factor_in_ks_memory_is_the_factor_in_fresh_memory() {
    for (element, nx, ny, symmetric) in split_cases() {
        let (mesh, dofs, k, trace) = contact_body(element, nx, ny, symmetric);
        let ordering = SplitOrdering::new(&k, &mesh, &dofs, &trace).unwrap().unwrap();
        let fresh = SplitFactor::new(&ordering, &k).unwrap();
        let reused = SplitFactor::of_values(&ordering, ordering.values_of(k.clone())).unwrap();
        let bits = |m: faer::Mat<f64>| -> Vec<u64> {
            m.col_iter()
                .flat_map(|c| c.iter().map(|v| v.to_bits()).collect::<Vec<_>>())
                .collect()
        };
        assert_eq!(
            bits(fresh.compliance()),
            bits(reused.compliance()),
            "{element:?} {nx}×{ny}"
        );
        let f = right_hand_sides(k.n, 2);
        let (mut a, mut b) = (f.clone(), f);
        fresh.solve_in_place(&mut a, 2);
        reused.solve_in_place(&mut b, 2);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b), "{element:?} {nx}×{ny}: u");
    }
}

/// Right-hand sides with every entry non-zero, the same on every run.
fn right_hand_sides(n: usize, ncols: usize) -> Vec<f64> {
    (0..n * ncols)
        .map(|k| ((k * 7919 + 17) % 2003) as f64 / 1001.0 - 1.0)
        .collect()
}

/// A solve with the two-subdomain factor, and with the whole grid as one part, is the single
/// factor's, and K u = f.
#[test]
fn the_split_factor_solves_as_the_single_factor() {
    for ((element, nx, ny, symmetric), halves) in split_cases().flat_map(|c| [(c, true), (c, false)]) {
        let (mesh, dofs, k, trace) = contact_body(element, nx, ny, symmetric);
        let single = TraceFactor::new(&TraceOrdering::grid(&k, &mesh, &dofs, &trace).unwrap(), &k).unwrap();
        let split = match halves {
            true => SplitOrdering::new(&k, &mesh, &dofs, &trace).unwrap().unwrap(),
            false => SplitOrdering::whole(&k, &mesh, &dofs, &trace).unwrap(),
        };
        let split = SplitFactor::new(&split, &k).unwrap();
        let f = right_hand_sides(k.n, 3);
        let (mut u, mut expect) = (f.clone(), f.clone());
        split.solve_in_place(&mut u, 3);
        single.solve_in_place(&mut expect, 3);
        let scale = max_abs(expect.iter().copied());
        let diff = max_abs(u.iter().zip(&expect).map(|(a, b)| a - b));
        assert!(
            diff <= 1e-12 * scale,
            "{element:?} {nx}×{ny}, halves {halves}: u differs by {diff:e} (scale {scale:e})"
        );
        for j in 0..3 {
            let (uj, fj) = (&u[j * k.n..(j + 1) * k.n], &f[j * k.n..(j + 1) * k.n]);
            let residual = max_abs(k.mul(uj).iter().zip(fj).map(|(a, b)| a - b));
            assert!(
                residual <= 1e-10,
                "{element:?} {nx}×{ny}: ‖K u − f‖∞ = {residual:e}"
            );
        }
    }
}
