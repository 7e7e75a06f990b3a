//! The numeric factorisation of a split ordering: the two halves, each on a thread of its own, then
//! their overlap, and the Schur factor and compliance of the trace.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt;
use faer::{Mat, MatMut, MatRef};

use super::{Half, SplitOrdering, each};
use crate::fem::SymCsc;
use crate::fem::condense::compliance_of;
use crate::fem::error::FemError;
use crate::fem::partial::PartialFactor;

/// A numeric factorisation on a [`SplitOrdering`]: both halves' factors and S's.
pub struct SplitFactor {
    ordering: SplitOrdering,
    halves: Vec<PartialFactor<u32>>,
    /// The Cholesky factor of S (its lower triangle; Γ's order: J, then the trace).
    s: Mat<f64>,
}

/// The entries of K a [`SplitFactor`] reads: each half's K_h in its pattern's order, and K on
/// (Γ_L ∩ Γ_R)² (as the ordering's `overlap`). With them, K itself may be dropped before the
/// factorisation, which then holds only the halves' copies (one entry of K in each, but the
/// column's in both).
pub struct SplitValues {
    pub(super) halves: Vec<Vec<f64>>,
    pub(super) overlap: Vec<f64>,
    /// Memory the halves' factors may reuse (K's values and row indices, when K was given up):
    /// on a machine that is slow to hand out fresh pages this is time saved (BENCHMARKS.md,
    /// "Fresh memory").
    pub(super) storage: Vec<Vec<f64>>,
}

impl SplitFactor {
    /// Factorise `a`, whose pattern is the one `ordering` analysed: the halves on two threads
    /// when [`crate::fem::set_threads`] allows (each sequential), then S on the threads allowed.
    pub fn new(ordering: &SplitOrdering, a: &SymCsc) -> Result<Self, FemError> {
        Self::of_values(ordering, ordering.values(a))
    }

    /// Factorise the matrix whose entries `ordering` gathered into `values`
    /// ([`SplitOrdering::values`]). The arithmetic, and so the bits, are the same on one
    /// thread and on two.
    pub fn of_values(ordering: &SplitOrdering, values: SplitValues) -> Result<Self, FemError> {
        let split = &*ordering.0;
        let SplitValues {
            halves,
            overlap,
            storage,
        } = values;
        let storage = storage.into_iter().chain(std::iter::repeat_with(Vec::new));
        let work = split.halves.iter().zip(halves).zip(storage).collect();
        let halves = each(work, |((h, values), storage)| {
            PartialFactor::new(&h.ordering, h.pattern(), &values, storage)
        })
        .into_iter()
        .collect::<Result<Vec<_>, _>>()?;
        // S = S_L + S_R − K on (Γ_L ∩ Γ_R)², lower triangle (each half's Γ is ascending in Γ),
        // read from the trailing blocks of the halves' factors.
        let ng = split.gamma.len();
        let mut s = Mat::<f64>::zeros(ng, ng);
        for (h, f) in split.halves.iter().zip(&halves) {
            f.for_each_schur_entry(|i, j, v| s[(h.gamma[i], h.gamma[j])] += v);
        }
        for (&(gr, gc, _), k) in split.overlap.iter().zip(overlap) {
            s[(gr.max(gc), gr.min(gc))] -= k;
        }
        let par = crate::fem::dense_parallelism(ng);
        let mut mem = MemBuffer::try_new(llt::factor::cholesky_in_place_scratch::<f64>(
            ng,
            par,
            Default::default(),
        ))
        .map_err(|_| FemError::OutOfMemory("the factorisation's workspace"))?;
        llt::factor::cholesky_in_place(
            s.as_mut(),
            Default::default(),
            par,
            MemStack::new(&mut mem),
            Default::default(),
        )
        .map_err(FemError::from)?;
        Ok(SplitFactor {
            ordering: ordering.clone(),
            halves,
            s,
        })
    }

    /// Solve K X = B in place for the `ncols` columns of the column-major `b`: eliminate each
    /// half's interior, solve S u_Γ = f_Γ − Σ_h K_Γh K_hh⁻¹ f_h, back-substitute each half.
    pub fn solve_in_place(&self, b: &mut [f64], ncols: usize) {
        let split = &*self.ordering.0;
        let ng = split.gamma.len();
        let rhs = MatRef::from_column_major_slice(&*b, split.n, ncols);
        // Each half's [K_hh⁻¹-forward of f_h; −K_Γh K_hh⁻¹ f_h] in its elimination order.
        let eliminate = |h: &Half, f: &PartialFactor<u32>| {
            let mut x = Mat::<f64>::zeros(h.n, ncols);
            for j in 0..ncols {
                for (p, &d) in h.interior.iter().enumerate() {
                    x[(p, j)] = rhs[(d, j)];
                }
            }
            f.eliminate_interior(x.as_mut());
            x
        };
        let mut xs = each(split.halves.iter().zip(&self.halves).collect(), |(h, f)| {
            eliminate(h, f)
        });
        let mut u = Mat::<f64>::from_fn(ng, ncols, |g, j| rhs[(split.gamma[g], j)]);
        for (h, x) in split.halves.iter().zip(&xs) {
            let n0 = h.interior.len();
            for j in 0..ncols {
                for (t, &g) in h.gamma.iter().enumerate() {
                    u[(g, j)] += x[(n0 + t, j)];
                }
            }
        }
        llt::solve::solve_in_place(
            self.s.as_ref(),
            u.as_mut(),
            crate::fem::dense_parallelism(ng),
            MemStack::new(&mut []),
        );
        let back = |h: &Half, f: &PartialFactor<u32>, x: &mut Mat<f64>| {
            let n0 = h.interior.len();
            for j in 0..ncols {
                for (t, &g) in h.gamma.iter().enumerate() {
                    x[(n0 + t, j)] = u[(g, j)];
                }
            }
            f.back_substitute_interior(x.as_mut());
        };
        let work = split.halves.iter().zip(&self.halves).zip(&mut xs).collect();
        each(work, |((h, f), x)| back(h, f, x));
        let mut out = MatMut::from_column_major_slice_mut(b, split.n, ncols);
        for j in 0..ncols {
            for (h, x) in split.halves.iter().zip(&xs) {
                for (p, &d) in h.interior.iter().enumerate() {
                    out[(d, j)] = x[(p, j)];
                }
            }
            for (g, &d) in split.gamma.iter().enumerate() {
                out[(d, j)] = u[(g, j)];
            }
        }
    }

    /// The number of parts factorised: two halves, or the whole grid as one.
    pub fn parts(&self) -> usize {
        self.halves.len()
    }

    /// The Cholesky factor L_T of the Schur complement of K on the trace (in the trace's
    /// order): the trailing block of S's factor, L_T L_Tᵀ = S_TT − S_TJ S_JJ⁻¹ S_JT.
    pub fn schur_factor(&self) -> Mat<f64> {
        let nt = self.ordering.0.n_trace;
        let n0 = self.s.nrows() - nt;
        Mat::from_fn(nt, nt, |i, j| if i >= j { self.s[(n0 + i, n0 + j)] } else { 0.0 })
    }

    /// The trace compliance C = E K⁻¹ Eᵀ = (L_T L_Tᵀ)⁻¹.
    pub fn compliance(&self) -> Mat<f64> {
        let l = self.schur_factor();
        compliance_of(l.as_ref(), crate::fem::dense_parallelism(l.nrows()))
    }
}
