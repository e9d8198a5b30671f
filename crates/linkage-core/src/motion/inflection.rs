//! Inflection circle and Ball point of a moving body (Euler–Savary), to third order.

use nalgebra::RealField;

use crate::motion::centres::{BodyMotion, Centre};
use crate::numeric::scalar::{lit, perp, Vec2};

/// The inflection circle of a body at one instant and its Ball point.
///
/// ```
/// use linkage_core::{catalog, Assembly, FourBar};
/// let fb = catalog::hoecken::<f64>();
/// let inf = fb.coupler_inflection(0.5).unwrap();
/// // The pole is the coupler's instant centre; the inflection pole is across the circle from it.
/// let i13 = fb.instant_centres(0.5).unwrap()[1].finite().unwrap();
/// assert!((inf.pole - i13).norm() < 1e-9);
/// assert!(((inf.inflection_pole - inf.pole).norm() - 2.0 * inf.radius).abs() < 1e-9);
/// assert!((inf.centre - (inf.pole + inf.inflection_pole) * 0.5).norm() < 1e-9);
/// // A parallelogram's coupler translates: no pole, no inflection circle.
/// let par = FourBar::new(3.0_f64, 1.0, 3.0, 1.0, (1.5, 0.0), Assembly::Open).unwrap();
/// assert_eq!(par.coupler_inflection(1.0), None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inflection<T> {
    /// The instantaneous centre of rotation (velocity pole) `I`.
    pub pole: Vec2<T>,
    /// The inflection pole `J = I + a_I/ω²`, diametrically opposite `I` on the circle.
    pub inflection_pole: Vec2<T>,
    /// Centre of the inflection circle, `I + a_I/(2ω²)`.
    pub centre: Vec2<T>,
    /// Radius of the inflection circle, `|a_I|/(2ω²)`.
    pub radius: T,
    /// The Ball point: the point of the circle whose path has stationary zero curvature (a
    /// four-point contact with its tangent), or [`Centre::Undefined`] when the third-order term
    /// vanishes.
    pub ball_point: Centre<T>,
}

/// The inflection circle and Ball point of a body moving with `m`.
///
/// Body points at `P = I + r` move with `v = ω r⊥` about the pole `I`, so their path normal is
/// along `r`; the path is at an inflection when the acceleration has no normal part,
/// `a_P·r = a_I·r − ω²|r|² = 0`: the circle through `I` with diameter `a_I/ω²` (Euler–Savary /
/// Bresse). Its curvature is also stationary when `v × j = 0`; with `j_P = j_I + (α̇ − ω³) r⊥ −
/// 3ωα r` that is `r·(j_I − 3(α/ω) a_I) = 0`, a line through `I`, meeting the circle again at
/// the Ball point. Timing does not matter (rates per unit crank angle are as good as per second).
/// `None` when the body is not turning (`ω = 0`: pole at infinity), the rates are not finite, or
/// the circle lies beyond the float range.
pub fn inflection<T: RealField + Copy>(m: &BodyMotion<T>) -> Option<Inflection<T>> {
    let w = m.omega;
    if w.abs() <= m.omega_tol || !w.is_finite() {
        return None;
    }
    let pole = m.origin + perp(m.v) / w;
    let a_i = m.acceleration_at(pole);
    let j_i = m.jerk_at(pole);
    if !(a_i.x.is_finite() && a_i.y.is_finite() && j_i.x.is_finite() && j_i.y.is_finite()) {
        return None;
    }
    let w2 = w * w;
    let diameter = a_i / w2;
    let g = j_i - a_i * (lit::<T>(3.0) * m.alpha / w);
    let gn = crate::numeric::scalar::length(g);
    let ball_point = if gn == T::zero() {
        Centre::Undefined
    } else {
        let e = perp(g) / gn;
        Centre::Finite(pole + e * diameter.dot(&e))
    };
    let out = Inflection {
        pole,
        inflection_pole: pole + diameter,
        centre: pole + diameter * lit::<T>(0.5),
        radius: crate::numeric::scalar::length(diameter) * lit::<T>(0.5),
        ball_point,
    };
    // A circle beyond the float range (ω² underflowing against a_I, e.g. a subnormal crank) is
    // no circle: `None`, not infinities. A Ball point that is not finite is undefined.
    let finite = |p: Vec2<T>| p.x.is_finite() && p.y.is_finite();
    let circle = finite(out.pole) && finite(out.inflection_pole) && finite(out.centre);
    if !(circle && out.radius.is_finite()) {
        return None;
    }
    let ball_point = match out.ball_point {
        Centre::Finite(p) if !finite(p) => Centre::Undefined,
        b => b,
    };
    Some(Inflection { ball_point, ..out })
}
