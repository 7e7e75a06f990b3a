//! The finite element layer: quadrature, cell bases, dofs and assembly (DESIGN §2).

pub mod assembly;
pub mod basis;
pub mod condense;
pub mod dofs;
pub mod quadrature;

pub use assembly::{Form, Integration, SymCsc, apply, assemble, body_load, h1_error};
pub use dofs::DofMap;

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::Llt;
use faer::{MatMut, Side};

/// Factorise the symmetric positive definite `a` (sparse Cholesky, fill-reducing ordering).
pub fn cholesky(a: &SymCsc) -> Result<Llt<usize, f64>, String> {
    let view = a.view(&a.values);
    Llt::try_new_with_symbolic(
        faer::sparse::linalg::solvers::SymbolicLlt::try_new(view.symbolic(), Side::Lower)
            .map_err(|e| format!("{e:?}"))?,
        view,
        Side::Lower,
    )
    .map_err(|e| format!("{e:?}"))
}

/// Solve A x = b in place for the columns of the column-major `b` (`a.n` rows each).
pub fn solve_in_place(llt: &Llt<usize, f64>, b: &mut [f64], n: usize) {
    let cols = b.len() / n;
    llt.solve_in_place(MatMut::from_column_major_slice_mut(b, n, cols));
}
