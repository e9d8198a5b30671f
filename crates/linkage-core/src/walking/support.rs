//! Static stability: the support polygon (convex hull of the stance pads) and the signed
//! distance of the centre of gravity's ground projection from its boundary.

use nalgebra::RealField;

use crate::error::Error;
use crate::numeric::pow2::pow2_scale;
use crate::numeric::scalar::{cross, Vec2};

/// A power of two that brings the largest coordinate of `points` (and `extra`) near 1, so that
/// differences and cross products of the scaled points neither overflow nor underflow; 1 for
/// ordinary coordinates (in [2⁻³², 2³²]), where nothing is rescaled. Dividing by it is exact
/// (short of subnormals).
fn hull_scale<T: RealField + Copy>(points: &[Vec2<T>], extra: Vec2<T>) -> T {
    let big = points
        .iter()
        .fold(extra.amax(), |m, p| if p.amax() > m { p.amax() } else { m });
    if big == T::zero() {
        T::one()
    } else {
        pow2_scale(big)
    }
}

/// Convex hull of `points` by Andrew's monotone chain, written counter-clockwise into `out`;
/// returns the hull's vertex count. Collinear points on an edge are dropped; 1 or 2 distinct
/// points give a degenerate hull of that many vertices.
///
/// Points with a NaN or infinite coordinate are left out (they are moved to the end of
/// `points`; the finite ones are sorted in place). Orientation tests run on the points scaled
/// by a power of two, so coordinates near the float maximum cannot overflow into a NaN test.
///
/// # Errors
/// [`Error::BufferLength`] when `out` is shorter than the number of finite points plus one.
pub fn convex_hull<T: RealField + Copy>(
    points: &mut [Vec2<T>],
    out: &mut [Vec2<T>],
) -> Result<usize, Error> {
    // Finite points first (a stable partition is not needed: they are sorted next).
    let mut n = 0;
    for i in 0..points.len() {
        if points[i].x.is_finite() && points[i].y.is_finite() {
            points.swap(n, i);
            n += 1;
        }
    }
    if out.len() < n + 1 {
        return Err(Error::BufferLength {
            what: "hull (finite points + 1)",
            expected: n + 1,
            got: out.len(),
        });
    }
    let points = &mut points[..n];
    if n == 0 {
        return Ok(0);
    }
    // Every coordinate is finite here, so `partial_cmp` never fails: the order is total.
    points.sort_unstable_by(|a, b| {
        a.x.partial_cmp(&b.x)
            .unwrap_or(core::cmp::Ordering::Equal)
            .then(a.y.partial_cmp(&b.y).unwrap_or(core::cmp::Ordering::Equal))
    });
    let s = hull_scale(points, Vec2::zeros());
    // `true` when `o → a → b` does not turn strictly counter-clockwise (so `a` is dropped). A
    // NaN test (impossible after scaling, kept as a guard) also drops, so the chain stays short.
    let drop = |o: Vec2<T>, a: Vec2<T>, b: Vec2<T>| {
        let (o, a, b) = (o / s, a / s, b / s);
        let turn = cross(a - o, b - o);
        turn.partial_cmp(&T::zero()) != Some(core::cmp::Ordering::Greater)
    };
    let mut k = 0;
    // Lower hull, then upper hull. Each chain is a stack of distinct points (popped before a
    // push), so `k` stays below `n + 1`; `get_mut` keeps even a broken order from writing past
    // `out`.
    for &p in points.iter() {
        while k >= 2 && drop(out[k - 2], out[k - 1], p) {
            k -= 1;
        }
        let Some(slot) = out.get_mut(k) else {
            return Err(Error::BufferLength {
                what: "hull (finite points + 1)",
                expected: k + 1,
                got: out.len(),
            });
        };
        *slot = p;
        k += 1;
    }
    let lower = k + 1;
    for &p in points[..n - 1].iter().rev() {
        while k >= lower && drop(out[k - 2], out[k - 1], p) {
            k -= 1;
        }
        let Some(slot) = out.get_mut(k) else {
            return Err(Error::BufferLength {
                what: "hull (finite points + 1)",
                expected: k + 1,
                got: out.len(),
            });
        };
        *slot = p;
        k += 1;
    }
    // The last point repeats the first (except for a single point).
    let mut count = if k > 1 { k - 1 } else { k };
    // Drop duplicates left by coincident points.
    if count == 2 && out[0] == out[1] {
        count = 1;
    }
    Ok(count)
}

/// Signed distance from `p` to the boundary of the convex polygon `hull` (counter-clockwise, as
/// [`convex_hull`] writes it): positive inside, negative outside — the static stability margin
/// of McGhee and Frank's CG projection method. A degenerate hull (a segment or a point) has no
/// inside: the result is minus the distance to it. `None` for an empty hull, or when `p` or a
/// vertex is not finite. Coordinates near the float maximum are scaled by a power of two first,
/// so the distance is right whenever it is representable (infinite only when it exceeds the
/// float maximum).
pub fn stability_margin<T: RealField + Copy>(p: Vec2<T>, hull: &[Vec2<T>]) -> Option<T> {
    let n = hull.len();
    let finite = |v: Vec2<T>| v.x.is_finite() && v.y.is_finite();
    if n == 0 || !finite(p) || !hull.iter().all(|&v| finite(v)) {
        return None;
    }
    let s = hull_scale(hull, p);
    let p = p / s;
    // Distance from `p` to the segment `a b`, all scaled.
    let seg_dist = |a: Vec2<T>, b: Vec2<T>| {
        let ab = b - a;
        let l2 = ab.norm_squared();
        let t = if l2 > T::zero() {
            ((p - a).dot(&ab) / l2).max(T::zero()).min(T::one())
        } else {
            T::zero()
        };
        crate::numeric::scalar::length(a + ab * t - p)
    };
    if n < 3 {
        return Some(-seg_dist(hull[0] / s, hull[n - 1] / s) * s);
    }
    let mut inside = true;
    let mut nearest = T::max_value().unwrap_or(T::one() / T::default_epsilon());
    // (scaled distances are at most 2³⁴, so the start value is above any of them)
    for i in 0..n {
        let (a, b) = (hull[i] / s, hull[(i + 1) % n] / s);
        if cross(b - a, p - a) < T::zero() {
            inside = false;
        }
        nearest = nearest.min(seg_dist(a, b));
    }
    Some(if inside { nearest * s } else { -nearest * s })
}

/// Support polygons and stability margins along a sweep of `cg.len()` samples with `feet`
/// pads each: for sample `s`, the convex hull of the finite points among
/// `pads[s·feet .. (s+1)·feet]` (a pad in the air is NaN) and the [`stability_margin`] of
/// `cg[s]` from it.
///
/// Writes sample `s`'s hull counter-clockwise into row `s` of `hulls` (rows of `feet + 1`
/// points, the unused tail set to NaN), its vertex count into `counts[s]` and the margin into
/// `margins[s]` (NaN when no pad is down or `cg[s]` is not finite). `scratch` holds one
/// sample's pads while they are sorted.
///
/// # Errors
/// [`Error::BufferLength`] when `pads` does not hold `feet` points per sample, `hulls` not
/// `feet + 1` per sample, `counts` or `margins` not one per sample, or `scratch` fewer than
/// `feet`.
pub fn support_margins<T: RealField + Copy>(
    pads: &[Vec2<T>],
    feet: usize,
    cg: &[Vec2<T>],
    scratch: &mut [Vec2<T>],
    hulls: &mut [Vec2<T>],
    counts: &mut [usize],
    margins: &mut [T],
) -> Result<(), Error> {
    let n = cg.len();
    let check = |what: &'static str, expected: Option<usize>, got: usize| match expected {
        Some(e) if e == got => Ok(()),
        e => Err(Error::BufferLength {
            what,
            expected: e.unwrap_or(usize::MAX),
            got,
        }),
    };
    check("pads (samples × feet)", n.checked_mul(feet), pads.len())?;
    let row = feet.checked_add(1);
    check(
        "hulls (samples × (feet + 1))",
        row.and_then(|r| r.checked_mul(n)),
        hulls.len(),
    )?;
    check("counts (one per sample)", Some(n), counts.len())?;
    check("margins (one per sample)", Some(n), margins.len())?;
    if scratch.len() < feet {
        return Err(Error::BufferLength {
            what: "scratch (feet)",
            expected: feet,
            got: scratch.len(),
        });
    }
    let nan = crate::numeric::scalar::nan::<T>();
    let row = feet + 1;
    for (s, &c) in cg.iter().enumerate() {
        let pts = &mut scratch[..feet];
        pts.copy_from_slice(&pads[s * feet..(s + 1) * feet]);
        let out = &mut hulls[s * row..(s + 1) * row];
        // `out` holds feet + 1 ≥ finite pads + 1 points: the hull always fits.
        let h = convex_hull(pts, out)?;
        out[h..].fill(Vec2::new(nan, nan));
        counts[s] = h;
        margins[s] = stability_margin(c, &out[..h]).unwrap_or(nan);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_hull_and_margins() {
        let mut pts = [
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(1.0, 1.0), // inside
            Vec2::new(2.0, 2.0),
            Vec2::new(0.0, 2.0),
            Vec2::new(1.0, 0.0), // on an edge
        ];
        let mut hull = [Vec2::zeros(); 7];
        let n = convex_hull(&mut pts, &mut hull).unwrap();
        assert_eq!(
            n, 4,
            "hull of a square with points inside and on an edge: {hull:?}"
        );
        let h = &hull[..n];
        assert_eq!(
            stability_margin(Vec2::new(1.0, 1.0), h),
            Some(1.0),
            "margin at the centre of {h:?}"
        );
        assert_eq!(
            stability_margin(Vec2::new(0.5, 1.0), h),
            Some(0.5),
            "margin at (0.5, 1) in {h:?}"
        );
        assert_eq!(
            stability_margin(Vec2::new(3.0, 1.0), h),
            Some(-1.0),
            "margin at (3, 1), outside {h:?}"
        );
        // Two pads touching at a point: a segment has no inside.
        let mut two = [Vec2::new(0.0, 0.0), Vec2::new(2.0, 0.0)];
        let m = convex_hull(&mut two, &mut hull).unwrap();
        assert_eq!(m, 2, "hull of two pads: {hull:?}");
        assert_eq!(
            stability_margin(Vec2::new(1.0, 0.5), &hull[..m]),
            Some(-0.5),
            "margin over a segment hull {:?}",
            &hull[..m]
        );
        assert_eq!(
            stability_margin::<f64>(Vec2::new(1.0, 0.5), &[]),
            None,
            "margin with no pads down"
        );
    }

    #[test]
    fn margins_along_a_sweep_skip_pads_in_the_air() {
        let nan = f64::NAN;
        // Sample 0: a 2 × 2 square of pads; sample 1: one pad lifted (a triangle); sample 2:
        // every pad lifted.
        let up = Vec2::new(nan, nan);
        let sq = [
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(2.0, 2.0),
            Vec2::new(0.0, 2.0),
        ];
        let mut pads = [up; 12];
        pads[..4].copy_from_slice(&sq);
        pads[4..8].copy_from_slice(&[sq[0], sq[1], up, sq[3]]);
        let cg = [
            Vec2::new(1.0, 1.0),
            Vec2::new(1.0, 0.5),
            Vec2::new(1.0, 1.0),
        ];
        let mut scratch = [Vec2::zeros(); 4];
        let mut hulls = [Vec2::zeros(); 15];
        let (mut counts, mut margins) = ([9; 3], [0.0; 3]);
        support_margins(
            &pads,
            4,
            &cg,
            &mut scratch,
            &mut hulls,
            &mut counts,
            &mut margins,
        )
        .unwrap();
        assert_eq!(counts, [4, 3, 0], "hull sizes per sample");
        assert_eq!(margins[0], 1.0, "centre of the square");
        // The triangle (0,0), (2,0), (0,2): (1, 0.5) is 0.5 from the bottom edge and
        // |1 + 0.5 − 2|/√2 ≈ 0.354 from the hypotenuse.
        assert!(
            (margins[1] - 0.5 / 2f64.sqrt()).abs() < 1e-15,
            "{}",
            margins[1]
        );
        assert!(margins[2].is_nan(), "no pad down: no margin");
        assert!(
            hulls[4].x.is_nan() && hulls[8].x.is_nan(),
            "unused hull rows are NaN"
        );
        // A wrong buffer is an error, not a panic.
        let err = support_margins(
            &pads,
            4,
            &cg,
            &mut scratch,
            &mut hulls[..14],
            &mut counts,
            &mut margins,
        );
        assert!(matches!(err, Err(Error::BufferLength { .. })), "{err:?}");
    }
}
