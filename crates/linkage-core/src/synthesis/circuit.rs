//! A four-bar's coupler curve as one smooth closed circuit, for path synthesis: points by a
//! circuit parameter, the tracker's check that the circuit is what a driven linkage traces, and
//! the true distance from target points to the curve.
//!
//! # The circuit parameter
//! A circuit is parametrised by `s` (period `2π`). A crank that turns fully sweeps
//! `θ = β + s` (`β` the ground direction `O → C`) on the declared assembly. A crank limited to
//! `[lo, hi]` (for two intervals, the first, as [`FourBar::circuit`]) sweeps
//! `θ = (lo + hi)/2 − (hi − lo)/2·cos s`: from `lo` to `hi` on the declared assembly
//! (`0 ≤ s ≤ π`) and back on the other one (`π < s < 2π`). At a limit the coupler and rocker are
//! collinear and the two assemblies meet, and since `θ_lim − θ ∝ s²` there while the coupler
//! point moves as `√(θ_lim − θ)`, the point is a smooth function of `s` through the limits: a
//! least-squares fit may move target points across them.
//!
//! # Placed linkages
//! A synthesis candidate is a four-bar in the target's frame, [`PLACED_PARAMS`] numbers
//! `[ox, oy, cx, cy, crank, coupler, rocker, along, left]` plus its assembly
//! ([`CircuitPath::placed`]); [`path_errors`] and [`path_residuals`] measure many at once.

use alloc::vec::Vec;
use nalgebra::RealField;

use crate::error::Error;
use crate::linkages::fourbar::{Assembly, FourBar, InputRange};
use crate::mechanism::program::Mechanism;
use crate::numeric::pow2::pow2_scale;
use crate::numeric::scalar::{lit, to_f64, Vec2};
use crate::sweep::tracker::{Rates, Tracker};
use crate::synthesis::efd::{Efd, Normalisation};

/// Local minima of the polyline distance refined by [`Circuit::foot`].
#[doc(hidden)]
pub const FOOT_STARTS: usize = 4;

/// Quarter steps of the polyline [`Circuit::foot`] scans about each local minimum (five
/// steps) before its golden-section search.
const FOOT_SCAN: usize = 20;

/// Numbers of a placed four-bar: `[ox, oy, cx, cy, crank, coupler, rocker, along, left]`.
pub const PLACED_PARAMS: usize = 9;

/// How far target points are from a candidate's coupler curve (its whole circuit), in the
/// target's units.
///
/// ```
/// use linkage_core::{path_errors, Circuit, CircuitPath, FootSearch, PathError};
/// // Hoecken's linkage against two points of its own curve, and a linkage that never assembles.
/// let hoecken = [0.0, 0.0, 20.0, 0.0, 10.0, 25.0, 25.0, 50.0, 0.0];
/// let broken = [0.0, 0.0, 20.0, 0.0, 1.0, 2.0, 2.0, 0.0, 0.0];
/// let path = CircuitPath::placed(&hoecken, false).unwrap();
/// let targets = [path.point(0.5).unwrap(), path.point(2.0).unwrap()];
/// let (mut errors, mut feet) = ([PathError::nan(); 2], [0.0; 4]);
/// let params = [hoecken, broken].concat();
/// let (exact, closed, threads) = (FootSearch::Exact, false, 1);
/// let crossed = [false; 2];
/// path_errors(&params, &crossed, &targets, 256, exact, closed, threads, &mut errors, &mut feet)
///     .unwrap();
/// assert!(errors[0].max < 1e-9 && errors[0].rms < 1e-9);
/// assert!(errors[1].max.is_nan() && feet[2].is_nan());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathError<T> {
    /// Largest distance from a target point to the curve.
    pub max: T,
    /// Root-mean-square distance from the target points to the curve.
    pub rms: T,
    /// Largest distance from the curve (its polyline's vertices) back to the target polygon,
    /// for a closed target (NaN for an open one, which matches only a part of the circuit):
    /// `max(max, back)` bounds the Hausdorff distance up to the polyline's chord error.
    pub back: T,
}

impl<T: RealField + Copy> PathError<T> {
    /// All three NaN: the circuit does not assemble throughout.
    pub fn nan() -> Self {
        let n = crate::numeric::scalar::nan::<T>();
        PathError {
            max: n,
            rms: n,
            back: n,
        }
    }
}

/// How [`Circuit::errors`] finds each target point's nearest curve point.
///
/// ```
/// use linkage_core::{Circuit, CircuitPath, FootSearch};
/// let hoecken = [0.0, 0.0, 20.0, 0.0, 10.0, 25.0, 25.0, 50.0, 0.0];
/// let path = CircuitPath::placed(&hoecken, false).unwrap();
/// // Two points of the curve between the vertices of a 64-point polyline.
/// let on = [path.point(0.3).unwrap(), path.point(3.0).unwrap()];
/// let mut feet = [0.0; 2];
/// let exact = path.errors(&on, 64, FootSearch::Exact, false, &mut feet).unwrap();
/// let chord = path.errors(&on, 64, FootSearch::Polyline, false, &mut feet).unwrap();
/// assert!(exact.max < 1e-9 && chord.max > 100.0 * exact.max);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FootSearch {
    /// The nearest segment of the circuit's polyline (fast; a chord error of the order of the
    /// squared sample spacing).
    Polyline,
    /// The true nearest point ([`Circuit::foot`]: local minima of the polyline, refined
    /// by golden-section search on the curve).
    Exact,
}

/// Figures of a circuit over an arc `s_lo ≤ s ≤ s_hi` of its parameter
/// ([`Circuit::arc`]).
///
/// ```
/// use linkage_core::{catalog, Circuit, CircuitPath};
/// // Evans C's circuit: limit to limit on one assembly (0 ≤ s ≤ π), back on the other.
/// let c = CircuitPath::new(catalog::evans_c::<f64>()).unwrap();
/// let a = c.arc(0.5, 2.5, 32);
/// assert!(!a.through_limit && a.theta.0 < a.theta.1);
/// assert!(a.min_transmission > 0.0);
/// assert!(c.arc(2.5, 3.5, 32).through_limit);
/// // A crank that turns fully never meets a limit.
/// assert!(!CircuitPath::new(catalog::hoecken::<f64>()).unwrap().arc(0.0, 7.0, 64).through_limit);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcFigures<T> {
    /// Least and greatest crank angle over the arc (radians, absolute).
    pub theta: (T, T),
    /// Least distance of the transmission angle from a toggle, `min(μ, π − μ)`, over the arc
    /// (radians); `+∞` if no sample assembles.
    pub min_transmission: T,
    /// Whether the arc passes a crank limit (the crank must reverse there); never for a full
    /// turn.
    pub through_limit: bool,
}

/// A four-bar's circuit, parametrised as in the module.
///
/// ```
/// use linkage_core::{catalog, Assembly, Circuit, CircuitPath, Error, FourBar};
/// let c = CircuitPath::new(catalog::hoecken::<f64>()).unwrap();
/// assert!(c.full_turn() && c.limits.is_none());
/// c.check(64).unwrap(); // the tracker follows the circuit
/// // A linkage that never assembles has no circuit.
/// let never = FourBar::new(20.0_f64, 1.0, 2.0, 2.0, (0.0, 0.0), Assembly::Open).unwrap();
/// assert!(matches!(CircuitPath::new(never), Err(Error::CannotAssemble { joint: 3, .. })));
/// // A parallelogram's circuit crosses its flat positions, where the tracker switches branch.
/// let par = FourBar::new(3.0_f64, 1.0, 3.0, 1.0, (1.0, 1.0), Assembly::Open).unwrap();
/// assert!(CircuitPath::new(par).unwrap().check(256).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CircuitPath<T> {
    /// The linkage on its declared assembly.
    pub linkage: FourBar<T>,
    other: FourBar<T>,
    /// `Some((lo, hi))` for a limited crank, `None` for a full turn.
    pub limits: Option<(T, T)>,
    base: T,
}

impl<T: RealField + Copy> CircuitPath<T> {
    /// The circuit of `linkage`.
    ///
    /// # Errors
    /// [`Error::CannotAssemble`] (joint 3) when the linkage never assembles.
    pub fn new(linkage: FourBar<T>) -> Result<Self, Error> {
        let limits = match linkage.input_range() {
            InputRange::Never => {
                return Err(Error::CannotAssemble {
                    joint: FourBar::<T>::B,
                    gap: f64::NAN,
                })
            }
            InputRange::Full => None,
            InputRange::Between { lo, hi } => Some((lo, hi)),
            InputRange::TwoIntervals { first, .. } => Some(first),
        };
        let mut other = linkage;
        other.assembly = match linkage.assembly {
            Assembly::Open => Assembly::Crossed,
            Assembly::Crossed => Assembly::Open,
        };
        let d = linkage.c - linkage.o;
        Ok(CircuitPath {
            linkage,
            other,
            limits,
            base: d.y.atan2(d.x),
        })
    }

    /// The circuit of the placed four-bar `p = [ox, oy, cx, cy, crank, coupler, rocker, along,
    /// left]` on the given assembly.
    ///
    /// # Errors
    /// [`Error::BufferLength`] unless `p` holds [`PLACED_PARAMS`] numbers; the errors of
    /// [`FourBar::with_pivots`] and [`CircuitPath::new`].
    ///
    /// # Example
    /// ```
    /// use linkage_core::{Circuit, CircuitPath, FootSearch, Vec2};
    /// // Hoecken's straight-line linkage, ground from (0, 0) to (20, 0), foot 50 along the coupler.
    /// let path = CircuitPath::placed(&[0.0, 0.0, 20.0, 0.0, 10.0, 25.0, 25.0, 50.0, 0.0], false)?;
    /// assert!(path.full_turn());
    /// // Two points on the curve are at distance 0 from it, and their feet are themselves.
    /// let on = [path.point(1.0).unwrap(), path.point(4.0).unwrap()];
    /// let mut feet = [0.0; 2];
    /// let e = path.errors(&on, 512, FootSearch::Exact, false, &mut feet).unwrap();
    /// assert!(e.max < 1e-9 && (path.point(feet[1]).unwrap() - on[1]).norm() < 1e-9);
    /// // Fewer than two targets measure nothing.
    /// assert!(path.errors(&on[..1], 512, FootSearch::Exact, false, &mut feet[..1]).is_none());
    /// # Ok::<(), linkage_core::Error>(())
    /// ```
    pub fn placed(p: &[T], crossed: bool) -> Result<Self, Error> {
        if p.len() != PLACED_PARAMS {
            return Err(Error::BufferLength {
                what: "placed four-bar parameters",
                expected: PLACED_PARAMS,
                got: p.len(),
            });
        }
        let assembly = if crossed {
            Assembly::Crossed
        } else {
            Assembly::Open
        };
        let fb = FourBar::with_pivots(
            Vec2::new(p[0], p[1]),
            Vec2::new(p[2], p[3]),
            p[4],
            p[5],
            p[6],
            (p[7], p[8]),
            assembly,
        )?;
        CircuitPath::new(fb)
    }

    /// The two programs, for posing many points.
    fn programs(&self) -> Poser<'_, T> {
        Poser {
            path: self,
            mechs: [self.linkage.mechanism(), self.other.mechanism()],
        }
    }
}

/// Joint of a [`Circuit::program`] whose branch the circuit passes to the other at a crank
/// limit: a four-bar's `B` ([`FourBar::B`]), a slider-crank's slider.
#[doc(hidden)]
pub const BRANCH_JOINT: usize = 3;

/// Joint of a [`Circuit::program`] that traces the curve: the coupler point.
#[doc(hidden)]
pub const POINT_JOINT: usize = 4;

/// A one-degree-of-freedom linkage's circuit as a closed curve of the circuit parameter `s`
/// (period `2π`, as the module describes), and what path synthesis measures on it: points,
/// the true distance of targets to the curve ([`Circuit::foot`], [`Circuit::errors`]), the
/// least-squares residuals ([`Circuit::residuals`]), the tracker's check that the circuit is
/// what the driven linkage traces ([`Circuit::check`]) and the figures of an arc
/// ([`Circuit::arc`]). Implemented by the four-bar's [`CircuitPath`] and the slider-crank's
/// [`SliderCircuit`](crate::SliderCircuit); the provided methods are the one implementation of
/// that machinery.
///
/// A limited crank's circuit has its limits at `s = 0` and `s = π`, on the declared branch
/// for `0 ≤ s ≤ π` and on the other back.
///
/// ```
/// use linkage_core::{catalog, Circuit, CircuitPath, FootSearch};
/// let c = CircuitPath::new(catalog::hoecken::<f64>()).unwrap();
/// let p = c.point(1.0).unwrap();
/// let mut feet = [0.0; 2];
/// let e = c.errors(&[p, c.point(2.0).unwrap()], 128, FootSearch::Exact, false, &mut feet);
/// assert!(e.unwrap().max < 1e-9 && (feet[0] - 1.0).abs() < 1e-6);
/// ```
pub trait Circuit<T: RealField + Copy> {
    /// A function of `s` giving the coupler point (`None` where rounding at a limit leaves it
    /// unassembled), prepared once for many points.
    fn poser(&self) -> impl Fn(T) -> Option<Vec2<T>> + '_;

    /// Crank angle at circuit parameter `s` (absolute, radians), and whether it is on the other
    /// branch.
    fn theta(&self, s: T) -> (T, bool);

    /// Transmission angle's distance from a toggle at `s` (radians, `0 … π/2`; `None` where it
    /// does not assemble).
    fn transmission(&self, s: T) -> Option<T>;

    /// Whether the crank turns fully.
    fn full_turn(&self) -> bool;

    /// A length of the linkage's size (its largest length or pivot offset).
    fn size(&self) -> T;

    /// The linkage as a mechanism on its declared branch, joint [`BRANCH_JOINT`] the one whose
    /// branch changes at a crank limit, joint [`POINT_JOINT`] the coupler point.
    fn program(&self) -> Mechanism<T, 5>;

    /// Coupler point at circuit parameter `s`; `None` where rounding at a limit leaves it
    /// unassembled.
    fn point(&self, s: T) -> Option<Vec2<T>> {
        self.poser()(s)
    }

    /// Sweeps the circuit with the [`Tracker`] (`n` samples at `s = 2πk/n`, passing to the other
    /// branch after the upper limit, as [`FourBar::circuit`] does) and checks that each
    /// tracked coupler point is [`Circuit::point`]: the circuit is one branch of the driven
    /// linkage, never switched at a flat position or lost.
    ///
    /// # Errors
    /// [`Error::CannotAssemble`] at a sample that does not assemble; [`Error::ToggleOnPath`]
    /// (its crank angle) where the tracked point leaves the circuit's (a branch switch);
    /// [`Error::BufferLength`] for `n < 4`.
    fn check(&self, n: usize) -> Result<(), Error> {
        if n < 4 {
            return Err(Error::BufferLength {
                what: "check samples",
                expected: 4,
                got: n,
            });
        }
        let m = self.program();
        let mut tracker = Tracker::new(&m)?;
        let mut joints = [Vec2::zeros(); 5];
        let size = self.size();
        let tol = lit::<T>(1e-9) * size;
        let limit_tol = crate::numeric::scalar::eps::<T>().sqrt() * lit::<T>(64.0) * size;
        let mut flipped = false;
        let poser = self.poser();
        for k in 0..n {
            let s = T::two_pi() * lit::<T>(k as f64) / lit::<T>(n as f64);
            let (theta, other) = self.theta(s);
            if other && !flipped {
                let b = tracker.branch(BRANCH_JOINT);
                tracker.set_branch(BRANCH_JOINT, -b);
                flipped = true;
            }
            tracker.step(theta, None, &mut joints, Rates::none())?;
            let want = poser(s).ok_or(Error::CannotAssemble {
                joint: BRANCH_JOINT,
                gap: 0.0,
            })?;
            // At a crank limit (s = 0, π of a limited crank) the two branches meet, and a
            // mechanism's pose there keeps only √ε of the size (the half chord is the root of a
            // difference that rounding leaves at ε): no switch is possible, only that noise.
            let at_limit = !self.full_turn() && (k == 0 || 2 * k == n);
            let tol = if at_limit { limit_tol } else { tol };
            if (joints[POINT_JOINT] - want).norm() > tol {
                return Err(Error::ToggleOnPath {
                    angle: to_f64(theta),
                });
            }
        }
        Ok(())
    }

    /// `m` points of the circuit at `s = 2πk/m` (NaN where a sample does not assemble).
    ///
    /// # Panics
    /// When `m` points cannot be allocated: more bytes than `isize::MAX` panics (capacity
    /// overflow), like any `Vec` of that length.
    fn polyline(&self, m: usize) -> Vec<Vec2<T>> {
        let poser = self.poser();
        let nan = crate::numeric::scalar::nan::<T>();
        (0..m)
            .map(|k| {
                let s = T::two_pi() * lit::<T>(k as f64) / lit::<T>(m as f64);
                poser(s).unwrap_or(Vec2::new(nan, nan))
            })
            .collect()
    }

    /// The normalisation frame ([`Efd::normalised`]) of the circuit's curve sampled at
    /// `samples` points (at least 8) with `harmonics` harmonics: the similarity an atlas
    /// entry's shape is matched in.
    ///
    /// # Errors
    /// As [`Efd::closed`] and [`Efd::normalised`] (an unassembled sample is not finite).
    ///
    /// # Panics
    /// As [`Circuit::polyline`] of `samples` points.
    fn normalisation(&self, samples: usize, harmonics: usize) -> Result<Normalisation<T>, Error> {
        let poly = self.polyline(samples.max(8));
        Ok(Efd::closed(&poly, harmonics)?.normalised()?.1)
    }

    /// True distance from `target` to the circuit's curve and the circuit parameter of the
    /// nearest point: the vertices of `poly` (from [`Circuit::polyline`]) nearest `target`
    /// by vertex or segment distance are found among the local minima along the polyline; about
    /// each of the best [`FOOT_STARTS`] the curve is sampled at a quarter of the polyline's step
    /// over five steps and a golden-section search of `|P(s) − target|` runs within a quarter
    /// step of the best sample (where the curve crosses itself or passes close by itself the
    /// nearest vertex may lie on the wrong pass, and two passes may lie within one step). `None` when `poly` has no finite point.
    fn foot(&self, target: Vec2<T>, poly: &[Vec2<T>]) -> Option<(T, T)> {
        let m = poly.len();
        let poser = self.poser();
        let finite = |p: &Vec2<T>| p.x.is_finite() && p.y.is_finite();
        let big = T::max_value().unwrap_or(T::one());
        // Distance of each segment j → j+1 (the vertex's own where the next is not finite).
        let seg = |j: usize| -> T {
            let (p, q) = (&poly[j], &poly[(j + 1) % m]);
            if !finite(p) {
                return big;
            }
            if !finite(q) {
                return (p - target).norm();
            }
            segment_distance(target, *p, *q)
        };
        let d: Vec<T> = (0..m).map(seg).collect();
        let mut starts: [(usize, T); FOOT_STARTS] = [(usize::MAX, big); FOOT_STARTS];
        for j in 0..m {
            let (prev, next) = (d[(j + m - 1) % m], d[(j + 1) % m]);
            if d[j] < big && d[j] <= prev && d[j] <= next {
                // Insert into the short sorted list of the best local minima.
                if let Some(at) = starts.iter().position(|&(_, b)| d[j] < b) {
                    starts[at..].rotate_right(1);
                    starts[at] = (j, d[j]);
                }
            }
        }
        if starts[0].0 == usize::MAX {
            return None;
        }
        let step = T::two_pi() / lit::<T>(m as f64);
        let mut best = (big, T::zero());
        for &(j, _) in starts.iter().filter(|s| s.0 != usize::MAX) {
            let centre = step * lit::<T>(j as f64);
            if finite(&poly[j]) {
                let dv = (poly[j] - target).norm();
                if dv < best.0 {
                    best = (dv, centre);
                }
            }
            // The curve between the polyline's vertices may pass the target twice within a
            // step (a loop or a near cusp): sample [−2, +3] steps at a quarter step and run a
            // golden-section search within a quarter step of every local minimum of the samples
            // (a sharp pass through the target can sample worse than a broad near miss).
            let (a, h) = (centre - step - step, step / lit::<T>(4.0));
            let mut dk = [big; FOOT_SCAN + 1];
            for (k, d) in dk.iter_mut().enumerate() {
                if let Some(p) = poser(a + h * lit::<T>(k as f64)) {
                    *d = (p - target).norm();
                }
            }
            for k in 0..=FOOT_SCAN {
                let prev = if k == 0 { big } else { dk[k - 1] };
                let next = if k == FOOT_SCAN { big } else { dk[k + 1] };
                if dk[k] >= big || dk[k] > prev || dk[k] > next {
                    continue;
                }
                let mid = a + h * lit::<T>(k as f64);
                let (dg, sg) = golden(&poser, target, mid - h, mid + h);
                for (dc, sc) in [(dk[k], mid), (dg, sg)] {
                    if dc < best.0 {
                        best = (dc, sc);
                    }
                }
            }
        }
        Some(best)
    }

    /// Residuals `P(sᵢ) − targetᵢ` of target points at circuit parameters `s` (NaN where a
    /// sample does not assemble): the least-squares fit's residuals. At a fit's optimum each
    /// `|P(sᵢ) − targetᵢ|` is the true point-to-curve distance.
    ///
    /// # Errors
    /// [`Error::BufferLength`] unless `s` and `out` have one entry per target.
    fn residuals(&self, targets: &[Vec2<T>], s: &[T], out: &mut [Vec2<T>]) -> Result<(), Error> {
        for (what, got) in [("circuit parameters", s.len()), ("residuals", out.len())] {
            if got != targets.len() {
                return Err(Error::BufferLength {
                    what,
                    expected: targets.len(),
                    got,
                });
            }
        }
        let (nan, poser) = (crate::numeric::scalar::nan::<T>(), self.poser());
        for ((r, &t), &si) in out.iter_mut().zip(targets).zip(s) {
            *r = poser(si).map_or(Vec2::new(nan, nan), |q| q - t);
        }
        Ok(())
    }

    /// Distances between target points and the circuit's curve, sampled by a `samples`-point
    /// polyline: [`PathError`], and in `feet` each target's circuit parameter of its nearest
    /// curve point. `closed` says whether the targets go round a closed curve (for
    /// [`PathError::back`]).
    ///
    /// `None` when the circuit has an unassembled sample, `samples < 8`, fewer than two
    /// targets, or `feet` is not one per target.
    ///
    /// # Panics
    /// As [`Circuit::polyline`] of `samples` points.
    fn errors(
        &self,
        targets: &[Vec2<T>],
        samples: usize,
        search: FootSearch,
        closed: bool,
        feet: &mut [T],
    ) -> Option<PathError<T>> {
        if samples < 8 || targets.len() < 2 || feet.len() != targets.len() {
            return None;
        }
        let poly = self.polyline(samples);
        if poly.iter().any(|q| !(q.x.is_finite() && q.y.is_finite())) {
            return None;
        }
        let m = poly.len();
        let step = T::two_pi() / lit::<T>(m as f64);
        let (mut worst, mut sum) = (T::zero(), T::zero());
        let curve = Segments::closed(&poly);
        for (&q, foot) in targets.iter().zip(feet.iter_mut()) {
            let d = match search {
                FootSearch::Exact => {
                    let (d, s) = self.foot(q, &poly)?;
                    *foot = s;
                    d
                }
                FootSearch::Polyline => {
                    let (d2, k) = curve.nearest(q);
                    *foot = step * lit::<T>(k as f64);
                    d2.sqrt()
                }
            };
            worst = worst.max(d);
            sum += d * d;
        }
        let n = targets.len();
        // The curve back to the target polygon: only for a closed target (an open one matches
        // a part of the circuit, whose other parts are no error).
        let back = if closed {
            let target = Segments::closed(targets);
            poly.iter()
                .map(|&q| target.nearest(q).0)
                .fold(T::zero(), |a, b| a.max(b))
                .sqrt()
        } else {
            crate::numeric::scalar::nan::<T>()
        };
        Some(PathError {
            max: worst,
            rms: (sum / lit::<T>(n as f64)).sqrt(),
            back,
        })
    }

    /// Crank interval, least transmission angle and whether a limit is passed, over the arc
    /// `s_lo ≤ s ≤ s_hi` sampled at `samples + 1` evenly spaced parameters (at least 2).
    fn arc(&self, s_lo: T, s_hi: T, samples: usize) -> ArcFigures<T> {
        let k = samples.max(1);
        let big = T::max_value().unwrap_or(T::one());
        let (mut lo, mut hi, mut mu) = (big, -big, big);
        for i in 0..=k {
            let s = s_lo + (s_hi - s_lo) * lit::<T>(i as f64) / lit::<T>(k as f64);
            let (theta, _) = self.theta(s);
            lo = lo.min(theta);
            hi = hi.max(theta);
            if let Some(m) = self.transmission(s) {
                mu = mu.min(m);
            }
        }
        // A limited circuit's crank limits are at s = 0 and π (mod 2π).
        let through_limit = !self.full_turn() && {
            let first = (s_lo / T::pi()).floor() + T::one();
            first * T::pi() < s_hi
        };
        ArcFigures {
            theta: (lo, hi),
            min_transmission: mu,
            through_limit,
        }
    }
}

/// Golden-section search of `|P(s) − target|` over `[a, b]`: `(distance, s)`.
fn golden<T: RealField + Copy>(
    poser: &impl Fn(T) -> Option<Vec2<T>>,
    target: Vec2<T>,
    mut a: T,
    mut b: T,
) -> (T, T) {
    let dist = |s: T| poser(s).map_or(T::max_value().unwrap_or(T::one()), |p| (p - target).norm());
    let g = lit::<T>(0.618_033_988_749_894_8);
    let (mut x1, mut x2) = (b - g * (b - a), a + g * (b - a));
    let (mut f1, mut f2) = (dist(x1), dist(x2));
    // 48 golden steps shrink the bracket (half a polyline step) by 0.618⁴⁸ ≈ 1e-10.
    for _ in 0..48 {
        if f1 < f2 {
            b = x2;
            (x2, f2) = (x1, f1);
            x1 = b - g * (b - a);
            f1 = dist(x1);
        } else {
            a = x1;
            (x1, f1) = (x2, f2);
            x2 = a + g * (b - a);
            f2 = dist(x2);
        }
    }
    if f1 < f2 {
        (f1, x1)
    } else {
        (f2, x2)
    }
}

impl<T: RealField + Copy> Circuit<T> for CircuitPath<T> {
    fn poser(&self) -> impl Fn(T) -> Option<Vec2<T>> + '_ {
        let p = self.programs();
        move |s| p.point(s)
    }

    fn theta(&self, s: T) -> (T, bool) {
        match self.limits {
            None => (self.base + s, false),
            Some((lo, hi)) => {
                let half = lit::<T>(0.5);
                let theta = (lo + hi) * half - (hi - lo) * half * s.cos();
                (theta, s.sin() < T::zero())
            }
        }
    }

    fn transmission(&self, s: T) -> Option<T> {
        let (theta, other) = self.theta(s);
        let fb = if other { &self.other } else { &self.linkage };
        fb.transmission_angle(theta).map(|mu| mu.min(T::pi() - mu))
    }

    fn full_turn(&self) -> bool {
        self.limits.is_none()
    }

    fn size(&self) -> T {
        let f = &self.linkage;
        f.crank
            .max(f.coupler)
            .max(f.rocker)
            .max(f.ground())
            .max(f.along.abs())
            .max(f.left.abs())
    }

    fn program(&self) -> Mechanism<T, 5> {
        self.linkage.mechanism()
    }
}

/// A circuit's two programs built once, for many points.
struct Poser<'a, T: RealField + Copy> {
    path: &'a CircuitPath<T>,
    mechs: [Mechanism<T, 5>; 2],
}

impl<T: RealField + Copy> Poser<'_, T> {
    /// [`Circuit::point`].
    fn point(&self, s: T) -> Option<Vec2<T>> {
        let (theta, other) = self.path.theta(s);
        let mut joints = [Vec2::zeros(); 5];
        self.mechs[usize::from(other)]
            .pose(theta, &mut joints)
            .ok()
            .map(|_| joints[FourBar::<T>::P])
    }
}

/// The segments of a closed polygon, each with the reciprocal of its squared length, for
/// nearest-point queries (one division a segment, not one a query).
struct Segments<T> {
    a: Vec<Vec2<T>>,
    ab: Vec<Vec2<T>>,
    inv: Vec<T>,
}

impl<T: RealField + Copy> Segments<T> {
    /// The polygon through `p` closed back to its first point.
    fn closed(p: &[Vec2<T>]) -> Self {
        let m = p.len();
        let ab: Vec<Vec2<T>> = (0..m).map(|k| p[(k + 1) % m] - p[k]).collect();
        let inv = ab
            .iter()
            .map(|d| {
                let l2 = d.norm_squared();
                if l2 > T::zero() {
                    T::one() / l2
                } else {
                    T::zero()
                }
            })
            .collect();
        Segments {
            a: p.to_vec(),
            ab,
            inv,
        }
    }

    /// The least squared distance from `q` to a segment, and that segment's index.
    fn nearest(&self, q: Vec2<T>) -> (T, usize) {
        let mut best = (T::max_value().unwrap_or(T::one()), 0usize);
        for (k, ((&a, &ab), &inv)) in self.a.iter().zip(&self.ab).zip(&self.inv).enumerate() {
            let w = q - a;
            let u = (w.dot(&ab) * inv).max(T::zero()).min(T::one());
            let d2 = (w - ab * u).norm_squared();
            if d2 < best.0 {
                best = (d2, k);
            }
        }
        best
    }
}

/// Distance from `p` to the segment `a b`.
fn segment_distance<T: RealField + Copy>(p: Vec2<T>, a: Vec2<T>, b: Vec2<T>) -> T {
    let ab = b - a;
    let l2 = ab.norm_squared();
    let u = if l2 > T::zero() {
        ((p - a).dot(&ab) / l2).max(T::zero()).min(T::one())
    } else {
        T::zero()
    };
    (a + ab * u - p).norm()
}

/// Places an atlas entry in a target's frame: the entry's linkage (ground pivots `(0, 0)` and
/// `(1, 0)`; `entry` its `[crank, coupler, rocker, along, left]`) moved by the similarity that
/// takes its curve's normalisation frame `curve` onto the target's `target` — scaled by
/// `target.scale / curve.scale`, turned by `target.rotation − curve.rotation` (plus `π` with
/// `flip`: the other end of the first harmonic's major axis), `curve.centre` onto
/// `target.centre`. Returns the [`PLACED_PARAMS`] numbers of [`CircuitPath::placed`].
///
/// ```
/// use linkage_core::{place_entry, Normalisation, Vec2};
/// let frame = |cx, cy, scale, rotation| Normalisation {
///     centre: Vec2::new(cx, cy),
///     scale,
///     rotation,
///     start: 0.0,
/// };
/// // The curve's frame at the origin, unit size; the target's twice as large, turned a quarter
/// // turn, centred at (5, 0): pivot (1, 0) lands at (5, 2), every length doubles.
/// let entry = [0.5, 2.0, 1.5, 1.0, 0.25];
/// let (curve, target) = (frame(0.0, 0.0, 1.0, 0.0), frame(5.0, 0.0, 2.0, std::f64::consts::FRAC_PI_2));
/// let p = place_entry(&entry, &curve, &target, false);
/// let want = [5.0, 0.0, 5.0, 2.0, 1.0, 4.0, 3.0, 2.0, 0.5];
/// assert!(p.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-15));
/// ```
#[doc(hidden)]
pub fn place_entry<T: RealField + Copy>(
    entry: &[T; 5],
    curve: &Normalisation<T>,
    target: &Normalisation<T>,
    flip: bool,
) -> [T; PLACED_PARAMS] {
    let (k, _, moved) = similarity(curve, target, flip);
    let (o, g) = (moved(Vec2::zeros()), moved(Vec2::new(T::one(), T::zero())));
    let [r, b, rk, along, left] = *entry;
    [
        o.x,
        o.y,
        g.x,
        g.y,
        k * r,
        k * b,
        k * rk,
        k * along,
        k * left,
    ]
}

/// The similarity that takes a curve's normalisation frame `curve` onto a target's `target`
/// (with `flip`, turned by `π` more: the other end of the first harmonic's major axis): its
/// scale, its turn and the map itself.
pub(crate) fn similarity<T: RealField + Copy>(
    curve: &Normalisation<T>,
    target: &Normalisation<T>,
    flip: bool,
) -> (T, T, impl Fn(Vec2<T>) -> Vec2<T>) {
    let k = target.scale / curve.scale;
    let turn = target.rotation - curve.rotation + if flip { T::pi() } else { T::zero() };
    let (s, c) = turn.sin_cos();
    let (from, to) = (curve.centre, target.centre);
    let moved = move |p: Vec2<T>| {
        let d = p - from;
        to + Vec2::new(c * d.x - s * d.y, s * d.x + c * d.y) * k
    };
    (k, turn, moved)
}

/// The distance from each of `points` to the polyline through `path` into `out`: a sample
/// that is not finite breaks the polyline (no segment is drawn across it), and a finite sample
/// between two that are not counts as a point. Infinity where `path` has no finite sample.
///
/// ```
/// use linkage_core::{polyline_distances, Vec2};
/// let nan = f64::NAN;
/// let path = [Vec2::new(0.0, 0.0), Vec2::new(2.0, 0.0), Vec2::new(nan, nan), Vec2::new(2.0, 2.0)];
/// let points = [Vec2::new(1.0, 1.0), Vec2::new(2.0, 1.5), Vec2::new(-3.0, 4.0)];
/// let mut d = [0.0; 3];
/// polyline_distances(&points, &path, &mut d).unwrap();
/// // (1, 1) is 1 above the first segment; (2, 1.5) is nearest the lone point (2, 2), not a
/// // segment across the gap; (−3, 4) is 5 from (0, 0).
/// assert_eq!(d, [1.0, 0.5, 5.0]);
/// ```
///
/// # Errors
/// [`Error::BufferLength`] when `out` is not as long as `points`.
pub fn polyline_distances<T: RealField + Copy>(
    points: &[Vec2<T>],
    path: &[Vec2<T>],
    out: &mut [T],
) -> Result<(), Error> {
    if out.len() != points.len() {
        return Err(Error::BufferLength {
            what: "polyline distances",
            expected: points.len(),
            got: out.len(),
        });
    }
    let finite = |p: &Vec2<T>| p.x.is_finite() && p.y.is_finite();
    // Distances are formed about the path's first finite sample, in units of a power of two
    // near the largest offset from it (exact, and 1 at ordinary sizes): no square overflows or
    // underflows at extreme scales.
    let origin = path
        .iter()
        .copied()
        .find(finite)
        .unwrap_or_else(Vec2::zeros);
    let extent = path
        .iter()
        .chain(points)
        .filter(|p| finite(p))
        .map(|p| (p.x - origin.x).abs().max((p.y - origin.y).abs()))
        .fold(T::zero(), |m, v| if v > m { v } else { m });
    let unit = pow2_scale(extent);
    let local = |p: Vec2<T>| {
        if unit == T::one() {
            p
        } else {
            (p - origin) / unit
        }
    };
    for (q, d) in points.iter().zip(out.iter_mut()) {
        let mut best = T::max_value().unwrap_or(T::one());
        let mut any = false;
        let q = local(*q);
        for (k, &a) in path.iter().enumerate() {
            if !finite(&a) {
                continue;
            }
            any = true;
            // The segment to the next sample when it is finite, else the point itself.
            let b = path.get(k + 1).filter(|b| finite(b)).copied().unwrap_or(a);
            best = best.min(segment_distance(q, local(a), local(b)));
        }
        *d = if any {
            best * unit
        } else {
            T::max_value().map_or(T::one() / T::zero(), |m| m * lit::<T>(2.0))
        };
    }
    Ok(())
}

/// The distance from each of `points` to its own polyline into `out`: `paths` holds
/// `points.len()` polylines of `stride` samples each, point `k`'s from sample `k·stride`, each
/// measured as [`polyline_distances`] measures (a sample that is not finite breaks it;
/// infinity for a polyline with no finite sample).
///
/// ```
/// use linkage_core::{polyline_distances_each, Vec2};
/// // Two points, each against its own two-sample polyline.
/// let paths = [
///     Vec2::new(0.0, 0.0), Vec2::new(2.0, 0.0), // the first point's
///     Vec2::new(5.0, 5.0), Vec2::new(5.0, 9.0), // the second's
/// ];
/// let points = [Vec2::new(1.0, 1.0), Vec2::new(2.0, 6.0)];
/// let mut d = [0.0; 2];
/// polyline_distances_each(&points, &paths, 2, &mut d).unwrap();
/// assert_eq!(d, [1.0, 3.0]);
/// ```
///
/// # Errors
/// [`Error::BufferLength`] when `paths` is not `points.len() × stride` long or `out` not as
/// long as `points`.
pub fn polyline_distances_each<T: RealField + Copy>(
    points: &[Vec2<T>],
    paths: &[Vec2<T>],
    stride: usize,
    out: &mut [T],
) -> Result<(), Error> {
    let expected = points.len().saturating_mul(stride);
    if paths.len() != expected || stride == 0 {
        return Err(Error::BufferLength {
            what: "polylines (points × stride)",
            expected,
            got: paths.len(),
        });
    }
    if out.len() != points.len() {
        return Err(Error::BufferLength {
            what: "polyline distances",
            expected: points.len(),
            got: out.len(),
        });
    }
    for ((q, path), d) in points
        .iter()
        .zip(paths.chunks_exact(stride))
        .zip(out.chunks_exact_mut(1))
    {
        polyline_distances(core::slice::from_ref(q), path, d)?;
    }
    Ok(())
}

/// The circuit-parameter arc `(start, end)` (`end` in `[start, start + 2π)`) that holds every
/// finite one of `feet` (circuit parameters, any turn): the complement of the largest gap
/// between them around the circle. `None` when none is finite.
///
/// ```
/// use linkage_core::covering_arc;
/// // Feet at 6.0, 0.1 and 0.5: the arc runs from 6.0 across 2π to 0.5 (+ 2π).
/// let (start, end) = covering_arc(&[0.1, 6.0, 0.5 + 4.0 * std::f64::consts::PI]).unwrap();
/// assert!((start - 6.0).abs() < 1e-12 && (end - (0.5 + std::f64::consts::TAU)).abs() < 1e-12);
/// assert_eq!(covering_arc(&[f64::NAN]), None);
/// ```
#[doc(hidden)]
pub fn covering_arc<T: RealField + Copy>(feet: &[T]) -> Option<(T, T)> {
    let tau = T::two_pi();
    let wrap = |s: T| {
        let r = s % tau;
        if r < T::zero() {
            r + tau
        } else {
            r
        }
    };
    // The largest gap between neighbours on the circle, the feet sorted once.
    let mut s: Vec<T> = feet
        .iter()
        .copied()
        .filter(|f| f.is_finite())
        .map(wrap)
        .collect();
    if s.is_empty() {
        return None;
    }
    s.sort_by(|a, b| a.partial_cmp(b).unwrap_or(core::cmp::Ordering::Equal));
    let n = s.len();
    let (mut gap, mut at) = (s[0] + tau - s[n - 1], n - 1);
    for k in 0..n - 1 {
        if s[k + 1] - s[k] > gap {
            (gap, at) = (s[k + 1] - s[k], k);
        }
    }
    let start = s[(at + 1) % n];
    let mut end = s[at];
    if end < start {
        end += tau;
    }
    Some((start, end))
}

/// Checks `M` placed four-bars: `params` rows of [`PLACED_PARAMS`], one `crossed` flag each.
fn placed_rows(params: &[f64], crossed: &[bool]) -> Result<usize, Error> {
    let m = crossed.len();
    let expected = m.saturating_mul(PLACED_PARAMS);
    if params.len() != expected {
        return Err(Error::BufferLength {
            what: "placed four-bar parameters",
            expected,
            got: params.len(),
        });
    }
    Ok(m)
}

/// `m·n`, the length of a `(linkages, targets)` output.
fn rows_times(m: usize, n: usize) -> Result<usize, Error> {
    m.checked_mul(n).ok_or(Error::CountOverflow {
        what: "linkages × targets",
    })
}

/// [`Circuit::errors`] of `M` placed four-bars (`params` rows of [`PLACED_PARAMS`], one
/// `crossed` flag each) against the same targets, on `threads` threads (the same bits for any
/// count): `errors[i]` (NaN for a linkage that cannot be built or whose circuit does not
/// assemble throughout) and `feet[i·n .. (i+1)·n]`.
///
/// # Errors
/// [`Error::BufferLength`] for buffers of the wrong length, fewer than two targets or fewer
/// than 8 samples; [`Error::CountOverflow`] when `M·n` overflows `usize`.
///
/// # Panics
/// As [`Circuit::polyline`] of `samples` points.
#[allow(
    clippy::too_many_arguments,
    reason = "the batch's inputs, its two outputs and the search settings"
)]
pub fn path_errors(
    params: &[f64],
    crossed: &[bool],
    targets: &[Vec2<f64>],
    samples: usize,
    search: FootSearch,
    closed: bool,
    threads: usize,
    errors: &mut [PathError<f64>],
    feet: &mut [f64],
) -> Result<(), Error> {
    let m = placed_rows(params, crossed)?;
    let build = |i: usize| {
        CircuitPath::placed(
            &params[PLACED_PARAMS * i..PLACED_PARAMS * (i + 1)],
            crossed[i],
        )
        .ok()
    };
    let settings = (samples, search, closed, threads);
    errors_of(m, build, targets, settings, errors, feet)
}

/// [`path_errors`] of `m` circuits, `build(i)` the `i`-th (`None`: NaN errors): the one
/// implementation for every kind of linkage. `settings` are `(samples, search, closed,
/// threads)`.
pub(crate) fn errors_of<C: Circuit<f64>>(
    m: usize,
    build: impl Fn(usize) -> Option<C> + Sync,
    targets: &[Vec2<f64>],
    settings: (usize, FootSearch, bool, usize),
    errors: &mut [PathError<f64>],
    feet: &mut [f64],
) -> Result<(), Error> {
    let (samples, search, closed, threads) = settings;
    let n = targets.len();
    let mn = rows_times(m, n)?;
    for (what, expected, got, short) in [
        ("targets (at least)", 2, n, n < 2),
        ("samples (at least)", 8, samples, samples < 8),
        ("errors", m, errors.len(), errors.len() != m),
        ("feet", mn, feet.len(), feet.len() != mn),
    ] {
        if short {
            return Err(Error::BufferLength {
                what,
                expected,
                got,
            });
        }
    }
    let rows = crate::numeric::parallel::map_parts(m, threads, |i| {
        let mut f = alloc::vec![f64::NAN; n];
        let e = build(i)
            .and_then(|path| path.errors(targets, samples, search, closed, &mut f))
            .unwrap_or_else(PathError::nan);
        (e, f)
    });
    for (i, (e, f)) in rows.into_iter().enumerate() {
        errors[i] = e;
        feet[i * n..(i + 1) * n].copy_from_slice(&f);
    }
    Ok(())
}

/// [`Circuit::residuals`] of `M` placed four-bars (as [`path_errors`]) at circuit
/// parameters `s[i·n .. (i+1)·n]`: `out[i·n + j] = P_i(s_ij) − target_j`, NaN where a linkage
/// or a sample does not assemble.
///
/// # Errors
/// [`Error::BufferLength`] for buffers of the wrong length; [`Error::CountOverflow`] when
/// `M·n` overflows `usize`.
pub fn path_residuals(
    params: &[f64],
    crossed: &[bool],
    targets: &[Vec2<f64>],
    s: &[f64],
    out: &mut [Vec2<f64>],
) -> Result<(), Error> {
    let m = placed_rows(params, crossed)?;
    let build = |i: usize| {
        CircuitPath::placed(
            &params[PLACED_PARAMS * i..PLACED_PARAMS * (i + 1)],
            crossed[i],
        )
        .ok()
    };
    residuals_of(m, build, targets, s, out)
}

/// [`path_residuals`] of `m` circuits, `build(i)` the `i`-th (`None`: NaN residuals).
pub(crate) fn residuals_of<C: Circuit<f64>>(
    m: usize,
    build: impl Fn(usize) -> Option<C>,
    targets: &[Vec2<f64>],
    s: &[f64],
    out: &mut [Vec2<f64>],
) -> Result<(), Error> {
    let n = targets.len();
    let mn = rows_times(m, n)?;
    for (what, got) in [("circuit parameters", s.len()), ("residuals", out.len())] {
        if got != mn {
            return Err(Error::BufferLength {
                what,
                expected: mn,
                got,
            });
        }
    }
    for i in 0..m {
        let rows = i * n..(i + 1) * n;
        match build(i) {
            Some(path) => path.residuals(targets, &s[rows.clone()], &mut out[rows])?,
            None => out[rows].fill(Vec2::new(f64::NAN, f64::NAN)),
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same figure at any scale and place: distances scale with it (to the last bits,
    /// since the work is in units of a power of two), with no square overflowing or vanishing.
    #[test]
    fn polyline_distances_hold_at_extreme_scales() {
        let path = [
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(2.0, 2.0),
        ];
        let points = [
            Vec2::new(1.0, 1.0),
            Vec2::new(3.0, 1.0),
            Vec2::new(-3.0, 4.0),
        ];
        let mut want = [0.0; 3];
        polyline_distances(&points, &path, &mut want).unwrap();
        assert_eq!(want, [1.0, 1.0, 5.0], "the unit figure");
        for scale in [1e-300, 1e-200, 1e-100, 1e100, 1e200, 1e300] {
            for shift in [0.0, 7.0 * scale, 1e6 * scale] {
                let at = |p: &Vec2<f64>| Vec2::new(p.x * scale + shift, p.y * scale - shift);
                let (path_s, points_s): (Vec<_>, Vec<_>) = (
                    path.iter().map(at).collect(),
                    points.iter().map(at).collect(),
                );
                let mut got = [0.0; 3];
                polyline_distances(&points_s, &path_s, &mut got).unwrap();
                for (g, w) in got.iter().zip(want) {
                    let rel = (g / scale - w).abs() / w;
                    // Far from the origin the points themselves carry 1e6·ε of the figure.
                    let tol = if shift > 8.0 * scale { 1e-8 } else { 1e-14 };
                    assert!(rel <= tol, "scale {scale:e}, shift {shift:e}: {got:?}");
                }
            }
        }
    }

    #[test]
    fn limited_circuit_is_continuous_and_tracked() {
        // Triple rocker (limited both ways): the circuit passes both limits smoothly.
        let fb = FourBar::new(20.0, 10.0, 10.0, 10.0, (20.0, 5.0), Assembly::Open).unwrap();
        let c = CircuitPath::new(fb).unwrap();
        assert!(
            !c.full_turn(),
            "a triple rocker's circuit reported a full turn"
        );
        c.check(512).unwrap();
        let poly = c.polyline(2000);
        let worst = (0..2000)
            .map(|k| (poly[(k + 1) % 2000] - poly[k]).norm())
            .fold(0.0, f64::max);
        assert!(worst < 0.2, "{worst}");
        // The foot of a curve point is the point itself.
        let t = c.point(1.234).unwrap();
        let (d, s) = c.foot(t, &c.polyline(256)).unwrap();
        assert!(d < 1e-12, "{d}");
        let foot = c.point(s).unwrap();
        assert!(
            (foot - t).norm() < 1e-12,
            "foot {foot:?} at s = {s} of the curve point {t:?}"
        );
    }

    #[test]
    fn a_change_point_through_its_flat_position_is_refused() {
        // Parallelogram: flat positions at θ = 0 and π, where the tracker switches branch.
        let fb = FourBar::new(3.0, 1.0, 3.0, 1.0, (1.0, 1.0), Assembly::Open).unwrap();
        let c = CircuitPath::new(fb).unwrap();
        assert!(
            c.check(256).is_err(),
            "the tracker crossed a flat position unnoticed"
        );
    }
}
