//! The two traces' share of the interface's condensed solve (docs/design.md §12): the
//! Delassus matrix G C Gᵀ of a coupling's rows on a body's trace compliance, and the rows' own
//! smoothing of the pressure to the slave's vertices (17).

use faer::Mat;

/// G C Gᵀ for the rows G (constraint k: (trace node, coefficient)) and the trace compliance C.
pub fn delassus(rows: &[Vec<(usize, f64)>], c: &Mat<f64>) -> Mat<f64> {
    let n = rows.len();
    // C Gᵀ, a column per constraint.
    let mut cg = Mat::<f64>::zeros(c.nrows(), n);
    for (k, row) in rows.iter().enumerate() {
        for &(i, g) in row {
            for r in 0..c.nrows() {
                cg[(r, k)] += g * c[(r, i)];
            }
        }
    }
    Mat::from_fn(n, n, |j, k| rows[j].iter().map(|&(i, g)| g * cg[(i, k)]).sum())
}

/// p̄_i = Σ_k w_k p_k φ_i(x_k) / Σ_k w_k φ_i(x_k) at the vertices `vertex_x`, φ_i the
/// vertex's hat function: the contact force on the vertex over its tributary length (17);
/// 0 where no constraint sees the vertex.
pub(crate) fn smoothed(vertex_x: &[f64], x: &[f64], w: &[f64], p: &[f64]) -> Vec<f64> {
    let nv = vertex_x.len();
    let (mut force, mut length) = (vec![0.0; nv], vec![0.0; nv]);
    for k in (0..x.len()).filter(|_| nv >= 2) {
        let e = vertex_x.partition_point(|&v| v <= x[k]).clamp(1, nv - 1) - 1;
        let t = ((x[k] - vertex_x[e]) / (vertex_x[e + 1] - vertex_x[e])).clamp(0.0, 1.0);
        for (i, phi) in [(e, 1.0 - t), (e + 1, t)] {
            force[i] += w[k] * p[k] * phi;
            length[i] += w[k] * phi;
        }
    }
    force
        .iter()
        .zip(&length)
        .map(|(f, l)| if *l > 0.0 { f / l } else { 0.0 })
        .collect()
}
