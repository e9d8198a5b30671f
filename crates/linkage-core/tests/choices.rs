//! The core's string choices (`Assembly`, `Side`, `Reach`, `AngleMode`): every name in `NAMES`
//! parses to the value whose `name()` it is, in declaration order, and near misses do not
//! parse. The Python package checks names against these lists (`linkage._core.CHOICES`).

use linkage_core::{AngleMode, Assembly, Error, Reach, Side};

#[test]
fn names_round_trip_in_order() {
    let assembly: Vec<&str> = [Assembly::Open, Assembly::Crossed]
        .map(Assembly::name)
        .to_vec();
    assert_eq!(assembly, Assembly::NAMES, "assembly names");
    let side: Vec<&str> = [Side::Left, Side::Right].map(Side::name).to_vec();
    assert_eq!(side, Side::NAMES, "side names");
    let reach: Vec<&str> = [Reach::Ahead, Reach::Behind].map(Reach::name).to_vec();
    assert_eq!(reach, Reach::NAMES, "reach names");
    let modes = [
        AngleMode::Trig,
        AngleMode::Table { block: 7 },
        AngleMode::Recurrence { block: 7 },
    ];
    assert_eq!(
        modes.map(AngleMode::name).to_vec(),
        AngleMode::NAMES,
        "mode names"
    );
    for n in Assembly::NAMES {
        assert_eq!(n.parse::<Assembly>().map(Assembly::name), Ok(n), "{n}");
    }
    for n in Side::NAMES {
        assert_eq!(n.parse::<Side>().map(Side::name), Ok(n), "{n}");
    }
    for n in Reach::NAMES {
        assert_eq!(n.parse::<Reach>().map(Reach::name), Ok(n), "{n}");
    }
    for (n, m) in AngleMode::NAMES.iter().zip(modes) {
        assert_eq!(AngleMode::named(n, 7), Ok(m), "{n}");
    }
}

#[test]
fn near_misses_are_invalid_choices() {
    for bad in ["", "Open", "open ", "crossed\0", "left"] {
        assert!(
            matches!(
                bad.parse::<Assembly>(),
                Err(Error::InvalidChoice {
                    what: "assembly",
                    ..
                })
            ),
            "{bad:?}"
        );
    }
    for bad in ["Left", "ahead", " right"] {
        assert!(
            matches!(
                bad.parse::<Side>(),
                Err(Error::InvalidChoice { what: "side", .. })
            ),
            "{bad:?}"
        );
    }
    for bad in ["Ahead", "back", "left"] {
        assert!(
            matches!(
                bad.parse::<Reach>(),
                Err(Error::InvalidChoice { what: "reach", .. })
            ),
            "{bad:?}"
        );
    }
    for bad in ["Trig", "fast", "tables"] {
        assert!(
            matches!(
                AngleMode::named(bad, 4),
                Err(Error::InvalidChoice { what: "mode", .. })
            ),
            "{bad:?}"
        );
    }
}
