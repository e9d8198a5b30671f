//! Path synthesis building blocks: circuits are one tracked branch, descriptors are similarity
//! invariant, the atlas finds a placed entry's own shape.

#![cfg(all(not(target_os = "none"), feature = "synthesis"))]

mod common;

use linkage_core::{
    candidate, nearest, path_errors, path_residuals, slider_candidate, slider_path_errors,
    slider_path_residuals, Assembly, Atlas, AtlasSpec, Circuit, CircuitPath, Efd, FootSearch,
    FourBar, GrashofClass, InputRange, PathError, Reach, SliderCircuit, SliderCrank, Vec2,
};
use proptest::prelude::*;

fn fourbar() -> impl Strategy<Value = FourBar<f64>> {
    (
        0.2f64..5.0,
        0.2f64..5.0,
        0.2f64..5.0,
        -2.0f64..2.0,
        -2.0f64..2.0,
        any::<bool>(),
    )
        .prop_filter_map("assembles, not a change point", |(r, b, c, u, v, open)| {
            let asm = if open {
                Assembly::Open
            } else {
                Assembly::Crossed
            };
            let fb = FourBar::new(1.0, r, b, c, (u * b, v * b), asm).ok()?;
            (fb.input_range() != InputRange::Never && fb.grashof() != GrashofClass::ChangePoint)
                .then_some(fb)
        })
}

proptest! {
    #![proptest_config(common::config("proptest-regressions/synthesis.txt"))]

    /// The circuit of any assembling four-bar, swept by the tracker, is its closed form on the
    /// declared assembly from limit to limit and the other assembly back: no branch switch,
    /// no unassembled sample. And it is the curve `FourBar::circuit` traces.
    #[test]
    fn circuits_are_one_tracked_branch(fb in fourbar()) {
        let path = CircuitPath::new(fb).unwrap();
        prop_assert!(path.check(512).is_ok(), "{:?}", path.check(512));
        let n = 301;
        let mut theta = vec![0.0; n];
        let mut joints = vec![Vec2::zeros(); 5 * n];
        prop_assert_eq!(fb.circuit(&mut theta, &mut joints, None).unwrap(), n, "circuit samples of {} for {:?}", n, fb);
        let poly = path.polyline(2048);
        let size = path.size();
        for k in (0..n).step_by(7) {
            let p = joints[5 * k + 4];
            let (d, _) = path.foot(p, &poly).unwrap();
            // √ε of the size at a crank limit, far below any branch jump.
            prop_assert!(d <= 1e-6 * size, "sample {k}: {d}");
        }
    }

    /// Normalised descriptors do not change under a similarity and a start shift (up to the
    /// even-harmonic sign), and the atlas finds a placed entry as its own nearest shape.
    #[test]
    fn placed_entry_is_found(idx in 0u64..4000, angle in -3.0f64..3.0, scale in 0.01f64..100.0,
                             shift in 0usize..128) {
        let fb = candidate(idx);
        prop_assume!(fb.is_some(), "not an atlas entry");
        let fb = fb.unwrap();
        let path = CircuitPath::new(fb).unwrap();
        let (s, c) = angle.sin_cos();
        let mut pts: Vec<_> = path
            .polyline(128)
            .into_iter()
            .map(|p| Vec2::new(c * p.x - s * p.y + 7.0, s * p.x + c * p.y - 3.0) * scale)
            .collect();
        pts.rotate_left(shift);
        let spec = AtlasSpec::default();
        let (norm, _) = Efd::closed(&pts, spec.harmonics).and_then(|e| e.normalised()).unwrap();
        let dim = linkage_core::descriptor_len(spec.harmonics);
        let mut q = vec![0.0f32; 2 * dim];
        norm.descriptor(false, &mut q[..dim]).unwrap();
        norm.descriptor(true, &mut q[dim..]).unwrap();
        let direct = Efd::closed(&path.polyline(128), spec.harmonics).unwrap().normalised().unwrap().0;
        let mut d0 = vec![0.0f32; dim];
        direct.descriptor(false, &mut d0).unwrap();
        let best = (0..2)
            .map(|j| q[j * dim..(j + 1) * dim].iter().zip(&d0).map(|(a, b)| (a - b).powi(2)).sum::<f32>())
            .fold(f32::INFINITY, f32::min);
        prop_assert!(best < 1e-8, "{best}");
    }

    /// Batched errors and residuals are the per-linkage ones, and a point on the curve is at
    /// distance 0 with its foot on it.
    #[test]
    fn batched_errors_are_the_single_ones(fb in fourbar(), s in 0.0f64..6.0) {
        let path = CircuitPath::new(fb).unwrap();
        let on = [path.point(s).unwrap(), path.point(s + 1.0).unwrap(), Vec2::new(9.0, -4.0)];
        let p = [fb.o.x, fb.o.y, fb.c.x, fb.c.y, fb.crank, fb.coupler, fb.rocker, fb.along, fb.left];
        let crossed = fb.assembly == Assembly::Crossed;
        let mut feet = [0.0; 3];
        let one = path.errors(&on, 256, FootSearch::Exact, true, &mut feet).unwrap();
        let mut errs = [PathError::nan(); 2];
        let mut feet2 = [0.0; 6];
        let params: Vec<f64> = p.iter().chain(p.iter()).copied().collect();
        path_errors(&params, &[crossed, crossed], &on, 256, FootSearch::Exact, true, 2, &mut errs, &mut feet2).unwrap();
        prop_assert_eq!(errs[0], one, "batched errors of linkage 0 vs path.errors");
        prop_assert_eq!(errs[1], one, "batched errors of linkage 1 vs path.errors");
        prop_assert_eq!(&feet2[3..], &feet[..], "batched feet of linkage 1 vs path.errors");
        let mut res = [Vec2::zeros(); 3];
        path_residuals(&p, &[crossed], &on, &feet, &mut res).unwrap();
        let size = path.size();
        prop_assert!(res[0].norm() <= 1e-9 * size && res[1].norm() <= 1e-9 * size, "{res:?}");
        prop_assert!((res[2].norm() - one.max).abs() <= 1e-9 * size, "off-curve point {:?}: residual {} vs error {}", on[2], res[2].norm(), one.max);
    }
}

/// Slider-cranks with crank 1 anywhere in the plane: rod, offset and coupler point over the
/// atlas's box, either reach, away from a change point (`|e| + r = l`, where the reaches meet
/// and the tracker may pass to the other).
fn slider_crank() -> impl Strategy<Value = SliderCrank<f64>> {
    (
        (0.2f64..5.0, -0.999f64..0.999, -1.0f64..2.0, -1.5f64..1.5),
        (-3.0f64..3.0, -5.0f64..5.0, -5.0f64..5.0, any::<bool>()),
    )
        .prop_filter_map(
            "moves, not near a change point",
            |((l, w, u, v), (angle, ox, oy, ahead))| {
                let reach = if ahead { Reach::Ahead } else { Reach::Behind };
                let e = (1.0 + l) * w;
                let sc =
                    SliderCrank::new(Vec2::new(ox, oy), angle, e, 1.0, l, (u * l, v * l), reach)
                        .ok()?;
                ((e.abs() + 1.0 - l).abs() > 1e-3 * l).then_some(sc)
            },
        )
}

proptest! {
    #![proptest_config(common::config("proptest-regressions/synthesis.txt"))]

    /// A slider-crank's circuit, swept by the tracker, is its closed form on the declared reach
    /// from limit to limit and the other reach back (a full turn: the declared reach): no branch
    /// switch, no unassembled sample; and every circuit point is the linkage's pose at the
    /// circuit's crank angle on that reach.
    #[test]
    fn slider_circuits_are_one_tracked_branch(sc in slider_crank()) {
        let c = SliderCircuit::new(sc).unwrap();
        prop_assert!(c.check(512).is_ok(), "{:?}", c.check(512));
        let other = SliderCrank { reach: if sc.reach == Reach::Ahead { Reach::Behind } else { Reach::Ahead }, ..sc };
        prop_assert_eq!(c.full_turn(), sc.offset.abs() + sc.crank <= sc.coupler, "full turn of {:?}", sc);
        let size = c.size();
        for k in 0..97 {
            let s = 0.0647 * k as f64;
            let (theta, flipped) = c.theta(s);
            let pose = if flipped { other } else { sc }.pose(theta);
            let got = c.pose(s).unwrap();
            // The direct pose keeps √ε of the size near a limit (the circuit's form keeps all).
            let tol = if got.transmission > 1e-3 { 1e-12 } else { 1e-7 } * size;
            prop_assert!(pose.is_some(), "s {s}: no pose at θ {theta}");
            let want = pose.unwrap().coupler_point;
            prop_assert!((got.coupler_point - want).norm() <= tol, "s {s}: {:?} vs {:?}", got.coupler_point, want);
        }
    }

    /// The other reach is the line reversed: `Behind` with `(γ, e)` draws `Ahead` with
    /// `(γ + π, −e)`, pose for pose.
    #[test]
    fn the_other_reach_is_the_line_reversed(sc in slider_crank(), theta in -7.0f64..7.0) {
        let reversed = SliderCrank {
            angle: sc.angle + core::f64::consts::PI,
            offset: -sc.offset,
            reach: if sc.reach == Reach::Ahead { Reach::Behind } else { Reach::Ahead },
            ..sc
        };
        let (p, q) = (sc.pose(theta), reversed.pose(theta));
        prop_assert_eq!(p.is_some(), q.is_some(), "θ {}", theta);
        if let (Some(p), Some(q)) = (p, q) {
            let tol = 1e-12 * SliderCircuit::new(sc).unwrap().size();
            // Away from a toggle (√ε there, as above).
            prop_assume!(p.transmission > 1e-3);
            prop_assert!((p.coupler_point - q.coupler_point).norm() <= tol, "{:?} {:?}", p, q);
        }
    }

    /// Batched slider-crank errors and residuals are the single ones, and a point on the curve
    /// is at distance 0 with its foot on it.
    #[test]
    fn batched_slider_errors_are_the_single_ones(idx in 0u64..4000, s in 0.0f64..6.0) {
        let sc = slider_candidate(idx);
        prop_assume!(sc.is_some(), "not an atlas entry");
        let sc = sc.unwrap();
        let p = [sc.o.x, sc.o.y, sc.angle, sc.offset, sc.crank, sc.coupler, sc.along, sc.left];
        let c = SliderCircuit::placed(&p).unwrap();
        let on = [c.point(s).unwrap(), c.point(s + 1.0).unwrap(), Vec2::new(9.0, -4.0)];
        let mut feet = [0.0; 3];
        let one = c.errors(&on, 256, FootSearch::Exact, true, &mut feet).unwrap();
        let (mut errs, mut feet2) = ([PathError::nan(); 2], [0.0; 6]);
        let params: Vec<f64> = p.iter().chain(p.iter()).copied().collect();
        slider_path_errors(&params, &on, 256, FootSearch::Exact, true, 2, &mut errs, &mut feet2).unwrap();
        prop_assert_eq!(errs[0], one, "batched errors of linkage 0 vs c.errors");
        prop_assert_eq!(errs[1], one, "batched errors of linkage 1 vs c.errors");
        let mut res = [Vec2::zeros(); 3];
        slider_path_residuals(&p, &on, &feet, &mut res).unwrap();
        let size = c.size();
        prop_assert!(res[0].norm() <= 1e-9 * size && res[1].norm() <= 1e-9 * size, "{res:?}");
        prop_assert!((res[2].norm() - one.max).abs() <= 1e-9 * size, "residual {} vs error {}", res[2].norm(), one.max);
    }
}

#[test]
fn slider_atlas_is_the_same_on_any_number_of_threads_and_finds_each_entry() {
    let spec = AtlasSpec::default();
    let atlas = Atlas::build_slider_cranks(3000, spec, 2).unwrap();
    assert_eq!(
        atlas,
        Atlas::build_slider_cranks(3000, spec, 1).unwrap(),
        "slider atlas on 2 threads vs 1"
    );
    let d = atlas.dim;
    let mut full = 0;
    for e in 0..atlas.len() {
        full += usize::from(
            SliderCircuit::new(slider_candidate(atlas.candidate[e]).unwrap())
                .unwrap()
                .full_turn(),
        );
        if e % 499 == 0 {
            let q = &atlas.descriptors[e * d..(e + 1) * d];
            let hits = nearest(&atlas.descriptors, d, q, 1, 2).unwrap();
            assert_eq!(hits[0].0, e, "entry {e}'s nearest: {:?}", hits[0]);
        }
    }
    // Both kinds of crank are present in numbers.
    assert!(full > 300 && full < 2700, "{full} of 3000 turn fully");
}

#[test]
fn atlas_query_finds_each_entry() {
    let atlas = Atlas::build(5000, AtlasSpec::default(), 2).unwrap();
    let d = atlas.dim;
    for e in (0..atlas.len()).step_by(997) {
        let hits = nearest(
            &atlas.descriptors,
            d,
            &atlas.descriptors[e * d..(e + 1) * d],
            1,
            2,
        )
        .unwrap();
        assert_eq!(hits[0].0, e, "entry {e}'s nearest: {:?}", hits[0]);
    }
    assert!(
        nearest(&atlas.descriptors, 0, &[], 1, 1).is_err(),
        "nearest with dim 0 accepted"
    );
}

/// Counts whose arithmetic or allocation would overflow are typed errors, not panics.
#[test]
fn absurd_counts_are_errors() {
    use linkage_core::{descriptor_len, query_descriptors, Error};
    let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(x, y)| Vec2::new(x, y));
    for harmonics in [usize::MAX, usize::MAX / 8] {
        assert_eq!(
            Efd::closed(&square, harmonics),
            Err(Error::CountOverflow { what: "harmonics" }),
            "Efd::closed with {harmonics} harmonics"
        );
    }
    assert_eq!(
        descriptor_len(usize::MAX),
        usize::MAX,
        "descriptor_len(usize::MAX) does not saturate"
    );
    let r = query_descriptors(&square, usize::MAX, true, &mut [0.0; 4]);
    assert!(
        matches!(r, Err(Error::BufferLength { .. })),
        "query_descriptors with usize::MAX harmonics: {r:?}"
    );
    let spec = AtlasSpec::default();
    let r = Atlas::build(usize::MAX, spec, 1);
    assert!(
        matches!(r, Err(Error::CountOverflow { .. })),
        "Atlas::build of usize::MAX entries: {:?}",
        r.as_ref().map(Atlas::len)
    );
    for bad in [
        AtlasSpec {
            harmonics: usize::MAX,
            ..spec
        },
        AtlasSpec {
            samples: usize::MAX,
            ..spec
        },
    ] {
        let r = Atlas::build(1, bad, 1);
        assert!(
            matches!(r, Err(Error::CountOverflow { .. })),
            "Atlas::build with {bad:?}: {:?}",
            r.as_ref().map(Atlas::len)
        );
    }
    // A `k` beyond every pair of entry and target asks for them all, not for memory.
    let rows = [0.0f32, 1.0, 2.0];
    assert_eq!(
        nearest(&rows, 1, &[0.0], usize::MAX, 1).unwrap().len(),
        3,
        "nearest with k = usize::MAX over 3 rows"
    );
}
