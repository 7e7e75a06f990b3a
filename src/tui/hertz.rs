//! The plane Hertz profile for a given load, the reference curve of the pressure chart
//! (DESIGN §6): a² = 4PR/(πE*), p₀ = 2P/(πa), p(x) = p₀√(1 − x²/a²).

use crate::material::Plane;
use crate::scenario::Scenario;

/// The Hertz contact of a rigid cylinder on an elastic half-plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hertz {
    /// Half-width of the contact.
    pub a: f64,
    /// Peak pressure.
    pub p0: f64,
    /// Axis of the cylinder.
    pub center: f64,
}

impl Hertz {
    /// The profile for the load `load` carried by the modelled body of `scenario` (doubled for
    /// a half model); None when there is no load.
    pub fn for_load(scenario: &Scenario, load: f64) -> Option<Hertz> {
        let full = if scenario.half_model { 2.0 * load } else { load };
        let m = scenario.material;
        let e_star = match m.plane {
            Plane::Strain => m.young / (1.0 - m.poisson * m.poisson),
            Plane::Stress => m.young,
        };
        let (radius, center) = (scenario.obstacle.hertz_radius()?, scenario.obstacle.center());
        if full.is_nan() || full <= 0.0 {
            return None;
        }
        let a = (4.0 * full * radius / (std::f64::consts::PI * e_star)).sqrt();
        let p0 = 2.0 * full / (std::f64::consts::PI * a);
        Some(Hertz { a, p0, center })
    }

    /// p(x), zero outside the contact.
    pub fn pressure(&self, x: f64) -> f64 {
        let r = (x - self.center) / self.a;
        if r.abs() < 1.0 {
            self.p0 * (1.0 - r * r).sqrt()
        } else {
            0.0
        }
    }
}
