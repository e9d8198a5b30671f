//! A batch sweep equals, linkage by linkage, the tracked sweep of each linkage's mechanism.

#![cfg(not(target_os = "none"))]

mod common;

use core::f64::consts::{PI, TAU};

use linkage_core::{
    Assembly, Error, FourBar, FourBarBatch, GrashofClass, InputRange, Rates, Tracker, Vec2,
};
use proptest::prelude::*;

/// A random four-bar of one of the shapes: any lengths (every Grashof class, non-Grashof
/// included), a crank-rocker, a change point (s + l = p + q exactly, any link shortest), a
/// parallelogram, a kite and a deltoid; any pivots, point and assembly.
fn linkage() -> impl Strategy<Value = FourBar<f64>> {
    (
        0usize..6,
        (0.2f64..3.0, 0.2f64..3.0, 0.2f64..3.0, 0.2f64..3.0),
        (0usize..4, -1.0f64..1.0),
        (0.0f64..TAU, -3.0f64..3.0, -3.0f64..3.0),
        (-2.0f64..2.0, -2.0f64..2.0),
        any::<bool>(),
    )
        .prop_filter_map(
            "a valid four-bar",
            |(kind, (a, b, c, d), (perm, lscale), (rot, ox, oy), (pa, pl), open)| {
                let (g, r, cp, rk) = match kind {
                    0 => (a, b, c, d),
                    1 => {
                        // Crank shortest and s + l < p + q.
                        let r = 0.3 * a.min(b).min(c);
                        (a, r, b, c.max((a - b).abs() + 2.0 * r))
                    }
                    2 => {
                        // Change point: s + l = p + q with the links permuted.
                        let (s, p, q) = (a.min(b).min(c) * 0.5, a, b);
                        let l = p + q - s;
                        let mut v = [s, l, p, q];
                        v.rotate_left(perm);
                        (v[0], v[1], v[2], v[3])
                    }
                    3 => (a, b, a, b), // parallelogram (ground = coupler)
                    4 => (a, a, b, b), // kite: crank = ground, coupler = rocker
                    _ => (a, b, b, a), // deltoid: ground = rocker, crank = coupler
                };
                let s = 10f64.powf(lscale);
                let o = Vec2::new(ox, oy) * s;
                let c = o + Vec2::new(rot.cos(), rot.sin()) * (g * s);
                let asm = if open {
                    Assembly::Open
                } else {
                    Assembly::Crossed
                };
                FourBar::with_pivots(o, c, r * s, cp * s, rk * s, (pa * cp * s, pl * cp * s), asm)
                    .ok()
            },
        )
}

/// Sample angles: random ones over a few turns in random order, and the linkage's input limits
/// and flat positions with points 1e-12 … 1e-3 rad either side.
fn angles(fbs: &[FourBar<f64>], start: f64, random: &[f64], specials: bool) -> Vec<f64> {
    let mut th: Vec<f64> = random.iter().map(|u| start + u * 2.5 * TAU).collect();
    if specials {
        for fb in fbs {
            let d = fb.c - fb.o;
            let base = d.y.atan2(d.x);
            let mut marks = vec![base, base + PI];
            match fb.input_range() {
                InputRange::Between { lo, hi } => marks.extend([lo, hi]),
                InputRange::TwoIntervals { first, second } => {
                    marks.extend([first.0, first.1, second.0, second.1])
                }
                _ => {}
            }
            for m in marks {
                for off in [0.0, 1e-12, 1e-9, 1e-6, 1e-3] {
                    th.extend([m - off, m + off, m + TAU + off]);
                }
            }
        }
    }
    th
}

fn batch_of<'a>(fbs: &[FourBar<f64>], store: &'a mut Store) -> FourBarBatch<'a, f64> {
    *store = Store {
        o: fbs.iter().map(|f| f.o).collect(),
        c: fbs.iter().map(|f| f.c).collect(),
        crank: fbs.iter().map(|f| f.crank).collect(),
        coupler: fbs.iter().map(|f| f.coupler).collect(),
        rocker: fbs.iter().map(|f| f.rocker).collect(),
        along: fbs.iter().map(|f| f.along).collect(),
        left: fbs.iter().map(|f| f.left).collect(),
        assembly: fbs.iter().map(|f| f.assembly).collect(),
    };
    FourBarBatch {
        o: &store.o,
        c: &store.c,
        crank: &store.crank,
        coupler: &store.coupler,
        rocker: &store.rocker,
        along: &store.along,
        left: &store.left,
        assembly: &store.assembly,
    }
}

#[derive(Default)]
struct Store {
    o: Vec<Vec2<f64>>,
    c: Vec<Vec2<f64>>,
    crank: Vec<f64>,
    coupler: Vec<f64>,
    rocker: Vec<f64>,
    along: Vec<f64>,
    left: Vec<f64>,
    assembly: Vec<Assembly>,
}

/// The reference: a tracked sweep of the linkage's mechanism.
fn tracked(fb: &FourBar<f64>, th: &[f64]) -> Vec<Option<Vec2<f64>>> {
    let m = fb.mechanism();
    let mut t = Tracker::new(&m).unwrap();
    th.iter()
        .map(|&x| {
            let mut j = [Vec2::zeros(); 5];
            t.step(x, None, &mut j, Rates::none()).ok().map(|_| j[4])
        })
        .collect()
}

fn size(fb: &FourBar<f64>) -> f64 {
    fb.crank
        .max(fb.coupler)
        .max(fb.rocker)
        .max(fb.along.abs())
        .max(fb.left.abs())
        .max(fb.o.amax())
        .max(fb.c.amax())
}

fn run(fbs: &[FourBar<f64>], th: &[f64]) -> (Vec<Vec2<f64>>, Vec<bool>, linkage_core::BatchWork) {
    let mut store = Store::default();
    let batch = batch_of(fbs, &mut store);
    let mut p = vec![Vec2::zeros(); fbs.len() * th.len()];
    let mut v = vec![false; p.len()];
    let work = batch.sweep(th, &mut p, &mut v).unwrap();
    (p, v, work)
}

fn bits(p: &[Vec2<f64>]) -> Vec<(u64, u64)> {
    p.iter().map(|q| (q.x.to_bits(), q.y.to_bits())).collect()
}

proptest! {
    #![proptest_config(common::config("proptest-regressions/batch.txt"))]

    /// Every row equals the tracked sweep of its linkage: the same validity exactly, the same
    /// points to 1e-13 of the linkage's size.
    #[test]
    fn batch_equals_tracked_sweeps(
        fbs in prop::collection::vec(linkage(), 1..5),
        start in -8.0f64..8.0,
        random in prop::collection::vec(0.0f64..1.0, 0..80),
        specials in any::<bool>(),
    ) {
        let th = angles(&fbs, start, &random, specials);
        let (p, v, work) = run(&fbs, &th);
        if !th.is_empty() {
            prop_assert_eq!(work.fast + work.tracked, fbs.len(), "fast + tracked rows vs linkages: {:?}", work);
        }
        let n = th.len();
        for (i, fb) in fbs.iter().enumerate() {
            let reference = tracked(fb, &th);
            let tol = 1e-13 * size(fb);
            for (k, want) in reference.iter().enumerate() {
                let (got, ok) = (p[i * n + k], v[i * n + k]);
                match want {
                    Some(q) => {
                        prop_assert!(ok, "linkage {} {:?} θ = {}: invalid, tracker {:?}", i, fb, th[k], q);
                        prop_assert!((got - q).norm() <= tol,
                            "linkage {} {:?} ({:?}) θ = {}: {:?} vs {:?}", i, fb, fb.grashof(), th[k], got, q);
                    }
                    None => prop_assert!(!ok && got.x.is_nan() && got.y.is_nan(),
                        "linkage {} {:?} θ = {}: {:?}, tracker invalid", i, fb, th[k], got),
                }
            }
        }
    }

    /// Sweeping the batch in parts (as threads do) gives the same bits as the whole.
    #[test]
    fn splitting_the_batch_keeps_every_bit(
        fbs in prop::collection::vec(linkage(), 2..8),
        cut in 0usize..8,
        random in prop::collection::vec(-10.0f64..10.0, 1..40),
    ) {
        let (whole, vw, _) = run(&fbs, &random);
        let cut = cut.min(fbs.len());
        let (a, va, _) = run(&fbs[..cut], &random);
        let (b, vb, _) = run(&fbs[cut..], &random);
        prop_assert_eq!(bits(&whole), bits(&[a, b].concat()), "points differ with the batch cut at {}", cut);
        prop_assert_eq!(vw, [va, vb].concat(), "validity differs with the batch cut at {}", cut);
    }
}

#[test]
fn crank_rockers_take_the_fast_path_and_change_points_over_a_flat_the_tracker() {
    let hoecken = FourBar::new(20.0, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
    let parallelogram = FourBar::new(3.0, 1.0, 3.0, 1.0, (1.5, 0.5), Assembly::Open).unwrap();
    assert_eq!(
        hoecken.grashof(),
        GrashofClass::CrankRocker,
        "Hoecken's Grashof class"
    );
    let th: Vec<f64> = (0..360).map(|k| (k as f64).to_radians()).collect();
    let (_, v, work) = run(&[hoecken, parallelogram], &th);
    assert_eq!(
        (work.fast, work.tracked),
        (1, 1),
        "fast and tracked rows: {work:?}"
    );
    assert_eq!(
        work.exact, 0,
        "Hoecken's transmission angle stays far from a toggle"
    );
    assert!(
        v.iter().all(|&ok| ok),
        "invalid samples (360 a row): {:?}",
        (0..v.len()).filter(|&k| !v[k]).collect::<Vec<_>>()
    );
    // Between its flat positions the parallelogram is on its declared assembly: fast.
    let (_, _, work) = run(&[parallelogram], &[0.5, 1.0, 2.0]);
    assert_eq!(
        (work.fast, work.tracked),
        (1, 0),
        "parallelogram between its flats: {work:?}"
    );
    // Through the flat position at π the parallelogram stays a parallelogram (B = A + (3, 0)).
    let (p, _, _) = run(&[parallelogram], &[2.0, 3.0, 4.0, 5.0]);
    for (k, t) in [2.0f64, 3.0, 4.0, 5.0].iter().enumerate() {
        let a = Vec2::new(t.cos(), t.sin());
        let expected = a + Vec2::new(1.5, 0.5);
        assert!((p[k] - expected).norm() < 1e-12, "{t}: {:?}", p[k]);
    }
}

#[test]
fn samples_at_input_limits_are_solved_exactly() {
    // A triple rocker swept through its input limits: the samples next to them are re-solved
    // by the pose, so they are the tracker's bits.
    let fb = FourBar::new(4.0, 2.0, 3.0, 2.5, (1.0, 0.5), Assembly::Crossed).unwrap();
    let InputRange::Between { lo, hi } = fb.input_range() else {
        panic!("{:?}", fb.input_range())
    };
    let th = [lo, lo + 1e-12, hi - 1e-12, hi, hi + 1e-9, 0.0];
    let (p, v, work) = run(&[fb], &th);
    assert!(work.exact >= 4, "{work:?}");
    let reference = tracked(&fb, &th);
    for (k, want) in reference.iter().enumerate() {
        assert_eq!(want.is_some(), v[k], "θ = {}", th[k]);
        if let Some(q) = want {
            assert_eq!(p[k], *q, "θ = {}", th[k]);
        }
    }
}

#[test]
fn extreme_sizes_go_through_the_tracker() {
    let fb = FourBar::new(
        20e-30,
        10e-30,
        25e-30,
        25e-30,
        (50e-30, 0.0),
        Assembly::Open,
    )
    .unwrap();
    let th = [0.0, 1.0, 2.0];
    let (p, v, work) = run(&[fb], &th);
    assert_eq!(work.tracked, 1, "a linkage 1e-29 in size: {work:?}");
    for (k, want) in tracked(&fb, &th).iter().enumerate() {
        assert_eq!(Some(p[k]), *want, "θ = {}", th[k]);
        assert!(v[k], "θ = {}: invalid", th[k]);
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let fb = FourBar::new(20.0, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
    let mut store = Store::default();
    let mut batch = batch_of(&[fb, fb], &mut store);
    let bad = [10.0, -1.0];
    batch.crank = &bad;
    let (mut p, mut v) = (vec![Vec2::zeros(); 4], vec![false; 4]);
    assert_eq!(
        batch.sweep(&[0.0, 1.0], &mut p, &mut v),
        Err(Error::InvalidLength {
            what: "crank",
            value: -1.0
        }),
        "crank −1 in row 1"
    );
    assert_eq!(
        batch.first_invalid(),
        Some((
            1,
            Error::InvalidLength {
                what: "crank",
                value: -1.0
            }
        )),
        "first invalid row"
    );
    let batch = batch_of(&[fb, fb], &mut store);
    let r = batch.sweep(&[0.0, f64::NAN], &mut p, &mut v);
    assert!(
        matches!(r, Err(Error::NotFinite { what: "theta", .. })),
        "θ = NaN: {r:?}"
    );
    assert_eq!(
        batch.sweep(&[0.0], &mut p, &mut v),
        Err(Error::BufferLength {
            what: "points",
            expected: 2,
            got: 4
        }),
        "a 4-point buffer for 2 linkages × 1 sample"
    );
    assert!(p.iter().all(|q| *q == Vec2::zeros()), "nothing written");
}

#[test]
fn go_on_stops_a_sweep_within_bounded_work() {
    // A parallelogram tracked through its flat positions: go_on is asked at least every
    // GO_ON_EVERY samples of a tracked row.
    let fb = FourBar::new(3.0, 1.0, 3.0, 1.0, (1.5, 0.5), Assembly::Open).unwrap();
    let th: Vec<f64> = (0..3000).map(|k| k as f64 * 0.37).collect();
    let mut store = Store::default();
    let batch = batch_of(&[fb, fb], &mut store);
    let (mut p, mut v) = (vec![Vec2::zeros(); 6000], vec![false; 6000]);
    let mut calls = 0;
    let work = batch
        .sweep_with(&th, &mut p, &mut v, &mut || {
            calls += 1;
            calls < 3
        })
        .unwrap();
    assert!(work.stopped, "go_on said stop, the sweep went on: {work:?}");
    assert_eq!(calls, 3, "go_on calls, the third saying stop");
    // Without stopping it runs to the end, every sample on the parallelogram, asking go_on at
    // least once per GO_ON_EVERY tracked samples.
    let mut calls = 0;
    let work = batch
        .sweep_with(&th, &mut p, &mut v, &mut || {
            calls += 1;
            true
        })
        .unwrap();
    assert!(
        !work.stopped && work.tracked == 2,
        "sweep never told to stop, two parallelograms: {work:?}"
    );
    assert!(
        v.iter().all(|&ok| ok),
        "invalid samples: {:?}",
        (0..v.len()).filter(|&k| !v[k]).collect::<Vec<_>>()
    );
    assert!(calls >= 2 * 3000 / linkage_core::GO_ON_EVERY, "{calls}");
}
