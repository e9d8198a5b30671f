//! Burmester motion generation: revolute dyads and four-bars that carry a body through three
//! or four prescribed poses, each checked by sweeping it through them.
//!
//! # Notation (Sandor & Erdman, *Advanced Mechanism Design* vol. 2, ch. 2; McCarthy & Soh,
//! *Geometric Design of Linkages*, 2nd ed., ch. 4–5)
//! A pose `j` places the moving body: its reference point `d_j` and its angle. A revolute dyad
//! is a *centre point* `G` (fixed pivot) and a *circle point* `K` (moving pivot, given where it
//! lies at pose 0): the positions `K_j` of that body point lie on a circle about `G`. Relative
//! to pose 0, with `α_j` the body's rotation and `δ_j = d_j − d_0`, the dyad `W = K_0 − G`,
//! `Z = d_0 − K_0` satisfies the *standard-form dyad equation* (complex numbers)
//!
//! ```text
//! W (e^{iβ_j} − 1) + Z (e^{iα_j} − 1) = δ_j,        j = 1, 2, 3,
//! ```
//!
//! where `β_j` is the crank's rotation from pose 0 to pose `j`.
//!
//! - Three poses ([`centre_point`], [`circle_point`]): every body point is a circle point; its
//!   centre point is the circumcentre of its three positions. The inverse — a chosen centre point
//!   to its circle point — is the same construction in the moving body's frame (kinematic
//!   inversion: the fixed point as seen from the body at each pose).
//! - Four poses ([`BurmesterCurve`]): the three equations in `W, Z` are compatible only when
//!   `det[e^{iβ_j} − 1, e^{iα_j} − 1, δ_j] = 0`, i.e. `Δ_0 + Δ_1 e^{iβ_1} + Δ_2 e^{iβ_2} +
//!   Δ_3 e^{iβ_3} = 0` with the `Δ` cofactors of the first column (`Δ_0 = −Δ_1 − Δ_2 − Δ_3`).
//!   One `β` is the free parameter; the other two close a triangle of sides `|Δ_i|`, `|Δ_j|` and
//!   `|Δ_0 + Δ_k e^{iβ_k}|`, two ways (or none). Each solution gives `W, Z`: a centre point on
//!   the *centre-point curve* and a circle point on the *circle-point curve* (circular cubics).
//!
//! Degenerate cases, all typed errors: coincident poses ([`Error::CoincidentPositions`]); a
//! circle point whose positions are collinear has its centre at infinity (a slider would guide
//! it) and a circle point at a pole has no unique centre ([`Error::Degenerate`]); four poses
//! related by pure translations, or by rotations about one point, make every `Δ` vanish
//! ([`Error::Degenerate`]). Poles at infinity (a single translation between two poses) need no
//! special case: the dyad equation never forms a pole.

use nalgebra::RealField;

use crate::error::{check_finite, Error};
use crate::linkages::fourbar::min_transmission_angle;
use crate::linkages::fourbar::{FourBar, GrashofClass, InputRange};
use crate::motion::centres::{circumcentre, Centre};
use crate::numeric::scalar::{eps, length, lit, nan, perp, Vec2};
use crate::sweep::tracker::{Rates, Tracker};

/// A position of a moving body: where its reference point is and how it is turned.
///
/// ```
/// use linkage_core::{BodyPose, Vec2};
/// // A body at (1, 2) turned a quarter turn: its point (1, 0) is at (1, 3) in the world.
/// let pose = BodyPose::new(1.0_f64, 2.0, core::f64::consts::FRAC_PI_2).unwrap();
/// let w = pose.to_world(Vec2::new(1.0, 0.0));
/// assert!((w - Vec2::new(1.0, 3.0)).norm() < 1e-15);
/// assert!((pose.to_body(w) - Vec2::new(1.0, 0.0)).norm() < 1e-15);
/// assert!(BodyPose::new(f64::NAN, 0.0, 0.0).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyPose<T> {
    /// The body's reference point (the coupler point of a synthesised four-bar).
    pub origin: Vec2<T>,
    /// The body's angle (radians, counter-clockwise from +x).
    pub angle: T,
}

impl<T: RealField + Copy> BodyPose<T> {
    /// A pose at `(x, y)` turned by `angle`.
    ///
    /// # Errors
    /// [`Error::NotFinite`] for a non-finite value.
    pub fn new(x: T, y: T, angle: T) -> Result<Self, Error> {
        Ok(BodyPose {
            origin: Vec2::new(check_finite("pose x", x)?, check_finite("pose y", y)?),
            angle: check_finite("pose angle", angle)?,
        })
    }

    /// World position of the body point with body coordinates `w`: `d + R(angle) w`.
    pub fn to_world(&self, w: Vec2<T>) -> Vec2<T> {
        let (s, c) = self.angle.sin_cos();
        self.origin + Vec2::new(c * w.x - s * w.y, s * w.x + c * w.y)
    }

    /// Body coordinates of the world point `p`: `R(−angle)(p − d)`.
    pub fn to_body(&self, p: Vec2<T>) -> Vec2<T> {
        let (s, c) = self.angle.sin_cos();
        let v = p - self.origin;
        Vec2::new(c * v.x + s * v.y, c * v.y - s * v.x)
    }
}

/// The pole of the displacement from pose `p` to pose `q`: the point that does not move.
///
/// With `δ = q.origin − p.origin` and `Δ` the rotation, the pole lies on the perpendicular
/// bisector of `δ`, at `mid(δ) + δ⊥·cot(Δ/2)/2` (from `X = d_p + δ/(1 − e^{iΔ})`). A pure
/// translation has its pole at infinity (perpendicular to `δ`); two equal poses have none.
pub fn pole<T: RealField + Copy>(p: &BodyPose<T>, q: &BodyPose<T>) -> Centre<T> {
    let delta = q.origin - p.origin;
    let turn = wrap(q.angle - p.angle);
    let half = turn * lit::<T>(0.5);
    let n = length(delta);
    if half.sin() == T::zero() || turn.abs() <= eps::<T>() {
        return if n == T::zero() {
            Centre::Undefined
        } else {
            Centre::AtInfinity(perp(delta) / n)
        };
    }
    let x = p.origin + delta * lit::<T>(0.5) + perp(delta) * (half.cos() / half.sin() * lit(0.5));
    if x.x.is_finite() && x.y.is_finite() {
        Centre::Finite(x)
    } else {
        Centre::AtInfinity(perp(delta) / n)
    }
}

/// The point that every displacement between `poses` leaves in place, when the poses are all
/// rotations about that one point; `None` otherwise.
///
/// Such poses make every body point's centre point that point (each point moves on a circle
/// about it), so any two dyads share their fixed pivot: no four-bar guides them, one link
/// pinned there does. The test: the pole of poses 0 and 1 is finite and every other pose
/// leaves it in place to `1024 ε` of the poses' size.
///
/// # Errors
/// [`Error::NotFinite`], [`Error::CoincidentPositions`] for bad poses; [`Error::TooFew`] for
/// fewer than 2.
///
/// ```
/// use linkage_core::{common_pole, BodyPose, Vec2};
/// // A body turning about (1, 2).
/// let pose = |a: f64| {
///     let d = Vec2::new(1.0, 2.0) + nalgebra::Rotation2::new(a) * Vec2::new(-1.0, -2.0);
///     BodyPose::new(d.x, d.y, a).unwrap()
/// };
/// let centre = common_pole(&[pose(0.0), pose(0.3), pose(0.9)]).unwrap().unwrap();
/// assert!((centre - Vec2::new(1.0, 2.0)).norm() < 1e-12);
/// let moved = BodyPose::new(0.5, 0.0, 0.9).unwrap();
/// assert_eq!(common_pole(&[pose(0.0), pose(0.3), moved]).unwrap(), None);
/// ```
pub fn common_pole<T: RealField + Copy>(poses: &[BodyPose<T>]) -> Result<Option<Vec2<T>>, Error> {
    if poses.len() < 2 {
        return Err(Error::TooFew {
            what: "poses",
            needed: 2,
            got: poses.len(),
        });
    }
    check_poses(poses)?;
    let Centre::Finite(x) = pole(&poses[0], &poses[1]) else {
        return Ok(None);
    };
    let mut size = (x - poses[0].origin).amax();
    for p in poses {
        size = size.max((p.origin - poses[0].origin).amax());
    }
    let w = poses[0].to_body(x);
    let tol = lit::<T>(1024.0) * eps::<T>() * size;
    let fixed = poses[2..].iter().all(|p| (p.to_world(w) - x).amax() <= tol);
    Ok(fixed.then_some(x))
}

/// A revolute dyad found by Burmester theory: a centre point (fixed pivot) and a circle point
/// (moving pivot, where it lies at pose 0).
///
/// ```
/// use linkage_core::{catalog, centre_point, circle_point, BodyPose};
/// // Three poses of Hoecken's coupler (its foot P and the direction of A → B).
/// let fb = catalog::hoecken::<f64>();
/// let at = |t: f64| {
///     let p = fb.pose(t).unwrap();
///     let d = p.b - p.a;
///     (BodyPose::new(p.coupler_point.x, p.coupler_point.y, d.y.atan2(d.x)).unwrap(), p.a)
/// };
/// let (poses, a0) = ([at(0.4).0, at(1.3).0, at(2.5).0], at(0.4).1);
/// // The crank pin's three positions lie on a circle about the crank pivot O.
/// let crank = centre_point(&poses, a0).unwrap();
/// assert!((crank.centre - fb.o).norm() < 1e-9 && (crank.radius() - fb.crank).abs() < 1e-9);
/// // And back: the fixed point O, seen from the moving body, gives the crank pin.
/// assert!((circle_point(&poses, fb.o).unwrap().circle - a0).norm() < 1e-9);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BurmesterPair<T> {
    /// Fixed pivot.
    pub centre: Vec2<T>,
    /// Moving pivot at pose 0.
    pub circle: Vec2<T>,
}

impl<T: RealField + Copy> BurmesterPair<T> {
    /// The crank length `|circle − centre|`.
    pub fn radius(&self) -> T {
        length(self.circle - self.centre)
    }
}

/// Angle reduced to `(−π, π]`.
pub(crate) fn wrap<T: RealField + Copy>(x: T) -> T {
    let tau = T::two_pi();
    let r = x - (x / tau).round() * tau;
    if r <= -T::pi() {
        r + tau
    } else if r > T::pi() {
        r - tau
    } else {
        r
    }
}

/// Whether `x` is NaN (`RealField` has no `is_nan`).
pub(crate) fn is_nan<T: RealField + Copy>(x: T) -> bool {
    x.partial_cmp(&x).is_none()
}

/// Angle reduced to `[0, 2π)`.
pub(crate) fn turns<T: RealField + Copy>(x: T) -> T {
    let tau = T::two_pi();
    let r = x - (x / tau).floor() * tau;
    if r >= tau || r < T::zero() {
        T::zero()
    } else {
        r
    }
}

/// Checks that poses are finite and pairwise distinct (to `64 ε` in position, relative to their
/// spread, and in angle).
fn check_poses<T: RealField + Copy>(poses: &[BodyPose<T>]) -> Result<(), Error> {
    for p in poses {
        check_finite("pose x", p.origin.x)?;
        check_finite("pose y", p.origin.y)?;
        check_finite("pose angle", p.angle)?;
    }
    let mut spread = T::zero();
    for p in poses {
        for q in poses {
            spread = spread.max((p.origin - q.origin).amax());
        }
    }
    let tol = lit::<T>(64.0) * eps::<T>();
    for (i, p) in poses.iter().enumerate() {
        for (j, q) in poses.iter().enumerate().skip(i + 1) {
            if (p.origin - q.origin).amax() <= tol * spread && wrap(p.angle - q.angle).abs() <= tol
            {
                return Err(Error::CoincidentPositions {
                    first: i,
                    second: j,
                });
            }
        }
    }
    Ok(())
}

/// [`circumcentre`], undefined also when two points coincide to `1024 ε` of their spread (a
/// point at a pole, computed to rounding, lands a few ulps from its other position, and the
/// circumcentre of such a needle triangle is rounding noise).
fn checked_circumcentre<T: RealField + Copy>(k: [Vec2<T>; 3]) -> Centre<T> {
    let d = [k[1] - k[0], k[2] - k[1], k[0] - k[2]].map(|v| v.amax());
    let spread = d[0].max(d[1]).max(d[2]).max(k[0].amax());
    if d.iter()
        .any(|&x| x <= lit::<T>(1024.0) * eps::<T>() * spread)
    {
        return Centre::Undefined;
    }
    circumcentre(k[0], k[1], k[2])
}

/// The centre point of circle point `circle` (where it lies at pose 0) for three poses: the
/// circumcentre of its three positions.
///
/// # Errors
/// [`Error::NotFinite`], [`Error::CoincidentPositions`] for bad poses;
/// [`Error::Degenerate`] when the three positions are collinear (the centre is at infinity: a
/// slider, not a crank, guides that point) or two coincide (the point is a pole, so its centre
/// lies anywhere on a line).
///
/// ```
/// use linkage_core::{centre_point, BodyPose, Vec2};
/// // A body turning about (1, 2): every circle point's centre is (1, 2).
/// let pose = |a: f64| {
///     let d = Vec2::new(1.0, 2.0) + nalgebra::Rotation2::new(a) * Vec2::new(-1.0, -2.0);
///     BodyPose::new(d.x, d.y, a).unwrap()
/// };
/// let pair = centre_point(&[pose(0.0), pose(0.3), pose(0.9)], Vec2::new(4.0, 0.5)).unwrap();
/// assert!((pair.centre - Vec2::new(1.0, 2.0)).norm() < 1e-12);
/// ```
pub fn centre_point<T: RealField + Copy>(
    poses: &[BodyPose<T>; 3],
    circle: Vec2<T>,
) -> Result<BurmesterPair<T>, Error> {
    check_poses(poses)?;
    check_finite("circle point x", circle.x)?;
    check_finite("circle point y", circle.y)?;
    let w = poses[0].to_body(circle);
    let k = poses.map(|p| p.to_world(w));
    match checked_circumcentre(k) {
        Centre::Finite(g) => Ok(BurmesterPair { centre: g, circle }),
        Centre::AtInfinity(_) => Err(Error::Degenerate {
            what: "the centre point is at infinity: the circle point's three positions are \
                   collinear (a slider guides that point, not a crank)",
        }),
        Centre::Undefined => Err(Error::Degenerate {
            what: "the centre point is not unique: the circle point is a pole of two poses, so \
                   two of its three positions coincide",
        }),
    }
}

/// The circle point (at pose 0) of centre point `centre` for three poses: the circumcentre, in
/// the moving body's frame, of the fixed point as the body sees it at each pose (kinematic
/// inversion), carried back to pose 0.
///
/// # Errors
/// As [`centre_point`], with the roles of the points exchanged.
pub fn circle_point<T: RealField + Copy>(
    poses: &[BodyPose<T>; 3],
    centre: Vec2<T>,
) -> Result<BurmesterPair<T>, Error> {
    check_poses(poses)?;
    check_finite("centre point x", centre.x)?;
    check_finite("centre point y", centre.y)?;
    let g = poses.map(|p| p.to_body(centre));
    match checked_circumcentre(g) {
        Centre::Finite(w) => Ok(BurmesterPair {
            centre,
            circle: poses[0].to_world(w),
        }),
        Centre::AtInfinity(_) => Err(Error::Degenerate {
            what: "the circle point is at infinity: seen from the moving body, the centre \
                   point's three positions are collinear (the body would carry a slider)",
        }),
        Centre::Undefined => Err(Error::Degenerate {
            what: "the circle point is not unique: the centre point is a pole of two poses",
        }),
    }
}

/// Complex product of `a` and `b` (as `x + iy`).
fn cmul<T: RealField + Copy>(a: Vec2<T>, b: Vec2<T>) -> Vec2<T> {
    Vec2::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x)
}

/// Complex quotient `a / b`.
fn cdiv<T: RealField + Copy>(a: Vec2<T>, b: Vec2<T>) -> Vec2<T> {
    let n = b.norm_squared();
    Vec2::new(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) / n
}

/// `e^{iβ} − 1` without the cancellation of `cos β − 1`: `(−2 sin²(β/2), sin β)`.
fn cis_minus_one<T: RealField + Copy>(beta: T) -> Vec2<T> {
    let h = (beta * lit::<T>(0.5)).sin();
    Vec2::new(-lit::<T>(2.0) * h * h, beta.sin())
}

fn arg<T: RealField + Copy>(z: Vec2<T>) -> T {
    z.y.atan2(z.x)
}

fn cis<T: RealField + Copy>(t: T) -> Vec2<T> {
    let (s, c) = t.sin_cos();
    Vec2::new(c, s)
}

/// The Burmester curves of four poses: every revolute dyad that guides the body through them,
/// parametrised by one crank rotation.
///
/// See the module notes for the compatibility equation solved. [`BurmesterCurve::dyads`] at
/// `β` (the crank's rotation from pose 0 to pose [`BurmesterCurve::free_pose`]) returns the
/// two dyads closing the compatibility triangle, or `None` where it does not close (the curve
/// has no real point there) or the dyad is at infinity (the trivial solutions `β_j = 0` and
/// `β_j = α_j`, where the dyad equations lose rank).
///
/// ```
/// use linkage_core::{Assembly, BodyPose, BurmesterCurve, BurmesterPair, Error, FourBar, Vec2};
/// // Four poses of a crank-rocker's coupler: its crank (O, A₀) is one of the dyads on the curve,
/// // at the crank's own rotation to the free pose.
/// let fb = FourBar::with_pivots(
///     Vec2::new(0.3, -0.2), Vec2::new(2.3, 0.4), 0.7, 1.9, 1.6, (0.8, 0.6), Assembly::Open,
/// ).unwrap();
/// let thetas = [0.2, 0.9, 1.7, 2.6];
/// let at = |t: f64| {
///     let p = fb.pose(t).unwrap();
///     let d = p.b - p.a;
///     BodyPose::new(p.coupler_point.x, p.coupler_point.y, d.y.atan2(d.x)).unwrap()
/// };
/// let curve = BurmesterCurve::new(&thetas.map(at)).unwrap();
/// let k = curve.free_pose();
/// let a0 = fb.pose(thetas[0]).unwrap().a;
/// let found = curve.dyads(thetas[k] - thetas[0]);
/// let near = |d: &BurmesterPair<f64>| (d.centre - fb.o).norm() + (d.circle - a0).norm() < 1e-10;
/// assert!(found.iter().flatten().any(near));
/// // Four pure translations have no Burmester curve.
/// let shift = |x: f64, y: f64| BodyPose::new(x, y, 0.2).unwrap();
/// let translations = [shift(0.0, 0.0), shift(1.0, 0.0), shift(1.0, 1.0), shift(0.0, 2.0)];
/// let r = BurmesterCurve::new(&translations);
/// assert!(matches!(r, Err(Error::Degenerate { .. })));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BurmesterCurve<T> {
    origin: Vec2<T>,
    /// Length unit of the local coordinates (a power of two near the largest displacement).
    unit: T,
    /// `e^{iα_j} − 1`, `j = 1, 2, 3`.
    rot: [Vec2<T>; 3],
    /// `δ_j / unit`.
    disp: [Vec2<T>; 3],
    /// `Δ_0 … Δ_3`.
    cof: [Vec2<T>; 4],
    free: usize,
}

impl<T: RealField + Copy> BurmesterCurve<T> {
    /// The curves of four poses.
    ///
    /// The free angle is the crank rotation to the pose `k` whose two other coefficients
    /// `|Δ_i|, |Δ_j|` have the largest minimum, so the triangle is well conditioned.
    ///
    /// # Errors
    /// [`Error::NotFinite`], [`Error::CoincidentPositions`]; [`Error::Degenerate`] when the
    /// compatibility equation loses its terms: the poses are pure translations (every pole at
    /// infinity) or rotations about one point, or three of them are.
    pub fn new(poses: &[BodyPose<T>; 4]) -> Result<Self, Error> {
        Self::build(poses, None)
    }

    /// The curves of four poses, parametrised by the crank rotation from pose 0 to pose
    /// `free` (1, 2 or 3) rather than the best-conditioned one.
    ///
    /// # Errors
    /// As [`BurmesterCurve::new`]; [`Error::InvalidChoice`] for `free` not 1, 2 or 3;
    /// [`Error::Degenerate`] when one of the other two coefficients vanishes, so the rotation to
    /// pose `free` does not parametrise the curve (another free pose does).
    ///
    /// ```
    /// use linkage_core::{BodyPose, BurmesterCurve};
    /// let p = |x: f64, y: f64, a: f64| BodyPose::new(x, y, a).unwrap();
    /// let poses = [p(1.0, 1.1, 0.4), p(0.3, 1.7, 0.3), p(-0.6, 1.5, 0.5), p(-1.0, 1.0, 0.9)];
    /// let curve = BurmesterCurve::with_free_pose(&poses, 1).unwrap();
    /// assert_eq!(curve.free_pose(), 1);
    /// assert!(BurmesterCurve::with_free_pose(&poses, 4).is_err());
    /// ```
    pub fn with_free_pose(poses: &[BodyPose<T>; 4], free: usize) -> Result<Self, Error> {
        if !(1..=3).contains(&free) {
            return Err(Error::InvalidChoice {
                what: "the free pose",
                choices: "1, 2 or 3",
            });
        }
        Self::build(poses, Some(free))
    }

    fn build(poses: &[BodyPose<T>; 4], chosen: Option<usize>) -> Result<Self, Error> {
        check_poses(poses)?;
        let origin = poses[0].origin;
        let mut big = T::zero();
        for p in &poses[1..] {
            big = big.max((p.origin - origin).amax());
        }
        let unit = if big > T::zero() {
            crate::numeric::pow2::pow2_scale(big)
        } else {
            T::one()
        };
        let rot = [1, 2, 3].map(|j| cis_minus_one(poses[j].angle - poses[0].angle));
        let disp = [1, 2, 3].map(|j| (poses[j].origin - origin) / unit);
        let (a, d) = (rot, disp);
        let c1 = cmul(a[1], d[2]) - cmul(a[2], d[1]);
        let c2 = cmul(a[2], d[0]) - cmul(a[0], d[2]);
        let c3 = cmul(a[0], d[1]) - cmul(a[1], d[0]);
        let cof = [-(c1 + c2 + c3), c1, c2, c3];
        let size = [c1, c2, c3].map(length);
        let largest = size[0].max(size[1]).max(size[2]);
        let mut free = 1;
        let mut best = -T::one();
        for k in 1..=3 {
            let (i, j) = Self::others(k);
            let m = size[i - 1].min(size[j - 1]);
            if m > best {
                best = m;
                free = k;
            }
        }
        let tol = lit::<T>(256.0) * eps::<T>();
        let conditioned = best;
        if let Some(k) = chosen {
            let (i, j) = Self::others(k);
            free = k;
            best = size[i - 1].min(size[j - 1]);
        }
        if largest <= tol || is_nan(largest) {
            return Err(Error::Degenerate {
                what: "the four poses have no Burmester curve: they are pure translations or \
                       rotations about one point (every compatibility coefficient vanishes)",
            });
        }
        let small = |m: T| m <= tol * largest.max(T::one()) || is_nan(m);
        if chosen.is_some() && small(best) && !small(conditioned) {
            return Err(Error::Degenerate {
                what: "the crank rotation to the chosen free pose does not parametrise the \
                       Burmester curve of these poses (a coefficient of the compatibility \
                       equation beside it vanishes): choose another free pose",
            });
        }
        if small(best) {
            return Err(Error::Degenerate {
                what: "the compatibility equation of the four poses has fewer than three terms \
                       (three of the poses are rotations about one point)",
            });
        }
        Ok(BurmesterCurve {
            origin,
            unit,
            rot,
            disp,
            cof,
            free,
        })
    }

    fn others(k: usize) -> (usize, usize) {
        match k {
            1 => (2, 3),
            2 => (1, 3),
            _ => (1, 2),
        }
    }

    /// The pose (1, 2 or 3) whose crank rotation from pose 0 is the curve parameter `β`.
    pub fn free_pose(&self) -> usize {
        self.free
    }

    /// The two dyads at free crank rotation `beta`, and their crank rotations
    /// `[0, β_1, β_2, β_3]` from pose 0 to each pose.
    pub fn dyads_with_rotations(&self, beta: T) -> [Option<(BurmesterPair<T>, [T; 4])>; 2] {
        let mut out = [None, None];
        if !beta.is_finite() {
            return out;
        }
        let k = self.free;
        let (i, j) = Self::others(k);
        let target = -(self.cof[0] + cmul(self.cof[k], cis(beta)));
        let (a, b, r) = (length(self.cof[i]), length(self.cof[j]), length(target));
        if r <= T::zero() || is_nan(r) {
            return out;
        }
        // Triangle u + v = target with |u| = a, |v| = b: the angle between u and the target
        // is atan2(4·Area, a² + r² − b²) (Kahan's area: accurate for needle triangles).
        let tol = lit::<T>(8.0) * eps::<T>() * (a + b + r);
        let Ok(area) = crate::constructions::dyad::triangle_area(a, b, r, tol) else {
            return out;
        };
        let theta = (lit::<T>(4.0) * area).atan2((a - b) * (a + b) + r * r);
        for (slot, s) in out.iter_mut().zip([T::one(), -T::one()]) {
            let u = cis(arg(target) + s * theta) * a;
            let v = target - u;
            let mut beta_all = [T::zero(); 4];
            beta_all[k] = beta;
            beta_all[i] = arg(u) - arg(self.cof[i]);
            beta_all[j] = arg(v) - arg(self.cof[j]);
            *slot = self.solve(beta_all).map(|p| (p, beta_all.map(wrap)));
            if area == T::zero() {
                break; // one double root
            }
        }
        out
    }

    /// The two dyads at free crank rotation `beta` (see the type's notes).
    pub fn dyads(&self, beta: T) -> [Option<BurmesterPair<T>>; 2] {
        self.dyads_with_rotations(beta).map(|d| d.map(|(p, _)| p))
    }

    /// `W, Z` from the dyad equations at crank rotations `beta`: Cramer's rule on the pair of
    /// equations with the largest determinant; `None` when every pair is singular to rounding
    /// (a dyad at infinity) or the third equation is not met.
    fn solve(&self, beta: [T; 4]) -> Option<BurmesterPair<T>> {
        let c = [1, 2, 3].map(|j| cis_minus_one(beta[j]));
        let (a, d) = (self.rot, self.disp);
        let mut best = (0, 1, 2, T::zero());
        for (p, q, r) in [(0, 1, 2), (0, 2, 1), (1, 2, 0)] {
            let det = length(cmul(c[p], a[q]) - cmul(c[q], a[p]));
            if det > best.3 {
                best = (p, q, r, det);
            }
        }
        let (p, q, r, det_abs) = best;
        if det_abs <= lit::<T>(256.0) * eps::<T>() || is_nan(det_abs) {
            return None;
        }
        let det = cmul(c[p], a[q]) - cmul(c[q], a[p]);
        let w = cdiv(cmul(d[p], a[q]) - cmul(d[q], a[p]), det);
        let z = cdiv(cmul(c[p], d[q]) - cmul(c[q], d[p]), det);
        let resid = length(cmul(c[r], w) + cmul(a[r], z) - d[r]);
        let scale = length(c[r]) * length(w) + length(a[r]) * length(z) + length(d[r]);
        if resid > eps::<T>().sqrt() * scale || is_nan(resid) {
            return None;
        }
        let circle = self.origin - z * self.unit;
        let centre = circle - w * self.unit;
        let ok = |v: Vec2<T>| v.x.is_finite() && v.y.is_finite();
        (ok(circle) && ok(centre)).then_some(BurmesterPair { centre, circle })
    }
}

/// A shortcoming of a synthesised linkage found by sweeping it through its precision positions.
///
/// ```
/// use linkage_core::{centre_point, Assembly, BodyPose, Defect, FourBar, MotionCandidate, Vec2};
/// // Poses 0 and 1 on a crank-rocker's open circuit, pose 2 on its crossed one: both dyads fit
/// // the three poses exactly, but no motion of the linkage joins them.
/// let fb = FourBar::with_pivots(
///     Vec2::new(0.3, -0.2), Vec2::new(2.3, 0.4), 0.7, 1.9, 1.6, (0.8, 0.6), Assembly::Open,
/// ).unwrap();
/// let at = |t: f64, assembly| {
///     let p = FourBar { assembly, ..fb }.pose(t).unwrap();
///     let d = p.b - p.a;
///     (BodyPose::new(p.coupler_point.x, p.coupler_point.y, d.y.atan2(d.x)).unwrap(), p.a, p.b)
/// };
/// let (p0, a0, b0) = at(0.4, Assembly::Open);
/// let poses = [p0, at(1.3, Assembly::Open).0, at(2.5, Assembly::Crossed).0];
/// let (crank, rocker) = (centre_point(&poses, a0).unwrap(), centre_point(&poses, b0).unwrap());
/// let check = MotionCandidate::new(&poses, crank, rocker).unwrap().check;
/// assert_eq!(check.defect, Some(Defect::Branch { pose: 2 }));
/// assert_eq!(check.defect.unwrap().name(), "branch");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Defect {
    /// At precision position `pose` the linkage is on the other assembly branch (a circuit
    /// defect): it reaches the crank angle there, but not the position.
    Branch {
        /// Index of the position (0-based).
        pose: usize,
    },
    /// Driving the crank from the previous position toward `pose` meets an input limit (a
    /// toggle), where the crank would have to reverse.
    Toggle {
        /// Index of the position (0-based).
        pose: usize,
    },
    /// Turning the crank one way, the positions come in another order within one turn, either
    /// way.
    Order,
    /// The motion passes a flat position of a change-point linkage, where its two branches
    /// meet: which way it continues is not determined by the linkage.
    FlatPosition,
    /// The input interval of a function generator reaches past an input limit.
    InputLimit,
}

impl Defect {
    /// The defect's name: `"branch"`, `"toggle"`, `"order"`, `"flat-position"`,
    /// `"input-limit"`.
    pub fn name(self) -> &'static str {
        match self {
            Defect::Branch { .. } => "branch",
            Defect::Toggle { .. } => "toggle",
            Defect::Order => "order",
            Defect::FlatPosition => "flat-position",
            Defect::InputLimit => "input-limit",
        }
    }
}

/// The most precision positions a [`MotionCandidate`] is checked against.
pub const MAX_POSES: usize = 4;

/// What sweeping a synthesised four-bar through its poses found.
///
/// ```
/// use linkage_core::{
///     centre_point, Assembly, BodyPose, FourBar, GrashofClass, MotionCandidate, Vec2,
/// };
/// let fb = FourBar::with_pivots(
///     Vec2::new(0.3, -0.2), Vec2::new(2.3, 0.4), 0.7, 1.9, 1.6, (0.8, 0.6), Assembly::Open,
/// ).unwrap();
/// let at = |t: f64| {
///     let p = fb.pose(t).unwrap();
///     let d = p.b - p.a;
///     (BodyPose::new(p.coupler_point.x, p.coupler_point.y, d.y.atan2(d.x)).unwrap(), p.a, p.b)
/// };
/// let thetas = [0.4, 1.3, 2.5];
/// let poses = thetas.map(|t| at(t).0);
/// let (_, a0, b0) = at(thetas[0]);
/// let (crank, rocker) = (centre_point(&poses, a0).unwrap(), centre_point(&poses, b0).unwrap());
/// let check = MotionCandidate::new(&poses, crank, rocker).unwrap().check;
/// // Counter-clockwise through the three poses in order, at the crank angles they were made at.
/// assert_eq!((check.defect, check.direction), (None, 1.0));
/// assert_eq!(check.grashof, GrashofClass::CrankRocker);
/// assert!((0..3).all(|k| (check.crank_angles[k] - thetas[k]).abs() < 1e-12));
/// assert!(check.crank_angles[3].is_nan()); // three poses of at most four
/// assert!(check.position_error < 1e-12 && check.angle_error < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionCheck<T> {
    /// `None` when the crank, turned one way, carries the body through every pose in order on
    /// one branch, without toggle or flat position; else the first defect met.
    pub defect: Option<Defect>,
    /// The crank's turning sense checked: `+1` counter-clockwise, `−1` clockwise (the one that
    /// passed, or the one whose defect is reported).
    pub direction: T,
    /// Crank angles at the poses along that travel (unwrapped; NaN past the number of poses and
    /// past a defect).
    pub crank_angles: [T; MAX_POSES],
    /// Largest distance between a tracked joint (crank pin, rocker pin, coupler point) and
    /// where the pose puts it, over the poses reached.
    pub position_error: T,
    /// Largest difference between the coupler's angle and the pose's, over the poses reached.
    pub angle_error: T,
    /// Smallest transmission angle met over the travel, folded to `[0, π/2]`
    /// (`asin` of the smallest assembly margin).
    pub min_transmission: T,
    /// Grashof class of the four-bar.
    pub grashof: GrashofClass,
}

/// A four-bar assembled from two Burmester dyads, with the check of its sweep through the poses.
///
/// ```
/// use linkage_core::{catalog, centre_point, BodyPose, Error, MotionCandidate};
/// // Three poses of Hoecken's coupler give back Hoecken's linkage from its two dyads.
/// let fb = catalog::hoecken::<f64>();
/// let at = |t: f64| {
///     let p = fb.pose(t).unwrap();
///     let d = p.b - p.a;
///     (BodyPose::new(p.coupler_point.x, p.coupler_point.y, d.y.atan2(d.x)).unwrap(), p.a, p.b)
/// };
/// let poses = [at(0.4).0, at(1.3).0, at(2.5).0];
/// let (_, a0, b0) = at(0.4);
/// let (crank, rocker) = (centre_point(&poses, a0).unwrap(), centre_point(&poses, b0).unwrap());
/// let cand = MotionCandidate::new(&poses, crank, rocker).unwrap();
/// assert_eq!((cand.check.defect, cand.four_bar.assembly), (None, fb.assembly));
/// let found = cand.four_bar;
/// assert!((found.coupler - 25.0).abs() < 1e-9 && (found.along - 50.0).abs() < 1e-9);
/// // Two poses are too few to check.
/// assert!(matches!(
///     MotionCandidate::new(&poses[..2], crank, rocker),
///     Err(Error::TooFew { needed: 3, got: 2, .. })
/// ));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionCandidate<T> {
    /// The linkage: crank pivot at the driving dyad's centre point, rocker pivot at the other's,
    /// coupler point at the body's reference point, on the branch through pose 0 (a change
    /// point's assembly names that branch at its start angle, [`FourBar::start_angle`]).
    pub four_bar: FourBar<T>,
    /// The driving dyad.
    pub crank: BurmesterPair<T>,
    /// The driven dyad.
    pub rocker: BurmesterPair<T>,
    /// The sweep through the poses.
    pub check: MotionCheck<T>,
}

impl<T: RealField + Copy> MotionCandidate<T> {
    /// Assembles the four-bar driven by `crank` with `rocker` and sweeps it through `poses`
    /// (3 or 4) with the [`Tracker`].
    ///
    /// For each turning sense of the crank, the crank angles at the poses are unwrapped along
    /// that sense; a travel of a whole turn or more is an [`Defect::Order`]; a limited crank must
    /// stay inside its input interval ([`Defect::Toggle`]); the tracked linkage must put the
    /// crank pin, rocker pin and coupler point where each pose puts them (to `√ε` of the
    /// linkage's size, else [`Defect::Branch`]), keeping its orientation
    /// ([`Defect::FlatPosition`]). A sense that passes is reported; else the defect of the sense
    /// that keeps the order (or the counter-clockwise one).
    ///
    /// # Errors
    /// [`Error::TooFew`] for fewer than 3 poses, [`Error::BufferLength`] for more than
    /// [`MAX_POSES`], [`Error::NotFinite`] / [`Error::CoincidentPositions`] for bad poses,
    /// [`Error::InvalidLength`] when the dyads do not make a four-bar (a circle point on its
    /// centre point, coincident circle points); [`Error::Degenerate`] when their centre points
    /// coincide to rounding (see [`common_pole`]).
    pub fn new(
        poses: &[BodyPose<T>],
        crank: BurmesterPair<T>,
        rocker: BurmesterPair<T>,
    ) -> Result<Self, Error> {
        if poses.len() < 3 {
            return Err(Error::TooFew {
                what: "poses",
                needed: 3,
                got: poses.len(),
            });
        }
        if poses.len() > MAX_POSES {
            return Err(Error::BufferLength {
                what: "poses",
                expected: MAX_POSES,
                got: poses.len(),
            });
        }
        check_poses(poses)?;
        for v in [crank.centre, crank.circle, rocker.centre, rocker.circle] {
            check_finite("dyad point", v.x)?;
            check_finite("dyad point", v.y)?;
        }
        let (o, c, a0, b0) = (crank.centre, rocker.centre, crank.circle, rocker.circle);
        // The lengths checked here, to name them; the four-bar as placed at the first pose.
        crate::error::check_length(
            "coupler (distance between the circle points)",
            length(b0 - a0),
        )?;
        crate::error::check_length("crank (circle point to centre point)", crank.radius())?;
        crate::error::check_length("rocker (circle point to centre point)", rocker.radius())?;
        // Centre points apart by rounding only (the dyads of poses turning about one point all
        // have that point as centre) would make a ground link of noise, not of length zero.
        let size = [a0 - o, b0 - o, poses[0].origin - o]
            .iter()
            .fold(length(c - o), |m, v| m.max(length(*v)));
        if length(c - o) <= lit::<T>(1024.0) * eps::<T>() * size {
            return Err(Error::Degenerate {
                what: "the two dyads share their fixed pivot (a ground link of length zero): as \
                       happens for every pair when the poses are rotations about one point, \
                       which is every dyad's centre point",
            });
        }
        let four_bar = FourBar::from_points(o, c, a0, b0, poses[0].origin)?;
        let check = check_motion(&four_bar, poses, crank, rocker);
        Ok(MotionCandidate {
            four_bar,
            crank,
            rocker,
            check,
        })
    }
}

/// The sweep of [`MotionCandidate::new`]: both turning senses, the passing one or the more
/// telling defect.
fn check_motion<T: RealField + Copy>(
    fb: &FourBar<T>,
    poses: &[BodyPose<T>],
    crank: BurmesterPair<T>,
    rocker: BurmesterPair<T>,
) -> MotionCheck<T> {
    let ccw = sweep_sense(fb, poses, crank, rocker, T::one());
    if ccw.defect.is_none() {
        return ccw;
    }
    let cw = sweep_sense(fb, poses, crank, rocker, -T::one());
    if cw.defect.is_none() || (ccw.defect == Some(Defect::Order) && cw.defect != ccw.defect) {
        cw
    } else {
        ccw
    }
}

/// The first pose whose crank angle (`t`, unwrapped from `t[0]`) a limited crank cannot reach
/// from the interval it starts in, `None` when it reaches them all. A limited crank must stay
/// inside the interval it starts in: exact limits, so no sampling can step over a locked zone.
fn leaves_input_range<T: RealField + Copy>(fb: &FourBar<T>, t: &[T]) -> Option<usize> {
    let tau = T::two_pi();
    let interval = match fb.input_range() {
        InputRange::Full => None,
        InputRange::Never => return Some(0),
        InputRange::Between { lo, hi } => Some((lo, hi)),
        InputRange::TwoIntervals { first, second } => {
            let inside = |(lo, hi): (T, T)| {
                let r = lo + turns(t[0] - lo);
                r <= hi || r - tau >= lo - lit::<T>(64.0) * eps::<T>() * tau
            };
            Some(if inside(first) { first } else { second })
        }
    };
    if let Some((lo, hi)) = interval {
        let slack = lit::<T>(64.0) * eps::<T>() * (tau + lo.abs() + hi.abs());
        let mut r = lo + turns(t[0] - lo);
        if r > hi + slack && r - tau >= lo - slack {
            r -= tau;
        }
        for (j, &tj) in t.iter().enumerate() {
            let x = r + (tj - t[0]);
            if x < lo - slack || x > hi + slack {
                return Some(j);
            }
        }
    }
    None
}

/// Sweeps the crank through the poses in turning sense `dir`.
fn sweep_sense<T: RealField + Copy>(
    fb: &FourBar<T>,
    poses: &[BodyPose<T>],
    crank: BurmesterPair<T>,
    rocker: BurmesterPair<T>,
    dir: T,
) -> MotionCheck<T> {
    let n = poses.len();
    let tau = T::two_pi();
    let a_body = poses[0].to_body(crank.circle);
    let b_body = poses[0].to_body(rocker.circle);
    let d0 = rocker.circle - crank.circle;
    // The body's angle minus the coupler line's: constant, as both are fixed in the body.
    let offset = poses[0].angle - arg(d0);
    let target = |j: usize| {
        (
            poses[j].to_world(a_body),
            poses[j].to_world(b_body),
            poses[j].origin,
        )
    };
    let mut out = MotionCheck {
        defect: None,
        direction: dir,
        crank_angles: [nan::<T>(); MAX_POSES],
        position_error: T::zero(),
        angle_error: T::zero(),
        min_transmission: T::frac_pi_2(),
        grashof: fb.grashof(),
    };
    let mut t = [nan::<T>(); MAX_POSES];
    t[0] = arg(target(0).0 - fb.o);
    for j in 1..n {
        let step = turns(dir * (arg(target(j).0 - fb.o) - arg(target(j - 1).0 - fb.o)));
        t[j] = t[j - 1] + dir * step;
    }
    if (t[n - 1] - t[0]).abs() >= tau {
        out.defect = Some(Defect::Order);
        return out;
    }
    if let Some(pose) = leaves_input_range(fb, &t[..n]) {
        out.defect = Some(Defect::Toggle { pose });
        return out;
    }
    let m = fb.mechanism();
    let Ok(mut tracker) = Tracker::new(&m) else {
        out.defect = Some(Defect::Toggle { pose: 0 });
        return out;
    };
    // The side of `B` on `A → C` changes only where the dyad is flat: for a crank that stays
    // in its interval (checked above), at a change point's flat position. Compared with its
    // side at pose 0 at every sample: a change point's declared assembly names its branch at
    // the start angle, not at pose 0, and a tracker whose orientations are known in closed form
    // does not report the flips it places.
    let side = |j: &[Vec2<T>; 5]| {
        FourBar::<T>::assembly_of(
            fb.c - j[FourBar::<T>::A],
            j[FourBar::<T>::B] - j[FourBar::<T>::A],
        )
    };
    let mut side0 = None;
    let size = fb
        .ground()
        .max(fb.crank)
        .max(fb.coupler)
        .max(fb.rocker)
        .max(fb.along.abs())
        .max(fb.left.abs());
    let tol = eps::<T>().sqrt() * size;
    let mut joints = [Vec2::zeros(); 5];
    let mut margin = T::one();
    let fine = T::pi() / lit::<T>(32.0);
    for j in 0..n {
        if j > 0 {
            let span = t[j] - t[j - 1];
            let k = (span.abs() / fine)
                .ceil()
                .to_subset()
                .unwrap_or(1.0)
                .max(1.0) as usize;
            for s in 1..k {
                let th = t[j - 1] + span * lit::<T>(s as f64) / lit::<T>(k as f64);
                match tracker.step(th, None, &mut joints, Rates::none()) {
                    Ok(sample) => margin = margin.min(sample.margin),
                    Err(_) => {
                        out.defect = Some(Defect::Toggle { pose: j });
                        return out;
                    }
                }
                if side0 != Some(side(&joints)) {
                    out.min_transmission = min_transmission_angle(margin);
                    out.defect = Some(Defect::FlatPosition);
                    return out;
                }
            }
        }
        match tracker.step(t[j], None, &mut joints, Rates::none()) {
            Ok(sample) => margin = margin.min(sample.margin),
            Err(_) => {
                out.defect = Some(Defect::Toggle { pose: j });
                return out;
            }
        }
        out.min_transmission = min_transmission_angle(margin);
        if j == 0 {
            side0 = Some(side(&joints));
        } else if side0 != Some(side(&joints)) {
            out.defect = Some(Defect::FlatPosition);
            return out;
        }
        let (a, b, p) = target(j);
        let (ja, jb, jp) = (
            joints[FourBar::<T>::A],
            joints[FourBar::<T>::B],
            joints[FourBar::<T>::P],
        );
        let err = length(ja - a).max(length(jb - b)).max(length(jp - p));
        if err > tol || is_nan(err) {
            out.defect = Some(Defect::Branch { pose: j });
            return out;
        }
        out.crank_angles[j] = t[j];
        out.position_error = out.position_error.max(err);
        let angle = arg(jb - ja) + offset;
        out.angle_error = out.angle_error.max(wrap(angle - poses[j].angle).abs());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pole_of_a_quarter_turn() {
        // A quarter turn about (1, 1) takes the origin to (2, 0).
        let p = BodyPose::new(0.0, 0.0, 0.0).unwrap();
        let q = BodyPose::new(2.0, 0.0, core::f64::consts::FRAC_PI_2).unwrap();
        let c = pole(&p, &q).finite().unwrap();
        assert!((c - Vec2::new(1.0, 1.0)).norm() < 1e-15, "{c:?}");
        let t = BodyPose::new(3.0, 4.0, 0.0).unwrap();
        let c = pole(&p, &t);
        assert!(
            matches!(c, Centre::AtInfinity(_)),
            "pole of a translation: {c:?}"
        );
        assert_eq!(pole(&p, &p), Centre::Undefined, "pole of no motion");
    }

    #[test]
    fn wrap_is_in_half_open_interval() {
        use core::f64::consts::PI;
        assert_eq!(wrap(PI), PI, "wrap(π)");
        assert!((wrap(-PI) - PI).abs() < 1e-15, "wrap(-π) = {}", wrap(-PI));
        assert!(
            (wrap(3.0 * PI + 0.1) - (-PI + 0.1)).abs() < 1e-14,
            "wrap(3π + 0.1) = {}",
            wrap(3.0 * PI + 0.1)
        );
    }
}
