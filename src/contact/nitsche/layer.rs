//! The layer of Nitsche's condensation (module doc of [`super`]): the dofs the rows of σ_n and u_n
//! use at the edge points of Γ_C, and K factorised with them last, its trailing block L_BB.

use faer::Mat;

use crate::contact::{ContactPoints, Rule};
use crate::discretization::{Discretization, fem_error};
use crate::error::{SolveError, Workload};
use crate::fem::basis::lagrange_1d;
use crate::fem::factor::{Analysis, Factor};
use crate::fem::memory::Limits;
use crate::fem::{Form, assemble};
use crate::material::Material;
use crate::mesh::{Diagonal, Element, Mesh};
use crate::stress::Stress;

/// K factorised with the layer's dofs last: L_BB, the trailing block, with L_BB L_BBᵀ the
/// Schur complement of K on the layer.
pub(super) struct Layer {
    /// For each free dof, its position in the layer (usize::MAX when outside it).
    pub(super) position: Vec<usize>,
    pub(super) l: Mat<f64>,
}

/// A linear functional of the displacement: Σ c·u over (free dof, c).
pub(super) type Row = Vec<(usize, f64)>;

/// One point of the rule on one edge of Γ_C, with the rows of σ_n and u_n there.
#[derive(Clone, Debug)]
pub(super) struct EdgePoint {
    /// The distinct point of [`ContactPoints`] it is.
    pub(super) point: usize,
    /// w_i^e h_e of (10).
    pub(super) weight: f64,
    /// The boundary cell's longest side.
    pub(super) h: f64,
    /// σ_n.
    pub(super) sigma: Row,
    /// u_n.
    pub(super) normal: Row,
}

/// The cell shape functions of the boundary cell over edge `ci` at the point s ∈ [0, 1] of
/// its top edge: (node, value, gradient). For P1 the triangle with the top edge.
pub(super) fn top_shape(mesh: &Mesh, ci: usize, s: f64) -> Vec<(usize, f64, [f64; 2])> {
    let cj = mesh.ny() - 1;
    let (x0, x1, y0, y1) = mesh.cell_rect(ci, cj);
    let (a, b) = (x1 - x0, y1 - y0);
    let nodes = mesh.cell_nodes(ci, cj);
    match mesh.element {
        Element::Q1 | Element::Q2 => {
            let p = mesh.element.order();
            let ((nx, dx), (ny, dy)) = (lagrange_1d(p, 2.0 * s - 1.0), lagrange_1d(p, 1.0));
            let mut out = Vec::with_capacity(nodes.len());
            for lj in 0..=p {
                for li in 0..=p {
                    out.push((
                        nodes[lj * (p + 1) + li],
                        nx[li] * ny[lj],
                        [dx[li] * ny[lj] * 2.0 / a, nx[li] * dy[lj] * 2.0 / b],
                    ));
                }
            }
            out
        }
        // Corners in tensor order 0 = (x0,y0), 1 = (x1,y0), 2 = (x0,y1), 3 = (x1,y1); the top
        // edge 2–3 lies in (0,3,2) for a rising diagonal, (1,3,2) for a falling one.
        Element::P1 => match mesh.diagonal(ci) {
            Diagonal::Rising => vec![
                (nodes[0], 0.0, [0.0, -1.0 / b]),
                (nodes[3], s, [1.0 / a, 0.0]),
                (nodes[2], 1.0 - s, [-1.0 / a, 1.0 / b]),
            ],
            Diagonal::Falling => vec![
                (nodes[1], 0.0, [0.0, -1.0 / b]),
                (nodes[3], s, [1.0 / a, 1.0 / b]),
                (nodes[2], 1.0 - s, [-1.0 / a, 0.0]),
            ],
        },
    }
}

/// The rows of σ_n = σ_yy (the full tensor of (2) at the point, [`Stress`]) and u_n = u_y at
/// s on the top edge of cell `ci`, over free dofs.
pub(super) fn rows(disc: &Discretization, material: &Material, ci: usize, s: f64) -> (Row, Row) {
    let (mut sigma, mut normal) = (Vec::new(), Vec::new());
    for (node, value, g) in top_shape(&disc.mesh, ci, s) {
        for comp in 0..2 {
            let Some(dof) = disc.dofs.free_index(2 * node + comp) else {
                continue;
            };
            // σ is linear in the gradient (u_x,x, u_x,y, u_y,x, u_y,y): the dof's coefficient
            // is the stress of its shape function's gradient.
            let mut grad = [0.0; 4];
            grad[2 * comp] = g[0];
            grad[2 * comp + 1] = g[1];
            let c = Stress::of_gradient(material, grad, None).yy;
            if c != 0.0 {
                sigma.push((dof, c));
            }
            if comp == 1 && value != 0.0 {
                normal.push((dof, value));
            }
        }
    }
    (sigma, normal)
}

/// The rule's points on every edge, with their rows.
pub(super) fn edge_points(
    disc: &Discretization,
    material: &Material,
    points: &ContactPoints,
) -> Vec<EdgePoint> {
    let mut out = Vec::new();
    let cj = disc.mesh.ny() - 1;
    for (e, mine) in points.edge_points.iter().enumerate() {
        let (x0, x1, y0, y1) = disc.mesh.cell_rect(e, cj);
        for (&point, (s, w)) in mine.iter().zip(points.rule.points()) {
            let (sigma, normal) = rows(disc, material, e, s);
            out.push(EdgePoint {
                point,
                weight: w * (x1 - x0),
                h: (x1 - x0).max(y1 - y0),
                sigma,
                normal,
            });
        }
    }
    out
}

/// The layer B: the free dofs the rows of σ_n and u_n use at any rule's points on Γ_C's edges,
/// node column by node column, so that a point's rows start late in the layer when it lies
/// far along Γ_C ([`Layer::couplings`] skips the leading zeros). G = R K⁻¹ Rᵀ needs K's Schur
/// complement on no more than these: u_x of Γ_C's nodes and u_y of the nodes of the elements
/// on Γ_C (σ_yy = λ u_x,x + (λ + 2μ) u_y,y on the top edge, where u_x,x sees only the edge's
/// nodes), about three dofs per node column for Q1 and P1 and four for Q2, where every dof of
/// those elements would be four and six.
pub(super) fn layer_dofs(disc: &Discretization) -> Vec<usize> {
    let mesh = &disc.mesh;
    let mut used = vec![false; disc.n_dofs()];
    for ci in 0..mesh.nx() {
        for (s, _) in Rule::ALL.iter().flat_map(|r| r.points()) {
            let (sigma, normal) = rows(disc, &disc.material, ci, s);
            for (d, _) in sigma.into_iter().chain(normal) {
                used[d] = true;
            }
        }
    }
    let nny = mesh.node_y.len();
    let below = nny.saturating_sub(mesh.element.order() + 1);
    let mut dofs = Vec::new();
    for i in 0..mesh.nnx() {
        for j in below..nny {
            for comp in 0..2 {
                if let Some(d) = disc
                    .dofs
                    .free_index(2 * mesh.node(i, j) + comp)
                    .filter(|&d| used[d])
                {
                    dofs.push(d);
                }
            }
        }
    }
    dofs
}

impl Layer {
    /// Factorise K with the layer's dofs last ([`layer_dofs`]; two subdomains on two cores
    /// from [`crate::fem::factor::SPLIT_UNKNOWNS`] unknowns, as the mesh's own factor) and keep
    /// the Schur complement's factor.
    pub(super) fn build(disc: &Discretization) -> Result<Layer, SolveError> {
        let mesh = &disc.mesh;
        let dofs = layer_dofs(disc);
        let n = disc.n_dofs();
        // The dense work: L_BB, the couplings' right-hand sides (at most 3 points per edge, and
        // the vertices), G and the operator's n×n matrices.
        let (nb, points) = (dofs.len() as u64, 3 * mesh.nx() as u64);
        let need = 8 * (nb * nb + nb * (2 * points + points / 3 + 1) + 12 * points * points);
        if let Some(available) = Limits::of_process().available()
            && need > available
        {
            return Err(SolveError::TooLarge {
                workload: Workload::Nitsche,
                unknowns: nb as usize,
                need,
                available,
            });
        }
        let stiffness = assemble(
            mesh,
            &disc.dofs,
            Form::Elasticity(disc.material, disc.integration),
        );
        // The layer alone last: the elements' other dofs just before it cost fewer flops with
        // faer's single factor, but 9–22% more instructions in a fresh solve with the whole
        // grid as one part, whose dense S they join (BENCHMARKS.md, "Nitsche's operator and the
        // active-set systems").
        let analysis = Analysis::grid(&stiffness, mesh, &disc.dofs, &dofs).map_err(|e| fem_error(e, n))?;
        let factor = Factor::new(&analysis, stiffness).map_err(|e| fem_error(e, n))?;
        let mut position = vec![usize::MAX; n];
        for (k, &d) in dofs.iter().enumerate() {
            position[d] = k;
        }
        Ok(Layer {
            position,
            l: factor.schur_factor(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::newton::active_forces;
    use super::*;
    use crate::fem::basis::evaluate;
    use crate::scenario::Scenario;

    /// The layer is u_x of Γ_C's nodes and u_y of the nodes of the elements on Γ_C (two node
    /// rows of the boundary cells for Q1, three for Q2; for P1 Γ_C's nodes and each top
    /// triangle's third vertex), the free ones, counted here from the dof map: distinct free
    /// dofs of the boundary cells.
    #[test]
    fn the_layer_is_the_dofs_the_rows_use() {
        for element in Element::ALL {
            let disc = Scenario::paper().discretize(2, element).unwrap();
            let mesh = &disc.mesh;
            let nny = mesh.node_y.len();
            let free = |i, j, comp| disc.dofs.free_index(2 * mesh.node(i, j) + comp).is_some();
            let rows = match element {
                Element::Q2 => 3,
                Element::Q1 | Element::P1 => 2,
            };
            // P1's third vertices: below the left end of a rising diagonal's cell, below the
            // right end of a falling one's.
            let third: Vec<usize> = (0..mesh.nx())
                .map(|ci| match mesh.diagonal(ci) {
                    Diagonal::Rising => ci,
                    Diagonal::Falling => ci + 1,
                })
                .collect();
            let below = |i: usize, j: usize| element != Element::P1 || j == nny - 1 || third.contains(&i);
            let expected: usize = (0..mesh.nnx())
                .map(|i| {
                    usize::from(free(i, nny - 1, 0))
                        + (nny - rows..nny)
                            .filter(|&j| below(i, j) && free(i, j, 1))
                            .count()
                })
                .sum();
            let in_cells: std::collections::BTreeSet<usize> = (0..mesh.nnx())
                .flat_map(|i| (nny - rows..nny).flat_map(move |j| [(i, j, 0), (i, j, 1)]))
                .filter_map(|(i, j, comp)| disc.dofs.free_index(2 * mesh.node(i, j) + comp))
                .collect();
            let layer = layer_dofs(&disc);
            assert_eq!(layer.len(), expected, "{element:?}");
            let distinct: std::collections::BTreeSet<usize> = layer.iter().copied().collect();
            assert!(
                distinct.len() == layer.len() && distinct.is_subset(&in_cells),
                "{element:?}: distinct dofs of the boundary cells"
            );
            assert!(
                layer.len() < 2 * rows * mesh.nnx() - 1,
                "{element:?}: fewer than the cells' dofs"
            );
        }
    }

    /// K's Schur complement on the layer is the same from two subdomains (the split the layer
    /// uses from 50,000 unknowns), from faer's one factor, and from the layer's own factor (the
    /// whole grid as one part, below 50,000), to round-off.
    #[test]
    fn the_layers_schur_complement_is_the_same_split_or_whole() {
        for element in [Element::Q1, Element::Q2] {
            let disc = Scenario::paper().discretize(3, element).unwrap();
            let stiffness = assemble(
                &disc.mesh,
                &disc.dofs,
                Form::Elasticity(disc.material, disc.integration),
            );
            let dofs = layer_dofs(&disc);
            let schur = |analysis: Analysis| {
                let l = Factor::new(&analysis, stiffness.clone()).unwrap().schur_factor();
                l.as_ref() * l.transpose()
            };
            let split = Analysis::split(&stiffness, &disc.mesh, &disc.dofs, &dofs).unwrap();
            assert!(matches!(split, Analysis::Split(_)), "{element:?}");
            let whole = Analysis::whole(&stiffness, &disc.mesh, &disc.dofs, &dofs).unwrap();
            let l = Layer::build(&disc).unwrap().l;
            let (a, b, c) = (schur(split), schur(whole), l.as_ref() * l.transpose());
            let scale = b.norm_max();
            assert!((&a - &b).norm_max() <= 1e-11 * scale, "{element:?}");
            assert!((&c - &b).norm_max() <= 1e-11 * scale, "{element:?}");
        }
    }

    /// Where Cholesky fails on a symmetric active-set matrix (indefinite: [[0, 2], [2, 0]]),
    /// LU solves it: (2ỹ₂, 2ỹ₁) = (2, 4).
    #[test]
    fn active_forces_fall_back_to_lu_where_cholesky_fails() {
        let h = Mat::<f64>::from_fn(2, 2, |i, j| if i == j { -1.0 } else { 2.0 });
        let y = active_forces(&h, &[1.0, 1.0], &[2.0, 4.0], &[0, 1], true).unwrap();
        assert_eq!(y, [2.0, 1.0]);
    }

    /// The boundary cell's shape functions at the top edge agree with the field evaluation of
    /// `basis::evaluate` just below it (inside the same element), for a random field.
    #[test]
    fn top_shape_matches_the_field_evaluation() {
        for element in Element::ALL {
            let mesh = Mesh::uniform(element, (-2.0, 2.0, 4), (0.0, 1.5, 2), false);
            let u: Vec<f64> = (0..2 * mesh.n_nodes())
                .map(|k| ((k * 7919) % 101) as f64 / 50.0 - 1.0)
                .collect();
            let top = mesh.ys[mesh.ys.len() - 1];
            for ci in 0..mesh.nx() {
                for s in [0.2, 0.5, 0.7] {
                    let x = mesh.xs[ci] + s * (mesh.xs[ci + 1] - mesh.xs[ci]);
                    let (val, grad) = evaluate(&mesh, &u, x, top - 1e-12);
                    let (mut v, mut g) = ([0.0; 2], [0.0; 4]);
                    for (node, n, d) in top_shape(&mesh, ci, s) {
                        for c in 0..2 {
                            v[c] += n * u[2 * node + c];
                            g[2 * c] += d[0] * u[2 * node + c];
                            g[2 * c + 1] += d[1] * u[2 * node + c];
                        }
                    }
                    for k in 0..2 {
                        assert!((v[k] - val[k]).abs() < 1e-9, "{element:?} value");
                    }
                    for k in 0..4 {
                        assert!(
                            (g[k] - grad[k]).abs() < 1e-9,
                            "{element:?} {ci} {s} {g:?} {grad:?}"
                        );
                    }
                }
            }
        }
    }
}
