//! Static stability: the support polygon (convex hull of the stance pads) and the signed
//! distance of the centre of gravity's ground projection from its boundary.

use nalgebra::RealField;

use crate::scalar::{cross, Vec2};

/// Convex hull of `points` by Andrew's monotone chain, written counter-clockwise into `out`
/// (which needs room for `points.len() + 1` vertices); returns the hull's vertex count.
/// Collinear points on an edge are dropped; 1 or 2 distinct points give a degenerate hull of
/// that many vertices. Sorts `points` in place. Non-finite points are not allowed.
pub fn convex_hull<T: RealField + Copy>(points: &mut [Vec2<T>], out: &mut [Vec2<T>]) -> usize {
    let n = points.len();
    if n == 0 {
        return 0;
    }
    points.sort_unstable_by(|a, b| {
        a.x.partial_cmp(&b.x)
            .unwrap_or(core::cmp::Ordering::Equal)
            .then(a.y.partial_cmp(&b.y).unwrap_or(core::cmp::Ordering::Equal))
    });
    let mut k = 0;
    // Lower hull, then upper hull.
    for &p in points.iter() {
        while k >= 2 && cross(out[k - 1] - out[k - 2], p - out[k - 2]) <= T::zero() {
            k -= 1;
        }
        out[k] = p;
        k += 1;
    }
    let lower = k + 1;
    for &p in points[..n.saturating_sub(1)].iter().rev() {
        while k >= lower && cross(out[k - 1] - out[k - 2], p - out[k - 2]) <= T::zero() {
            k -= 1;
        }
        out[k] = p;
        k += 1;
    }
    // The last point repeats the first (except for a single point).
    let mut count = if k > 1 { k - 1 } else { k };
    // Drop duplicates left by coincident points.
    if count == 2 && out[0] == out[1] {
        count = 1;
    }
    count
}

/// Signed distance from `p` to the boundary of the convex polygon `hull` (counter-clockwise, as
/// [`convex_hull`] writes it): positive inside, negative outside — the static stability margin
/// of McGhee and Frank's CG projection method. A degenerate hull (a segment or a point) has no
/// inside: the result is minus the distance to it. `None` for an empty hull.
pub fn stability_margin<T: RealField + Copy>(p: Vec2<T>, hull: &[Vec2<T>]) -> Option<T> {
    let n = hull.len();
    if n == 0 {
        return None;
    }
    let seg_dist = |a: Vec2<T>, b: Vec2<T>| {
        let ab = b - a;
        let l2 = ab.norm_squared();
        let t = if l2 > T::zero() {
            ((p - a).dot(&ab) / l2).max(T::zero()).min(T::one())
        } else {
            T::zero()
        };
        (a + ab * t - p).norm()
    };
    if n < 3 {
        return Some(-seg_dist(hull[0], hull[n - 1]));
    }
    let mut inside = true;
    let mut nearest = T::max_value().unwrap_or(T::one() / T::default_epsilon());
    for i in 0..n {
        let (a, b) = (hull[i], hull[(i + 1) % n]);
        if cross(b - a, p - a) < T::zero() {
            inside = false;
        }
        nearest = nearest.min(seg_dist(a, b));
    }
    Some(if inside { nearest } else { -nearest })
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
        let n = convex_hull(&mut pts, &mut hull);
        assert_eq!(n, 4);
        let h = &hull[..n];
        assert_eq!(stability_margin(Vec2::new(1.0, 1.0), h), Some(1.0));
        assert_eq!(stability_margin(Vec2::new(0.5, 1.0), h), Some(0.5));
        assert_eq!(stability_margin(Vec2::new(3.0, 1.0), h), Some(-1.0));
        // Two pads touching at a point: a segment has no inside.
        let mut two = [Vec2::new(0.0, 0.0), Vec2::new(2.0, 0.0)];
        let m = convex_hull(&mut two, &mut hull);
        assert_eq!(m, 2);
        assert_eq!(
            stability_margin(Vec2::new(1.0, 0.5), &hull[..m]),
            Some(-0.5)
        );
        assert_eq!(stability_margin::<f64>(Vec2::new(1.0, 0.5), &[]), None);
    }
}
