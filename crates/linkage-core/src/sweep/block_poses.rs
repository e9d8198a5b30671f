//! The held pass's poses, a block of samples at a time: every construction evaluated over
//! [`BLOCK`] crank angles in a straight loop the compiler vectorises, with the same formulas,
//! in the same order, as [`Mechanism::pose_watched`] — so each sample gets the bits that one
//! pose gives it.
//!
//! # What a block does not do itself
//! A dyad on a crank pin and a fixed joint whose triangle is within
//! [`crate::constructions::dyad::EXACT_BASE_SLACK`] of flat forms its base without cancellation from the crank
//! angle (`Mechanism::crank_base`), which this kernel does not: such samples are marked and
//! posed one by one. A slider dyad has no block kernel: a mechanism with one is posed one
//! sample at a time ([`BlockPoses::applies`]). Nor does a mechanism whose numbers lie outside
//! `[2⁻²⁸, 2²⁸]`: there the scalar code rescales by powers of two, which the kernel skips.

use nalgebra::RealField;

use crate::constructions::dyad::EXACT_BASE_SLACK;
use crate::mechanism::program::{Construction, CrankBaseFrame, FlatParity, Mechanism};
use crate::numeric::scalar::{eps, lit, tiny_square, Vec2};

/// Samples per block.
pub(crate) const BLOCK: usize = 16;

/// The first [`BLOCK`] of `v` as a block, zeros past its end. A whole block is copied at a
/// fixed length: the kernel's vector loads of it then read what vector stores wrote (a copy of
/// unknown length, stored four or one at a time and loaded eight at a time, stalls on every
/// block: measured 8 % of a point-only sweep).
#[inline(always)]
pub(crate) fn padded<T: RealField + Copy>(v: &[T]) -> [T; BLOCK] {
    match v.get(..BLOCK).and_then(|w| <&[T; BLOCK]>::try_from(w).ok()) {
        Some(&whole) => whole,
        None => {
            let mut b = [T::zero(); BLOCK];
            for (d, &s) in b.iter_mut().zip(v) {
                *d = s;
            }
            b
        }
    }
}

/// Marks in `dst` the samples `src` marks, when `any` (whether `src` marks one) says so.
/// Flags are built in a fresh local array and merged only in the rare block that has one: a
/// copy of the block's flags in and out of every construction loaded sixteen bytes that the
/// loop had just stored eight at a time, and stalled on it (measured under perf).
#[inline(always)]
pub(crate) fn merge(dst: &mut [bool; BLOCK], src: &[bool; BLOCK], any: bool) {
    if any {
        for (d, &s) in dst.iter_mut().zip(src) {
            *d |= s;
        }
    }
}

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
    /// The frame of each dyad's crank base, if it has one (see [`Self::prepare`]).
    bases: [Option<CrankBaseFrame<T>>; N],
    /// The length of the link each carried point divides by, when the mechanism fixes it
    /// (`Mechanism::link_length`), looked up once by [`Self::prepare`].
    links: [Option<T>; N],
    /// For a mechanism with its orientations in closed form ([`Self::orient`]), each dyad's
    /// flat positions and their parity at the reference angle: the dyad is on its declared
    /// side where the parity is the reference's, on the other where not.
    flats: [Option<(FlatParity<T>, bool)>; N],
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
            bases: [None; N],
            links: [None; N],
            flats: [None; N],
        }
    }

    /// Places `mech`'s fixed joints and the frames of its crank bases, which every block
    /// shares (call before [`Self::pose`]).
    pub(crate) fn prepare(&mut self, mech: &Mechanism<T, N>) {
        let mut fixed = [Vec2::zeros(); N];
        for (i, step) in mech.constructions().iter().enumerate() {
            match *step {
                Construction::Fixed { at } => {
                    self.x[i] = [at.x; BLOCK];
                    self.y[i] = [at.y; BLOCK];
                    fixed[i] = at;
                }
                Construction::Dyad { p1, p2, .. } => {
                    self.bases[i] = mech.crank_base_frame(p1, p2, &fixed[..i]);
                }
                Construction::Point { from, to, .. } => {
                    self.links[i] = mech.link_length(from, to);
                }
                _ => {}
            }
        }
    }

    /// Orients the dyads with flat positions per sample, as the tracker does for a mechanism
    /// whose orientations are in closed form: declared at driver angle `reference` (the start
    /// angle, or the first sample), turned at each flat position crossed from there.
    pub(crate) fn orient(&mut self, mech: &Mechanism<T, N>, reference: T) {
        for (i, f) in self.flats.iter_mut().enumerate().take(mech.len()) {
            *f = mech
                .has_flats(i)
                .then(|| mech.flat_positions(i))
                .flatten()
                .map(|p| (p, p.at(reference)));
        }
    }

    /// The dyads [`Self::orient`] turns at driver angle `t`, for a sample posed one by one
    /// ([`Mechanism::pose_oriented`]): the parity of their flat positions differs from the
    /// reference's ([`FlatParity::at`], the same bits as the block's).
    pub(crate) fn flipped(&self, t: T) -> [bool; N] {
        self.flats
            .map(|f| f.is_some_and(|(flats, at_reference)| flats.at(t) != at_reference))
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

    /// Poses the block of angles `theta` ([`padded`]: entries past the samples are zeros, whose
    /// rows nobody reads) on the declared orientations, the fixed joints placed by
    /// [`Self::prepare`].
    #[inline(always)]
    pub(crate) fn pose(&mut self, mech: &Mechanism<T, N>, theta: &[T; BLOCK], watched: &[bool]) {
        // Large angles reduced to two turns as the scalar pose does ([`crate::numeric::turns`]): the
        // same bits, a comparison per sample where none is large.
        let reduced;
        let from = lit::<T>(crate::numeric::turns::REDUCE_FROM);
        let theta = if theta.iter().any(|t| t.abs() >= from) {
            reduced = theta.map(crate::numeric::turns::reduce);
            &reduced
        } else {
            theta
        };
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
                    for (a, &t) in angle.iter_mut().zip(theta) {
                        *a = t + phase;
                    }
                    // sin/cos of the whole block, a fixed-length loop.
                    let (mut s, mut c) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
                    crate::numeric::trig::sin_cos_block(&angle, &mut s, &mut c);
                    let (cx, cy) = (self.x[centre], self.y[centre]);
                    let (mut xi, mut yi) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
                    for k in 0..BLOCK {
                        xi[k] = cx[k] + c[k] * radius;
                        yi[k] = cy[k] + s[k] * radius;
                    }
                    (self.x[i], self.y[i]) = (xi, yi);
                }
                Construction::Dyad { p1, p2, dyad, side } => {
                    let th = *theta;
                    let (base, declared) = (self.bases[i], side.sign::<T>());
                    let mut sign = [declared; BLOCK];
                    if let Some((flats, at_reference)) = self.flats[i] {
                        // FlatParity::at term for term, a block at a time.
                        let mut half = [T::zero(); BLOCK];
                        for (h, &t) in half.iter_mut().zip(&th) {
                            *h = flats.half(t);
                        }
                        let (mut s, mut c) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
                        crate::numeric::trig::sin_cos_block(&half, &mut s, &mut c);
                        for k in 0..BLOCK {
                            if flats.of(s[k], c[k]) != at_reference {
                                sign[k] = -declared;
                            }
                        }
                    }
                    let lengths = (dyad.r1, dyad.r2);
                    self.dyad(i, (p1, p2), lengths, &sign, base, watched[i], &th);
                }
                Construction::Point {
                    from,
                    to,
                    along,
                    left,
                } => {
                    let (fx, fy, tx, ty) = (self.x[from], self.y[from], self.x[to], self.y[to]);
                    let (mut xi, mut yi) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
                    let (mut scalar, mut any) = ([false; BLOCK], false);
                    let tiny = tiny_square::<T>();
                    let fixed = self.links[i];
                    let inv_fixed = fixed.map_or(T::zero(), |l| T::one() / l);
                    if fixed.is_some() {
                        // The link's own length (ordinary, `applies`): never near zero, and a
                        // sample whose joints are not finite is already marked (a failed dyad).
                        for k in 0..BLOCK {
                            let (dx, dy) = (tx[k] - fx[k], ty[k] - fy[k]);
                            let (ex, ey) = (dx * inv_fixed, dy * inv_fixed);
                            xi[k] = fx[k] + ex * along + -ey * left;
                            yi[k] = fy[k] + ey * along + ex * left;
                        }
                    } else {
                        for k in 0..BLOCK {
                            let (dx, dy) = (tx[k] - fx[k], ty[k] - fy[k]);
                            let n2 = dx * dx + dy * dy;
                            let inv = T::one() / n2.sqrt();
                            // A link of (nearly) zero length: the scalar code rescales or
                            // refuses.
                            scalar[k] = n2 <= tiny || !n2.is_finite();
                            any |= scalar[k];
                            let (ex, ey) = (dx * inv, dy * inv);
                            xi[k] = fx[k] + ex * along + -ey * left;
                            yi[k] = fy[k] + ey * along + ex * left;
                        }
                    }
                    (self.x[i], self.y[i]) = (xi, yi);
                    merge(&mut self.scalar, &scalar, any);
                }
                Construction::Slider { .. } => self.failed = [true; BLOCK],
            }
        }
        // Nothing here overflows (ordinary sizes, `applies`); a value that is not finite comes
        // from an angle that is not (the callers check those) or from a sample marked above.
    }

    /// The RRR dyad `i` on `p1`, `p2` over the block: [`crate::Dyad::solve_with_base`] term
    /// for term, with the crank-pin-and-fixed-joint base of `Mechanism::crank_base` (`base`)
    /// at the samples within [`EXACT_BASE_SLACK`] of flat.
    #[allow(
        clippy::too_many_arguments,
        reason = "the dyad's joints, lengths, side, base and flags, passed as plain numbers so the loop vectorises"
    )]
    #[inline(always)]
    fn dyad(
        &mut self,
        i: usize,
        (p1, p2): (usize, usize),
        (r1, r2): (T, T),
        sign: &[T; BLOCK],
        base: Option<CrankBaseFrame<T>>,
        watched: bool,
        theta: &[T; BLOCK],
    ) {
        // Local copies: the loop then reads and writes distinct arrays of known length, which
        // is what lets it vectorise (measured: twice as fast as slices into the tables).
        let (ax, ay, bx, by) = (self.x[p1], self.y[p1], self.x[p2], self.y[p2]);
        let (mut scalar, mut failed) = ([false; BLOCK], [false; BLOCK]);
        let (mut any_scalar, mut any_failed) = (false, false);
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
        // The base vector and its length, replaced by the crank base's (with Kahan's vanishing
        // factor `given`) at the samples that take it.
        let (mut dvx, mut dvy) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
        let mut dd = [T::zero(); BLOCK];
        let mut use_base = [false; BLOCK];
        let mut any_base = false;
        for k in 0..BLOCK {
            let (dx, dy) = (bx[k] - ax[k], by[k] - ay[k]);
            let n2 = dx * dx + dy * dy;
            let d = n2.sqrt();
            // (nearly) zero base, where the scalar length rescales or the dyad is refused.
            scalar[k] = n2 <= tiny || !n2.is_finite();
            any_scalar |= scalar[k];
            let longest = d.max(r1).max(r2);
            let plain = (d + rmin).min(sum) - longest;
            use_base[k] = base.is_some() && plain < longest * slack;
            any_base |= use_base[k];
            (dvx[k], dvy[k], dd[k]) = (dx, dy, d);
        }
        let mut given = [T::zero(); BLOCK];
        if let (true, Some(b)) = (any_base, base) {
            let base_out = (&mut dvx, &mut dvy, &mut dd);
            Self::crank_base(
                b,
                (r1, r2),
                theta,
                &use_base,
                base_out,
                &mut given,
                &mut scalar,
            );
            // The base may mark samples (rare: merged whether it did or not).
            any_scalar = true;
        }
        let (mut flat_at, mut any_flat) = ([false; BLOCK], false);
        for k in 0..BLOCK {
            let (dx, dy, d) = (dvx[k], dvy[k], dd[k]);
            // Kahan's sides sorted: with r1, r2 fixed, hi = max(d, rmax), lo = min(d, rmin),
            // mid the other (the compare-swaps of `sorted_desc` give the same values).
            let (hi, mid, lo) = crate::constructions::dyad::sorted_with(d, rmin, rmax);
            let amb = hi - mid;
            let f2 = if use_base[k] { given[k] } else { lo - amb };
            let flat = f2 < T::zero() || (use_base[k] && !f2.is_finite());
            let prod = (hi + (mid + lo)) * f2 * (lo + amb) * (hi + (mid - lo));
            let area = if flat {
                T::zero()
            } else {
                prod.sqrt() * quarter
            };
            // Judged below (a rare case: the tolerance is not worth forming at every sample).
            (flat_at[k], any_flat, given[k]) = (flat, any_flat | flat, f2);
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
            xi[k] = fx + (-uy * h) * sign[k];
            yi[k] = fy + (ux * h) * sign[k];
        }
        if any_flat {
            any_failed = true;
            for k in 0..BLOCK {
                let (d, f2) = (dd[k], given[k]);
                let tol = eight_eps
                    * (d + r1 + r2 + ax[k].abs().max(ay[k].abs()) + bx[k].abs().max(by[k].abs()));
                // A closure miss beyond rounding (NaN included) is a failure.
                failed[k] |= flat_at[k] && (-f2 > tol || !f2.is_finite());
            }
        }
        (self.x[i], self.y[i]) = (xi, yi);
        merge(&mut self.scalar, &scalar, any_scalar);
        merge(&mut self.failed, &failed, any_failed);
        (self.margin, self.watched) = (margin_of, watched_of);
    }

    /// `Mechanism::crank_base` over the block at the samples `use_base` marks: the base
    /// vector `(dvx, dvy)`, its length `dd` and the vanishing factor `given`, term for term.
    #[allow(
        clippy::too_many_arguments,
        reason = "the frame, the lengths, the angles and the block's arrays"
    )]
    #[allow(clippy::type_complexity, reason = "the three arrays the base replaces")]
    #[inline(always)]
    fn crank_base(
        b: CrankBaseFrame<T>,
        (r1, r2): (T, T),
        theta: &[T; BLOCK],
        use_base: &[bool; BLOCK],
        (dvx, dvy, dd): (&mut [T; BLOCK], &mut [T; BLOCK], &mut [T; BLOCK]),
        given: &mut [T; BLOCK],
        scalar: &mut [bool; BLOCK],
    ) {
        let (gv, g, beta, r) = (b.gv, b.g, b.beta, b.r);
        let (mut halfs, mut turned) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
        for k in 0..BLOCK {
            let psi = theta[k] + b.phase - beta;
            halfs[k] = psi * lit::<T>(0.5);
            turned[k] = beta + halfs[k];
        }
        let (mut s, mut c) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
        let (mut sb, mut cb) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
        crate::numeric::trig::sin_cos_block(&halfs, &mut s, &mut c);
        crate::numeric::trig::sin_cos_block(&turned, &mut sb, &mut cb);
        let (delta, sigma) = ((r1 - r2).abs(), r1 + r2);
        let four_gr = lit::<T>(4.0) * g * r;
        let (stretched, folded) = crate::mechanism::program::flat_products(g, r, r1, r2);
        let shrink = (g - r) / g;
        let two_r = lit::<T>(2.0) * r;
        let (lo, hi) = (
            lit::<T>(2.328_306_436_538_696_3e-10),
            lit::<T>(4_294_967_296.0),
        );
        let rmax = r1.max(r2);
        let tiny = tiny_square::<T>();
        for k in 0..BLOCK {
            // Q − A = gv·(g − r)/g + (sin, −cos)(β + ψ/2)·2r·sin(ψ/2).
            let qx = gv.x * shrink + sb[k] * (two_r * s[k]);
            let qy = gv.y * shrink + -cb[k] * (two_r * s[k]);
            let (x, y) = if b.crank_first { (qx, qy) } else { (-qx, -qy) };
            let n2 = x * x + y * y;
            let d = n2.sqrt();
            let stretch = (stretched + four_gr * c[k] * c[k]) / (sigma + d);
            let fold = (folded + four_gr * s[k] * s[k]) / (d + delta);
            let f2 = if d >= rmax { stretch } else { fold };
            let top = g.max(r).max(sigma).max(d);
            if use_base[k] {
                (dvx[k], dvy[k], dd[k], given[k]) = (x, y, d, f2);
                // Scales at which the scalar code's power-of-two units are not 1.
                scalar[k] |= n2 <= tiny || !n2.is_finite() || top > hi || top < lo;
            }
        }
    }
}

/// Velocities and accelerations of a block of posed samples (structure of arrays), by the
/// formulas of [`Mechanism::rates`] term for term for fixed joints, cranks, dyads and carried
/// points (a block never holds a slider).
pub(crate) struct BlockJointRates<T, const N: usize> {
    pub(crate) vx: [[T; BLOCK]; N],
    pub(crate) vy: [[T; BLOCK]; N],
    pub(crate) ax: [[T; BLOCK]; N],
    pub(crate) ay: [[T; BLOCK]; N],
    /// Whether every joint's velocity is finite (the motion's `regular`).
    pub(crate) regular: [bool; BLOCK],
    /// Samples whose rows the kernel cannot vouch for (a scale the scalar code would change):
    /// to be redone one by one.
    pub(crate) scalar: [bool; BLOCK],
}

impl<T: RealField + Copy, const N: usize> BlockJointRates<T, N> {
    /// An empty block.
    pub(crate) fn new() -> Self {
        let z = [[T::zero(); BLOCK]; N];
        BlockJointRates {
            vx: z,
            vy: z,
            ax: z,
            ay: z,
            regular: [true; BLOCK],
            scalar: [false; BLOCK],
        }
    }

    /// Rates of the posed block `pos` for the drive `(omega, alpha)` per sample.
    #[inline(always)]
    pub(crate) fn rates(
        &mut self,
        mech: &Mechanism<T, N>,
        pos: &BlockPoses<T, N>,
        omega: &[T; BLOCK],
        alpha: &[T; BLOCK],
    ) {
        let zero = [T::zero(); BLOCK];
        let m_star = crate::mechanism::joint_rates::rate_margin::<T>();
        let (lo, hi) = (
            lit::<T>(2.328_306_436_538_696_3e-10),
            lit::<T>(4_294_967_296.0),
        );
        self.regular = [true; BLOCK];
        self.scalar = [false; BLOCK];
        for (i, step) in mech.constructions().iter().enumerate() {
            let (px, py) = (pos.x[i], pos.y[i]);
            let (mut vx, mut vy, mut ax, mut ay) = (zero, zero, zero, zero);
            match *step {
                Construction::Fixed { .. } | Construction::Slider { .. } => {}
                Construction::Crank { centre: c, .. } => {
                    let (cx, cy) = (pos.x[c], pos.y[c]);
                    let (cvx, cvy, cax, cay) = (self.vx[c], self.vy[c], self.ax[c], self.ay[c]);
                    for k in 0..BLOCK {
                        let (rx, ry) = (px[k] - cx[k], py[k] - cy[k]);
                        let (w, al) = (omega[k], alpha[k]);
                        // carried: origin + perp(r)·ω, origin + perp(r)·α − r·ω².
                        vx[k] = cvx[k] + -ry * w;
                        vy[k] = cvy[k] + rx * w;
                        ax[k] = cax[k] + -ry * al - rx * (w * w);
                        ay[k] = cay[k] + rx * al - ry * (w * w);
                    }
                }
                Construction::Dyad { p1, p2, dyad, .. } => {
                    let (x1, y1, x2, y2) = (pos.x[p1], pos.y[p1], pos.x[p2], pos.y[p2]);
                    let (v1x, v1y, v2x, v2y) = (self.vx[p1], self.vy[p1], self.vx[p2], self.vy[p2]);
                    let (a1x, a1y, a2x, a2y) = (self.ax[p1], self.ay[p1], self.ax[p2], self.ay[p2]);
                    let bound = m_star * dyad.r1 * dyad.r2;
                    let (mut scalar, mut any) = ([false; BLOCK], false);
                    for k in 0..BLOCK {
                        let (e1x, e1y) = (px[k] - x1[k], py[k] - y1[k]);
                        let (e2x, e2y) = (px[k] - x2[k], py[k] - y2[k]);
                        let amax = e1x.abs().max(e1y.abs()).max(e2x.abs()).max(e2y.abs());
                        scalar[k] = amax > hi || amax < lo;
                        any |= scalar[k];
                        let det = e1x * e2y - e1y * e2x;
                        let ok = det.abs() >= bound && det != T::zero() && det.is_finite();
                        let b1 = e1x * v1x[k] + e1y * v1y[k];
                        let b2 = e2x * v2x[k] + e2y * v2y[k];
                        let inv = T::one() / det;
                        let wx = (b1 * e2y - b2 * e1y) * inv;
                        let wy = (e1x * b2 - e2x * b1) * inv;
                        let (w1x, w1y) = (wx - v1x[k], wy - v1y[k]);
                        let (w2x, w2y) = (wx - v2x[k], wy - v2y[k]);
                        let c1 = (e1x * a1x[k] + e1y * a1y[k]) - (w1x * w1x + w1y * w1y);
                        let c2 = (e2x * a2x[k] + e2y * a2y[k]) - (w2x * w2x + w2y * w2y);
                        let nan = T::zero() / T::zero();
                        vx[k] = if ok { wx } else { nan };
                        vy[k] = if ok { wy } else { nan };
                        ax[k] = if ok { (c1 * e2y - c2 * e1y) * inv } else { nan };
                        ay[k] = if ok { (e1x * c2 - e2x * c1) * inv } else { nan };
                    }
                    merge(&mut self.scalar, &scalar, any);
                }
                Construction::Point { from, to, .. } => {
                    let (fx, fy, tx, ty) = (pos.x[from], pos.y[from], pos.x[to], pos.y[to]);
                    let (fvx, fvy, fax, fay) =
                        (self.vx[from], self.vy[from], self.ax[from], self.ay[from]);
                    let (tvx, tvy, tax, tay) = (self.vx[to], self.vy[to], self.ax[to], self.ay[to]);
                    let two = lit::<T>(2.0);
                    let (mut scalar, mut any) = ([false; BLOCK], false);
                    for k in 0..BLOCK {
                        // direction_rates(d, d1, d2): ω = (d × d1)/|d|², α = (d × d2 − 2ω(d·d1))/|d|².
                        let (dx, dy) = (tx[k] - fx[k], ty[k] - fy[k]);
                        let (d1x, d1y) = (tvx[k] - fvx[k], tvy[k] - fvy[k]);
                        let (d2x, d2y) = (tax[k] - fax[k], tay[k] - fay[k]);
                        let amax = dx.abs().max(dy.abs());
                        scalar[k] = amax > hi || amax < lo;
                        any |= scalar[k];
                        let l2 = dx * dx + dy * dy;
                        let sd = dx * d1x + dy * d1y;
                        let inv = T::one() / l2;
                        let w = (dx * d1y - dy * d1x) * inv;
                        let n = dx * d2y - dy * d2x;
                        let al = (n - two * w * sd) * inv;
                        let (rx, ry) = (px[k] - fx[k], py[k] - fy[k]);
                        vx[k] = fvx[k] + -ry * w;
                        vy[k] = fvy[k] + rx * w;
                        ax[k] = fax[k] + -ry * al - rx * (w * w);
                        ay[k] = fay[k] + rx * al - ry * (w * w);
                    }
                    merge(&mut self.scalar, &scalar, any);
                }
            }
            // Marked in a fresh array and merged only when some sample is marked (see `merge`).
            let (mut irregular, mut any) = ([false; BLOCK], false);
            for k in 0..BLOCK {
                irregular[k] = !(vx[k].is_finite() & vy[k].is_finite());
                any |= irregular[k];
            }
            if any {
                for (r, &bad) in self.regular.iter_mut().zip(&irregular) {
                    *r &= !bad;
                }
            }
            (self.vx[i], self.vy[i], self.ax[i], self.ay[i]) = (vx, vy, ax, ay);
        }
    }
}

#[cfg(test)]
mod timing {
    use super::*;

    #[test]
    #[ignore = "timing helper"]
    fn block_pose_timing() {
        use crate::constructions::dyad::Side;
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
                    blk.pose(mech, &padded(c), &watched[..mech.len()]);
                    sum += blk.x[mech.len() - 1][0];
                }
                best = best.min(t.elapsed().as_secs_f64());
            }
            std::println!("{name}: {:.2} ns/sample ({sum})", best * 1e9 / n as f64);
        }
    }
}
