//! Estimates of how long mesh work takes, for the time left shown while it runs. Building a
//! level (assembly, ordering, factorisation, trace compliance) grows like n^1.3 in the number
//! of unknowns n on these meshes (BENCHMARKS.md: levels 5 → 6 take 6.1× as long for 4× the
//! unknowns, 270 ms → 1655 ms at 262 400 unknowns). The constant starts from those numbers
//! and is re-measured on every build, so that the estimate follows the machine it runs on.

/// The exponent of n in the cost of a build.
const EXPONENT: f64 = 1.3;
/// Milliseconds and unknowns of the benchmark's level-6 build, the first calibration.
const BENCH: (f64, f64) = (1655.0, 262_400.0);
/// Milliseconds and unknowns of Nitsche's preparation at level 6 with cold memory (the lab's
/// usual state after a pause; 1.2 s warm: BENCHMARKS.md, "The study and Nitsche's method
/// beside the lab's worker"), the first calibration of its model: 12 s at level 7, as
/// measured there.
const PREPARING_BENCH: (f64, f64) = (1900.0, 262_400.0);
/// Below this many milliseconds no estimate is shown.
pub const SHOWN_FROM_MS: f64 = 500.0;

/// The cost model t = c·n^1.3 with its constant c.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Eta {
    c: f64,
}

impl Default for Eta {
    fn default() -> Self {
        Eta {
            c: BENCH.0 / BENCH.1.powf(EXPONENT),
        }
    }
}

impl Eta {
    /// The model of Nitsche's preparation ([`crate::solve::prepare`]): another factorisation of
    /// the mesh's size and dense work on Γ_C, calibrated on its own benchmark.
    pub fn preparing() -> Self {
        Eta {
            c: PREPARING_BENCH.0 / PREPARING_BENCH.1.powf(EXPONENT),
        }
    }

    /// The expected milliseconds of a build of `unknowns` unknowns.
    pub fn predict_ms(&self, unknowns: usize) -> f64 {
        self.c * (unknowns as f64).powf(EXPONENT)
    }

    /// Learn from a build of `unknowns` that took `ms` (builds under 20 ms are too noisy).
    pub fn record(&mut self, unknowns: usize, ms: f64) {
        if ms >= 20.0 && unknowns > 0 && ms.is_finite() {
            self.c = ms / (unknowns as f64).powf(EXPONENT);
        }
    }
}

/// "about 3 s left" (or "a moment more" once the estimate has passed); None when the whole
/// job is expected to take under [`SHOWN_FROM_MS`].
pub fn time_left(estimate_ms: f64, elapsed_ms: f64) -> Option<String> {
    if estimate_ms < SHOWN_FROM_MS {
        return None;
    }
    let left = (estimate_ms - elapsed_ms) / 1e3;
    Some(if left < 0.5 {
        "a moment more".into()
    } else {
        format!("about {} s left", left.ceil() as u64)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_model_reproduces_its_calibration_and_the_benchmarks_ratio() {
        let eta = Eta::default();
        assert!((eta.predict_ms(262_400) - 1655.0).abs() < 1e-6);
        // ×4 unknowns: ×4^1.3 = 6.06 (the benchmark: 1655 / 270.5 = 6.1).
        let ratio = eta.predict_ms(262_400) / eta.predict_ms(65_600);
        assert!((ratio - 4f64.powf(1.3)).abs() < 1e-9);
        let mut eta = eta;
        eta.record(1000, 100.0);
        assert!((eta.predict_ms(1000) - 100.0).abs() < 1e-9);
        eta.record(1000, 1.0); // too short to learn from
        assert!((eta.predict_ms(1000) - 100.0).abs() < 1e-9);
    }

    #[test]
    fn time_left_reads_in_whole_seconds() {
        assert_eq!(time_left(400.0, 0.0), None);
        assert_eq!(time_left(3000.0, 600.0).as_deref(), Some("about 3 s left"));
        assert_eq!(time_left(3000.0, 2900.0).as_deref(), Some("a moment more"));
    }
}
