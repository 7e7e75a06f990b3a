//! Observed rates (docs/design.md §6): from one row to the next, and the least-squares slope
//! over a scheme's rows (its fit).

use serde::Serialize;

use super::errors::Errors;
use super::row::{Status, StudyRow};
use crate::contact::method::MethodFields;
use crate::mesh::Element;

/// Observed rates between two rows with results (None unless both are [`Status::Ok`]).
fn rates(prev: &StudyRow, row: &StudyRow, by_epsilon: bool) -> Option<Errors> {
    if prev.status != Status::Ok || row.status != Status::Ok {
        return None;
    }
    let (a, b) = (prev.errors?, row.errors?);
    let scale = if by_epsilon {
        (row.epsilon / prev.epsilon).ln()
    } else {
        (row.abscissa() / prev.abscissa()).ln()
    };
    let r = |a: f64, b: f64| (b / a).ln() / scale;
    // t̄'s and Q's rates only where both rows have a nonzero error (μ = 0: none).
    let both = |a: Option<f64>, b: Option<f64>| Some(r(a?, b?)).filter(|v| v.is_finite());
    let rates = Errors {
        p: r(a.p, b.p),
        pbar: r(a.pbar, b.pbar),
        u: r(a.u, b.u),
        load: r(a.load, b.load),
        tbar: both(a.tbar, b.tbar),
        tangential_load: both(a.tangential_load, b.tangential_load),
    };
    // An error of 0 (or a scale of 0) has no rate: never a non-finite one.
    rates.values().all(f64::is_finite).then_some(rates)
}

/// Rows grouped per scheme, in `schemes`' order, each group with its rates from the row
/// before it (`by_epsilon`: rates against ε; rows with ε = 0 get none).
pub(super) fn with_rates(groups: Vec<Vec<StudyRow>>, by_epsilon: bool) -> Vec<StudyRow> {
    let mut rows = Vec::new();
    for group in groups {
        for (i, mut row) in group.iter().cloned().enumerate() {
            let prev = i.checked_sub(1).map(|j| &group[j]);
            if let Some(prev) = prev.filter(|p| !by_epsilon || (p.epsilon > 0.0 && row.epsilon > 0.0)) {
                row.rates = rates(prev, &row, by_epsilon);
            }
            rows.push(row);
        }
    }
    rows
}

/// The least-squares slope of y against x over `points` (None with fewer than two distinct x).
pub fn least_squares_slope(points: &[(f64, f64)]) -> Option<f64> {
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let sxx: f64 = points.iter().map(|(x, _)| (x - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    (points.len() >= 2 && sxx > 0.0).then(|| sxy / sxx)
}

/// The least-squares rates of one scheme (and method) over its rows: the slopes of log error
/// against log h (an ε sweep: log ε), beside the row-to-row [`StudyRow::rates`].
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Fit {
    /// The scheme's label: M1–M4 or `element+rule`.
    pub scheme: String,
    /// The element: `q1`, `q2` or `p1`.
    pub element: Element,
    /// The contact rule.
    pub rule: &'static str,
    /// The contact method and its parameters (`method`, `theta`, `gamma0`, `alm_tol`).
    #[serde(flatten)]
    /// The method as asked ([`MethodFields::setting`]: `auto`'s γ₀ varies by level).
    pub method: MethodFields,
    /// The grading asked of its rows (`0`, `3`, `auto` or `3z`; [`crate::grading`]).
    pub refine_edges: String,
    /// Its abscissa: `h`, `epsilon`, or for graded rows `n^-1/2` (the unknowns n).
    pub abscissa: &'static str,
    /// The rows fitted: those with a result ([`Status::Ok`]), every error > 0, and h (ε) > 0.
    pub rows: usize,
    /// The slopes (None with fewer than two such rows).
    pub rates: Option<Errors>,
}

/// One [`Fit`] per run of rows with the same scheme and method, in the rows' order.
pub fn fits(rows: &[StudyRow], by_epsilon: bool) -> Vec<Fit> {
    let mut out: Vec<Fit> = Vec::new();
    let mut start = 0;
    while start < rows.len() {
        let first = &rows[start];
        let len = rows[start..].iter().take_while(|r| r.same_series(first)).count();
        let usable: Vec<(f64, Errors)> = rows[start..start + len]
            .iter()
            .filter(|r| r.status == Status::Ok)
            .filter_map(|r| Some((if by_epsilon { r.epsilon } else { r.abscissa() }, r.errors?)))
            .filter(|(x, e)| {
                *x > 0.0
                    && [e.p, e.pbar, e.u, e.load]
                        .iter()
                        .all(|v| *v > 0.0 && v.is_finite())
            })
            .collect();
        let slope = |f: fn(&Errors) -> f64| {
            let points: Vec<(f64, f64)> = usable.iter().map(|(x, e)| (x.ln(), f(e).ln())).collect();
            least_squares_slope(&points)
        };
        // t̄'s and Q's slopes only when every fitted row has a nonzero error of them.
        let optional = |f: fn(&Errors) -> Option<f64>| {
            let points: Option<Vec<(f64, f64)>> = usable
                .iter()
                .map(|(x, e)| f(e).filter(|v| *v > 0.0).map(|v| (x.ln(), v.ln())))
                .collect();
            least_squares_slope(&points?)
        };
        let rates = (|| {
            Some(Errors {
                p: slope(|e| e.p)?,
                pbar: slope(|e| e.pbar)?,
                u: slope(|e| e.u)?,
                load: slope(|e| e.load)?,
                tbar: optional(|e| e.tbar),
                tangential_load: optional(|e| e.tangential_load),
            })
        })();
        out.push(Fit {
            scheme: first.scheme.clone(),
            element: first.element,
            rule: first.rule,
            method: first.method.setting(),
            refine_edges: first.grading.to_string(),
            abscissa: match (by_epsilon, first.grading.grades()) {
                (true, _) => "epsilon",
                (false, true) => "n^-1/2",
                (false, false) => "h",
            },
            rows: usable.len(),
            rates,
        });
        start += len;
    }
    out
}
