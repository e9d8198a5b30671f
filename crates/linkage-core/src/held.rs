//! The held pass's poses, a block of samples at a time: every construction evaluated over
//! [`BLOCK`] crank angles in a straight loop the compiler vectorises, with the same formulas,
//! in the same order, as [`Mechanism::pose_watched`] — so each sample gets the bits that one
//! pose gives it.
//!
//! # What a block does not do itself
//! A dyad on a crank pin and a fixed joint whose triangle is within
//! [`crate::dyad::EXACT_BASE_SLACK`] of flat forms its base without cancellation from the crank
//! angle (`Mechanism::crank_base`), which this kernel does not: such samples are marked and
//! posed one by one. A slider dyad has no block kernel: a mechanism with one is posed one
//! sample at a time ([`BlockPoses::applies`]). Nor does a mechanism whose numbers lie outside
//! `[2⁻²⁸, 2²⁸]`: there the scalar code rescales by powers of two, which the kernel skips.

use nalgebra::RealField;

use crate::dyad::EXACT_BASE_SLACK;
use crate::mechanism::{Construction, Mechanism};
use crate::scalar::{eps, lit, tiny_square};

/// Samples per block.
pub(crate) const BLOCK: usize = 16;

/// Joint positions of a block of samples, structure of arrays: `x[j][k]`, `y[j][k]` of joint
/// `j` at sample `k`.
pub(crate) struct BlockPoses<T, const N: usize> {
    pub(crate) x: [[T; BLOCK]; N],
    pub(crate) y: [[T; BLOCK]; N],
    /// Smallest margin of every dyad, per sample.
    pub(crate) margin: [T; BLOCK],
    /// Smallest margin of the watched dyads, per sample (1 if none).
    pub(crate) watched: [T; BLOCK],
    /// Samples to pose one by one ([`Mechanism::pose_watched`]): a near-flat dyad on a crank
    /// pin, a base of zero length, or a value that is not finite.
    pub(crate) scalar: [bool; BLOCK],
    /// Samples where a dyad or point cannot be placed by the kernel's own rule (a closure miss
    /// beyond rounding, a zero-length link): the held pass cannot vouch for them.
    pub(crate) failed: [bool; BLOCK],
    /// Whether `margin` is wanted (else only the watched dyads' margins are computed and
    /// `margin` holds 1).
    pub(crate) margins: bool,
}

/// Powers of two of ordinary sizes: a mechanism whose every nonzero length and coordinate lies
/// within `[2⁻²⁸, 2²⁸]` is posed by the kernel (the scalar code's rescaling factors are all 1).
const ORDINARY: (f64, f64) = (3.725_290_298_461_914e-9, 268_435_456.0);

impl<T: RealField + Copy, const N: usize> BlockPoses<T, N> {
    /// An empty block.
    pub(crate) fn new() -> Self {
        BlockPoses {
            x: [[T::zero(); BLOCK]; N],
            y: [[T::zero(); BLOCK]; N],
            margin: [T::zero(); BLOCK],
            watched: [T::zero(); BLOCK],
            scalar: [false; BLOCK],
            failed: [false; BLOCK],
            margins: true,
        }
    }

    /// Places `mech`'s fixed joints, which every block shares (call before [`Self::pose`]).
    pub(crate) fn prepare(&mut self, mech: &Mechanism<T, N>) {
        for (i, step) in mech.constructions().iter().enumerate() {
            if let Construction::Fixed { at } = *step {
                self.x[i] = [at.x; BLOCK];
                self.y[i] = [at.y; BLOCK];
            }
        }
    }

    /// Whether the kernel poses `mech` (see the module): no slider, ordinary sizes.
    pub(crate) fn applies(mech: &Mechanism<T, N>) -> bool {
        let (lo, hi) = (lit::<T>(ORDINARY.0), lit::<T>(ORDINARY.1));
        let ordinary = |v: T| v == T::zero() || (v.abs() >= lo && v.abs() <= hi);
        mech.constructions().iter().all(|c| match *c {
            Construction::Fixed { at } => ordinary(at.x) && ordinary(at.y),
            Construction::Crank { radius, .. } => ordinary(radius),
            Construction::Dyad { dyad, .. } => ordinary(dyad.r1) && ordinary(dyad.r2),
            Construction::Point { along, left, .. } => ordinary(along) && ordinary(left),
            Construction::Slider { .. } => false,
        })
    }

    /// Poses `theta` (at most [`BLOCK`] angles) on the declared orientations, the fixed joints
    /// placed by [`Self::prepare`].
    #[inline(always)]
    pub(crate) fn pose(&mut self, mech: &Mechanism<T, N>, theta: &[T], watched: &[bool]) {
        let n = theta.len().min(BLOCK);
        let one = T::one();
        // Whole blocks (entries past n are never read): constant-length loops, no memset calls.
        self.margin = [one; BLOCK];
        self.watched = [one; BLOCK];
        self.scalar = [false; BLOCK];
        self.failed = [false; BLOCK];
        for (i, step) in mech.constructions().iter().enumerate() {
            match *step {
                // Placed once for all blocks by `prepare`.
                Construction::Fixed { .. } => {}
                Construction::Crank {
                    centre,
                    radius,
                    phase,
                } => {
                    let mut angle = [T::zero(); BLOCK];
                    for (a, &t) in angle.iter_mut().zip(&theta[..n]) {
                        *a = t + phase;
                    }
                    // Angles past n stay 0: sin/cos of the whole block, a fixed-length loop.
                    let (mut s, mut c) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
                    crate::trig::sin_cos_block(&angle, &mut s, &mut c);
                    let (cx, cy) = (self.x[centre], self.y[centre]);
                    let (mut xi, mut yi) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
                    for k in 0..BLOCK {
                        xi[k] = cx[k] + c[k] * radius;
                        yi[k] = cy[k] + s[k] * radius;
                    }
                    (self.x[i], self.y[i]) = (xi, yi);
                }
                Construction::Dyad { p1, p2, dyad, side } => {
                    let exact_base = mech.has_crank_base(p1, p2);
                    let sign = side.sign::<T>();
                    self.dyad(
                        i,
                        (p1, p2),
                        (dyad.r1, dyad.r2),
                        sign,
                        exact_base,
                        watched[i],
                    );
                }
                Construction::Point {
                    from,
                    to,
                    along,
                    left,
                } => {
                    let (fx, fy, tx, ty) = (self.x[from], self.y[from], self.x[to], self.y[to]);
                    let (mut xi, mut yi) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
                    let mut scalar = self.scalar;
                    let tiny = tiny_square::<T>();
                    let fixed = mech.link_length(from, to);
                    let inv_fixed = fixed.map_or(T::zero(), |l| T::one() / l);
                    for k in 0..BLOCK {
                        let (dx, dy) = (tx[k] - fx[k], ty[k] - fy[k]);
                        let n2 = dx * dx + dy * dy;
                        let inv = if fixed.is_some() {
                            inv_fixed
                        } else {
                            T::one() / n2.sqrt()
                        };
                        // A link of (nearly) zero length: the scalar code rescales or refuses.
                        scalar[k] |= n2 <= tiny || !n2.is_finite();
                        let (ex, ey) = (dx * inv, dy * inv);
                        xi[k] = fx[k] + ex * along + -ey * left;
                        yi[k] = fy[k] + ey * along + ex * left;
                    }
                    (self.x[i], self.y[i], self.scalar) = (xi, yi, scalar);
                }
                Construction::Slider { .. } => self.failed = [true; BLOCK],
            }
        }
        // Nothing here overflows (ordinary sizes, `applies`); a value that is not finite comes
        // from an angle that is not (the callers check those) or from a sample marked above.
    }

    /// The RRR dyad `i` on `p1`, `p2` over the block: [`crate::Dyad::solve_with_base`] without
    /// a base, term for term.
    #[allow(
        clippy::too_many_arguments,
        reason = "the dyad's joints, lengths, side and flags, passed as plain numbers so the loop vectorises"
    )]
    #[inline(always)]
    fn dyad(
        &mut self,
        i: usize,
        (p1, p2): (usize, usize),
        (r1, r2): (T, T),
        sign: T,
        exact_base: bool,
        watched: bool,
    ) {
        // Local copies: the loop then reads and writes distinct arrays of known length, which
        // is what lets it vectorise (measured: twice as fast as slices into the tables).
        let (ax, ay, bx, by) = (self.x[p1], self.y[p1], self.x[p2], self.y[p2]);
        let (mut scalar, mut failed) = (self.scalar, self.failed);
        let (mut margin_of, mut watched_of) = (self.margin, self.watched);
        let (mut xi, mut yi) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
        let (rmax, rmin) = (r1.max(r2), r1.min(r2));
        let (two, quarter, half) = (lit::<T>(2.0), lit::<T>(0.25), lit::<T>(0.5));
        let slack = lit::<T>(EXACT_BASE_SLACK);
        let eight_eps = eps::<T>() * lit::<T>(8.0);
        let (diff, sum) = (r1 - r2, r1 + r2);
        let two_r1r2 = two / (r1 * r2);
        let margins = self.margins || watched;
        let tiny = tiny_square::<T>();
        for k in 0..BLOCK {
            let (dx, dy) = (bx[k] - ax[k], by[k] - ay[k]);
            let n2 = dx * dx + dy * dy;
            let d = n2.sqrt();
            let tol = eight_eps
                * (d + r1 + r2 + ax[k].abs().max(ay[k].abs()) + bx[k].abs().max(by[k].abs()));
            // Kahan's sides sorted: with r1, r2 fixed, hi = max(d, rmax), lo = min(d, rmin),
            // mid the other (the compare-swaps of `sorted_desc` give the same values).
            let hi = if d > rmax { d } else { rmax };
            let lo = if d < rmin { d } else { rmin };
            let mid = if d < rmin {
                rmin
            } else if d > rmax {
                rmax
            } else {
                d
            };
            let amb = hi - mid;
            let f2 = lo - amb;
            let flat = f2 < T::zero();
            let prod = (hi + (mid + lo)) * f2 * (lo + amb) * (hi + (mid - lo));
            let area = if flat {
                T::zero()
            } else {
                prod.sqrt() * quarter
            };
            // Where the scalar code would take the crank base, or meets a zero base.
            // (nearly) zero base, where the scalar length rescales or the dyad is refused.
            scalar[k] |= (exact_base && f2 < slack * hi) || n2 <= tiny || !n2.is_finite();
            failed[k] |= flat && -f2 > tol;
            let inv_d = T::one() / d;
            let (ux, uy) = (dx * inv_d, dy * inv_d);
            let x = (d + diff * (sum * inv_d)) * half;
            let h = two * (area * inv_d);
            if margins {
                let margin = area * two_r1r2;
                margin_of[k] = margin_of[k].min(margin);
                if watched {
                    watched_of[k] = watched_of[k].min(margin);
                }
            }
            // foot + sign·offset, offset = perp(u)·h.
            let (fx, fy) = (ax[k] + ux * x, ay[k] + uy * x);
            xi[k] = fx + (-uy * h) * sign;
            yi[k] = fy + (ux * h) * sign;
        }
        (self.x[i], self.y[i]) = (xi, yi);
        (self.scalar, self.failed) = (scalar, failed);
        (self.margin, self.watched) = (margin_of, watched_of);
    }
}

#[cfg(test)]
mod timing {
    use super::*;

    #[test]
    #[ignore = "timing helper"]
    fn block_pose_timing() {
        use crate::dyad::Side;
        let n = 1_000_000;
        let theta: Vec<f64> = (0..n).map(|k| (k as f64 * 0.618_034).sin() * 7.0).collect();
        let mut m = Mechanism::<f64, 5>::new();
        let o = m.fixed(crate::Vec2::new(0.0, 0.0)).unwrap();
        let c = m.fixed(crate::Vec2::new(20.0, 0.0)).unwrap();
        let a = m.crank(o, 10.0, 0.0).unwrap();
        let mut m3 = m.clone();
        let b = m.dyad(a, c, 25.0, 25.0, Side::Left).unwrap();
        let m4 = m.clone();
        m.point(a, b, 50.0, 0.0).unwrap();
        let _ = m3.len();
        m3 = m3.clone();
        let watched = [false; 5];
        for (name, mech) in [("crank", &m3), ("+dyad", &m4), ("+point", &m)] {
            let mut blk = BlockPoses::<f64, 5>::new();
            blk.margins = false;
            blk.prepare(mech);
            let mut best = f64::INFINITY;
            let mut sum = 0.0;
            for _ in 0..9 {
                let t = std::time::Instant::now();
                for c in theta.chunks(BLOCK) {
                    blk.pose(mech, c, &watched[..mech.len()]);
                    sum += blk.x[mech.len() - 1][0];
                }
                best = best.min(t.elapsed().as_secs_f64());
            }
            std::println!("{name}: {:.2} ns/sample ({sum})", best * 1e9 / n as f64);
        }
    }
}
