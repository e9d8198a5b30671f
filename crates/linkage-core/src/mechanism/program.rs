//! A mechanism as an ordered program of closed-form constructions.

use nalgebra::RealField;

use crate::constructions::dyad::{Dyad, DyadFailure, Side};
use crate::constructions::slider::{LineDirection, Reach, SliderDyad};
use crate::error::{check_finite, check_length, Error};
use crate::numeric::scalar::{eps, lit, perp, Vec2};

/// One step of a mechanism's program: it places one joint from joints placed before it.
///
/// ```
/// use linkage_core::{Construction, Error, Mechanism, Side, Vec2};
/// let mut m = Mechanism::<f64, 4>::new();
/// m.push(Construction::Fixed { at: Vec2::zeros() }).unwrap();
/// m.push(Construction::Fixed { at: Vec2::new(3.0, 0.0) }).unwrap();
/// let a = m.push(Construction::Crank { centre: 0, radius: 1.0, phase: 0.0 }).unwrap();
/// assert!(!m.constructions()[a].has_branch());
/// // A construction may refer only to joints placed before it.
/// assert_eq!(
///     m.push(Construction::Point { from: a, to: 3, along: 1.0, left: 0.0 }),
///     Err(Error::UnknownJoint { joint: 3, refers_to: 3 })
/// );
/// let b = m.dyad(a, 1, 3.0, 1.0, Side::Left).unwrap();
/// assert!(m.constructions()[b].has_branch());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Construction<T> {
    /// A joint fixed to the frame.
    Fixed {
        /// Its position.
        at: Vec2<T>,
    },
    /// The driven crank: `centre + radius·(cos(θ + phase), sin(θ + phase))` for the driver angle
    /// `θ`.
    Crank {
        /// The joint the crank turns about.
        centre: usize,
        /// Crank radius.
        radius: T,
        /// Angle added to the driver angle (radians).
        phase: T,
    },
    /// An RRR dyad on joints `p1`, `p2` (see [`Dyad`]), assembled on `side` of `p1 → p2`.
    Dyad {
        /// First base joint (at distance `dyad.r1`).
        p1: usize,
        /// Second base joint (at distance `dyad.r2`).
        p2: usize,
        /// The two link lengths.
        dyad: Dyad<T>,
        /// Initial assembly side; sweeps track it by continuity.
        side: Side,
    },
    /// An RRP dyad: a joint on the line through `origin` with `direction`, at distance
    /// `slider.r` from `pivot` (see [`SliderDyad`]).
    Slider {
        /// The joint the connecting link turns about.
        pivot: usize,
        /// A joint the line passes through.
        origin: usize,
        /// The line's direction.
        direction: LineDirection<T>,
        /// The link length.
        slider: SliderDyad<T>,
        /// Initial intersection; sweeps track it by continuity.
        reach: Reach,
    },
    /// A point rigidly carried by the link `from → to`: `from + along·û + left·û⊥` with
    /// `û` the unit vector from `from` to `to`.
    Point {
        /// Origin of the local frame.
        from: usize,
        /// The joint that sets the local x axis.
        to: usize,
        /// Coordinate along `from → to` (length units, not a fraction).
        along: T,
        /// Coordinate to the left of `from → to`.
        left: T,
    },
}

impl<T: RealField + Copy> Construction<T> {
    /// The joints this construction is built on.
    fn references(&self) -> ([usize; 4], usize) {
        match *self {
            Construction::Fixed { .. } => ([0; 4], 0),
            Construction::Crank { centre, .. } => ([centre, 0, 0, 0], 1),
            Construction::Dyad { p1, p2, .. } => ([p1, p2, 0, 0], 2),
            Construction::Slider {
                pivot,
                origin,
                direction,
                ..
            } => match direction {
                LineDirection::Fixed(_) => ([pivot, origin, 0, 0], 2),
                LineDirection::Link { from, to, .. } => ([pivot, origin, from, to], 4),
            },
            Construction::Point { from, to, .. } => ([from, to, 0, 0], 2),
        }
    }

    /// Whether the construction has two solutions (a branch to track).
    pub fn has_branch(&self) -> bool {
        matches!(
            self,
            Construction::Dyad { .. } | Construction::Slider { .. }
        )
    }

    /// `+1`/`-1` for the initial branch of a dyad or slider, `+1` otherwise.
    pub(crate) fn initial_sign(&self) -> T {
        match *self {
            Construction::Dyad { side, .. } => side.sign(),
            Construction::Slider { reach, .. } => reach.sign(),
            _ => T::one(),
        }
    }
}

/// The fixed part of a crank-pin-and-fixed-joint dyad's base ([`Mechanism::crank_base_frame`]):
/// from the crank centre `O` to the fixed joint `Q`, `gv = Q − O`, its length `g` and direction
/// `β`; the crank radius `r` and phase; whether the crank pin is the dyad's first base joint.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CrankBaseFrame<T> {
    pub(crate) gv: Vec2<T>,
    pub(crate) g: T,
    pub(crate) beta: T,
    pub(crate) r: T,
    pub(crate) phase: T,
    pub(crate) crank_first: bool,
}

/// A dyad on a crank pin and a fixed joint ([`Mechanism::crank_fixed_dyad`]).
#[derive(Clone, Copy, Debug)]
struct CrankFixedDyad<T> {
    /// From the crank centre to the fixed joint.
    gv: Vec2<T>,
    r: T,
    phase: T,
    r1: T,
    r2: T,
}

impl<T: RealField + Copy> CrankFixedDyad<T> {
    /// The ground length `|gv|`.
    fn g(&self) -> T {
        crate::numeric::scalar::length(self.gv)
    }
}

/// The flat positions of a dyad on a crank pin and a fixed joint, for their parity up to a
/// driver angle ([`Mechanism::flat_positions`]): at `ψ = 0` (`zero`) and at `ψ = π` (`pi`), `ψ`
/// the crank angle `t + phase` measured from the ground direction `β`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FlatParity<T> {
    pub(crate) zero: bool,
    pub(crate) pi: bool,
    pub(crate) beta: T,
    pub(crate) phase: T,
}

impl<T: RealField + Copy> FlatParity<T> {
    /// Half of `ψ` at driver angle `t`: the parity is read off its sine and cosine.
    #[inline(always)]
    pub(crate) fn half(&self, t: T) -> T {
        (t + self.phase - self.beta) * lit::<T>(0.5)
    }

    /// The parity from `sin`, `cos` of [`Self::half`]: `⌊(ψ − ψ_f)/2π⌋` is odd exactly when
    /// `sin((ψ − ψ_f)/2) < 0`, the sign of a sine reduced accurately ([`crate::numeric::trig`], the
    /// function `Mechanism::crank_base` forms its base with, from the same `ψ`), so a sample on
    /// the float nearest a flat position is on the side it truly is.
    #[inline(always)]
    pub(crate) fn of(&self, sin: T, cos: T) -> bool {
        (self.zero && sin < T::zero()) != (self.pi && cos > T::zero())
    }

    /// Whether the dyad has a flat position on its turn at all.
    pub(crate) fn any(&self) -> bool {
        self.zero || self.pi
    }

    /// The parity at driver angle `t`, reduced to two turns first ([`crate::numeric::turns`]: the
    /// parity's period is `4π`), so `t + phase − β` does not round away at a large `t`.
    pub(crate) fn at(&self, t: T) -> bool {
        let (s, c) = crate::numeric::trig::sin_cos(self.half(crate::numeric::turns::reduce(t)));
        self.of(s, c)
    }
}

/// Where a construction may put its joint.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Candidates<T: RealField + Copy> {
    /// Exactly one place.
    One(Vec2<T>),
    /// `foot + sign·offset` for `sign = ±1`, with the assembly margin.
    Two {
        foot: Vec2<T>,
        offset: Vec2<T>,
        margin: T,
    },
}

/// Rates of the driver: angular velocity, acceleration and jerk of the crank.
///
/// ```
/// use linkage_core::{CrankRates, Mechanism, Vec2};
/// // A crank of radius 2 turning at 3 rad/s: its pin moves at 6, perpendicular to the crank.
/// let mut m = Mechanism::<f64, 2>::new();
/// let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
/// let a = m.crank(o, 2.0, 0.0).unwrap();
/// let mut pos = [Vec2::zeros(); 2];
/// m.pose(0.0, &mut pos).unwrap();
/// let mut vel = [Vec2::zeros(); 2];
/// let regular = m.rates(&pos, CrankRates::new(3.0, 0.0), &mut vel, None, None).unwrap();
/// assert!(regular && (vel[a] - Vec2::new(0.0, 6.0)).norm() < 1e-15);
/// assert_eq!(CrankRates::<f64>::unit(), CrankRates { omega: 1.0, alpha: 0.0, jerk: 0.0 });
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrankRates<T> {
    /// Crank angular velocity `dθ/dt`.
    pub omega: T,
    /// Crank angular acceleration `d²θ/dt²`.
    pub alpha: T,
    /// Crank angular jerk `d³θ/dt³` (used only when joint jerks are asked for).
    pub jerk: T,
}

impl<T: RealField + Copy> CrankRates<T> {
    /// A drive with angular velocity `omega` and acceleration `alpha`, zero jerk.
    pub fn new(omega: T, alpha: T) -> Self {
        CrankRates {
            omega,
            alpha,
            jerk: T::zero(),
        }
    }

    /// Unit crank speed, no acceleration: rates per radian of crank, `d/dθ`.
    pub fn unit() -> Self {
        Self::new(T::one(), T::zero())
    }
}

/// A planar mechanism: at most `N` joints, each placed by one [`Construction`] from joints
/// before it, driven by one crank angle.
///
/// ```
/// use linkage_core::{Mechanism, Side, Vec2};
/// // Hoecken linkage as a program: O, C fixed; A crank; B dyad; P on A→B.
/// let mut m = Mechanism::<f64, 8>::new();
/// let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
/// let c = m.fixed(Vec2::new(20.0, 0.0)).unwrap();
/// let a = m.crank(o, 10.0, 0.0).unwrap();
/// let b = m.dyad(a, c, 25.0, 25.0, Side::Left).unwrap();
/// let p = m.point(a, b, 50.0, 0.0).unwrap();
/// let mut joints = [Vec2::zeros(); 5];
/// m.pose(core::f64::consts::PI, &mut joints).unwrap();
/// assert!((joints[p] - Vec2::new(20.0, 40.0)).norm() < 1e-12);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Mechanism<T: RealField + Copy, const N: usize> {
    steps: [Construction<T>; N],
    len: usize,
    driver: Option<usize>,
    start: Option<T>,
}

impl<T: RealField + Copy, const N: usize> Default for Mechanism<T, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: RealField + Copy, const N: usize> Mechanism<T, N> {
    /// An empty mechanism.
    pub fn new() -> Self {
        Mechanism {
            steps: [Construction::Fixed { at: Vec2::zeros() }; N],
            len: 0,
            driver: None,
            start: None,
        }
    }

    /// Number of joints.
    #[inline]
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when the mechanism has no joints.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The constructions, in order.
    #[inline]
    pub fn constructions(&self) -> &[Construction<T>] {
        &self.steps[..self.len]
    }

    /// Index of the crank joint, if any.
    #[inline]
    pub fn driver(&self) -> Option<usize> {
        self.driver
    }

    /// Appends a construction after validating its lengths and references.
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`], [`Error::UnknownJoint`] for a reference to a joint not
    /// placed before it, [`Error::InvalidLength`] / [`Error::SubnormalLength`] /
    /// [`Error::NotFinite`] for bad numbers,
    /// [`Error::SecondDriver`] for a second crank, [`Error::Coincident`] when a link or
    /// direction is built on one joint twice.
    pub fn push(&mut self, c: Construction<T>) -> Result<usize, Error> {
        let index = self.len;
        if index >= N {
            return Err(Error::CapacityExceeded { capacity: N });
        }
        let (refs, n) = c.references();
        if let Some(&bad) = refs[..n].iter().find(|&&r| r >= index) {
            return Err(Error::UnknownJoint {
                joint: index,
                refers_to: bad,
            });
        }
        let c = match c {
            Construction::Fixed { at } => {
                check_finite("fixed joint x", at.x)?;
                check_finite("fixed joint y", at.y)?;
                c
            }
            Construction::Crank { radius, phase, .. } => {
                check_length("crank radius", radius)?;
                check_finite("crank phase", phase)?;
                if self.driver.is_some() {
                    return Err(Error::SecondDriver { joint: index });
                }
                c
            }
            Construction::Dyad { p1, p2, dyad, .. } => {
                check_length("dyad r1", dyad.r1)?;
                check_length("dyad r2", dyad.r2)?;
                if p1 == p2 {
                    return Err(Error::Coincident { joint: index });
                }
                c
            }
            Construction::Slider {
                pivot,
                origin,
                direction,
                slider,
                reach,
            } => {
                check_length("slider r", slider.r)?;
                let direction = match direction {
                    LineDirection::Fixed(u) => {
                        check_finite("slider direction x", u.x)?;
                        check_finite("slider direction y", u.y)?;
                        let n = crate::numeric::scalar::length(u);
                        if n == T::zero() {
                            return Err(Error::InvalidLength {
                                what: "slider direction",
                                value: 0.0,
                            });
                        }
                        LineDirection::Fixed(u / n)
                    }
                    LineDirection::Link { from, to, angle } => {
                        check_finite("slider direction angle", angle)?;
                        if from == to {
                            return Err(Error::Coincident { joint: index });
                        }
                        direction
                    }
                };
                Construction::Slider {
                    pivot,
                    origin,
                    direction,
                    slider,
                    reach,
                }
            }
            Construction::Point {
                from,
                to,
                along,
                left,
            } => {
                check_finite("point along", along)?;
                check_finite("point left", left)?;
                if from == to {
                    return Err(Error::Coincident { joint: index });
                }
                c
            }
        };
        if matches!(c, Construction::Crank { .. }) {
            self.driver = Some(index);
        }
        self.steps[index] = c;
        self.len += 1;
        Ok(index)
    }

    /// The same program in a mechanism of capacity `M` (constructions copied as they are, bit
    /// for bit): a sweep of a small linkage held at a large capacity runs on arrays sized to
    /// it.
    ///
    /// # Errors
    /// [`Error::CapacityExceeded`] when the program has more than `M` joints.
    pub fn resized<const M: usize>(&self) -> Result<Mechanism<T, M>, Error> {
        let mut m = Mechanism::<T, M>::new();
        if self.len > M {
            return Err(Error::CapacityExceeded { capacity: M });
        }
        m.steps[..self.len].copy_from_slice(self.constructions());
        m.len = self.len;
        m.driver = self.driver;
        m.start = self.start;
        Ok(m)
    }

    /// The crank angle at which the declared sides name the branches, if set (see
    /// [`Mechanism::set_start_angle`]).
    #[inline]
    pub fn start_angle(&self) -> Option<T> {
        self.start
    }

    /// Sets the crank angle at which the constructions' declared sides name the branches: a
    /// [`crate::Tracker`] then poses its first sample by walking there from this angle, so the
    /// branch a sweep is on does not depend on where it starts. Without it (the default) the
    /// first sample takes the declared sides. It matters where branches cross (a change-point
    /// four-bar at its flat positions, where a dyad's side flips along its circuit);
    /// [`crate::FourBar::mechanism`] sets it to the crank-up position for those. When the
    /// mechanism cannot be assembled at `start`, or the motion cannot pass from there to the
    /// first sample, the first sample takes the declared sides.
    ///
    /// ```
    /// use linkage_core::{Assembly, FourBar, Tracker, Rates, Vec2};
    /// // A parallelogram: started with the crank below the ground line it stays a
    /// // parallelogram (the coupler parallel to the ground) instead of crossing.
    /// let fb = FourBar::new(3.0_f64, 1.0, 3.0, 1.0, (1.0, 0.0), Assembly::Open).unwrap();
    /// let m = fb.mechanism();
    /// assert!(m.start_angle().is_some());
    /// let mut t = Tracker::new(&m).unwrap();
    /// let mut j = [Vec2::zeros(); 5];
    /// t.step(3.5, None, &mut j, Rates::none()).unwrap();
    /// let ab = j[FourBar::<f64>::B] - j[FourBar::<f64>::A];
    /// assert!(ab.y.abs() < 1e-12 && (ab.x - 3.0).abs() < 1e-12);
    /// ```
    pub fn set_start_angle(&mut self, start: Option<T>) {
        self.start = start.filter(|a| a.is_finite());
    }

    /// Adds a fixed joint. See [`Construction::Fixed`].
    ///
    /// # Errors
    /// As [`Mechanism::push`].
    pub fn fixed(&mut self, at: Vec2<T>) -> Result<usize, Error> {
        self.push(Construction::Fixed { at })
    }

    /// Adds the crank. See [`Construction::Crank`].
    ///
    /// # Errors
    /// As [`Mechanism::push`].
    pub fn crank(&mut self, centre: usize, radius: T, phase: T) -> Result<usize, Error> {
        self.push(Construction::Crank {
            centre,
            radius,
            phase,
        })
    }

    /// Adds an RRR dyad. See [`Construction::Dyad`].
    ///
    /// # Errors
    /// As [`Mechanism::push`].
    pub fn dyad(&mut self, p1: usize, p2: usize, r1: T, r2: T, side: Side) -> Result<usize, Error> {
        self.push(Construction::Dyad {
            p1,
            p2,
            dyad: Dyad { r1, r2 },
            side,
        })
    }

    /// Adds an RRP slider dyad. See [`Construction::Slider`].
    ///
    /// # Errors
    /// As [`Mechanism::push`].
    pub fn slider(
        &mut self,
        pivot: usize,
        r: T,
        origin: usize,
        direction: LineDirection<T>,
        reach: Reach,
    ) -> Result<usize, Error> {
        self.push(Construction::Slider {
            pivot,
            origin,
            direction,
            slider: SliderDyad { r },
            reach,
        })
    }

    /// Adds a point carried by the link `from → to`. See [`Construction::Point`].
    ///
    /// # Errors
    /// As [`Mechanism::push`].
    pub fn point(&mut self, from: usize, to: usize, along: T, left: T) -> Result<usize, Error> {
        self.push(Construction::Point {
            from,
            to,
            along,
            left,
        })
    }

    /// For a dyad on a crank pin `A` and a fixed joint `Q` (the crank turning about a fixed
    /// joint `O`), the base vector `p2 − p1` and Kahan's vanishing factor for it without
    /// cancellation (see [`Dyad::solve_with_base`]): `(d² − Δ²)/(d + Δ)` folded,
    /// `(Σ² − d²)/(Σ + d)` stretched.
    ///
    /// With `g = |Q − O|`, crank radius `r` and `ψ` the angle from `O → Q` to `O → A`,
    /// `d² = (g − r)² + 4gr·sin²(ψ/2) = (g + r)² − 4gr·cos²(ψ/2)`, so
    /// `d² − Δ² = (g − r − Δ)(g − r + Δ) + 4gr·sin²(ψ/2)` and
    /// `Σ² − d² = (Σ − g − r)(Σ + g + r) + 4gr·cos²(ψ/2)` (`Δ = |r1 − r2|`, `Σ = r1 + r2`). On a
    /// change-point linkage the first products vanish exactly at the flat positions, and what
    /// is left is a product of accurate factors: the pose keeps full accuracy right up to them.
    /// The products of two lengths are formed on the lengths divided by a power of two near the
    /// longest (exact, and no change for ordinary sizes), so they neither underflow nor overflow
    /// at any linkage scale.
    fn crank_base(
        &self,
        p1: usize,
        p2: usize,
        theta: T,
        pos: &[Vec2<T>],
        dyad: Dyad<T>,
    ) -> Option<(Vec2<T>, T)> {
        let b = self.crank_base_frame(p1, p2, pos)?;
        let (gv, g, beta, r) = (b.gv, b.g, b.beta, b.r);
        let psi = theta + b.phase - beta;
        let half = psi * lit::<T>(0.5);
        let (s, c) = crate::numeric::trig::sin_cos(half);
        // Q − A = (g − r)·ĝ + r·(ĝ − ŵ), and ĝ − ŵ = 2 sin(ψ/2)·(sin(β + ψ/2), −cos(β + ψ/2)).
        let (sb, cb) = crate::numeric::trig::sin_cos(beta + half);
        let qa = gv * ((g - r) / g) + Vec2::new(sb, -cb) * (lit::<T>(2.0) * r * s);
        let dv = if b.crank_first { qa } else { -qa };
        let d = crate::numeric::scalar::length(dv);
        let (delta, sigma) = ((dyad.r1 - dyad.r2).abs(), dyad.r1 + dyad.r2);
        let unit = crate::numeric::pow2::pow2_scale(g.max(r).max(sigma).max(d));
        let (g, r, delta, sigma, ds) = if unit == T::one() {
            (g, r, delta, sigma, d)
        } else {
            (g / unit, r / unit, delta / unit, sigma / unit, d / unit)
        };
        let four_gr = lit::<T>(4.0) * g * r;
        let (r1, r2) = if unit == T::one() {
            (dyad.r1, dyad.r2)
        } else {
            (dyad.r1 / unit, dyad.r2 / unit)
        };
        let (stretched, folded) = flat_products(g, r, r1, r2);
        let f2 = if d >= dyad.r1.max(dyad.r2) {
            let stretch = stretched + four_gr * c * c;
            stretch / (sigma + ds)
        } else {
            let fold = folded + four_gr * s * s;
            fold / (ds + delta)
        };
        Some((dv, if unit == T::one() { f2 } else { f2 * unit }))
    }

    /// The flat positions of joint `i` when it is a dyad on a crank pin and a fixed joint
    /// (see [`Mechanism::crank_base`]), for the parity of those between two driver angles.
    ///
    /// The dyad is flat where the crank pin is on the line through the crank centre and the
    /// fixed joint (`ψ = 0` or `π`) and the base length `|g ∓ r|` equals `|r1 − r2|` or
    /// `r1 + r2` (to `8ε` of the lengths: a change point). There the joint's signed height over
    /// its base is `∝ sin(ψ/2)` (or `cos`), an analytic function with a simple zero: each of
    /// the two branches through the flat position changes side there, and only there. The
    /// parity up to driver angle `t` ([`FlatParity::at`]) is `⌊(ψ − ψ_f)/2π⌋ mod 2` summed over
    /// the flat positions `ψ_f`, a function of the angle: an odd number lies between two angles
    /// exactly when their parities differ, and counts along any path telescope (a path that
    /// returns changes nothing).
    pub(crate) fn flat_positions(&self, i: usize) -> Option<FlatParity<T>> {
        let d = self.crank_fixed_dyad(i)?;
        let [at_zero, at_pi] = crate::constructions::dyad::flat_angles(d.g(), d.r, d.r1, d.r2);
        Some(FlatParity {
            zero: at_zero.is_some(),
            pi: at_pi.is_some(),
            beta: d.gv.y.atan2(d.gv.x),
            phase: d.phase,
        })
    }

    /// Joint `i` when it is a dyad on a crank pin and a fixed joint: the ground vector from
    /// the crank centre to the fixed joint, the crank's radius and phase, the dyad's lengths.
    fn crank_fixed_dyad(&self, i: usize) -> Option<CrankFixedDyad<T>> {
        let Construction::Dyad { p1, p2, dyad, .. } = self.steps[i] else {
            return None;
        };
        let (k, q) = self.crank_and_fixed(p1, p2)?;
        let (
            Construction::Crank {
                centre,
                radius,
                phase,
            },
            Construction::Fixed { at: qp },
        ) = (self.steps[k], self.steps[q])
        else {
            return None;
        };
        let Construction::Fixed { at: o } = self.steps[centre] else {
            return None;
        };
        Some(CrankFixedDyad {
            gv: qp - o,
            r: radius,
            phase,
            r1: dyad.r1,
            r2: dyad.r2,
        })
    }

    /// Whether a tracked sweep may ever change joint `i`'s orientation: false for joints
    /// without a branch and for a dyad on a crank pin and a fixed joint with no flat position
    /// (the tracker turns such a dyad only at its flat positions, counted in closed form, and
    /// never by extrapolation: see [`Mechanism::flat_positions`]); true otherwise.
    pub(crate) fn may_flip(&self, i: usize) -> bool {
        match self.steps[i] {
            Construction::Dyad { .. } => self.crank_fixed_dyad(i).is_none_or(|d| {
                let (g, r, r1, r2) = (d.g(), d.r, d.r1, d.r2);
                let [at_zero, at_pi] = crate::constructions::dyad::flat_angles(g, r, r1, r2);
                at_zero.is_some() || at_pi.is_some()
            }),
            Construction::Slider { .. } => true,
            _ => false,
        }
    }

    /// Whether every joint's orientation is a function of the driver angle alone, known in
    /// closed form: every dyad is on a crank pin and a fixed joint, assembles over the whole
    /// turn (its base `|g − r| … g + r` within `[|r1 − r2|, r1 + r2]`, to the `8ε` of
    /// [`Mechanism::flat_positions`]), and there is no slider. Its orientation is then the
    /// declared one, turned at each flat position crossed (counted by `flat_positions`), and a
    /// tracker needs no walk between samples.
    pub(crate) fn branches_in_closed_form(&self) -> bool {
        (0..self.len).all(|i| match self.steps[i] {
            Construction::Dyad { .. } => self.crank_fixed_dyad(i).is_some_and(|d| {
                let (g, r, r1, r2) = (d.g(), d.r, d.r1, d.r2);
                let (delta, sigma) = ((r1 - r2).abs(), r1 + r2);
                let tol = eps::<T>() * lit::<T>(8.0) * (g + r + sigma);
                (g - r).abs() >= delta - tol && g + r <= sigma + tol
            }),
            Construction::Slider { .. } => false,
            _ => true,
        })
    }

    /// Whether joint `i` is a dyad on a crank pin and a fixed joint with a flat position on its
    /// turn: its orientation turns there, counted in closed form ([`Mechanism::flat_positions`]).
    pub(crate) fn has_flats(&self, i: usize) -> bool {
        match self.steps[i] {
            Construction::Dyad { p1, p2, .. } => {
                self.crank_and_fixed(p1, p2).is_some() && self.may_flip(i)
            }
            _ => false,
        }
    }

    /// [`Mechanism::pose`] (the same bits), returning also the smallest margin of the joints
    /// `watched` marks (1 when none is marked).
    pub(crate) fn pose_watched(
        &self,
        theta: T,
        joints: &mut [Vec2<T>],
        watched: &[bool],
    ) -> Result<(T, T), Error> {
        self.pose_oriented(theta, joints, watched, &[false; N])
    }

    /// [`Mechanism::pose_watched`] with the joints `flipped` marks on the other side of their
    /// declared one.
    pub(crate) fn pose_oriented(
        &self,
        theta: T,
        joints: &mut [Vec2<T>],
        watched: &[bool],
        flipped: &[bool; N],
    ) -> Result<(T, T), Error> {
        let theta = crate::numeric::turns::reduce(theta);
        let mut margin = T::one();
        let mut least = T::one();
        for i in 0..self.len {
            joints[i] = match self.candidates(i, theta, joints, T::zero())? {
                Candidates::One(p) => p,
                Candidates::Two {
                    foot,
                    offset,
                    margin: m,
                } => {
                    margin = margin.min(m);
                    if watched[i] {
                        least = least.min(m);
                    }
                    let sign = self.steps[i].initial_sign();
                    foot + offset * if flipped[i] { -sign } else { sign }
                }
            };
        }
        Ok((margin, least))
    }

    /// What [`Mechanism::crank_base`] needs of a dyad on a crank pin and a fixed joint besides
    /// the crank angle (`None` for other dyads); `pos` holds the fixed joints.
    pub(crate) fn crank_base_frame(
        &self,
        p1: usize,
        p2: usize,
        pos: &[Vec2<T>],
    ) -> Option<CrankBaseFrame<T>> {
        let (k, q) = self.crank_and_fixed(p1, p2)?;
        let Construction::Crank {
            centre,
            radius,
            phase,
        } = self.steps[k]
        else {
            return None;
        };
        let gv = pos[q] - pos[centre];
        Some(CrankBaseFrame {
            gv,
            g: crate::numeric::scalar::length(gv),
            beta: gv.y.atan2(gv.x),
            r: radius,
            phase,
            crank_first: k == p1,
        })
    }

    /// The length of the link `from → to` when the mechanism fixes it (a crank, or one side of
    /// a dyad): a point carried by that link divides by it instead of the computed distance,
    /// which it equals to rounding (one square root and one division fewer a sample).
    pub(crate) fn link_length(&self, from: usize, to: usize) -> Option<T> {
        let side = |j: usize, other: usize| match self.steps[j] {
            Construction::Crank { centre, radius, .. } if centre == other => Some(radius),
            Construction::Dyad { p1, dyad, .. } if p1 == other => Some(dyad.r1),
            Construction::Dyad { p2, dyad, .. } if p2 == other => Some(dyad.r2),
            _ => None,
        };
        side(to, from).or_else(|| side(from, to))
    }

    /// The crank joint and the fixed joint of a dyad on `p1`, `p2`, when it is built on a crank
    /// pin (turning about a fixed joint) and another fixed joint.
    fn crank_and_fixed(&self, p1: usize, p2: usize) -> Option<(usize, usize)> {
        let fixed = |j: usize| matches!(self.steps[j], Construction::Fixed { .. });
        let (k, q) = match (self.steps[p1], self.steps[p2]) {
            (Construction::Crank { .. }, _) if fixed(p2) => (p1, p2),
            (_, Construction::Crank { .. }) if fixed(p1) => (p2, p1),
            _ => return None,
        };
        let Construction::Crank { centre, .. } = self.steps[k] else {
            return None;
        };
        match (self.steps[centre], self.steps[q]) {
            // A fixed joint on the crank centre keeps the base at the crank radius: nothing to
            // gain, and no ground direction to measure angles from.
            (Construction::Fixed { at: o }, Construction::Fixed { at }) if at != o => Some((k, q)),
            _ => None,
        }
    }

    /// Where joint `i` may go at driver angle `theta`, given the joints before it. The angle
    /// is reduced to two turns first ([`crate::numeric::turns`]), so a crank angle of any size is exact.
    ///
    /// `slack` widens the toggle tolerance (length units, see [`Dyad::solve`]).
    pub(crate) fn candidates(
        &self,
        i: usize,
        theta: T,
        pos: &[Vec2<T>],
        slack: T,
    ) -> Result<Candidates<T>, Error> {
        // Idempotent: callers that pose every joint reduce once, and this is a comparison.
        let c = self.solve_step(i, crate::numeric::turns::reduce(theta), pos, slack)?;
        // Numbers so large that the arithmetic overflows give no position, not garbage.
        let finite = |p: Vec2<T>| p.x.is_finite() && p.y.is_finite();
        let ok = match c {
            Candidates::One(p) => finite(p),
            Candidates::Two { foot, offset, .. } => finite(foot) && finite(offset),
        };
        if ok {
            Ok(c)
        } else {
            Err(Error::NotFinite {
                what: "joint position (the linkage's numbers overflow)",
                value: f64::NAN,
            })
        }
    }

    /// The construction's candidates, before the finiteness check.
    fn solve_step(
        &self,
        i: usize,
        theta: T,
        pos: &[Vec2<T>],
        slack: T,
    ) -> Result<Candidates<T>, Error> {
        let fail = |f: DyadFailure<T>| match f {
            DyadFailure::Gap(g) => Error::CannotAssemble {
                joint: i,
                gap: crate::numeric::scalar::to_f64(g),
            },
            DyadFailure::Undetermined => Error::Coincident { joint: i },
        };
        match self.steps[i] {
            Construction::Fixed { at } => Ok(Candidates::One(at)),
            Construction::Crank {
                centre,
                radius,
                phase,
            } => {
                let (s, c) = crate::numeric::trig::sin_cos(theta + phase);
                Ok(Candidates::One(pos[centre] + Vec2::new(c, s) * radius))
            }
            Construction::Dyad { p1, p2, dyad, .. } => {
                let base = || self.crank_base(p1, p2, theta, pos, dyad);
                let d = dyad
                    .solve_with_base(pos[p1], pos[p2], slack, base)
                    .map_err(fail)?;
                Ok(Candidates::Two {
                    foot: d.foot,
                    offset: d.offset,
                    margin: d.margin,
                })
            }
            Construction::Slider {
                pivot,
                origin,
                direction,
                slider,
                ..
            } => {
                let u = direction.at(pos).ok_or(Error::Coincident { joint: i })?;
                let s = slider
                    .solve(pos[pivot], pos[origin], u, slack)
                    .map_err(fail)?;
                Ok(Candidates::Two {
                    foot: s.foot,
                    offset: s.offset,
                    margin: s.margin,
                })
            }
            Construction::Point {
                from,
                to,
                along,
                left,
            } => {
                let d = pos[to] - pos[from];
                let n = crate::numeric::scalar::length(d);
                if n == T::zero() {
                    return Err(Error::Coincident { joint: i });
                }
                let e = d * (T::one() / self.link_length(from, to).unwrap_or(n));
                Ok(Candidates::One(pos[from] + e * along + perp(e) * left))
            }
        }
    }

    /// Solves every joint at driver angle `theta` on the branches the constructions declare,
    /// writing positions into `joints` (length [`Mechanism::len`]). Returns the smallest
    /// assembly margin of the dyads (1 if there are none).
    ///
    /// This is a single pose with no history; use a [`crate::Tracker`] to sweep.
    ///
    /// # Errors
    /// [`Error::BufferLength`], or the first joint that cannot be placed.
    pub fn pose(&self, theta: T, joints: &mut [Vec2<T>]) -> Result<T, Error> {
        if joints.len() != self.len {
            return Err(Error::BufferLength {
                what: "joints",
                expected: self.len,
                got: joints.len(),
            });
        }
        let theta = crate::numeric::turns::reduce(theta);
        let mut margin = T::one();
        for i in 0..self.len {
            joints[i] = match self.candidates(i, theta, joints, T::zero())? {
                Candidates::One(p) => p,
                Candidates::Two {
                    foot,
                    offset,
                    margin: m,
                } => {
                    margin = margin.min(m);
                    foot + offset * self.steps[i].initial_sign()
                }
            };
        }
        Ok(margin)
    }
}

/// `(Σ − g − r)(Σ + g + r)` and `(g − r − Δ)(g − r + Δ)` (`Σ = r1 + r2`, `Δ = |r1 − r2|`), the
/// parts of a crank-pin dyad's vanishing factors ([`Mechanism::crank_base`]) that are zero at a
/// change point's flat positions, with their vanishing differences formed from the lengths
/// paired largest with largest: `Σ − g − r = (max(r1, r2) − max(g, r)) + (min(r1, r2) − min(g, r))`,
/// `g − r ∓ Δ = (g − max(r1, r2)) + (min(r1, r2) − r)` or `(g − min(r1, r2)) + (max(r1, r2) − r)`.
/// Each difference of near-equal lengths is exact (Sterbenz), so the product is exactly zero at
/// a change point and accurate next to one; `Σ` or `g − r` formed first would carry a rounding
/// of `ε·Σ` (a parallelogram whose `r1 + r2` is not a float), whose square root put an error of
/// `√ε` of the size on the pose at the flat position.
// Not inlined: called once per block of the held pass (and per near-flat sample of the
// tracker), it made the inlined block kernels slower (instant centres 47 → 55 ns a sample).
#[inline(never)]
pub(crate) fn flat_products<T: RealField + Copy>(g: T, r: T, r1: T, r2: T) -> (T, T) {
    let (hi, lo) = (r1.max(r2), r1.min(r2));
    let stretched = ((hi - g.max(r)) + (lo - g.min(r))) * ((r1 + r2) + (g + r));
    let folded = ((g - hi) + (lo - r)) * ((g - lo) + (hi - r));
    (stretched, folded)
}
#[cfg(test)]
mod tests {
    use super::*;

    fn slider_crank() -> (Mechanism<f64, 4>, usize) {
        let mut m = Mechanism::new();
        let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
        let a = m.crank(o, 2.0, 0.0).unwrap();
        let b = m
            .slider(
                a,
                5.0,
                o,
                LineDirection::Fixed(Vec2::new(3.0, 0.0)),
                Reach::Ahead,
            )
            .unwrap();
        (m, b)
    }

    #[test]
    fn rejects_bad_programs() {
        let mut m = Mechanism::<f64, 3>::new();
        assert_eq!(
            m.crank(0, 1.0, 0.0),
            Err(Error::UnknownJoint {
                joint: 0,
                refers_to: 0
            }),
            "a crank about a joint not yet defined"
        );
        let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
        let negative = m.crank(o, -1.0, 0.0);
        assert!(
            matches!(
                negative,
                Err(Error::InvalidLength {
                    what: "crank radius",
                    ..
                })
            ),
            "a negative crank radius gave {negative:?}"
        );
        let nan = m.fixed(Vec2::new(f64::NAN, 0.0));
        assert!(
            matches!(nan, Err(Error::NotFinite { .. })),
            "a NaN fixed joint gave {nan:?}"
        );
        m.crank(o, 1.0, 0.0).unwrap();
        assert_eq!(
            m.crank(o, 1.0, 0.0),
            Err(Error::SecondDriver { joint: 2 }),
            "a second crank"
        );
        m.fixed(Vec2::new(1.0, 0.0)).unwrap();
        assert_eq!(
            m.fixed(Vec2::new(1.0, 0.0)),
            Err(Error::CapacityExceeded { capacity: 3 }),
            "a fourth joint in a program of capacity 3"
        );
    }

    #[test]
    fn slider_crank_acceleration_matches_closed_form() {
        let (m, b) = slider_crank();
        let (r, l, th, w, al) = (2.0_f64, 5.0_f64, 0.9_f64, 1.5, 0.4);
        let mut pos = [Vec2::zeros(); 3];
        m.pose(th, &mut pos).unwrap();
        let mut vel = [Vec2::zeros(); 3];
        let mut acc = [Vec2::zeros(); 3];
        m.rates(&pos, CrankRates::new(w, al), &mut vel, Some(&mut acc), None)
            .unwrap();
        // x(θ) = r cos θ + √(l² − r² sin² θ): x' and x'' in θ by hand, then chain rule.
        let (s, c) = th.sin_cos();
        let g = l * l - r * r * s * s;
        let root = g.sqrt();
        let x1 = -r * s - r * r * s * c / root;
        let x2 = -r * c - r * r * (c * c - s * s) / root - (r * r * s * c).powi(2) / (g * root);
        let (x, v, a) = (r * c + root, x1 * w, x2 * w * w + x1 * al);
        assert!(
            (pos[b].x - x).abs() < 1e-14,
            "position {} against {x}",
            pos[b].x
        );
        assert!(
            (vel[b].x - v).abs() < 1e-13,
            "velocity {} against {v}",
            vel[b].x
        );
        assert!(
            (acc[b].x - a).abs() < 1e-12,
            "acceleration {} against {a}",
            acc[b].x
        );
        assert!(
            acc[b].y.abs() < 1e-14,
            "the slider leaves its line: {}",
            acc[b].y
        );
    }

    #[test]
    fn toggle_velocity_is_nan_not_garbage() {
        // Slider-crank with r = l: at θ = 90° the rod is perpendicular to the line.
        let mut m = Mechanism::<f64, 3>::new();
        let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
        let a = m.crank(o, 1.0, 0.0).unwrap();
        let b = m
            .slider(
                a,
                1.0,
                o,
                LineDirection::Fixed(Vec2::new(1.0, 0.0)),
                Reach::Ahead,
            )
            .unwrap();
        let mut pos = [Vec2::zeros(); 3];
        // Exactly at the toggle the pose is valid (joint at the foot) ...
        let margin = m.pose(core::f64::consts::FRAC_PI_2, &mut pos).unwrap();
        assert!(margin < 1e-7, "margin {margin:e} at the toggle");
        // ... and a velocity solve there reports the singularity, or stays finite only if the
        // rounding left the rod not exactly perpendicular.
        let mut vel = [Vec2::zeros(); 3];
        pos[b] = Vec2::new(0.0, 0.0);
        pos[a] = Vec2::new(0.0, 1.0);
        let regular = m
            .rates(&pos, CrankRates::unit(), &mut vel, None, None)
            .unwrap();
        assert!(
            !regular && vel[b].x.is_nan(),
            "at the toggle: regular {regular}, velocity {:?}",
            vel[b]
        );
    }
}
