//! The fast path: a four-bar's coupler point over uniformly spaced crank angles.
//!
//! Three ways to produce the crank's `(cos θ, sin θ)` are offered (see [`AngleMode`]); the rest of
//! the kernel is the same closed form as [`crate::Dyad::solve`] (Kahan's area, no cancellation
//! near a toggle) specialised to the four-bar and written branch-free over structure-of-arrays
//! blocks so the compiler can vectorise it.

use nalgebra::RealField;

use crate::error::{check_finite, check_length, Error};
use crate::linkages::fourbar::FourBar;
use crate::numeric::scalar::{lit, Vec2};

/// How crank angles `θ_k = θ₀ + k·Δ` are turned into `(cos θ_k, sin θ_k)`.
///
/// ```
/// use linkage_core::{catalog, AngleMode, Error, Vec2, MAX_TABLE};
/// let fb = catalog::hoecken::<f64>();
/// let (mut trig, mut table) = ([Vec2::zeros(); 100], [Vec2::zeros(); 100]);
/// fb.uniform_sweep(0.0, 0.01, 0, AngleMode::Trig, &mut trig).unwrap();
/// fb.uniform_sweep(0.0, 0.01, 0, AngleMode::Table { block: 64 }, &mut table).unwrap();
/// assert!(trig.iter().zip(&table).all(|(p, q)| (p - q).norm() < 1e-12));
/// // The small table lives on the stack: at most MAX_TABLE entries.
/// assert_eq!(
///     fb.uniform_sweep(0.0, 0.01, 0, AngleMode::Table { block: 300 }, &mut table),
///     Err(Error::OutOfRange { what: "table block", value: 300, max: MAX_TABLE })
/// );
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AngleMode {
    /// `sin_cos` of every angle (libm or the platform's): the reference.
    Trig,
    /// Two-level table: exact `sin_cos` at anchors every `block` samples, times a table of
    /// `(cos jΔ, sin jΔ)` for `j < block`, by the angle-addition formula (one complex product).
    Table {
        /// Samples per anchor (the small table's length).
        block: usize,
    },
    /// Rotation recurrence `z_{k+1} = z_k·e^{iΔ}`, re-anchored with an exact `sin_cos` every
    /// `block` samples so rounding cannot accumulate past `block` steps.
    Recurrence {
        /// Samples between re-anchorings.
        block: usize,
    },
}

impl AngleMode {
    /// Every name [`AngleMode::named`] takes, in declaration order.
    pub const NAMES: [&'static str; 3] = ["trig", "table", "recurrence"];

    /// The mode named `"trig"`, `"table"` or `"recurrence"`, with `block` samples per anchor
    /// for the last two (checked when sweeping: see [`MAX_TABLE`]).
    ///
    /// ```
    /// use linkage_core::{AngleMode, Error};
    /// assert_eq!(AngleMode::named("table", 64), Ok(AngleMode::Table { block: 64 }));
    /// assert_eq!(AngleMode::Recurrence { block: 8 }.name(), "recurrence");
    /// assert_eq!(
    ///     AngleMode::named("fast", 64),
    ///     Err(Error::InvalidChoice { what: "mode", choices: "'trig', 'table' or 'recurrence'" })
    /// );
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidChoice`] for any other name.
    pub fn named(name: &str, block: usize) -> Result<Self, Error> {
        match name {
            "trig" => Ok(AngleMode::Trig),
            "table" => Ok(AngleMode::Table { block }),
            "recurrence" => Ok(AngleMode::Recurrence { block }),
            _ => Err(Error::InvalidChoice {
                what: "mode",
                choices: "'trig', 'table' or 'recurrence'",
            }),
        }
    }

    /// The name users write: `"trig"`, `"table"` or `"recurrence"`.
    pub fn name(self) -> &'static str {
        match self {
            AngleMode::Trig => "trig",
            AngleMode::Table { .. } => "table",
            AngleMode::Recurrence { .. } => "recurrence",
        }
    }
}

/// Longest small table of the [`AngleMode::Table`] mode (it lives on the stack).
pub const MAX_TABLE: usize = 256;

impl<T: RealField + Copy> FourBar<T> {
    /// Checks that crank angles from `theta0` to `theta1` (either order, both included) can be
    /// swept on the declared assembly: no flat position of a change-point four-bar lies on the
    /// path. At a flat position (crank pin on the ground line with coupler and rocker
    /// collinear) the open and crossed branches meet and the motion continues on the other
    /// orientation, so a sweep that keeps one would silently switch branch there.
    ///
    /// # Errors
    /// [`Error::ToggleOnPath`] with the first such angle; [`Error::NotFinite`] for bad angles.
    pub fn check_fixed_assembly_path(&self, theta0: T, theta1: T) -> Result<(), Error> {
        check_finite("theta0", theta0)?;
        check_finite("theta1", theta1)?;
        let (lo, hi) = (theta0.min(theta1), theta0.max(theta1));
        let flats = crate::constructions::dyad::flat_angles(
            self.ground(),
            self.crank,
            self.coupler,
            self.rocker,
        );
        let dv = self.c - self.o;
        let base = dv.y.atan2(dv.x);
        let mut first: Option<T> = None;
        for psi in flats.into_iter().flatten() {
            let a = base + psi;
            let turns = ((lo - a) / T::two_pi()).ceil();
            let at = a + turns * T::two_pi();
            if at <= hi && first.is_none_or(|f| at < f) {
                first = Some(at);
            }
        }
        match first {
            Some(angle) => Err(Error::ToggleOnPath {
                angle: crate::numeric::scalar::to_f64(angle),
            }),
            None => Ok(()),
        }
    }

    /// Coupler point at `θ_k = theta0 + k·dtheta` for `k` in `first .. first + out.len()`, on
    /// the declared assembly (no branch tracking: right for cranks that turn fully without a
    /// toggle — crank-rockers and double cranks — and anywhere a toggle is not crossed). A sample
    /// that cannot assemble is NaN. `first` lets a caller split one sweep across threads; with
    /// the anchors at absolute multiples of the block, every mode gives the same bits whatever
    /// the split.
    ///
    /// # Errors
    /// Nothing is written on an error. [`Error::NotFinite`] for a non-finite
    /// `theta0`/`dtheta`; [`Error::InvalidLength`] for a zero block; [`Error::OutOfRange`] for
    /// an [`AngleMode::Table`] block above [`MAX_TABLE`]; [`Error::CountOverflow`] when
    /// `first + out.len()` overflows `usize`; [`Error::ToggleOnPath`] when a change-point
    /// linkage's flat position lies on the samples' path (see
    /// [`FourBar::check_fixed_assembly_path`]).
    // Always inlined, so a caller compiled for wider vectors (the Python binding's AVX-512 and
    // AVX2 paths) gets this kernel compiled for them too.
    #[inline(always)]
    pub fn uniform_sweep(
        &self,
        theta0: T,
        dtheta: T,
        first: usize,
        mode: AngleMode,
        out: &mut [Vec2<T>],
    ) -> Result<(), Error> {
        check_finite("theta0", theta0)?;
        check_finite("dtheta", dtheta)?;
        let block = match mode {
            AngleMode::Trig => MAX_TABLE,
            AngleMode::Table { block } | AngleMode::Recurrence { block } => {
                check_length("block", lit::<T>(block as f64))?;
                block
            }
        };
        if block > MAX_TABLE && matches!(mode, AngleMode::Table { .. }) {
            return Err(Error::OutOfRange {
                what: "table block",
                value: block,
                max: MAX_TABLE,
            });
        }
        let end = first.checked_add(out.len()).ok_or(Error::CountOverflow {
            what: "first sample + samples",
        })?;
        let angle = |i: usize| theta0 + dtheta * lit::<T>(i as f64);
        if !out.is_empty() {
            self.check_fixed_assembly_path(angle(first), angle(end - 1))?;
        }
        // The step's rotation (recurrence) and the small table of its multiples (table mode).
        let (ds, dc) = dtheta.sin_cos();
        let mut tc = [T::zero(); MAX_TABLE];
        let mut ts = [T::zero(); MAX_TABLE];
        if let AngleMode::Table { .. } = mode {
            for j in 0..block {
                let (s, c) = (dtheta * lit::<T>(j as f64)).sin_cos();
                tc[j] = c;
                ts[j] = s;
            }
        }
        // The kernel squares and multiplies four lengths (Kahan's product): a linkage far from
        // unit size would underflow or overflow there. Run it on the linkage scaled by a power
        // of two to unit size and scale the points back: exact, so the bits are those of the
        // unit-size linkage (ordinary sizes are left alone and keep their own bits).
        let unscale = unit_scale(self.size());
        let work = if unscale == T::one() {
            *self
        } else {
            self.scaled(T::one() / unscale)
        };
        let mut cos_buf = [T::zero(); MAX_TABLE];
        let mut sin_buf = [T::zero(); MAX_TABLE];
        let span = block.min(MAX_TABLE);
        let mut k = first;
        let mut written = 0;
        // One anchor block at a time: the anchor's exact direction, then the samples up to the
        // next anchor (or the end), in a straight loop the compiler can vectorise.
        while k < end {
            let anchor = k - k % span;
            // (saturating: the last anchor block of an index range ending near `usize::MAX`)
            let stop = anchor.saturating_add(span).min(end);
            let m = stop - k;
            match mode {
                AngleMode::Trig => {
                    let mut angles = [T::zero(); MAX_TABLE];
                    for (a, idx) in angles.iter_mut().zip(k..stop) {
                        *a = angle(idx);
                    }
                    crate::numeric::trig::sin_cos_block(
                        &angles[..m],
                        &mut sin_buf[..m],
                        &mut cos_buf[..m],
                    );
                }
                AngleMode::Table { .. } => {
                    let (sa, ca) = crate::numeric::trig::sin_cos(angle(anchor));
                    let j0 = k - anchor;
                    for i in 0..m {
                        let (c, s) = (tc[j0 + i], ts[j0 + i]);
                        cos_buf[i] = ca * c - sa * s;
                        sin_buf[i] = sa * c + ca * s;
                    }
                }
                AngleMode::Recurrence { .. } => {
                    // Start at the anchor and step up, so a sweep split at any sample gives the
                    // same bits as the whole.
                    let (mut zs, mut zc) = crate::numeric::trig::sin_cos(angle(anchor));
                    for _ in anchor..k {
                        (zc, zs) = (zc * dc - zs * ds, zs * dc + zc * ds);
                    }
                    for i in 0..m {
                        cos_buf[i] = zc;
                        sin_buf[i] = zs;
                        (zc, zs) = (zc * dc - zs * ds, zs * dc + zc * ds);
                    }
                }
            }
            let dst = &mut out[written..written + m];
            work.coupler_block(&cos_buf[..m], &sin_buf[..m], dst);
            if unscale != T::one() {
                for p in dst.iter_mut() {
                    *p *= unscale;
                }
            }
            written += m;
            k = stop;
        }
        Ok(())
    }

    /// The closed-form kernel over a block of crank directions: branch-free, so it
    /// vectorises. A sample that cannot close gets a negative Kahan product, whose square root
    /// is NaN, which then runs through to the output.
    #[inline(always)]
    fn coupler_block(&self, cos: &[T], sin: &[T], out: &mut [Vec2<T>]) {
        let (o, c) = (self.o, self.c);
        let (r, r1, r2) = (self.crank, self.coupler, self.rocker);
        let sign = self.assembly.side().sign::<T>();
        let (along, left) = (self.along, self.left);
        let (half, quarter, two) = (lit::<T>(0.5), lit::<T>(0.25), lit::<T>(2.0));
        let inv_r1 = T::one() / r1;
        let (rmax, rmin) = (r1.max(r2), r1.min(r2));
        let diff = (r1 - r2) * (r1 + r2);
        let tol = T::default_epsilon() * lit::<T>(8.0) * (r1 + r2 + o.amax() + c.amax() + r);
        for ((p, &cs), &sn) in out.iter_mut().zip(cos).zip(sin) {
            let ax = o.x + r * cs;
            let ay = o.y + r * sn;
            let (dx, dy) = (c.x - ax, c.y - ay);
            let d = (dx * dx + dy * dy).sqrt();
            // Kahan's area of the triangle (d, r1, r2): with r1, r2 fixed the sorted sides are
            // hi = max(d, rmax), lo = min(d, rmin), mid = clamp(d, rmin, rmax) — exact.
            let (hi, mid, lo) = crate::constructions::dyad::sorted_with(d, rmin, rmax);
            let f2 = lo - (hi - mid);
            let f2 = if f2 < T::zero() && f2 >= -tol {
                T::zero()
            } else {
                f2
            };
            let prod = (hi + (mid + lo)) * f2 * (lo + (hi - mid)) * (hi + (mid - lo));
            let area = prod.sqrt() * quarter;
            let inv_d = T::one() / d;
            let (ux, uy) = (dx * inv_d, dy * inv_d);
            let x = (d + diff * inv_d) * half;
            let h = two * area * inv_d * sign;
            // B − A = x·u + h·u⊥; P = A + along·e + left·e⊥ with e = (B − A)/r1.
            let ex = (x * ux - h * uy) * inv_r1;
            let ey = (x * uy + h * ux) * inv_r1;
            *p = Vec2::new(ax + along * ex - left * ey, ay + along * ey + left * ex);
        }
    }
}

impl<T: RealField + Copy> FourBar<T> {
    /// The largest length or pivot coordinate: the linkage's size for scaling.
    fn size(&self) -> T {
        let lengths = self.crank.max(self.coupler).max(self.rocker);
        let point = self.along.abs().max(self.left.abs());
        lengths.max(point).max(self.o.amax()).max(self.c.amax())
    }

    /// The same linkage with every length and coordinate multiplied by `k` (a power of two in
    /// [`FourBar::uniform_sweep`], so exactly).
    fn scaled(&self, k: T) -> Self {
        FourBar {
            o: self.o * k,
            c: self.c * k,
            crank: self.crank * k,
            coupler: self.coupler * k,
            rocker: self.rocker * k,
            along: self.along * k,
            left: self.left * k,
            assembly: self.assembly,
        }
    }
}

/// A power of two `s` with `size / s` in `[1, 2)` when `size` is outside `[2⁻¹⁶, 2¹⁶]`; `1`
/// for ordinary sizes and for a size that is zero or not finite (nothing to gain there).
fn unit_scale<T: RealField + Copy>(size: T) -> T {
    let (lo, hi) = (lit::<T>(1.0 / 65_536.0), lit::<T>(65_536.0));
    if !size.is_finite() || size <= T::zero() || (size >= lo && size <= hi) {
        return T::one();
    }
    let (two, coarse) = (lit::<T>(2.0), lit::<T>(65_536.0));
    let mut s = T::one();
    // Coarse steps first (at most ~64 for f64), then single bits.
    while size / s >= coarse && (s * coarse).is_finite() {
        s *= coarse;
    }
    while size / s < T::one() / coarse && s / coarse > T::zero() {
        s /= coarse;
    }
    while size / s >= two && (s * two).is_finite() {
        s *= two;
    }
    while size / s < T::one() && s / two > T::zero() {
        s /= two;
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalog;
    use crate::linkages::fourbar::Assembly;

    #[test]
    fn modes_agree_with_the_general_solver() {
        let fb = catalog::hoecken::<f64>();
        let n = 3600;
        let dt = core::f64::consts::TAU / n as f64;
        for mode in [
            AngleMode::Trig,
            AngleMode::Table { block: 64 },
            AngleMode::Recurrence { block: 64 },
        ] {
            let mut out = vec![Vec2::zeros(); n];
            fb.uniform_sweep(0.3, dt, 0, mode, &mut out).unwrap();
            for (k, p) in out.iter().enumerate() {
                let q = fb.pose(0.3 + dt * k as f64).unwrap().coupler_point;
                assert!((p - q).norm() < 1e-12, "{mode:?} {k}: {p:?} vs {q:?}");
            }
        }
    }

    #[test]
    fn split_sweeps_give_the_same_bits() {
        let fb = catalog::hoecken::<f64>();
        let n = 1000;
        let dt = 0.01;
        for mode in [
            AngleMode::Table { block: 32 },
            AngleMode::Recurrence { block: 32 },
        ] {
            let mut whole = vec![Vec2::zeros(); n];
            fb.uniform_sweep(0.0, dt, 0, mode, &mut whole).unwrap();
            let mut parts = vec![Vec2::zeros(); n];
            let (a, b) = parts.split_at_mut(421);
            fb.uniform_sweep(0.0, dt, 0, mode, a).unwrap();
            fb.uniform_sweep(0.0, dt, 421, mode, b).unwrap();
            assert_eq!(whole, parts, "{mode:?}");
        }
    }

    #[test]
    fn change_point_flat_positions_on_the_path_are_refused() {
        // Parallelogram: flat at θ = 0 and π.
        let fb = FourBar::new(3.0_f64, 1.0, 3.0, 1.0, (1.5, 0.5), Assembly::Open).unwrap();
        let mut out = vec![Vec2::zeros(); 10];
        let e = fb.uniform_sweep(0.1, 0.5, 0, AngleMode::Trig, &mut out);
        assert_eq!(
            e,
            Err(Error::ToggleOnPath {
                angle: core::f64::consts::PI
            }),
            "parallelogram swept from 0.1 in steps of 0.5 across its flat position at π"
        );
        assert!(out.iter().all(|p| *p == Vec2::zeros()), "nothing written");
        // Between the flat positions it runs.
        fb.uniform_sweep(0.1, 0.3, 0, AngleMode::Trig, &mut out)
            .unwrap();
        // A Grashof crank-rocker never flattens.
        let h = catalog::hoecken::<f64>();
        let got = h.check_fixed_assembly_path(-1e3, 1e3);
        assert!(got.is_ok(), "Hoecken's crank-rocker over ±1e3 rad: {got:?}");
    }

    #[test]
    fn extreme_sizes_sweep_like_the_unit_size_linkage() {
        // Power-of-two scales: the points must be exactly the unit linkage's, scaled.
        let base = catalog::hoecken::<f64>();
        let mut unit = [Vec2::zeros(); 40];
        base.uniform_sweep(0.1, 0.157, 0, AngleMode::Table { block: 16 }, &mut unit)
            .unwrap();
        for e in [-1000, -330, -100, 100, 330, 1000] {
            let k = 2f64.powi(e);
            let fb = base.scaled(k);
            let mut out = [Vec2::zeros(); 40];
            fb.uniform_sweep(0.1, 0.157, 0, AngleMode::Table { block: 16 }, &mut out)
                .unwrap();
            for (p, q) in out.iter().zip(&unit) {
                assert_eq!(*p / k, *q, "scale 2^{e}: {p:?} vs {q:?}");
            }
        }
    }

    #[test]
    fn unassemblable_samples_are_nan() {
        let fb = catalog::evans_b::<f64>();
        let mut out = vec![Vec2::zeros(); 4];
        fb.uniform_sweep(
            0.0,
            core::f64::consts::FRAC_PI_2,
            0,
            AngleMode::Trig,
            &mut out,
        )
        .unwrap();
        assert!(
            out[0].x.is_finite() && out[2].x.is_nan(),
            "Evans B at θ = 0, π/2, π, 3π/2 (want θ = 0 finite, π NaN): {out:?}"
        );
    }
}
