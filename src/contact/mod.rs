//! Unilateral contact, every concept of it in one place (docs/design.md §2–§4, §10, §11): the
//! gap and the obstacles, the contact rules and their points, the methods that impose the
//! constraint (the reduced-integration penalty, the exact multipliers, the augmented
//! Lagrangian, [`nitsche`]) with their parameters and checks, the semismooth Newton they share,
//! the pressures, [`friction`] (the laws and their solve), the closed forms, and what a
//! contact solve on a [`crate::discretization::Discretization`] gives: a rule's coupling on the
//! mesh's trace ([`coupling`]), the [`solution`] and its [`warnings`]. It stands above the
//! discretisation, which knows nothing of contact, and below the scenario and the one solve
//! entry ([`crate::solve()`]), which chooses among its solvers.

#[doc(hidden)]
pub mod alm;
pub mod circle;
pub mod coupling;
pub mod distance;
pub mod friction;
pub mod gap;
pub mod half_plane;
pub mod hertz;
pub mod interface;
pub mod method;
pub mod mindlin;
pub mod newton;
#[doc(hidden)]
pub mod nitsche;
pub mod params;
#[doc(hidden)]
pub mod penalty;
pub mod pressure;
pub mod rounded_punch;
pub mod rule;
#[doc(hidden)]
pub mod signorini;
pub mod solution;
pub mod warnings;

pub use gap::{Obstacle, Outline};
pub use method::Method;
pub use params::ContactParams;
pub use pressure::{carried_forces, load, raw_pressure, smoothed_pressure};
pub use rule::{ContactPoints, Rule};
