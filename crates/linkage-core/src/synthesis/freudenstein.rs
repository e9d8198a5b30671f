//! Function generation by Freudenstein's equation: a four-bar whose output angle follows a
//! prescribed function of its input angle at precision points.
//!
//! # The equation (F. Freudenstein, "Approximate synthesis of four-bar linkages", Trans. ASME
//! 77, 1955; as in Norton, *Design of Machinery*, and Uicker, Pennock & Shigley, *Theory of
//! Machines and Mechanisms*)
//! For ground `d` from the input pivot `O = (0, 0)` to the output pivot `C = (d, 0)`, input link
//! `a` at angle `φ`, coupler `b`, output link `c` at angle `ψ` (both from the ground line), the
//! loop `a e^{iφ} + b e^{iθ} = d + c e^{iψ}` squared gives
//!
//! ```text
//! K1 cos ψ − K2 cos φ + K3 = cos(φ − ψ),   K1 = d/a,  K2 = d/c,  K3 = (a² − b² + c² + d²)/(2ac),
//! ```
//!
//! linear in `K1, K2, K3` (Norton's labelling; Freudenstein's paper and other texts arrange the
//! angles and signs differently — this form is the one derived above, and the tests check it
//! against the loop of a known linkage). Three precision points `(φ_j, ψ_j)` give a 3×3 linear system; more
//! give a linear least-squares problem (solved here by Givens rotations, row by row, with no
//! heap). Back from the `K`s: `a = d/K1`, `c = d/K2`, `b² = a² + c² + d² − 2ac·K3`. A negative
//! `a` (or `c`) is a link of length `|a|` turned by `π`: the generator records that offset.
//!
//! Degenerate cases: two equal precision points of three ([`Error::CoincidentPositions`]); a
//! singular system ([`Error::Degenerate`]: e.g. all input angles equal, or fewer than three
//! distinct points); `K1` or `K2` zero (a link of infinite length, [`Error::Degenerate`]);
//! `b² ≤ 0` (no real coupler, [`Error::NoSolution`]).

use nalgebra::RealField;

use crate::error::{check_finite, check_length, Error};
use crate::linkages::fourbar::min_transmission_angle;
use crate::linkages::fourbar::{Assembly, FourBar, GrashofClass, InputRange};
use crate::numeric::scalar::{eps, lit, nan, Vec2};
use crate::sweep::tracker::{Rates, Tracker};
use crate::synthesis::burmester::{is_nan, turns, wrap, Defect};

/// The `j`-th of `n` Chebyshev precision points on `[x0, x1]` (`j = 0 … n−1`, increasing):
/// `x_j = (x0 + x1)/2 − (x1 − x0)/2 · cos((2j + 1)π / 2n)`, the zeros of the degree-`n`
/// Chebyshev polynomial mapped to the interval, which spread the structural error most evenly
/// (Freudenstein 1955; Norton, *Design of Machinery*, "Chebyshev spacing"). NaN for `j ≥ n`.
///
/// ```
/// use linkage_core::chebyshev_spacing;
/// let x = chebyshev_spacing(0.0_f64, 1.0, 3, 0);
/// assert!((x - (0.5 - 0.75_f64.sqrt() / 2.0)).abs() < 1e-15);
/// ```
pub fn chebyshev_spacing<T: RealField + Copy>(x0: T, x1: T, n: usize, j: usize) -> T {
    if j >= n {
        return nan();
    }
    let half = lit::<T>(0.5);
    // π(2j + 1)/2n as π(j + ½)/n: the same bits (halving is exact), and no `usize` overflow.
    let angle = T::pi() * (lit::<T>(j as f64) + lit::<T>(0.5)) / lit::<T>(n as f64);
    (x0 + x1) * half - (x1 - x0) * half * angle.cos()
}

/// The coefficients of Freudenstein's equation (see the module notes).
///
/// ```
/// use linkage_core::{Assembly, Error, Freudenstein, FourBar};
/// let (d, a, b, c) = (1.0_f64, 0.45, 1.1, 0.8);
/// let k = Freudenstein::of_lengths(d, a, b, c).unwrap();
/// assert_eq!((k.k1, k.k2), (d / a, d / c));
/// // The equation holds along the linkage's motion, and three points of it give K back.
/// let fb = FourBar::new(d, a, b, c, (0.0, 0.0), Assembly::Open).unwrap();
/// let output = |phi: f64| {
///     let r = fb.pose(phi).unwrap().b - fb.c;
///     r.y.atan2(r.x)
/// };
/// let phi = [0.6, 1.2, 2.0];
/// let psi = phi.map(output);
/// assert!(phi.iter().zip(&psi).all(|(&f, &s)| k.residual(f, s).abs() < 1e-14));
/// assert!((Freudenstein::fit(&phi, &psi).unwrap().k3 - k.k3).abs() < 1e-12);
/// // One input angle three times does not determine the coefficients.
/// let same_input = Freudenstein::fit(&[1.0; 3], &[0.5, 0.6, 0.7]);
/// assert!(matches!(same_input, Err(Error::Degenerate { .. })));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Freudenstein<T> {
    /// `K1 = d/a` (input link `a`).
    pub k1: T,
    /// `K2 = d/c` (output link `c`).
    pub k2: T,
    /// `K3 = (a² − b² + c² + d²)/(2ac)`.
    pub k3: T,
}

impl<T: RealField + Copy> Freudenstein<T> {
    /// The coefficients of a four-bar with these lengths.
    ///
    /// # Errors
    /// [`Error::InvalidLength`] for a length that is not positive and finite.
    pub fn of_lengths(ground: T, crank: T, coupler: T, rocker: T) -> Result<Self, Error> {
        let d = check_length("ground", ground)?;
        let a = check_length("crank", crank)?;
        let b = check_length("coupler", coupler)?;
        let c = check_length("rocker", rocker)?;
        Ok(Freudenstein {
            k1: d / a,
            k2: d / c,
            k3: (a * a - b * b + c * c + d * d) / (lit::<T>(2.0) * a * c),
        })
    }

    /// `K1 cos ψ − K2 cos φ + K3 − cos(φ − ψ)`: zero where the linkage meets `(φ, ψ)`.
    pub fn residual(&self, phi: T, psi: T) -> T {
        self.k1 * psi.cos() - self.k2 * phi.cos() + self.k3 - (phi - psi).cos()
    }

    /// The coefficients through precision points `(phi[j], psi[j])`: exact for three, least
    /// squares on the residuals for more.
    ///
    /// # Errors
    /// [`Error::TooFew`] for fewer than 3 points; [`Error::BufferLength`] when `psi` is not as
    /// long as `phi`; [`Error::NotFinite`]; [`Error::CoincidentPositions`] for two equal points
    /// of three (of more, a repeated point weighs twice in the least squares: O(m) time);
    /// [`Error::Degenerate`] when the points do not determine the three coefficients.
    pub fn fit(phi: &[T], psi: &[T]) -> Result<Self, Error> {
        let m = phi.len();
        if psi.len() != m {
            return Err(Error::BufferLength {
                what: "output angles",
                expected: m,
                got: psi.len(),
            });
        }
        if m < 3 {
            return Err(Error::TooFew {
                what: "precision points",
                needed: 3,
                got: m,
            });
        }
        for (&f, &s) in phi.iter().zip(psi) {
            check_finite("input angle", f)?;
            check_finite("output angle", s)?;
        }
        // Three points are an exact solve, which one repeated point makes singular: name the
        // pair. More are a least-squares fit, in which a repeated point only weighs twice (and
        // a pairwise search would cost O(m²)); too few distinct points fail the rank test below.
        let tol = lit::<T>(64.0) * eps::<T>();
        if m == 3 {
            for i in 0..m {
                for j in i + 1..m {
                    if wrap(phi[i] - phi[j]).abs() <= tol && wrap(psi[i] - psi[j]).abs() <= tol {
                        return Err(Error::CoincidentPositions {
                            first: i,
                            second: j,
                        });
                    }
                }
            }
        }
        // Givens QR, one row at a time: r (upper triangular) and qb = Qᵀ·rhs.
        let mut r = [[T::zero(); 3]; 3];
        let mut qb = [T::zero(); 3];
        for (&f, &s) in phi.iter().zip(psi) {
            let mut row = [s.cos(), -f.cos(), T::one()];
            let mut rhs = (f - s).cos();
            for k in 0..3 {
                let (x, y) = (r[k][k], row[k]);
                if y == T::zero() {
                    continue;
                }
                let h = x.hypot(y);
                let (c, sn) = (x / h, y / h);
                for col in k..3 {
                    let (u, v) = (r[k][col], row[col]);
                    r[k][col] = c * u + sn * v;
                    row[col] = c * v - sn * u;
                }
                let (u, v) = (qb[k], rhs);
                qb[k] = c * u + sn * v;
                rhs = c * v - sn * u;
            }
        }
        // Columns have norms up to √m; a pivot below 1e3·ε·√m of that is rank loss.
        let small = lit::<T>(1024.0) * eps::<T>() * lit::<T>(m as f64).sqrt();
        if (0..3).any(|k| r[k][k].abs() <= small || is_nan(r[k][k].abs())) {
            return Err(Error::Degenerate {
                what: "the precision points do not determine K1, K2, K3 (the linear system is \
                       singular, e.g. all input or all output angles equal)",
            });
        }
        let mut k = [T::zero(); 3];
        for i in (0..3).rev() {
            let mut s = qb[i];
            for col in i + 1..3 {
                s -= r[i][col] * k[col];
            }
            k[i] = s / r[i][i];
        }
        Ok(Freudenstein {
            k1: k[0],
            k2: k[1],
            k3: k[2],
        })
    }
}

/// A four-bar function generator: input angle `φ` drives the crank at `φ + input_offset`, and
/// the output angle is the rocker's angle minus `output_offset` (both from the ground line
/// `O → C`, with `O = (0, 0)` and `C = (ground, 0)`).
///
/// ```
/// use linkage_core::{Assembly, Error, FourBar, FunctionGenerator};
/// // The function a known linkage generates, at three precision points, gives that linkage back.
/// let fb = FourBar::new(1.0_f64, 0.45, 1.1, 0.8, (0.0, 0.0), Assembly::Open).unwrap();
/// let output = |phi: f64| {
///     let r = fb.pose(phi).unwrap().b - fb.c;
///     r.y.atan2(r.x)
/// };
/// let phi = [0.6, 1.2, 2.0];
/// let psi = phi.map(output);
/// let gen = FunctionGenerator::synthesise(&phi, &psi, 1.0).unwrap();
/// assert!((gen.four_bar.crank - 0.45).abs() < 1e-12 && (gen.four_bar.rocker - 0.8).abs() < 1e-12);
/// assert!((gen.output(1.5).unwrap() - output(1.5)).abs() < 1e-12);
/// // Two precision points are too few.
/// assert_eq!(
///     FunctionGenerator::synthesise(&phi[..2], &psi[..2], 1.0).err(),
///     Some(Error::TooFew { what: "precision points", needed: 3, got: 2 })
/// );
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FunctionGenerator<T> {
    /// The linkage (its coupler point is the crank pin `A`; the function does not use it).
    pub four_bar: FourBar<T>,
    /// The equation's coefficients.
    pub freudenstein: Freudenstein<T>,
    /// `0`, or `π` when `K1 < 0` (the input link points opposite to `φ`).
    pub input_offset: T,
    /// `0`, or `π` when `K2 < 0`.
    pub output_offset: T,
}

/// What sweeping a function generator over its input interval found.
///
/// ```
/// use linkage_core::{Assembly, FourBar, FunctionGenerator, GrashofClass};
/// let fb = FourBar::new(1.0_f64, 0.45, 1.1, 0.8, (0.0, 0.0), Assembly::Open).unwrap();
/// let output = |phi: f64| {
///     let r = fb.pose(phi).unwrap().b - fb.c;
///     r.y.atan2(r.x)
/// };
/// let phi = [0.6, 1.2, 2.0];
/// let psi = phi.map(output);
/// let gen = FunctionGenerator::synthesise(&phi, &psi, 1.0).unwrap();
/// // Swept over 0.5 ≤ φ ≤ 2.2: every precision point met, no toggle on the way.
/// let sweep: Vec<f64> = (0..=34).map(|i| 0.5 + 0.05 * i as f64).collect();
/// let mut out = vec![0.0; sweep.len()];
/// let check = gen.sweep(&sweep, &mut out, &phi, &psi).unwrap();
/// assert_eq!((check.defect, check.grashof), (None, GrashofClass::CrankRocker));
/// assert!(check.precision_error < 1e-12 && check.min_transmission > 0.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FunctionCheck<T> {
    /// `None` when every precision point is met on the linkage's assembly and the whole input
    /// interval is swept on it without toggle or flat position; else the first defect found.
    pub defect: Option<Defect>,
    /// Largest `|ψ(φ_j) − ψ_j|` at the precision points (radians; rounding for exact synthesis,
    /// the fit's residual for least squares).
    pub precision_error: T,
    /// Smallest transmission angle over the sweep, folded to `[0, π/2]`.
    pub min_transmission: T,
    /// Grashof class of the linkage.
    pub grashof: GrashofClass,
}

impl<T: RealField + Copy> FunctionGenerator<T> {
    /// The linkage of coefficients `k` with ground length `ground`, on the assembly whose
    /// output at input `phi_ref` is nearer `psi_ref`.
    ///
    /// # Errors
    /// [`Error::InvalidLength`] for a bad ground; [`Error::Degenerate`] when `K1` or `K2` is zero
    /// (a link of infinite length) or a length is not representable; [`Error::NoSolution`] when
    /// `b² ≤ 0`; [`Error::CannotAssemble`] when the linkage does not assemble at `phi_ref`.
    pub fn new(k: Freudenstein<T>, ground: T, phi_ref: T, psi_ref: T) -> Result<Self, Error> {
        let d = check_length("ground", ground)?;
        check_finite("input angle", phi_ref)?;
        check_finite("output angle", psi_ref)?;
        if k.k1 == T::zero() || k.k2 == T::zero() {
            return Err(Error::Degenerate {
                what: "K1 or K2 is zero: a link of infinite length",
            });
        }
        let (a, c) = (d / k.k1, d / k.k2);
        let b2 = a * a + c * c + d * d - lit::<T>(2.0) * a * c * k.k3;
        if !(a.is_finite() && c.is_finite() && b2.is_finite()) {
            return Err(Error::Degenerate {
                what: "a link length is too large to represent (K1 or K2 near zero)",
            });
        }
        if b2 <= T::zero() || is_nan(b2) {
            return Err(Error::NoSolution {
                what: "the coefficients give no real coupler (b² = a² + c² + d² − 2ac·K3 ≤ 0)",
            });
        }
        let pi_if = |neg: bool| if neg { T::pi() } else { T::zero() };
        let (input_offset, output_offset) = (pi_if(a < T::zero()), pi_if(c < T::zero()));
        let make = |assembly| {
            FourBar::new(
                d,
                a.abs(),
                b2.sqrt(),
                c.abs(),
                (T::zero(), T::zero()),
                assembly,
            )
        };
        let mut best: Option<(T, FourBar<T>)> = None;
        for assembly in [Assembly::Open, Assembly::Crossed] {
            let fb = make(assembly)?;
            let Ok(p) = fb.pose(phi_ref + input_offset) else {
                continue;
            };
            let out = (p.b.y - fb.c.y).atan2(p.b.x - fb.c.x) - output_offset;
            let miss = wrap(out - psi_ref).abs();
            if best.is_none_or(|(m, _)| miss < m) {
                best = Some((miss, fb));
            }
        }
        let Some((_, four_bar)) = best else {
            let fb = make(Assembly::Open)?;
            return Err(fb
                .pose(phi_ref + input_offset)
                .err()
                .unwrap_or(Error::NoSolution {
                    what: "the linkage does not assemble at the first precision point",
                }));
        };
        Ok(FunctionGenerator {
            four_bar,
            freudenstein: k,
            input_offset,
            output_offset,
        })
    }

    /// Fits the coefficients through `(phi[j], psi[j])` ([`Freudenstein::fit`]) and builds the
    /// generator on the assembly that meets the first point.
    ///
    /// # Errors
    /// As [`Freudenstein::fit`] and [`FunctionGenerator::new`].
    pub fn synthesise(phi: &[T], psi: &[T], ground: T) -> Result<Self, Error> {
        let k = Freudenstein::fit(phi, psi)?;
        Self::new(k, ground, phi[0], psi[0])
    }

    /// The output angle on the generator's assembly at input `phi` (no tracking), or `None`
    /// where it does not assemble.
    pub fn output(&self, phi: T) -> Option<T> {
        let p = self.four_bar.pose(phi + self.input_offset).ok()?;
        let c = self.four_bar.c;
        Some((p.b.y - c.y).atan2(p.b.x - c.x) - self.output_offset)
    }

    /// Sweeps the input over `phi` (the caller's samples of its interval, in order) with the
    /// [`Tracker`], writing the output angle at each into `psi` (continuous, starting within `π`
    /// of `precision_psi[0]`; NaN where the sweep stops), and checks the precision points.
    ///
    /// Defects: a precision point met only on the other assembly ([`Defect::Branch`]); an
    /// interval that reaches past an input limit ([`Defect::InputLimit`], checked against the
    /// exact limits over the hull of `phi` and the precision inputs); the tracker passing a flat
    /// position ([`Defect::FlatPosition`]).
    ///
    /// # Errors
    /// [`Error::BufferLength`] when `psi` is not as long as `phi` or the precision slices differ
    /// in length; [`Error::TooFew`] for no precision point; [`Error::NotFinite`] for a
    /// non-finite angle.
    pub fn sweep(
        &self,
        phi: &[T],
        psi: &mut [T],
        precision_phi: &[T],
        precision_psi: &[T],
    ) -> Result<FunctionCheck<T>, Error> {
        if psi.len() != phi.len() {
            return Err(Error::BufferLength {
                what: "output angles",
                expected: phi.len(),
                got: psi.len(),
            });
        }
        if precision_psi.len() != precision_phi.len() {
            return Err(Error::BufferLength {
                what: "precision output angles",
                expected: precision_phi.len(),
                got: precision_psi.len(),
            });
        }
        if precision_phi.is_empty() {
            return Err(Error::TooFew {
                what: "precision points",
                needed: 1,
                got: 0,
            });
        }
        for &x in phi.iter().chain(precision_phi).chain(precision_psi) {
            check_finite("angle", x)?;
        }
        let fb = &self.four_bar;
        let mut out = FunctionCheck {
            defect: None,
            precision_error: T::zero(),
            min_transmission: T::frac_pi_2(),
            grashof: fb.grashof(),
        };
        for v in psi.iter_mut() {
            *v = nan();
        }
        // Precision points: on this assembly, not the mirror one.
        let mirror = FourBar {
            assembly: match fb.assembly {
                Assembly::Open => Assembly::Crossed,
                Assembly::Crossed => Assembly::Open,
            },
            ..*fb
        };
        let mirror = FunctionGenerator {
            four_bar: mirror,
            ..*self
        };
        for (j, (&f, &s)) in precision_phi.iter().zip(precision_psi).enumerate() {
            let here = self.output(f).map(|o| wrap(o - s).abs());
            let there = mirror.output(f).map(|o| wrap(o - s).abs());
            match (here, there) {
                (Some(h), Some(t)) if t < h => {
                    out.defect.get_or_insert(Defect::Branch { pose: j });
                }
                (None, _) => {
                    out.defect.get_or_insert(Defect::InputLimit);
                }
                (Some(h), _) => out.precision_error = out.precision_error.max(h),
            }
        }
        // The whole input hull inside one assembly interval (exact limits).
        let tau = T::two_pi();
        let (mut lo_in, mut hi_in) = (precision_phi[0], precision_phi[0]);
        for &x in phi.iter().chain(precision_phi) {
            lo_in = lo_in.min(x);
            hi_in = hi_in.max(x);
        }
        let start = precision_phi[0] + self.input_offset;
        let interval = match fb.input_range() {
            InputRange::Full => None,
            InputRange::Never => Some((T::one(), T::zero())),
            InputRange::Between { lo, hi } => Some((lo, hi)),
            InputRange::TwoIntervals { first, second } => {
                let r = first.0 + turns(start - first.0);
                Some(if r <= first.1 { first } else { second })
            }
        };
        if let Some((lo, hi)) = interval {
            let slack = lit::<T>(64.0) * eps::<T>() * (tau + lo.abs() + hi.abs());
            let mut r = lo + turns(start - lo);
            if r > hi + slack && r - tau >= lo - slack {
                r -= tau;
            }
            let (a, b) = (
                r + (lo_in - precision_phi[0]),
                r + (hi_in - precision_phi[0]),
            );
            if a < lo - slack || b > hi + slack {
                out.defect.get_or_insert(Defect::InputLimit);
            }
        }
        let m = fb.mechanism();
        let mut tracker = Tracker::new(&m)?;
        let sign0 = tracker.branch(FourBar::<T>::B);
        let mut joints = [Vec2::zeros(); 5];
        let mut margin = T::one();
        let mut prev = precision_psi[0];
        for (k, &f) in phi.iter().enumerate() {
            let Ok(sample) = tracker.step(f + self.input_offset, None, &mut joints, Rates::none())
            else {
                out.defect.get_or_insert(Defect::InputLimit);
                break;
            };
            if tracker.branch(FourBar::<T>::B) != sign0 {
                out.defect.get_or_insert(Defect::FlatPosition);
                break;
            }
            margin = margin.min(sample.margin);
            let b = joints[FourBar::<T>::B];
            let o = (b.y - fb.c.y).atan2(b.x - fb.c.x) - self.output_offset;
            let v = prev + wrap(o - prev);
            psi[k] = v;
            prev = v;
        }
        out.min_transmission = min_transmission_angle(margin);
        Ok(out)
    }
}
