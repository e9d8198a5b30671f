//! Straight-line quality of a sampled path: the longest run of samples within a tolerance of
//! its best-fit line.

use nalgebra::RealField;

use crate::scalar::{cross, lit, Vec2};

/// A near-straight run of a sampled path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StraightPart<T> {
    /// Index of the run's first sample.
    pub start: usize,
    /// Number of samples in the run (on a closed path it may wrap past the last sample).
    pub count: usize,
    /// A point of the best-fit line: the run's centroid.
    pub point: Vec2<T>,
    /// Unit direction of the best-fit line, pointing from the run's first sample to its last.
    pub direction: Vec2<T>,
    /// Largest distance of a run sample from the line.
    pub max_deviation: T,
    /// Extent of the run along the line.
    pub length: T,
}

/// Total-least-squares line through `pts`: centroid, unit direction (first → last), largest
/// deviation and extent along the line. Coordinates are taken relative to the first point so
/// that paths far from the origin keep their digits.
fn fit<T: RealField + Copy>(
    pts: impl Iterator<Item = Vec2<T>> + Clone,
) -> (Vec2<T>, Vec2<T>, T, T) {
    let mut it = pts.clone();
    let Some(first) = it.next() else {
        return (
            Vec2::zeros(),
            Vec2::new(T::one(), T::zero()),
            T::zero(),
            T::zero(),
        );
    };
    let mut last = first;
    let (mut n, mut sx, mut sy) = (T::zero(), T::zero(), T::zero());
    for p in pts.clone() {
        let d = p - first;
        n += T::one();
        sx += d.x;
        sy += d.y;
        last = p;
    }
    let c = Vec2::new(sx / n, sy / n);
    let (mut sxx, mut sxy, mut syy) = (T::zero(), T::zero(), T::zero());
    for p in pts.clone() {
        let d = p - first - c;
        sxx += d.x * d.x;
        sxy += d.x * d.y;
        syy += d.y * d.y;
    }
    // Principal axis of the scatter: angle ½·atan2(2 Sxy, Sxx − Syy).
    let phi = (lit::<T>(2.0) * sxy).atan2(sxx - syy) * lit::<T>(0.5);
    let (s, co) = phi.sin_cos();
    let mut dir = Vec2::new(co, s);
    if dir.dot(&(last - first)) < T::zero() {
        dir = -dir;
    }
    let (mut dev, mut lo, mut hi) = (T::zero(), T::zero(), T::zero());
    for p in pts {
        let d = p - first - c;
        dev = dev.max(cross(dir, d).abs());
        let t = dir.dot(&d);
        lo = lo.min(t);
        hi = hi.max(t);
    }
    (first + c, dir, dev, hi - lo)
}

/// The longest run of consecutive samples of `path` that stays within `tol` of its own
/// total-least-squares line (at least 3 samples), or `None` if there is none.
///
/// On a `closed` path (the last sample followed by the first, without repeating it) runs may
/// wrap around. Non-finite samples break runs. The scan is a two-pointer sweep refitting each
/// candidate window, `O(n·w)` for runs of `w` samples. The least-squares line is not the
/// minimax one, so the reported deviation can exceed the narrowest strip's half-width by a
/// little; it is the honest deviation from the reported line.
pub fn straight_part<T: RealField + Copy>(
    path: &[Vec2<T>],
    tol: T,
    closed: bool,
) -> Option<StraightPart<T>> {
    let n = path.len();
    if n < 3 || !tol.is_finite() || tol < T::zero() {
        return None;
    }
    let ok = |k: usize| {
        let p = path[k % n];
        p.x.is_finite() && p.y.is_finite()
    };
    let window = |i: usize, j: usize| (i..j).map(move |k| path[k % n]);
    let fits = |i: usize, j: usize| fit(window(i, j)).2 <= tol;
    let mut best: Option<(usize, usize)> = None;
    let mut j = 0;
    for i in 0..n {
        if !ok(i) {
            continue;
        }
        let limit = if closed { i + n } else { n };
        j = j.max(i + 1);
        // Dropping the first sample can (rarely) tilt the fit; shrink until it holds.
        while j > i + 2 && !fits(i, j) {
            j -= 1;
        }
        while j < limit && ok(j) && fits(i, j + 1) {
            j += 1;
        }
        if j - i >= 3 && best.is_none_or(|(a, b)| j - i > b - a) {
            best = Some((i, j));
        }
        if closed && j - i == n {
            break;
        }
    }
    let (i, j) = best?;
    let (point, direction, max_deviation, length) = fit(window(i, j));
    Some(StraightPart {
        start: i,
        count: j - i,
        point,
        direction,
        max_deviation,
        length,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_flat_of_a_d_shape() {
        // A "D": 21 samples on y = 0 from x = 0 to 10, then a half circle back.
        let mut path = [Vec2::zeros(); 60];
        for (k, p) in path.iter_mut().enumerate() {
            *p = if k <= 20 {
                Vec2::new(k as f64 * 0.5, 0.0)
            } else {
                let t = core::f64::consts::PI * (k - 20) as f64 / 40.0;
                Vec2::new(5.0 + 5.0 * t.cos(), 5.0 * t.sin())
            };
        }
        let s = straight_part(&path, 1e-9, false).unwrap();
        assert_eq!((s.start, s.count), (0, 21));
        assert!((s.length - 10.0).abs() < 1e-12 && s.max_deviation < 1e-12);
        assert!((s.direction - Vec2::new(1.0, 0.0)).norm() < 1e-12);
        // Closed: the flat run is the same; a looser tolerance takes in more of the arc.
        let c = straight_part(&path, 1e-9, true).unwrap();
        assert_eq!(c.count, 21);
        let loose = straight_part(&path, 0.5, true).unwrap();
        assert!(loose.count > 21 && loose.max_deviation <= 0.5);
    }

    #[test]
    fn wraps_around_a_closed_path() {
        // A 2 × 1 rectangle sampled every 0.1 by arc length, starting mid-bottom: the longest
        // side (21 samples with its corners) is split between the array's end and start.
        let mut path = [Vec2::zeros(); 60];
        for (k, p) in path.iter_mut().enumerate() {
            let s = (k as f64 * 0.1 + 1.0) % 6.0; // arc length from the bottom-left corner
            *p = if s < 2.0 {
                Vec2::new(s, 0.0)
            } else if s < 3.0 {
                Vec2::new(2.0, s - 2.0)
            } else if s < 5.0 {
                Vec2::new(5.0 - s, 1.0)
            } else {
                Vec2::new(0.0, 6.0 - s)
            };
        }
        let open = straight_part(&path, 1e-9, false).unwrap();
        let closed = straight_part(&path, 1e-9, true).unwrap();
        assert_eq!(open.count, 21); // the top side, inside the array
        assert_eq!(closed.count, 21);
        assert!((closed.length - 2.0).abs() < 1e-9);
        // Break the top side: only the wrapped bottom side is left at full length.
        let mut broken = path;
        broken[30] = Vec2::new(f64::NAN, f64::NAN);
        assert!(straight_part(&broken, 1e-9, false).unwrap().count < 21);
        let wrapped = straight_part(&broken, 1e-9, true).unwrap();
        assert_eq!(wrapped.count, 21);
        assert!(wrapped.start + wrapped.count > 60 && wrapped.point.y.abs() < 1e-12);
    }
}
