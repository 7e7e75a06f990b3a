//! Unilateral contact: the gap, the contact rules, the methods that impose the constraint
//! (the reduced-integration penalty, the exact multipliers, the augmented Lagrangian, Nitsche) and the
//! pressures (docs/design.md §2–§4, §10).

#[doc(hidden)]
pub mod alm;
pub mod circle;
pub mod coupling;
pub mod distance;
pub mod friction;
pub mod gap;
pub mod half_plane;
pub mod hertz;
pub mod method;
pub mod mindlin;
pub mod newton;
pub mod params;
#[doc(hidden)]
pub mod penalty;
pub mod pressure;
pub mod rounded_punch;
pub mod rule;
#[doc(hidden)]
pub mod signorini;
pub mod warnings;

pub use gap::{Obstacle, Outline};
pub use method::Method;
pub use params::ContactParams;
pub use pressure::{carried_forces, load, raw_pressure, smoothed_pressure};
pub use rule::{ContactPoints, Rule};
