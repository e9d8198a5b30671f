//! The offset slider-crank with a coupler point: crank `O A`, coupler (connecting rod) `A B`,
//! slider `B` on a fixed line, and a point `P` rigid with the coupler.
//!
//! # Geometry
//! The line has the direction `u = (cos γ, sin γ)` and passes at the signed distance `e` (the
//! offset) to the left of the crank pivot `O`: through `G = O + e·u⊥`. In the line's frame
//! (origin `O`, `x` along `u`) and with `φ = θ − γ` the crank angle from the line,
//! `A = r (cos φ, sin φ)`, the height of `A` above the line is `d = r sin φ − e`, and
//! `B = (r cos φ ± √(l² − d²), e)`: the textbook position of an offset slider-crank's slider,
//! `x = r cos φ + √(l² − (r sin φ − e)²)`, with `+` for [`Reach::Ahead`] (along `u` from the
//! foot of `A`) and `−` for [`Reach::Behind`]. `P = A + along·ê + left·ê⊥` with
//! `ê = (B − A)/l`.
//!
//! The two reaches are one linkage seen along opposite directions: `Behind` with `(γ, e)` is
//! `Ahead` with `(γ + π, −e)`, the same line, pivot and point for every crank angle.
//!
//! # Range of the crank
//! The rod reaches the line while `|d| ≤ l`, i.e. `sin φ ∈ [a, b]` with `a = (e − l)/r`,
//! `b = (e + l)/r`: the crank turns fully iff `|e| + r ≤ l`; otherwise it rocks between the
//! positions where the rod is perpendicular to the line (`|d| = l`, the two reaches meet, a
//! toggle), in one interval or, when `−1 < a < b < 1`, in two mirror-image intervals (two
//! separate circuits). At `|e| + r = l` the rod is perpendicular to the line at one crank angle
//! of a full turn: the reaches meet there (a change point, [`SliderCrank::is_change_point`]).

use nalgebra::RealField;

use crate::constructions::slider::{LineDirection, Reach};
use crate::error::{check_finite, check_length, Error};
use crate::linkages::fourbar::InputRange;
use crate::mechanism::program::Mechanism;
use crate::numeric::scalar::{lit, perp, Vec2};

/// An offset slider-crank with a coupler point (see the module).
///
/// ```
/// use linkage_core::{InputRange, Reach, SliderCrank, Vec2};
/// // Crank 2, rod 5, the line 1 above O along +x, the point halfway along the rod.
/// let sc = SliderCrank::new(Vec2::zeros(), 0.0_f64, 1.0, 2.0, 5.0, (2.5, 0.0), Reach::Ahead)?;
/// assert_eq!(sc.input_range(), InputRange::Full); // |e| + r = 3 ≤ 5
/// let pose = sc.pose(0.0).unwrap();
/// // x = r cos θ + √(l² − (r sin θ − e)²) = 2 + √24, on the line y = 1.
/// assert!((pose.b - Vec2::new(2.0 + 24.0_f64.sqrt(), 1.0)).norm() < 1e-15);
/// assert!((pose.coupler_point - (pose.a + pose.b) / 2.0).norm() < 1e-15);
/// // A rod shorter than crank + offset rocks the crank: here between the two positions where
/// // the rod stands perpendicular to the line.
/// let rocking = SliderCrank { coupler: 2.5, ..sc };
/// let InputRange::Between { lo, hi } = rocking.input_range() else { unreachable!() };
/// assert!((rocking.pose(lo).unwrap().transmission).abs() < 1e-7);
/// assert!(lo < hi && rocking.pose(0.5 * (lo + hi)).is_some());
/// # Ok::<(), linkage_core::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderCrank<T> {
    /// The crank pivot `O`.
    pub o: Vec2<T>,
    /// Direction of the slider's line (radians, counter-clockwise from `+x`).
    pub angle: T,
    /// Signed distance of the line from `O`, positive when the line passes to the left of `O`
    /// (looking along its direction).
    pub offset: T,
    /// Crank length `r`.
    pub crank: T,
    /// Coupler (connecting rod) length `l`, from `A` to `B`.
    pub coupler: T,
    /// Coupler point: distance along `A → B`.
    pub along: T,
    /// Coupler point: distance left of `A → B`.
    pub left: T,
    /// Which of the two slider positions; sweeps track it by continuity.
    pub reach: Reach,
}

/// A solved slider-crank position.
///
/// ```
/// use linkage_core::{Reach, SliderCrank, Vec2};
/// // Crank 1 at 90°, rod 3, on the x axis (no offset): B at x = √(3² − 1²).
/// let sc = SliderCrank::new(Vec2::zeros(), 0.0, 0.0, 1.0, 3.0, (1.0, 0.0), Reach::Ahead).unwrap();
/// let p = sc.pose(core::f64::consts::FRAC_PI_2).unwrap();
/// assert!((p.b - Vec2::new(8f64.sqrt(), 0.0)).norm() < 1e-12);
/// // The rod's angle from the line's normal: atan2(√8, 1).
/// assert!((p.transmission - 8f64.sqrt().atan2(1.0)).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderCrankPose<T> {
    /// Crank pin `A`.
    pub a: Vec2<T>,
    /// Slider `B`.
    pub b: Vec2<T>,
    /// Coupler point `P`.
    pub coupler_point: Vec2<T>,
    /// Angle between the rod and the normal to the line, `atan2(|half chord|, |d|)` in
    /// `[0, π/2]`: `π/2` with the rod along the line, `0` at a toggle (rod perpendicular to
    /// the line). The slider-crank's transmission angle folded to its distance from a toggle.
    pub transmission: T,
}

impl<T: RealField + Copy> SliderCrank<T> {
    /// Joint indices of [`SliderCrank::mechanism`]: crank pivot `O`.
    pub const O: usize = 0;
    /// Point `G` of the line nearest `O`.
    pub const G: usize = 1;
    /// Crank pin `A`.
    pub const A: usize = 2;
    /// Slider `B`.
    pub const B: usize = 3;
    /// Coupler point `P`.
    pub const P: usize = 4;

    /// A slider-crank with crank pivot `o`, line direction `angle`, line `offset`, crank and
    /// coupler lengths, coupler point `(along, left)` and `reach`.
    ///
    /// # Errors
    /// [`Error::InvalidLength`] for a crank or coupler that is not positive and finite,
    /// [`Error::SubnormalLength`] for a subnormal one;
    /// [`Error::NotFinite`] for any other number that is not finite.
    pub fn new(
        o: Vec2<T>,
        angle: T,
        offset: T,
        crank: T,
        coupler: T,
        point: (T, T),
        reach: Reach,
    ) -> Result<Self, Error> {
        for (what, v) in [
            ("crank pivot", o.x),
            ("crank pivot", o.y),
            ("line angle", angle),
            ("line offset", offset),
            ("coupler point", point.0),
            ("coupler point", point.1),
        ] {
            check_finite(what, v)?;
        }
        Ok(SliderCrank {
            o,
            angle,
            offset,
            crank: check_length("crank", crank)?,
            coupler: check_length("coupler", coupler)?,
            along: point.0,
            left: point.1,
            reach,
        })
    }

    /// The cognate: the other slider-crank whose coupler point draws the same curve.
    ///
    /// With `ζ = (along + i·left)/coupler` (so `P = A + ζ(B − A)`, complex numbers), the cognate
    /// keeps the crank pivot `O` and takes the slider to `B′ = O + ζ(B − O)`, on the line
    /// `O + ζ(L − O)`: direction `angle + arg ζ`, offset `|ζ|·offset`. Its crank `A′ = O + ζ(B − A)`
    /// has length `|ζ|·coupler = |AP|` and turns with the original's rod; its rod
    /// `B′ − A′ = ζ(A − O)` has length `|ζ|·crank`, and its coupler point is
    /// `crank·(cos arg ζ, −sin arg ζ)` (so `P = A′ + (B′ − A′)/ζ`). Crank and rod trade roles:
    /// the cognate of a crank-slider is a rocker-slider, and conversely when the crank keeps to
    /// one side of the line's normal through `O`.
    ///
    /// Its reach is where its slider is at the middle of the original's first input interval
    /// (ahead when `(A − O)·u > 0` there). A cognate whose crank rocks traces the whole curve
    /// over its circuit, which passes both reaches. For an original on reach behind the cognate
    /// is written with its line reversed (direction `+ π`, offset negated: the same linkage), so
    /// that its first input interval is the one the original's curve maps to.
    ///
    /// ```
    /// use linkage_core::{Reach, SliderCrank, Vec2};
    /// let sc =
    ///     SliderCrank::<f64>::new(Vec2::zeros(), 0.0, 6.0, 10.0, 32.0, (12.0, 9.0), Reach::Ahead)
    ///         .unwrap();
    /// let cog = sc.cognate().unwrap();
    /// // Crank |AP| = 15, rod 10·15/32, offset 6·15/32, the line turned by arg ζ = atan(9/12).
    /// assert!((cog.crank - 15.0).abs() < 1e-12 && (cog.coupler - 4.6875).abs() < 1e-12);
    /// assert!((cog.offset - 2.8125).abs() < 1e-12 && (cog.angle - 0.75f64.atan()).abs() < 1e-12);
    /// assert!((cog.along - 8.0).abs() < 1e-12 && (cog.left + 6.0).abs() < 1e-12);
    /// ```
    ///
    /// # Errors
    /// [`Error::Degenerate`] when the coupler point is at the crank pin `A` (the cognate's crank
    /// would have no length); as [`SliderCrank::new`] for numbers out of range.
    pub fn cognate(&self) -> Result<SliderCrank<T>, Error> {
        if self.along == T::zero() && self.left == T::zero() {
            return Err(Error::Degenerate {
                what: "the coupler point is at the crank pin A",
            });
        }
        // |ζ| and arg ζ without squaring the point's coordinates (no overflow at any scale).
        let ap = self.along.hypot(self.left);
        let rho = ap / self.coupler;
        let alpha = self.left.atan2(self.along);
        let (s, c) = alpha.sin_cos();
        // Which reach: the sign of (A − O)·u at the middle of the first input interval.
        let mid = match self.input_range() {
            InputRange::Full | InputRange::Never => self.angle,
            InputRange::Between { lo, hi } => (lo + hi) / lit(2.0),
            InputRange::TwoIntervals { first, .. } => (first.0 + first.1) / lit(2.0),
        };
        let ahead = (mid - self.angle).cos() >= T::zero();
        // The cognate's crank pin is ahead of `O` along its line where the original's rod points
        // ahead along its own: for an original on reach behind, the cognate is written with its
        // line reversed (the same linkage), so that its first input interval is the one the
        // original's curve maps to.
        let (turn, sign, ahead) = match self.reach {
            Reach::Ahead => (T::zero(), T::one(), ahead),
            Reach::Behind => (T::pi(), -T::one(), !ahead),
        };
        SliderCrank::new(
            self.o,
            self.angle + alpha + turn,
            sign * self.offset * rho,
            ap,
            self.crank * rho,
            (self.crank * c, -self.crank * s),
            if ahead { Reach::Ahead } else { Reach::Behind },
        )
    }

    /// The line's unit direction `u`.
    pub fn direction(&self) -> Vec2<T> {
        let (s, c) = self.angle.sin_cos();
        Vec2::new(c, s)
    }

    /// The point `G = O + e·u⊥` of the line nearest the crank pivot.
    pub fn line_point(&self) -> Vec2<T> {
        self.o + perp(self.direction()) * self.offset
    }

    /// `(a, b)`: the crank assembles while `sin φ ∈ [a, b]` (see the module).
    fn sine_bounds(&self) -> (T, T) {
        let (e, r, l) = (self.offset, self.crank, self.coupler);
        ((e - l) / r, (e + l) / r)
    }

    /// Whether the rod is perpendicular to the line at one crank angle of a full turn
    /// (`|e| + r = l`): the two reaches meet there and a sweep may pass to the other.
    pub fn is_change_point(&self) -> bool {
        let (a, b) = self.sine_bounds();
        a == -T::one() || b == T::one()
    }

    /// The crank angles (absolute, radians) at which the linkage assembles, as
    /// [`InputRange`]: `Full` iff `|e| + r ≤ l`; otherwise one interval or two mirror-image
    /// intervals (`first` with the crank pin ahead of `O` along the line, `cos φ > 0`), each
    /// between toggle positions; `Never` when the line is out of the rod's reach
    /// (`|e| ≥ r + l`: at most one pose).
    pub fn input_range(&self) -> InputRange<T> {
        match self.relative_range() {
            RelativeRange::Never => InputRange::Never,
            RelativeRange::Full => InputRange::Full,
            RelativeRange::One(lim) => InputRange::Between {
                lo: self.angle + lim.lo,
                hi: self.angle + lim.hi,
            },
            RelativeRange::Two(first, second) => InputRange::TwoIntervals {
                first: (self.angle + first.lo, self.angle + first.hi),
                second: (self.angle + second.lo, self.angle + second.hi),
            },
        }
    }

    /// [`SliderCrank::input_range`] in angles from the line, with the side of the line the
    /// crank pin is on at each limit.
    pub(crate) fn relative_range(&self) -> RelativeRange<T> {
        let (a, b) = self.sine_bounds();
        let one = T::one();
        let pi = T::pi();
        if a >= one || b <= -one {
            return RelativeRange::Never;
        }
        match (a <= -one, b >= one) {
            (true, true) => RelativeRange::Full,
            // sin φ ≤ b: below the top of the circle, limits where d = +l.
            (true, false) => RelativeRange::One(Limits {
                lo: pi - b.asin(),
                hi: T::two_pi() + b.asin(),
                above: (true, true),
            }),
            // sin φ ≥ a: limits where d = −l.
            (false, true) => RelativeRange::One(Limits {
                lo: a.asin(),
                hi: pi - a.asin(),
                above: (false, false),
            }),
            (false, false) => RelativeRange::Two(
                Limits {
                    lo: a.asin(),
                    hi: b.asin(),
                    above: (false, true),
                },
                Limits {
                    lo: pi - b.asin(),
                    hi: pi - a.asin(),
                    above: (true, false),
                },
            ),
        }
    }

    /// The position at crank angle `theta` on the declared reach; `None` where the rod cannot
    /// reach the line.
    pub fn pose(&self, theta: T) -> Option<SliderCrankPose<T>> {
        self.pose_from_line(theta - self.angle)
    }

    /// [`SliderCrank::pose`] at the crank angle `phi` from the line.
    pub(crate) fn pose_from_line(&self, phi: T) -> Option<SliderCrankPose<T>> {
        let d = self.crank * phi.sin() - self.offset;
        let l = self.coupler;
        // (l − d)(l + d) without the cancellation of l² − d², each factor rooted apart so
        // that the product cannot overflow.
        let (lo, hi) = (l - d, l + d);
        let tol = crate::numeric::scalar::eps::<T>() * lit::<T>(8.0) * (l + d.abs());
        if lo < -tol || hi < -tol {
            return None;
        }
        let half = lo.max(T::zero()).sqrt() * hi.max(T::zero()).sqrt();
        Some(self.place(phi, self.reach.sign::<T>() * half, d))
    }

    /// The joints in the world frame from `φ`, the signed half chord `h` (`B` at `h` along
    /// `u` from the foot of `A`) and the height `d` of `A` above the line.
    pub(crate) fn place(&self, phi: T, h: T, d: T) -> SliderCrankPose<T> {
        let (s, c) = phi.sin_cos();
        let a = Vec2::new(self.crank * c, self.crank * s);
        let b = Vec2::new(a.x + h, self.offset);
        let e = (b - a) / self.coupler;
        let p = a + e * self.along + perp(e) * self.left;
        let u = self.direction();
        let world = |q: Vec2<T>| self.o + u * q.x + perp(u) * q.y;
        SliderCrankPose {
            a: world(a),
            b: world(b),
            coupler_point: world(p),
            transmission: h.abs().atan2(d.abs()),
        }
    }

    /// The linkage as a mechanism: joints `O`, `G`, `A` (the crank, driven at the absolute
    /// angle `θ`), `B` (a slider through `G` along the line, on the declared reach) and `P`.
    pub fn mechanism(&self) -> Mechanism<T, 5> {
        let mut m = Mechanism::new();
        let line = LineDirection::Fixed(self.direction());
        let steps = [
            m.fixed(self.o),
            m.fixed(self.line_point()),
            m.crank(Self::O, self.crank, T::zero()),
            m.slider(Self::A, self.coupler, Self::G, line, self.reach),
            m.point(Self::A, Self::B, self.along, self.left),
        ];
        // As `FourBar::mechanism`: a push fails only for public fields set to invalid numbers
        // after construction; the program is then short and every solve of it reports
        // `Error::BufferLength` (no panic, no wrong value).
        let _ = steps;
        m
    }
}

/// A crank interval in angles from the line, and on which side of the line the crank pin is
/// at each limit (`true`: `d = +l`, above).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Limits<T> {
    pub(crate) lo: T,
    pub(crate) hi: T,
    pub(crate) above: (bool, bool),
}

/// [`InputRange`] in angles from the line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum RelativeRange<T> {
    Never,
    Full,
    One(Limits<T>),
    Two(Limits<T>, Limits<T>),
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sc(e: f64, r: f64, l: f64, reach: Reach) -> SliderCrank<f64> {
        SliderCrank::new(Vec2::zeros(), 0.0, e, r, l, (0.3 * l, 0.2 * l), reach).unwrap()
    }

    /// The textbook slider position `x = r cos θ + √(l² − (r sin θ − e)²)` (and `−` for the
    /// other reach), the rod length kept, and the mechanism's pose the same point.
    #[test]
    fn pose_is_the_textbook_position() {
        for &(e, r, l) in &[
            (0.0, 2.0, 5.0),
            (1.0, 2.0, 5.0),
            (-1.5, 1.0, 3.0),
            (0.7, 3.0, 2.5),
        ] {
            for reach in [Reach::Ahead, Reach::Behind] {
                let s = sc(e, r, l, reach);
                let m = s.mechanism();
                let mut joints = [Vec2::zeros(); 5];
                for k in 0..64 {
                    let th = 0.1 + k as f64 * 0.098;
                    let root2 = l * l - (r * th.sin() - e).powi(2);
                    let Some(p) = s.pose(th) else {
                        assert!(root2 < 1e-12, "{e} {r} {l} {th}: no pose, {root2}");
                        continue;
                    };
                    let x = r * th.cos() + reach.sign::<f64>() * root2.sqrt();
                    assert!(
                        (p.b.x - x).abs() < 1e-13 && (p.b.y - e).abs() < 1e-15,
                        "{p:?}"
                    );
                    assert!(
                        ((p.b - p.a).norm() - l).abs() < 1e-13,
                        "{e} {r} {l} {th}: rod length {} (want {l})",
                        (p.b - p.a).norm()
                    );
                    m.pose(th, &mut joints).unwrap();
                    let got = joints[SliderCrank::<f64>::P];
                    assert!(
                        (got - p.coupler_point).norm() < 1e-13,
                        "{e} {r} {l} {th}: mechanism's coupler point {got:?} against {:?}",
                        p.coupler_point
                    );
                }
            }
        }
    }

    /// Behind with `(γ, e)` is Ahead with `(γ + π, −e)`: the same linkage.
    #[test]
    fn the_reaches_are_the_line_reversed() {
        let behind = SliderCrank::new(
            Vec2::new(1.0, 2.0),
            0.4,
            0.6,
            1.5,
            3.0,
            (1.0, 0.5),
            Reach::Behind,
        )
        .unwrap();
        let ahead = SliderCrank {
            angle: 0.4 + core::f64::consts::PI,
            offset: -0.6,
            reach: Reach::Ahead,
            ..behind
        };
        assert!(
            (ahead.line_point() - behind.line_point()).norm() < 1e-15,
            "line points: ahead {:?}, behind {:?}",
            ahead.line_point(),
            behind.line_point()
        );
        for k in 0..50 {
            let th = k as f64 * 0.13;
            let (p, q) = (behind.pose(th).unwrap(), ahead.pose(th).unwrap());
            assert!((p.coupler_point - q.coupler_point).norm() < 1e-13, "{th}");
        }
    }

    #[test]
    fn the_crank_turns_fully_iff_offset_plus_crank_reaches_the_rod() {
        let full =
            |e: f64, r: f64, l: f64| sc(e, r, l, Reach::Ahead).input_range() == InputRange::Full;
        assert!(
            full(0.0, 1.0, 1.0) && full(1.0, 1.0, 2.0) && full(-1.0, 1.0, 2.0),
            "full turn for (e, r, l) = (0, 1, 1): {}, (1, 1, 2): {}, (-1, 1, 2): {}",
            full(0.0, 1.0, 1.0),
            full(1.0, 1.0, 2.0),
            full(-1.0, 1.0, 2.0)
        );
        assert!(
            !full(1.0 + 1e-9, 1.0, 2.0) && !full(0.0, 1.0, 0.999),
            "full turn for (e, r, l) = (1 + 1e-9, 1, 2): {}, (0, 1, 0.999): {}",
            full(1.0 + 1e-9, 1.0, 2.0),
            full(0.0, 1.0, 0.999)
        );
        assert!(
            sc(1.0, 1.0, 2.0, Reach::Ahead).is_change_point(),
            "|e| + r = l (1 + 1 = 2) not a change point"
        );
        assert_eq!(
            sc(3.5, 1.0, 2.0, Reach::Ahead).input_range(),
            InputRange::Never,
            "offset 3.5 past crank 1 + rod 2"
        );
        // Every kind of limited range: at each limit the rod is perpendicular to the line.
        for &(e, r, l) in &[
            (1.5, 1.0, 1.0),
            (-1.5, 1.0, 1.0),
            (0.2, 3.0, 1.0),
            (0.0, 2.0, 1.0),
        ] {
            let s = sc(e, r, l, Reach::Ahead);
            let limits = match s.input_range() {
                InputRange::Between { lo, hi } => [lo, hi, lo, hi],
                InputRange::TwoIntervals { first, second } => {
                    [first.0, first.1, second.0, second.1]
                }
                r => panic!("{e} {r:?}"),
            };
            for th in limits {
                let d = r * th.sin() - e;
                assert!((d.abs() - l).abs() < 1e-14, "{e} {r} {l}: {th} {d}");
                let mid = s.pose(th + 1e-6).or(s.pose(th - 1e-6)).unwrap();
                assert!(mid.transmission < 1e-2, "{mid:?}");
            }
        }
    }

    #[test]
    fn bad_numbers_are_refused() {
        let o = Vec2::zeros();
        let new =
            |r: f64, l: f64, e: f64| SliderCrank::new(o, 0.0, e, r, l, (0.0, 0.0), Reach::Ahead);
        assert_eq!(
            new(-1.0, 2.0, 0.0),
            Err(Error::InvalidLength {
                what: "crank",
                value: -1.0
            }),
            "crank -1"
        );
        assert_eq!(
            new(1.0, 0.0, 0.0),
            Err(Error::InvalidLength {
                what: "coupler",
                value: 0.0
            }),
            "rod 0"
        );
        let got = new(1.0, 2.0, f64::NAN);
        assert!(
            matches!(
                got,
                Err(Error::NotFinite {
                    what: "line offset",
                    ..
                })
            ),
            "NaN offset: {got:?}"
        );
    }
}
