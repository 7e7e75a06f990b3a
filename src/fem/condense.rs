//! Condensation of a symmetric positive definite form onto the trace dofs of Γ_C.
//!
//! The matrix is factorised once, A = Pᵀ L Lᵀ P, with an ordering that eliminates every other
//! dof first (the grid's nested dissection, [`super::ordering`], or approximate minimum degree
//! for any pattern) and the `trace` dofs last. The trailing
//! block L_cc of L then satisfies L_cc L_ccᵀ = S, the Schur complement of A on the trace dofs,
//! and the *trace compliance* C = E A⁻¹ Eᵀ = S⁻¹ follows from dense work of the trace's size:
//! no solve per trace dof. The same factor solves with A when the full field is wanted.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::perm::PermRef;

use faer::sparse::SymbolicSparseColMatRef;
use faer::sparse::linalg::cholesky::simplicial::SymbolicSimplicialCholesky;
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::linalg::{SupernodalThreshold, amd};
use faer::traits::Index;
use faer::{Conj, Mat, MatMut, Par, Side};

use super::SymCsc;
use super::dofs::DofMap;
use super::error::FemError;
use super::memory::Limits;
use super::ordering::nested_dissection;
use super::supernodes::Supernodes;
use crate::mesh::Mesh;

mod blocks;
pub(in crate::fem) use blocks::{Blocks, compliance_of};

/// The symbolic analysis of a pattern with the trace dofs ordered last (one per mesh).
#[derive(Clone)]
pub struct TraceOrdering {
    /// faer's analysis of the pattern in the dofs' order, with the permutation it was given
    /// or chose; supernodal or simplicial.
    symbolic: Arc<SymbolicCholesky<usize>>,
    /// The trace dofs, in the order of C's rows and columns.
    trace: Vec<usize>,
}

/// The layout of a factor's values: faer's supernodes or one column at a time, or supernodes
/// read from the grid ([`super::supernodes`]).
pub(super) enum Layout<'a, I: Index> {
    Supernodal(&'a SymbolicSupernodalCholesky<I>),
    Simplicial(&'a SymbolicSimplicialCholesky<I>),
    Grid(&'a Supernodes<I>),
}

impl<'a, I: Index> Layout<'a, I> {
    fn of(symbolic: &'a SymbolicCholesky<I>) -> Self {
        match symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => Layout::Supernodal(s),
            SymbolicCholeskyRaw::Simplicial(s) => Layout::Simplicial(s),
        }
    }
}

impl TraceOrdering {
    /// Analyse the pattern of `a` (lower triangle) with `trace` (free dof indices) last and
    /// approximate minimum degree on the other dofs: for any pattern.
    pub fn new(a: &SymCsc, trace: &[usize]) -> Result<Self, FemError> {
        let n = a.n;
        let mut is_trace = vec![false; n];
        for &d in trace {
            is_trace[d] = true;
        }
        // The pattern of the other dofs, renumbered, for the minimum degree ordering.
        let mut local = vec![usize::MAX; n];
        let mut global = Vec::with_capacity(n - trace.len());
        for d in (0..n).filter(|&d| !is_trace[d]) {
            local[d] = global.len();
            global.push(d);
        }
        let ni = global.len();
        let (mut col_ptr, mut row_idx) = (Vec::with_capacity(ni + 1), Vec::with_capacity(a.nnz()));
        col_ptr.push(0);
        for &c in &global {
            for k in a.col_ptr[c]..a.col_ptr[c + 1] {
                let r = a.row_idx[k];
                if !is_trace[r] {
                    row_idx.push(local[r]);
                }
            }
            col_ptr.push(row_idx.len());
        }
        let (mut perm, mut perm_inv) = (vec![0usize; ni], vec![0usize; ni]);
        let interior = SymbolicSparseColMatRef::new_checked(ni, ni, &col_ptr, None, &row_idx);
        let mut mem = MemBuffer::try_new(amd::order_scratch::<usize>(ni, row_idx.len()))
            .map_err(|_| FemError::OutOfMemory("the ordering"))?;
        amd::order(
            &mut perm,
            &mut perm_inv,
            interior,
            amd::Control::default(),
            MemStack::new(&mut mem),
        )
        .map_err(FemError::from_faer("the ordering"))?;
        Self::with_interior_order(
            a,
            perm.iter().map(|&k| global[k]).collect(),
            trace,
            SupernodalThreshold::AUTO,
        )
    }

    /// Analyse the pattern of `a`, the form on `mesh` over `dofs`, with `trace` last and the
    /// grid's nested dissection on the other dofs ([`super::ordering`]).
    pub fn grid(a: &SymCsc, mesh: &Mesh, dofs: &DofMap, trace: &[usize]) -> Result<Self, FemError> {
        // Supernodal at every size: faer's flop-ratio rule picks the simplicial layout for this
        // order below ~10⁴ unknowns, 2.7× slower at level 3 (4128 unknowns).
        Self::with_interior_order(
            a,
            nested_dissection(mesh, dofs, trace),
            trace,
            SupernodalThreshold::FORCE_SUPERNODAL,
        )
    }

    /// Analyse the pattern of `a` with `interior` (every free dof but the trace, in an order
    /// made elsewhere) first and `trace` last, supernodal as [`TraceOrdering::grid`]: for
    /// comparing other fill-reducing orders (the METIS row of `benches/ordering.rs`).
    pub fn with_order(a: &SymCsc, interior: Vec<usize>, trace: &[usize]) -> Result<Self, FemError> {
        Self::with_interior_order(a, interior, trace, SupernodalThreshold::FORCE_SUPERNODAL)
    }

    /// The symbolic analysis for the elimination order `interior` followed by `trace`.
    fn with_interior_order(
        a: &SymCsc,
        interior: Vec<usize>,
        trace: &[usize],
        supernodal: SupernodalThreshold,
    ) -> Result<Self, FemError> {
        let n = a.n;
        let mut fwd = interior;
        fwd.extend_from_slice(trace);
        let mut inv = vec![0usize; n];
        for (k, &d) in fwd.iter().enumerate() {
            inv[d] = k;
        }
        let symbolic = factorize_symbolic_cholesky(
            a.symbolic(),
            Side::Lower,
            SymmetricOrdering::Custom(PermRef::new_checked(&fwd, &inv, n)),
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: supernodal,
                ..Default::default()
            },
        )
        .map_err(FemError::from_faer("the symbolic factorisation"))?;
        Ok(TraceOrdering {
            symbolic: Arc::new(symbolic),
            trace: trace.to_vec(),
        })
    }

    /// The number of stored values of the factor L (explicit zeros of merged supernodes
    /// included): its memory is eight bytes each.
    pub fn factor_len(&self) -> usize {
        self.symbolic.len_val()
    }

    /// Floating point operations of one numeric factorisation ([`factor_flops`]).
    pub fn factor_flops(&self) -> f64 {
        factor_flops(&self.symbolic)
    }

    /// Whether faer chose its supernodal (blocked) factorisation for this pattern.
    pub fn is_supernodal(&self) -> bool {
        matches!(Layout::of(&self.symbolic), Layout::Supernodal(_))
    }
}

/// Floating point operations of one numeric factorisation on `symbolic`: Σ_j c_j² over the
/// columns of L with c_j stored values (c_j divisions and about c_j² multiply-adds of the
/// updates it sends, the count of George and Liu).
pub fn factor_flops<I: Index>(symbolic: &SymbolicCholesky<I>) -> f64 {
    let square = |c: usize| (c as f64) * (c as f64);
    match symbolic.raw() {
        SymbolicCholeskyRaw::Supernodal(sym) => (0..sym.n_supernodes())
            .map(|s| {
                let below = sym.supernode(s).pattern().len();
                let width = sym.supernode_end()[s].zx() - sym.supernode_begin()[s].zx();
                (1..=width).map(|k| square(k + below)).sum::<f64>()
            })
            .sum(),
        SymbolicCholeskyRaw::Simplicial(sym) => sym
            .col_ptr()
            .windows(2)
            .map(|w| square(w[1].zx() - w[0].zx()))
            .sum(),
    }
}

/// A numeric factorisation on a [`TraceOrdering`].
pub struct TraceFactor {
    ordering: TraceOrdering,
    values: Vec<f64>,
}

impl TraceFactor {
    /// Factorise `a`, whose pattern is the one `ordering` analysed, on the threads of
    /// [`super::set_threads`].
    pub fn new(ordering: &TraceOrdering, a: &SymCsc) -> Result<Self, FemError> {
        let symbolic = &*ordering.symbolic;
        let par = super::sparse_parallelism(a.n);
        let scratch = symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default());
        let mut factor = factor_storage(symbolic.len_val(), scratch, a.n, Vec::new())?;
        let mut mem = MemBuffer::try_new(scratch)
            .map_err(|_| FemError::OutOfMemory("the factorisation's workspace"))?;
        symbolic
            .factorize_numeric_llt(
                &mut factor,
                a.view(&a.values),
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            // The numeric factorisation's only failure is a non-positive pivot.
            .map_err(FemError::from)?;
        Ok(TraceFactor {
            ordering: ordering.clone(),
            values: factor,
        })
    }
}

/// The zeroed storage of a factor of `len_val` values, with `scratch` beside it, for a matrix
/// of `unknowns` rows, in `storage`'s memory (its contents discarded; an empty vector when
/// there is none to reuse). The factor's exact size is known here: it is refused, rather than
/// the process killed for it, when it does not fit in what the process may still use.
pub(super) fn factor_storage(
    len_val: usize,
    scratch: StackReq,
    unknowns: usize,
    storage: Vec<f64>,
) -> Result<Vec<f64>, FemError> {
    let need = (8 * len_val + scratch.unaligned_bytes_required()) as u64;
    match Limits::of_process().available() {
        Some(available) if need > available => {
            return Err(FemError::TooLarge {
                unknowns,
                need,
                available,
            });
        }
        _ => {}
    }
    let mut factor = storage;
    factor.clear();
    factor
        .try_reserve_exact(len_val)
        .map_err(|_| FemError::OutOfMemory("the factor"))?;
    factor.resize(len_val, 0.0);
    Ok(factor)
}

impl TraceFactor {
    /// Solve A X = B in place for the `ncols` columns of the column-major `b`.
    pub fn solve_in_place(&self, b: &mut [f64], ncols: usize) {
        let symbolic = &*self.ordering.symbolic;
        let b = MatMut::from_column_major_slice_mut(b, symbolic.nrows(), ncols);
        let mut mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(ncols, Par::Seq));
        LltRef::new(symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            b,
            Par::Seq,
            MemStack::new(&mut mem),
        );
    }

    /// The factor's blocks of columns, in elimination order.
    fn blocks(&self) -> Blocks<'_, usize> {
        let symbolic = &*self.ordering.symbolic;
        Blocks::new(
            Layout::of(symbolic),
            &self.values,
            symbolic.nrows() - self.ordering.trace.len(),
        )
    }

    /// The trailing block L_cc of L (trace dofs, in the ordering's trace order):
    /// L_cc L_ccᵀ is the Schur complement of A on the trace dofs.
    pub fn schur_factor(&self) -> Mat<f64> {
        self.blocks().trailing_block()
    }

    /// The trace compliance C = E A⁻¹ Eᵀ = (L_cc L_ccᵀ)⁻¹ = L_cc⁻ᵀ L_cc⁻¹.
    pub fn compliance(&self) -> Mat<f64> {
        let l = self.schur_factor();
        compliance_of(l.as_ref(), super::dense_parallelism(l.nrows()))
    }
}

#[cfg(test)]
mod tests {
    use faer::linalg::triangular_solve;
    use faer::reborrow::ReborrowMut;

    use super::*;
    use crate::fem::{DofMap, Form, Integration, assemble};
    use crate::material::{Material, Plane};
    use crate::mesh::{Element, Mesh};

    /// A body held nowhere has rigid motions: its stiffness's factorisation fails with the
    /// pivot faer met as a number, not a message. (Here faer names n, the end of the last
    /// block, where round-off left the rigid motions' pivots: hence ≤ n.)
    #[test]
    fn a_free_body_reports_its_pivot() {
        let mesh = Mesh::uniform(Element::Q1, (0.0, 2.0, 4), (0.0, 1.0, 3), true);
        let dofs = DofMap::new(mesh.n_nodes(), |_, _| false);
        let material = Material {
            young: 3.0,
            poisson: 0.3,
            plane: Plane::Strain,
        };
        let a = assemble(&mesh, &dofs, Form::Elasticity(material, Integration::Full));
        let ordering = TraceOrdering::new(&a, &[]).unwrap();
        match TraceFactor::new(&ordering, &a) {
            Err(FemError::NotPositiveDefinite { pivot }) => assert!(pivot <= a.n, "{pivot} of {}", a.n),
            Err(e) => panic!("another failure: {e}"),
            Ok(_) => panic!("a free body factorised"),
        }
    }

    /// C from the trailing block equals the trace rows of A⁻¹ computed by plain solves.
    #[test]
    fn compliance_equals_solves() {
        let mut layouts = [false, false];
        for element in Element::ALL {
            for n in [2, 9, 40] {
                let mesh = Mesh::uniform(element, (0.0, 2.0, n), (0.0, 1.0, n / 2 + 1), true);
                let dofs = DofMap::model(&mesh);
                let a = assemble(
                    &mesh,
                    &dofs,
                    Form::Elasticity(
                        Material {
                            young: 3.0,
                            poisson: 0.3,
                            plane: Plane::Strain,
                        },
                        Integration::Full,
                    ),
                );
                let trace: Vec<usize> = mesh
                    .top_nodes()
                    .iter()
                    .map(|&t| dofs.free_index(2 * t + 1).unwrap())
                    .collect();
                let orderings = [
                    TraceOrdering::new(&a, &trace).unwrap(),
                    TraceOrdering::grid(&a, &mesh, &dofs, &trace).unwrap(),
                ];
                for ordering in &orderings {
                    layouts[usize::from(ordering.is_supernodal())] = true;
                    let factor = TraceFactor::new(ordering, &a).unwrap();
                    let c = factor.compliance();
                    let nc = trace.len();
                    let mut rhs = vec![0.0; a.n * nc];
                    for (j, &d) in trace.iter().enumerate() {
                        rhs[j * a.n + d] = 1.0;
                    }
                    factor.solve_in_place(&mut rhs, nc);
                    for j in 0..nc {
                        // The solve is right: A x = e_j.
                        let x = &rhs[j * a.n..(j + 1) * a.n];
                        let ax = a.mul(x);
                        assert!(
                            ax.iter()
                                .enumerate()
                                .all(|(i, v)| (v - f64::from(i == trace[j])).abs() < 1e-10)
                        );
                        for (i, &d) in trace.iter().enumerate() {
                            assert!(
                                (c[(i, j)] - x[d]).abs() < 1e-10 * x[trace[j]].abs(),
                                "{element:?} n={n} C[{i},{j}]"
                            );
                            // C is symmetric to the bit, as the Newton's dense solves assume.
                            assert_eq!(c[(i, j)].to_bits(), c[(j, i)].to_bits(), "{element:?} n={n}");
                        }
                    }
                }
            }
        }
        assert_eq!(
            layouts,
            [true, true],
            "both the simplicial and the supernodal layout are checked"
        );
    }

    /// Eliminating the interior, solving with the trailing block L_cc L_ccᵀ = S and
    /// back-substituting the interior is a solve with A, on both layouts of the factor and
    /// for supernodes that straddle the interior's end.
    #[test]
    fn interior_elimination_and_back_substitution_solve_with_a() {
        let mut layouts = [false, false];
        for element in Element::ALL {
            for n in [3, 12, 40] {
                let mesh = Mesh::uniform(element, (0.0, 2.0, n), (0.0, 1.0, n / 2 + 1), false);
                let dofs = DofMap::model(&mesh);
                let a = assemble(&mesh, &dofs, Form::H1);
                let trace: Vec<usize> = mesh
                    .top_nodes()
                    .iter()
                    .map(|&t| dofs.free_index(2 * t + 1).unwrap())
                    .collect();
                for ordering in [
                    TraceOrdering::new(&a, &trace).unwrap(),
                    TraceOrdering::grid(&a, &mesh, &dofs, &trace).unwrap(),
                ] {
                    layouts[usize::from(ordering.is_supernodal())] = true;
                    let factor = TraceFactor::new(&ordering, &a).unwrap();
                    let perm = ordering.symbolic.perm().unwrap().arrays().0.to_vec();
                    let f: Vec<f64> = (0..2 * a.n).map(|k| ((k * 7919) % 113) as f64 - 56.0).collect();
                    let mut expect = f.clone();
                    factor.solve_in_place(&mut expect, 2);
                    // In elimination order: eliminate, solve S u_c = x_c, back-substitute.
                    let mut x = Mat::<f64>::from_fn(a.n, 2, |p, j| f[j * a.n + perm[p]]);
                    factor.blocks().eliminate_interior(x.as_mut());
                    let l = factor.schur_factor();
                    let n0 = a.n - trace.len();
                    let mut trailing = x.as_mut().subrows_mut(n0, trace.len());
                    triangular_solve::solve_lower_triangular_in_place(
                        l.as_ref(),
                        trailing.rb_mut(),
                        Par::Seq,
                    );
                    triangular_solve::solve_upper_triangular_in_place(l.transpose(), trailing, Par::Seq);
                    factor.blocks().back_substitute_interior(x.as_mut());
                    let scale = expect.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    for j in 0..2 {
                        for (p, &d) in perm.iter().enumerate() {
                            assert!(
                                (x[(p, j)] - expect[j * a.n + d]).abs() <= 1e-12 * scale,
                                "{element:?} n={n} supernodal={}",
                                ordering.is_supernodal()
                            );
                        }
                    }
                }
            }
        }
        assert_eq!(layouts, [true, true], "both layouts are checked");
    }

    /// The grid's nested dissection beats minimum degree with Γ_C last, for every
    /// element, and the flop count
    /// is Σ c_j² over L's columns (a dense n×n factor: Σ_{c=1}^{n} c²).
    #[test]
    fn nested_dissection_needs_fewer_flops() {
        let material = Material {
            young: 3.0,
            poisson: 0.3,
            plane: Plane::Strain,
        };
        for element in Element::ALL {
            let mesh = Mesh::uniform(
                element,
                (0.0, 16.0, 128 / element.order()),
                (0.0, 4.0, 32 / element.order()),
                true,
            );
            let dofs = DofMap::model(&mesh);
            let a = assemble(&mesh, &dofs, Form::Elasticity(material, Integration::Full));
            let trace: Vec<usize> = mesh
                .top_nodes()
                .iter()
                .map(|&t| dofs.free_index(2 * t + 1).unwrap())
                .collect();
            let grid = TraceOrdering::grid(&a, &mesh, &dofs, &trace).unwrap();
            let amd = TraceOrdering::new(&a, &trace).unwrap();
            assert!(
                grid.factor_flops() < 0.85 * amd.factor_flops(),
                "{element:?}: {:.3e} against {:.3e}",
                grid.factor_flops(),
                amd.factor_flops()
            );
        }
        // One Q2 cell: all 10 free dofs couple, L is dense.
        let mesh = Mesh::uniform(Element::Q2, (0.0, 1.0, 1), (0.0, 1.0, 1), false);
        let dofs = DofMap::model(&mesh);
        let a = assemble(&mesh, &dofs, Form::Elasticity(material, Integration::Full));
        let ordering = TraceOrdering::new(&a, &[]).unwrap();
        assert_eq!(dofs.n_free(), 12);
        assert_eq!(ordering.factor_len(), 12 * 13 / 2);
        assert_eq!(
            ordering.factor_flops(),
            (1..=12).map(|c| f64::from(c * c)).sum::<f64>()
        );
    }
}
