//! Four-bars from the equation of their coupler curve, in closed form.
//!
//! # The curve's equation
//! A four-bar's coupler curve is a tricircular sextic: with `z = x + iy`, its equation is
//! `Σ c_ij z^i z̄^j = 0` over `i, j ≤ 3`, with `c_ji = conj(c_ij)` (16 real numbers, one of
//! them a free scale). The coefficients are therefore the null vector of a 16-column matrix of
//! the target points' monomials, whatever part of the curve the points cover: a closed curve,
//! an open arc, any placement and scale. Two different such sextics share at most 18 points
//! besides the circular points, so 19 points on a four-bar's curve fix it (16 do in general).
//!
//! # The linkage
//! - **Pivots.** Along the isotropic lines `z = const` the equation has degree 3 in `z̄`; the
//!   lines tangent at the circular point meet it in degree 2, at the roots of the cubic
//!   `Σ_i c_i3 z^i = 0`. Those three roots are the curve's singular foci: the fixed pivots of
//!   the three Roberts cognates that draw the curve.
//! - **Coupler triangle.** The pivots' triangle `A₀B₀C₀` is similar to each cognate's coupler
//!   triangle `ABP` (Roberts' law), so with `C₀` chosen, the triangle's shape is known and its
//!   size is one unknown, the coupler `c`. With `t = (C₀ − A₀)/(B₀ − A₀)` (or its conjugate, for
//!   the mirrored triangle), `P = A + c·t` in the coupler's frame.
//! - **Lengths.** For a coupler turned by `ζ = e^{iψ}`, the crank pin is `A = P − c·t·ζ` and
//!   `|A − A₀|² = a²` is linear in `ζ`, as is the rocker's condition; eliminating `ζ`
//!   (`|ζ| = 1`) gives the curve's equation, which is linear in `p = a² − |PA|²`,
//!   `q = b² − |PB|²`, `p²`, `pq`, `q²` and `s = c²`, up to the scale of the fitted
//!   coefficients. One least-squares solve of 32 real equations in those 6 unknowns and the
//!   scale gives the cognate; its relative residual says how well the labelling fits.
//!
//! Each of the three choices of `C₀`, with the triangle direct or mirrored, gives one solve;
//! for points on a four-bar's curve, the three cognates solve exactly (residual at rounding).
//! Points on no four-bar's curve still give linkages: starting points for a least-squares fit.

use alloc::vec::Vec;
use nalgebra::{DMatrix, DVector, RealField};

use crate::error::Error;
use crate::numeric::scalar::{lit, Vec2};

/// Whether `x > 0` (false for NaN).
pub(crate) fn positive<T: RealField + Copy>(x: T) -> bool {
    x.partial_cmp(&T::zero()) == Some(core::cmp::Ordering::Greater)
}

/// The fewest points [`fourbars_from_curve`] takes: one fewer than the curve's coefficients.
pub const CURVE_EQUATION_POINTS: usize = 16;

/// A complex number (the few operations the elimination needs, generic over the scalar).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Cx<T> {
    pub(crate) re: T,
    pub(crate) im: T,
}

impl<T: RealField + Copy> Cx<T> {
    pub(crate) fn new(re: T, im: T) -> Self {
        Cx { re, im }
    }
    pub(crate) fn zero() -> Self {
        Cx::new(T::zero(), T::zero())
    }
    pub(crate) fn real(re: T) -> Self {
        Cx::new(re, T::zero())
    }
    pub(crate) fn add(self, o: Self) -> Self {
        Cx::new(self.re + o.re, self.im + o.im)
    }
    pub(crate) fn sub(self, o: Self) -> Self {
        Cx::new(self.re - o.re, self.im - o.im)
    }
    pub(crate) fn mul(self, o: Self) -> Self {
        Cx::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
    pub(crate) fn scale(self, k: T) -> Self {
        Cx::new(self.re * k, self.im * k)
    }
    pub(crate) fn conj(self) -> Self {
        Cx::new(self.re, -self.im)
    }
    pub(crate) fn norm(self) -> T {
        self.re.hypot(self.im)
    }
    pub(crate) fn div(self, o: Self) -> Self {
        // Scaled by the larger part of `o`: no square overflows.
        let k = o.re.abs().max(o.im.abs());
        let (a, b) = (self.scale(T::one() / k), o.scale(T::one() / k));
        let d = b.re * b.re + b.im * b.im;
        a.mul(b.conj()).scale(T::one() / d)
    }
}

/// A polynomial `Σ c_ij z^i z̄^j`, `i, j ≤ 3`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Poly<T> {
    pub(crate) c: [[Cx<T>; 4]; 4],
}

impl<T: RealField + Copy> Poly<T> {
    pub(crate) fn zero() -> Self {
        Poly {
            c: [[Cx::zero(); 4]; 4],
        }
    }
    /// `c0 + cz·z + cb·z̄`.
    fn linear(c0: Cx<T>, cz: Cx<T>, cb: Cx<T>) -> Self {
        let mut p = Poly::zero();
        p.c[0][0] = c0;
        p.c[1][0] = cz;
        p.c[0][1] = cb;
        p
    }
    fn add(&self, o: &Self) -> Self {
        let mut p = *self;
        for i in 0..4 {
            for j in 0..4 {
                p.c[i][j] = p.c[i][j].add(o.c[i][j]);
            }
        }
        p
    }
    pub(crate) fn scale(&self, k: Cx<T>) -> Self {
        let mut p = *self;
        for row in &mut p.c {
            for v in row {
                *v = v.mul(k);
            }
        }
        p
    }
    /// The product; every product formed here stays within degree 3 in `z` and in `z̄`.
    fn mul(&self, o: &Self) -> Self {
        let mut p = Poly::zero();
        for i in 0..4 {
            for j in 0..4 {
                let a = self.c[i][j];
                if a == Cx::zero() {
                    continue;
                }
                for k in 0..4 - i {
                    for l in 0..4 - j {
                        p.c[i + k][j + l] = p.c[i + k][j + l].add(a.mul(o.c[k][l]));
                    }
                }
            }
        }
        p
    }
    /// The conjugate polynomial (`z ↔ z̄`, coefficients conjugated): its values are the
    /// conjugates of this one's.
    fn conj(&self) -> Self {
        let mut p = Poly::zero();
        for i in 0..4 {
            for j in 0..4 {
                p.c[j][i] = self.c[i][j].conj();
            }
        }
        p
    }
    /// `self·conj(o) + conj(self)·o`: twice the real part of `self·conj(o)`, a real polynomial.
    fn cross(&self, o: &Self) -> Self {
        self.mul(&o.conj()).add(&self.conj().mul(o))
    }
    /// The 32 real numbers of the coefficients, real parts then imaginary.
    fn column(&self) -> [T; 32] {
        let mut out = [T::zero(); 32];
        for i in 0..4 {
            for j in 0..4 {
                out[4 * i + j] = self.c[i][j].re;
                out[16 + 4 * i + j] = self.c[i][j].im;
            }
        }
        out
    }
}

/// A four-bar found from the curve's equation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EquationFit<T> {
    /// The placed four-bar `[ox, oy, cx, cy, crank, coupler, rocker, along, left]` (the layout
    /// of [`crate::PLACED_PARAMS`]), in the points' frame; its assembly is not known (the
    /// equation holds both circuits' curves).
    pub params: [T; 9],
    /// The linear solve's relative residual: at rounding for a labelling of the foci that
    /// fits the curve's equation.
    pub residual: T,
}

/// What [`fourbars_from_curve`] found.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveEquation<T> {
    /// The four-bars, least residual first (at most 6: three choices of the coupler point's
    /// pivot, the triangle direct or mirrored — one triangle when the coupler point is on the
    /// coupler line; those with a coupler or a link of no real length are left out).
    pub fits: Vec<EquationFit<T>>,
    /// The curve's three singular foci (the cognates' fixed pivots), in the points' frame.
    pub foci: [Vec2<T>; 3],
    /// The least singular value of the monomial matrix over its largest: how far the points
    /// are from a tricircular sextic (rounding for points on a four-bar's curve).
    pub misfit: T,
    /// The second-least over the largest: how well the points single out one sextic (near
    /// rounding when they fit a whole family, e.g. too short an arc, or a curve that is not a
    /// true sextic).
    pub spread: T,
}

/// The curve's coefficients `c[i][j]` of `z^i z̄^j` (`i, j ≤ 3`, `i + j ≤ degree`) from points
/// in the unit frame, and the singular values' ratios (least, second least). `degree` 6: a
/// tricircular sextic (16 real coefficients); 4: a circular quartic (13).
pub(crate) fn fit_equation<T: RealField + Copy>(
    z: &[Cx<T>],
    degree: usize,
) -> Option<(Poly<T>, T, T)> {
    let n = z.len();
    let terms = (0..4)
        .flat_map(|i| (i..4).map(move |j| (i, j)))
        .filter(|&(i, j)| i + j <= degree)
        .map(|(i, j)| if i == j { 1 } else { 2 })
        .sum::<usize>();
    if n < terms {
        return None;
    }
    let mut a = DMatrix::<T>::zeros(n, terms);
    let two = lit::<T>(2.0);
    for (r, &p) in z.iter().enumerate() {
        let mut zi = [Cx::real(T::one()); 4];
        let mut bi = [Cx::real(T::one()); 4];
        for k in 1..4 {
            zi[k] = zi[k - 1].mul(p);
            bi[k] = bi[k - 1].mul(p.conj());
        }
        let mut col = 0;
        for (i, zp) in zi.iter().enumerate() {
            for (j, bp) in bi.iter().enumerate().skip(i) {
                if i + j > degree {
                    continue;
                }
                let m = zp.mul(*bp);
                if i == j {
                    a[(r, col)] = m.re;
                    col += 1;
                } else {
                    // c_ij z^i z̄^j + conj: 2·Re(c)·Re(m) − 2·Im(c)·Im(m).
                    a[(r, col)] = two * m.re;
                    a[(r, col + 1)] = -two * m.im;
                    col += 2;
                }
            }
        }
    }
    let svd = a.svd(false, true);
    let v_t = svd.v_t?;
    let s = &svd.singular_values;
    // Sorted in decreasing order by nalgebra's `svd`.
    let top = s[0];
    if !positive(top) || v_t.nrows() < terms {
        return None;
    }
    let f = v_t.row(terms - 1);
    let mut poly = Poly::zero();
    let mut col = 0;
    for i in 0..4 {
        for j in i..4 {
            if i + j > degree {
                continue;
            }
            if i == j {
                poly.c[i][i] = Cx::real(f[col]);
                col += 1;
            } else {
                poly.c[i][j] = Cx::new(f[col], f[col + 1]);
                poly.c[j][i] = poly.c[i][j].conj();
                col += 2;
            }
        }
    }
    Some((poly, s[terms - 1] / top, s[terms - 2] / top))
}

/// The roots of `Σ_k a[k] z^k` (`a[3] ≠ 0`): Durand–Kerner's iteration, then Newton's.
fn cubic_roots<T: RealField + Copy>(a: [Cx<T>; 4]) -> Option<[Cx<T>; 3]> {
    let lead = a[3];
    if !positive(lead.norm()) {
        return None;
    }
    let m = [a[0].div(lead), a[1].div(lead), a[2].div(lead)];
    let f = |z: Cx<T>| m[0].add(z.mul(m[1].add(z.mul(m[2].add(z)))));
    let df = |z: Cx<T>| {
        m[1].add(z.mul(m[2].scale(lit(2.0))))
            .add(z.mul(z).scale(lit(3.0)))
    };
    // Starts on a circle of the roots' bound, off the axes.
    let bound = T::one() + m[0].norm().max(m[1].norm()).max(m[2].norm());
    let w = Cx::new(lit::<T>(0.4), lit::<T>(0.9));
    let mut r = [
        w.scale(bound),
        w.mul(w).scale(bound),
        w.mul(w).mul(w).scale(bound),
    ];
    for _ in 0..500 {
        let mut moved = T::zero();
        for k in 0..3 {
            let mut d = Cx::real(T::one());
            for l in 0..3 {
                if l != k {
                    d = d.mul(r[k].sub(r[l]));
                }
            }
            if d.norm() == T::zero() {
                return None;
            }
            let step = f(r[k]).div(d);
            r[k] = r[k].sub(step);
            moved = moved.max(step.norm());
        }
        if moved <= T::default_epsilon() * bound {
            break;
        }
    }
    for z in &mut r {
        for _ in 0..3 {
            let d = df(*z);
            if d.norm() == T::zero() {
                break;
            }
            *z = z.sub(f(*z).div(d));
        }
        if !(z.re.is_finite() && z.im.is_finite()) {
            return None;
        }
    }
    Some(r)
}

/// The solve for pivots `a0`, `b0` and the coupler point at `P = A + c·t`: the placed
/// parameters (unit frame) and the relative residual.
fn solve<T: RealField + Copy>(
    curve: &Poly<T>,
    a0: Cx<T>,
    b0: Cx<T>,
    t: Cx<T>,
) -> Option<([T; 9], T)> {
    let one = Cx::real(T::one());
    let (k1, k2) = (t.norm(), one.sub(t).norm());
    if !(positive(k1) && positive(k2)) {
        return None;
    }
    // Unit directions from P to A and from P to B, in the coupler's frame.
    let u1 = t.scale(-T::one() / k1);
    let u2 = one.sub(t).scale(T::one() / k2);
    let zero = Cx::zero();
    // ω = conj(z − pivot)·u: the dyad's condition is 2·r·Re(ω ζ) = ρ.
    let w1 = Poly::linear(a0.conj().scale(-T::one()), zero, one).scale(u1);
    let w2 = Poly::linear(b0.conj().scale(-T::one()), zero, one).scale(u2);
    // |z − pivot|².
    let wa = Poly::linear(a0.scale(-T::one()), one, zero).mul(&Poly::linear(
        a0.conj().scale(-T::one()),
        zero,
        one,
    ));
    let wb = Poly::linear(b0.scale(-T::one()), one, zero).mul(&Poly::linear(
        b0.conj().scale(-T::one()),
        zero,
        one,
    ));
    // T = k1·ρ2·ω1 − k2·ρ1·ω2 = q·X + p·Y + Z, with ρ1 = p − |z − a0|², ρ2 = q − |z − b0|².
    let x = w1.scale(Cx::real(k1));
    let y = w2.scale(Cx::real(-k2));
    let zz = wb
        .mul(&w1)
        .scale(Cx::real(-k1))
        .add(&wa.mul(&w2).scale(Cx::real(k2)));
    // |T|² − 4·s·k1²·k2²·Im(ω1 conj ω2)² = 0.
    let im = w1
        .mul(&w2.conj())
        .add(&w1.conj().mul(&w2).scale(Cx::real(-T::one())))
        .scale(Cx::new(T::zero(), lit(-0.5)));
    let h = im
        .mul(&im)
        .scale(Cx::real(lit::<T>(-4.0) * k1 * k1 * k2 * k2));
    let half = Cx::real(lit::<T>(0.5));
    let cols = [
        y.cross(&zz),                     // p
        x.cross(&zz),                     // q
        y.cross(&y).scale(half),          // p²
        x.cross(&y),                      // pq
        x.cross(&x).scale(half),          // q²
        h,                                // s
        curve.scale(Cx::real(-T::one())), // the fitted equation's scale
    ];
    let rhs = zz.cross(&zz).scale(half).column();
    let mut m = DMatrix::<T>::zeros(32, 7);
    for (k, c) in cols.iter().enumerate() {
        for (r, v) in c.column().iter().enumerate() {
            m[(r, k)] = *v;
        }
    }
    let b = -DVector::from_column_slice(&rhs);
    let scale = b.norm();
    if !positive(scale) {
        return None;
    }
    let svd = m.clone().svd(true, true);
    let sol = svd.solve(&b, T::default_epsilon()).ok()?;
    let residual = (&m * &sol - &b).norm() / scale;
    let (p, q, s) = (sol[0], sol[1], sol[5]);
    if !positive(s) {
        return None;
    }
    let c = s.sqrt();
    let (r1, r2) = (k1 * c, k2 * c);
    let (a2, b2) = (p + r1 * r1, q + r2 * r2);
    if !(positive(a2) && positive(b2)) {
        return None;
    }
    let point = t.scale(c);
    let params = [
        a0.re,
        a0.im,
        b0.re,
        b0.im,
        a2.sqrt(),
        c,
        b2.sqrt(),
        point.re,
        point.im,
    ];
    params
        .iter()
        .all(|v| v.is_finite())
        .then_some((params, residual))
}

/// The frame's centre and radius, and the points in it.
pub(crate) type Frame<T> = (Vec2<T>, T, Vec<Cx<T>>);

/// The points in the unit frame (centred, RMS radius 1), with the frame's centre and radius:
/// formed in units of a power of two near the largest coordinate, so no sum or square
/// overflows or underflows at extreme scales.
///
/// # Errors
/// [`Error::TooFew`] for fewer than `needed` points, [`Error::NotFinite`] for a point that is
/// not finite, [`Error::Degenerate`] when they are all one point.
pub(crate) fn unit_frame<T: RealField + Copy>(
    points: &[Vec2<T>],
    needed: usize,
) -> Result<Frame<T>, Error> {
    if points.len() < needed {
        return Err(Error::TooFew {
            what: "points on the curve",
            needed,
            got: points.len(),
        });
    }
    for p in points {
        for v in [p.x, p.y] {
            if !v.is_finite() {
                return Err(Error::NotFinite {
                    what: "curve point",
                    value: crate::numeric::scalar::to_f64(v),
                });
            }
        }
    }
    // The unit frame: centred, RMS radius 1, formed in units of a power of two near the largest
    // coordinate (no sum or square overflows or underflows at extreme scales).
    let largest = points
        .iter()
        .fold(T::zero(), |m, p| m.max(p.x.abs()).max(p.y.abs()));
    let unit = crate::numeric::pow2::pow2_scale(largest);
    let n: T = lit(points.len() as f64);
    let centre = points.iter().fold(Vec2::zeros(), |s, p| s + p / unit) / n;
    let rms = (points
        .iter()
        .map(|p| (p / unit - centre).norm_squared())
        .fold(T::zero(), |s, v| s + v)
        / n)
        .sqrt();
    if !(positive(rms) && rms.is_finite()) {
        return Err(Error::Degenerate {
            what: "the points are all one point",
        });
    }
    let (centre, rms) = (centre * unit, rms * unit);
    let z: Vec<Cx<T>> = points
        .iter()
        .map(|p| Cx::new((p.x - centre.x) / rms, (p.y - centre.y) / rms))
        .collect();
    Ok((centre, rms, z))
}

/// Four-bars whose coupler curve passes through `points`, from the curve's equation (module
/// docs): exact, to rounding, for points on a four-bar's curve; starting points for a fit
/// otherwise.
///
/// ```
/// use linkage_core::{fourbars_from_curve, Assembly, FourBar, Vec2};
/// // 24 points on half of a crank-rocker's coupler curve.
/// let fb = FourBar::new(1.0_f64, 0.4, 1.2, 1.1, (0.5, 0.3), Assembly::Open).unwrap();
/// let points: Vec<Vec2<f64>> = (0..24)
///     .map(|k| fb.pose(3.0 * k as f64 / 23.0).unwrap().coupler_point)
///     .collect();
/// let found = fourbars_from_curve(&points).unwrap();
/// // The pivots are two of the curve's foci, and the three cognates solve exactly.
/// for pivot in [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0)] {
///     assert!(found.foci.iter().any(|f| (f - pivot).norm() < 1e-6));
/// }
/// assert!(found.fits[..3].iter().all(|f| f.residual < 1e-9));
/// // One of them is the linkage itself: crank 0.4, coupler 1.2, rocker 1.1.
/// assert!(found.fits.iter().any(|f| {
///     let want = [0.0, 0.0, 1.0, 0.0, 0.4, 1.2, 1.1, 0.5, 0.3];
///     f.params.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-7)
/// }));
/// ```
///
/// # Errors
/// - [`Error::TooFew`] for fewer than [`CURVE_EQUATION_POINTS`] points.
/// - [`Error::NotFinite`] for a point that is not finite.
/// - [`Error::Degenerate`] when the points are all one point, fit a family of sextics rather
///   than one (to rounding: collinear points, a few positions repeated, a circle, too short an
///   arc), or fix no sextic with three finite foci.
pub fn fourbars_from_curve<T: RealField + Copy>(
    points: &[Vec2<T>],
) -> Result<CurveEquation<T>, Error> {
    let (centre, rms, z) = unit_frame(points, CURVE_EQUATION_POINTS)?;
    let degenerate = |what| Error::Degenerate { what };
    let (curve, misfit, spread) =
        fit_equation(&z, 6).ok_or(degenerate("the points fix no curve equation"))?;
    if !positive(spread - lit::<T>(4.0) * T::default_epsilon()) {
        // A family of curves fits them (rank deficient to rounding): the foci of its least
        // singular vector are arbitrary (20 collinear points gave a pivot 1e16 away).
        return Err(degenerate(
            "the points fit a family of curves, not one: too few distinct points, all on a \
             line or a circle, or too short an arc",
        ));
    }
    let f = cubic_roots([curve.c[0][3], curve.c[1][3], curve.c[2][3], curve.c[3][3]])
        .ok_or(degenerate("the curve's equation has no three finite foci"))?;
    let mut fits = Vec::new();
    for ic in 0..3 {
        let (a0, b0) = (f[(ic + 1) % 3], f[(ic + 2) % 3]);
        let ground = b0.sub(a0);
        if !positive(ground.norm()) {
            continue;
        }
        let t = f[ic].sub(a0).div(ground);
        // A coupler point on the coupler line (`t` real to rounding): the mirrored triangle is
        // the same one, and its solve the same four-bar.
        let flat = t.im.abs() <= lit::<T>(1e-9) * t.norm();
        for tt in [t, t.conj()].into_iter().take(if flat { 1 } else { 2 }) {
            if let Some((mut params, residual)) = solve(&curve, a0, b0, tt) {
                for (k, v) in params.iter_mut().enumerate() {
                    *v = match k {
                        0 | 2 => centre.x + *v * rms,
                        1 | 3 => centre.y + *v * rms,
                        _ => *v * rms,
                    };
                }
                fits.push(EquationFit { params, residual });
            }
        }
    }
    fits.sort_by(|a, b| {
        a.residual
            .partial_cmp(&b.residual)
            .unwrap_or(core::cmp::Ordering::Equal)
    });
    let focus = |c: Cx<T>| Vec2::new(centre.x + c.re * rms, centre.y + c.im * rms);
    Ok(CurveEquation {
        fits,
        foci: [focus(f[0]), focus(f[1]), focus(f[2])],
        misfit,
        spread,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linkages::fourbar::{Assembly, FourBar};
    use crate::synthesis::circuit::{Circuit, CircuitPath, FootSearch};

    /// `n` points of `fb`'s circuit from circuit parameter `from` to `to`.
    fn on_circuit(fb: [f64; 9], crossed: bool, n: usize, from: f64, to: f64) -> Vec<Vec2<f64>> {
        let path = CircuitPath::placed(&fb, crossed).unwrap();
        (0..n)
            .map(|k| {
                let s = from + (to - from) * k as f64 / (n - 1) as f64;
                path.point(s).unwrap()
            })
            .collect()
    }

    /// The least largest distance from `points` to a found linkage's curve (either assembly).
    /// The points' rounding, amplified by the fit's conditioning, is what is left: 1e-12 …
    /// 3e-9 of the size on closed curves, up to 5e-6 on the arcs below (a fit of these
    /// linkages, as `linkage.synthesis.path` runs, takes them to 1e-13).
    fn recovered(points: &[Vec2<f64>], closed: bool) -> f64 {
        let found = fourbars_from_curve(points).unwrap();
        let mut feet = vec![0.0; points.len()];
        let mut best = f64::INFINITY;
        for fit in &found.fits {
            for crossed in [false, true] {
                let Ok(path) = CircuitPath::placed(&fit.params, crossed) else {
                    continue;
                };
                if let Some(e) = path.errors(points, 512, FootSearch::Exact, closed, &mut feet) {
                    if e.max < best {
                        best = e.max;
                    }
                }
            }
        }
        best
    }

    const LINKAGES: [([f64; 9], bool); 4] = [
        // A crank-rocker, a double rocker (crossed), a drag link, a point off the coupler.
        ([0.0, 0.0, 1.0, 0.0, 0.4, 1.2, 1.1, 0.5, 0.3], false),
        ([2.0, -1.0, 3.5, 0.5, 1.3, 0.7, 1.6, -0.4, 0.9], true),
        ([0.0, 0.0, 0.5, 0.0, 1.5, 1.4, 1.2, 0.2, -1.1], false),
        ([-3.0, 4.0, -1.0, 4.0, 0.6, 2.2, 1.9, 2.6, 1.7], false),
    ];

    #[test]
    fn closed_curves_are_recovered_to_rounding() {
        for (fb, crossed) in LINKAGES {
            let pts = on_circuit(fb, crossed, 41, 0.0, 6.0);
            let size = pts.iter().map(|q| (q - pts[0]).norm()).fold(0.0, f64::max);
            let e = recovered(&pts, false);
            assert!(e < 1e-8 * size, "{fb:?}: {e:e} of {size:e}");
        }
    }

    #[test]
    fn open_arcs_at_any_scale_are_recovered() {
        for (fb, crossed) in LINKAGES {
            // Moved by a few of its sizes: the points carry the same relative rounding (a
            // short arc's fit amplifies it; refining a fit removes that).
            for scale in [1e-3, 1.0, 1e4] {
                let mut p = fb;
                for (k, v) in p.iter_mut().enumerate() {
                    *v = *v * scale + if k < 4 { -2.5 * scale } else { 0.0 };
                }
                // 40 % of the circuit, 24 points. (Shorter arcs single out the curve less
                // well: a sixth of the first linkage's circuit gives `spread` 8e-15, and a
                // start 2 % of the arc's size off.)
                let pts = on_circuit(p, crossed, 24, 0.5, 3.0);
                let size = pts.iter().map(|q| (q - pts[0]).norm()).fold(0.0, f64::max);
                let e = recovered(&pts, false);
                assert!(e < 2e-5 * size, "{p:?}: {e:e} of {size:e}");
            }
        }
    }

    #[test]
    fn the_foci_are_the_three_cognates_pivots() {
        let fb = FourBar::new(1.0, 0.4, 1.2, 1.1, (0.5, 0.3), Assembly::Open).unwrap();
        let pts: Vec<_> = (0..30)
            .map(|k| fb.pose(0.2 * k as f64).unwrap().coupler_point)
            .collect();
        let found = fourbars_from_curve(&pts).unwrap();
        let [a, b] = fb.cognates().unwrap();
        for pivot in [fb.o, fb.c, a.o, a.c, b.o, b.c] {
            let near = found
                .foci
                .iter()
                .map(|f| (f - pivot).norm())
                .fold(1.0, f64::min);
            assert!(near < 1e-9, "pivot {pivot:?} {near:e}");
        }
        assert!(found.misfit < 1e-12 && found.spread > 1e-9, "{found:?}");
    }

    #[test]
    fn single_precision_finds_the_linkage_approximately() {
        let fb = FourBar::new(1.0_f32, 0.4, 1.2, 1.1, (0.5, 0.3), Assembly::Open).unwrap();
        let pts: Vec<_> = (0..40)
            .map(|k| fb.pose(0.157 * k as f32).unwrap().coupler_point)
            .collect();
        let found = fourbars_from_curve(&pts).unwrap();
        let want = [0.0_f32, 0.0, 1.0, 0.0, 0.4, 1.2, 1.1, 0.5, 0.3];
        let off = |f: &EquationFit<f32>| {
            f.params
                .iter()
                .zip(want)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f32::max)
        };
        let best = found.fits.iter().map(off).fold(f32::INFINITY, f32::min);
        // Single precision's rounding, amplified by the fit's conditioning, leaves the
        // linkage a few hundredths off: a start for a fit, not an answer.
        assert!(best < 5e-2, "{best}");
    }

    #[test]
    fn bad_points_are_errors() {
        let one = vec![Vec2::new(1.0, 2.0); 20];
        let few = fourbars_from_curve(&one[..15]);
        let want = Error::TooFew {
            what: "points on the curve",
            needed: 16,
            got: 15,
        };
        assert_eq!(few, Err(want), "15 points");
        let same = fourbars_from_curve(&one);
        assert!(matches!(same, Err(Error::Degenerate { .. })), "{same:?}");
        let mut nan = on_circuit(LINKAGES[0].0, false, 20, 0.0, 6.0);
        nan[3].y = f64::NAN;
        let got = fourbars_from_curve(&nan);
        assert!(matches!(got, Err(Error::NotFinite { .. })), "{got:?}");
        // Points that fit a family of curves: collinear, or a few positions repeated.
        let line: Vec<_> = (0..20)
            .map(|k| Vec2::new(k as f64, 2.0 * k as f64))
            .collect();
        let two: Vec<_> = (0..20).map(|k| Vec2::new((k % 2) as f64, 0.0)).collect();
        for (what, pts) in [("collinear", line), ("two positions", two)] {
            let got = fourbars_from_curve(&pts);
            assert!(
                matches!(got, Err(Error::Degenerate { .. })),
                "{what}: {got:?}"
            );
        }
    }

    #[test]
    fn extreme_scales_are_the_same_problem() {
        // Squares of 1e±300 overflow or underflow: the frame is formed in units of a power of two.
        let pts = on_circuit(LINKAGES[0].0, false, 30, 0.0, 6.0);
        let base = fourbars_from_curve(&pts).expect("unit scale");
        for k in [1e300, 1e-300] {
            let far: Vec<_> = pts.iter().map(|p| p * k).collect();
            let got = fourbars_from_curve(&far).expect("a scaled curve");
            assert_eq!(got.fits.len(), base.fits.len(), "{k:e}");
            // The same four-bars scaled (their order may differ: residuals tie at rounding).
            for b in &base.fits {
                let same = |a: &EquationFit<f64>| {
                    let off = a
                        .params
                        .iter()
                        .zip(b.params)
                        .map(|(x, y)| (x / k - y).abs());
                    off.fold(0.0, f64::max) <= 1e-9
                };
                assert!(
                    got.fits.iter().any(same),
                    "{k:e}: {b:?} not in {:?}",
                    got.fits
                );
            }
        }
    }

    #[test]
    fn a_point_on_the_coupler_line_gives_each_cognate_once() {
        // Hoecken's linkage: P on the line AB, so the mirrored triangle is the same one.
        let hoecken = [0.0, 0.0, 20.0, 0.0, 10.0, 25.0, 25.0, 50.0, 0.0];
        let pts = on_circuit(hoecken, false, 40, 0.0, 6.0);
        let found = fourbars_from_curve(&pts).expect("Hoecken's curve");
        assert_eq!(found.fits.len(), 3, "{found:?}");
        for (i, a) in found.fits.iter().enumerate() {
            for b in &found.fits[i + 1..] {
                let apart = a.params.iter().zip(b.params).map(|(x, y)| (x - y).abs());
                assert!(apart.fold(0.0, f64::max) > 1e-3, "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn points_on_a_conic_single_out_no_curve() {
        // An ellipse times any line is a cubic, and every cubic is among the curves' equations:
        // the points fit a family of them, which `spread` shows (or no three foci are found).
        let pts: Vec<_> = (0..32)
            .map(|k| {
                let a = k as f64 * core::f64::consts::TAU / 32.0;
                Vec2::new(3.0 * a.cos(), a.sin())
            })
            .collect();
        match fourbars_from_curve(&pts) {
            Ok(found) => assert!(found.spread < 1e-9, "{found:?}"),
            Err(e) => assert!(matches!(e, Error::Degenerate { .. }), "{e}"),
        }
    }
}
