//! The ticks of a chart's axes: a 1-2-5 grid on a linear axis, decades (and their 2 and 5)
//! on a log10 axis, and their labels.

use super::fmt::sig;

/// How an axis maps values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// The data are the values.
    Linear,
    /// The data are log10 of the values; labels show the values.
    Log10,
}

/// Ticks on a linear axis: multiples of a 1-2-5 step, at most `max` of them.
pub fn linear_ticks(bounds: [f64; 2], max: usize) -> Vec<f64> {
    let (lo, hi) = (bounds[0], bounds[1]);
    let ordered = hi > lo;
    if !ordered {
        return vec![lo];
    }
    let max = max.max(2);
    let raw = (hi - lo) / (max - 1) as f64;
    let p = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&s| (((hi - lo) / s).floor() as usize) < max)
        .unwrap_or(10.0 * p);
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// Ticks on a log10 axis (data in log10): the decades inside, with 2× and 5× when fewer than
/// three decades fit and there is room; at most `max`.
pub fn log_ticks(bounds: [f64; 2], max: usize) -> Vec<f64> {
    let (lo, hi) = (bounds[0], bounds[1]);
    let decades: Vec<f64> = ((lo - 1e-9).ceil() as i64..=(hi + 1e-9).floor() as i64)
        .map(|k| k as f64)
        .collect();
    if decades.len() >= 3 || max < 3 {
        // Every decade, thinned to fit.
        let every = decades.len().div_ceil(max.max(1)).max(1);
        return decades.into_iter().step_by(every).collect();
    }
    let fine: Vec<f64> = ((lo - 1e-9).floor() as i64..=(hi + 1e-9).ceil() as i64)
        .flat_map(|k| [1.0f64, 2.0, 5.0].map(|m| k as f64 + m.log10()))
        .filter(|&v| v >= lo - 1e-9 && v <= hi + 1e-9)
        .collect();
    if fine.len() <= max && fine.len() >= 2 {
        fine
    } else {
        decades
    }
}

/// The text of a tick at `value` (data units).
pub fn tick_label(value: f64, scale: Scale) -> String {
    match scale {
        Scale::Linear => sig(value, 3),
        Scale::Log10 => sig(10f64.powf(value), 2),
    }
}
