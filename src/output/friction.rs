//! The friction parts of `riplab solve`'s report (docs/design.md §7, §11): the `friction`
//! object (the law, the loading, Q and the states' counts), the `mindlin` object (the
//! Cattaneo–Mindlin stick half-width for the computed P and Q, the computed one and t̄'s
//! distance from q), and their table line.

use serde::Serialize;

use crate::contact::friction::{Law, State};
use crate::contact::mindlin::{Mindlin, dundurs_beta, stick_half_width};
use crate::contact::solution::Solution;
use crate::scenario::Scenario;
use crate::text::{fixed, num};

/// Why a relative distance from a closed form is undefined: the closed form vanishes on Γ_C
/// (a contact narrower than round-off), and a distance relative to 0 is no number.
pub(super) const NO_NORM: &str = "the closed form's L² norm on Γ_C is 0";

/// The `friction` object: present in every solve's JSON, `law = "none"` and nulls without
/// friction.
#[derive(Serialize)]
pub struct FrictionReport {
    /// `none`, `coulomb` or `tresca`.
    pub law: &'static str,
    /// Coulomb's μ.
    pub mu: Option<f64>,
    /// Tresca's threshold g.
    pub threshold: Option<f64>,
    /// The obstacle's shift ξ after the press.
    pub shift: Option<f64>,
    /// The shift's quasi-static steps.
    pub steps: Option<usize>,
    /// The tangential penalty ε_t, when given.
    pub epsilon_t: Option<f64>,
    /// Q = I(t, 1) (0 without friction).
    pub tangential_load: f64,
    /// Q/(μP), Coulomb only, where something presses (P > 0).
    pub load_ratio: Option<f64>,
    /// The computed stick half-width: half the distance between the midpoints outside the
    /// outermost stick points; null with no stick point.
    pub stick_half_width: Option<f64>,
    /// Points stuck, slipping and open.
    pub stick: usize,
    /// See `stick`.
    pub slip: usize,
    /// See `stick`.
    pub open: usize,
    /// Newton iterations per step, the press first.
    pub step_iterations: Vec<usize>,
}

/// The `mindlin` object: Cattaneo–Mindlin for the computed P and Q (a cylinder, Coulomb,
/// 0 < Q < μP).
#[derive(Serialize)]
pub struct MindlinReport {
    /// The stick half-width c = a√(1 − Q/(μP)).
    pub c: f64,
    /// The computed stick half-width.
    pub stick_half_width: Option<f64>,
    /// ‖t̄ − q‖₀/‖q‖₀ on Γ_C.
    pub relative_error: f64,
    /// The body's Dundurs |β| (the solution assumes 0).
    pub beta: f64,
}

impl FrictionReport {
    /// The report of `sol` (none without friction).
    pub fn new(sol: &Solution) -> Self {
        let Some(f) = &sol.friction else {
            return FrictionReport {
                law: Law::None.name(),
                mu: None,
                threshold: None,
                shift: None,
                steps: None,
                epsilon_t: None,
                tangential_load: 0.0,
                load_ratio: None,
                stick_half_width: None,
                stick: 0,
                slip: 0,
                open: 0,
                step_iterations: Vec::new(),
            };
        };
        let count = |s: State| f.states.iter().filter(|&&x| x == s).count();
        let law = f.friction.law;
        FrictionReport {
            law: law.name(),
            mu: law.mu(),
            threshold: law.threshold(),
            shift: Some(f.friction.shift),
            steps: Some(f.friction.steps),
            epsilon_t: f.friction.epsilon_t,
            tangential_load: f.tangential_load,
            // Q/(μP) is undefined where nothing presses (P = 0): absent, not NaN.
            load_ratio: law
                .mu()
                .filter(|_| sol.load > 0.0)
                .map(|mu| f.tangential_load / (mu * sol.load)),
            stick_half_width: stick_half_width(&sol.points, &f.states).map(|w| w.0),
            stick: count(State::Stick),
            slip: count(State::Slip),
            open: count(State::Open),
            step_iterations: f.steps.iter().map(|s| s.iterations).collect(),
        }
    }

    /// The table's line: Q, Q/(μP) and the stick half-width.
    pub fn line(&self) -> Option<String> {
        if self.law == "none" {
            return None;
        }
        let parameter = match (self.mu, self.threshold) {
            (Some(mu), _) => format!("μ = {}", num(mu)),
            (_, Some(g)) => format!("g = {}", num(g)),
            _ => String::new(),
        };
        let ratio = self
            .load_ratio
            .map_or(String::new(), |r| format!(", Q/(μP) = {r:.4}"));
        let width = self
            .stick_half_width
            .map_or("no stick point".into(), |w| format!("stick half-width {w:.5}"));
        let steps = match self.steps.unwrap_or(0) {
            1 => "1 step".to_string(),
            n => format!("{n} steps"),
        };
        Some(format!(
            "friction {} ({parameter}), shift {} in {steps}: Q = {}{ratio}; {} stick, {} slip, {} open points; {width}",
            self.law,
            num(self.shift.unwrap_or(0.0)),
            fixed(self.tangential_load, 6),
            self.stick,
            self.slip,
            self.open
        ))
    }
}

impl MindlinReport {
    /// Cattaneo–Mindlin for `sol` on `scenario` (the full body's P); None unless it applies.
    pub fn new(scenario: &Scenario, sol: &Solution) -> Option<Self> {
        let f = sol.friction.as_ref()?;
        let mu = f.friction.law.mu()?;
        let m = Mindlin::for_loads(
            &sol.params.obstacle,
            &scenario.material,
            sol.load,
            f.tangential_load,
            mu,
        )?;
        Some(MindlinReport {
            c: m.c,
            stick_half_width: stick_half_width(&sol.points, &f.states).map(|w| w.0),
            relative_error: m.relative_error(&sol.points, &f.tbar),
            beta: dundurs_beta(&scenario.material),
        })
    }

    /// The table's line.
    pub fn line(&self) -> String {
        let width = self.stick_half_width.map_or("none".into(), |w| format!("{w:.5}"));
        format!(
            "Cattaneo–Mindlin (β = 0; this body's β = {:.3}, for this P and Q): c = {:.5} (computed stick half-width {width}); ‖t̄ − q‖₀/‖q‖₀ = {}",
            self.beta,
            self.c,
            crate::text::sci(self.relative_error, 3, NO_NORM)
        )
    }
}
