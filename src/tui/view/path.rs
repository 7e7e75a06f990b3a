//! Whether one series lies along another's polyline: how the chart's legend finds a line
//! drawn on an earlier one's path ([`super::plot`]: "(= p̄)").

/// Whether `a` and `b` span the same x range (within `tx`) and every point of `a` lies on the
/// polyline through `b` (within `tx` in x and `ty` in y of one of its segments; a vertical
/// segment holds the y between its ends).
pub(super) fn on_path(a: &[(f64, f64)], b: &[(f64, f64)], tx: f64, ty: f64) -> bool {
    let range = |d: &[(f64, f64)]| {
        d.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.0), hi.max(p.0))
        })
    };
    let ((alo, ahi), (blo, bhi)) = (range(a), range(b));
    let on_segment = |&(x, y): &(f64, f64), w: &[(f64, f64)]| {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        if x < x0.min(x1) - tx || x > x0.max(x1) + tx {
            return false;
        }
        if (x1 - x0).abs() <= tx {
            return y >= y0.min(y1) - ty && y <= y0.max(y1) + ty;
        }
        let at = y0 + (y1 - y0) * ((x - x0) / (x1 - x0)).clamp(0.0, 1.0);
        (y - at).abs() <= ty
    };
    // The segments that can hold x: all of them, or, along a path drawn left to right, those
    // from the last vertex left of x − tx on.
    let sorted = b.windows(2).all(|w| w[0].0 <= w[1].0);
    let holds = |p: &(f64, f64)| {
        let from = if sorted {
            b.partition_point(|q| q.0 < p.0 - tx).saturating_sub(1)
        } else {
            0
        };
        b[from..]
            .windows(2)
            .take_while(|w| !sorted || w[0].0 <= p.0 + tx)
            .any(|w| on_segment(p, w))
    };
    (alo - blo).abs() <= tx && (ahi - bhi).abs() <= tx && a.iter().all(holds)
}
