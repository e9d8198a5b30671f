//! Dimensionless rise laws and piecewise motion programs (cam and crank drives).

use nalgebra::RealField;

use crate::error::{check_finite, check_length, Error};
use crate::numeric::scalar::lit;

/// A rise law on `u ∈ [0, 1]`: displacement from 0 to 1 with its derivatives in `u`.
///
/// Formulas after Norton, "Cam Design and Manufacturing Handbook" / "Design of Machinery" ch. 8.
/// Peaks (in `u`): constant velocity `v = 1` (infinite acceleration at the ends); parabolic
/// `a = ±4`; simple harmonic `v = π/2`, `a = π²/2`; cycloidal `v = 2`, `a = 2π`; 3-4-5
/// `v = 15/8`, `a = 10/√3`; 4-5-6-7 `v = 35/16`, `a = 84/(5√5)`·…; modified trapezoid
/// `a ≈ 4.888`.
///
/// ```
/// use linkage_core::MotionLaw;
/// let law = MotionLaw::from_name("cycloidal").unwrap();
/// assert_eq!(law.name(), "cycloidal");
/// // Halfway at mid-rise with the peak velocity 2; no acceleration at either end.
/// let [s, v, _, _] = law.eval(0.5_f64);
/// assert!((s - 0.5).abs() < 1e-15 && (v - 2.0).abs() < 1e-15);
/// assert!(law.eval(0.0_f64)[2].abs() < 1e-14 && law.eval(1.0_f64)[2].abs() < 1e-14);
/// // `u` outside [0, 1] is clamped; an unknown name is `None`.
/// assert_eq!(law.eval(2.0_f64), law.eval(1.0));
/// assert_eq!(MotionLaw::from_name("sinusoid"), None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MotionLaw {
    /// `s = u`: velocity jumps at both ends.
    ConstantVelocity,
    /// Constant acceleration then constant deceleration (parabolic): acceleration jumps.
    ConstantAcceleration,
    /// `s = (1 − cos πu)/2`: acceleration jumps at the ends (to and from a dwell).
    SimpleHarmonic,
    /// `s = u − sin(2πu)/2π`: acceleration continuous, jerk jumps.
    Cycloidal,
    /// `s = 10u³ − 15u⁴ + 6u⁵`: acceleration continuous, jerk jumps.
    Polynomial345,
    /// `s = 35u⁴ − 84u⁵ + 70u⁶ − 20u⁷`: jerk continuous.
    Polynomial4567,
    /// Modified trapezoid: cycloidal blends (1/8 of the rise each) around constant
    /// acceleration and deceleration; acceleration continuous, jerk jumps.
    ModifiedTrapezoid,
}

/// Displacement, velocity, acceleration and jerk.
///
/// ```
/// use linkage_core::{Derivatives, MotionLaw};
/// let [s, v, a, j]: Derivatives<f64> = MotionLaw::ConstantVelocity.eval(0.25);
/// assert_eq!([s, v, a, j], [0.25, 1.0, 0.0, 0.0]);
/// ```
pub type Derivatives<T> = [T; 4];

/// One piece of the modified trapezoid's acceleration, `a = C(A sin kx + B cos kx + D)` with
/// `x = u − u0`.
const TRAPEZOID: [(f64, f64, f64, f64); 5] = [
    (0.0, 1.0, 0.0, 0.0),
    (0.125, 0.0, 0.0, 1.0),
    (0.375, 0.0, 1.0, 0.0),
    (0.625, 0.0, 0.0, -1.0),
    (0.875, 0.0, -1.0, 0.0),
];

impl MotionLaw {
    /// Every law, in the order above.
    pub const ALL: [MotionLaw; 7] = [
        MotionLaw::ConstantVelocity,
        MotionLaw::ConstantAcceleration,
        MotionLaw::SimpleHarmonic,
        MotionLaw::Cycloidal,
        MotionLaw::Polynomial345,
        MotionLaw::Polynomial4567,
        MotionLaw::ModifiedTrapezoid,
    ];

    /// The law's name as users write it.
    pub fn name(self) -> &'static str {
        match self {
            MotionLaw::ConstantVelocity => "constant-velocity",
            MotionLaw::ConstantAcceleration => "constant-acceleration",
            MotionLaw::SimpleHarmonic => "simple-harmonic",
            MotionLaw::Cycloidal => "cycloidal",
            MotionLaw::Polynomial345 => "3-4-5",
            MotionLaw::Polynomial4567 => "4-5-6-7",
            MotionLaw::ModifiedTrapezoid => "modified-trapezoid",
        }
    }

    /// The law named `name` (see [`MotionLaw::name`]).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|l| l.name() == name)
    }

    /// `[s, s', s'', s''']` at `u` (clamped to `[0, 1]`), derivatives with respect to `u`.
    pub fn eval<T: RealField + Copy>(self, u: T) -> Derivatives<T> {
        let u = u.max(T::zero()).min(T::one());
        let c = lit::<T>;
        let pi = T::pi();
        match self {
            MotionLaw::ConstantVelocity => [u, T::one(), T::zero(), T::zero()],
            MotionLaw::ConstantAcceleration => {
                if u < c(0.5) {
                    [c(2.0) * u * u, c(4.0) * u, c(4.0), T::zero()]
                } else {
                    let w = T::one() - u;
                    [T::one() - c(2.0) * w * w, c(4.0) * w, c(-4.0), T::zero()]
                }
            }
            MotionLaw::SimpleHarmonic => {
                let (s, co) = (pi * u).sin_cos();
                let h = c(0.5);
                [
                    h * (T::one() - co),
                    h * pi * s,
                    h * pi * pi * co,
                    -h * pi * pi * pi * s,
                ]
            }
            MotionLaw::Cycloidal => {
                let tp = T::two_pi();
                let (s, co) = (tp * u).sin_cos();
                [u - s / tp, T::one() - co, tp * s, tp * tp * co]
            }
            MotionLaw::Polynomial345 => {
                let (u2, u3) = (u * u, u * u * u);
                [
                    u3 * (c(10.0) - c(15.0) * u + c(6.0) * u2),
                    u2 * (c(30.0) - c(60.0) * u + c(30.0) * u2),
                    u * (c(60.0) - c(180.0) * u + c(120.0) * u2),
                    c(60.0) - c(360.0) * u + c(360.0) * u2,
                ]
            }
            MotionLaw::Polynomial4567 => {
                let (u2, u3) = (u * u, u * u * u);
                [
                    u2 * u2 * (c(35.0) - c(84.0) * u + c(70.0) * u2 - c(20.0) * u3),
                    u3 * (c(140.0) - c(420.0) * u + c(420.0) * u2 - c(140.0) * u3),
                    u2 * (c(420.0) - c(1680.0) * u + c(2100.0) * u2 - c(840.0) * u3),
                    u * (c(840.0) - c(5040.0) * u + c(8400.0) * u2 - c(4200.0) * u3),
                ]
            }
            MotionLaw::ModifiedTrapezoid => modified_trapezoid(u),
        }
    }
}

/// The modified trapezoid, integrated in closed form piece by piece (see [`TRAPEZOID`]) and
/// scaled so that `s(1) = 1` (which makes the peak acceleration `1/s₁ ≈ 4.888`).
fn modified_trapezoid<T: RealField + Copy>(u: T) -> Derivatives<T> {
    let k = lit::<T>(4.0) * T::pi();
    // Integrates one piece from its start over `x`, from `(v0, s0)` at unit scale.
    let piece = |(_, a, b, d): (f64, f64, f64, f64), x: T, v0: T, s0: T| -> Derivatives<T> {
        let (a, b, d) = (lit::<T>(a), lit::<T>(b), lit::<T>(d));
        let (sn, cs) = (k * x).sin_cos();
        let acc = a * sn + b * cs + d;
        let vel = v0 + a * (T::one() - cs) / k + b * sn / k + d * x;
        let disp = s0
            + v0 * x
            + a * (x / k - sn / (k * k))
            + b * (T::one() - cs) / (k * k)
            + d * x * x * lit::<T>(0.5);
        [disp, vel, acc, k * (a * cs - b * sn)]
    };
    // Walk the pieces at unit scale to find the piece of `u` and the total rise.
    let (mut v0, mut s0) = (T::zero(), T::zero());
    let mut here = None;
    for (i, p) in TRAPEZOID.iter().enumerate() {
        let start = lit::<T>(p.0);
        let end = TRAPEZOID.get(i + 1).map_or(T::one(), |q| lit::<T>(q.0));
        if here.is_none() && u <= end {
            here = Some(piece(*p, u - start, v0, s0));
        }
        let e = piece(*p, end - start, v0, s0);
        v0 = e[1];
        s0 = e[0];
    }
    let total = s0;
    let r = here.unwrap_or([total, T::zero(), T::zero(), T::zero()]);
    [r[0] / total, r[1] / total, r[2] / total, r[3] / total]
}

/// One segment of a motion program: over `duration`, the output moves by `rise` following
/// `law` (a dwell when `law` is `None` or `rise` is 0).
///
/// ```
/// use linkage_core::{MotionLaw, Segment};
/// // A simple-harmonic rise of 10 in 2 s: halfway at 1 s, at its peak speed (π/2)·10/2.
/// let seg = Segment::new(2.0_f64, 10.0, Some(MotionLaw::SimpleHarmonic)).unwrap();
/// let [y, v, _, _] = seg.eval(1.0);
/// assert!((y - 5.0).abs() < 1e-12 && (v - 2.5 * core::f64::consts::PI).abs() < 1e-12);
/// // A dwell has zero rates; a segment of no duration is refused.
/// assert_eq!(Segment::new(1.0_f64, 0.0, None).unwrap().eval(0.5), [0.0; 4]);
/// assert!(Segment::new(0.0_f64, 1.0, None).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment<T> {
    /// Length of the segment in the program's independent variable (time, or cam angle).
    pub duration: T,
    /// Change of the output over the segment (negative for a return).
    pub rise: T,
    /// The law, or `None` for a dwell.
    pub law: Option<MotionLaw>,
}

impl<T: RealField + Copy> Segment<T> {
    /// A segment; `duration` must be positive and `rise` finite.
    ///
    /// # Errors
    /// [`Error::InvalidLength`] / [`Error::NotFinite`].
    pub fn new(duration: T, rise: T, law: Option<MotionLaw>) -> Result<Self, Error> {
        Ok(Segment {
            duration: check_length("segment duration", duration)?,
            rise: check_finite("segment rise", rise)?,
            law,
        })
    }

    /// `[y, y', y'', y''']` relative to the segment's start value, at local time `t`.
    pub fn eval(&self, t: T) -> Derivatives<T> {
        let Some(law) = self.law else {
            return [T::zero(); 4];
        };
        let d = self.duration;
        let [s, v, a, j] = law.eval(t / d);
        let l = self.rise;
        let (d2, d3) = (d * d, d * d * d);
        // Normal and finite: at least 4/max (just above the smallest normal number).
        let tiny = T::max_value().map_or(T::zero(), |m| lit::<T>(4.0) / m);
        let normal = |x: T| x.is_finite() && x >= tiny;
        if normal(d2) && normal(d3) {
            [l * s, l * v / d, l * a / d2, l * j / d3]
        } else {
            // d² or d³ underflows or overflows: divide one factor at a time, so a zero
            // derivative stays zero and a large one is infinite only if it exceeds the maximum.
            [l * s, l * v / d, l * a / d / d, l * j / d / d / d]
        }
    }
}

/// A piecewise motion program: an initial value and segments in sequence, repeating with
/// period the sum of the durations (the output advancing by the sum of the rises per period).
///
/// ```
/// use linkage_core::{MotionLaw, Program, Segment};
/// // Rise 1 in 1 s, dwell 1 s, return in 1 s: period 3 s, no net advance.
/// let segments = [
///     Segment::new(1.0_f64, 1.0, Some(MotionLaw::Cycloidal)).unwrap(),
///     Segment::new(1.0, 0.0, None).unwrap(),
///     Segment::new(1.0, -1.0, Some(MotionLaw::Cycloidal)).unwrap(),
/// ];
/// let prog = Program { start: 0.0, segments: &segments };
/// assert_eq!((prog.period(), prog.advance()), (3.0, 0.0));
/// assert_eq!(prog.eval(1.5)[0], 1.0); // on the dwell
/// assert_eq!(prog.eval(4.5), prog.eval(1.5)); // one period later
/// // An empty program stays at its start; a non-finite time is NaN.
/// assert_eq!(Program::<f64> { start: 2.0, segments: &[] }.eval(1.0), [2.0, 0.0, 0.0, 0.0]);
/// assert!(prog.eval(f64::NAN)[0].is_nan());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Program<'a, T> {
    /// Output at the program's start.
    pub start: T,
    /// The segments, in order.
    pub segments: &'a [Segment<T>],
}

/// A jump of a derivative at a join of a motion program.
///
/// ```
/// use linkage_core::{Discontinuity, MotionLaw, Program, Segment};
/// // A constant-velocity rise into a dwell: the velocity drops by 1 at the join, and jumps back
/// // up where the dwell wraps round to the next rise.
/// let segments = [
///     Segment::new(1.0_f64, 1.0, Some(MotionLaw::ConstantVelocity)).unwrap(),
///     Segment::new(1.0, 0.0, None).unwrap(),
/// ];
/// let prog = Program { start: 0.0, segments: &segments };
/// let mut out = [Discontinuity { after: 0, order: 0, jump: 0.0 }; 4];
/// assert_eq!(prog.discontinuities(1e-9, &mut out), 2);
/// assert_eq!(out[0], Discontinuity { after: 0, order: 1, jump: 1.0 });
/// assert_eq!(out[1], Discontinuity { after: 1, order: 1, jump: -1.0 });
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Discontinuity<T> {
    /// Index of the segment that ends at the join (the last one for the wrap-around join).
    pub after: usize,
    /// Which derivative jumps: 1 velocity, 2 acceleration, 3 jerk.
    pub order: usize,
    /// Value before the join minus value after it.
    pub jump: T,
}

impl<T: RealField + Copy> Program<'_, T> {
    /// Duration of one period.
    pub fn period(&self) -> T {
        self.segments
            .iter()
            .fold(T::zero(), |acc, s| acc + s.duration)
    }

    /// Output change per period.
    pub fn advance(&self) -> T {
        self.segments.iter().fold(T::zero(), |acc, s| acc + s.rise)
    }

    /// `[y, y', y'', y''']` at `t`; the program repeats with its period. Zero rates for an
    /// empty program; NaN for a non-finite `t`.
    ///
    /// When the durations add up to more than the float maximum (the period overflows), `t` is
    /// placed by walking the segments forward from the start (`t ≥ 0`) or back from the end of
    /// the previous period (`t < 0`), so the value is still the one at `t`, not a wrap-around.
    pub fn eval(&self, t: T) -> Derivatives<T> {
        let period = self.period();
        let Some(last) = self.segments.len().checked_sub(1) else {
            return [self.start, T::zero(), T::zero(), T::zero()];
        };
        // (a NaN period, from unvalidated public fields, returns here too)
        if period.partial_cmp(&T::zero()) != Some(core::cmp::Ordering::Greater) {
            return [self.start, T::zero(), T::zero(), T::zero()];
        }
        if !t.is_finite() {
            return [crate::numeric::scalar::nan::<T>(); 4];
        }
        if !period.is_finite() && t < T::zero() {
            // In the previous period, `-t` before its end: walk back from the last segment.
            let mut back = -t;
            let mut end = self.start;
            for seg in self.segments.iter().rev() {
                if back <= seg.duration {
                    let [y, v, a, j] = seg.eval(seg.duration - back);
                    return [end - seg.rise + y, v, a, j];
                }
                back -= seg.duration;
                end -= seg.rise;
            }
            // Not reached for finite `t`: the durations add up to more than `|t|`.
            return [end, T::zero(), T::zero(), T::zero()];
        }
        let (cycles, mut local) = if period.is_finite() {
            // `%` is exact (fmod): the time within the period is right however large `t` is.
            let mut local = t % period;
            if local < T::zero() {
                local += period;
            }
            (((t - local) / period).round(), local.min(period))
        } else {
            (T::zero(), t)
        };
        let mut base = if cycles == T::zero() {
            self.start
        } else {
            self.start + cycles * self.advance()
        };
        for (i, seg) in self.segments.iter().enumerate() {
            if local <= seg.duration || i == last {
                let [y, v, a, j] = seg.eval(local.min(seg.duration));
                return [base + y, v, a, j];
            }
            local -= seg.duration;
            base += seg.rise;
        }
        // Not reached: the loop returns at the last segment (`i == last`), and there is one.
        [base, T::zero(), T::zero(), T::zero()]
    }

    /// Jumps of velocity, acceleration and jerk larger than `tol` at the joins, including the
    /// wrap from the last segment to the first, written into `out`; returns how many were found
    /// (those beyond `out.len()` are counted but not stored).
    pub fn discontinuities(&self, tol: T, out: &mut [Discontinuity<T>]) -> usize {
        let n = self.segments.len();
        let mut found = 0;
        for i in 0..n {
            let (a, b) = (&self.segments[i], &self.segments[(i + 1) % n]);
            let end = a.eval(a.duration);
            let start = b.eval(T::zero());
            for order in 1..4 {
                let jump = end[order] - start[order];
                if jump.abs() > tol {
                    if let Some(slot) = out.get_mut(found) {
                        *slot = Discontinuity {
                            after: i,
                            order,
                            jump,
                        };
                    }
                    found += 1;
                }
            }
        }
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fd(law: MotionLaw, u: f64, order: usize) -> f64 {
        let h = 1e-5;
        (law.eval(u + h)[order] - law.eval(u - h)[order]) / (2.0 * h)
    }

    #[test]
    fn boundary_values_and_derivatives_are_consistent() {
        for law in MotionLaw::ALL {
            let [s0, ..] = law.eval(0.0_f64);
            let [s1, ..] = law.eval(1.0_f64);
            assert!(
                s0.abs() < 1e-15 && (s1 - 1.0).abs() < 1e-12,
                "{}",
                law.name()
            );
            for k in 1..40 {
                let u = k as f64 / 40.0 + 0.003;
                for order in 0..3 {
                    let d = fd(law, u, order);
                    let want = law.eval(u)[order + 1];
                    assert!(
                        (d - want).abs() < 1e-5 * (1.0 + want.abs()),
                        "{} u {u} order {order}",
                        law.name()
                    );
                }
            }
        }
    }

    /// Textbook peaks (Norton): cycloidal a = 2π, simple harmonic v = π/2, 3-4-5 v = 15/8,
    /// parabolic a = 4, modified trapezoid a = 4.8881.
    #[test]
    fn peaks_match_textbook_values() {
        let peak = |law: MotionLaw, order: usize| {
            (0..=100_000)
                .map(|k| law.eval(k as f64 / 100_000.0)[order].abs())
                .fold(0.0, f64::max)
        };
        for (law, order, want, tol) in [
            (MotionLaw::Cycloidal, 2, core::f64::consts::TAU, 1e-9),
            (MotionLaw::Cycloidal, 1, 2.0, 1e-9),
            (
                MotionLaw::SimpleHarmonic,
                1,
                core::f64::consts::FRAC_PI_2,
                1e-9,
            ),
            (MotionLaw::Polynomial345, 1, 1.875, 1e-9),
            (MotionLaw::Polynomial345, 2, 10.0 / 3f64.sqrt(), 1e-6),
            (MotionLaw::Polynomial4567, 1, 2.1875, 1e-9),
            (MotionLaw::ConstantAcceleration, 2, 4.0, 1e-12),
            (MotionLaw::ModifiedTrapezoid, 2, 4.8881, 1e-4),
        ] {
            let got = peak(law, order);
            assert!(
                (got - want).abs() < tol,
                "{}: peak of derivative {order} is {got}, want {want}",
                law.name()
            );
        }
    }

    /// The first source's drive: 91° → 271° over 1 s by 3-4-5, then 271° → 451° over the next
    /// second; peak crank speed 180°·15/8 = 337.5°/s; smooth at the joins up to acceleration.
    #[test]
    fn thesis_one_drive_program() {
        let seg = Segment::new(1.0_f64, 180.0, Some(MotionLaw::Polynomial345)).unwrap();
        let segs = [seg, seg];
        let p = Program {
            start: 91.0,
            segments: &segs,
        };
        for (t, order, want, tol) in [
            (0.0, 0, 91.0, 1e-12),
            (1.0, 0, 271.0, 1e-12),
            (2.0, 0, 451.0, 1e-12),
            (0.5, 1, 337.5, 1e-12),
            (2.5, 0, 451.0 + 90.0, 1e-9), // one period on
        ] {
            let got = p.eval(t)[order];
            assert!(
                (got - want).abs() < tol,
                "derivative {order} at t = {t} is {got}, want {want}"
            );
        }
        let mut out = [Discontinuity {
            after: 0,
            order: 0,
            jump: 0.0,
        }; 4];
        let n = p.discontinuities(1e-9, &mut out);
        // Velocity and acceleration are continuous (zero at both ends); only jerk jumps (60 → 60
        // is no jump either: s''' is 60 at both ends, so the 3-4-5 chain is C³ here).
        assert_eq!(n, 0, "{:?}", &out[..n.min(4)]);
        // Rise–dwell with simple harmonic: acceleration jumps from −π²/2·L/β² to 0.
        let rise = Segment::new(1.0_f64, 2.0, Some(MotionLaw::SimpleHarmonic)).unwrap();
        let dwell = Segment::new(0.5, 0.0, None).unwrap();
        let back = Segment::new(1.0, -2.0, Some(MotionLaw::SimpleHarmonic)).unwrap();
        let segs = [rise, dwell, back, dwell];
        let q = Program {
            start: 0.0,
            segments: &segs,
        };
        let n = q.discontinuities(1e-9, &mut out);
        assert!(
            n >= 4 && out.iter().take(n.min(4)).all(|d| d.order >= 2),
            "rise-dwell-return-dwell: {n} discontinuities, want at least 4 of order ≥ 2: {:?}",
            &out[..n.min(4)]
        );
    }
}
