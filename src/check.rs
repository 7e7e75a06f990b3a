//! Checks of single values against their allowed ranges (docs/design.md §1, "Ranges"), shared
//! by the scenario file ([`crate::input`]), the tour file, the command-line overrides and the
//! library's own checks of a solve's parameters. A leaf: it knows no scenario and no solver.

use thiserror::Error;

use crate::mesh::MAX_LEVEL;
use crate::text::num;

/// The largest and smallest magnitude of a length (body sizes, radii, coordinates): a
/// scenario's units must put its lengths within 1e-6 to 1e6, so that the stiffness, the
/// gaps and the forces stay far from the limits of double precision.
pub const LENGTH: (f64, f64) = (1e-6, 1e6);
/// The range of Young's modulus E (any units).
pub const YOUNG: (f64, f64) = (1e-6, 1e12);
/// The largest aspect ratio of a level-0 cell: beyond it the stiffness of a cell is lost
/// to round-off (Q1's entries scale with hx/hy and hy/hx).
pub const ASPECT: f64 = 1e4;
/// The largest level-0 grid in either direction.
pub const MAX_CELLS_0: i64 = 4096;

/// A value outside its allowed range; the message says what is allowed.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum CheckError {
    /// NaN or ±∞ where a finite number in `allowed` is needed.
    #[error("{} is not a finite number; allowed: {allowed}", num(*value))]
    NotFinite {
        /// The value given.
        value: f64,
        /// What is allowed.
        allowed: Allowed,
    },
    /// A finite number outside `allowed`.
    #[error("{} is out of range; allowed: {allowed}", num(*value))]
    OutOfRange {
        /// The value given.
        value: f64,
        /// What is allowed.
        allowed: Allowed,
    },
    /// An integer outside lo..=hi.
    #[error("{value} is out of range; allowed: {lo} to {hi}")]
    Integer {
        /// The value given.
        value: i64,
        /// The smallest allowed.
        lo: i64,
        /// The largest allowed.
        hi: i64,
    },
    /// ε > 0 outside the range of the mesh and the material ([`crate::material::epsilon_range`]).
    #[error(
        "ε = {} is out of range; allowed: 0 (the exact constraint) or {} to {} here (ε·E/h from {} to {}, so that the penalty's products stay finite)",
        num(*value),
        num(range.0),
        num(range.1),
        num(crate::material::KAPPA_RANGE.0),
        num(crate::material::KAPPA_RANGE.1)
    )]
    Epsilon {
        /// The ε given.
        value: f64,
        /// The allowed ε > 0 of this mesh and material, (smallest, largest).
        range: (f64, f64),
    },
    /// A polyline point that is not a pair [x, height].
    #[error("a point has {0} coordinates; allowed: [x, height]")]
    Point(usize),
}

/// What a [`CheckError`] allows.
#[derive(Clone, Copy, Debug, PartialEq, Error)]
pub enum Allowed {
    /// A range or a set said in words, e.g. "a finite number > 0".
    #[error("{0}")]
    Said(&'static str),
    /// `what` from `lo` to `hi`, then `note` (e.g. why the range).
    #[error("{what} from {} to {}{note}", num(*lo), num(*hi))]
    Range {
        /// What the value is, e.g. "a length".
        what: &'static str,
        /// The smallest allowed.
        lo: f64,
        /// The largest allowed.
        hi: f64,
        /// After the range: "" or " (why)".
        note: &'static str,
    },
    /// An indentation depth within ± the body's `height`.
    #[error("a depth between {} and {} (the body is {} high)", num(-height), num(*height), num(*height))]
    Depth {
        /// The body's height.
        height: f64,
    },
}

/// A finite number in (lo, hi) (open ends).
pub fn open(value: f64, lo: f64, hi: f64, allowed: Allowed) -> Result<(), CheckError> {
    if !value.is_finite() {
        Err(CheckError::NotFinite { value, allowed })
    } else if value > lo && value < hi {
        Ok(())
    } else {
        Err(CheckError::OutOfRange { value, allowed })
    }
}
/// A finite number in [lo, hi] (closed ends).
pub fn closed(value: f64, lo: f64, hi: f64, allowed: Allowed) -> Result<(), CheckError> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(())
    } else {
        open(value, f64::NAN, f64::NAN, allowed)
    }
}
/// A finite number > 0.
#[cfg(feature = "tui")]
pub fn positive(value: f64) -> Result<(), CheckError> {
    open(value, 0.0, f64::INFINITY, Allowed::Said("a finite number > 0"))
}
/// A finite number ≥ 0.
pub fn nonnegative(value: f64) -> Result<(), CheckError> {
    if value == 0.0 {
        Ok(())
    } else {
        open(value, 0.0, f64::INFINITY, Allowed::Said("a finite number ≥ 0"))
    }
}
/// A length: within [`LENGTH`].
pub fn length(value: f64) -> Result<(), CheckError> {
    let (lo, hi) = LENGTH;
    closed(value, lo, hi, range("a length", lo, hi))
}
/// [`Allowed::Range`] without a note.
fn range(what: &'static str, lo: f64, hi: f64) -> Allowed {
    Allowed::Range {
        what,
        lo,
        hi,
        note: "",
    }
}
/// A length that may be 0 (a punch's flat half-width).
pub fn length_or_zero(value: f64) -> Result<(), CheckError> {
    if value == 0.0 { Ok(()) } else { length(value) }
}
/// A coordinate or a signed offset: |value| at most [`LENGTH`]'s upper end.
pub fn coordinate(value: f64) -> Result<(), CheckError> {
    let hi = LENGTH.1;
    closed(value, -hi, hi, range("a finite number", -hi, hi))
}
/// Young's modulus: within [`YOUNG`].
pub fn young(value: f64) -> Result<(), CheckError> {
    let (lo, hi) = YOUNG;
    closed(value, lo, hi, range("a modulus", lo, hi))
}
/// The penalty parameter: ε > 0, or 0 for the exact constraint (its range depends on the
/// mesh and the material: see [`crate::material::epsilon_range`]).
pub fn epsilon(value: f64) -> Result<(), CheckError> {
    if value == 0.0 {
        Ok(())
    } else {
        open(
            value,
            0.0,
            f64::INFINITY,
            Allowed::Said("a finite number > 0, or 0 for the exact constraint"),
        )
    }
}
/// ε within `range` (from [`crate::material::epsilon_range`]), or 0.
pub fn epsilon_in(value: f64, range: (f64, f64)) -> Result<(), CheckError> {
    epsilon(value)?;
    if value == 0.0 || (range.0..=range.1).contains(&value) {
        Ok(())
    } else {
        Err(CheckError::Epsilon { value, range })
    }
}
/// The indentation depth: beyond the body's height it is meaningless (the obstacle would
/// pass through the clamped base).
pub fn depth(value: f64, height: f64) -> Result<(), CheckError> {
    open(value, -height, height, Allowed::Depth { height })
}
/// Poisson's ratio ν of an isotropic solid, short of incompressibility.
pub fn poisson(value: f64) -> Result<(), CheckError> {
    open(
        value,
        -1.0,
        0.5,
        Allowed::Said(
            "−1 < ν < 0.5 (ν = 0.5 is incompressible, which the displacement formulation cannot represent)",
        ),
    )
}
/// An integer in lo..=hi.
pub fn integer(value: i64, lo: i64, hi: i64) -> Result<(), CheckError> {
    if (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(CheckError::Integer { value, lo, hi })
    }
}
/// A mesh level: 0 to [`MAX_LEVEL`].
pub fn level(value: i64) -> Result<(), CheckError> {
    integer(value, 0, i64::from(MAX_LEVEL))
}
/// A point of a polyline: a pair [x, height] of coordinates.
pub fn point(value: &[f64]) -> Result<(), CheckError> {
    match value {
        [x, y] => coordinate(*x).and(coordinate(*y)),
        _ => Err(CheckError::Point(value.len())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The messages the files, the CLI and the tests quote, spelled out once by hand.
    #[test]
    fn messages_name_the_value_and_the_range() {
        assert_eq!(
            positive(f64::NAN).unwrap_err().to_string(),
            "NaN is not a finite number; allowed: a finite number > 0"
        );
        assert_eq!(
            level(9).unwrap_err().to_string(),
            "9 is out of range; allowed: 0 to 8"
        );
        assert_eq!(
            point(&[1.0]).unwrap_err().to_string(),
            "a point has 1 coordinates; allowed: [x, height]"
        );
        let one = Allowed::Said("one");
        assert_eq!(closed(1.0, 1.0, 1.0, one), Ok(()));
        assert!(matches!(
            closed(2.0, 1.0, 1.0, one),
            Err(CheckError::OutOfRange { value: 2.0, .. })
        ));
        assert_eq!(
            length(0.0),
            Err(CheckError::OutOfRange {
                value: 0.0,
                allowed: Allowed::Range {
                    what: "a length",
                    lo: 1e-6,
                    hi: 1e6,
                    note: ""
                }
            })
        );
        assert_eq!(
            length(0.0).unwrap_err().to_string(),
            "0 is out of range; allowed: a length from 1e-6 to 1e6"
        );
        assert_eq!(
            depth(3.0, 2.0).unwrap_err().to_string(),
            "3 is out of range; allowed: a depth between -2 and 2 (the body is 2 high)"
        );
        assert!(matches!(
            epsilon_in(1.0, (1e-3, 1e-2)),
            Err(CheckError::Epsilon { value: 1.0, .. })
        ));
        assert_eq!(epsilon_in(0.0, (1e-3, 1e-2)), Ok(()));
    }
}
