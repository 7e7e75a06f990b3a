//! The gather-scatter product of a supernodal factorisation's update: dst[rows, cols] −=
//! lhs rhsᵀ on the product's lower triangle, through faer's own kernel (private-gemm-x86)
//! where the processor runs it, else a dense product scattered afterwards. Its first call on
//! a thread maps the kernel's packing buffers, which the memory guard counts
//! (src/fem/memory/kernel.rs).

use faer::linalg::matmul::matmul;
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::reborrow::ReborrowMut;
use faer::traits::Index;
use faer::{Accum, MatMut, MatRef, Par};

/// How [`subtract_lower_product`] multiplies: faer's own gather-scatter kernel (the one its
/// supernodal factorisation calls, from `private-gemm-x86`), or a dense product scattered
/// afterwards where that kernel does not run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Kernel {
    #[cfg(target_arch = "x86_64")]
    Gather(private_gemm_x86::InstrSet),
    Dense,
}

impl Kernel {
    /// The gather-scatter kernel where the processor runs it (AVX-512, or AVX2 with FMA, as
    /// faer decides), else the dense product.
    pub(super) fn detect() -> Self {
        #[cfg(target_arch = "x86_64")]
        {
            use private_gemm_x86::InstrSet;
            if std::arch::is_x86_feature_detected!("avx512f") {
                return Kernel::Gather(InstrSet::Avx512);
            }
            if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
                return Kernel::Gather(InstrSet::Avx256);
            }
        }
        Kernel::Dense
    }
}

/// One 1×1 product through the gather kernel on the calling thread: the kernel maps its
/// per-thread packing buffers on a thread's first product (src/fem/memory/kernel.rs). Nothing
/// where the processor does not run it.
pub(super) fn map_buffers() {
    let kernel = Kernel::detect();
    if kernel == Kernel::Dense {
        return;
    }
    let one = [1.0f64];
    let mut dst = [0.0f64];
    let factor = MatRef::from_column_major_slice(&one, 1, 1);
    let dst_mat = MatMut::from_column_major_slice_mut(&mut dst, 1, 1);
    subtract_lower_product(dst_mat, &[0u32], &[0u32], factor, factor, kernel, &mut Vec::new());
    debug_assert_eq!(dst, [-1.0]);
}

/// dst[rows[i], cols[j]] −= (lhs rhsᵀ)[i, j] for i ≥ j (the product's lower triangle, rhs
/// being lhs's first rows), with `buffer` as the dense path's scratch.
pub(super) fn subtract_lower_product<I: Index>(
    mut dst: MatMut<'_, f64>,
    rows: &[I],
    cols: &[I],
    lhs: MatRef<'_, f64>,
    rhs: MatRef<'_, f64>,
    kernel: Kernel,
    buffer: &mut Vec<f64>,
) {
    let (nrows, ncols) = (lhs.nrows(), rhs.nrows());
    // The kernel below reads `lhs` and `rhs` through raw pointers with one depth for both:
    // a mismatch would read past one of them.
    assert_eq!(lhs.ncols(), rhs.ncols(), "the product's inner dimensions differ");
    assert!(ncols <= nrows, "rhs is lhs's first rows");
    #[cfg(target_arch = "x86_64")]
    if let Kernel::Gather(instr) = kernel
        && rows.len() == nrows
        && cols.len() == ncols
        && rows.iter().all(|r| r.zx() < dst.nrows())
        && cols.iter().all(|c| c.zx() < dst.ncols())
    {
        use private_gemm_x86::{Accum, DType, DstKind, IType};
        let alpha = -1.0f64;
        let itype = if size_of::<I>() == 4 {
            IType::U32
        } else {
            IType::U64
        };
        // SAFETY: the arguments are those of faer's `spicy_matmul` for the same update in
        // `factorize_supernodal_numeric_llt`: `lhs` (nrows × depth) and `rhs`ᵀ (depth × ncols)
        // are read through their own pointers and strides; every index in `rows` and `cols`
        // (checked just above, one per row of lhs and per column of rhsᵀ) addresses an entry
        // of `dst`, which is written through its pointer and strides alone; the index type
        // matches I's width (u32 or u64); one thread.
        unsafe {
            private_gemm_x86::gemm(
                DType::F64,
                itype,
                instr,
                nrows,
                ncols,
                lhs.ncols(),
                dst.as_ptr_mut() as *mut (),
                dst.row_stride(),
                dst.col_stride(),
                rows.as_ptr() as *const (),
                cols.as_ptr() as *const (),
                DstKind::Lower,
                Accum::Add,
                lhs.as_ptr() as *const (),
                lhs.row_stride(),
                lhs.col_stride(),
                false,
                std::ptr::null(),
                0,
                rhs.as_ptr() as *const (),
                rhs.col_stride(),
                rhs.row_stride(),
                false,
                (&raw const alpha) as *const (),
                1,
            );
        }
        return;
    }
    let _ = kernel;
    buffer.clear();
    buffer.resize(nrows * ncols, 0.0);
    let mut w = MatMut::from_column_major_slice_mut(buffer, nrows, ncols);
    let (w_mid, w_bot) = w.rb_mut().split_at_row_mut(ncols);
    triangular::matmul(
        w_mid,
        BlockStructure::TriangularLower,
        Accum::Replace,
        rhs,
        BlockStructure::Rectangular,
        rhs.transpose(),
        BlockStructure::Rectangular,
        1.0,
        Par::Seq,
    );
    matmul(
        w_bot,
        Accum::Replace,
        lhs.subrows(ncols, nrows - ncols),
        rhs.transpose(),
        1.0,
        Par::Seq,
    );
    for (j, c) in cols.iter().enumerate() {
        for (i, r) in rows.iter().enumerate().skip(j) {
            dst[(r.zx(), c.zx())] -= w[(i, j)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    /// The pinned `private-gemm-x86` (Cargo.toml: `=`) computes what the dense path computes:
    /// dst[rows[i], rows[j]] −= (lhs lhs[..ncols]ᵀ)[i, j] for i ≥ j, with scattered rows, both
    /// index widths, every other entry of dst untouched. A new version that changed the
    /// kernel's meaning or argument order fails here before it reaches a factor.
    #[test]
    fn the_gather_kernel_equals_the_dense_product() {
        fn run<I: Index>(kernel: Kernel) -> Vec<f64> {
            let (n, depth) = (11, 4);
            let rows: Vec<I> = [0usize, 2, 3, 6, 7, 10].iter().map(|&r| I::truncate(r)).collect();
            let ncols = 3;
            let lhs = Mat::<f64>::from_fn(rows.len(), depth, |i, k| ((i * 5 + k * 3) % 7) as f64 - 2.5);
            let mut dst = Mat::<f64>::from_fn(n, n, |i, j| (i * n + j) as f64);
            let mut buffer = Vec::new();
            subtract_lower_product(
                dst.as_mut(),
                &rows,
                &rows[..ncols],
                lhs.as_ref(),
                lhs.as_ref().subrows(0, ncols),
                kernel,
                &mut buffer,
            );
            (0..n)
                .flat_map(|j| (0..n).map(move |i| (i, j)))
                .map(|(i, j)| dst[(i, j)])
                .collect()
        }
        let dense = run::<u32>(Kernel::Dense);
        // The dense path against the definition, entry by entry.
        let rows = [0usize, 2, 3, 6, 7, 10];
        let lhs = |i: usize, k: usize| ((i * 5 + k * 3) % 7) as f64 - 2.5;
        for j in 0..11 {
            for i in 0..11 {
                let mut expect = (i * 11 + j) as f64;
                if let (Some(a), Some(b)) = (
                    rows.iter().position(|&r| r == i),
                    rows[..3].iter().position(|&r| r == j),
                ) && a >= b
                {
                    expect -= (0..4).map(|k| lhs(a, k) * lhs(b, k)).sum::<f64>();
                }
                assert_eq!(dense[j * 11 + i], expect, "dense path, dst[{i}, {j}]");
            }
        }
        let kernel = Kernel::detect();
        assert_eq!(run::<u32>(kernel), dense, "{kernel:?} with u32 indices");
        assert_eq!(run::<u64>(kernel), dense, "{kernel:?} with u64 indices");
    }
}
