//! An obstacle of one's own: the paper's problem (docs/design.md §1) pressed by a parabolic
//! indenter η(x) = x²/2R, the outline Hertz's theory assumes, beside the paper's exact
//! cylinder of the same radius R = 8. The parabola lies below the circle
//! (x²/2R ≤ R − √(R² − x²)), so it reaches the body over a wider zone and carries more load.
//!
//! Run: `cargo run --release --example custom_obstacle`

use std::sync::Arc;

use riplab::contact::{Obstacle, Outline};
use riplab::scenario::Scenario;
use riplab::solve::solve_scenario;

/// η(x) = (x − c)²/2R: a cylinder's outline to second order.
struct Parabola {
    radius: f64,
    center: f64,
}

impl Outline for Parabola {
    fn outline(&self, x: f64) -> f64 {
        (x - self.center).powi(2) / (2.0 * self.radius)
    }
    fn center(&self) -> f64 {
        self.center
    }
    fn describe(&self) -> String {
        format!("a parabola of radius {}", self.radius)
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut scenario = Scenario::paper();
    scenario.level = 3;
    let Obstacle::Cylinder {
        radius,
        depth,
        center,
    } = scenario.obstacle
    else {
        return Err("the paper's obstacle is a cylinder".into());
    };
    let (_, cylinder) = solve_scenario(&scenario)?;
    scenario.obstacle = Obstacle::Custom {
        outline: Arc::new(Parabola { radius, center }),
        depth,
    };
    let (_, parabola) = solve_scenario(&scenario)?;
    for (name, sol) in [("cylinder", &cylinder), ("parabola", &parabola)] {
        let x = &sol.points.vertex_x;
        let reach = (0..x.len())
            .filter(|&i| sol.pbar[i] > 0.0)
            .map(|i| x[i])
            .fold(0.0, f64::max);
        let peak = sol.pbar.iter().cloned().fold(0.0, f64::max);
        println!(
            "{name:>8}: load P = {:.4}, max p̄ = {peak:.4}, p̄ > 0 up to x = {reach:.4} ({} Newton steps)",
            sol.load, sol.newton.iterations
        );
    }
    Ok(())
}
