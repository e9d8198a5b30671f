//! Rate analysis of a solved pose: velocities, accelerations and jerks of every joint.

use nalgebra::RealField;

use crate::constructions::dyad::solve_rows;
use crate::constructions::slider::LineDirection;
use crate::error::Error;
use crate::mechanism::program::{Construction, CrankRates, Mechanism};
use crate::numeric::scalar::{cross, eps, lit, nan, perp, Vec2};

/// The smallest assembly margin at which rates are computed: `m* = 32·√ε` (4.8e-7 for `f64`,
/// 0.011 for `f32`).
///
/// Why: next to a toggle a dyad's joint carries a rounding error of about `ε·L/m` (its height
/// over the base line is `√` of a small quantity known to `ε·L`), along the one direction the
/// links do not hold. The rate equations' determinant `(p − p1) × (p − p2) = ±r1·r2·m` therefore
/// carries a relative error `ε/m²`, and so do the velocities, accelerations and jerks solved
/// with it. Below `m*` that bound exceeds `2⁻¹⁰`: the rates are no longer numbers worth giving
/// (at an exact toggle they are `0/0` or unbounded), so they are NaN and the sample is flagged
/// (`regular == false`) instead — never a huge number. Above it, rates keep at least three
/// digits, and all of them once `m > ε^{1/4}` (1.2e-4).
pub fn rate_margin<T: RealField + Copy>() -> T {
    lit::<T>(32.0) * eps::<T>().sqrt()
}

/// Angular velocity, acceleration and jerk of the direction of `d(t)`, from `d` and its first
/// three time derivatives.
///
/// With `L² = d·d`, `S = d·ḋ`, `N = d × d̈`: `ω = (d × ḋ)/L²`, `α = (N − 2ωS)/L²`,
/// `α̇ = (ḋ × d̈ + d × d⃛ − 2NS/L² − 2(αS + ω(|ḋ|² + d·d̈)) + 4ωS²/L²)/L²` — exact whether or not
/// `|d|` is constant. Terms of orders not supplied are zero.
#[inline]
pub(crate) fn direction_rates<T: RealField + Copy>(
    d: Vec2<T>,
    d1: Vec2<T>,
    d2: Vec2<T>,
    d3: Vec2<T>,
) -> (T, T, T) {
    // The rates are homogeneous of degree 0 in (d, d1, d2, d3): dividing all four by one power
    // of two near |d| (exact, and no change for ordinary sizes) keeps |d|² and the cross
    // products from overflowing or underflowing at any linkage scale.
    let s = crate::numeric::pow2::pow2_scale(d.amax());
    let (d, d1, d2, d3) = if s == T::one() {
        (d, d1, d2, d3)
    } else {
        (d / s, d1 / s, d2 / s, d3 / s)
    };
    let two = lit::<T>(2.0);
    let l2 = d.norm_squared();
    // Times 1/|d|², formed once (the held pass's kernels form it once a sample too).
    let inv = T::one() / l2;
    let s = d.dot(&d1);
    let w = cross(d, d1) * inv;
    let n = cross(d, d2);
    let al = (n - two * w * s) * inv;
    let ds = d1.norm_squared() + d.dot(&d2);
    let jk = (cross(d1, d2) + cross(d, d3) - two * n * s * inv - two * (al * s + w * ds)
        + lit::<T>(4.0) * w * s * s * inv)
        * inv;
    (w, al, jk)
}

/// Velocity, acceleration and jerk of a point `r` from a body origin that moves with `(v, a, j)`
/// while the body turns with `(ω, α, α̇)`.
#[inline]
fn carried<T: RealField + Copy>(
    r: Vec2<T>,
    origin: (Vec2<T>, Vec2<T>, Vec2<T>),
    turn: (T, T, T),
) -> (Vec2<T>, Vec2<T>, Vec2<T>) {
    let (w, al, jk) = turn;
    let rp = perp(r);
    (
        origin.0 + rp * w,
        origin.1 + rp * al - r * (w * w),
        origin.2 + rp * (jk - w * w * w) - r * (lit::<T>(3.0) * w * al),
    )
}

impl<T: RealField + Copy, const N: usize> Mechanism<T, N> {
    /// Velocities of every joint of a solved pose and, when the slices are given,
    /// accelerations and jerks (jerks need accelerations).
    ///
    /// Each construction's rate equations are solved in program order: the dyad's 2×2 system
    /// `[(p − p1)ᵀ; (p − p2)ᵀ]` (see [`crate::Dyad::velocity`]) with right-hand sides
    /// `(p − pi)·vi`, `(p − pi)·ai − |v − vi|²` and `(p − pi)·ji − 3(v − vi)·(a − ai)`; the
    /// slider's scalar equation along its line; carried points by rigid-body kinematics. A joint
    /// whose assembly margin is below [`rate_margin`] (at or next to a toggle, where the rates
    /// are unbounded, `0/0`, or lost to rounding) gets NaN rates, and so does every joint built
    /// on it; the return value is then `false`.
    ///
    /// # Errors
    /// [`Error::BufferLength`] when a slice is not [`Mechanism::len`] long, or jerks are asked
    /// without accelerations.
    pub fn rates(
        &self,
        pos: &[Vec2<T>],
        drive: CrankRates<T>,
        vel: &mut [Vec2<T>],
        mut acc: Option<&mut [Vec2<T>]>,
        mut jerk: Option<&mut [Vec2<T>]>,
    ) -> Result<bool, Error> {
        let n = self.len();
        for (what, got) in [
            ("joints", pos.len()),
            ("velocities", vel.len()),
            ("accelerations", acc.as_ref().map_or(n, |a| a.len())),
            ("jerks", jerk.as_ref().map_or(n, |a| a.len())),
        ] {
            if got != n {
                return Err(Error::BufferLength {
                    what,
                    expected: n,
                    got,
                });
            }
        }
        if jerk.is_some() && acc.is_none() {
            return Err(Error::BufferLength {
                what: "accelerations (needed for jerks)",
                expected: n,
                got: 0,
            });
        }
        let (want_a, want_j) = (acc.is_some(), jerk.is_some());
        let zero = Vec2::zeros();
        let bad = Vec2::new(nan::<T>(), nan::<T>());
        // Accelerations and jerks of earlier joints, kept locally so every construction can read
        // them whether or not the caller asked for them.
        let mut al = [zero; N];
        let mut jk = [zero; N];
        let mut regular = true;
        let m_star = rate_margin::<T>();
        for (i, c) in self.constructions().iter().enumerate() {
            let p = pos[i];
            let (v, a, j) = match *c {
                Construction::Fixed { .. } => (zero, zero, zero),
                Construction::Crank { centre, .. } => carried(
                    p - pos[centre],
                    (vel[centre], al[centre], jk[centre]),
                    (drive.omega, drive.alpha, drive.jerk),
                ),
                Construction::Dyad { p1, p2, dyad, .. } => {
                    // Both rows divided by a power of two near the links' length (exact, no
                    // change for ordinary sizes): the system is the same, but neither the
                    // determinant nor `e·v`, `|w|²` overflow at any linkage scale.
                    let (e1, e2) = (p - pos[p1], p - pos[p2]);
                    let s = crate::numeric::pow2::pow2_scale(e1.amax().max(e2.amax()));
                    // (no division at all in the common case s = 1)
                    let sc = |v: Vec2<T>| if s == T::one() { v } else { v / s };
                    let (e1, e2) = (sc(e1), sc(e2));
                    // The rate margin on the scaled rows: |e1 × e2| = r1·r2·m, all over s².
                    let toggle = cross(e1, e2).abs() < m_star * (dyad.r1 / s) * (dyad.r2 / s);
                    match solve_rows(e1, e2, e1.dot(&vel[p1]), e2.dot(&vel[p2])) {
                        _ if toggle => (bad, bad, bad),
                        None => (bad, bad, bad),
                        Some(v) => {
                            let (w1, w2) = (v - vel[p1], v - vel[p2]);
                            let a = if want_a {
                                solve_rows(
                                    e1,
                                    e2,
                                    e1.dot(&al[p1]) - sc(w1).dot(&w1),
                                    e2.dot(&al[p2]) - sc(w2).dot(&w2),
                                )
                                .unwrap_or(bad)
                            } else {
                                zero
                            };
                            let j = if want_j {
                                let three = lit::<T>(3.0);
                                solve_rows(
                                    e1,
                                    e2,
                                    e1.dot(&jk[p1]) - three * sc(w1).dot(&(a - al[p1])),
                                    e2.dot(&jk[p2]) - three * sc(w2).dot(&(a - al[p2])),
                                )
                                .unwrap_or(bad)
                            } else {
                                zero
                            };
                            (v, a, j)
                        }
                    }
                }
                Construction::Slider {
                    pivot,
                    origin,
                    direction,
                    slider,
                    ..
                } => {
                    let u = direction.at(pos).unwrap_or(bad);
                    let toggle = (p - pos[pivot]).dot(&u).abs() < m_star * slider.r;
                    let turn = match direction {
                        LineDirection::Fixed(_) => (T::zero(), T::zero(), T::zero()),
                        LineDirection::Link { from, to, .. } => direction_rates(
                            pos[to] - pos[from],
                            vel[to] - vel[from],
                            al[to] - al[from],
                            jk[to] - jk[from],
                        ),
                    };
                    if toggle {
                        (bad, bad, bad)
                    } else {
                        slider_rates(
                            p,
                            u,
                            turn,
                            (pos[pivot], vel[pivot], al[pivot], jk[pivot]),
                            (pos[origin], vel[origin], al[origin], jk[origin]),
                            want_a,
                            want_j,
                        )
                        .unwrap_or((bad, bad, bad))
                    }
                }
                Construction::Point { from, to, .. } => {
                    let turn = direction_rates(
                        pos[to] - pos[from],
                        vel[to] - vel[from],
                        al[to] - al[from],
                        jk[to] - jk[from],
                    );
                    carried(p - pos[from], (vel[from], al[from], jk[from]), turn)
                }
            };
            if !(v.x.is_finite() && v.y.is_finite()) {
                regular = false;
            }
            vel[i] = v;
            al[i] = a;
            jk[i] = j;
            if let Some(out) = acc.as_deref_mut() {
                out[i] = a;
            }
            if let Some(out) = jerk.as_deref_mut() {
                out[i] = j;
            }
        }
        Ok(regular)
    }
}

/// Rates of a slider joint `p = q + s·u` at distance `r` from the pivot `a`.
///
/// `u` turns with `(ω, α, α̇)`; differentiating `(p − a)·(p − a) = r²` up to three times gives one
/// scalar equation per order for `ṡ`, `s̈`, `s⃛`, each divided by `(p − a)·u` (zero at a toggle,
/// where `None` is returned).
#[allow(
    clippy::type_complexity,
    reason = "a tuple of the slider's rates, named at the call"
)]
fn slider_rates<T: RealField + Copy>(
    p: Vec2<T>,
    u: Vec2<T>,
    turn: (T, T, T),
    pivot: (Vec2<T>, Vec2<T>, Vec2<T>, Vec2<T>),
    origin: (Vec2<T>, Vec2<T>, Vec2<T>, Vec2<T>),
    want_a: bool,
    want_j: bool,
) -> Option<(Vec2<T>, Vec2<T>, Vec2<T>)> {
    let (pa, va, aa, ja) = pivot;
    let (q, vq, aq, jq) = origin;
    let (w, al, jk) = turn;
    let (two, three) = (lit::<T>(2.0), lit::<T>(3.0));
    // The link vector divided by a power of two near its length (exact; 1 for ordinary sizes):
    // each equation below is divided through by it, so no dot product of two large vectors
    // overflows at any linkage scale.
    let unit = crate::numeric::pow2::pow2_scale((p - pa).amax());
    let sc = |v: Vec2<T>| if unit == T::one() { v } else { v / unit };
    let e = sc(p - pa);
    let den = e.dot(&u);
    if den == T::zero() || !den.is_finite() {
        return None;
    }
    let s = (p - q).dot(&u);
    let up = perp(u);
    let du = up * w;
    let ddu = up * al - u * (w * w);
    let dddu = up * (jk - w * w * w) - u * (three * w * al);
    let sd = e.dot(&(va - vq - du * s)) / den;
    let v = vq + u * sd + du * s;
    if !want_a {
        return Some((v, Vec2::zeros(), Vec2::zeros()));
    }
    let k2 = aq + du * (two * sd) + ddu * s;
    let sdd = (e.dot(&(aa - k2)) - sc(v - va).dot(&(v - va))) / den;
    let a = k2 + u * sdd;
    if !want_j {
        return Some((v, a, Vec2::zeros()));
    }
    let k3 = jq + du * (three * sdd) + ddu * (three * sd) + dddu * s;
    let sddd = (e.dot(&(ja - k3)) - three * sc(v - va).dot(&(a - aa))) / den;
    Some((v, a, k3 + u * sddd))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constructions::slider::Reach;

    /// Jerk of a slider-crank against the third derivative of x(θ) = r cos θ + √(l² − r² sin² θ),
    /// taken by a five-point difference of the analytic acceleration.
    #[test]
    fn slider_crank_jerk_matches_difference_of_acceleration() {
        let mut m = Mechanism::<f64, 3>::new();
        let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
        let a = m.crank(o, 2.0, 0.0).unwrap();
        let b = m
            .slider(
                a,
                5.0,
                o,
                LineDirection::Fixed(Vec2::new(1.0, 0.0)),
                Reach::Ahead,
            )
            .unwrap();
        let acc_at = |th: f64| {
            let mut p = [Vec2::zeros(); 3];
            m.pose(th, &mut p).unwrap();
            let (mut v, mut ac) = ([Vec2::zeros(); 3], [Vec2::zeros(); 3]);
            m.rates(&p, CrankRates::unit(), &mut v, Some(&mut ac), None)
                .unwrap();
            ac[b]
        };
        let th = 0.8;
        let mut p = [Vec2::zeros(); 3];
        m.pose(th, &mut p).unwrap();
        let (mut v, mut ac, mut j) = ([Vec2::zeros(); 3], [Vec2::zeros(); 3], [Vec2::zeros(); 3]);
        m.rates(&p, CrankRates::unit(), &mut v, Some(&mut ac), Some(&mut j))
            .unwrap();
        let h = 1e-3;
        let fd = (-acc_at(th + 2.0 * h) + acc_at(th + h) * 8.0 - acc_at(th - h) * 8.0
            + acc_at(th - 2.0 * h))
            / (12.0 * h);
        assert!((j[b] - fd).norm() < 1e-9, "{:?} vs {fd:?}", j[b]);
    }

    #[test]
    fn jerk_needs_acceleration() {
        let mut m = Mechanism::<f64, 2>::new();
        let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
        m.crank(o, 1.0, 0.0).unwrap();
        let p = [Vec2::zeros(), Vec2::new(1.0, 0.0)];
        let (mut v, mut j) = ([Vec2::zeros(); 2], [Vec2::zeros(); 2]);
        let got = m.rates(&p, CrankRates::unit(), &mut v, None, Some(&mut j));
        assert!(
            matches!(got, Err(Error::BufferLength { .. })),
            "jerk asked without acceleration: {got:?}"
        );
    }
}
