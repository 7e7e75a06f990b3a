//! The contact methods riplab compares (docs/design.md §10): how the constraint u_n − g ≤ 0 of
//! (4) is imposed on Γ_C. One type, one parser, one name, one place that checks parameters.
//!
//! - `penalty`: the paper's penalised problem (8), (11) at ε > 0 (raw p and smoothed p̄).
//! - `exact`: the limit ε = 0, Lagrange multipliers at the rule's points (primal–dual active
//!   set, [`super::signorini`]); needs a rule without kernel (inf-sup).
//! - `alm`: the augmented Lagrangian at a finite ε ([`super::alm`]): Uzawa updates of the
//!   multiplier around the penalty Newton; no penalty error.
//! - `nitsche`: Nitsche's method, θ ∈ {1, 0, −1}, γ = γ₀·E/h (Chouly and Hild 2013): no
//!   multiplier, no inf-sup condition. γ₀ is a number or [`Gamma0::Auto`]: a multiple of the
//!   symmetric variant's stability threshold γ₀* on the mesh and rule, which varies by orders
//!   of magnitude between elements, rules and cell shapes (1.57 for q1 + gauss1 on the paper's
//!   mesh, 9.1 for q2 + simpson, 1.3·10³ on the tall cells of `hertz-block`).

use serde::Serialize;

use crate::check::Allowed;
use crate::error::MethodError;
use crate::text::num;

/// θ of Nitsche's method: 1 symmetric, 0 incomplete, −1 skew-symmetric.
pub const THETAS: [i8; 3] = [1, 0, -1];
/// The range of Nitsche's γ₀ (γ = γ₀·E/h). Nitsche's contact term acts like a penalty of
/// ε = h/(γ₀E), i.e. κ = εE/h = 1/γ₀: γ₀ ≤ 1e8 keeps κ ≥ 1e-8, well above κ ≈ 1e-13 where
/// round-off swamps a penalty's contact forces (STABILITY.md); γ₀ ≥ 1e-8 keeps 1/γ finite
/// and representable in every product. Whether a γ₀ is *stable* (the symmetric variant
/// needs it large enough) is the method's to report, not an input error.
pub const GAMMA0_RANGE: (f64, f64) = (1e-8, 1e8);
/// Nitsche's default parameters: symmetric, γ₀ chosen from the mesh ([`Gamma0::Auto`]).
pub const DEFAULT_THETA: i8 = 1;
/// Nitsche's default γ₀: [`Gamma0::Auto`].
pub const DEFAULT_GAMMA0: Gamma0 = Gamma0::Auto;
/// `auto`'s γ₀ = 10·γ₀*: ten times the threshold of the symmetric variant (θ = 1), forty times
/// the incomplete one's (θ = 0), past the 2·γ₀* from which γ₀ no longer changes the errors
/// (docs/convergence.md, "The default γ₀").
pub const AUTO_GAMMA0_FACTOR: f64 = 10.0;

/// Nitsche's γ₀: a number, or `auto` ([`AUTO_GAMMA0_FACTOR`]·γ₀*, γ₀* computed on the mesh
/// and rule of the solve by `nitsche::stability_threshold`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Gamma0 {
    /// γ₀ = [`AUTO_GAMMA0_FACTOR`]·γ₀*, chosen from the mesh and rule of the solve.
    Auto,
    /// The given γ₀ > 0.
    Given(f64),
}

impl Gamma0 {
    /// `auto` (any case) or a number; the range is [`Method::check`]'s.
    ///
    /// # Errors
    ///
    /// Text that is neither `auto` nor a number.
    pub fn parse(text: &str) -> Result<Gamma0, MethodError> {
        let text = text.trim();
        if text.eq_ignore_ascii_case("auto") {
            return Ok(Gamma0::Auto);
        }
        text.parse()
            .map(Gamma0::Given)
            .map_err(|_| MethodError::Gamma0Text {
                given: text.to_string(),
            })
    }
}

impl std::fmt::Display for Gamma0 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Gamma0::Auto => f.write_str("auto"),
            Gamma0::Given(g) => f.write_str(&num(*g)),
        }
    }
}
/// The ALM's default relative tolerance on the multiplier's change.
pub const DEFAULT_ALM_TOL: f64 = 1e-10;

/// A contact method with its parameters (the penalty parameter ε is the scenario's).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Method {
    /// The penalised problem (11) at ε > 0.
    Penalty,
    /// The exact constraint at the rule's points (the limit ε = 0).
    Exact,
    /// The augmented Lagrangian at the scenario's ε > 0, stopped when the multiplier's
    /// relative change falls below `tolerance` ∈ (0, 1).
    Alm {
        /// The relative tolerance on the multiplier's change, in (0, 1).
        tolerance: f64,
    },
    /// Nitsche's method with θ ∈ {1, 0, −1} and γ = γ₀·E/h.
    Nitsche {
        /// θ: 1 symmetric, 0 incomplete, −1 skew-symmetric.
        theta: i8,
        /// γ₀, a number or `auto`.
        gamma0: Gamma0,
    },
}

/// The names [`Method::parse`] accepts, in the order the lab cycles them.
pub const NAMES: [&str; 4] = ["penalty", "exact", "alm", "nitsche"];

impl Method {
    /// The name of the command line, the files and every output.
    pub fn name(self) -> &'static str {
        match self {
            Method::Penalty => "penalty",
            Method::Exact => "exact",
            Method::Alm { .. } => "alm",
            Method::Nitsche { .. } => "nitsche",
        }
    }

    /// A short label with the parameters, e.g. `alm (tol 1e-10)`, `nitsche (θ = 1, γ₀ = 100)`
    /// or `nitsche (θ = 1, γ₀ auto)`.
    pub fn label(self) -> String {
        MethodFields::from(self).label()
    }

    /// What the method needs, in a line: its stability condition and its parameter.
    pub fn needs(self) -> &'static str {
        match self {
            Method::Penalty => "needs ε > 0 (load error O(ε)); p̄ smooths p",
            Method::Exact => "needs inf-sup (a rule without kernel); no ε",
            Method::Alm { .. } => "needs ε > 0 (no ε error); p unique with inf-sup",
            Method::Nitsche { .. } => "needs γ₀ > γ₀* (θ = 1); no multiplier, no inf-sup",
        }
    }

    /// The method named `name` (any case), with `theta`, `gamma0` and `alm_tol` where it takes
    /// them (their defaults when None); a parameter given to a method that does not take it is
    /// refused, so that a typo is not silently ignored. Errors name the allowed values.
    ///
    /// # Errors
    ///
    /// An unknown name, a parameter the method does not take, or one out of its range
    /// ([`MethodError`]).
    pub fn parse(
        name: &str,
        theta: Option<f64>,
        gamma0: Option<Gamma0>,
        alm_tol: Option<f64>,
    ) -> Result<Method, MethodError> {
        let method = match name.trim().to_ascii_lowercase().as_str() {
            "penalty" => Method::Penalty,
            "exact" => Method::Exact,
            "alm" => Method::Alm {
                tolerance: DEFAULT_ALM_TOL,
            },
            "nitsche" => Method::Nitsche {
                theta: DEFAULT_THETA,
                gamma0: DEFAULT_GAMMA0,
            },
            _ => {
                return Err(MethodError::Name {
                    given: name.to_string(),
                    allowed: &NAMES,
                });
            }
        };
        method.with(theta, gamma0, alm_tol)
    }

    /// This method with the parameters that are given replaced, checked.
    ///
    /// # Errors
    ///
    /// A parameter the method does not take, or one out of its range ([`Method::check`]).
    pub fn with(
        self,
        theta: Option<f64>,
        gamma0: Option<Gamma0>,
        alm_tol: Option<f64>,
    ) -> Result<Method, MethodError> {
        let foreign = |key: &'static str, takes: &'static str| {
            Err(MethodError::NotTaken {
                key,
                method: self.name(),
                takes,
            })
        };
        let method = match self {
            Method::Nitsche {
                theta: t0,
                gamma0: g0,
            } => {
                if alm_tol.is_some() {
                    return foreign("alm_tol", "alm");
                }
                let theta = match theta {
                    Some(t) => check_theta(t)?,
                    None => t0,
                };
                Method::Nitsche {
                    theta,
                    gamma0: gamma0.unwrap_or(g0),
                }
            }
            Method::Alm { tolerance } => {
                if theta.is_some() {
                    return foreign("theta", "nitsche");
                }
                if gamma0.is_some() {
                    return foreign("gamma0", "nitsche");
                }
                Method::Alm {
                    tolerance: alm_tol.unwrap_or(tolerance),
                }
            }
            Method::Penalty | Method::Exact => {
                if theta.is_some() {
                    return foreign("theta", "nitsche");
                }
                if gamma0.is_some() {
                    return foreign("gamma0", "nitsche");
                }
                if alm_tol.is_some() {
                    return foreign("alm_tol", "alm");
                }
                self
            }
        };
        method.check()?;
        Ok(method)
    }

    /// The parameters' ranges: θ ∈ {1, 0, −1}, a given γ₀ in [`GAMMA0_RANGE`], the ALM's
    /// tolerance in (0, 1).
    ///
    /// # Errors
    ///
    /// The first parameter out of its range, with the allowed values.
    pub fn check(self) -> Result<(), MethodError> {
        match self {
            Method::Penalty | Method::Exact => Ok(()),
            Method::Alm { tolerance } => crate::check::open(
                tolerance,
                0.0,
                1.0,
                Allowed::Said(
                    "a relative tolerance 0 < tol < 1 (tolerances below about 1e-14 are not reachable in double precision and end as not converged)",
                ),
            )
            .map_err(MethodError::Tolerance),
            Method::Nitsche { theta, gamma0 } => {
                check_theta(f64::from(theta))?;
                let Gamma0::Given(gamma0) = gamma0 else {
                    return Ok(());
                };
                let (lo, hi) = GAMMA0_RANGE;
                crate::check::closed(
                    gamma0,
                    lo,
                    hi,
                    Allowed::Range {
                        what: "`auto` or γ₀",
                        lo,
                        hi,
                        note: " (γ = γ₀·E/h; γ₀ ≤ 1e8 keeps Nitsche's equivalent penalty εE/h = 1/γ₀ above round-off)",
                    },
                )
                .map_err(MethodError::Gamma0)
            }
        }
    }

    /// The method and the penalty parameter a solve uses when the scenario or the command line
    /// gives `method` (None: not named) and ε: ε = 0 with no method named is `exact` (riplab's
    /// convention before methods were named); `exact` reports ε = 0 whatever was given (it has
    /// no ε); `penalty` and `alm` need ε > 0.
    ///
    /// # Errors
    ///
    /// `penalty` or `alm` with ε = 0 ([`MethodError`]).
    pub fn resolve(method: Option<Method>, epsilon: f64) -> Result<(Method, f64), MethodError> {
        match (method, epsilon == 0.0) {
            (None, true) | (Some(Method::Exact), _) => Ok((Method::Exact, 0.0)),
            (None, false) => Ok((Method::Penalty, epsilon)),
            (Some(m @ (Method::Penalty | Method::Alm { .. })), true) => {
                Err(MethodError::NeedsEpsilon(m.name()))
            }
            (Some(m), _) => Ok((m, epsilon)),
        }
    }

    /// The next method in the lab's cycle (penalty → exact → alm → nitsche → penalty), each
    /// with its default parameters.
    pub fn next(self) -> Method {
        let i = NAMES.iter().position(|&n| n == self.name()).unwrap_or(0);
        Method::parse(NAMES[(i + 1) % NAMES.len()], None, None, None).expect("the names parse")
    }

    /// θ, when the method takes it.
    pub fn theta(self) -> Option<i8> {
        match self {
            Method::Nitsche { theta, .. } => Some(theta),
            _ => None,
        }
    }

    /// γ₀, when the method takes it.
    pub fn gamma0(self) -> Option<Gamma0> {
        match self {
            Method::Nitsche { gamma0, .. } => Some(gamma0),
            _ => None,
        }
    }

    /// The ALM's tolerance, when the method is the ALM.
    pub fn alm_tol(self) -> Option<f64> {
        match self {
            Method::Alm { tolerance } => Some(tolerance),
            _ => None,
        }
    }

    /// Whether the method uses the penalty parameter ε.
    pub fn uses_epsilon(self) -> bool {
        matches!(self, Method::Penalty | Method::Alm { .. })
    }
}

/// The method and its parameters as the JSON and CSV of every output carry them (flattened
/// into a row: `method`, `theta`, `gamma0`, `gamma0_auto`, `alm_tol`; null or empty where the
/// method has no such parameter). `gamma0` is the γ₀ a solve used, `auto`'s included
/// ([`MethodFields::used`]); null for `auto` before a solve chose it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MethodFields {
    /// The method's name: `penalty`, `exact`, `alm` or `nitsche` ([`Method::name`]).
    pub method: &'static str,
    /// Nitsche's θ ∈ {1, 0, −1}; None for the other methods.
    pub theta: Option<i8>,
    /// Nitsche's γ₀ as given or as a solve used it; None for the other methods and for `auto`
    /// before a solve.
    pub gamma0: Option<f64>,
    /// Whether γ₀ was chosen from the mesh ([`Gamma0::Auto`]).
    pub gamma0_auto: Option<bool>,
    /// The ALM's relative tolerance on the multiplier's change; None for the other methods.
    pub alm_tol: Option<f64>,
}

impl MethodFields {
    /// The fields of a solve by `method` that used Nitsche's γ₀ `gamma0` (None for the other
    /// methods).
    pub fn used(method: Method, gamma0: Option<f64>) -> Self {
        MethodFields {
            gamma0: gamma0.or(MethodFields::from(method).gamma0),
            ..MethodFields::from(method)
        }
    }

    /// The method as asked, which rows of a study share: `auto`'s γ₀, chosen on each mesh
    /// (γ₀* varies in its last digits from level to level), left out.
    pub fn setting(&self) -> MethodFields {
        if self.gamma0_auto == Some(true) {
            MethodFields {
                gamma0: None,
                ..*self
            }
        } else {
            *self
        }
    }

    /// The method with its parameters, e.g. `alm (tol 1e-10)`, `nitsche (θ = 1, γ₀ = 15.69
    /// auto)` ([`Method::label`]).
    pub fn label(&self) -> String {
        let auto = self.gamma0_auto == Some(true);
        match (self.theta, self.gamma0, self.alm_tol) {
            // `auto`'s choice to four significant digits (the JSON has every digit).
            (Some(theta), Some(gamma0), _) if auto && (1e-4..1e6).contains(&gamma0) => {
                let decimals = (3.0 - gamma0.log10().floor()).max(0.0) as usize;
                format!("{} (θ = {theta}, γ₀ = {gamma0:.decimals$} auto)", self.method)
            }
            (Some(theta), Some(gamma0), _) => {
                let auto = if auto { " auto" } else { "" };
                format!("{} (θ = {theta}, γ₀ = {}{auto})", self.method, num(gamma0))
            }
            (Some(theta), None, _) => format!("{} (θ = {theta}, γ₀ auto)", self.method),
            (_, _, Some(tol)) => format!("{} (tol {tol:e})", self.method),
            _ => self.method.to_string(),
        }
    }

    /// Whether ε means anything for this method (not for Nitsche, whose γ₀ takes its place):
    /// the tables print "—" for it otherwise.
    pub fn uses_epsilon(&self) -> bool {
        self.method != "nitsche"
    }

    /// ε as the tables print it, `width` wide: "—" when the method does not use it.
    pub fn epsilon_text(&self, epsilon: f64, width: usize) -> String {
        if self.uses_epsilon() {
            format!("{epsilon:>width$.1e}")
        } else {
            format!("{:>width$}", "—")
        }
    }
}

impl From<Method> for MethodFields {
    fn from(m: Method) -> Self {
        MethodFields {
            method: m.name(),
            theta: m.theta(),
            gamma0: match m.gamma0() {
                Some(Gamma0::Given(g)) => Some(g),
                _ => None,
            },
            gamma0_auto: m.gamma0().map(|g| g == Gamma0::Auto),
            alm_tol: m.alm_tol(),
        }
    }
}

/// θ ∈ {1, 0, −1}, or the error that names the allowed values.
fn check_theta(value: f64) -> Result<i8, MethodError> {
    THETAS
        .into_iter()
        .find(|&t| f64::from(t) == value)
        .ok_or(MethodError::Theta { theta: value })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_parses_and_is_its_own_name() {
        for name in NAMES {
            let m = Method::parse(&name.to_uppercase(), None, None, None).unwrap();
            assert_eq!(m.name(), name);
        }
        assert!(matches!(
            Method::parse("foo", None, None, None),
            Err(e @ MethodError::Name { .. }) if e.to_string() == "`foo` is not a method; allowed: penalty, exact, alm, nitsche"
        ));
    }

    #[test]
    fn parameters_are_checked_in_one_place() {
        let n = |t, g| Method::parse("nitsche", t, g, None);
        assert_eq!(
            n(Some(-1.0), Some(Gamma0::Given(5.0))).unwrap(),
            Method::Nitsche {
                theta: -1,
                gamma0: Gamma0::Given(5.0)
            }
        );
        assert_eq!(
            n(None, None).unwrap(),
            Method::Nitsche {
                theta: 1,
                gamma0: Gamma0::Auto
            }
        );
        for bad in [2.0, 0.5, -2.0, f64::NAN] {
            assert!(
                matches!(n(Some(bad), None), Err(MethodError::Theta { theta }) if theta.to_bits() == bad.to_bits())
            );
        }
        for bad in [-1.0, 0.0, 1e-9, 1e9, f64::INFINITY] {
            assert!(
                matches!(n(None, Some(Gamma0::Given(bad))), Err(MethodError::Gamma0(_))),
                "{bad}"
            );
        }
        assert_eq!(Gamma0::parse(" AUTO "), Ok(Gamma0::Auto));
        assert_eq!(Gamma0::parse("1e3"), Ok(Gamma0::Given(1e3)));
        assert!(
            matches!(Gamma0::parse("automatic"), Err(MethodError::Gamma0Text { given }) if given == "automatic")
        );
        for bad in [0.0, 1.0, -1e-3, f64::NAN] {
            assert!(matches!(
                Method::parse("alm", None, None, Some(bad)),
                Err(MethodError::Tolerance(_))
            ));
        }
        assert!(matches!(
            Method::parse("alm", Some(1.0), None, None),
            Err(MethodError::NotTaken { key: "theta", .. })
        ));
        assert!(matches!(
            Method::parse("penalty", None, None, Some(1e-3)),
            Err(MethodError::NotTaken { key: "alm_tol", .. })
        ));
    }

    /// `auto` is said before a solve and its choice after, to four significant digits.
    #[test]
    fn labels_say_what_gamma0_is() {
        let auto = Method::parse("nitsche", None, None, None).unwrap();
        assert_eq!(auto.label(), "nitsche (θ = 1, γ₀ auto)");
        assert_eq!(
            MethodFields::used(auto, Some(15.690_123)).label(),
            "nitsche (θ = 1, γ₀ = 15.69 auto)"
        );
        assert_eq!(
            MethodFields::used(auto, Some(12_758.057)).label(),
            "nitsche (θ = 1, γ₀ = 12758 auto)"
        );
        let given = Method::parse("nitsche", Some(0.0), Some(Gamma0::Given(100.0)), None).unwrap();
        assert_eq!(given.label(), "nitsche (θ = 0, γ₀ = 100)");
        assert_eq!(MethodFields::used(given, Some(100.0)), MethodFields::from(given));
        let fields = MethodFields::used(auto, Some(2.5));
        assert_eq!((fields.gamma0, fields.gamma0_auto), (Some(2.5), Some(true)));
        // Two meshes' `auto` choices are one setting; a given γ₀ is part of it.
        assert_eq!(fields.setting(), MethodFields::used(auto, Some(2.6)).setting());
        assert_eq!(fields.setting().label(), "nitsche (θ = 1, γ₀ auto)");
        assert_ne!(
            MethodFields::from(given).setting(),
            MethodFields::from(given.with(None, Some(Gamma0::Given(99.0)), None).unwrap()).setting()
        );
        let penalty = MethodFields::from(Method::Penalty);
        assert_eq!((penalty.gamma0, penalty.gamma0_auto), (None, None));
    }

    #[test]
    fn epsilon_zero_is_exact() {
        assert_eq!(Method::resolve(None, 0.0), Ok((Method::Exact, 0.0)));
        assert_eq!(Method::resolve(None, 1e-6), Ok((Method::Penalty, 1e-6)));
        assert_eq!(
            Method::resolve(Some(Method::Exact), 1e-6),
            Ok((Method::Exact, 0.0))
        );
        assert_eq!(
            Method::resolve(Some(Method::Penalty), 0.0),
            Err(MethodError::NeedsEpsilon("penalty"))
        );
        let alm = Method::Alm { tolerance: 1e-9 };
        assert_eq!(Method::resolve(Some(alm), 1e-3), Ok((alm, 1e-3)));
    }

    #[test]
    fn the_cycle_visits_every_method() {
        let mut m = Method::Penalty;
        let mut seen = Vec::new();
        for _ in 0..4 {
            seen.push(m.name());
            m = m.next();
        }
        assert_eq!(seen, NAMES);
        assert_eq!(m, Method::Penalty);
    }
}
