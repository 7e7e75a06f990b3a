//! The contact zone of a solution as the views zoom to it: where p̄ > 0 (the vertices in
//! contact, with the neighbouring vertices where p̄ falls to 0), mirrored for a half model,
//! widened by a margin. Computed here from the solution's p̄ (the library has no such call).

use super::super::protocol::Solved;

/// The x range to zoom to: the contact zone plus a quarter of its width on each side (at
/// least two of the mesh's cells at the zone's edges), within `[lo, hi]`; None without
/// contact.
pub fn zoom_range(solved: &Solved, half: bool, (lo, hi): (f64, f64)) -> Option<[f64; 2]> {
    let xs = &solved.solution.points.vertex_x;
    let pbar = &solved.solution.pbar;
    let inside: Vec<usize> = (0..pbar.len()).filter(|&i| pbar[i] > 0.0).collect();
    let (&first, &last) = (inside.first()?, inside.last()?);
    let (i, j) = (first.saturating_sub(1), (last + 1).min(xs.len() - 1));
    let (a, b) = (xs[i], xs[j]);
    // The local cell size at the zone's edges (graded meshes are finer there).
    let cell = (xs[i + 1] - xs[i]).max(xs[j] - xs[j - 1]);
    let (a, b) = if half { (-b, b) } else { (a, b) };
    let margin = (0.25 * (b - a)).max(2.0 * cell);
    Some([(a - margin).max(lo), (b + margin).min(hi)])
}
