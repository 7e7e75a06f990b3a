//! Unilateral contact by the reduced-integration penalty method: the gap, the contact
//! rules, the penalty Newton solver and the pressures (docs/design.md §2–§4).

pub mod gap;
pub mod hertz;
pub mod nitsche;
pub mod penalty;
pub mod pressure;
pub mod rule;
pub mod signorini;

pub use gap::Obstacle;
pub use pressure::{load, raw_pressure, smoothed_pressure};
pub use rule::{ContactPoints, Rule};
