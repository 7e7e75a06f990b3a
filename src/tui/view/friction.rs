//! Friction on the pressure chart (docs/design.md §11, "The lab"): the raw tangential
//! traction t at the rule's points (`×`), the smoothed t̄ through Γ_C's vertices (a solid
//! line with `~` at every vertex), the stick zone (`═` on the x axis between its ends), and,
//! with the Mindlin overlay (`M`), Cattaneo–Mindlin's traction q (`*`) for the computed P and
//! Q. With Coulomb's law t, t̄ and q are drawn divided by μ, on p's axis: a slipping point's
//! t/μ reaches its p, and the stick zone is where t/μ stays below (Johnson's figure 7.7);
//! Tresca's t is drawn as it is (g shares p's unit).

use ratatui::Frame;
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;

use super::super::friction_settings::label;
use super::super::shown_friction::FrictionShown;
use super::fmt::sig;
use super::plot::{Placed, Series, Stroke, cell_of, dots_per_cell};
use crate::contact::friction::{Friction, Law};

/// Samples of q across the chart.
const SAMPLES: usize = 41;
/// The stick zone's mark on the x axis.
const STICK: char = '═';

/// The sampled series of a solve with friction over the chart's x range.
pub struct Layer {
    /// q(x) where the Hertz contact holds it (|x − centre| < a), with Mindlin.
    pub q: Vec<(f64, f64)>,
    /// t̄ where it or a neighbour is not 0, and t where it is not 0: outside the contact
    /// both are 0, on p̄'s line, and their marks along the whole axis hid it.
    pub tbar: Vec<(f64, f64)>,
    /// See `tbar`.
    pub t: Vec<(f64, f64)>,
    /// The stick zone's ends within the chart's x range, marked on the x axis.
    pub stick: Option<(f64, f64)>,
    /// "/μ" where t and q are drawn divided by μ (Coulomb, μ > 0), else "".
    pub over: &'static str,
}

/// The colours of the friction series (the theme's inks, set apart from p's).
pub struct Inks {
    /// t̄.
    pub smooth: Color,
    /// t.
    pub raw: Color,
    /// q.
    pub overlay: Color,
    /// The stick zone.
    pub stick: Color,
}

impl Layer {
    /// The layer of `shown` over the x range `[lo, hi]`, q when `mindlin` (the `M` overlay).
    pub fn new(shown: &FrictionShown, [lo, hi]: [f64; 2], mindlin: bool) -> Layer {
        let q = shown
            .mindlin
            .filter(|_| mindlin)
            .map(|m| {
                (0..SAMPLES)
                    .map(|i| lo + (hi - lo) * i as f64 / (SAMPLES - 1) as f64)
                    .filter(|&x| (x - m.hertz.center).abs() < m.hertz.a)
                    .map(|x| (x, m.traction(x) / m.mu))
                    .collect()
            })
            .unwrap_or_default();
        let stick = shown
            .stick
            .map(|(a, b, _)| (a.max(lo), b.min(hi)))
            .filter(|(a, b)| a <= b);
        let per = per_mu(shown);
        let v = &shown.tbar;
        let loaded = |i: usize| v.get(i).is_some_and(|p| p.1 != 0.0);
        let tbar = (0..v.len())
            .filter(|&i| loaded(i) || (i > 0 && loaded(i - 1)) || loaded(i + 1))
            .map(|i| (v[i].0, v[i].1 * per))
            .collect();
        let t = shown
            .t
            .iter()
            .filter(|p| p.1 != 0.0)
            .map(|&(x, t)| (x, t * per))
            .collect();
        Layer {
            q,
            tbar,
            t,
            stick,
            over: if per == 1.0 { "" } else { "/μ" },
        }
    }

    /// q's series (none without it): one of the chart's overlays, under p̄.
    pub fn overlay<'a>(&'a self, inks: &Inks) -> Option<Series<'a>> {
        (!self.q.is_empty()).then(|| Series {
            name: format!("q{} Mindlin", self.over),
            color: inks.overlay,
            stroke: Stroke::None,
            glyph: Some('*'),
            data: &self.q,
        })
    }

    /// t̄, t and the stick zone, drawn after p̄ and p.
    pub fn series<'a>(&'a self, inks: &Inks) -> Vec<Series<'a>> {
        let mut out = vec![
            Series {
                name: format!("t̄{}", self.over),
                color: inks.smooth,
                stroke: Stroke::Solid,
                glyph: Some('~'),
                data: &self.tbar,
            },
            Series {
                name: format!("t{}", self.over),
                color: inks.raw,
                stroke: Stroke::None,
                glyph: Some('×'),
                data: &self.t,
            },
        ];
        if self.stick.is_some() {
            // Its mark is on the x axis ([`draw_stick`]): the legend names it, nothing is
            // drawn in the graph.
            out.push(Series {
                name: "stick".into(),
                color: inks.stick,
                stroke: Stroke::None,
                glyph: Some(STICK),
                data: &[],
            });
        }
        out
    }

    /// The smallest value the layer draws, and 0.
    pub fn low(&self) -> f64 {
        self.values().fold(0.0, f64::min)
    }

    /// The largest value the layer draws, and 0.
    pub fn peak(&self) -> f64 {
        self.values().fold(0.0, f64::max)
    }

    fn values(&self) -> impl Iterator<Item = f64> + '_ {
        self.q.iter().chain(&self.tbar).chain(&self.t).map(|p| p.1)
    }

    /// The y axis's title: "p, t/μ (units of E)" (or "p, t" without a μ to divide by).
    pub fn y_title(&self) -> String {
        format!("p, t{} (units of E)", self.over)
    }
}

/// 1/μ for Coulomb with μ > 0 (t/μ reaches p where a point slips: the stick zone is where it
/// stays below), else 1 (Tresca's t and g share p's unit).
pub(super) fn per_mu(shown: &FrictionShown) -> f64 {
    match shown.law {
        Law::Coulomb { mu } if mu > 0.0 => 1.0 / mu,
        _ => 1.0,
    }
}

/// The stick zone `ends` on the x axis under the graph `placed` (x bounds `bounds`): every
/// axis cell whose column holds an x between them drawn `═` (`╤` at a tick).
pub fn draw_stick(
    frame: &mut Frame,
    placed: Placed,
    bounds: [f64; 2],
    ends: (f64, f64),
    marker: Marker,
    color: Color,
) {
    let graph = placed.graph;
    let per = dots_per_cell(marker).0;
    let (Some(a), Some(b)) = (
        cell_of(ends.0, bounds, graph.width, per),
        cell_of(ends.1, bounds, graph.width, per),
    ) else {
        return;
    };
    let buf = frame.buffer_mut();
    for col in a..=b {
        let cell = &mut buf[(graph.x + col, graph.bottom())];
        let mark = if cell.symbol() == "┬" { "╤" } else { "═" };
        cell.set_symbol(mark).set_style(Style::new().fg(color));
    }
}

/// The Dundurs |β| from which the status line says that Mindlin's q assumes β = 0
/// (cattaneo-mindlin's ν = 0.499 gives 0.002).
const BETA_NAMED: f64 = 0.05;

/// The status line's friction part, the numbers `riplab solve` prints: "coulomb μ = 0.3,
/// shift ξ = 0.0815: Q=20.51 Q/(μP)=0.4995 · stick half-width 0.8125, Mindlin c=0.809,
/// t̄ off q 2.3%" (Mindlin for a cylinder with Coulomb and 0 < Q < μP).
pub fn status(shown: &FrictionShown) -> String {
    let law = label(&Friction {
        law: shown.law,
        shift: shown.shift,
        ..Friction::NONE
    });
    let ratio = shown
        .load_ratio
        .map_or(String::new(), |r| format!(" Q/(μP)={}", sig(r, 4)));
    let width = shown.stick_half_width.map_or("no stick point".into(), |w| {
        format!("stick half-width {}", sig(w, 4))
    });
    let mindlin = match (shown.mindlin, shown.mindlin_error) {
        // Mindlin's q assumes β = 0: a body far from it is named (hertz-paper-full's 0.29).
        (Some(m), Some(e)) => {
            let beta = if shown.beta >= BETA_NAMED {
                format!(" (β=0; here {})", sig(shown.beta, 2))
            } else {
                String::new()
            };
            format!(
                ", Mindlin{beta} c={}, t̄ off q {}%",
                sig(m.c, 4),
                sig(100.0 * e, 2)
            )
        }
        _ => String::new(),
    };
    format!(
        "{law}: Q={}{ratio} · {width}{mindlin}",
        sig(shown.tangential_load, 5)
    )
}
