//! The vertical axis fitted to the rows it has: ticks on evenly spaced rows, each at its value.
//! An axis whose ticks already sit so is left as it is.
//!
//! A canvas row holds `per` dots and ratatui draws a value at the dot
//! round((v − lo)/(hi − lo)·(dots − 1)) ([`super::plot::cell_of`]). Ticks a step `s` apart land
//! on rows a fixed `m` apart exactly when `s` spans `m·per` dots, so the upper bound is raised
//! to lo + (dots − 1)·s/(m·per): the data keep their lower bound and scale, the ticks sit on
//! rows 0, m, 2m, … from the first, each in the row of its value. Of the steps and spacings
//! that hold the data, the one with the most ticks among those within a quarter of the least
//! height is taken (a small chart keeps its rows for the data, a big one gets its ticks).

use super::cells::cell_of;

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

/// The axis over `bounds` with `ticks` as they are when those ticks sit on evenly spaced rows
/// of the `rows` rows of `per` dots; else [`fit`]'s (when it finds one; `log`: a log10 axis).
pub fn even_or_fit(
    bounds: [f64; 2],
    ticks: Vec<f64>,
    log: bool,
    rows: u16,
    per: u16,
    max: usize,
) -> ([f64; 2], Vec<f64>) {
    // The rows of the ticks drawn (a tick outside the bounds is not).
    let cells: Vec<i32> = ticks
        .iter()
        .filter_map(|&v| cell_of(v, bounds, rows, per))
        .map(i32::from)
        .collect();
    let gaps: Vec<i32> = cells.windows(2).map(|w| w[1] - w[0]).collect();
    if cells.len() >= 2 && gaps.iter().all(|&d| d > 0 && d == gaps[0]) {
        return (bounds, ticks);
    }
    fit(bounds, log, rows, per, max).unwrap_or((bounds, ticks))
}

/// The bounds and ticks of an axis over `bounds` drawn on `rows` rows of `per` dots, at most
/// `max` ticks: the upper bound raised so that the ticks sit on evenly spaced rows (module
/// doc). None when no step gives two ticks (the caller keeps its bounds).
pub fn fit(bounds: [f64; 2], log: bool, rows: u16, per: u16, max: usize) -> Option<([f64; 2], Vec<f64>)> {
    let (lo, hi) = (bounds[0], bounds[1]);
    let span = hi - lo;
    if !(span > 0.0 && span.is_finite()) || rows < 2 || per == 0 {
        return None;
    }
    let dots = f64::from(rows) * f64::from(per);
    // Ticks at least two rows apart where there are rows for it.
    let least = if rows >= 4 { 2 } else { 1 };
    let mut fits: Vec<(f64, Vec<f64>)> = Vec::new();
    for s in steps(log, span) {
        for m in least..=rows {
            let per_dot = s / (f64::from(m) * f64::from(per));
            let top = lo + (dots - 1.0) * per_dot;
            if top < hi - 1e-12 * span.abs() {
                continue;
            }
            let first = (lo / s - 1e-9).ceil() as i64;
            let last = (top / s + 1e-9).floor() as i64;
            let ticks: Vec<f64> = (first..=last).map(|k| k as f64 * s).collect();
            if (2..=max.max(2)).contains(&ticks.len()) {
                fits.push((top, ticks));
            }
        }
    }
    // The least waste; then, of the fits within a quarter more height, the most ticks.
    let least_top = fits.iter().map(|f| f.0).fold(f64::INFINITY, f64::min);
    let room = lo + 1.25 * (least_top - lo) * (1.0 + 1e-9);
    fits.into_iter()
        .filter(|f| f.0 <= room)
        .min_by(|a, b| b.1.len().cmp(&a.1.len()).then(a.0.total_cmp(&b.0)))
        .map(|(top, ticks)| ([lo, top], ticks))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tui::view::cells::cell_of;

    /// The rows of `ticks` as the canvas draws them (from the bottom).
    fn rows_of(bounds: [f64; 2], ticks: &[f64], rows: u16, per: u16) -> Vec<u16> {
        ticks
            .iter()
            .map(|&v| cell_of(v, bounds, rows, per).unwrap())
            .collect()
    }

    #[test]
    fn ticks_sit_on_evenly_spaced_rows_and_the_data_fit() {
        for (lo, hi) in [
            (0.0, 283.0),
            (0.0, 230.0),
            (-12.0, 410.0),
            (0.0, 0.7),
            (-2.05, 0.03),
        ] {
            for rows in [3u16, 5, 6, 11, 20] {
                for per in [1u16, 2, 4] {
                    for log in [false, true] {
                        let Some((b, ticks)) = fit([lo, hi], log, rows, per, 6) else {
                            continue;
                        };
                        assert_eq!(b[0], lo);
                        assert!(b[1] >= hi, "{b:?} holds {hi}");
                        let r = rows_of(b, &ticks, rows, per);
                        let gaps: Vec<i32> =
                            r.windows(2).map(|w| i32::from(w[1]) - i32::from(w[0])).collect();
                        assert!(
                            gaps.iter().all(|&g| g == gaps[0] && g > 0),
                            "{lo} {hi} {rows} {per}: {r:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn the_paper_pressure_at_80x24_has_two_ticks_and_little_waste() {
        // Five rows of braille (the explore scene at 80×24), p from 0 to 283.
        let (b, ticks) = fit([0.0, 283.0], false, 5, 4, 3).unwrap();
        assert_eq!(ticks, [0.0, 250.0]);
        assert!(b[1] < 300.0, "{b:?}");
    }
}
