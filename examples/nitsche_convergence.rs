//! The tables of docs/convergence.md's Nitsche section:
//! `cargo run --release --example nitsche_convergence [max_level]`.
//!
//! 1. Errors against the study's reference (level max + 1) of the exact constraint and of
//!    Nitsche's method (θ = 1, 0, −1 at γ₀ = 10 γ₀*) for M3's, M4's and P1 + trapezoid's
//!    element and rule, levels 1..=max, with observed rates.
//! 2. The γ₀ sweep: the errors at level 3 for γ₀ over decades and near the thresholds.

use std::ops::ControlFlow;

use riplab::contact::ContactParams;
use riplab::contact::Rule;
use riplab::contact::newton::NewtonOptions;
use riplab::contact::nitsche::{self, NitscheParams};
use riplab::mesh::Element;
use riplab::scenario::Scenario;
use riplab::solve::solve_contact;
use riplab::study::{Errors, Reference, errors};

const PAIRS: [(Element, Rule); 3] = [
    (Element::Q1, Rule::Trapezoid),
    (Element::Q2, Rule::Simpson),
    (Element::P1, Rule::Trapezoid),
];

fn row(label: &str, level: u32, e: &Errors, prev: Option<&Errors>, iterations: usize, converged: bool) {
    let rate =
        |a: f64, b: Option<f64>| b.map_or(String::from("     "), |b| format!("{:5.2}", (b / a).log2()));
    println!(
        "| {label} | {level} | {iterations}{} | {:.3e} | {} | {:.3e} | {} | {:.3e} |",
        if converged { "" } else { " (not converged)" },
        e.u,
        rate(e.u, prev.map(|p| p.u)),
        e.p,
        rate(e.p, prev.map(|p| p.p)),
        e.load
    );
}

fn main() {
    riplab::fem::set_threads(1);
    let max: u32 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(5);
    let scenario = Scenario::paper();
    let reference = Reference::compute(&scenario, max + 1).expect("the reference");
    println!(
        "reference: q2 + simpson, exact constraint, level {}, {} dofs, load {:.6}\n",
        max + 1,
        reference.n_dofs,
        reference.load
    );
    for (element, rule) in PAIRS {
        println!("### {} + {}\n", element.name(), rule.name());
        println!(
            "| method | level | Newton | u (H¹) | rate | p (L²) | rate | load |\n|---|---|---|---|---|---|---|---|"
        );
        let params = ContactParams::by_epsilon(rule, 0.0, scenario.obstacle.clone());
        let mut rows: Vec<Vec<(u32, Errors, usize, bool)>> = vec![Vec::new(); 4];
        let mut star = 0.0;
        for level in 1..=max {
            let disc = scenario.discretize(level, element).unwrap();
            star = nitsche::stability_threshold(&disc, rule).unwrap();
            let exact = solve_contact(&disc, &params, None, &NewtonOptions::default(), &mut |_| {
                ControlFlow::Continue(())
            })
            .unwrap();
            rows[0].push((
                level,
                errors(&reference, &disc, &exact),
                exact.newton.iterations,
                exact.newton.converged,
            ));
            for (k, theta) in [1.0, 0.0, -1.0].into_iter().enumerate() {
                let sol = nitsche::solve_once(
                    &disc,
                    &params,
                    NitscheParams {
                        theta,
                        gamma0: 10.0 * star,
                    },
                )
                .unwrap();
                rows[k + 1].push((
                    level,
                    errors(&reference, &disc, &sol),
                    sol.newton.iterations,
                    sol.newton.converged,
                ));
            }
        }
        for (k, label) in ["exact", "nitsche θ = 1", "nitsche θ = 0", "nitsche θ = −1"]
            .iter()
            .enumerate()
        {
            for (i, (level, e, it, ok)) in rows[k].iter().enumerate() {
                row(
                    label,
                    *level,
                    e,
                    i.checked_sub(1).map(|j| &rows[k][j].1),
                    *it,
                    *ok,
                );
            }
        }
        println!(
            "\nγ₀* = {star:.4} (Nitsche rows at γ₀ = 10 γ₀* = {:.3})\n",
            10.0 * star
        );
    }
    println!("### γ₀ sweep at level 3\n");
    println!("| pair | γ₀* | γ₀ | θ = 1: u, p | θ = 0: u, p | θ = −1: u, p |\n|---|---|---|---|---|---|");
    for (element, rule) in PAIRS {
        let disc = scenario.discretize(3, element).unwrap();
        let params = ContactParams::by_epsilon(rule, 0.0, scenario.obstacle.clone());
        let star = nitsche::stability_threshold(&disc, rule).unwrap();
        let mut gammas = vec![
            1e-4,
            1e-3,
            1e-2,
            1e-1,
            0.2 * star,
            0.3 * star,
            0.99 * star,
            1.01 * star,
            1.1 * star,
            2.0 * star,
            10.0 * star,
            1e2,
            1e3,
            1e4,
        ];
        gammas.sort_by(f64::total_cmp);
        for g in gammas {
            let cell =
                |theta: f64| match nitsche::solve_once(&disc, &params, NitscheParams { theta, gamma0: g }) {
                    Ok(s) if s.newton.converged => {
                        let e = errors(&reference, &disc, &s);
                        format!("{:.2e}, {:.2e}", e.u, e.p)
                    }
                    Ok(s) => format!("not converged ({} it.)", s.newton.iterations),
                    Err(_) => "refused".to_string(),
                };
            println!(
                "| {} + {} | {star:.3} | {g:.3e} | {} | {} | {} |",
                element.name(),
                rule.name(),
                cell(1.0),
                cell(0.0),
                cell(-1.0)
            );
        }
    }
}
