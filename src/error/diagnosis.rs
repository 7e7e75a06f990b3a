//! Why a contact solve stopped without a result it can certify: the typed diagnosis of the
//! semismooth Newton driver ([`crate::contact::newton`]) and of the methods around it, kept in
//! a [`crate::contact::newton::NewtonResult`] and in [`super::SolveError::NotConverged`].

/// The cause of a non-converged solve, with the numbers that show it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Diagnosis {
    /// The iteration limit was reached, or the residual is not finite.
    #[error("{}", stalled(*iterations, *residual))]
    Stalled {
        /// Newton iterations taken.
        iterations: usize,
        /// The last relative residual.
        residual: f64,
    },
    /// The iterate's state set was one seen before: the iteration cycles.
    #[error("the active set cycles (after {iterations} iterations, relative residual {residual:.1e})")]
    Cycling {
        /// Newton iterations taken.
        iterations: usize,
        /// The last relative residual.
        residual: f64,
    },
    /// Round-off in u_n − g, amplified by 1/ε, is as large as the contact forces of (11).
    #[error(
        "ε = {epsilon:e} is below what double precision resolves here: round-off in u_n − g, amplified by 1/ε, is as large as the contact forces; use a larger ε (or --kappa), or ε = 0 for the exact constraint"
    )]
    Swamped {
        /// The penalty parameter ε of (8).
        epsilon: f64,
    },
    /// Nitsche's Newton system of the active set is singular (below the stability threshold).
    #[error(
        "the Newton system of the active set is singular (θ = {theta}, γ₀ = {gamma0}): choose a larger γ₀"
    )]
    Singular {
        /// Nitsche's θ.
        theta: f64,
        /// Nitsche's γ₀.
        gamma0: f64,
    },
    /// The augmented Lagrangian's inner penalty Newton failed at one multiplier update.
    #[error("the inner penalty Newton of outer iteration {outer} did not converge: {inner}")]
    Inner {
        /// The multiplier update (from 1) whose inner solve failed.
        outer: usize,
        /// Why the inner solve failed.
        inner: Box<Diagnosis>,
    },
    /// The augmented Lagrangian's multiplier updates did not settle.
    #[error(
        "no convergence in {updates} multiplier updates (relative change {change:.1e}); each update shrinks the error by about ε/(ε + σ), σ the compliance: a smaller ε needs fewer updates"
    )]
    Updates {
        /// Multiplier updates taken.
        updates: usize,
        /// The last relative change of the contact forces.
        change: f64,
    },
    /// Friction's Coulomb system of a state set is singular ([`crate::contact::friction`]).
    #[error("the Coulomb system is singular: μ too large for a unique incremental solution on this mesh")]
    CoulombSingular,
    /// Friction's press (the shift 0) failed.
    #[error("the press (shift 0) did not converge: {0}")]
    Press(Box<Diagnosis>),
    /// A friction shift step failed after its bisections: the solve stopped at `from`.
    #[error(
        "the shift step from {from} to {to} did not converge after {bisections} bisections; the solve stopped at shift {from}: {cause}"
    )]
    Shift {
        /// The shift reached.
        from: f64,
        /// The shift the step aimed at.
        to: f64,
        /// Bisections tried.
        bisections: u32,
        /// Why the last sub-step failed.
        cause: Box<Diagnosis>,
    },
    /// A converged iterate whose forces, pressures or displacements are not finite.
    #[error(
        "a contact force, pressure or displacement is not finite: the problem's scaling overflows double precision"
    )]
    Overflow,
}

/// [`Diagnosis::Stalled`]'s message.
fn stalled(iterations: usize, residual: f64) -> String {
    if residual.is_finite() {
        format!("no convergence in {iterations} Newton iterations (relative residual {residual:.1e})")
    } else {
        "the residual is not finite".to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The messages carry the numbers of their variant, formatted as the solvers did.
    #[test]
    fn messages_carry_their_numbers() {
        let stalled = Diagnosis::Stalled {
            iterations: 3,
            residual: 1.5,
        };
        assert_eq!(
            stalled.to_string(),
            "no convergence in 3 Newton iterations (relative residual 1.5e0)"
        );
        let nan = Diagnosis::Stalled {
            iterations: 3,
            residual: f64::NAN,
        };
        assert_eq!(nan.to_string(), "the residual is not finite");
        let inner = Diagnosis::Inner {
            outer: 2,
            inner: Box::new(Diagnosis::Swamped { epsilon: 1e-20 }),
        };
        assert!(
            inner.to_string().starts_with(
                "the inner penalty Newton of outer iteration 2 did not converge: ε = 1e-20 is below"
            ),
            "{inner}"
        );
    }
}
