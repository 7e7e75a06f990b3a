//! Where M1's p̄ error lies on the paper's problem (BENCHMARKS.md "Grading over the
//! contact zone"): p̄'s relative L²(Γ_C) error against the study's certified reference (level
//! 7 + 4 edge refinements, from the user's cache as `riplab study --levels 3..6` leaves it),
//! split into the contact zone's inside (x < a − 0.1), the band |x − a| ≤ 0.1 around the
//! contact edge a, and beyond; on uniform levels, after edge passes, over the zone, and on a
//! mesh graded around the edge alone (sides 1/32, down to 1/256 at the edge, a side at most a
//! eighth of its distance from the edge or from Γ_C).
//!
//! Run: `cargo run --release --example pbar_error_split` (the reference costs minutes when the
//! cache does not hold it).

use riplab::contact::newton::NewtonOptions;
use riplab::contact::{ContactParams, ContactPoints, Method, Rule};
use riplab::fem::quadrature::gauss_legendre;
use riplab::grading::{Grading, RefineEdges};
use riplab::solve::solve_graded;
use riplab::study::{
    Reference, ReferenceFields, ReferenceMesh, Target, errors, refine_reference, uniform_reference,
};
use riplab::{Element, Scenario, SolveError};

/// `lines` bisected until each interval [x0, x1] is at most `side(x0, x1)`.
fn bisected(mut lines: Vec<f64>, side: impl Fn(f64, f64) -> f64) -> Vec<f64> {
    loop {
        let mut out = vec![lines[0]];
        for w in lines.windows(2) {
            if w[1] - w[0] > side(w[0], w[1]) * (1.0 + 1e-9) {
                out.push(0.5 * (w[0] + w[1]));
            }
            out.push(w[1]);
        }
        if out.len() == lines.len() {
            return out;
        }
        lines = out;
    }
}

fn main() -> Result<(), SolveError> {
    let s = Scenario::paper();
    let dir = riplab::cache::default_dir();
    let mut fetch = |g: &ReferenceMesh| riplab::cache::fields(&s, g, dir.as_deref()).map(|(f, _)| f);
    let (reference, fields) = uniform_reference(&s, 7, &mut fetch)?;
    // A target no refinement meets: refine to the study's cap of 4, as `--levels 3..6` does.
    let target = Target {
        p: 0.0,
        u: f64::INFINITY,
    };
    let (reference, fields): (Reference, ReferenceFields) =
        refine_reference(&s, (reference, fields), Some(target), 4, &mut fetch);
    let mesh = reference.grid.mesh(&s);
    let points = ContactPoints::new(Rule::Simpson, &mesh.node_x[..mesh.nnx()], 2);
    let top = fields.p.iter().fold(0.0_f64, |m, v| m.max(*v));
    let a = (points.points.iter().zip(&fields.p))
        .filter(|(_, p)| **p > 1e-9 * top)
        .map(|(q, _)| q.x)
        .fold(0.0, f64::max);
    let epsilon = riplab::study::penalty_error::default_epsilon(&s, 6);
    let params = ContactParams {
        rule: Rule::Gauss1,
        method: Method::Penalty,
        epsilon,
        obstacle: s.obstacle.clone(),
    };
    println!(
        "reference: level 7 + {} edge refinements, contact edge a = {a:.4}; M1 at ε = {epsilon:e}",
        reference.grid.refinements
    );
    // Around the edge alone: sides ≤ 1/32, ≥ 1/256, at most r/8 from the edge (across) and Γ_C.
    let mut around = s.clone();
    let side = |r: f64| (r / 8.0).clamp(1.0 / 256.0, 1.0 / 32.0);
    let uniform = s.mesh(0, Element::Q1);
    around.x_lines = bisected(uniform.xs.clone(), |x0, x1| side((a - x1).max(x0 - a).max(0.0)));
    around.y_lines = bisected(uniform.ys.clone(), |_, y1| side(s.height - y1));
    let cases: [(&Scenario, u32, Grading); 7] = [
        (&s, 5, Grading::default()),
        (&s, 5, RefineEdges::Passes(3).into()),
        (&s, 6, Grading::default()),
        (&s, 6, RefineEdges::Passes(2).into()),
        (&s, 3, Grading::Zone(3)),
        (&s, 4, Grading::Zone(3)),
        (&around, 0, Grading::default()),
    ];
    let gauss = gauss_legendre(6);
    let vx = &points.vertex_x;
    println!(
        "{:<24} {:>8} {:>10} {:>10} {:>10} {:>10}",
        "mesh", "unknowns", "p̄", "inside", "edge band", "beyond"
    );
    for (scenario, level, grading) in cases {
        let uniform = scenario.discretize(level, Element::Q1)?;
        let g = solve_graded(
            scenario,
            (level, &uniform),
            &params,
            grading,
            &NewtonOptions::default(),
        )?;
        let (disc, sol) = (g.disc(&uniform), &g.sol);
        // ∫ (p̄ − p_ref)² over each part, at 6 Gauss points of every reference edge.
        let mut parts = [0.0; 3];
        let mut norm = 0.0;
        for e in 0..vx.len() - 1 {
            let h = vx[e + 1] - vx[e];
            for &(xi, w) in &gauss {
                let x = vx[e] + h * (xi + 1.0) / 2.0;
                let p_ref = points.interpolate(&fields.p, x);
                let d = sol.points.interpolate_vertices(&sol.pbar, x) - p_ref;
                let part = if x < a - 0.1 {
                    0
                } else if x <= a + 0.1 {
                    1
                } else {
                    2
                };
                parts[part] += w * h / 2.0 * d * d;
                norm += w * h / 2.0 * p_ref * p_ref;
            }
        }
        let label = if std::ptr::eq(scenario, &around) {
            "around the edge".to_string()
        } else {
            grading.level_label(level, g.grid.passes)
        };
        println!(
            "{label:<24} {:>8} {:>10.3e} {:>10.3e} {:>10.3e} {:>10.3e}",
            disc.n_dofs(),
            errors(&reference, disc, sol).pbar,
            (parts[0] / norm).sqrt(),
            (parts[1] / norm).sqrt(),
            (parts[2] / norm).sqrt()
        );
    }
    Ok(())
}
