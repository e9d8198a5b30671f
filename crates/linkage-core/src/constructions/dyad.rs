//! The RRR dyad: a joint at given distances from two known joints.

use nalgebra::RealField;

use crate::numeric::pow2::pow2_scale;
use crate::numeric::scalar::{cross, eps, length, lit, perp, Vec2};

/// Which of the two mirror-image solutions of a dyad: the side of the directed line from the
/// first base joint to the second on which the new joint lies.
///
/// Named `"left"` and `"right"` ([`Side::name`], parsed back by `FromStr`).
///
/// ```
/// use linkage_core::{Dyad, Error, Side, Vec2};
/// // Base (0, 0) → (5, 0): the left solution is above the x axis, the right one its mirror.
/// let d = Dyad { r1: 3.0_f64, r2: 4.0 };
/// let pose = d.solve(Vec2::zeros(), Vec2::new(5.0, 0.0), 0.0).unwrap();
/// assert!((pose.point(Side::Left) - Vec2::new(1.8, 2.4)).norm() < 1e-15);
/// assert!((pose.point(Side::Right) - Vec2::new(1.8, -2.4)).norm() < 1e-15);
/// assert_eq!((Side::Left.sign::<f64>(), Side::Left.flipped()), (1.0, Side::Right));
/// assert_eq!("right".parse::<Side>(), Ok(Side::Right));
/// assert_eq!(Side::Left.to_string(), "left");
/// assert_eq!(
///     "up".parse::<Side>(),
///     Err(Error::InvalidChoice { what: "side", choices: "'left' or 'right'" })
/// );
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    /// Left of `p1 → p2` (the triangle `p1, p2, joint` is counter-clockwise).
    Left,
    /// Right of `p1 → p2` (the triangle `p1, p2, joint` is clockwise).
    Right,
}

impl Side {
    /// `+1` for [`Side::Left`], `-1` for [`Side::Right`].
    #[inline]
    pub fn sign<T: RealField>(self) -> T {
        match self {
            Side::Left => T::one(),
            Side::Right => -T::one(),
        }
    }

    /// The other side.
    #[inline]
    pub fn flipped(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    }
}

crate::choice::choice_names!(Side, "side", Left => "left", Right => "right");

/// Area of a triangle with sides `a`, `b`, `c` (any order), by Kahan's formula
/// `¼·√((a+(b+c))(c−(a−b))(c+(a−b))(a+(b−c)))` with `a ≥ b ≥ c`.
///
/// Unlike Heron's formula or `h = √(r² − x²)`, every factor is formed without cancellation, so
/// the area keeps full relative accuracy for needle-like triangles — which is what a dyad near
/// its toggle position is (W. Kahan, "Miscalculating Area and Angles of a Needle-like
/// Triangle", 2014).
///
/// # Errors
/// When the sides violate the triangle inequality by more than `tol`, returns `Err(gap)` with
/// `gap = a − (b + c) > tol` (how much the longest side exceeds the other two). A violation of at
/// most `tol` is treated as a touching (flat) triangle of area zero; pass `tol` at rounding level.
pub fn triangle_area<T: RealField + Copy>(a: T, b: T, c: T, tol: T) -> Result<T, T> {
    let (a, b, c) = sorted_desc(a, b, c);
    let amb = a - b;
    let f2 = c - amb;
    if f2 < T::zero() {
        let gap = -f2;
        return if gap <= tol { Ok(T::zero()) } else { Err(gap) };
    }
    let prod = (a + (b + c)) * f2 * (c + amb) * (a + (b - c));
    Ok(prod.sqrt() * lit::<T>(0.25))
}

/// `a, b, c` in descending order, by three compare-swaps.
fn sorted_desc<T: RealField + Copy>(a: T, b: T, c: T) -> (T, T, T) {
    let (mut a, mut b, mut c) = (a, b, c);
    if a < b {
        core::mem::swap(&mut a, &mut b);
    }
    if b < c {
        core::mem::swap(&mut b, &mut c);
    }
    if a < b {
        core::mem::swap(&mut a, &mut b);
    }
    (a, b, c)
}

/// The sides `(hi, mid, lo)` of a triangle with one varying side `d` and two fixed ones whose
/// longer is `rmax` and shorter `rmin`: `hi = max(d, rmax)`, `lo = min(d, rmin)`, `mid` the
/// other — the values [`sorted_desc`]'s compare-swaps give, as selects, so the vectorised
/// kernels (the held pass, the batch, the uniform sweep) sort by the same rule.
#[inline(always)]
pub(crate) fn sorted_with<T: RealField + Copy>(d: T, rmin: T, rmax: T) -> (T, T, T) {
    let hi = if d > rmax { d } else { rmax };
    let lo = if d < rmin { d } else { rmin };
    let mid = if d < rmin {
        rmin
    } else if d > rmax {
        rmax
    } else {
        d
    };
    (hi, mid, lo)
}

/// [`triangle_area`] with its vanishing factor `f2 = (b + c) − a` (`a` the longest side) given,
/// formed by the caller without cancellation.
fn triangle_area_given<T: RealField + Copy>(a: T, b: T, c: T, f2: T, tol: T) -> Result<T, T> {
    let (a, b, c) = sorted_desc(a, b, c);
    if f2 < T::zero() || !f2.is_finite() {
        let gap = -f2;
        return if gap <= tol { Ok(T::zero()) } else { Err(gap) };
    }
    let prod = (a + (b + c)) * f2 * (c + (a - b)) * (a + (b - c));
    Ok(prod.sqrt() * lit::<T>(0.25))
}

/// The crank angles, measured from the ground direction, at which a crank of radius `r` about
/// a pivot `g` from the rocker pivot puts a dyad `(r1, r2)` flat: `0` when `|g − r|`, `π` when
/// `g + r` equals `|r1 − r2|` or `r1 + r2` to `8ε` of the lengths (a change point).
pub(crate) fn flat_angles<T: RealField + Copy>(g: T, r: T, r1: T, r2: T) -> [Option<T>; 2] {
    let (delta, sigma) = ((r1 - r2).abs(), r1 + r2);
    let tol = eps::<T>() * lit::<T>(8.0) * (g + r + sigma);
    let flat = |d: T| (d - delta).abs() <= tol || (d - sigma).abs() <= tol;
    [flat((g - r).abs()).then(T::zero), flat(g + r).then(T::pi)]
}

/// Relative triangle slack (`f₂` over the longest side) below which a dyad asks its caller for a
/// cancellation-free base ([`Dyad::solve_with_base`]); vectorised kernels that have no such
/// base solve those samples again exactly, so both agree to rounding everywhere.
pub(crate) const EXACT_BASE_SLACK: f64 = 0.0625;

/// A solved dyad: both mirror-image candidates are `foot ± offset`.
///
/// ```
/// use linkage_core::{Dyad, Side, Vec2};
/// // Links 3 and 4 on a base of 5: a right angle at the joint.
/// let d = Dyad { r1: 3.0_f64, r2: 4.0 };
/// let pose = d.solve(Vec2::zeros(), Vec2::new(5.0, 0.0), 0.0).unwrap();
/// assert!((pose.foot - Vec2::new(1.8, 0.0)).norm() < 1e-15);
/// assert_eq!(pose.point(Side::Left), pose.foot + pose.offset);
/// assert!((pose.margin - 1.0).abs() < 1e-15);
/// // Stretched flat (base 7 = 3 + 4): the two solutions coincide, margin 0 (a toggle).
/// let flat = d.solve(Vec2::zeros(), Vec2::new(7.0, 0.0), 0.0).unwrap();
/// assert_eq!((flat.offset.norm(), flat.margin), (0.0, 0.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DyadPose<T: RealField + Copy> {
    /// Foot of the perpendicular from the joint onto the line `p1 p2`.
    pub foot: Vec2<T>,
    /// From the foot to the joint on the [`Side::Left`] candidate (length `h`).
    pub offset: Vec2<T>,
    /// Assembly margin `sin γ = 2·Area/(r1·r2)`, where `γ` is the angle between the two links at
    /// the joint: 1 when they are perpendicular, 0 at a toggle (links collinear). It is also
    /// the velocity Jacobian's determinant divided by `r1·r2`, so `1/margin` bounds how much
    /// velocities and accelerations amplify input errors.
    pub margin: T,
}

impl<T: RealField + Copy> DyadPose<T> {
    /// The joint on the given side.
    #[inline]
    pub fn point(&self, side: Side) -> Vec2<T> {
        match side {
            Side::Left => self.foot + self.offset,
            Side::Right => self.foot - self.offset,
        }
    }
}

/// An RRR dyad: a joint at distance `r1` from a first known joint and `r2` from a second.
///
/// ```
/// use linkage_core::{Dyad, Side, Vec2};
/// let d = Dyad { r1: 3.0_f64, r2: 4.0 };
/// let pose = d.solve(Vec2::new(0.0, 0.0), Vec2::new(5.0, 0.0), 0.0).unwrap();
/// let p = pose.point(Side::Left);
/// assert!((p - Vec2::new(1.8, 2.4)).norm() < 1e-15);
/// assert!((pose.margin - 1.0).abs() < 1e-15); // a right angle at the joint
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dyad<T> {
    /// Distance from the first base joint.
    pub r1: T,
    /// Distance from the second base joint.
    pub r2: T,
}

/// How a dyad failed to close.
///
/// ```
/// use linkage_core::{Dyad, DyadFailure, Vec2};
/// // A base of 10 for links 3 and 4: the circles miss each other by 3.
/// let d = Dyad { r1: 3.0_f64, r2: 4.0 };
/// assert_eq!(d.solve(Vec2::zeros(), Vec2::new(10.0, 0.0), 0.0), Err(DyadFailure::Gap(3.0)));
/// // Coincident base joints and equal links: every point of the circle would do.
/// let e = Dyad { r1: 2.0_f64, r2: 2.0 };
/// let p = Vec2::new(1.0, 1.0);
/// assert_eq!(e.solve(p, p, 0.0), Err(DyadFailure::Undetermined));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DyadFailure<T> {
    /// The circles do not meet; the lengths miss closure by this much.
    Gap(T),
    /// The base joints coincide and `r1 = r2`: every point of the circle is a solution.
    Undetermined,
}

impl<T: RealField + Copy> Dyad<T> {
    /// Solves the dyad on base joints `p1`, `p2`.
    ///
    /// With `d = |p2 − p1|`, the joint lies at `x = (d² + (r1 − r2)(r1 + r2)) / 2d` along
    /// `p1 → p2` and at height `h = 2·Area(d, r1, r2)/d` from that line ([`triangle_area`]).
    /// `slack` (length units, ≥ 0) widens the rounding tolerance below which a closure miss is
    /// treated as a toggle; the tolerance always includes `8 ε (d + r1 + r2 + |p1| + |p2|)`,
    /// the rounding the inputs themselves carry.
    ///
    /// # Errors
    /// [`DyadFailure::Gap`] when the circles do not meet, [`DyadFailure::Undetermined`] when
    /// `p1 = p2` and `r1 = r2`.
    pub fn solve(&self, p1: Vec2<T>, p2: Vec2<T>, slack: T) -> Result<DyadPose<T>, DyadFailure<T>> {
        self.solve_with_base(p1, p2, slack, || None)
    }

    /// As [`Dyad::solve`], given a cancellation-free form of the base when the caller has one:
    /// `base()` returns the base vector `p2 − p1` and Kahan's vanishing factor for it, in length
    /// units: `r1 + r2 − d` when `d ≥ max(r1, r2)` (stretched), else `d − |r1 − r2|` (folded).
    ///
    /// Next to a toggle Kahan's vanishing factor is `d − |r1 − r2|` (folded) or `r1 + r2 − d`
    /// (stretched); from a `d` rounded to `ε·d` it keeps only the digits its size allows, and the
    /// joint's height `h ∝ √factor` loses half of them; a base that shrinks to nothing (a kite's
    /// crank pin passing over the rocker pivot) loses its direction the same way. When the base
    /// joints are a crank pin and a fixed joint, the vector and both differences have exact
    /// closed forms in the crank angle (see [`crate::Mechanism`]), so the pose keeps full
    /// accuracy up to the flat position itself. `base` is called only when the plain factor is
    /// below 1/16 of the longest side, so the common case pays nothing.
    pub(crate) fn solve_with_base(
        &self,
        p1: Vec2<T>,
        p2: Vec2<T>,
        slack: T,
        base: impl FnOnce() -> Option<(Vec2<T>, T)>,
    ) -> Result<DyadPose<T>, DyadFailure<T>> {
        let (r1, r2) = (self.r1, self.r2);
        let (mut dv, mut d) = (p2 - p1, length(p2 - p1));
        let longest = d.max(r1).max(r2);
        let plain = (d + r1.min(r2)).min(r1 + r2) - longest;
        let mut flat = None;
        if plain < longest * lit::<T>(EXACT_BASE_SLACK) {
            if let Some((v, f2)) = base() {
                (dv, d) = (v, length(v));
                flat = Some(f2);
            }
        }
        let scale = d + r1 + r2 + p1.amax() + p2.amax();
        let tol = eps::<T>() * lit::<T>(8.0) * scale + slack;
        if d == T::zero() {
            let gap = (r1 - r2).abs();
            return if gap > tol {
                Err(DyadFailure::Gap(gap))
            } else {
                Err(DyadFailure::Undetermined)
            };
        }
        // Work in units of a power of two near the longest side, so that no product in Kahan's
        // formula or in the margin overflows or underflows whatever the linkage's scale, and the
        // scaling itself is exact (it changes no bit of an ordinary-sized linkage).
        let s = pow2_scale(d.max(r1).max(r2));
        let (ds, r1s, r2s, tols) = if s == T::one() {
            (d, r1, r2, tol)
        } else {
            (d / s, r1 / s, r2 / s, tol / s)
        };
        let area = match flat {
            Some(f2) => triangle_area_given(ds, r1s, r2s, f2 / s, tols),
            None => triangle_area(ds, r1s, r2s, tols),
        }
        .map_err(|g| DyadFailure::Gap(g * s))?;
        // Products by reciprocals rather than divisions (the block kernel's formulas, see
        // `held.rs`: the same bits either way).
        let inv_d = T::one() / d;
        let inv_ds = if s == T::one() { inv_d } else { T::one() / ds };
        let u = dv * inv_d;
        let x = (d + (r1 - r2) * ((r1 + r2) * inv_d)) * lit::<T>(0.5);
        let h = lit::<T>(2.0) * (area * inv_ds) * s;
        Ok(DyadPose {
            foot: p1 + u * x,
            offset: perp(u) * h,
            margin: area * (lit::<T>(2.0) / (r1s * r2s)),
        })
    }

    /// Velocity of the joint `p` from the velocities of the base joints.
    ///
    /// Differentiating `|p − p1|² = r1²`, `|p − p2|² = r2²` gives the 2×2 system
    /// `[(p − p1)ᵀ; (p − p2)ᵀ] v = [(p − p1)·v1; (p − p2)·v2]`, whose determinant
    /// `(p − p1) × (p − p2) = ±r1·r2·margin` is the dyad's doubled area. Returns `None` at a toggle
    /// (determinant zero), where the velocity is unbounded.
    pub fn velocity(
        p1: Vec2<T>,
        v1: Vec2<T>,
        p2: Vec2<T>,
        v2: Vec2<T>,
        p: Vec2<T>,
    ) -> Option<Vec2<T>> {
        let (e1, e2) = unit_rows(p - p1, p - p2);
        solve_rows(e1, e2, e1.dot(&v1), e2.dot(&v2))
    }

    /// Acceleration of the joint `p` (velocity `v`) from the base joints' motion.
    ///
    /// Differentiating twice: `(p − pi)·(a − ai) + |v − vi|² = 0` for `i = 1, 2`, the same matrix
    /// as [`Dyad::velocity`]. Returns `None` at a toggle.
    #[allow(
        clippy::too_many_arguments,
        reason = "the dyad's two base points with their velocities and accelerations, and the joint"
    )]
    pub fn acceleration(
        p1: Vec2<T>,
        v1: Vec2<T>,
        a1: Vec2<T>,
        p2: Vec2<T>,
        v2: Vec2<T>,
        a2: Vec2<T>,
        p: Vec2<T>,
        v: Vec2<T>,
    ) -> Option<Vec2<T>> {
        let (e1, e2) = (p - p1, p - p2);
        let s = pow2_scale(e1.amax().max(e2.amax()));
        let (w1, w2) = (v - v1, v - v2);
        let sc = |x: Vec2<T>| if s == T::one() { x } else { x / s };
        let (e1, e2) = (sc(e1), sc(e2));
        solve_rows(
            e1,
            e2,
            e1.dot(&a1) - sc(w1).dot(&w1),
            e2.dot(&a2) - sc(w2).dot(&w2),
        )
    }
}

/// The rows `e1`, `e2` of the rate equations divided by one power of two near the larger
/// (exact, and no change for ordinary sizes): the solution is the same, but the determinant
/// and the right-hand sides `e·v` neither underflow nor overflow at any linkage scale.
#[inline]
fn unit_rows<T: RealField + Copy>(e1: Vec2<T>, e2: Vec2<T>) -> (Vec2<T>, Vec2<T>) {
    let s = pow2_scale(e1.amax().max(e2.amax()));
    if s == T::one() {
        (e1, e2)
    } else {
        (e1 / s, e2 / s)
    }
}

/// Solves `[e1ᵀ; e2ᵀ] x = [b1; b2]` by Cramer's rule; `None` if the rows are parallel.
///
/// The numerators are multiplied by `1/det` (half an ulp more error than dividing each): the
/// held pass forms `1/det` once a sample for a dyad's velocity and acceleration, and must give
/// these bits.
#[inline]
pub(crate) fn solve_rows<T: RealField + Copy>(
    e1: Vec2<T>,
    e2: Vec2<T>,
    b1: T,
    b2: T,
) -> Option<Vec2<T>> {
    let det = cross(e1, e2);
    if det == T::zero() || !det.is_finite() {
        return None;
    }
    let inv = T::one() / det;
    Some(Vec2::new(
        (b1 * e2.y - b2 * e1.y) * inv,
        (e1.x * b2 - e2.x * b1) * inv,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pow2_scale_is_one_for_ordinary_sizes_and_tight_otherwise() {
        for x in [1.0, 2.5e-10, 4.0e9, 2f64.powi(-32), 2f64.powi(32)] {
            assert_eq!(pow2_scale(x), 1.0, "{x:e}");
        }
        for x in [
            1e-300,
            3.7e-301,
            2f64.powi(-1000),
            1e300,
            2f64.powi(1000),
            1.7e308,
            4e-320,
        ] {
            let s = pow2_scale(x);
            assert_eq!(s.log2().fract(), 0.0, "{x:e}: {s:e} not a power of two");
            assert!((1.0..2.0).contains(&(x / s)), "{x:e}: x/s = {}", x / s);
        }
        // f32 the same way.
        let s = pow2_scale(1e-30_f32);
        assert!(
            (1.0..2.0).contains(&(1e-30_f32 / s)),
            "1e-30_f32: x/s = {}",
            1e-30_f32 / s
        );
        assert_eq!(pow2_scale(f64::NAN), 1.0, "scale of NaN");
    }

    #[test]
    fn kahan_area_of_3_4_5() {
        assert_eq!(triangle_area(3.0, 4.0, 5.0, 0.0), Ok(6.0), "sides 3, 4, 5");
        assert_eq!(triangle_area(5.0, 3.0, 4.0, 0.0), Ok(6.0), "sides 5, 3, 4");
    }

    #[test]
    fn needle_triangle_keeps_relative_accuracy() {
        // Sides 1, 1, 2 − δ: exact area = ½·(1 − δ/2)·√(δ(4 − δ))·... computed in closed form:
        // height h = √(1 − (1 − δ/2)²) = √(δ − δ²/4); area = (1 − δ/2)·h.
        let delta = 1e-12_f64;
        let base = 2.0 - delta;
        let exact = (1.0 - delta / 2.0) * (delta - delta * delta / 4.0).sqrt();
        let kahan = triangle_area(1.0, 1.0, base, 0.0).unwrap();
        // The base 2 − δ itself is rounded (relative 1e-16, i.e. δ changes by ~2e-16 relative
        // 2e-4): the area follows √δ, so a relative error up to 1e-4 is the conditioning, not
        // the formula. Heron's formula gives no correct digits here.
        let base_delta = 2.0 - base;
        let exact_rounded =
            (1.0 - base_delta / 2.0) * (base_delta - base_delta * base_delta / 4.0).sqrt();
        assert!(
            (kahan - exact_rounded).abs() <= 1e-14 * exact_rounded,
            "{kahan} vs {exact_rounded}"
        );
        assert!(
            (kahan - exact).abs() <= 2e-4 * exact,
            "{kahan} vs unrounded {exact}"
        );
    }

    #[test]
    fn violation_reports_gap_and_rounding_touch() {
        assert_eq!(
            triangle_area(1.0, 1.0, 3.0, 0.0),
            Err(1.0),
            "sides 1, 1, 3: gap"
        );
        assert_eq!(
            triangle_area(1.0, 1.0, 2.0 + 1e-15, 1e-14),
            Ok(0.0),
            "sides 1, 1, 2 + 1e-15 within the rounding allowance 1e-14"
        );
    }

    #[test]
    fn dyad_3_4_5_both_sides() {
        let d = Dyad { r1: 3.0, r2: 4.0 };
        let pose = d
            .solve(Vec2::new(1.0, 1.0), Vec2::new(1.0, 6.0), 0.0)
            .unwrap();
        // p1 → p2 points +y; left is −x.
        assert!(
            (pose.point(Side::Left) - Vec2::new(1.0 - 2.4, 1.0 + 1.8)).norm() < 1e-15,
            "left {:?} against (-1.4, 2.8)",
            pose.point(Side::Left)
        );
        assert!(
            (pose.point(Side::Right) - Vec2::new(1.0 + 2.4, 1.0 + 1.8)).norm() < 1e-15,
            "right {:?} against (3.4, 2.8)",
            pose.point(Side::Right)
        );
    }

    #[test]
    fn dyad_apart_and_coincident() {
        let d = Dyad { r1: 1.0, r2: 1.0 };
        assert_eq!(
            d.solve(Vec2::new(0.0, 0.0), Vec2::new(3.0, 0.0), 0.0),
            Err(DyadFailure::Gap(1.0)),
            "links 1, 1 on a base 3"
        );
        assert_eq!(
            d.solve(Vec2::new(0.0, 0.0), Vec2::new(0.0, 0.0), 0.0),
            Err(DyadFailure::Undetermined),
            "links 1, 1 on coincident pivots"
        );
        let d = Dyad { r1: 1.0, r2: 3.0 };
        assert_eq!(
            d.solve(Vec2::new(0.0, 0.0), Vec2::new(0.0, 0.0), 0.0),
            Err(DyadFailure::Gap(2.0)),
            "links 1, 3 on coincident pivots"
        );
    }

    #[test]
    fn dyad_near_toggle_keeps_lengths() {
        // Links 1 and 1 on a base 2 − 1e-10: the joint is 1e-5 off the line.
        let d = Dyad {
            r1: 1.0_f64,
            r2: 1.0,
        };
        let p1 = Vec2::new(0.0, 0.0);
        let p2 = Vec2::new(2.0 - 1e-10, 0.0);
        let pose = d.solve(p1, p2, 0.0).unwrap();
        let p = pose.point(Side::Left);
        assert!(
            ((p - p1).norm() - 1.0).abs() < 4e-16,
            "link 1 length {} (want 1)",
            (p - p1).norm()
        );
        assert!(
            ((p - p2).norm() - 1.0).abs() < 4e-16,
            "link 2 length {} (want 1)",
            (p - p2).norm()
        );
        // h = √(1 − (d/2)²) ≈ 1e-5 and margin = h·d/(r1·r2) ≈ 2e-5; the naive √(r1² − x²) would
        // keep only about half of h's digits.
        // With δ = 2 − d (exact, Sterbenz), h² = 1 − (d/2)² = δ(1 − δ/4) exactly.
        let delta = 2.0 - p2.x;
        let h = (delta * (1.0 - delta / 4.0)).sqrt();
        assert!(p.y > 0.0 && (p.y - h).abs() < 1e-12 * h, "{} vs {h}", p.y);
        assert!(
            (pose.margin - h * p2.x).abs() < 1e-12 * pose.margin,
            "margin {} vs h·d = {}",
            pose.margin,
            h * p2.x
        );
    }
}
