//! Slider-cranks from the equation of their coupler curve.
//!
//! # The curve's equation
//! A slider-crank's coupler curve is a circular quartic: with `z = x + iy`, its equation is
//! `Σ c_ij z^i z̄^j = 0` over `i, j ≤ 3`, `i + j ≤ 4`, with `c_ji = conj(c_ij)` (13 real
//! numbers, one of them a free scale), found as for a four-bar ([`crate::fourbars_from_curve`])
//! as the null vector of the points' monomials, from a closed curve or an open arc.
//!
//! # The linkage
//! - **Crank pivot.** The equation has degree 1 in `z` where `z̄³` appears: the root of
//!   `c_03 + c_13·z` is the curve's one singular focus, the crank pivot `O`.
//! - **The rest.** With `O` at the origin, the line along `x` at height `e`, crank `r`,
//!   coupler `l` and coupler point `P = A + κ·(B − A)` (`κ = (along + i·left)/l`), the slider
//!   `B = (P − (1 − κ)A)/κ` must lie on the line and `|P − A| = |κ|·l`; with `A = r·u`,
//!   `|u| = 1`, both conditions are linear in `u` and `ū`, and `u·ū = 1` gives the curve:
//!   `Y|w|²N² + |P|²q² − 2qN·Im(ᾱwP) − 4r²·Re(ᾱwP)² = 0` with `α = κ̄`, `Y = |κ|²`,
//!   `w = 1 − κ`, `N = |P|² + r² − l²Y` and `q = 2(Im(κ̄P) − Ye)`. Its quartic part is
//!   `Y|z|²((1 + Y)|z|² − αz² − ᾱz̄²)`, so `c_31/c_22` gives `|κ|` (two roots `ρ`, `1/ρ`: the
//!   linkage and its cognate) and `arg κ` less twice the line's direction `φ`. For each `φ` the
//!   remaining coefficients are linear in `λ`, `λe`, `λr²`, `λn`, `λe²`, `λen`, `λn²`
//!   (`n = r² − l²Y`, `λ` the fitted scale): `c_31`, `c_22` and `c_21` give `λ` and `λe` by
//!   least squares; with `e` known, `c_20`, `c_11` and `c_10` are linear in `λr²` and `λn`;
//!   the residual of all 11 real equations, with every product formed from `λ, e, r², n`,
//!   measures the direction. `φ` is the one-dimensional search: sampled over a half turn (the
//!   line reversed is the same line), each local minimum of that residual refined by golden
//!   section. An offset of zero (a centric slider-crank) and a coupler point on the coupler
//!   line (`κ` real) need no other branch.
//!
//! For points on a slider-crank's curve, the linkage and its cognate solve exactly (residual at
//! rounding). Points on no slider-crank's curve still give linkages: starting points for a fit.

use alloc::vec::Vec;
use nalgebra::{DMatrix, DVector, RealField};

use crate::error::Error;
use crate::numeric::scalar::{lit, Vec2};
use crate::synthesis::curve_equation::{fit_equation, positive, unit_frame, Cx, Poly};
use crate::synthesis::slider_circuit::SLIDER_PARAMS;

/// The fewest points [`slider_cranks_from_curve`] takes: the curve's coefficients.
pub const SLIDER_EQUATION_POINTS: usize = 13;

/// Directions of the line sampled over a half turn (a step of 0.5°).
const DIRECTIONS: usize = 360;

/// Local minima of the residual over the line's direction refined for each `|κ|`.
const MINIMA: usize = 3;

/// A slider-crank found from the curve's equation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderEquationFit<T> {
    /// The placed slider-crank `[ox, oy, angle, offset, crank, coupler, along, left]` (the
    /// layout of [`SLIDER_PARAMS`], on `Reach::Ahead`), in the points' frame. Its reach is not
    /// known (the equation holds both): the other is `angle + π`, `−offset`.
    pub params: [T; SLIDER_PARAMS],
    /// The linear solve's relative residual: at rounding for the line's true direction.
    pub residual: T,
}

/// What [`slider_cranks_from_curve`] found.
#[derive(Clone, Debug, PartialEq)]
pub struct SliderEquation<T> {
    /// The slider-cranks, least residual first (at most 6: two roots of `|κ|`, up to three
    /// directions of the line each; those with a link of no real length are left out).
    pub fits: Vec<SliderEquationFit<T>>,
    /// The curve's singular focus (the crank pivot), in the points' frame.
    pub pivot: Vec2<T>,
    /// The least singular value of the monomial matrix over its largest: how far the points
    /// are from a circular quartic (rounding for points on a slider-crank's curve).
    pub misfit: T,
    /// The second-least over the largest: how well the points single out one quartic.
    pub spread: T,
}

/// `C(n, k)` for `n ≤ 3`.
fn binomial<T: RealField + Copy>(n: usize, k: usize) -> T {
    const ROWS: [[f64; 4]; 4] = [
        [1.0, 0.0, 0.0, 0.0],
        [1.0, 1.0, 0.0, 0.0],
        [1.0, 2.0, 1.0, 0.0],
        [1.0, 3.0, 3.0, 1.0],
    ];
    lit(ROWS[n][k])
}

/// The polynomial in `w = (z − o)/s`: `c'_kl = s^(k+l) Σ_{i≥k, j≥l} C(i,k) C(j,l) c_ij
/// o^(i−k) ō^(j−l)`.
fn moved<T: RealField + Copy>(p: &Poly<T>, o: Cx<T>, s: T) -> Poly<T> {
    let mut op = [Cx::real(T::one()); 4];
    let mut ob = [Cx::real(T::one()); 4];
    let mut sp = [T::one(); 7];
    for k in 1..4 {
        op[k] = op[k - 1].mul(o);
        ob[k] = ob[k - 1].mul(o.conj());
    }
    for k in 1..7 {
        sp[k] = sp[k - 1] * s;
    }
    let mut out = Poly::zero();
    for k in 0..4 {
        for l in 0..4 {
            let mut sum = Cx::zero();
            for i in k..4 {
                for j in l..4 {
                    let c = p.c[i][j];
                    if c == Cx::zero() {
                        continue;
                    }
                    let w = binomial::<T>(i, k) * binomial::<T>(j, l);
                    sum = sum.add(c.mul(op[i - k]).mul(ob[j - l]).scale(w));
                }
            }
            out.c[k][l] = sum.scale(sp[k + l]);
        }
    }
    out
}

/// The coefficients the solve matches, in order, and whether each is real (one equation) or
/// complex (two).
const MATCHED: [(usize, usize, bool); 7] = [
    (3, 1, false),
    (2, 2, true),
    (2, 1, false),
    (2, 0, false),
    (1, 1, true),
    (1, 0, false),
    (0, 0, true),
];

/// The solve at the line's direction `phi` (`big_a = κ̄·e^{2iφ}`) against the normalised
/// coefficients `c` (pivot at the origin): `[λ, λe, λr², λn, λe², λen, λn²]` and the relative
/// residual of the 11 equations.
fn solve_at<T: RealField + Copy>(c: &Poly<T>, big_a: Cx<T>, phi: T) -> Option<([T; 7], T)> {
    let g = Cx::new(phi.cos(), -phi.sin());
    let g2 = g.mul(g);
    let a = big_a.mul(g2.conj());
    let ab = a.conj();
    let y = a.re * a.re + a.im * a.im;
    let one = Cx::real(T::one());
    let i2 = Cx::new(T::zero(), lit(2.0));
    let two_re = a.re + a.re;
    let z = Cx::zero();
    let k20 = a.mul(a).mul(ab.sub(one)).mul(g2).scale(-T::one());
    let am1 = a.sub(one);
    let rows: [[Cx<T>; 7]; 7] = [
        [a.mul(g2).scale(-y), z, z, z, z, z, z],
        [Cx::real(y * (T::one() + y)), z, z, z, z, z, z],
        [z, i2.mul(a).mul(ab.add(one)).mul(g).scale(y), z, z, z, z, z],
        [z, z, k20.mul(ab.sub(one)), k20, z, z, z],
        [
            z,
            z,
            Cx::real(-y * (y + y - two_re - two_re + lit(2.0))),
            Cx::real(-y * (two_re - y - y)),
            Cx::real(lit::<T>(4.0) * y * y),
            z,
            z,
        ],
        [z, z, z, z, z, i2.mul(a).mul(ab.sub(one)).mul(g).scale(y), z],
        [
            z,
            z,
            z,
            z,
            z,
            z,
            Cx::real(y * (am1.re * am1.re + am1.im * am1.im)),
        ],
    ];
    let mut m = DMatrix::<T>::zeros(11, 7);
    let mut b = DVector::<T>::zeros(11);
    let mut r = 0;
    for (row, &(i, j, real)) in rows.iter().zip(MATCHED.iter()) {
        for (k, v) in row.iter().enumerate() {
            m[(r, k)] = v.re;
            if !real {
                m[(r + 1, k)] = v.im;
            }
        }
        b[r] = c.c[i][j].re;
        if !real {
            b[r + 1] = c.c[i][j].im;
        }
        r += if real { 1 } else { 2 };
    }
    let scale = b.norm();
    if !positive(scale) {
        return None;
    }
    // Two small solves in turn, then the residual of all 11 equations. Rows 0–4 (c_31, c_22,
    // c_21) give λ and λe; with e known, rows 5–9 (c_20, c_11 less its λe² term, c_10) are
    // linear in λr² and λn. (One solve with λe², λen and λn² as free unknowns leaves r² and n
    // unseparated when κ is real: c_20 then holds one combination of them, and a free λe²
    // absorbs c_11.)
    let solve =
        |a: DMatrix<T>, y: DVector<T>| a.svd(true, true).solve(&y, T::default_epsilon()).ok();
    let first = solve(
        m.view((0, 0), (5, 2)).into_owned(),
        b.rows(0, 5).into_owned(),
    )?;
    let lambda = first[0];
    if !positive(lambda.abs()) {
        return None;
    }
    let e = first[1] / lambda;
    // Rows 5–9 in λr² and λn; c_10 (rows 8–9) holds λen, its column times e.
    let mut a = DMatrix::<T>::zeros(5, 2);
    let mut y = b.rows(5, 5).into_owned();
    for i in 0..5 {
        let r = 5 + i;
        a[(i, 0)] = m[(r, 2)];
        a[(i, 1)] = if r >= 8 { m[(r, 5)] * e } else { m[(r, 3)] };
    }
    y[2] -= m[(7, 4)] * lambda * e * e;
    let second = solve(a, y)?;
    let (r2, n) = (second[0] / lambda, second[1] / lambda);
    let v = [
        lambda,
        lambda * e,
        lambda * r2,
        lambda * n,
        lambda * e * e,
        lambda * e * n,
        lambda * n * n,
    ];
    let residual = (&m * DVector::from_column_slice(&v) - &b).norm() / scale;
    residual.is_finite().then_some((v, residual))
}

/// The slider-crank of a solve at `phi` in the pivot's unit frame (lengths in its units), or
/// `None` when a length is not real.
fn linkage_of<T: RealField + Copy>(big_a: Cx<T>, phi: T, v: &[T; 7]) -> Option<[T; 6]> {
    let lambda = v[0];
    if lambda == T::zero() {
        return None;
    }
    let (e, r2, n) = (v[1] / lambda, v[2] / lambda, v[3] / lambda);
    let g2 = Cx::new((phi + phi).cos(), -(phi + phi).sin());
    let kappa = big_a.mul(g2.conj()).conj();
    let y = kappa.re * kappa.re + kappa.im * kappa.im;
    let l2 = (r2 - n) / y;
    if !(positive(r2) && positive(l2)) {
        return None;
    }
    let l = l2.sqrt();
    let out = [phi, e, r2.sqrt(), l, l * kappa.re, l * kappa.im];
    out.iter().all(|x| x.is_finite()).then_some(out)
}

/// Slider-cranks whose coupler curve passes through `points`, from the curve's equation
/// (module docs): exact, to rounding, for points on a slider-crank's curve; starting points
/// for a fit otherwise.
///
/// ```
/// use linkage_core::{slider_cranks_from_curve, Circuit, SliderCircuit};
/// // 24 points on 40 % of an offset slider-crank's coupler curve.
/// let want = [0.5_f64, -0.2, 0.3, 0.25, 1.0, 2.5, 1.2, 0.6];
/// let c = SliderCircuit::placed(&want).unwrap();
/// let points: Vec<_> = (0..24).map(|k| c.point(2.5 * k as f64 / 23.0).unwrap()).collect();
/// let found = slider_cranks_from_curve(&points).unwrap();
/// assert!((found.pivot.x - 0.5).abs() < 1e-7 && (found.pivot.y + 0.2).abs() < 1e-7);
/// // The linkage itself (or the same one with the line reversed) is among the fits.
/// assert!(found.fits.iter().any(|f| {
///     let p = f.params;
///     let same = [p[4] - 1.0, p[5] - 2.5, p[6] - 1.2, p[7] - 0.6];
///     let turn = (p[2] - 0.3).rem_euclid(std::f64::consts::PI);
///     let turn = turn.min(std::f64::consts::PI - turn);
///     same.iter().all(|d| d.abs() < 1e-6) && turn < 1e-6 && (p[3].abs() - 0.25).abs() < 1e-6
/// }));
/// ```
///
/// # Errors
/// - [`Error::TooFew`] for fewer than [`SLIDER_EQUATION_POINTS`] points.
/// - [`Error::NotFinite`] for a point that is not finite.
/// - [`Error::Degenerate`] when the points are all one point, fit a family of quartics rather
///   than one (to rounding: collinear points, a few positions repeated, a circle, too short an
///   arc), or fix no quartic with a finite focus.
pub fn slider_cranks_from_curve<T: RealField + Copy>(
    points: &[Vec2<T>],
) -> Result<SliderEquation<T>, Error> {
    let (centre, rms, z) = unit_frame(points, SLIDER_EQUATION_POINTS)?;
    let degenerate = |what| Error::Degenerate { what };
    let (curve, misfit, spread) =
        fit_equation(&z, 4).ok_or(degenerate("the points fix no curve equation"))?;
    if !positive(spread - lit::<T>(4.0) * T::default_epsilon()) {
        return Err(degenerate(
            "the points fit a family of curves, not one: too few distinct points, all on a \
             line or a circle, or too short an arc",
        ));
    }
    let lead = curve.c[1][3];
    if !positive(lead.norm()) {
        return Err(degenerate("the curve's equation has no finite focus"));
    }
    let o = curve.c[0][3].div(lead).scale(-T::one());
    let n: T = lit(z.len() as f64);
    let s = (z
        .iter()
        .map(|p| {
            let d = p.sub(o);
            d.re * d.re + d.im * d.im
        })
        .fold(T::zero(), |a, b| a + b)
        / n)
        .sqrt();
    if !(o.re.is_finite() && o.im.is_finite() && positive(s) && s.is_finite()) {
        return Err(degenerate("the curve's equation has no finite focus"));
    }
    let mut c = moved(&curve, o, s);
    let norm = c.c.iter().flatten().fold(T::zero(), |m, v| m.max(v.norm()));
    if !positive(norm) {
        return Err(degenerate("the points fix no curve equation"));
    }
    c = c.scale(Cx::real(T::one() / norm));
    let mut fits = Vec::new();
    let pivot = Vec2::new(centre.x + o.re * rms, centre.y + o.im * rms);
    let unit = s * rms;
    let c22 = c.c[2][2].re;
    let ratio = if positive(c22.abs()) {
        c.c[3][1].scale(-T::one() / c22)
    } else {
        Cx::zero()
    };
    let m = ratio.norm();
    let pi = T::pi();
    if positive(m) {
        // ρ/(1 + ρ²) = m: two roots ρ, 1/ρ (one at m = ½, the most it can be; rounding may
        // pass it).
        let root = (T::one() - lit::<T>(4.0) * m * m).max(T::zero()).sqrt();
        let rhos = [(T::one() - root) / (m + m), (T::one() + root) / (m + m)];
        for (k, &rho) in rhos.iter().enumerate() {
            if k == 1 && root == T::zero() {
                break;
            }
            let big_a = ratio.scale(rho / m);
            let at = |phi: T| solve_at(&c, big_a, phi).map_or(lit(2.0), |r| r.1);
            let step = pi / lit(DIRECTIONS as f64);
            let f: Vec<T> = (0..DIRECTIONS).map(|j| at(step * lit(j as f64))).collect();
            // Local minima of the residual on the circle of directions.
            let mut minima: Vec<usize> = (0..DIRECTIONS)
                .filter(|&j| {
                    let before = f[(j + DIRECTIONS - 1) % DIRECTIONS];
                    let after = f[(j + 1) % DIRECTIONS];
                    f[j] < before && f[j] <= after
                })
                .collect();
            minima.sort_by(|&p, &q| {
                f[p].partial_cmp(&f[q])
                    .unwrap_or(core::cmp::Ordering::Equal)
            });
            for &j in minima.iter().take(MINIMA) {
                // Golden section in the samples' bracket (60 steps: to 5e-15 rad).
                let (mut lo, mut hi) = (
                    step * (lit::<T>(j as f64) - T::one()),
                    step * (lit::<T>(j as f64) + T::one()),
                );
                let g = lit::<T>(0.381_966_011_250_105_1);
                let (mut x1, mut x2) = (lo + g * (hi - lo), hi - g * (hi - lo));
                let (mut f1, mut f2) = (at(x1), at(x2));
                for _ in 0..60 {
                    if f1 < f2 {
                        hi = x2;
                        (x2, f2) = (x1, f1);
                        x1 = lo + g * (hi - lo);
                        f1 = at(x1);
                    } else {
                        lo = x1;
                        (x1, f1) = (x2, f2);
                        x2 = hi - g * (hi - lo);
                        f2 = at(x2);
                    }
                }
                let phi = if f1 < f2 { x1 } else { x2 };
                let Some((v, residual)) = solve_at(&c, big_a, phi) else {
                    continue;
                };
                let Some([angle, e, r, l, along, left]) = linkage_of(big_a, phi, &v) else {
                    continue;
                };
                fits.push(SliderEquationFit {
                    params: [
                        pivot.x,
                        pivot.y,
                        angle,
                        e * unit,
                        r * unit,
                        l * unit,
                        along * unit,
                        left * unit,
                    ],
                    residual,
                });
            }
        }
    }
    fits.sort_by(|a, b| {
        a.residual
            .partial_cmp(&b.residual)
            .unwrap_or(core::cmp::Ordering::Equal)
    });
    Ok(SliderEquation {
        fits,
        pivot,
        misfit,
        spread,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthesis::circuit::{Circuit, FootSearch};
    use crate::synthesis::slider_circuit::SliderCircuit;

    /// `n` points of the placed slider-crank `p`'s circuit from circuit parameter `from` to `to`.
    fn on_circuit(p: [f64; 8], n: usize, from: f64, to: f64) -> Vec<Vec2<f64>> {
        let c = SliderCircuit::placed(&p).unwrap();
        (0..n)
            .map(|k| {
                let s = from + (to - from) * k as f64 / (n - 1) as f64;
                c.point(s).unwrap()
            })
            .collect()
    }

    fn size(pts: &[Vec2<f64>]) -> f64 {
        pts.iter().map(|q| (q - pts[0]).norm()).fold(0.0, f64::max)
    }

    /// The least largest distance from `points` to a found linkage's curve (either reach).
    fn recovered(points: &[Vec2<f64>], closed: bool) -> f64 {
        let found = slider_cranks_from_curve(points).unwrap();
        let mut feet = vec![0.0; points.len()];
        let mut best = f64::INFINITY;
        for fit in &found.fits {
            let mut other = fit.params;
            other[2] += core::f64::consts::PI;
            other[3] = -other[3];
            for p in [fit.params, other] {
                let Ok(c) = SliderCircuit::placed(&p) else {
                    continue;
                };
                if let Some(e) = c.errors(points, 512, FootSearch::Exact, closed, &mut feet) {
                    best = best.min(e.max);
                }
            }
        }
        best
    }

    const LINKAGES: [[f64; 8]; 5] = [
        // [ox, oy, angle, offset, crank, coupler, along, left]: an offset full-turn crank, a
        // rocking crank, a centric slider, a point on the coupler line, a point far out.
        [0.5, -0.2, 0.3, 0.25, 1.0, 2.5, 1.2, 0.6],
        [-2.0, 1.0, -1.1, 1.5, 2.0, 3.0, 1.0, 0.5],
        [0.0, 0.0, 2.0, 0.0, 1.0, 3.0, 1.5, -0.8],
        [3.0, 4.0, 0.7, -0.4, 1.0, 2.0, 2.7, 0.0],
        [0.0, 0.0, 0.93, -0.12, 1.0, 2.39, 2.69, 0.49],
    ];

    #[test]
    fn closed_curves_are_recovered_to_rounding() {
        for p in LINKAGES {
            let pts = on_circuit(p, 41, 0.0, 6.0);
            let e = recovered(&pts, false);
            assert!(e < 1e-8 * size(&pts), "{p:?}: {e:e} of {:e}", size(&pts));
            // The crank pivot is the curve's focus.
            let found = slider_cranks_from_curve(&pts).unwrap();
            let off = (found.pivot - Vec2::new(p[0], p[1])).norm();
            assert!(off < 1e-9 * size(&pts), "{p:?}: pivot {off:e} off");
            assert!(found.misfit < 1e-12 && found.spread > 1e-9, "{found:?}");
        }
    }

    #[test]
    fn the_linkage_and_its_cognate_both_solve_exactly() {
        // Two roots of |κ|: the two best fits draw the curve, and they are different linkages.
        let pts = on_circuit(LINKAGES[0], 41, 0.0, 6.0);
        let found = slider_cranks_from_curve(&pts).unwrap();
        let [a, b] = [found.fits[0], found.fits[1]];
        assert!(a.residual < 1e-10 && b.residual < 1e-10, "{found:?}");
        assert!((a.params[4] - b.params[4]).abs() > 1e-3, "{a:?} {b:?}");
    }

    #[test]
    fn open_arcs_at_any_scale_are_recovered() {
        for p in LINKAGES {
            for scale in [1e-3, 1.0, 1e4] {
                let mut q = p;
                for (k, v) in q.iter_mut().enumerate() {
                    *v = match k {
                        0 | 1 => *v * scale - 2.5 * scale,
                        2 => *v,
                        _ => *v * scale,
                    };
                }
                // 40 % of the circuit, 24 points.
                let pts = on_circuit(q, 24, 0.5, 0.5 + 0.4 * core::f64::consts::TAU);
                let e = recovered(&pts, false);
                assert!(e < 2e-5 * size(&pts), "{q:?}: {e:e} of {:e}", size(&pts));
            }
        }
    }

    #[test]
    fn extreme_scales_are_the_same_problem() {
        let pts = on_circuit(LINKAGES[0], 30, 0.0, 6.0);
        let base = slider_cranks_from_curve(&pts).expect("unit scale");
        for k in [1e300, 1e-300] {
            let far: Vec<_> = pts.iter().map(|p| p * k).collect();
            let got = slider_cranks_from_curve(&far).expect("a scaled curve");
            assert_eq!(got.fits.len(), base.fits.len(), "{k:e}");
            for b in &base.fits {
                let same = |a: &SliderEquationFit<f64>| {
                    let off = a
                        .params
                        .iter()
                        .zip(b.params)
                        .enumerate()
                        .map(|(i, (x, y))| {
                            // The angle is not scaled.
                            if i == 2 {
                                (x - y).abs()
                            } else {
                                (x / k - y).abs()
                            }
                        });
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
    fn single_precision_finds_the_linkage_approximately() {
        let p64 = LINKAGES[0];
        let p: [f32; 8] = core::array::from_fn(|k| p64[k] as f32);
        let c = SliderCircuit::placed(&p).unwrap();
        let pts: Vec<_> = (0..40)
            .map(|k| c.point(0.157 * k as f32).unwrap())
            .collect();
        let found = slider_cranks_from_curve(&pts).unwrap();
        // The lengths (crank, coupler, along, left) of the best fit, against the linkage's.
        let off = |f: &SliderEquationFit<f32>| {
            [4, 5, 6, 7]
                .iter()
                .map(|&k| (f.params[k] - p[k]).abs())
                .fold(0.0, f32::max)
        };
        let best = found.fits.iter().map(off).fold(f32::INFINITY, f32::min);
        assert!(best < 5e-2, "{best}");
    }

    #[test]
    fn bad_points_are_errors() {
        let one = vec![Vec2::new(1.0, 2.0); 20];
        let few = slider_cranks_from_curve(&one[..12]);
        let want = Error::TooFew {
            what: "points on the curve",
            needed: 13,
            got: 12,
        };
        assert_eq!(few, Err(want), "12 points");
        let same = slider_cranks_from_curve(&one);
        assert!(matches!(same, Err(Error::Degenerate { .. })), "{same:?}");
        let mut nan = on_circuit(LINKAGES[0], 20, 0.0, 6.0);
        nan[3].x = f64::INFINITY;
        let got = slider_cranks_from_curve(&nan);
        assert!(matches!(got, Err(Error::NotFinite { .. })), "{got:?}");
        // Points that fit a family of curves: collinear, a few positions repeated, a circle.
        let line: Vec<_> = (0..20)
            .map(|k| Vec2::new(k as f64, 2.0 * k as f64))
            .collect();
        let two: Vec<_> = (0..20).map(|k| Vec2::new((k % 2) as f64, 0.0)).collect();
        let circle: Vec<_> = (0..20)
            .map(|k| {
                let a = 0.3 * k as f64;
                Vec2::new(1.0 + 2.0 * a.cos(), 2.0 * a.sin())
            })
            .collect();
        for (what, pts) in [
            ("collinear", line),
            ("two positions", two),
            ("circle", circle),
        ] {
            let got = slider_cranks_from_curve(&pts);
            assert!(
                matches!(got, Err(Error::Degenerate { .. })),
                "{what}: {got:?}"
            );
        }
    }
}
