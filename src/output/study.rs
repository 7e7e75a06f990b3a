//! `riplab study`'s report: the reference, every row's errors and rates, and the fits (docs/design.md §6).

use std::fmt::Write as _;

use serde::Serialize;

use super::Report;
use super::csv::{Cell, csv_table};
use crate::study::{Errors, Reference, Status, Study};

/// `riplab study`: the reference, the rows and each scheme's least-squares fit; JSON
/// `{ "scenario", "reference", "rows", "fits" }` (docs/design.md §7).
pub struct StudyReport<'a> {
    /// The scenario's name.
    pub scenario: &'a str,
    /// The study: reference, rows and fits.
    pub study: &'a Study,
}

impl StudyReport<'_> {
    /// The JSON of the reference (the study's `reference` object).
    fn reference_json(&self) -> serde_json::Value {
        let reference = &self.study.reference;
        let mut json = serde_json::json!({
            "element": reference.element.name(), "rule": reference.rule.name(), "epsilon": 0.0,
            "level": reference.level, "refinements": reference.grid.refinements,
            "h_min": reference.grid.h_min(), "n_dofs": reference.n_dofs,
            "load": reference.load, "ms": reference.ms, "source": reference.source,
            "estimate": reference.estimate, "target": reference.target,
            "target_met": reference.target.map(|_| reference.stopped.is_none()), "stopped": reference.stopped,
        });
        if let Some(q) = reference.tangential_load() {
            json["tangential_load"] = q.into();
        }
        json
    }

    /// The study's `friction` object (present with friction only): the law, its parameter,
    /// the shift, its steps and ε_t of the rows (the reference imposes friction exactly).
    fn friction_json(&self) -> Option<serde_json::Value> {
        let f = &self.study.friction;
        f.is_on().then(|| {
            serde_json::json!({
                "law": f.law.name(), "mu": f.law.mu(), "threshold": f.law.threshold(),
                "shift": f.shift, "steps": f.steps, "epsilon_t": f.epsilon_t,
            })
        })
    }
}

impl Serialize for StudyReport<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut json = serde_json::json!({
            "scenario": self.scenario,
            "reference": self.reference_json(),
            "rows": self.study.rows,
            "fits": self.study.fits,
        });
        if let Some(f) = self.friction_json() {
            json["friction"] = f;
        }
        json.serialize(s)
    }
}

/// The study's CSV columns. A line is a `row` (a [`crate::study::StudyRow`]'s JSON), a `fit` (a
/// [`crate::study::Fit`]'s: its rates in the `rate_*` columns) or, last, the `reference` (its
/// smallest cell side as `h`, its estimated error in `err_*`, why its refinement stopped in
/// `reason`, and in `source` whether it was `computed` or read from the `cache`).
pub const STUDY_COLUMNS: [(&str, Cell); 38] = [
    ("kind", Cell::Field("/kind")),
    ("scheme", Cell::Field("/scheme")),
    ("element", Cell::Field("/element")),
    ("rule", Cell::Field("/rule")),
    ("level", Cell::Field("/level")),
    ("refinements", Cell::Field("/refinements")),
    ("refine_edges", Cell::Field("/refine_edges")),
    ("grading", Cell::Field("/grading")),
    ("epsilon_dominated", Cell::Field("/epsilon_dominated")),
    ("h", Cell::First(&["/h", "/h_min"])),
    ("h_min", Cell::Field("/h_min")),
    ("epsilon", Cell::Field("/epsilon")),
    ("method", Cell::Field("/method")),
    ("theta", Cell::Field("/theta")),
    ("gamma0", Cell::Field("/gamma0")),
    ("gamma0_auto", Cell::Field("/gamma0_auto")),
    ("alm_tol", Cell::Field("/alm_tol")),
    ("n_dofs", Cell::Field("/n_dofs")),
    ("status", Cell::Field("/status")),
    ("newton_iterations", Cell::Field("/newton_iterations")),
    ("outer_iterations", Cell::Field("/outer_iterations")),
    ("converged", Cell::Field("/converged")),
    ("solve_ms", Cell::First(&["/solve_ms", "/ms"])),
    ("load", Cell::Field("/load")),
    ("err_p", Cell::First(&["/errors/p", "/estimate/p"])),
    ("err_pbar", Cell::Field("/errors/pbar")),
    ("err_u", Cell::First(&["/errors/u", "/estimate/u"])),
    ("err_load", Cell::First(&["/errors/load", "/estimate/load"])),
    ("err_tbar", Cell::Field("/errors/tbar")),
    ("err_tangential_load", Cell::Field("/errors/tangential_load")),
    ("rate_p", Cell::Field("/rates/p")),
    ("rate_pbar", Cell::Field("/rates/pbar")),
    ("rate_u", Cell::Field("/rates/u")),
    ("rate_load", Cell::Field("/rates/load")),
    ("rate_tbar", Cell::Field("/rates/tbar")),
    ("rate_tangential_load", Cell::Field("/rates/tangential_load")),
    ("reason", Cell::First(&["/reason", "/stopped"])),
    ("source", Cell::Field("/source")),
];

/// `value`, an object, with `kind` first.
pub(super) fn kind(kind: &str, value: serde_json::Value) -> serde_json::Value {
    let mut record = serde_json::Map::new();
    record.insert("kind".into(), kind.into());
    if let serde_json::Value::Object(fields) = value {
        record.extend(fields);
    }
    serde_json::Value::Object(record)
}

impl Report for StudyReport<'_> {
    fn csv(&self) -> String {
        fn value(v: &impl Serialize) -> serde_json::Value {
            serde_json::to_value(v).expect("a record is plain data")
        }
        let mut records: Vec<serde_json::Value> = Vec::new();
        records.extend(self.study.rows.iter().map(|r| kind("row", value(r))));
        records.extend(self.study.fits.iter().map(|f| kind("fit", value(f))));
        let mut reference = kind("reference", self.reference_json());
        // The reference is the exact method, solved (or read) and certified.
        for (key, v) in [
            ("scheme", "reference".into()),
            ("method", "exact".into()),
            ("status", "ok".into()),
            ("converged", true.into()),
        ] {
            reference[key] = v;
        }
        records.push(reference);
        csv_table(&records, &STUDY_COLUMNS)
    }

    fn table(&self) -> String {
        let (scenario, study) = (self.scenario, self.study);
        let (reference, rows) = (&study.reference, &study.rows);
        let mut s = String::new();
        let rate = |r: &Option<Errors>, f: fn(&Errors) -> f64| {
            r.as_ref().map_or(String::new(), |e| format!("{:.2}", f(e)))
        };
        let friction = study.friction.is_on();
        let _ = writeln!(
            s,
            "{scenario}: reference {}+{}, ε = 0 (exact constraint{}), level {}{}, {} dofs, load {:.6}{}",
            reference.element.name(),
            reference.rule.name(),
            friction_words(study),
            reference.level,
            match reference.grid.refinements {
                0 => String::new(),
                1 => " + 1 edge refinement".into(),
                k => format!(" + {k} edge refinements"),
            },
            reference.n_dofs,
            reference.load,
            reference
                .tangential_load()
                .map_or(String::new(), |q| format!(", Q {q:.6}"))
        );
        let _ = writeln!(s, "{}", reference_estimate(reference));
        if let Some(why) = &reference.stopped {
            let _ = writeln!(
                s,
                "warning: the reference's refinement stopped short of the target: {why}"
            );
        }
        let mut methods: Vec<String> = rows.iter().map(|r| r.method.setting().label()).collect();
        methods.dedup();
        if !methods.is_empty() {
            let _ = writeln!(s, "method: {}", methods.join(", "));
        }
        let _ = writeln!(
            s,
            "relative errors: p, p̄ in L²(Γ_C); u in H¹ (7); load P; rate = observed order between successive rows; fit = least-squares order over the scheme's rows"
        );
        if friction {
            let _ = writeln!(
                s,
                "friction: t̄ in L²(Γ_C) relative to ‖p‖, Q relative to P (docs/design.md §11)"
            );
        }
        let _ = write!(
            s,
            "{:<14} {:>5} {:>9} {:>8} {:>8} {:>7} {:>9} {:>10} {:>5} {:>10} {:>5} {:>10} {:>5} {:>10} {:>5}",
            "scheme",
            "level",
            "h",
            "ε",
            "dofs",
            "Newton",
            "solve ms",
            "p",
            "rate",
            "p̄",
            "rate",
            "u",
            "rate",
            "load",
            "rate"
        );
        let _ = writeln!(
            s,
            "{}",
            if friction {
                format!(" {:>10} {:>5} {:>10} {:>5}", "t̄", "rate", "Q", "rate")
            } else {
                String::new()
            }
        );
        for (i, r) in rows.iter().enumerate() {
            if i > 0 && !rows[i - 1].same_series(r) {
                s.push('\n');
            }
            let head = format!(
                "{:<14} {:>5} {:>9.6} {} {:>8}",
                r.scheme,
                r.level_label(),
                r.h,
                r.method.epsilon_text(r.epsilon, 8),
                r.n_dofs
            );
            let last = rows.get(i + 1).is_none_or(|n| !n.same_series(r));
            let fit = study.fits.iter().find(|f| {
                last && f.scheme == r.scheme
                    && f.method == r.method.setting()
                    && f.refine_edges == r.grading.to_string()
                    // A fit needs two rows: with fewer it has no rates to show.
                    && f.rows >= 2
            });
            let (Some(e), Some(iterations), Some(ms)) = (&r.errors, r.newton_iterations, r.solve_ms) else {
                // No result: the reason in place of the numbers.
                let reason = r.reason.as_deref().unwrap_or("");
                let _ = writeln!(s, "{head}  {}: {}", r.status.word(), short_reason(reason));
                if let Some(f) = fit {
                    let _ = writeln!(s, "{}", fit_line(f, &rate));
                }
                continue;
            };
            let flag = if r.status == Status::Ok {
                String::new()
            } else {
                format!("  {}", r.status.word().to_uppercase())
            };
            let tangential = match friction {
                true => friction_cells(Some(e), &r.rates),
                false => String::new(),
            };
            let _ = writeln!(
                s,
                "{head} {:>7} {:>9.1} {:>10.3e} {:>5} {:>10.3e} {:>5} {:>10.3e} {:>5} {:>10.3e} {:>5}{tangential}{flag}",
                iterations,
                ms,
                e.p,
                rate(&r.rates, |e| e.p),
                e.pbar,
                rate(&r.rates, |e| e.pbar),
                e.u,
                rate(&r.rates, |e| e.u),
                e.load,
                rate(&r.rates, |e| e.load)
            );
            if let Some(f) = fit {
                let tangential = match friction {
                    true => friction_cells(None, &f.rates),
                    false => String::new(),
                };
                let _ = writeln!(s, "{}{tangential}", fit_line(f, &rate));
            }
        }
        let reasons: Vec<String> = rows
            .iter()
            .filter(|r| r.status != Status::Ok)
            .filter_map(|r| {
                r.reason.as_ref().map(|why| {
                    let setting = if r.method.uses_epsilon() {
                        format!("ε = {:e}", r.epsilon)
                    } else {
                        r.method.label()
                    };
                    format!("{} level {} {setting}: {why}", r.scheme, r.level)
                })
            })
            .collect();
        if !reasons.is_empty() {
            let _ = writeln!(s, "\nrows without a certified result:");
            for why in reasons {
                let _ = writeln!(s, "  {why}");
            }
        }
        let warned: Vec<String> = rows
            .iter()
            .flat_map(|r| {
                r.warnings
                    .iter()
                    .map(move |w| format!("{} level {}: {w}", r.scheme, r.level_label()))
            })
            .collect();
        if !warned.is_empty() {
            let _ = writeln!(s, "\nwarnings:");
            for w in warned {
                let _ = writeln!(s, "  {w}");
            }
        }
        s
    }
}

/// The reference's friction for the table's first line: `, coulomb μ = 0.3` (empty without).
fn friction_words(study: &Study) -> String {
    let f = &study.friction;
    match (f.law.mu(), f.law.threshold()) {
        (Some(mu), _) => format!(", coulomb μ = {}", crate::text::num(mu)),
        (_, Some(g)) => format!(", tresca g = {}", crate::text::num(g)),
        _ => String::new(),
    }
}

/// The table's t̄ and Q cells: a row's errors (`errors`) and rates, or a fit's rates alone.
fn friction_cells(errors: Option<&Errors>, rates: &Option<Errors>) -> String {
    let error = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.3e}"));
    let rate = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.2}"));
    let r = |f: fn(&Errors) -> Option<f64>| rate(rates.as_ref().and_then(f));
    format!(
        " {:>10} {:>5} {:>10} {:>5}",
        error(errors.and_then(|e| e.tbar)),
        r(|e| e.tbar),
        error(errors.and_then(|e| e.tangential_load)),
        r(|e| e.tangential_load)
    )
}

/// The table's lines on the reference's estimated error and what the study asked of it.
pub(super) fn reference_estimate(reference: &Reference) -> String {
    let Some(e) = &reference.estimate else {
        return "reference's estimated error: none (no coarser reference)".into();
    };
    let u_note = if reference.grid.refinements > 0 {
        " (the uniform level's)"
    } else {
        ""
    };
    let mut line = format!(
        "reference's estimated error (difference from {}): p {:.3e}, u {:.3e}{u_note}, load {:.3e}",
        e.against, e.p, e.u, e.load
    );
    if let Some(t) = &reference.target {
        let _ = write!(
            line,
            "\nreference's target (a tenth of the smallest row errors): p ≤ {:.3e}, u ≤ {:.3e}: {}",
            t.p,
            t.u,
            if reference.stopped.is_none() {
                "met"
            } else {
                "not met"
            }
        );
    }
    line
}

/// Formats one rate of a row's (or a fit's) rates, empty when there are none.
pub(super) type RateText = dyn Fn(&Option<Errors>, fn(&Errors) -> f64) -> String;

/// The table's `fit` line of a scheme: its least-squares rates in the rate columns.
pub(super) fn fit_line(f: &crate::study::Fit, rate: &RateText) -> String {
    format!(
        "{:<66} {:>10} {:>5} {:>10} {:>5} {:>10} {:>5} {:>10} {:>5}",
        format!("  fit: least squares over {} rows", f.rows),
        "",
        rate(&f.rates, |e| e.p),
        "",
        rate(&f.rates, |e| e.pbar),
        "",
        rate(&f.rates, |e| e.u),
        "",
        rate(&f.rates, |e| e.load)
    )
}

/// The first clause of a reason, for a table cell (the whole reason follows the table).
pub(super) fn short_reason(reason: &str) -> &str {
    if reason.contains("multipliers are not unique") {
        return "multipliers not unique";
    }
    reason.split([':', ';']).next().unwrap_or(reason).trim()
}
