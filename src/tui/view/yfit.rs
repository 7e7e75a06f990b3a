//! The vertical axis fitted to its data and to the rows it has, every row read at its value.
//!
//! A reader reads a glyph's value off the tick labels: the row of a tick means the tick's
//! value, the rows between mean the values between, evenly. A canvas row holds `per` dots and
//! ratatui draws a value at the dot round((v − lo)/(hi − lo)·(dots − 1))
//! ([`super::plot::cell_of`]). So the rows are given an even step r (value per row) and the
//! bounds are set so that a row's middle, dot (per − 1)/2 of it, is a multiple of r: every
//! value then lands in the row whose middle is within r/2 of it (half a row), and the ticks,
//! multiples of a 1-2-5 step s = m·r (decades 1, 2, 3, 5 on a log10 axis), sit on every m-th
//! row at their values. Of the steps and spacings that hold the data on the rows there are,
//! the finest r is taken (two values more than a row apart never share a row), then the most
//! ticks; rows left over go above the data (an axis from 0 keeps 0 on its bottom row) or half
//! above, half below.

/// The steps tried, in data units: 1, 2, 2.5 and 5 times the powers of ten (a linear axis);
/// 1, 2, 3 and 5 decades (a log10 axis, `log`, whose data are log10 values).
fn steps(log: bool, span: f64) -> Vec<f64> {
    match log {
        true => vec![1.0, 2.0, 3.0, 5.0],
        false => {
            let p = 10f64.powf(span.log10().floor());
            [0.01, 0.1, 1.0, 10.0]
                .into_iter()
                .flat_map(|k| [1.0, 2.0, 2.5, 5.0].map(|m| m * k * p))
                .collect()
        }
    }
}

/// One way to lay the axis out: value per row, the bottom row's middle (in rows of r), the
/// ticks.
struct Layout {
    r: f64,
    bottom: i64,
    ticks: Vec<f64>,
}

/// The axis over the data's range `bounds` drawn on `rows` rows of `per` dots, at most `max`
/// ticks (module doc): its bounds and ticks. None when no step gives two ticks (the caller
/// keeps its bounds).
pub fn fit(bounds: [f64; 2], log: bool, rows: u16, per: u16, max: usize) -> Option<([f64; 2], Vec<f64>)> {
    let (lo, hi) = (bounds[0], bounds[1]);
    let span = hi - lo;
    if !(span >= 0.0 && span.is_finite() && lo.is_finite()) || rows < 2 || per == 0 {
        return None;
    }
    let half = f64::from(per - 1) / 2.0 / f64::from(per);
    // Ticks at least two rows apart where there are rows for it.
    let least = if rows >= 4 { 2 } else { 1 };
    let n = i64::from(rows);
    let mut best: Option<Layout> = None;
    let basis = if span > 0.0 { span } else { lo.abs().max(1.0) };
    for s in steps(log, basis) {
        for m in least..=i64::from(rows) {
            let r = s / m as f64;
            // The rows of the lowest and highest value: a row holds the values from
            // `half` of a row below its middle's first dot to as far above its last.
            let (mut k_lo, mut k_hi) = ((lo / r).round() as i64, (hi / r).round() as i64);
            if lo < (k_lo as f64 - half) * r {
                k_lo -= 1;
            }
            if hi > (k_hi as f64 + half) * r {
                k_hi += 1;
            }
            let used = k_hi - k_lo + 1;
            if used > n {
                continue;
            }
            let spare = n - used;
            let bottom = if lo == 0.0 { k_lo } else { k_lo - spare / 2 };
            let ticks: Vec<f64> = (bottom..bottom + n)
                .filter(|k| k.rem_euclid(m) == 0)
                .map(|k| k as f64 * r)
                .collect();
            if !(2..=max.max(2)).contains(&ticks.len()) {
                continue;
            }
            let better = best.as_ref().is_none_or(|b| {
                r < b.r * (1.0 - 1e-9) || (r <= b.r * (1.0 + 1e-9) && ticks.len() > b.ticks.len())
            });
            if better {
                best = Some(Layout { r, bottom, ticks });
            }
        }
    }
    let Layout { r, bottom, ticks } = best?;
    // The bottom row's middle at `bottom`·r: dot (per − 1)/2 of the dots·per − 1 steps.
    let d = r / f64::from(per);
    let low = bottom as f64 * r - f64::from(per - 1) / 2.0 * d;
    let high = low + (f64::from(rows) * f64::from(per) - 1.0) * d;
    Some(([low, high], ticks))
}

/// The range of the y values of every series of `data` ((x, y) points), [−1, 1] when there
/// are none: the bounds a chart's y axis is fitted to.
pub fn span(data: &[Vec<(f64, f64)>]) -> [f64; 2] {
    let (lo, hi) = data
        .iter()
        .flatten()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &(_, y)| {
            (lo.min(y), hi.max(y))
        });
    if lo.is_finite() { [lo, hi] } else { [-1.0, 1.0] }
}

/// The axis of [`fit`], or `bounds` and `ticks` as they are when it finds none.
pub fn fit_or(
    bounds: [f64; 2],
    ticks: Vec<f64>,
    log: bool,
    rows: u16,
    per: u16,
    max: usize,
) -> ([f64; 2], Vec<f64>) {
    fit(bounds, log, rows, per, max).unwrap_or((bounds, ticks))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tui::view::cells::cell_of;

    /// The value a reader reads at the middle of `row`, from the first two ticks.
    fn read(b: [f64; 2], ticks: &[f64], rows: u16, per: u16, row: u16) -> f64 {
        let r0 = cell_of(ticks[0], b, rows, per).unwrap();
        let r1 = cell_of(ticks[1], b, rows, per).unwrap();
        let per_row = (ticks[1] - ticks[0]) / f64::from(r1 - r0);
        ticks[0] + (f64::from(row) - f64::from(r0)) * per_row
    }

    #[test]
    fn every_value_reads_within_half_a_row_and_the_ticks_are_even() {
        for (lo, hi) in [
            (0.0, 283.0),
            (0.0, 230.0),
            (-12.0, 410.0),
            (0.0, 0.7),
            (-2.05, 0.03),
            (-2.018, 0.0294),
        ] {
            for rows in [3u16, 5, 6, 11, 17, 20] {
                for per in [1u16, 2, 4] {
                    for log in [false, true] {
                        let Some((b, ticks)) = fit([lo, hi], log, rows, per, 6) else {
                            continue;
                        };
                        assert!(b[0] <= lo && b[1] >= hi, "{b:?} holds {lo} {hi}");
                        let r: Vec<u16> = ticks.iter().map(|&v| cell_of(v, b, rows, per).unwrap()).collect();
                        let gaps: Vec<i32> =
                            r.windows(2).map(|w| i32::from(w[1]) - i32::from(w[0])).collect();
                        assert!(
                            gaps.iter().all(|&g| g == gaps[0] && g > 0),
                            "{lo} {hi} {rows} {per}: {r:?}"
                        );
                        let per_row = (ticks[1] - ticks[0]) / f64::from(gaps[0]);
                        for i in 0..=100 {
                            let v = lo + (hi - lo) * f64::from(i) / 100.0;
                            let row = cell_of(v, b, rows, per).unwrap();
                            let off = (read(b, &ticks, rows, per, row) - v).abs();
                            assert!(
                                off <= per_row * (0.5 + 1e-9),
                                "{v} on row {row}, reads {off} off, {lo} {hi} {rows} {per} {log}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn the_paper_pressure_at_80x24_has_two_ticks_and_little_waste() {
        // Five rows of braille (the explore scene at 80×24), p from 0 to 283.
        let (b, ticks) = fit([0.0, 283.0], false, 5, 4, 3).unwrap();
        assert_eq!(ticks, [0.0, 200.0]);
        assert!(b[1] < 300.0, "{b:?}");
    }

    /// The inf-sup chart's data (M1 at level 4 to M3) on 19 rows: a ninth of a decade a row,
    /// M4's 0.526 three rows under M3's 1.07.
    #[test]
    fn infsup_values_on_19_rows_keep_m3_and_m4_three_rows_apart() {
        let (b, ticks) = fit([0.0096f64.log10(), 1.07f64.log10()], true, 19, 4, 6).unwrap();
        let row = |v: f64| cell_of(v.log10(), b, 19, 4).unwrap();
        assert!(row(1.07) - row(0.526) >= 3, "{b:?} {ticks:?}");
    }
}
