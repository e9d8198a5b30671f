//! Subnormal lengths (issue 29, item 10): they used to construct (and classify) but never
//! assemble; every constructor refuses them with `Error::SubnormalLength`, in f64 and f32.

use linkage_core::{Assembly, Error, FourBar, Mechanism, Side, Vec2};

#[test]
fn four_bars_refuse_a_subnormal_length() {
    let tiny = 1e-309_f64;
    assert!(tiny > 0.0 && !tiny.is_normal(), "{tiny} is not subnormal");
    for (dims, what) in [
        ([tiny, 1.0, 1.0, 1.0], "ground"),
        ([1.0, tiny, 1.0, 1.0], "crank"),
        ([1.0, 1.0, tiny, 1.0], "coupler"),
        ([1.0, 1.0, 1.0, tiny], "rocker"),
    ] {
        let e = FourBar::new(
            dims[0],
            dims[1],
            dims[2],
            dims[3],
            (0.0, 0.0),
            Assembly::Open,
        );
        assert_eq!(
            e.unwrap_err(),
            Error::SubnormalLength { what, value: tiny },
            "a subnormal {what}"
        );
    }
    // Pivots a subnormal distance apart.
    let e = FourBar::with_pivots(
        Vec2::new(0.0, 0.0),
        Vec2::new(tiny, 0.0),
        1.0,
        1.0,
        1.0,
        (0.0, 0.0),
        Assembly::Open,
    );
    assert!(
        matches!(e, Err(Error::SubnormalLength { what: "ground", .. })),
        "{e:?}"
    );
    // The smallest normal length is a length (a linkage of such lengths assembles: the solver
    // scales by powers of two).
    let m = f64::MIN_POSITIVE;
    let fb = FourBar::new(2.0 * m, m, 2.0 * m, 2.0 * m, (0.0, 0.0), Assembly::Open).unwrap();
    assert!(
        fb.pose(0.5).is_ok(),
        "lengths of the smallest normal size assemble"
    );
    // f32 has its own threshold (1.2e-38).
    let e = FourBar::new(1.0_f32, 1e-39, 1.0, 1.0, (0.0, 0.0), Assembly::Open).unwrap_err();
    assert!(
        matches!(e, Error::SubnormalLength { what: "crank", .. }),
        "{e:?}"
    );
    assert!(
        FourBar::new(1.0_f32, 1e-37, 1.0, 1.0, (0.0, 0.0), Assembly::Open).is_ok(),
        "1e-37 is a normal f32"
    );
}

#[test]
fn mechanisms_refuse_a_subnormal_length() {
    let tiny = 4e-310_f64;
    let mut m = Mechanism::<f64, 4>::new();
    let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
    let c = m.fixed(Vec2::new(3.0, 0.0)).unwrap();
    let e = m.crank(o, tiny, 0.0).unwrap_err();
    assert_eq!(
        e,
        Error::SubnormalLength {
            what: "crank radius",
            value: tiny
        },
        "a subnormal crank radius"
    );
    let a = m.crank(o, 1.0, 0.0).unwrap();
    let e = m.dyad(a, c, 3.0, tiny, Side::Left).unwrap_err();
    assert_eq!(
        e,
        Error::SubnormalLength {
            what: "dyad r2",
            value: tiny
        },
        "a subnormal dyad link"
    );
    assert!(e.to_string().contains("subnormal"), "{e}");
}

#[cfg(feature = "synthesis")]
#[test]
fn slider_cranks_refuse_a_subnormal_length() {
    use linkage_core::{Reach, SliderCrank};
    let e = SliderCrank::new(
        Vec2::new(0.0, 0.0),
        0.0,
        0.0,
        1e-309_f64,
        3.0,
        (0.0, 0.0),
        Reach::Ahead,
    )
    .unwrap_err();
    assert_eq!(
        e,
        Error::SubnormalLength {
            what: "crank",
            value: 1e-309
        },
        "a subnormal slider-crank crank"
    );
}
