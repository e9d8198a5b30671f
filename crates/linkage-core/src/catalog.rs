//! The straight-line linkages of thesis 1, chapter 1 (docs/domain.md; lengths in mm, after Norton,
//! "Diseño de Maquinaria"), and a pantograph that scales the Hoecken foot path.
//!
//! Four-bars are placed with the crank pivot `O` at the origin and the rocker pivot `C` on the
//! +x axis; their assembly is the one drawn in the source (the one whose coupler point traces the
//! straight part).
//!
//! # Panics
//! None of these functions panics. The fixed entries are built from constants through a helper
//! with an `unreachable!` for construction errors that cannot occur for them (proof at
//! `program`'s definition; `tests/catalog.rs` builds every entry in f32 and f64); the one entry
//! with a caller's number, [`hoecken_pantograph`], returns its errors.

use nalgebra::RealField;

use crate::constructions::dyad::Side;
use crate::error::Error;
use crate::linkages::fourbar::{Assembly, FourBar};
use crate::mechanism::program::Mechanism;
use crate::numeric::scalar::{lit, Vec2};

/// Capacity of the catalogue's multi-loop mechanisms.
pub const CAPACITY: usize = 16;

/// A catalogued mechanism: its program, joint names and the joint that traces the path.
///
/// ```
/// use linkage_core::{catalog, Vec2};
/// let p = catalog::peaucellier::<f64>();
/// assert_eq!((p.name, p.joint_names[p.trace]), ("peaucellier", "P"));
/// // Peaucellier's inversor traces the exact line x = 40 while the crank is in range.
/// let mut j = [Vec2::zeros(); 6];
/// for theta in [-1.0, 0.0, 1.2] {
///     p.mechanism.pose(theta, &mut j).unwrap();
///     assert!((j[p.trace].x - 40.0).abs() < 1e-12);
/// }
/// assert!(catalog::linkage_by_name::<f64>("klann").is_none());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Linkage<T: RealField + Copy> {
    /// Catalogue name.
    pub name: &'static str,
    /// The construction program.
    pub mechanism: Mechanism<T, CAPACITY>,
    /// One name per joint, in program order.
    pub joint_names: &'static [&'static str],
    /// Index of the tracing joint.
    pub trace: usize,
}

/// Names of the catalogued four-bars, in the source's order.
pub const FOUR_BARS: [&str; 7] = [
    "watt",
    "roberts",
    "chebyshev",
    "hoecken",
    "evans_a",
    "evans_b",
    "evans_c",
];

/// Names of the catalogued multi-loop linkages.
pub const MULTI_LOOP: [&str; 4] = ["peaucellier", "hart", "hoecken_pantograph", "jansen"];

fn four_bar<T: RealField + Copy>(
    dims: [f64; 4],
    point: (f64, f64),
    assembly: Assembly,
) -> FourBar<T> {
    let [g, a, b, c] = dims.map(lit::<T>);
    // Unreachable: every caller passes positive constants below 100 and a finite point, which
    // `FourBar::new` accepts for any `RealField` (f32 and f64 both hold them exactly enough to
    // stay positive and finite); `tests/catalog.rs` builds every entry in f32 and f64.
    FourBar::new(g, a, b, c, (lit(point.0), lit(point.1)), assembly)
        .unwrap_or_else(|_| unreachable!("catalogue dimensions are valid"))
}

/// Watt: ground 40, rockers 20, coupler 10, trace at the coupler's midpoint. A triple rocker;
/// the straight part is the crossing of its figure-eight, traced with the rockers nearly parallel.
pub fn watt<T: RealField + Copy>() -> FourBar<T> {
    four_bar([40.0, 20.0, 10.0, 20.0], (5.0, 0.0), Assembly::Crossed)
}

/// Roberts: ground 40, rockers 40, coupler 20, trace at the apex of the isosceles coupler
/// triangle (AP = BP = 40), on the ground side: it runs along the line `O C`.
pub fn roberts<T: RealField + Copy>() -> FourBar<T> {
    // Apex below A→B at 10 along, √(40² − 10²) = √1500 to the right.
    let mut fb = four_bar([40.0, 40.0, 20.0, 40.0], (10.0, 0.0), Assembly::Open);
    fb.left = -lit::<T>(1500.0).sqrt();
    fb
}

/// Chebyshev: ground 20, rockers 25 (crossed), coupler 10, trace at the coupler's midpoint.
pub fn chebyshev<T: RealField + Copy>() -> FourBar<T> {
    four_bar([20.0, 25.0, 10.0, 25.0], (5.0, 0.0), Assembly::Crossed)
}

/// Hoecken: ground 20, crank 10, coupler 25, rocker 25, foot on the coupler line 50 from `A`.
/// A crank-rocker; the straight part is traced while the crank is on the far side of `O` from
/// `C`, the curved part bulges away from the pivots.
pub fn hoecken<T: RealField + Copy>() -> FourBar<T> {
    four_bar([20.0, 10.0, 25.0, 25.0], (50.0, 0.0), Assembly::Open)
}

/// Evans A: ground 12, crank 10, coupler 16, rocker 10.39, trace on the coupler line 26.9 from
/// `A`. Triple rocker, input ≈ 27°…333°.
pub fn evans_a<T: RealField + Copy>() -> FourBar<T> {
    four_bar([12.0, 10.0, 16.0, 10.39], (26.9, 0.0), Assembly::Open)
}

/// Evans B: ground 23.05, crank 10, coupler 12, rocker 11.67, trace on the coupler line 15 from
/// `A`. Triple rocker, input ≈ ±81°.
pub fn evans_b<T: RealField + Copy>() -> FourBar<T> {
    four_bar([23.05, 10.0, 12.0, 11.67], (15.0, 0.0), Assembly::Open)
}

/// Evans C: ground 20, crank 10, coupler 10, rocker 10, trace on the coupler line 10 beyond `B`.
/// Triple rocker, input ≈ ±75°.
pub fn evans_c<T: RealField + Copy>() -> FourBar<T> {
    four_bar([20.0, 10.0, 10.0, 10.0], (20.0, 0.0), Assembly::Open)
}

/// A catalogued four-bar by name (see [`FOUR_BARS`]).
pub fn four_bar_by_name<T: RealField + Copy>(name: &str) -> Option<FourBar<T>> {
    Some(match name {
        "watt" => watt(),
        "roberts" => roberts(),
        "chebyshev" => chebyshev(),
        "hoecken" => hoecken(),
        "evans_a" => evans_a(),
        "evans_b" => evans_b(),
        "evans_c" => evans_c(),
        _ => return None,
    })
}

/// Builds a program, passing on the first construction that fails.
fn try_program<T: RealField + Copy>(
    build: impl FnOnce(&mut Mechanism<T, CAPACITY>) -> Result<(), Error>,
) -> Result<Mechanism<T, CAPACITY>, Error> {
    let mut m = Mechanism::new();
    build(&mut m)?;
    Ok(m)
}

/// Builds a program of constants.
///
/// Unreachable panic: only the fixed catalogue programs below use it. Their lengths are
/// positive constants below 100, their references point backwards, they have one crank and
/// fewer than `CAPACITY` joints, so no construction can fail for any `RealField`;
/// `tests/catalog.rs` builds and sweeps each in f32 and f64. Programs with a caller's numbers
/// (the pantograph's scale) use [`try_program`] and return its error.
fn program<T: RealField + Copy>(
    build: impl FnOnce(&mut Mechanism<T, CAPACITY>) -> Result<(), Error>,
) -> Mechanism<T, CAPACITY> {
    try_program(build).unwrap_or_else(|_| unreachable!("catalogue programs are valid"))
}

/// Peaucellier–Lipkin inversor: centre of inversion `D` at the origin, crank pivot `O` 15 along
/// +x, crank 15 (so `A` circles through `D`), arms `DB = DC = 40`, rhombus sides 20. `P` runs on
/// the exact line `x = (40² − 20²)/(2·15) = 40` while `20 ≤ |DA| ≤ 60` (crank within ≈ ±96.4°).
pub fn peaucellier<T: RealField + Copy>() -> Linkage<T> {
    let c = lit::<T>;
    let mechanism = program(|m| {
        let d = m.fixed(Vec2::new(c(0.0), c(0.0)))?;
        let o = m.fixed(Vec2::new(c(15.0), c(0.0)))?;
        let a = m.crank(o, c(15.0), c(0.0))?;
        let b = m.dyad(d, a, c(40.0), c(20.0), Side::Left)?;
        let cc = m.dyad(d, a, c(40.0), c(20.0), Side::Right)?;
        m.dyad(b, cc, c(20.0), c(20.0), Side::Left)?;
        Ok(())
    });
    Linkage {
        name: "peaucellier",
        mechanism,
        joint_names: &["D", "O", "A", "B", "C", "P"],
        trace: 5,
    }
}

/// Hart's inversor (six links, seven revolutes): `O2` at the origin, `O4` 15 along +x, crank
/// `O2 E` 15 (so `E` circles through `O4`); `A` from `O4` (5) and `E` (10); `B` on `A → O4` at 20,
/// `D` on `A → E` at 40; `C` from `B` (40) and `D` (20) on the crossed (antiparallelogram)
/// branch; `P` on `B → C` at 30. Two dyads in sequence; `P` runs on the exact line `x = 7.5`.
pub fn hart<T: RealField + Copy>() -> Linkage<T> {
    let c = lit::<T>;
    let mechanism = program(|m| {
        let o2 = m.fixed(Vec2::new(c(0.0), c(0.0)))?;
        let o4 = m.fixed(Vec2::new(c(15.0), c(0.0)))?;
        let e = m.crank(o2, c(15.0), c(0.0))?;
        let a = m.dyad(o4, e, c(5.0), c(10.0), Side::Left)?;
        let b = m.point(a, o4, c(20.0), c(0.0))?;
        let d = m.point(a, e, c(40.0), c(0.0))?;
        let cc = m.dyad(b, d, c(40.0), c(20.0), Side::Left)?;
        m.point(b, cc, c(30.0), c(0.0))?;
        Ok(())
    });
    Linkage {
        name: "hart",
        mechanism,
        joint_names: &["O2", "O4", "E", "A", "B", "D", "C", "P"],
        trace: 7,
    }
}

/// The Hoecken linkage driving a pantograph that scales its foot path `T` by `scale` about the
/// fixed pivot `Q = (20, 80)`: arms `Q E = E T = 30`, `F` on `Q → E` at `30·scale`, `G` closing
/// the parallelogram `E F G T`, output `P` on `F → G` at `30·scale`, so `P = Q + scale·(T − Q)`.
///
/// # Errors
/// [`Error::NotFinite`] for a scale that is not finite, [`Error::NotAbove`] unless `scale > 1`,
/// [`Error::NotRepresentable`] when the arms (`30·scale`) overflow.
pub fn hoecken_pantograph<T: RealField + Copy>(scale: T) -> Result<Linkage<T>, Error> {
    let c = lit::<T>;
    let arm = c(30.0);
    let what = "pantograph scale";
    let value = crate::numeric::scalar::to_f64(scale);
    if !scale.is_finite() {
        return Err(Error::NotFinite { what, value });
    }
    if scale <= T::one() {
        return Err(Error::NotAbove {
            what,
            value,
            min: 1.0,
        });
    }
    if !(arm * scale).is_finite() {
        return Err(Error::NotRepresentable {
            what: "pantograph scale's arms (30·scale)",
        });
    }
    let build = |g_side: Side| {
        try_program(|m| {
            let o = m.fixed(Vec2::new(c(0.0), c(0.0)))?;
            let cc = m.fixed(Vec2::new(c(20.0), c(0.0)))?;
            let a = m.crank(o, c(10.0), c(0.0))?;
            let b = m.dyad(a, cc, c(25.0), c(25.0), Side::Left)?;
            let t = m.point(a, b, c(50.0), c(0.0))?;
            let q = m.fixed(Vec2::new(c(20.0), c(80.0)))?;
            let e = m.dyad(q, t, arm, arm, Side::Left)?;
            let f = m.point(q, e, arm * scale, c(0.0))?;
            let g = m.dyad(f, t, arm, arm * (scale - T::one()), g_side)?;
            m.point(f, g, arm * scale, c(0.0))?;
            Ok(())
        })
    };
    // Pick the side of G that closes the parallelogram (G = F + T − E), not its mirror.
    let mut best = (build(Side::Left)?, T::max_value().unwrap_or(T::one()));
    for side in [Side::Left, Side::Right] {
        let m = build(side)?;
        let mut j = [Vec2::zeros(); 10];
        if m.pose(T::zero(), &mut j).is_ok() {
            let miss = (j[8] - (j[7] + j[4] - j[6])).norm();
            if miss < best.1 {
                best = (m, miss);
            }
        }
    }
    Ok(Linkage {
        name: "hoecken_pantograph",
        mechanism: best.0,
        joint_names: &["O", "C", "A", "B", "T", "Q", "E", "F", "G", "P"],
        trace: 9,
    })
}

/// Theo Jansen's Strandbeest leg with his "holy numbers" (a = 38, b = 41.5, c = 39.3,
/// d = 40.1, e = 55.8, f = 39.4, g = 36.7, h = 65.7, i = 49, j = 50, k = 61.9, l = 7.8, m = 15):
/// crank `O A` (m) about the origin, frame pivot `Q` at (−a, −l), and five dyads in sequence —
/// `B` (j from A, b from Q, above), `C` (k, c, below), `D` (e from B, d from Q), `E` (f from D,
/// g from C) and the foot `F` (h from E, i from C). Eight links, one degree of freedom; the foot
/// runs a flat-bottomed path about 68 wide and 22 high. An extra catalogue leg for walkers.
pub fn jansen<T: RealField + Copy>() -> Linkage<T> {
    let c = lit::<T>;
    let mechanism = program(|m| {
        let o = m.fixed(Vec2::new(c(0.0), c(0.0)))?;
        let q = m.fixed(Vec2::new(c(-38.0), c(-7.8)))?;
        let a = m.crank(o, c(15.0), c(0.0))?;
        let b = m.dyad(a, q, c(50.0), c(41.5), Side::Right)?;
        let cc = m.dyad(a, q, c(61.9), c(39.3), Side::Left)?;
        let d = m.dyad(b, q, c(55.8), c(40.1), Side::Right)?;
        let e = m.dyad(d, cc, c(39.4), c(36.7), Side::Right)?;
        m.dyad(e, cc, c(65.7), c(49.0), Side::Right)?;
        Ok(())
    });
    Linkage {
        name: "jansen",
        mechanism,
        joint_names: &["O", "Q", "A", "B", "C", "D", "E", "F"],
        trace: 7,
    }
}

/// A catalogued multi-loop linkage by name (see [`MULTI_LOOP`]); the pantograph at scale 2.
pub fn linkage_by_name<T: RealField + Copy>(name: &str) -> Option<Linkage<T>> {
    match name {
        "peaucellier" => Some(peaucellier()),
        "hart" => Some(hart()),
        "hoecken_pantograph" => hoecken_pantograph(lit(2.0)).ok(),
        "jansen" => Some(jansen()),
        _ => None,
    }
}
