//! The factorisation of a form on the grid with Γ_C's normal dofs last: one part, the whole
//! grid, below [`SPLIT_UNKNOWNS`] unknowns, two subdomains from there on ([`super::split`]),
//! factorised side by side on two threads or one after the other on one; both on the
//! supernodes the grid gives, with no symbolic analysis. faer's own analysis and
//! factorisation of the grid's order ([`super::condense`]) remain as [`Analysis::whole`], the
//! reference the tests compare with.
//! The choice depends on the mesh alone, never on the threads, so that every result has the
//! same bits whatever `--threads` says (tests/threads/main.rs). The two factorisations
//! agree to round-off (within 10⁻¹² relative, tests/numerics/fem.rs).

use faer::Mat;

use super::SymCsc;
use super::condense::{TraceFactor, TraceOrdering};
use super::dofs::DofMap;
use super::error::FemError;
use super::split::{SplitFactor, SplitOrdering};
use crate::mesh::Mesh;

/// The number of free dofs from which the grid is factorised as two subdomains
/// (BENCHMARKS.md, "Two subdomains on two cores": on two threads the split is as fast as the
/// single factor at level 4 Q1, 16,448 unknowns, and 1.5× faster at level 5, 65,664; on one
/// thread it costs 15–20% more at level 7, the price of the same bits on any thread count:
/// "Huge pages, and the same bits on any thread count"). Those comparisons were with faer's
/// single factor, which the whole grid as one part replaced below this size ("Supernodes from
/// the grid"; not measured again against two halves).
pub const SPLIT_UNKNOWNS: usize = 50_000;

/// The symbolic analysis of a form's pattern on the grid, Γ_C's normal dofs last (one per
/// mesh, shared by every form on it).
#[derive(Clone)]
pub enum Analysis {
    /// One factor of the whole grid.
    Whole(TraceOrdering),
    /// Two halves beside the middle column and S on the column and the trace, or the whole
    /// grid as one part and S on the trace.
    Split(SplitOrdering),
}

impl Analysis {
    /// The analysis of `a`, the form on `mesh` over `dofs`, with `trace` last: two subdomains
    /// when `a` has [`SPLIT_UNKNOWNS`] free dofs or more (and the grid a middle column), else
    /// the whole grid as one part ([`SplitOrdering::whole`]).
    pub fn grid(a: &SymCsc, mesh: &Mesh, dofs: &DofMap, trace: &[usize]) -> Result<Self, FemError> {
        if a.n >= SPLIT_UNKNOWNS {
            Self::split(a, mesh, dofs, trace)
        } else {
            SplitOrdering::whole(a, mesh, dofs, trace).map(Analysis::Split)
        }
    }

    /// One factor of the whole grid by faer ([`TraceOrdering::grid`]).
    pub fn whole(a: &SymCsc, mesh: &Mesh, dofs: &DofMap, trace: &[usize]) -> Result<Self, FemError> {
        TraceOrdering::grid(a, mesh, dofs, trace).map(Analysis::Whole)
    }

    /// Two subdomains ([`SplitOrdering::new`]), or the whole grid as one part when it has no
    /// middle column.
    pub fn split(a: &SymCsc, mesh: &Mesh, dofs: &DofMap, trace: &[usize]) -> Result<Self, FemError> {
        match SplitOrdering::new(a, mesh, dofs, trace)? {
            Some(split) => Ok(Analysis::Split(split)),
            None => SplitOrdering::whole(a, mesh, dofs, trace).map(Analysis::Split),
        }
    }

    /// The number of stored values of the factors: eight bytes each.
    pub fn factor_len(&self) -> usize {
        match self {
            Analysis::Whole(o) => o.factor_len(),
            Analysis::Split(o) => o.factor_len(),
        }
    }

    /// Floating point operations of one numeric factorisation
    /// ([`super::condense::factor_flops`]).
    pub fn factor_flops(&self) -> f64 {
        match self {
            Analysis::Whole(o) => o.factor_flops(),
            Analysis::Split(o) => o.factor_flops(),
        }
    }
}

/// A numeric factorisation on an [`Analysis`].
pub enum Factor {
    /// One factor of the whole grid.
    Whole(TraceFactor),
    /// Both halves' factors (or the one part's) and S's.
    Split(SplitFactor),
}

impl Factor {
    /// Factorise `a`, whose pattern is the one `analysis` analysed, on the threads of
    /// [`super::set_threads`]. `a` is consumed: the split copies the entries it reads and
    /// gives K's memory to the factors (0.6 GB at level 8: BENCHMARKS.md, "Huge pages" and
    /// "Fresh memory").
    pub fn new(analysis: &Analysis, a: SymCsc) -> Result<Self, FemError> {
        Ok(match analysis {
            Analysis::Whole(o) => Factor::Whole(TraceFactor::new(o, &a)?),
            Analysis::Split(o) => Factor::Split(SplitFactor::of_values(o, o.values_of(a))?),
        })
    }

    /// Solve A X = B in place for the `ncols` columns of the column-major `b`.
    pub fn solve_in_place(&self, b: &mut [f64], ncols: usize) {
        match self {
            Factor::Whole(f) => f.solve_in_place(b, ncols),
            Factor::Split(f) => f.solve_in_place(b, ncols),
        }
    }

    /// The Cholesky factor of the Schur complement of A on the trace (in the trace's order).
    pub fn schur_factor(&self) -> Mat<f64> {
        match self {
            Factor::Whole(f) => f.schur_factor(),
            Factor::Split(f) => f.schur_factor(),
        }
    }

    /// The trace compliance C = E A⁻¹ Eᵀ.
    pub fn compliance(&self) -> Mat<f64> {
        match self {
            Factor::Whole(f) => f.compliance(),
            Factor::Split(f) => f.compliance(),
        }
    }
}
