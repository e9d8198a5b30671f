//! A slider-crank's coupler curve as one smooth closed circuit, for path synthesis: the
//! [`Circuit`] of a [`SliderCrank`], placed slider-cranks measured many at once, and atlas
//! entries placed in a target's frame.
//!
//! # The circuit parameter
//! As for four-bars ([`CircuitPath`](crate::CircuitPath)): a crank that turns fully sweeps
//! `θ = γ + s` (`γ` the line's direction) on the declared reach; a crank limited to
//! `[lo, hi]` (for two intervals, the first, [`SliderCrank::input_range`]) sweeps
//! `θ = (lo + hi)/2 − (hi − lo)/2·cos s`, from `lo` to `hi` on the declared reach
//! (`0 ≤ s ≤ π`) and back on the other. At a limit the rod is perpendicular to the line and
//! the half chord `√(l² − d²)` vanishes like `√(θ − θ_lim)`, i.e. like `|s|`: with the reach's
//! sign it is a smooth function of `s` through the limits.
//!
//! # Near the limits
//! Near a limit `λ` (where `d = ±l`) the factor `l ∓ d` of `l² − d²` is formed as
//! `±r (sin λ − sin φ) = ±2r cos((λ + φ)/2) sin((λ − φ)/2)`, with `φ − lo = 2w sin²(s/2)` and
//! `hi − φ = 2w cos²(s/2)` (`w` the half width): no cancellation, so the half chord keeps its
//! relative accuracy down to the limit (formed from `d` directly it would keep only `√ε` of the
//! linkage's size there, and finite differences of the residuals would be noise).
//!
//! # Placed slider-cranks
//! A synthesis candidate is [`SLIDER_PARAMS`] numbers
//! `[ox, oy, angle, offset, crank, coupler, along, left]` on [`Reach::Ahead`]
//! ([`SliderCircuit::placed`]): the other reach is the same linkage with `angle + π` and
//! `−offset` (see [`SliderCrank`]), so one reach covers every slider-crank and no flag is
//! needed.

use nalgebra::RealField;

use crate::constructions::slider::Reach;
use crate::error::Error;
use crate::linkages::slider_crank::{Limits, RelativeRange, SliderCrank, SliderCrankPose};
use crate::mechanism::program::Mechanism;
use crate::numeric::scalar::{lit, Vec2};
use crate::synthesis::circuit::{
    errors_of, residuals_of, similarity, Circuit, FootSearch, PathError,
};
use crate::synthesis::efd::Normalisation;

/// Numbers of a placed slider-crank: `[ox, oy, angle, offset, crank, coupler, along, left]`.
pub const SLIDER_PARAMS: usize = 8;

/// A slider-crank's circuit, parametrised as in the module.
///
/// ```
/// use linkage_core::{Circuit, FootSearch, InputRange, Reach, SliderCircuit, SliderCrank, Vec2};
/// // Crank 2, rod 3, line 1.5 above O: |e| + r > l, the crank rocks.
/// let sc = SliderCrank::new(Vec2::zeros(), 0.0_f64, 1.5, 2.0, 3.0, (1.0, 0.5), Reach::Ahead)?;
/// let c = SliderCircuit::new(sc)?;
/// assert!(!c.full_turn());
/// c.check(256)?; // the tracker follows the circuit through both limits
/// // The circuit is the linkage's curve on the declared reach for 0 ≤ s ≤ π.
/// let (theta, other) = c.theta(1.0);
/// assert!(!other && (c.point(1.0).unwrap() - sc.pose(theta).unwrap().coupler_point).norm() < 1e-12);
/// // Points of the curve are at distance 0 from it.
/// let on = [c.point(0.5).unwrap(), c.point(4.0).unwrap()];
/// let mut feet = [0.0; 2];
/// assert!(c.errors(&on, 256, FootSearch::Exact, false, &mut feet).unwrap().max < 1e-9);
/// # Ok::<(), linkage_core::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderCircuit<T> {
    /// The linkage on its declared reach.
    pub linkage: SliderCrank<T>,
    /// `Some((lo, hi))` (absolute crank angles) for a limited crank, `None` for a full turn.
    pub limits: Option<(T, T)>,
    relative: Option<Limits<T>>,
}

impl<T: RealField + Copy> SliderCircuit<T> {
    /// The circuit of `linkage`.
    ///
    /// # Errors
    /// [`Error::CannotAssemble`] (joint 3, the slider) when the linkage never assembles.
    pub fn new(linkage: SliderCrank<T>) -> Result<Self, Error> {
        let relative = match linkage.relative_range() {
            RelativeRange::Never => {
                // The rod cannot reach the line from any crank position: |e| − r > l.
                let gap = linkage.offset.abs() - linkage.crank - linkage.coupler;
                return Err(Error::CannotAssemble {
                    joint: SliderCrank::<T>::B,
                    gap: crate::numeric::scalar::to_f64(gap),
                });
            }
            RelativeRange::Full => None,
            RelativeRange::One(lim) | RelativeRange::Two(lim, _) => Some(lim),
        };
        Ok(SliderCircuit {
            linkage,
            limits: relative.map(|lim| (linkage.angle + lim.lo, linkage.angle + lim.hi)),
            relative,
        })
    }

    /// The circuit of the placed slider-crank `p = [ox, oy, angle, offset, crank, coupler,
    /// along, left]` on [`Reach::Ahead`].
    ///
    /// # Errors
    /// [`Error::BufferLength`] unless `p` holds [`SLIDER_PARAMS`] numbers; the errors of
    /// [`SliderCrank::new`] and [`SliderCircuit::new`].
    pub fn placed(p: &[T]) -> Result<Self, Error> {
        let &[ox, oy, angle, offset, crank, coupler, along, left] = p else {
            return Err(Error::BufferLength {
                what: "placed slider-crank parameters",
                expected: SLIDER_PARAMS,
                got: p.len(),
            });
        };
        let sc = SliderCrank::new(
            Vec2::new(ox, oy),
            angle,
            offset,
            crank,
            coupler,
            (along, left),
            Reach::Ahead,
        )?;
        SliderCircuit::new(sc)
    }

    /// The circuit in `theta.len()` samples at `s = 2πk/(n − 1)` (the last repeats the
    /// first): crank angles into `theta`, joints `O, G, A, B, P` into `joints` (`5·n`) and the
    /// assembly margin `sin μ` (see [`SliderCrankPose::transmission`]) into `margin` (`n`);
    /// NaN joints and margin where a sample does not assemble. Returns how many assembled.
    ///
    /// ```
    /// use linkage_core::{Reach, SliderCircuit, SliderCrank, Vec2};
    /// let sc = SliderCrank::new(Vec2::zeros(), 0.0_f64, 0.0, 1.0, 3.0, (1.0, 0.5), Reach::Ahead);
    /// let c = SliderCircuit::new(sc.unwrap()).unwrap();
    /// let (mut th, mut joints, mut margin) = ([0.0; 9], [Vec2::zeros(); 45], [0.0; 9]);
    /// assert_eq!(c.sample(&mut th, &mut joints, &mut margin), Ok(9));
    /// // The rod (length 3) at every sample; sin μ = |half chord|/rod: 1 with the crank along
    /// // the line (θ = 0), √8/3 with it across (θ = 90°).
    /// let rod = |k: usize| (joints[5 * k + 3] - joints[5 * k + 2]).norm();
    /// assert!((0..9).all(|k| (rod(k) - 3.0).abs() < 1e-12), "rod lengths");
    /// assert!((margin[0] - 1.0).abs() < 1e-12, "crank at 0: {}", margin[0]);
    /// assert!((th[2] - core::f64::consts::FRAC_PI_2).abs() < 1e-12, "θ = {}", th[2]);
    /// assert!((margin[2] - 8f64.sqrt() / 3.0).abs() < 1e-12, "crank at 90°: {}", margin[2]);
    /// ```
    ///
    /// # Errors
    /// [`Error::BufferLength`] for mismatched slices or fewer than two samples.
    pub fn sample(
        &self,
        theta: &mut [T],
        joints: &mut [Vec2<T>],
        margin: &mut [T],
    ) -> Result<usize, Error> {
        let n = theta.len();
        let n5 = n.checked_mul(5).ok_or(Error::CountOverflow {
            what: "circuit samples",
        })?;
        for (what, expected, got) in [
            ("theta (at least two samples)", n.max(2), n),
            ("joints", n5, joints.len()),
            ("margin", n, margin.len()),
        ] {
            if got != expected {
                return Err(Error::BufferLength {
                    what,
                    expected,
                    got,
                });
            }
        }
        let (o, g) = (self.linkage.o, self.linkage.line_point());
        let nan = crate::numeric::scalar::nan::<T>();
        let last = lit::<T>((n - 1) as f64);
        let mut ok = 0;
        for k in 0..n {
            let s = T::two_pi() * lit::<T>(k as f64) / last;
            theta[k] = self.theta(s).0;
            let row = &mut joints[5 * k..5 * k + 5];
            match self.pose(s) {
                Some(p) => {
                    row.copy_from_slice(&[o, g, p.a, p.b, p.coupler_point]);
                    margin[k] = p.transmission.sin();
                    ok += 1;
                }
                None => {
                    row.fill(Vec2::new(nan, nan));
                    margin[k] = nan;
                }
            }
        }
        Ok(ok)
    }

    /// The pose at circuit parameter `s` (see the module); `None` where the rod does not
    /// reach the line (rounding of a full turn near a change point).
    pub fn pose(&self, s: T) -> Option<SliderCrankPose<T>> {
        let sc = &self.linkage;
        let (r, l) = (sc.crank, sc.coupler);
        let Some(lim) = self.relative else {
            return sc.pose_from_line(s);
        };
        let two = lit::<T>(2.0);
        let w = (lim.hi - lim.lo) / two;
        let (ss, cs) = s.sin_cos();
        let phi = (lim.lo + lim.hi) / two - w * cs;
        // The nearer limit λ, the gap |λ − φ| (cancellation-free) and whether d = +l there.
        let (lambda, gap, above, toward) = if cs >= T::zero() {
            let h = (s / two).sin();
            (lim.lo, two * w * h * h, lim.above.0, -T::one())
        } else {
            let h = (s / two).cos();
            (lim.hi, two * w * h * h, lim.above.1, T::one())
        };
        // sin λ − sin φ = 2 cos((λ + φ)/2) sin((λ − φ)/2), λ − φ = toward·gap.
        let mean = lambda - toward * gap / two;
        let diff = two * mean.cos() * (toward * gap / two).sin();
        let sign = if above { T::one() } else { -T::one() };
        let small = (sign * r * diff).max(T::zero());
        let other = (two * l - small).max(T::zero());
        let half = small.sqrt() * other.sqrt();
        let branch = if ss < T::zero() { -T::one() } else { T::one() };
        let d = r * phi.sin() - sc.offset;
        Some(sc.place(phi, branch * sc.reach.sign::<T>() * half, d))
    }
}

impl<T: RealField + Copy> Circuit<T> for SliderCircuit<T> {
    fn poser(&self) -> impl Fn(T) -> Option<Vec2<T>> + '_ {
        move |s| self.pose(s).map(|p| p.coupler_point)
    }

    fn theta(&self, s: T) -> (T, bool) {
        match self.relative {
            None => (self.linkage.angle + s, false),
            Some(lim) => {
                let half = lit::<T>(0.5);
                let phi = (lim.lo + lim.hi) * half - (lim.hi - lim.lo) * half * s.cos();
                (self.linkage.angle + phi, s.sin() < T::zero())
            }
        }
    }

    fn transmission(&self, s: T) -> Option<T> {
        self.pose(s).map(|p| p.transmission)
    }

    fn full_turn(&self) -> bool {
        self.relative.is_none()
    }

    fn size(&self) -> T {
        let f = &self.linkage;
        f.crank
            .max(f.coupler)
            .max(f.offset.abs())
            .max(f.along.abs())
            .max(f.left.abs())
    }

    fn program(&self) -> Mechanism<T, 5> {
        self.linkage.mechanism()
    }
}

/// Places a slider-crank atlas entry in a target's frame: the entry's linkage (crank pivot
/// `(0, 0)`, crank 1, line along `+x`; `entry` its `[coupler, offset, along, left]`) moved by
/// the similarity that takes its curve's normalisation frame `curve` onto the target's
/// `target`, as [`place_entry`](crate::place_entry) does for four-bars. Returns the
/// [`SLIDER_PARAMS`] numbers of [`SliderCircuit::placed`].
///
/// ```
/// use linkage_core::{place_slider_entry, Normalisation, Vec2};
/// let frame = |cx, cy, scale, rotation| Normalisation { centre: Vec2::new(cx, cy), scale, rotation, start: 0.0 };
/// // Twice as large, a quarter turn, the curve's centre (0, 0) onto (5, 0).
/// let (curve, target) = (frame(0.0, 0.0, 1.0, 0.0), frame(5.0, 0.0, 2.0, std::f64::consts::FRAC_PI_2));
/// let p = place_slider_entry(&[3.0, 0.5, 1.0, -0.25], &curve, &target, false);
/// let want = [5.0, 0.0, std::f64::consts::FRAC_PI_2, 1.0, 2.0, 6.0, 2.0, -0.5];
/// assert!(p.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-15));
/// ```
#[doc(hidden)]
pub fn place_slider_entry<T: RealField + Copy>(
    entry: &[T; 4],
    curve: &Normalisation<T>,
    target: &Normalisation<T>,
    flip: bool,
) -> [T; SLIDER_PARAMS] {
    let (k, turn, moved) = similarity(curve, target, flip);
    let o = moved(Vec2::zeros());
    let [coupler, offset, along, left] = *entry;
    [
        o.x,
        o.y,
        turn,
        k * offset,
        k,
        k * coupler,
        k * along,
        k * left,
    ]
}

/// Rows of placed slider-cranks in `params`.
fn slider_rows(params: &[f64]) -> Result<usize, Error> {
    if !params.len().is_multiple_of(SLIDER_PARAMS) {
        return Err(Error::BufferLength {
            what: "placed slider-crank parameters",
            expected: params.len().next_multiple_of(SLIDER_PARAMS),
            got: params.len(),
        });
    }
    Ok(params.len() / SLIDER_PARAMS)
}

/// The circuit of row `i` of `params`, `None` where it cannot be built.
fn row(params: &[f64], i: usize) -> Option<SliderCircuit<f64>> {
    SliderCircuit::placed(&params[SLIDER_PARAMS * i..SLIDER_PARAMS * (i + 1)]).ok()
}

/// [`Circuit::errors`] of `M` placed slider-cranks (`params` rows of [`SLIDER_PARAMS`])
/// against the same targets, on `threads` threads (the same bits for any count), as
/// [`path_errors`](crate::path_errors) does for four-bars: `errors[i]` (NaN for a linkage that
/// cannot be built or whose circuit does not assemble throughout) and
/// `feet[i·n .. (i+1)·n]`.
///
/// ```
/// use linkage_core::{slider_path_errors, Circuit, FootSearch, PathError, SliderCircuit};
/// let p = [0.0, 0.0, 0.3, 0.5, 1.0, 3.0, 1.5, 0.4];
/// let c = SliderCircuit::placed(&p).unwrap();
/// let targets = [c.point(0.5).unwrap(), c.point(2.5).unwrap(), c.point(5.0).unwrap()];
/// let (mut errors, mut feet) = ([PathError::nan(); 1], [0.0; 3]);
/// slider_path_errors(&p, &targets, 256, FootSearch::Exact, true, 1, &mut errors, &mut feet).unwrap();
/// assert!(errors[0].max < 1e-9);
/// ```
///
/// # Errors
/// [`Error::BufferLength`] for buffers of the wrong length (`params` not whole rows), fewer
/// than two targets or fewer than 8 samples; [`Error::CountOverflow`] when `M·n` overflows
/// `usize`.
///
/// # Panics
/// As [`Circuit::polyline`] of `samples` points.
#[allow(
    clippy::too_many_arguments,
    reason = "the batch's inputs, its two outputs and the search settings, as path_errors"
)]
pub fn slider_path_errors(
    params: &[f64],
    targets: &[Vec2<f64>],
    samples: usize,
    search: FootSearch,
    closed: bool,
    threads: usize,
    errors: &mut [PathError<f64>],
    feet: &mut [f64],
) -> Result<(), Error> {
    let m = slider_rows(params)?;
    let settings = (samples, search, closed, threads);
    errors_of(m, |i| row(params, i), targets, settings, errors, feet)
}

/// [`Circuit::residuals`] of `M` placed slider-cranks (as [`slider_path_errors`]) at circuit
/// parameters `s[i·n .. (i+1)·n]`: `out[i·n + j] = P_i(s_ij) − target_j`, NaN where a linkage
/// or a sample does not assemble.
///
/// # Errors
/// [`Error::BufferLength`] for buffers of the wrong length; [`Error::CountOverflow`] when
/// `M·n` overflows `usize`.
pub fn slider_path_residuals(
    params: &[f64],
    targets: &[Vec2<f64>],
    s: &[f64],
    out: &mut [Vec2<f64>],
) -> Result<(), Error> {
    let m = slider_rows(params)?;
    residuals_of(m, |i| row(params, i), targets, s, out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linkages::fourbar::InputRange;

    fn sc(e: f64, r: f64, l: f64) -> SliderCrank<f64> {
        SliderCrank::new(
            Vec2::new(0.5, -1.0),
            0.7,
            e,
            r,
            l,
            (0.6 * l, -0.3 * l),
            Reach::Ahead,
        )
        .unwrap()
    }

    /// The circuit's points are the linkage's poses at its crank angles, on the declared reach
    /// for `0 ≤ s ≤ π` and on the other back; and the tracker follows it.
    #[test]
    fn the_circuit_is_the_linkage_on_both_reaches() {
        for &(e, r, l) in &[
            (0.3, 1.0, 2.0),
            (1.5, 1.0, 1.0),
            (-1.5, 1.0, 1.0),
            (0.2, 3.0, 1.0),
        ] {
            let s = sc(e, r, l);
            let c = SliderCircuit::new(s).unwrap();
            c.check(512).unwrap();
            let other = SliderCrank {
                reach: Reach::Behind,
                ..s
            };
            for k in 0..200 {
                let t = k as f64 * 0.0314;
                let (theta, flipped) = c.theta(t);
                let want = if flipped { other } else { s }.pose(theta);
                let got = c.point(t).unwrap();
                // Near a limit the direct form keeps √ε of the size.
                let tol = 1e-7 * c.size();
                assert!(
                    (want.unwrap().coupler_point - got).norm() < tol,
                    "{e} {r} {l} {t}"
                );
            }
        }
    }

    /// Through a limit the rod keeps its length to rounding and the curve is smooth in `s`:
    /// one-sided difference quotients on either side of `s = 0` and `s = π` agree.
    #[test]
    fn the_circuit_is_smooth_and_exact_through_its_limits() {
        let c = SliderCircuit::new(sc(0.4, 2.0, 1.5)).unwrap();
        let range = c.linkage.input_range();
        assert!(
            matches!(range, InputRange::TwoIntervals { .. }),
            "offset 0.4, crank 2, rod 1.5: {range:?}"
        );
        for limit in [0.0, core::f64::consts::PI] {
            for k in 1..12 {
                let ds = 10f64.powi(-k);
                for s in [limit - ds, limit + ds] {
                    let p = c.pose(s).unwrap();
                    let rod = (p.b - p.a).norm();
                    assert!((rod - 1.5).abs() < 4e-16 * 2.0, "s {s}: rod {rod}");
                }
            }
            let h = 1e-5;
            let q = |s: f64| c.point(s).unwrap();
            let left = (q(limit) - q(limit - h)) / h;
            let right = (q(limit + h) - q(limit)) / h;
            assert!(
                (left - right).norm() < 1e-3 * left.norm(),
                "{limit}: {left} {right}"
            );
        }
    }

    #[test]
    fn placed_rows_are_checked() {
        let mut out = [Vec2::zeros(); 2];
        let t = [Vec2::zeros(); 2];
        let p = [0.0; 9];
        let got = slider_path_residuals(&p, &t, &[0.0; 2], &mut out);
        assert!(
            matches!(
                got,
                Err(Error::BufferLength {
                    expected: 16,
                    got: 9,
                    ..
                })
            ),
            "9 parameters: {got:?}"
        );
        // A row that cannot be built (crank 0) gives NaN residuals, not an error.
        let p = [0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0];
        slider_path_residuals(&p, &t, &[0.0; 2], &mut out).unwrap();
        assert!(
            out.iter().all(|r| r.x.is_nan()),
            "residuals of a row with crank 0: {out:?}"
        );
    }
}
