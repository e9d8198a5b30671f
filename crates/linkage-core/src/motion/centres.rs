//! Instant centres, centres of curvature and circumcentres, with points at infinity explicit.

use nalgebra::RealField;

use crate::mechanism::bodies::{Bodies, BodyFrame, BodyId};
use crate::mechanism::joint_rates::direction_rates;
use crate::numeric::scalar::{cross, eps, length, lit, perp, size, Vec2};

/// A point of the projective plane: finite, at infinity in a direction, or undefined.
///
/// ```
/// use linkage_core::{circumcentre, Centre, Vec2};
/// let ring = circumcentre(Vec2::new(1.0_f64, 0.0), Vec2::new(0.0, 1.0), Vec2::new(-1.0, 0.0));
/// assert!(ring.finite().unwrap().norm() < 1e-15);
/// // Three collinear points: the centre is at infinity, along the line's normal.
/// let line = circumcentre(Vec2::new(0.0_f64, 0.0), Vec2::new(1.0, 0.0), Vec2::new(2.0, 0.0));
/// assert!(matches!(line, Centre::AtInfinity(d) if d.x == 0.0 && d.y.abs() == 1.0));
/// assert_eq!(line.finite(), None);
/// // Three coincident points: no centre at all.
/// let p = Vec2::new(1.0_f64, 1.0);
/// assert_eq!(circumcentre(p, p, p), Centre::Undefined);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Centre<T> {
    /// A finite point.
    Finite(Vec2<T>),
    /// A point at infinity, in this unit direction (either sense).
    AtInfinity(Vec2<T>),
    /// No centre: the construction is degenerate (e.g. a point at rest has no path curvature).
    Undefined,
}

impl<T: RealField + Copy> Centre<T> {
    /// The finite point, if it is one.
    pub fn finite(&self) -> Option<Vec2<T>> {
        match *self {
            Centre::Finite(p) => Some(p),
            _ => None,
        }
    }
}

/// Tolerance multiple of ε below which a rate difference counts as zero.
pub(crate) const ZERO_RATE: f64 = 64.0;

/// Circumcentre of three points (the first source's three-point estimate of a centre of
/// curvature, thesis 1 §2.1.1).
///
/// Relative to `p1`, with `a = p0 − p1`, `b = p2 − p1`: `c = (|a|²·b⊥' − |b|²·a⊥') / (2 a × b)`
/// written out as `((|a|² b_y − |b|² a_y), (|b|² a_x − |a|² b_x)) / (2 a × b)`. Collinear points
/// give [`Centre::AtInfinity`] along the normal to the line (zero `a × b` to rounding);
/// coincident ones [`Centre::Undefined`].
pub fn circumcentre<T: RealField + Copy>(p0: Vec2<T>, p1: Vec2<T>, p2: Vec2<T>) -> Centre<T> {
    // Work in units of a power of two near the largest coordinate (exact; 1 for coordinates in
    // [2⁻³², 2³²]), so neither the differences nor their squares overflow or underflow.
    let big = p0.amax().max(p1.amax()).max(p2.amax());
    let s = crate::numeric::pow2::pow2_scale(big);
    let (q0, q1, q2) = (p0 / s, p1 / s, p2 / s);
    // Measure from the vertex opposite the longest side: the two shorter sides then meet there,
    // and their cross product has no cancellation (Shewchuk's advice for circumcentres).
    let (l0, l1, l2) = (
        (q2 - q1).norm_squared(),
        (q2 - q0).norm_squared(),
        (q1 - q0).norm_squared(),
    );
    let (q0, q1, q2) = if l1 >= l0 && l1 >= l2 {
        (q2, q1, q0) // longest side q0–q2: measure from q1 (order kept: the sign is not used)
    } else if l0 >= l2 {
        (q1, q0, q2) // longest side q1–q2: measure from q0
    } else {
        (q0, q2, q1) // longest side q0–q1: measure from q2
    };
    let (a, b) = (q0 - q1, q2 - q1);
    let (na, nb) = (a.norm_squared(), b.norm_squared());
    let d = lit::<T>(2.0) * cross(a, b);
    if na == T::zero() || nb == T::zero() || !(na.is_finite() && nb.is_finite()) {
        return Centre::Undefined;
    }
    if d.abs() <= lit::<T>(16.0) * eps::<T>() * (na * nb).sqrt() {
        let dir = q2 - q0;
        let n = dir.norm();
        return if n == T::zero() {
            Centre::Undefined
        } else {
            Centre::AtInfinity(perp(dir / n))
        };
    }
    let c = (q1 + Vec2::new(na * b.y - nb * a.y, nb * a.x - na * b.x) / d) * s;
    if c.x.is_finite() && c.y.is_finite() {
        Centre::Finite(c)
    } else {
        // The centre lies beyond the float range: as good as at infinity, along the normal.
        let dir = q2 - q0;
        Centre::AtInfinity(perp(dir / dir.norm()))
    }
}

/// Signed curvature and centre of curvature of a path at a point moving with velocity `v` and
/// acceleration `a`, in any timing.
///
/// `κ = (v × a)/|v|³`, positive when the path turns counter-clockwise in the direction of
/// motion; the centre is `p + v⊥·|v|²/(v × a)`, which is the same for every timing of the same
/// path (a re-timing `s(t)` scales `v × a` by `ṡ³` and `|v|²·v⊥` alike). The radius is `1/|κ|`.
/// At a point at rest (`v = 0`, e.g. a cusp) the curvature is NaN and the centre undefined;
/// where `v × a` vanishes to rounding (an inflection or a straight path) the centre is at
/// infinity along the normal.
pub fn path_curvature<T: RealField + Copy>(p: Vec2<T>, v: Vec2<T>, a: Vec2<T>) -> (T, Centre<T>) {
    let finite = |w: Vec2<T>| w.x.is_finite() && w.y.is_finite();
    if !(finite(p) && finite(v) && finite(a)) || v == Vec2::zeros() {
        return (crate::numeric::scalar::nan(), Centre::Undefined);
    }
    // Velocity and acceleration in units of powers of two near their sizes (exact; skipped for
    // ordinary sizes): κ = (sa/sv²)·κ' and the centre offset scales by sv²/sa.
    let (sv, sa) = (
        crate::numeric::pow2::pow2_scale(v.amax()),
        crate::numeric::pow2::pow2_scale(a.amax()),
    );
    let ordinary = sv == T::one() && sa == T::one();
    let (v, a) = if ordinary { (v, a) } else { (v / sv, a / sa) };
    let v2 = v.norm_squared();
    let c = cross(v, a);
    let speed = v2.sqrt();
    let kappa = c / (v2 * speed);
    let kappa = if ordinary {
        kappa
    } else {
        kappa * (sa / sv) / sv
    };
    // |c| ≤ 16ε·|v|·|a|, squared (no root for |a|; the sizes are ordinary here).
    let t = lit::<T>(16.0) * eps::<T>();
    if c * c <= t * t * v2 * a.norm_squared() {
        return (T::zero(), Centre::AtInfinity(perp(v) / speed));
    }
    let offset = perp(v) * (v2 / c);
    let mut centre = if ordinary {
        p + offset
    } else {
        p + offset * (sv / sa) * sv
    };
    if !finite(centre) {
        // The offset alone may pass the float range while the point cancels part of it (a
        // centre near the range's end seen from a point far out): the same sum, halved and
        // doubled (exact), is finite whenever the centre is.
        let half = lit::<T>(0.5);
        let offset = if ordinary {
            offset * half
        } else {
            offset * (sv / sa) * (sv * half)
        };
        centre = (p * half + offset) * lit::<T>(2.0);
    }
    if finite(centre) {
        (kappa, Centre::Finite(centre))
    } else {
        // The radius exceeds the float range: the centre is as good as at infinity.
        (kappa, Centre::AtInfinity(perp(v) / speed))
    }
}

/// Instantaneous motion of a rigid body: a reference point's position and first three
/// derivatives, and the body's angular velocity, acceleration and jerk.
///
/// ```
/// use linkage_core::{
///     catalog, instant_centre, Bodies, BodyId, BodyMotion, CrankRates, Vec2, GROUND,
/// };
/// let fb = catalog::hoecken::<f64>();
/// let m = fb.mechanism(); // joints O, C, A, B, P
/// let mut p = [Vec2::zeros(); 5];
/// m.pose(0.5, &mut p).unwrap();
/// let (mut v, mut a, j) = ([Vec2::zeros(); 5], [Vec2::zeros(); 5], [Vec2::zeros(); 5]);
/// m.rates(&p, CrankRates::unit(), &mut v, Some(&mut a), None).unwrap();
/// let bodies = Bodies::of(&m);
/// let motion = |id| BodyMotion::of(&bodies, id, &p, &v, &a, &j);
/// let crank = motion(BodyId { joint: 2, slot: 0 });
/// assert!((crank.omega - 1.0).abs() < 1e-12 && crank.velocity_at(p[0]).norm() < 1e-12);
/// // The coupler's instant centre from its motion is Kennedy's I13 = OA ∩ CB.
/// let coupler = motion(BodyId { joint: 3, slot: 0 });
/// let i13 = instant_centre(&coupler, &motion(GROUND)).finite().unwrap();
/// let kennedy = fb.instant_centres(0.5).unwrap()[1].finite().unwrap();
/// assert!((i13 - kennedy).norm() < 1e-9);
/// // Slices too short for the body's joints give a NaN motion, not a panic.
/// let short = BodyMotion::of(&bodies, BodyId { joint: 3, slot: 0 }, &p[..3], &v, &a, &j);
/// assert!(short.omega.is_nan());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyMotion<T> {
    /// Reference point.
    pub origin: Vec2<T>,
    /// Its velocity.
    pub v: Vec2<T>,
    /// Its acceleration.
    pub a: Vec2<T>,
    /// Its jerk.
    pub j: Vec2<T>,
    /// Angular velocity.
    pub omega: T,
    /// Angular acceleration.
    pub alpha: T,
    /// Angular jerk.
    pub alpha_rate: T,
    /// Rounding bound of `omega` (it is formed from joint velocities).
    pub omega_tol: T,
}

impl<T: RealField + Copy> BodyMotion<T> {
    /// Velocity of the body point at `p`.
    pub fn velocity_at(&self, p: Vec2<T>) -> Vec2<T> {
        self.v + perp(p - self.origin) * self.omega
    }

    /// Acceleration of the body point at `p`.
    pub fn acceleration_at(&self, p: Vec2<T>) -> Vec2<T> {
        let r = p - self.origin;
        self.a + perp(r) * self.alpha - r * (self.omega * self.omega)
    }

    /// Jerk of the body point at `p`.
    pub fn jerk_at(&self, p: Vec2<T>) -> Vec2<T> {
        let r = p - self.origin;
        let w = self.omega;
        self.j + perp(r) * (self.alpha_rate - w * w * w) - r * (lit::<T>(3.0) * w * self.alpha)
    }

    /// The same motion with `omega_tol` widened for rates solved at assembly margin `margin`
    /// (the sample's smallest): such rates carry a relative error `ε/margin²` (see
    /// [`crate::rate_margin`]), so an angular velocity below `omega_tol/margin²` is zero to
    /// rounding — a parallelogram's coupler next to its flat position translates, and its
    /// instant centre is at infinity, not at a distance set by rounding.
    pub fn conditioned(mut self, margin: T) -> Self {
        let m = margin.min(T::one()).max(eps::<T>());
        // Times 1/m² (not over m²): the held pass forms 1/m² once a sample, for every body.
        self.omega_tol *= T::one() / (m * m);
        self
    }

    /// Motion of body `id` from joint positions and rates (accelerations and jerks may be
    /// zero slices when only velocities matter). A joint index beyond a slice reads as NaN, so
    /// short slices give a NaN motion, not a panic.
    pub fn of<const N: usize>(
        bodies: &Bodies<N>,
        id: BodyId,
        pos: &[Vec2<T>],
        vel: &[Vec2<T>],
        acc: &[Vec2<T>],
        jerk: &[Vec2<T>],
    ) -> Self {
        let zero = Vec2::zeros();
        let still = BodyMotion {
            origin: zero,
            v: zero,
            a: zero,
            j: zero,
            omega: T::zero(),
            alpha: T::zero(),
            alpha_rate: T::zero(),
            omega_tol: T::zero(),
        };
        let frame = bodies.frame(id);
        // The joints the frame reads must be in every slice; otherwise the motion is NaN.
        let (i, j) = match frame {
            BodyFrame::Ground => (0, 0),
            BodyFrame::Link { origin, toward } => (origin, toward),
            BodyFrame::Block { joint, carrier } => {
                carrier.map_or((joint, joint), |(p, q)| (joint.max(p), q))
            }
        };
        let shortest = pos.len().min(vel.len()).min(acc.len()).min(jerk.len());
        if !matches!(frame, BodyFrame::Ground) && i.max(j) >= shortest {
            let nan = crate::numeric::scalar::nan::<T>();
            let bad = Vec2::new(nan, nan);
            return BodyMotion {
                origin: bad,
                v: bad,
                a: bad,
                j: bad,
                omega: nan,
                alpha: nan,
                alpha_rate: nan,
                omega_tol: nan,
            };
        }
        // (every index below is now within every slice)
        let (pos, vel, acc, jerk) = (
            |k: usize| pos[k],
            |k: usize| vel[k],
            |k: usize| acc[k],
            |k: usize| jerk[k],
        );
        let turn = |p: usize, q: usize| {
            let d = pos(q) - pos(p);
            let (w, al, jk) =
                direction_rates(d, vel(q) - vel(p), acc(q) - acc(p), jerk(q) - jerk(p));
            // Sizes, not lengths (max-abs: within √2, no roots): this only sets a tolerance.
            let (vp, vq) = (vel(p), vel(q));
            let scale = (size(vp.x, vp.y) + size(vq.x, vq.y)) / size(d.x, d.y);
            (
                w,
                al,
                jk,
                lit::<T>(ZERO_RATE) * eps::<T>() * (w.abs() + scale),
            )
        };
        let at = |k: usize, (w, al, jk, tol): (T, T, T, T)| BodyMotion {
            origin: pos(k),
            v: vel(k),
            a: acc(k),
            j: jerk(k),
            omega: w,
            alpha: al,
            alpha_rate: jk,
            omega_tol: tol,
        };
        match frame {
            BodyFrame::Ground => still,
            BodyFrame::Link { origin, toward } => at(origin, turn(origin, toward)),
            BodyFrame::Block { joint, carrier } => match carrier {
                None => at(joint, (T::zero(), T::zero(), T::zero(), T::zero())),
                Some((p, q)) => at(joint, turn(p, q)),
            },
        }
    }
}

/// Instant centre of the relative motion of two bodies: the point with the same velocity in
/// both, `P + (Δv)⊥/Δω` for any `P` (here `k`'s reference point).
///
/// When `Δω` is zero to rounding (parallel links, a translating coupler) the centre is at
/// infinity perpendicular to the relative velocity; when both bodies move alike it is undefined.
pub fn instant_centre<T: RealField + Copy>(k: &BodyMotion<T>, l: &BodyMotion<T>) -> Centre<T> {
    let p = k.origin;
    let dv = k.velocity_at(p) - l.velocity_at(p);
    let dw = k.omega - l.omega;
    if !(dv.x.is_finite() && dv.y.is_finite() && dw.is_finite()) {
        return Centre::Undefined;
    }
    if dw.abs() <= k.omega_tol + l.omega_tol {
        let n = length(dv);
        let vscale = size(k.v.x, k.v.y) + size(l.v.x, l.v.y);
        return if n <= lit::<T>(ZERO_RATE) * eps::<T>() * vscale || n == T::zero() {
            Centre::Undefined
        } else {
            Centre::AtInfinity(perp(dv) / n)
        };
    }
    // One division, then products (the held pass's formula, for every pair of a sample).
    Centre::Finite(p + perp(dv) * (T::one() / dw))
}

/// Instant centre of bodies `k` and `l` of a mechanism moving with `mk`, `ml`: the pin joining
/// them if they share one (a primary centre, which stays defined even at an instant where the
/// two bodies happen to move alike), otherwise [`instant_centre`].
pub fn relative_centre<T: RealField + Copy, const N: usize>(
    bodies: &Bodies<N>,
    (k, mk): (BodyId, &BodyMotion<T>),
    (l, ml): (BodyId, &BodyMotion<T>),
    pos: &[Vec2<T>],
) -> Centre<T> {
    match bodies.shared_joint(k, l) {
        Some(j) => pos.get(j).map_or(Centre::Undefined, |&p| Centre::Finite(p)),
        None => instant_centre(mk, ml),
    }
}

/// Intersection of the lines `p + t·d` and `q + s·e`: at infinity along `d` when they are
/// parallel to rounding. Used for the Aronhold–Kennedy construction of a four-bar's centres.
pub fn line_intersection<T: RealField + Copy>(
    p: Vec2<T>,
    d: Vec2<T>,
    q: Vec2<T>,
    e: Vec2<T>,
) -> Centre<T> {
    // Directions divided by powers of two near their sizes (exact; 1 for ordinary sizes): the
    // lines are the same, and the cross product cannot overflow.
    let (d, e) = (
        d / crate::numeric::pow2::pow2_scale(d.amax()),
        e / crate::numeric::pow2::pow2_scale(e.amax()),
    );
    let w = cross(d, e);
    let (nd, ne) = (d.norm(), e.norm());
    if nd == T::zero() || ne == T::zero() {
        return Centre::Undefined;
    }
    if w.abs() <= lit::<T>(ZERO_RATE) * eps::<T>() * nd * ne {
        return Centre::AtInfinity(d / nd);
    }
    Centre::Finite(p + d * (cross(q - p, e) / w))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circumcentre_of_unit_circle_points() {
        let c = circumcentre(
            Vec2::new(1.0_f64, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(-1.0, 0.0),
        );
        assert!(
            c.finite().unwrap().norm() < 1e-15,
            "circumcentre of the unit circle {c:?}"
        );
        let line = circumcentre(
            Vec2::new(0.0_f64, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(2.0, 2.0),
        );
        assert!(
            matches!(line, Centre::AtInfinity(_)),
            "circumcentre of collinear points {line:?}"
        );
    }

    #[test]
    fn curvature_of_circle_any_timing() {
        // Circle of radius 2 about (1, 1), at angle φ with φ̇ = 3, φ̈ = −5.
        let (r, phi, w, al) = (2.0_f64, 0.7_f64, 3.0, -5.0);
        let (s, c) = phi.sin_cos();
        let p = Vec2::new(1.0 + r * c, 1.0 + r * s);
        let v = Vec2::new(-r * s, r * c) * w;
        let a = Vec2::new(-r * s, r * c) * al - Vec2::new(r * c, r * s) * (w * w);
        let (k, centre) = path_curvature(p, v, a);
        assert!((k - 0.5).abs() < 1e-15, "curvature {k} for radius 2");
        assert!(
            (centre.finite().unwrap() - Vec2::new(1.0, 1.0)).norm() < 1e-14,
            "centre {centre:?} against (1, 1)"
        );
        // Reversed travel: curvature changes sign, the centre does not.
        let (k2, c2) = path_curvature(p, -v, a);
        assert!(
            (k2 + 0.5).abs() < 1e-15,
            "curvature {k2} travelled backwards"
        );
        assert!(
            (c2.finite().unwrap() - Vec2::new(1.0, 1.0)).norm() < 1e-14,
            "centre {c2:?} travelled backwards, against (1, 1)"
        );
        let (k0, c0) = path_curvature(p, Vec2::zeros(), a);
        assert!(
            matches!(c0, Centre::Undefined),
            "at rest: curvature {k0}, centre {c0:?}"
        );
    }
}
