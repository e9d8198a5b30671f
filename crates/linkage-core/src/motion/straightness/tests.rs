use super::*;
use proptest::prelude::*;

/// The direct scan: every window refitted (the algorithm before the segment tree).
fn reference<T: RealField + Copy>(
    path: &[Vec2<T>],
    tol: T,
    closed: bool,
) -> Option<StraightPart<T>> {
    if path.len() < 3 || !tol.is_finite() || tol < T::zero() {
        return None;
    }
    let (i, j) = scan(path, closed, |i, j| fits_directly(path, tol, i, j))?;
    let (point, direction, max_deviation, length) = fit(window(path, i, j));
    Some(StraightPart {
        start: i,
        count: j - i,
        point,
        direction,
        max_deviation,
        length,
    })
}

/// Same run, and the same numbers bit for bit (NaN equal to NaN).
fn same<T: RealField + Copy>(a: Option<StraightPart<T>>, b: Option<StraightPart<T>>) -> bool {
    #[allow(clippy::eq_op, reason = "x != x is the NaN test")]
    let eq = |x: T, y: T| x == y || (x != x && y != y);
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => {
            (a.start, a.count) == (b.start, b.count)
                && [a.point, a.direction]
                    .iter()
                    .zip([b.point, b.direction].iter())
                    .all(|(u, v)| eq(u.x, v.x) && eq(u.y, v.y))
                && eq(a.max_deviation, b.max_deviation)
                && eq(a.length, b.length)
        }
        _ => false,
    }
}

/// A test path of one of several kinds, from per-sample random numbers `raw`.
fn make_path(kind: u8, raw: &[(u8, f64, f64)], angle: f64, offset: f64) -> Vec<Vec2<f64>> {
    let n = raw.len();
    let (mut pos, mut heading) = (Vec2::new(0.0, 0.0), 0.0_f64);
    let mut out = Vec::with_capacity(n);
    for (k, &(b, r1, r2)) in raw.iter().enumerate() {
        let p = match kind {
            // Smooth curve with flats: the heading turns at one step in three.
            0 => {
                if b % 3 == 0 {
                    heading += r1 * 0.3;
                }
                pos += Vec2::new(heading.cos(), heading.sin()) * 0.1;
                pos
            }
            // Noisy line.
            1 => Vec2::new(k as f64 * 0.1, r1 * 1e-3 * f64::from(b) / 255.0),
            // Closed curve, slightly noisy.
            2 => {
                let t = core::f64::consts::TAU * k as f64 / n as f64;
                Vec2::new(2.0 * t.cos(), t.sin() + 0.2 * (3.0 * t).sin()) + Vec2::new(r1, r2) * 1e-4
            }
            // Small integer grid, many repeated samples and exact flats.
            3 => {
                if b % 2 == 0 && k > 0 {
                    pos
                } else {
                    pos = Vec2::new((r1 * 3.0).round(), (r2 * 3.0).round());
                    pos
                }
            }
            // Axis-parallel walk: exact flats along x, some random steps.
            _ => {
                pos += if b % 4 == 0 {
                    Vec2::new(r1, r2) * 0.1
                } else {
                    Vec2::new(0.125, 0.0)
                };
                pos
            }
        };
        out.push(p);
    }
    let (s, c) = angle.sin_cos();
    for (p, &(b, _, _)) in out.iter_mut().zip(raw) {
        if angle != 0.0 {
            *p = Vec2::new(c * p.x - s * p.y, s * p.x + c * p.y);
        }
        *p += Vec2::new(offset, -0.5 * offset);
        match b {
            255 => p.x = f64::NAN,
            254 => p.y = f64::INFINITY,
            _ => {}
        }
    }
    out
}

fn tolerance(kind: u8, log: f64) -> f64 {
    match kind {
        0 => 0.0,
        1 => 1e300,
        2 => f64::MAX,
        _ => 10f64.powf(log),
    }
}

/// Cases of the property below: `LINKAGE_PROPTEST_CASES` (default 2000), as for the crate's
/// integration tests.
fn cases() -> u32 {
    extern crate std;
    std::env::var("LINKAGE_PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2000)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    /// The fast scan finds exactly the run, line, deviation and length of the direct one.
    #[test]
    fn equals_the_direct_scan(
        kind in 0u8..5,
        raw in prop::collection::vec((any::<u8>(), -1.0f64..1.0, -1.0f64..1.0), 0..200),
        tol_kind in 0u8..7,
        log_tol in -9.0f64..0.5,
        closed in any::<bool>(),
        angle in prop_oneof![Just(0.0), -3.2f64..3.2],
        offset in prop_oneof![Just(0.0), Just(1e6), Just(-3e3)],
    ) {
        let path = make_path(kind, &raw, angle, offset);
        let tol = tolerance(tol_kind, log_tol);
        let fast = straight_part(&path, tol, closed);
        let direct = reference(&path, tol, closed);
        prop_assert!(same(fast, direct), "fast {fast:?}\ndirect {direct:?}");
        // And in single precision.
        let p32: Vec<Vec2<f32>> = path.iter().map(|p| p.cast::<f32>()).collect();
        let t32 = tol as f32;
        let fast = straight_part(&p32, t32, closed);
        let direct = reference(&p32, t32, closed);
        prop_assert!(same(fast, direct), "f32: fast {fast:?}\ndirect {direct:?}");
    }
}

#[test]
fn equals_the_direct_scan_on_long_paths() {
    // Long enough for deep trees: a noisy closed curve and an open smooth one with flats.
    for (n, kind, tol, closed) in [
        (3000, 2, 0.05, true),
        (3000, 2, 1e-3, false),
        (4000, 0, 1e-4, false),
        (4000, 0, 0.0, true),
        (4000, 1, 4e-4, false),
        (4000, 4, 0.0, true),
    ] {
        let raw: Vec<(u8, f64, f64)> = (0..n)
            .map(|k: usize| {
                let h = (k as f64 * 12.9898).sin() * 43758.5453;
                let f = h - h.floor();
                (
                    (f * 253.0) as u8,
                    2.0 * f - 1.0,
                    ((f * 7.0).fract() - 0.5) * 2.0,
                )
            })
            .collect();
        let path = make_path(kind, &raw, 0.3, 1e6);
        let fast = straight_part(&path, tol, closed);
        let direct = reference(&path, tol, closed);
        assert!(
            fast.is_some_and(|s| s.count >= 3),
            "{kind}: no run of 3 samples: {fast:?}"
        );
        assert!(
            same(fast, direct),
            "{kind}: fast {fast:?}\ndirect {direct:?}"
        );
    }
}

/// The path file named by `STRAIGHT_BENCH_PATH` (a first line `tol closed`, then one `x y`
/// line per sample) for the two timing helpers below.
fn bench_path() -> (Vec<Vec2<f64>>, f64, bool) {
    extern crate std;
    let file = std::env::var("STRAIGHT_BENCH_PATH").expect("STRAIGHT_BENCH_PATH");
    let text = std::fs::read_to_string(file).expect("readable path file");
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().expect("header").split_whitespace().collect();
    let tol: f64 = head[0].parse().expect("tol");
    let closed = head[1] == "1";
    let path = lines
        .map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .map(|x| x.parse().expect("number"))
                .collect();
            Vec2::new(v[0], v[1])
        })
        .collect();
    (path, tol, closed)
}

/// The scan with the window check used before the queue (a segment tree of hulls).
fn tree_scan(path: &[Vec2<f64>], tol: f64, closed: bool) -> Option<StraightPart<f64>> {
    let (i, j) = super::tree_check::longest_run(path, tol, closed)?;
    let (point, direction, max_deviation, length) = fit(window(path, i, j));
    Some(StraightPart {
        start: i,
        count: j - i,
        point,
        direction,
        max_deviation,
        length,
    })
}

/// Best of 3 wall times of `f`, and its result.
fn best_of_3<R>(mut f: impl FnMut() -> R) -> (f64, R) {
    extern crate std;
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..3 {
        let t = std::time::Instant::now();
        out = Some(f());
        best = best.min(t.elapsed().as_secs_f64());
    }
    (best, out.expect("three runs"))
}

/// Not a check of speed: `bench/straightness.py` runs it to time the direct scan against
/// the fast one (and the tree check it replaced), in one process, on the path it writes to
/// the file named by `STRAIGHT_BENCH_PATH` (a first line `tol closed`, then one `x y` line
/// per sample).
#[test]
#[ignore = "run by bench/straightness.py"]
fn direct_scan_timing() {
    extern crate std;
    use std::time::Instant;
    let (path, tol, closed) = bench_path();
    let t = Instant::now();
    let direct = reference(&path, tol, closed);
    let direct_s = t.elapsed().as_secs_f64();
    let (tree_s, tree) = best_of_3(|| tree_scan(&path, tol, closed));
    let (fast_s, fast) = best_of_3(|| straight_part(&path, tol, closed));
    std::println!(
        "n = {}: direct scan {direct_s:.3} s, tree check {tree_s:.4} s, queue {fast_s:.4} s; \
         direct/queue {:.0}, tree/queue {:.2}; run of {:?}",
        path.len(),
        direct_s / fast_s,
        tree_s / fast_s,
        fast.map(|s| s.count)
    );
    assert!(same(fast, direct), "fast {fast:?}\ndirect {direct:?}");
    assert!(same(tree, direct), "tree {tree:?}\ndirect {direct:?}");
}

/// Not a check of speed: times the fast scan and the tree check it replaced (best of 3
/// each, one process) on the path file named by `STRAIGHT_BENCH_PATH` (as for
/// `direct_scan_timing`), for paths too long for the direct scan.
#[test]
#[ignore = "timing helper for bench/straightness.py"]
fn fast_scan_timing() {
    extern crate std;
    let (path, tol, closed) = bench_path();
    let (tree_s, tree) = best_of_3(|| tree_scan(&path, tol, closed));
    let (fast_s, fast) = best_of_3(|| straight_part(&path, tol, closed));
    let (_, counts) = super::queue::longest_run_counted(&path, tol, closed);
    std::println!(
        "n = {}: tree check {tree_s:.4} s, queue {fast_s:.4} s (best of 3), tree/queue {:.2}; \
         run of {:?}; {counts:?}",
        path.len(),
        tree_s / fast_s,
        fast.map(|s| (s.start, s.count))
    );
    assert!(fast.is_some(), "no straight run in the bench path");
    assert!(same(fast, tree), "fast {fast:?}\ntree {tree:?}");
}

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
    assert_eq!(
        (s.start, s.count),
        (0, 21),
        "(start, count) of the flat: {s:?}"
    );
    assert!(
        (s.length - 10.0).abs() < 1e-12 && s.max_deviation < 1e-12,
        "flat's length {} (want 10), deviation {:e}",
        s.length,
        s.max_deviation
    );
    assert!(
        (s.direction - Vec2::new(1.0, 0.0)).norm() < 1e-12,
        "flat's direction {:?} (want (1, 0))",
        s.direction
    );
    // Closed: the flat run is the same; a looser tolerance takes in more of the arc.
    let c = straight_part(&path, 1e-9, true).unwrap();
    assert_eq!(c.count, 21, "flat's samples on the closed path: {c:?}");
    let loose = straight_part(&path, 0.5, true).unwrap();
    assert!(
        loose.count > 21 && loose.max_deviation <= 0.5,
        "tolerance 0.5: {} samples, deviation {}",
        loose.count,
        loose.max_deviation
    );
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
    assert_eq!(open.count, 21, "open path: {open:?}"); // the top side, inside the array
    assert_eq!(closed.count, 21, "closed path: {closed:?}");
    assert!(
        (closed.length - 2.0).abs() < 1e-9,
        "closed path's run length {} (want 2)",
        closed.length
    );
    // Break the top side: only the wrapped bottom side is left at full length.
    let mut broken = path;
    broken[30] = Vec2::new(f64::NAN, f64::NAN);
    let inside = straight_part(&broken, 1e-9, false).unwrap();
    assert!(
        inside.count < 21,
        "open path with the top side broken: {inside:?}"
    );
    let wrapped = straight_part(&broken, 1e-9, true).unwrap();
    assert_eq!(
        wrapped.count, 21,
        "closed path with the top side broken: {wrapped:?}"
    );
    assert!(
        wrapped.start + wrapped.count > 60 && wrapped.point.y.abs() < 1e-12,
        "run not the wrapped bottom side: {wrapped:?}"
    );
}
