//! The crate's error type.

use core::fmt;

/// Why a mechanism could not be built, solved or swept.
///
/// Lengths and gaps are carried as `f64` whatever the scalar type, so the error type is the same
/// for `f32` and `f64` mechanisms.
///
/// ```
/// use linkage_core::{Assembly, Error, FourBar};
/// let e = FourBar::new(20.0_f64, -1.0, 25.0, 25.0, (0.0, 0.0), Assembly::Open).unwrap_err();
/// assert_eq!(e, Error::InvalidLength { what: "crank", value: -1.0 });
/// assert_eq!(e.to_string(), "crank must be a positive finite length, got -1");
/// // A linkage that cannot close says where, and by how much (|AC| = 19 against 2 + 2).
/// let short = FourBar::new(20.0_f64, 1.0, 2.0, 2.0, (0.0, 0.0), Assembly::Open).unwrap();
/// match short.pose(0.0) {
///     Err(Error::CannotAssemble { joint: 3, gap }) => assert!((gap - 15.0).abs() < 1e-12),
///     r => panic!("{r:?}"),
/// }
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// A length that must be positive and finite is not (zero, negative, NaN or infinite).
    InvalidLength {
        /// Which length, e.g. `"crank"` or `"dyad r1"`.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A length that is positive but subnormal (below the scalar type's smallest normal number,
    /// `2.2e-308` in `f64`, `1.2e-38` in `f32`): it carries fewer significant bits than the
    /// type, and the solver's products and power-of-two scalings of it lose the rest, so such a
    /// linkage would construct but never assemble. Scale the linkage up.
    ///
    /// ```
    /// use linkage_core::{Assembly, Error, FourBar};
    /// let e = FourBar::new(2.0_f64, 1e-309, 2.0, 2.0, (0.0, 0.0), Assembly::Open).unwrap_err();
    /// assert_eq!(e, Error::SubnormalLength { what: "crank", value: 1e-309 });
    /// assert!(e.to_string().starts_with("crank = 1e-309 is subnormal"));
    /// ```
    SubnormalLength {
        /// Which length.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A coordinate, angle or other value that must be finite is not.
    NotFinite {
        /// Which value.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// The joint cannot be placed: the two circles (or the circle and the line) do not meet.
    CannotAssemble {
        /// Index of the joint that could not be placed.
        joint: usize,
        /// By how much the lengths miss closure (length units, > 0): the longest side exceeds
        /// the sum of the other two by this amount, or the line passes this far outside the
        /// circle.
        gap: f64,
    },
    /// The two joints a construction is built on coincide, so its position is undetermined.
    Coincident {
        /// Index of the joint whose construction is undetermined.
        joint: usize,
    },
    /// A joint that is not a slider was given where a slider's joint is needed (e.g. for its
    /// line's direction, [`crate::Mechanism::line_directions`]).
    NotASlider {
        /// The joint given.
        joint: usize,
    },
    /// A construction refers to a joint that is not (yet) defined.
    UnknownJoint {
        /// Index of the construction being added.
        joint: usize,
        /// The index it referred to.
        refers_to: usize,
    },
    /// The mechanism's fixed capacity is full.
    CapacityExceeded {
        /// The capacity `N`.
        capacity: usize,
    },
    /// An output slice has the wrong length.
    BufferLength {
        /// Which buffer.
        what: &'static str,
        /// The length needed.
        expected: usize,
        /// The length given.
        got: usize,
    },
    /// The mechanism has no crank, so there is nothing to sweep.
    NoDriver,
    /// The mechanism has more than one crank; a sweep drives exactly one.
    SecondDriver {
        /// Index of the second crank.
        joint: usize,
    },
    /// A sweep that keeps one assembly would cross a flat position of a change-point linkage,
    /// where its two branches meet and the motion continues on the other orientation.
    ToggleOnPath {
        /// The crank angle (radians) of the first flat position on the path.
        angle: f64,
    },
    /// A result exists but is too large or too small for the floating-point type (it would
    /// overflow to infinity or underflow to zero), so no value is returned rather than a wrong one.
    NotRepresentable {
        /// Which result.
        what: &'static str,
    },
    /// A crank-speed schedule cannot hold the foot speed asked for: `why` says what fails,
    /// `figure` names the figure that shows it, `value` and `unit` give it, `hint` says what to
    /// change (may be empty).
    ScheduleInfeasible {
        /// What fails.
        why: &'static str,
        /// The figure that shows it.
        figure: &'static str,
        /// Its value.
        value: f64,
        /// Its unit.
        unit: &'static str,
        /// What to change.
        hint: &'static str,
    },
    /// A count or index is so large that the arithmetic on it would overflow `usize`.
    CountOverflow {
        /// Which count.
        what: &'static str,
    },
    /// Fewer items than a synthesis needs (e.g. two poses for a three-pose problem).
    TooFew {
        /// What was counted.
        what: &'static str,
        /// The least number needed.
        needed: usize,
        /// The number given.
        got: usize,
    },
    /// Two precision positions (poses of a body, or input–output pairs of a function) are the
    /// same to rounding, so they set one condition instead of two.
    CoincidentPositions {
        /// Index of the first (0-based).
        first: usize,
        /// Index of the second (0-based).
        second: usize,
    },
    /// The synthesis is degenerate: the sought point is at infinity or not unique.
    Degenerate {
        /// What is degenerate and why.
        what: &'static str,
    },
    /// The precision positions admit no real solution.
    NoSolution {
        /// Which solution and why.
        what: &'static str,
    },
    /// A name that is none of the choices, e.g. an assembly other than `"open"` or `"crossed"`
    /// (see [`crate::Assembly`]'s `FromStr`). The name itself is not kept (the error type has
    /// no heap): a caller that has it adds it to the message.
    InvalidChoice {
        /// What was named, e.g. `"assembly"`.
        what: &'static str,
        /// The choices as a message lists them, e.g. `"'open' or 'crossed'"`.
        choices: &'static str,
    },
    /// A value that must be greater than a bound is not (e.g. a pantograph's scale, which must
    /// exceed 1).
    NotAbove {
        /// Which value.
        what: &'static str,
        /// The value given.
        value: f64,
        /// The bound it must exceed.
        min: f64,
    },
    /// A count or size above the most a computation takes.
    OutOfRange {
        /// Which count, e.g. `"table block"`.
        what: &'static str,
        /// The value given.
        value: usize,
        /// The most allowed.
        max: usize,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::InvalidLength { what, value } => {
                write!(
                    f,
                    "{what} must be a positive finite length, got {}",
                    Num(value)
                )
            }
            Error::SubnormalLength { what, value } => write!(
                f,
                "{what} = {} is subnormal (below the smallest normal float, 2.2e-308 in f64): \
                 too few significant bits for the solver, so the linkage could never be \
                 assembled; scale the linkage up",
                Num(value)
            ),
            Error::NotFinite { what, value } => {
                write!(f, "{what} must be finite, got {}", Num(value))
            }
            Error::CannotAssemble { joint, gap } => write!(
                f,
                "joint {joint} cannot be assembled: the lengths miss closure by {}",
                Sig3(gap)
            ),
            Error::Coincident { joint } => write!(
                f,
                "joint {joint} is undetermined: the joints it is built on coincide"
            ),
            Error::NotASlider { joint } => write!(f, "joint {joint} is not a slider"),
            Error::UnknownJoint { joint, refers_to } => write!(
                f,
                "construction {joint} refers to joint {refers_to}, which is not defined before it"
            ),
            Error::CapacityExceeded { capacity } => {
                write!(
                    f,
                    "the mechanism is full: it holds at most {capacity} joints"
                )
            }
            Error::BufferLength {
                what,
                expected,
                got,
            } => write!(f, "{what} must have length {expected}, got {got}"),
            Error::NoDriver => write!(f, "the mechanism has no crank to drive"),
            Error::SecondDriver { joint } => write!(
                f,
                "joint {joint} is a second crank; a mechanism is driven by exactly one"
            ),
            Error::ToggleOnPath { angle } => write!(
                f,
                "the linkage flattens at crank angle {angle} on the requested path, where its \
                 two assembly branches meet: a sweep on one fixed assembly would switch branch \
                 there (use sweep(), which tracks the branch through it)"
            ),
            Error::NotRepresentable { what } => write!(
                f,
                "{what} is too large or too small to represent as a floating-point number"
            ),
            Error::CountOverflow { what } => {
                write!(f, "{what} is too large: the count overflows")
            }
            Error::ScheduleInfeasible {
                why,
                figure,
                value,
                unit,
                hint,
            } => {
                write!(f, "{why} ({figure} {} {unit})", Sig3(value))?;
                if !hint.is_empty() {
                    write!(f, "; {hint}")?;
                }
                Ok(())
            }
            Error::TooFew { what, needed, got } => {
                write!(f, "needs at least {needed} {what}, got {got}")
            }
            Error::CoincidentPositions { first, second } => write!(
                f,
                "precision positions {first} and {second} coincide (to rounding): they set one \
                 condition, not two"
            ),
            Error::Degenerate { what } => write!(f, "degenerate synthesis: {what}"),
            Error::NoSolution { what } => write!(f, "no solution: {what}"),
            Error::InvalidChoice { what, choices } => write!(f, "{what} must be {choices}"),
            Error::NotAbove { what, value, min } => {
                write!(
                    f,
                    "{what} must be greater than {}, got {}",
                    Num(min),
                    Num(value)
                )
            }
            Error::OutOfRange { what, value, max } => {
                write!(f, "{what} must be at most {max}, got {value}")
            }
        }
    }
}

impl core::error::Error for Error {}

/// A value for a message: plain (`0.5`, `-3`) in the ordinary range, scientific (`1e308`,
/// `5e-324`) outside it, so extreme values do not print as hundreds of digits.
struct Num(f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || !a.is_finite() || (1e-4..1e16).contains(&a) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// A figure to three significant digits (the error messages' figures are for reading).
struct Sig3(f64);

impl fmt::Display for Sig3 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || !a.is_finite() {
            write!(f, "{}", self.0)
        } else if (1e-3..1e6).contains(&a) {
            // Decimals so that three significant digits show: 2 for [1, 10), 0 from 100 up.
            let mut decimals = 2usize;
            let mut top = 10.0;
            while a >= top && decimals > 0 {
                decimals -= 1;
                top *= 10.0;
            }
            let mut bottom = 1.0;
            while a < bottom {
                decimals += 1;
                bottom /= 10.0;
            }
            write!(f, "{:.*}", decimals, self.0)
        } else {
            write!(f, "{:.2e}", self.0)
        }
    }
}

/// Checks that `value` is a positive finite length, and a normal number
/// ([`Error::SubnormalLength`] otherwise).
pub(crate) fn check_length<T: nalgebra::RealField + Copy>(
    what: &'static str,
    value: T,
) -> Result<T, Error> {
    if value.is_finite() && value > T::zero() {
        if value < crate::numeric::scalar::min_normal::<T>() {
            return Err(Error::SubnormalLength {
                what,
                value: crate::numeric::scalar::to_f64(value),
            });
        }
        Ok(value)
    } else {
        Err(Error::InvalidLength {
            what,
            value: crate::numeric::scalar::to_f64(value),
        })
    }
}

/// Checks that `value` is finite.
pub(crate) fn check_finite<T: nalgebra::RealField + Copy>(
    what: &'static str,
    value: T,
) -> Result<T, Error> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NotFinite {
            what,
            value: crate::numeric::scalar::to_f64(value),
        })
    }
}

#[cfg(test)]
mod sig3_tests {
    use super::Sig3;
    extern crate std;
    use std::format;

    #[test]
    fn three_significant_digits() {
        let cases = [
            (-3.524_584, "-3.52"),
            (0.001_234_5, "0.00123"),
            (12.349, "12.3"),
            (999.4, "999"),
            (123_456.0, "123456"),
            (1.5e7, "1.50e7"),
            (2.5e-5, "2.50e-5"),
            (0.0, "0"),
        ];
        for (x, want) in cases {
            assert_eq!(format!("{}", Sig3(x)), want, "{x}");
        }
    }
}

#[cfg(test)]
mod message_tests {
    use super::Error;
    extern crate std;
    use std::string::ToString;

    #[test]
    fn a_bound_or_a_count_is_not_called_a_length() {
        // A new user's trial: a pantograph scale of 0.5 and a one-gear train were each "not a
        // positive finite length".
        let scale = crate::catalog::hoecken_pantograph(0.5_f64)
            .map(|_| ())
            .unwrap_err();
        assert_eq!(
            scale.to_string(),
            "pantograph scale must be greater than 1, got 0.5",
            "{scale:?}"
        );
        let gears = crate::GearTrain::simple(&[18]).unwrap_err();
        assert_eq!(
            gears.to_string(),
            "needs at least 2 gears in a simple gear train, got 1",
            "{gears:?}"
        );
        let teeth = crate::GearTrain::simple(&[18, 0]).unwrap_err();
        assert!(
            matches!(
                teeth,
                Error::TooFew {
                    needed: 1,
                    got: 0,
                    ..
                }
            ),
            "{teeth:?}"
        );
        let huge = crate::catalog::hoecken_pantograph(1e308_f64)
            .map(|_| ())
            .unwrap_err();
        assert!(matches!(huge, Error::NotRepresentable { .. }), "{huge:?}");
    }
}
