//! Number formatting and axis labels (ratatui spaces labels evenly between the bounds, so
//! they are generated from the bounds).

/// `x` to `digits` significant digits, trailing zeros trimmed; scientific outside [1e-3, 1e5).
pub fn sig(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x == 0.0 { "0".into() } else { format!("{x}") };
    }
    let e = x.abs().log10().floor() as i32;
    if !(-3..5).contains(&e) {
        let s = format!("{:.*e}", digits.saturating_sub(1), x);
        // 1.50e-5 → 1.5e-5
        return match s.split_once('e') {
            Some((m, exp)) => format!("{}e{exp}", trim(m)),
            None => s,
        };
    }
    let decimals = (digits as i32 - 1 - e).max(0) as usize;
    trim(&format!("{x:.decimals$}")).to_string()
}

/// Trailing zeros (and a trailing dot) of a decimal number removed.
fn trim(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// `n` labels evenly spaced over `[lo, hi]`.
pub fn linear_labels(lo: f64, hi: f64, n: usize) -> Vec<String> {
    evenly(lo, hi, n).map(|v| sig(v, 3)).collect()
}

/// `n` labels evenly spaced over `[lo, hi]` in log10, showing 10^v.
pub fn log_labels(lo: f64, hi: f64, n: usize) -> Vec<String> {
    evenly(lo, hi, n).map(|v| sig(10f64.powf(v), 2)).collect()
}

fn evenly(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
    let n = n.max(2);
    (0..n).map(move |i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
}

pub use crate::plot::nice_ceil;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn significant_digits() {
        assert_eq!(sig(0.0, 3), "0");
        assert_eq!(sig(12.3456, 3), "12.3");
        assert_eq!(sig(1.5e-5, 3), "1.5e-5");
        assert_eq!(sig(0.5, 3), "0.5");
        assert_eq!(sig(-8.0, 3), "-8");
        assert_eq!(nice_ceil(11.0), 12.0);
        assert_eq!(linear_labels(-8.0, 8.0, 5), ["-8", "-4", "0", "4", "8"]);
    }
}
