//! The four-bar linkage: Grashof class, input limits, transmission angle, circuits.

use nalgebra::RealField;

use crate::constructions::dyad::{triangle_area, Side};
use crate::error::{check_finite, check_length, Error};
use crate::mechanism::bodies::{Bodies, BodyId};
use crate::mechanism::program::CrankRates;
use crate::mechanism::program::Mechanism;
use crate::motion::centres::{line_intersection, BodyMotion, Centre};
use crate::motion::inflection::{inflection, Inflection};
use crate::numeric::scalar::{cross, eps, lit, Vec2};
use crate::sweep::tracker::{Rates, Tracker};

/// Assembly of a four-bar: on which side of the diagonal `A → C` the coupler–rocker joint `B`
/// lies.
///
/// Named `"open"` and `"crossed"` ([`Assembly::name`], parsed back by `FromStr`).
///
/// ```
/// use linkage_core::{Assembly, Error, FourBar};
/// // The two assemblies of one four-bar are mirror images in the diagonal A → C.
/// let fb = |assembly| FourBar::new(20.0_f64, 10.0, 25.0, 25.0, (0.0, 0.0), assembly).unwrap();
/// let open = fb(Assembly::Open).pose(1.0).unwrap();
/// let crossed = fb(Assembly::Crossed).pose(1.0).unwrap();
/// assert_eq!(open.a, crossed.a);
/// assert!(open.b.y > crossed.b.y);
/// assert_eq!("crossed".parse::<Assembly>(), Ok(Assembly::Crossed));
/// assert_eq!(Assembly::Open.to_string(), "open");
/// assert_eq!(
///     "sideways".parse::<Assembly>(),
///     Err(Error::InvalidChoice { what: "assembly", choices: "'open' or 'crossed'" })
/// );
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Assembly {
    /// `B` left of `A → C`. With the crank up and the pivots left to right this is the convex,
    /// uncrossed quadrilateral `O A B C`.
    Open,
    /// `B` right of `A → C`: the mirror assembly, coupler and rocker crossing the ground line.
    Crossed,
}

impl Assembly {
    /// The dyad side this assembly puts `B` on.
    pub fn side(self) -> Side {
        match self {
            Assembly::Open => Side::Left,
            Assembly::Crossed => Side::Right,
        }
    }
}

crate::choice::choice_names!(Assembly, "assembly", Open => "open", Crossed => "crossed");

/// Grashof classification by `s + l` against `p + q` and by which link is shortest.
///
/// ```
/// use linkage_core::{Assembly, FourBar, GrashofClass};
/// let class = |g, a, b, c| {
///     FourBar::new(g, a, b, c, (0.0, 0.0), Assembly::Open).unwrap().grashof()
/// };
/// assert_eq!(class(20.0_f64, 10.0, 25.0, 25.0), GrashofClass::CrankRocker);
/// // s + l = p + q: a parallelogram, which can fold flat.
/// assert_eq!(class(3.0, 1.0, 3.0, 1.0), GrashofClass::ChangePoint);
/// assert_eq!(class(40.0, 20.0, 10.0, 20.0).name(), "triple-rocker");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GrashofClass {
    /// `s + l < p + q`, crank shortest: the crank turns fully, the rocker oscillates.
    CrankRocker,
    /// `s + l < p + q`, ground shortest: both crank and rocker turn fully (drag link).
    DoubleCrank,
    /// `s + l < p + q`, rocker shortest: the input oscillates, the output turns fully.
    RockerCrank,
    /// `s + l < p + q`, coupler shortest: both side links oscillate, the coupler turns fully.
    DoubleRocker,
    /// `s + l = p + q` (to rounding): the linkage can flatten, where its branches meet.
    ChangePoint,
    /// `s + l > p + q`: non-Grashof, no link turns fully relative to another.
    TripleRocker,
}

impl GrashofClass {
    /// The class name as users write it: `"crank-rocker"`, `"double-crank"`, `"rocker-crank"`,
    /// `"double-rocker"`, `"change-point"`, `"triple-rocker"`.
    pub fn name(self) -> &'static str {
        match self {
            GrashofClass::CrankRocker => "crank-rocker",
            GrashofClass::DoubleCrank => "double-crank",
            GrashofClass::RockerCrank => "rocker-crank",
            GrashofClass::DoubleRocker => "double-rocker",
            GrashofClass::ChangePoint => "change-point",
            GrashofClass::TripleRocker => "triple-rocker",
        }
    }
}

/// The crank angles at which a four-bar assembles (absolute angles, radians).
///
/// ```
/// use linkage_core::{catalog, Assembly, FourBar, InputRange};
/// assert_eq!(catalog::hoecken::<f64>().input_range(), InputRange::Full);
/// // Evans C (ground 20, crank 10, coupler 10, rocker 10): |AC| = 20 at θ = ±acos(1/4).
/// match catalog::evans_c::<f64>().input_range() {
///     InputRange::Between { lo, hi } => {
///         assert!((hi - 0.25_f64.acos()).abs() < 1e-15 && (lo + hi).abs() < 1e-15)
///     }
///     r => panic!("{r:?}"),
/// }
/// // Coupler and rocker (2 + 2) cannot reach across the gap of 19 at least: never assembles.
/// let short = FourBar::new(20.0_f64, 1.0, 2.0, 2.0, (0.0, 0.0), Assembly::Open).unwrap();
/// assert_eq!(short.input_range(), InputRange::Never);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InputRange<T> {
    /// Every crank angle: the crank turns fully.
    Full,
    /// `lo ≤ θ ≤ hi` (`hi − lo < 2π`; `lo` may exceed `π`): limited by toggle positions.
    Between {
        /// Lower limit.
        lo: T,
        /// Upper limit.
        hi: T,
    },
    /// Two mirror-image intervals (the coupler and rocker toggle both stretched and folded):
    /// `first` is the one counter-clockwise of the ground line, `second` its mirror. Each is a
    /// separate circuit of the linkage.
    TwoIntervals {
        /// `(lo, hi)` counter-clockwise of the ground line.
        first: (T, T),
        /// `(lo, hi)` clockwise of it.
        second: (T, T),
    },
    /// At no angle: the coupler and rocker cannot reach across the crank's circle.
    Never,
}

/// A solved four-bar position.
///
/// ```
/// use linkage_core::{catalog, Vec2};
/// let fb = catalog::hoecken::<f64>();
/// let p = fb.pose(0.0).unwrap();
/// assert_eq!(p.a, Vec2::new(10.0, 0.0)); // the crank pin, 10 along +x
/// assert!(((p.b - p.a).norm() - 25.0).abs() < 1e-12); // the coupler
/// assert!(((p.b - fb.c).norm() - 25.0).abs() < 1e-12); // the rocker
/// // The margin is the sine of the transmission angle.
/// assert!((p.margin - fb.transmission_angle(0.0).unwrap().sin()).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBarPose<T: RealField + Copy> {
    /// Crank pin.
    pub a: Vec2<T>,
    /// Coupler–rocker joint.
    pub b: Vec2<T>,
    /// The coupler point.
    pub coupler_point: Vec2<T>,
    /// Assembly margin of the coupler–rocker dyad (`sin` of the transmission angle).
    pub margin: T,
}

impl<T: RealField + Copy> FourBarPose<T> {
    /// World point `p` in the coupler's frame: `(along, left)` with the origin at `A`, `along`
    /// the coupler line toward `B` and `left` of it — the frame of [`FourBar::along`] and
    /// [`FourBar::left`].
    /// The coupler's direction is normalised by an overflow-free length, so the result is
    /// right at any scale.
    ///
    /// ```
    /// use linkage_core::{catalog, FourBar};
    /// let fb = catalog::hoecken::<f64>();
    /// let pose = fb.pose(1.0).unwrap();
    /// let local = pose.to_coupler_frame(pose.coupler_point);
    /// assert!((local.x - 50.0).abs() < 1e-12 && local.y.abs() < 1e-12);
    /// ```
    pub fn to_coupler_frame(&self, p: Vec2<T>) -> Vec2<T> {
        let d = self.b - self.a;
        let u = d / crate::numeric::scalar::length(d);
        let r = p - self.a;
        Vec2::new(r.dot(&u), cross(u, r))
    }
}

/// A four-bar linkage: ground pivots `O` (crank) and `C` (rocker), crank `O A`, coupler `A B`,
/// rocker `C B`, and a coupler point in coupler coordinates.
///
/// Joints of [`FourBar::mechanism`] are numbered `O = 0, C = 1, A = 2, B = 3, P = 4`.
///
/// ```
/// use linkage_core::{Assembly, Error, FourBar, Vec2};
/// // Hoecken's straight-line linkage (mm): the foot 50 along the coupler line.
/// let fb = FourBar::new(20.0_f64, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
/// assert_eq!((fb.ground(), fb.c), (20.0, Vec2::new(20.0, 0.0)));
/// let top = fb.pose(core::f64::consts::PI).unwrap().coupler_point;
/// assert!((top - Vec2::new(20.0, 40.0)).norm() < 1e-12);
/// // A length must be positive; a linkage that cannot close has no pose.
/// assert_eq!(
///     FourBar::new(20.0, 0.0, 25.0, 25.0, (0.0, 0.0), Assembly::Open),
///     Err(Error::InvalidLength { what: "crank", value: 0.0 })
/// );
/// let short = FourBar::new(20.0_f64, 1.0, 2.0, 2.0, (0.0, 0.0), Assembly::Open).unwrap();
/// assert!(matches!(short.pose(0.0), Err(Error::CannotAssemble { joint: 3, .. })));
/// assert_eq!(short.transmission_angle(0.0), None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBar<T> {
    /// Crank pivot.
    pub o: Vec2<T>,
    /// Rocker pivot.
    pub c: Vec2<T>,
    /// Crank length `|OA|`.
    pub crank: T,
    /// Coupler length `|AB|`.
    pub coupler: T,
    /// Rocker length `|CB|`.
    pub rocker: T,
    /// Coupler point: distance along `A → B`.
    pub along: T,
    /// Coupler point: distance to the left of `A → B`.
    pub left: T,
    /// Which assembly.
    pub assembly: Assembly,
}

impl<T: RealField + Copy> FourBar<T> {
    /// Index of the crank pivot in [`FourBar::mechanism`].
    pub const O: usize = 0;
    /// Index of the rocker pivot.
    pub const C: usize = 1;
    /// Index of the crank pin.
    pub const A: usize = 2;
    /// Index of the coupler–rocker joint.
    pub const B: usize = 3;
    /// Index of the coupler point.
    pub const P: usize = 4;

    /// A four-bar with `O = (0, 0)` and `C = (ground, 0)`; `point = (along, left)`.
    ///
    /// # Errors
    /// [`Error::InvalidLength`] for a length that is not positive and finite,
    /// [`Error::SubnormalLength`] for a subnormal one, [`Error::NotFinite`] for a non-finite
    /// point coordinate.
    pub fn new(
        ground: T,
        crank: T,
        coupler: T,
        rocker: T,
        point: (T, T),
        assembly: Assembly,
    ) -> Result<Self, Error> {
        let ground = check_length("ground", ground)?;
        Self::with_pivots(
            Vec2::zeros(),
            Vec2::new(ground, T::zero()),
            crank,
            coupler,
            rocker,
            point,
            assembly,
        )
    }

    /// A four-bar on explicit pivots.
    ///
    /// # Errors
    /// As [`FourBar::new`]; [`Error::InvalidLength`] (`"ground"`) when the pivots coincide.
    pub fn with_pivots(
        o: Vec2<T>,
        c: Vec2<T>,
        crank: T,
        coupler: T,
        rocker: T,
        point: (T, T),
        assembly: Assembly,
    ) -> Result<Self, Error> {
        for (what, v) in [("o.x", o.x), ("o.y", o.y), ("c.x", c.x), ("c.y", c.y)] {
            check_finite(what, v)?;
        }
        check_length("ground", crate::numeric::scalar::length(c - o))?;
        Ok(FourBar {
            o,
            c,
            crank: check_length("crank", crank)?,
            coupler: check_length("coupler", coupler)?,
            rocker: check_length("rocker", rocker)?,
            along: check_finite("point along", point.0)?,
            left: check_finite("point left", point.1)?,
            assembly,
        })
    }

    /// Ground length `|OC|`.
    pub fn ground(&self) -> T {
        crate::numeric::scalar::length(self.c - self.o)
    }

    /// `(ground, crank, coupler, rocker)` divided by a power of two near the longest (exact),
    /// so sums and squares of them neither overflow nor underflow.
    fn scaled_lengths(&self) -> (T, T, T, T) {
        let (g, r, b, c) = (self.ground(), self.crank, self.coupler, self.rocker);
        let s = crate::numeric::pow2::pow2_scale(g.max(r).max(b).max(c));
        if s == T::one() {
            (g, r, b, c)
        } else {
            (g / s, r / s, b / s, c / s)
        }
    }

    /// The four-bar as a [`Mechanism`] program: `O, C` fixed, `A` crank, `B` dyad, `P` point.
    pub fn mechanism(&self) -> Mechanism<T, 5> {
        let mut m = Mechanism::new();
        let steps = [
            m.fixed(self.o),
            m.fixed(self.c),
            m.crank(Self::O, self.crank, T::zero()),
            m.dyad(
                Self::A,
                Self::C,
                self.coupler,
                self.rocker,
                self.assembly.side(),
            ),
            m.point(Self::A, Self::B, self.along, self.left),
        ];
        // A push can fail only if the public fields were set to invalid numbers after
        // construction; the program is then shorter than 5 joints and every solve of it reports
        // `Error::BufferLength` instead of a position (no panic, no wrong value).
        let _ = steps;
        m.set_start_angle(self.start_angle());
        m
    }

    /// For a change point, the crank-up angle (the ground direction `O → C` plus `π/2`) at which
    /// the declared assembly names the branch: where the circuits cross (the flat positions,
    /// crank along the ground line) the side of `B` flips along a circuit, so sweeps of
    /// [`FourBar::mechanism`] reach their first sample from there
    /// ([`Mechanism::set_start_angle`]). `None` otherwise (the side never flips).
    ///
    /// ```
    /// use linkage_core::{Assembly, FourBar};
    /// let parallelogram = FourBar::new(3.0_f64, 1.0, 3.0, 1.0, (1.0, 0.0), Assembly::Open).unwrap();
    /// assert_eq!(parallelogram.start_angle(), Some(core::f64::consts::FRAC_PI_2));
    /// let hoecken = FourBar::new(20.0_f64, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
    /// assert_eq!(hoecken.start_angle(), None);
    /// ```
    pub fn start_angle(&self) -> Option<T> {
        (self.grashof() == GrashofClass::ChangePoint).then(|| {
            let d = self.c - self.o;
            d.y.atan2(d.x) + T::frac_pi_2()
        })
    }

    /// Position at crank angle `theta` on the declared assembly (no tracking).
    ///
    /// # Errors
    /// [`Error::CannotAssemble`] (joint 3) outside the input range.
    pub fn pose(&self, theta: T) -> Result<FourBarPose<T>, Error> {
        let m = self.mechanism();
        let mut j = [Vec2::zeros(); 5];
        let margin = m.pose(theta, &mut j)?;
        Ok(FourBarPose {
            a: j[Self::A],
            b: j[Self::B],
            coupler_point: j[Self::P],
            margin,
        })
    }

    /// Grashof class. Ties `s + l = p + q` within `8 ε (s + l + p + q)` are
    /// [`GrashofClass::ChangePoint`].
    pub fn grashof(&self) -> GrashofClass {
        let (g, r, b, c) = self.scaled_lengths();
        let links = [g, r, b, c];
        let mut s = links[0];
        let mut l = links[0];
        let mut shortest = 0;
        for (i, &x) in links.iter().enumerate() {
            if x < s {
                s = x;
                shortest = i;
            }
            if x > l {
                l = x;
            }
        }
        let total = links[0] + links[1] + links[2] + links[3];
        let pq = total - s - l;
        let diff = (s + l) - pq;
        if diff.abs() <= eps::<T>() * lit::<T>(8.0) * total {
            GrashofClass::ChangePoint
        } else if diff > T::zero() {
            GrashofClass::TripleRocker
        } else {
            match shortest {
                0 => GrashofClass::DoubleCrank,
                1 => GrashofClass::CrankRocker,
                2 => GrashofClass::DoubleRocker,
                _ => GrashofClass::RockerCrank,
            }
        }
    }

    /// Crank angle (from `O → C`, in `[0, π]`) at which `|AC| = diag`, or `None` when `diag` lies
    /// outside the open range the crank can give `|AC|`.
    ///
    /// In the triangle `O A C` with sides `r`, `g`, `diag`, the angle at `O` is
    /// `atan2(4·Area, r² + g² − diag²)`: the area comes from [`triangle_area`], so the angle is
    /// accurate even at the toggle extremes where `acos` of a cosine near ±1 loses half its digits.
    ///
    /// `r`, `g` and `diag` are the crank, ground and diagonal in any common unit (the caller
    /// scales them by a power of two so that no square overflows).
    fn angle_for_diagonal(r: T, g: T, diag: T) -> Option<T> {
        if diag <= (g - r).abs() || diag >= g + r {
            return None;
        }
        let area = triangle_area(r, g, diag, T::zero()).ok()?;
        let adjacent = (r - diag) * (r + diag) + g * g;
        Some((lit::<T>(4.0) * area).atan2(adjacent))
    }

    /// The crank angles at which the linkage assembles, bounded by toggle positions where
    /// coupler and rocker are collinear (`|AC| = coupler + rocker` stretched, or
    /// `|coupler − rocker|` folded).
    ///
    /// The angles do not depend on the unit, so the lengths are first divided by a power of two
    /// near the longest (exact): lengths near the float maximum or minimum give the same range.
    pub fn input_range(&self) -> InputRange<T> {
        let (g, r, coupler, rocker) = self.scaled_lengths();
        let stretched = coupler + rocker;
        let folded = (coupler - rocker).abs();
        if stretched <= (g - r).abs() || folded >= g + r {
            return InputRange::Never;
        }
        let d = self.c - self.o;
        let base = d.y.atan2(d.x);
        let lo = Self::angle_for_diagonal(r, g, folded);
        let hi = Self::angle_for_diagonal(r, g, stretched);
        match (lo, hi) {
            (None, None) => InputRange::Full,
            (None, Some(h)) => InputRange::Between {
                lo: base - h,
                hi: base + h,
            },
            (Some(l), None) => InputRange::Between {
                lo: base + l,
                hi: base + T::two_pi() - l,
            },
            (Some(l), Some(h)) => InputRange::TwoIntervals {
                first: (base + l, base + h),
                second: (base - h, base - l),
            },
        }
    }

    /// The two Roberts–Chebyshev cognates: the other four-bars whose coupler point draws this
    /// one's coupler curve, placed in the same frame.
    ///
    /// With `z = (P − A)/(B − A)` (complex: the coupler triangle's shape), the third pivot is
    /// `D = O + z (C − O)` (triangle `O C D` similar to `A B P`). The first cognate turns about
    /// `O` and `D`: its crank `O → A₁ = z (B − A)` turns with this coupler, its coupler
    /// `A₁ → E₁ = z (A − O)` with this crank (`P = A₁ + (A − O)`), its rocker is
    /// `D → E₁ = z (B − C)`. The second turns about `C` and `D`: crank `C → B₂ = (z − 1)(B − A)`,
    /// coupler `B₂ → E₂ = (1 − z)(B − C)` (`P = B₂ + (B − C)`), rocker `D → E₂ = (1 − z)(A − O)`.
    /// Lengths are those of this linkage times `|z|` or `|1 − z|`; each cognate's assembly is
    /// the side its `B` is on in one assembled pose. A cognate's crank turns with another link
    /// of this one, so its Grashof class and input range are its own: a triple-rocker's curve
    /// may be drawn by a cognate whose crank turns fully (and the other way round).
    ///
    /// ```
    /// use linkage_core::{catalog, Assembly, FourBar, Vec2};
    /// let fb = catalog::hoecken::<f64>(); // a crank-rocker
    /// let [first, second] = fb.cognates().unwrap();
    /// assert_eq!((first.o, second.o), (fb.o, fb.c));
    /// assert_eq!(first.c, second.c); // the third pivot D
    /// // The same coupler curve: at θ the coupler point of `fb` is the first cognate's with its
    /// // crank O → A₁ parallel to P − A, the second's with C → B₂ parallel to P − B. (Their
    /// // cranks rock: the curve passes their toggles, so either assembly, as a circuit does.)
    /// let on = |cog: FourBar<f64>, angle: f64, p: Vec2<f64>| {
    ///     [Assembly::Open, Assembly::Crossed].into_iter().any(|assembly| {
    ///         let q = FourBar { assembly, ..cog }.pose(angle);
    ///         q.is_ok_and(|q| (q.coupler_point - p).norm() < 1e-12 * 100.0)
    ///     })
    /// };
    /// for k in 0..63 {
    ///     let p = fb.pose(k as f64 * 0.1).unwrap();
    ///     let (da, db) = (p.coupler_point - p.a, p.coupler_point - p.b);
    ///     assert!(on(first, da.y.atan2(da.x), p.coupler_point));
    ///     assert!(on(second, db.y.atan2(db.x), p.coupler_point));
    /// }
    /// ```
    ///
    /// A cognate's crank may rock over two intervals (a double-rocker): the curve is then drawn
    /// on the circuit of one of them, which need not be the first that
    /// [`FourBar::circuit`] traces; its crank angle at a pose of this linkage is `arg(P − A)`
    /// (first) or `arg(P − B)` (second).
    ///
    /// # Errors
    /// [`Error::CannotAssemble`] when the linkage never assembles; [`Error::Degenerate`] when
    /// the coupler point is at `A` or `B` (a cognate's link would have no length).
    pub fn cognates(&self) -> Result<[FourBar<T>; 2], Error> {
        let theta = self.assembled_angle();
        let p = self.pose(theta)?;
        let (o, c, a, b, pt) = (self.o, self.c, p.a, p.b, p.coupler_point);
        // Complex products and quotients on Vec2 (x + iy).
        let mul = |z: Vec2<T>, w: Vec2<T>| Vec2::new(z.x * w.x - z.y * w.y, z.x * w.y + z.y * w.x);
        // z = (P − A)/(B − A) = (along + i·left)/|AB|, exactly as the linkage is defined.
        let z = Vec2::new(self.along, self.left) / self.coupler;
        let one_minus_z = Vec2::new(T::one() - z.x, -z.y);
        if z == Vec2::zeros() || one_minus_z == Vec2::zeros() {
            return Err(Error::Degenerate {
                what: "coupler point at A or B: a cognate's link would have no length",
            });
        }
        let d = o + mul(z, c - o);
        let (u, v, w) = (a - o, b - a, b - c);
        let first = Self::from_points(o, d, o + mul(z, v), d + mul(z, w), pt)?;
        let second = Self::from_points(
            c,
            d,
            c + mul(Vec2::new(z.x - T::one(), z.y), v),
            d + mul(one_minus_z, u),
            pt,
        )?;
        Ok([first, second])
    }

    /// The same linkage driven at its rocker: crank pivot `C`, rocker pivot `O`, the coupler
    /// point unchanged (the crank and rocker lengths swap; the assembly is the side the old
    /// `A` is on in one assembled pose). A cognate that draws a curve with a rocking crank may
    /// draw it with a crank that turns fully this way round.
    ///
    /// A `FourBar` whose crank rocks does not say which of its circuits it is on (the
    /// assembly flips at each limit, and [`FourBar::circuit`] traces the first interval's):
    /// the pose taken here is the declared assembly's mid-range one, so reversing such a
    /// linkage twice may give the other circuit's assembly.
    ///
    /// ```
    /// use linkage_core::{catalog, GrashofClass};
    /// let fb = catalog::hoecken::<f64>();
    /// let [_, second] = fb.cognates().unwrap();
    /// assert_eq!(second.grashof(), GrashofClass::RockerCrank);
    /// let driven = second.reversed().unwrap();
    /// assert_eq!(driven.grashof(), GrashofClass::CrankRocker);
    /// assert_eq!((driven.o, driven.c, driven.crank), (second.c, second.o, second.rocker));
    /// ```
    ///
    /// # Errors
    /// [`Error::CannotAssemble`] when the linkage never assembles.
    pub fn reversed(&self) -> Result<FourBar<T>, Error> {
        let p = self.pose(self.assembled_angle())?;
        // The lengths swap exactly; P from B towards A: along `coupler − along`, left negated.
        // Driven at C, the new B is A.
        let assembly = Self::assembly_of(self.o - p.b, p.a - p.b);
        FourBar::with_pivots(
            self.c,
            self.o,
            self.rocker,
            self.coupler,
            self.crank,
            (self.coupler - self.along, -self.left),
            assembly,
        )
    }

    /// A crank angle at which the linkage assembles, away from flat positions: square to the
    /// ground line for a full turn (a change point is flat along it), else mid-range; when it
    /// never assembles, any (the pose then says by how much).
    fn assembled_angle(&self) -> T {
        let d = self.c - self.o;
        match self.input_range() {
            InputRange::Full | InputRange::Never => d.y.atan2(d.x) + T::frac_pi_2(),
            InputRange::Between { lo, hi } => (lo + hi) / lit::<T>(2.0),
            InputRange::TwoIntervals {
                first: (lo, hi), ..
            } => (lo + hi) / lit::<T>(2.0),
        }
    }

    /// The assembly that puts `B` where it is, from `A → C` and `A → B`: open when `B` is left
    /// of `A → C`. The sign is taken in units of a power of two near their size (exact), so it
    /// is right at any scale (the cross product of tiny vectors underflows to 0).
    pub(crate) fn assembly_of(to_c: Vec2<T>, to_b: Vec2<T>) -> Assembly {
        let big = to_c.amax().max(to_b.amax());
        let s = crate::numeric::pow2::pow2_scale(big);
        if cross(to_c / s, to_b / s) >= T::zero() {
            Assembly::Open
        } else {
            Assembly::Crossed
        }
    }

    /// The four-bar with crank pivot `o`, rocker pivot `c`, crank pin `a`, coupler–rocker joint
    /// `b` and coupler point `p` as placed (one pose): lengths, coupler point and assembly.
    ///
    /// The assembly is the side `B` is on as placed, except for a change point, whose declared
    /// assembly names the branch at its [`FourBar::start_angle`]: the side of `B` flips at each
    /// flat position between there and the placed crank angle `arg(a − o)`, so the assembly is
    /// the one whose tracked sweep ([`Tracker`], from the start angle) puts `B` where it is
    /// placed. (Taking the placed side alone built a parallelogram whose placed crank angle is
    /// past a flat position from its start angle on its antiparallelogram branch.)
    pub(crate) fn from_points(
        o: Vec2<T>,
        c: Vec2<T>,
        a: Vec2<T>,
        b: Vec2<T>,
        p: Vec2<T>,
    ) -> Result<FourBar<T>, Error> {
        // In units of a power of two near the linkage's size (exact), so the products below
        // neither overflow nor underflow at any scale.
        let big = [c - o, a - o, b - o, p - o]
            .iter()
            .fold(T::zero(), |m, v| m.max(v.amax()));
        let s = crate::numeric::pow2::pow2_scale(big);
        let (e, rel) = ((b - a) / s, (p - a) / s);
        let len = crate::numeric::scalar::length(e);
        let (along, left) = (
            (rel.x * e.x + rel.y * e.y) / len * s,
            cross(e, rel) / len * s,
        );
        let placed = FourBar::with_pivots(
            o,
            c,
            crate::numeric::scalar::length(a - o),
            len * s,
            crate::numeric::scalar::length(b - c),
            (along, left),
            Self::assembly_of(c - a, b - a),
        )?;
        if placed.start_angle().is_none() {
            return Ok(placed);
        }
        // A change point: track from the start angle to the placed crank angle and see which
        // side `B` arrives on. Where the sweep cannot get there, the placed side stands.
        let m = placed.mechanism();
        let mut joints = [Vec2::zeros(); 5];
        let theta = (a - o).y.atan2((a - o).x);
        let tracked = Tracker::new(&m)
            .and_then(|mut t| t.step(theta, None, &mut joints, Rates::none()))
            .map(|_| Self::assembly_of(c - joints[Self::A], joints[Self::B] - joints[Self::A]));
        match tracked {
            Ok(side) if side != placed.assembly => Ok(FourBar {
                assembly: match placed.assembly {
                    Assembly::Open => Assembly::Crossed,
                    Assembly::Crossed => Assembly::Open,
                },
                ..placed
            }),
            _ => Ok(placed),
        }
    }

    /// Transmission angle `μ ∈ [0, π]`: the angle at `B` between coupler and rocker. Force
    /// transmission is best at `μ = 90°` and fails at the toggles `μ = 0, π`. `None` when the
    /// linkage cannot assemble at `theta`.
    pub fn transmission_angle(&self, theta: T) -> Option<T> {
        let p = self.pose(theta).ok()?;
        let (ba, bc) = (p.a - p.b, self.c - p.b);
        // The angle does not depend on scale: bring both sides near unit size first (a power
        // of two, exact) so the products neither overflow nor underflow at extreme sizes.
        let s = crate::numeric::pow2::pow2_scale(ba.amax().max(bc.amax()));
        let (ba, bc) = (ba / s, bc / s);
        Some(cross(ba, bc).abs().atan2(ba.dot(&bc)))
    }

    /// The six instant centres at `theta` by the Aronhold–Kennedy construction, numbering the
    /// links 1 ground, 2 crank, 3 coupler, 4 rocker, in the order `I12, I13, I14, I23, I24, I34`.
    ///
    /// `I12 = O`, `I14 = C`, `I23 = A`, `I34 = B` are pins; by Kennedy's theorem `I13` lies on
    /// lines `I12 I23` and `I14 I34` (`OA ∩ CB`) and `I24` on `I23 I34` and `I12 I14`
    /// (`AB ∩ OC`). Parallel lines give a centre at infinity. `None` where it cannot assemble.
    pub fn instant_centres(&self, theta: T) -> Option<[Centre<T>; 6]> {
        let p = self.pose(theta).ok()?;
        let (o, c) = (self.o, self.c);
        Some([
            Centre::Finite(o),
            line_intersection(o, p.a - o, c, p.b - c),
            Centre::Finite(c),
            Centre::Finite(p.a),
            line_intersection(p.a, p.b - p.a, o, c - o),
            Centre::Finite(p.b),
        ])
    }

    /// Inflection circle and Ball point of the coupler at `theta` (see [`inflection`]), from
    /// rates per unit crank angle. `None` where it cannot assemble, within the rate margin of a
    /// toggle ([`crate::rate_margin`]: the rates are not known there), or when the coupler is
    /// instantaneously translating to rounding (its pole at infinity).
    pub fn coupler_inflection(&self, theta: T) -> Option<Inflection<T>> {
        let m = self.mechanism();
        let mut pos = [Vec2::zeros(); 5];
        let margin = m.pose(theta, &mut pos).ok()?;
        let (mut v, mut a, mut j) = ([Vec2::zeros(); 5], [Vec2::zeros(); 5], [Vec2::zeros(); 5]);
        if !m
            .rates(&pos, CrankRates::unit(), &mut v, Some(&mut a), Some(&mut j))
            .ok()?
        {
            return None;
        }
        let bodies = Bodies::of(&m);
        let coupler = BodyId {
            joint: Self::B,
            slot: 0,
        };
        inflection(&BodyMotion::of(&bodies, coupler, &pos, &v, &a, &j).conditioned(margin))
    }

    /// The `k`-th of `n` samples of a circuit sweep, and whether it is on the flipped branch.
    ///
    /// A full-turn crank sweeps `θ0 … θ0 + 2π` (from the ground direction) on the declared
    /// assembly. A limited crank goes limit to limit on the declared assembly and back on the
    /// other (`n/2` samples each way, both including the limits): the whole coupler curve of
    /// the circuit. Limited ranges are sampled at `lo + (hi − lo)(1 − cos πs)/2` for uniform
    /// `s`, which spaces the points evenly through the square-root motion at the toggles. For [`InputRange::TwoIntervals`], the `first` interval's circuit.
    /// `None` when `k ≥ n`, `n < 2`, or the linkage never assembles.
    pub fn circuit_sample(&self, k: usize, n: usize) -> Option<(T, bool)> {
        if k >= n || n < 2 {
            return None;
        }
        let d = self.c - self.o;
        let base = d.y.atan2(d.x);
        let at = |lo: T, hi: T, i: usize, m: usize| {
            if m <= 1 {
                lo
            } else {
                lo + (hi - lo) * lit::<T>(i as f64) / lit::<T>((m - 1) as f64)
            }
        };
        let (lo, hi) = match self.input_range() {
            InputRange::Never => return None,
            InputRange::Full => return Some((at(base, base + T::two_pi(), k, n), false)),
            InputRange::Between { lo, hi } => (lo, hi),
            InputRange::TwoIntervals { first, .. } => first,
        };
        // Near a toggle the coupler point moves as √(θ_lim − θ): spacing the angles as
        // (1 − cos πs)/2 in a uniform s makes θ_lim − θ ∝ s², so the points come out evenly
        // spaced instead of leaving a gap at each limit.
        let eased = |lo: T, hi: T, i: usize, m: usize| {
            let s = at(T::zero(), T::pi(), i, m);
            lo + (hi - lo) * (T::one() - s.cos()) * lit::<T>(0.5)
        };
        let half = n.div_ceil(2);
        if k < half {
            Some((eased(lo, hi, k, half), false))
        } else {
            Some((eased(hi, lo, k - half, n - half), true))
        }
    }

    /// Fills `theta` and `joints` (`n` and `5·n` long) with a circuit sweep (see
    /// [`FourBar::circuit_sample`]), tracking the branch and passing to the other one at the
    /// limit; `velocity` (`5·n`), if given, receives rates per unit crank angle. Samples that
    /// cannot assemble (rounding at a limit) are NaN; returns how many assembled.
    ///
    /// # Errors
    /// [`Error::BufferLength`] for mismatched slices; [`Error::CannotAssemble`] (joint 3) when
    /// the linkage never assembles.
    pub fn circuit(
        &self,
        theta: &mut [T],
        joints: &mut [Vec2<T>],
        velocity: Option<&mut [Vec2<T>]>,
    ) -> Result<usize, Error> {
        self.circuit_with_margin(theta, joints, velocity, None)
    }

    /// [`FourBar::circuit`], also writing each sample's assembly margin (`|sin γ|`, γ the
    /// transmission angle at `B`; NaN where the sample does not assemble) into `margin`
    /// (`n` long), if given.
    ///
    /// ```
    /// use linkage_core::{Assembly, FourBar, Vec2};
    /// let fb = FourBar::new(20.0_f64, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
    /// let (mut th, mut j, mut m) = ([0.0; 5], [Vec2::zeros(); 25], [0.0; 5]);
    /// fb.circuit_with_margin(&mut th, &mut j, None, Some(&mut m)).unwrap();
    /// // |sin γ| from the joints: the cross product of the unit links at B.
    /// let (ba, bc) = ((j[2] - j[3]) / 25.0, (j[1] - j[3]) / 25.0);
    /// assert!((m[0] - (ba.x * bc.y - ba.y * bc.x).abs()).abs() < 1e-15);
    /// ```
    ///
    /// # Errors
    /// As [`FourBar::circuit`]; [`Error::BufferLength`] for a `margin` of the wrong length.
    pub fn circuit_with_margin(
        &self,
        theta: &mut [T],
        joints: &mut [Vec2<T>],
        mut velocity: Option<&mut [Vec2<T>]>,
        mut margin: Option<&mut [T]>,
    ) -> Result<usize, Error> {
        let n = theta.len();
        if let Some(got) = margin.as_ref().map(|m| m.len()).filter(|&l| l != n) {
            return Err(Error::BufferLength {
                what: "margin",
                expected: n,
                got,
            });
        }
        let n5 = n.checked_mul(5).ok_or(Error::CountOverflow {
            what: "circuit samples",
        })?;
        for (what, got) in [
            ("joints", joints.len()),
            ("velocity", velocity.as_ref().map_or(n5, |v| v.len())),
        ] {
            if got != n5 {
                return Err(Error::BufferLength {
                    what,
                    expected: n5,
                    got,
                });
            }
        }
        if matches!(self.input_range(), InputRange::Never) {
            return Err(Error::CannotAssemble {
                joint: Self::B,
                gap: crate::numeric::scalar::to_f64(
                    ((self.ground() - self.crank).abs() - self.coupler - self.rocker)
                        .max((self.coupler - self.rocker).abs() - self.ground() - self.crank),
                ),
            });
        }
        let m = self.mechanism();
        let mut tracker = Tracker::new(&m)?;
        let mut flipped = false;
        let mut ok = 0;
        for k in 0..n {
            let (t, second) = self
                .circuit_sample(k, n)
                .unwrap_or((crate::numeric::scalar::nan::<T>(), false));
            if second && !flipped {
                let s = tracker.branch(Self::B);
                tracker.set_branch(Self::B, -s);
                flipped = true;
            }
            theta[k] = t;
            let out = &mut joints[5 * k..5 * k + 5];
            let rates = match velocity.as_deref_mut() {
                Some(v) => Rates::velocity(&mut v[5 * k..5 * k + 5]),
                None => Rates::none(),
            };
            let placed = tracker.step(t, Some(CrankRates::unit()), out, rates);
            if let Some(m) = margin.as_deref_mut() {
                m[k] = placed.map_or(crate::numeric::scalar::nan::<T>(), |s| s.margin);
            }
            ok += usize::from(placed.is_ok());
        }
        Ok(ok)
    }
}

/// The smallest transmission angle over a travel, folded to `[0, π/2]`, from the smallest sine
/// of it met there: `asin(min(max(s, 0), 1))`. The sine is what a sweep measures anyway, the
/// coupler–rocker dyad's assembly margin ([`crate::Sample::margin`], [`FourBarPose::margin`]),
/// so a travel keeps a running minimum of margins and takes one arcsine at the end. A margin
/// below 0 (a sample in the tracker's toggle band) is a transmission angle of 0, and so is NaN.
/// Burmester's and Freudenstein's checks and the gait figures all call this one function.
///
/// ```
/// use linkage_core::min_transmission_angle;
/// assert_eq!(min_transmission_angle(1.0_f64), core::f64::consts::FRAC_PI_2);
/// assert_eq!(min_transmission_angle(0.5_f64), 0.5_f64.asin());
/// assert_eq!(min_transmission_angle(-1e-9_f64), 0.0);
/// assert_eq!(min_transmission_angle(f64::NAN), 0.0);
/// ```
#[inline]
pub fn min_transmission_angle<T: RealField + Copy>(min_sine: T) -> T {
    min_sine.max(T::zero()).min(T::one()).asin()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A parallelogram's coupler translates: `P = A + (along, left)` exactly in the reals. At and
    /// next to both flat positions the pose (and so the tracker and the held pass, which share
    /// its vanishing factors) stays within a few ε of the size, also when `a + b` is not a float
    /// (2.3e-8 of the size at the stretched one when `Σ − g − r` was formed from a rounded `Σ`).
    #[test]
    fn parallelogram_flat_positions_keep_full_accuracy() {
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut unit = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut worst: f64 = 0.0;
        let mut inexact = 0;
        for _ in 0..500 {
            let (a, b) = (0.2 + 2.8 * unit(), 0.2 + 2.8 * unit());
            let (along, left) = (0.3, 0.7);
            if a + b - a != b {
                inexact += 1;
            }
            // The assembly that is the parallelogram with the crank up, swept by the tracker
            // (which stays on it through both flat positions) over angles around them.
            let want = |th: f64| Vec2::new(b * th.cos() + along, b * th.sin() + left);
            let up = core::f64::consts::FRAC_PI_2;
            let fb = [Assembly::Open, Assembly::Crossed]
                .map(|asm| FourBar::new(a, b, a, b, (along, left), asm).unwrap())
                .into_iter()
                .find(|fb| (fb.pose(up).unwrap().coupler_point - want(up)).norm() < 1e-9)
                .expect("one assembly is the parallelogram");
            let m = fb.mechanism();
            let mut tracker = Tracker::new(&m).unwrap();
            let mut j = [Vec2::zeros(); 5];
            let offsets = [-1e-4, -1e-8, -1e-12, 0.0, 1e-12, 1e-8, 1e-4];
            let flats = [0.0, core::f64::consts::PI];
            for th in flats.iter().flat_map(|&f| offsets.map(move |o| f + o)) {
                tracker.step(th, None, &mut j, Rates::none()).unwrap();
                let err = (j[FourBar::<f64>::P] - want(th)).norm() / a.max(b);
                assert!(
                    err <= 8.0 * f64::EPSILON,
                    "a = {a}, b = {b}, θ = {th:e}: {err:e} of the size"
                );
                worst = worst.max(err);
            }
        }
        assert!(
            inexact > 100,
            "too few cases with a + b not a float: {inexact}"
        );
        assert!(worst > 0.0, "no case was posed");
    }

    fn deg(x: f64) -> f64 {
        x.to_degrees()
    }

    #[test]
    fn classes_of_the_catalogue() {
        let fb = |g, a, b, c| FourBar::new(g, a, b, c, (0.0, 0.0), Assembly::Open).unwrap();
        for ((g, a, b, c), class) in [
            ((20.0, 10.0, 25.0, 25.0), GrashofClass::CrankRocker),
            ((20.0, 25.0, 10.0, 25.0), GrashofClass::DoubleRocker),
            ((40.0, 20.0, 10.0, 20.0), GrashofClass::TripleRocker),
            ((2.0, 3.0, 4.0, 3.5), GrashofClass::DoubleCrank),
            ((3.0, 1.0, 3.0, 1.0), GrashofClass::ChangePoint),
            ((3.0, 2.5, 4.0, 1.0), GrashofClass::RockerCrank),
        ] {
            assert_eq!(fb(g, a, b, c).grashof(), class, "links {g}, {a}, {b}, {c}");
        }
    }

    /// Evans linkages' input ranges: docs/domain.md (thesis 1 §1.4.3.6, after Norton) gives about
    /// 27°…333°, −81°…+81°, −75°…+75°.
    #[test]
    fn evans_input_limits_golden() {
        let evans = |g, a, b, c| FourBar::new(g, a, b, c, (0.0, 0.0), Assembly::Open).unwrap();
        match evans(12.0, 10.0, 16.0, 10.39).input_range() {
            InputRange::Between { lo, hi } => {
                assert!(
                    (deg(lo) - 27.0).abs() < 1.0 && (deg(hi) - 333.0).abs() < 1.0,
                    "Evans A input range {}°…{}° against 27°…333°",
                    deg(lo),
                    deg(hi)
                );
            }
            r => panic!("{r:?}"),
        }
        for ((g, b, c), lim) in [((23.05, 12.0, 11.67), 81.0), ((20.0, 10.0, 10.0), 75.0)] {
            match evans(g, 10.0, b, c).input_range() {
                InputRange::Between { lo, hi } => {
                    assert!((deg(hi) - lim).abs() < 0.6, "{}", deg(hi));
                    assert!(
                        (lo + hi).abs() < 1e-15,
                        "range {lo}…{hi} not symmetric for links {g}, 10, {b}, {c}"
                    );
                }
                r => panic!("{r:?}"),
            }
        }
        // Evans C in closed form: |AC|² = 500 − 400 cos θ = 20²  ⇒  θ = acos(1/4).
        match evans(20.0, 10.0, 10.0, 10.0).input_range() {
            InputRange::Between { hi, .. } => {
                assert!((hi - 0.25_f64.acos()).abs() < 1e-15, "{hi}");
            }
            r => panic!("Evans C should have a limited input range, got {r:?}"),
        }
    }

    #[test]
    fn limit_is_a_toggle_and_accurate_near_extreme() {
        // Near-degenerate: stretched toggle angle tiny (≈ 1e-6 rad), where acos would lose
        // half the digits. Reference from the law of cosines in high precision, expanded:
        // for g = 1, r = 1, the diagonal 2 sin(θ/2)... use sides so that θ = 2 asin(D/2).
        let theta_true = 2e-6_f64;
        let diag = 2.0 * (theta_true / 2.0).sin();
        let fb =
            FourBar::new(1.0, 1.0, diag / 2.0, diag / 2.0, (0.0, 0.0), Assembly::Open).unwrap();
        match fb.input_range() {
            InputRange::Between { hi, .. } => {
                assert!((hi - theta_true).abs() < 1e-15 * 100.0, "{hi}");
            }
            r => panic!("{r:?}"),
        }
        let fb = FourBar::new(23.05, 10.0, 12.0, 11.67, (15.0, 0.0), Assembly::Open).unwrap();
        match fb.input_range() {
            InputRange::Between { hi, .. } => {
                let p = fb.pose(hi).unwrap();
                assert!(p.margin < 1e-6, "margin {} at the limit", p.margin);
                let mu = fb.transmission_angle(hi).unwrap();
                assert!(
                    mu > core::f64::consts::PI - 1e-3,
                    "transmission angle {mu} at the limit {hi} (want a toggle, near π)"
                );
                assert!(fb.pose(hi + 1e-6).is_err(), "assembles past its limit");
            }
            r => panic!("Evans A should have a limited input range, got {r:?}"),
        }
    }

    #[test]
    fn circuit_of_triple_rocker_closes() {
        let fb = FourBar::new(20.0, 10.0, 10.0, 10.0, (20.0, 0.0), Assembly::Open).unwrap();
        let n = 400;
        let mut th = [0.0; 400];
        let mut j = [Vec2::zeros(); 2000];
        let ok = fb.circuit(&mut th, &mut j, None).unwrap();
        assert_eq!(ok, n, "samples the circuit filled");
        // Consecutive points close together (no branch jump), and the two halves meet.
        let p = |k: usize| j[5 * k + 4];
        let mut worst: f64 = 0.0;
        for k in 1..n {
            worst = worst.max((p(k) - p(k - 1)).norm());
        }
        assert!(worst < 2.5, "largest step {worst}");
        assert!(
            (p(0) - p(n - 1)).norm() < 1e-6,
            "circuit not closed: first {:?}, last {:?}",
            p(0),
            p(n - 1)
        );
        assert!(
            (p(n / 2 - 1) - p(n / 2)).norm() < 1e-6,
            "halves do not meet: {:?}, {:?}",
            p(n / 2 - 1),
            p(n / 2)
        );
    }
}
