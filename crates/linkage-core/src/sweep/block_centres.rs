//! The held pass's instant centres and path curvatures, a block of samples at a time: the
//! formulas of [`BodyMotion::of`](crate::motion::centres::BodyMotion::of),
//! [`instant_centre`](crate::motion::centres::instant_centre) and
//! [`path_curvature`](crate::motion::centres::path_curvature) term for term, over [`BLOCK`] posed
//! samples in straight loops the compiler vectorises — so each sample gets the bits that the
//! sample-by-sample sweep gives it.
//!
//! Rates are per unit crank angle (a [`BlockJointRates`] for the drive `ω = 1, α = 0`). Which pair
//! of bodies shares a joint is looked up once a block, not once a sample.
//!
//! # What a block does not do itself
//! The scalar code rescales by powers of two where a length, speed or acceleration is outside
//! `[2⁻³², 2³²]` (or its square is not a normal number); a sample that reaches such a branch is
//! marked in [`BlockCentres::scalar`] and its block is redone one sample at a time.

use nalgebra::RealField;

use crate::mechanism::bodies::{Bodies, BodyFrame, BodyId, GROUND};
use crate::motion::centres::ZERO_RATE;
use crate::numeric::pow2::unit_scale;
use crate::numeric::scalar::{eps, lit, nan, size, tiny_square, Vec2};
use crate::sweep::block_poses::{merge, BlockJointRates, BlockPoses, BLOCK};
use crate::sweep::layout::{Columns, Pairs};

/// `length` of `(x, y)` as the scalar code forms it in the common case, `√(x² + y²)`, and
/// whether the scalar code takes another branch whose result may differ (a square sum that is
/// not a normal number, for a vector that is not zero).
#[inline(always)]
fn length<T: RealField + Copy>(x: T, y: T, tiny: T) -> (T, bool) {
    let n2 = x * x + y * y;
    let plain = (n2.is_finite() && n2 > tiny) || (x == T::zero() && y == T::zero());
    (n2.sqrt(), !plain)
}

/// Writes `value(b)` into `out[start + b·stride]` for the first `m` samples `b` of a block: a
/// plain loop, inlined into the kernel (an iterator's `for_each` was not, and checked bounds at
/// every sample).
#[inline(always)]
fn scatter<V>(
    out: &mut [V],
    (start, stride): (usize, usize),
    m: usize,
    value: impl Fn(usize) -> V,
) {
    if m == 0 {
        return;
    }
    let out = &mut out[start..=start + (m - 1) * stride];
    for b in 0..m.min(BLOCK) {
        out[b * stride] = value(b);
    }
}

/// The unit-drive angular velocity of every body over a block, with its zero tolerance
/// conditioned on the sample's margin ([`BodyMotion::conditioned`](crate::motion::centres::BodyMotion::conditioned)).
pub(crate) struct BlockCentres<'p, T, const N: usize> {
    /// `ω` of body `(joint, slot)` per sample.
    w: [[[T; BLOCK]; 2]; N],
    /// Its tolerance for "no relative turn".
    tol: [[[T; BLOCK]; 2]; N],
    /// The ground's everything.
    zero: [T; BLOCK],
    /// Samples the kernel cannot vouch for (see the module): redo them one by one.
    pub(crate) scalar: [bool; BLOCK],
    /// The first [`PAIRS`] pairs of bodies asked for ([`pack`]ed; [`UNKNOWN`] for a body whose
    /// joint does not fit), and the joint each shares ([`NO_PIN`] if none), looked up once a
    /// sweep (4 KiB less stack than whole ids: firmware runs this too).
    ids: [[u16; 2]; PAIRS],
    pins: [u16; PAIRS],
    /// The pairs asked for.
    pairs: Pairs<'p>,
}

/// Body `id` in 16 bits: `2·joint + slot`, the ground [`GROUND_ID`]; [`UNKNOWN`] if it does
/// not fit.
#[inline(always)]
fn pack(id: BodyId) -> u16 {
    if id == GROUND {
        return GROUND_ID;
    }
    id.joint
        .checked_mul(2)
        .and_then(|j| j.checked_add(usize::from(id.slot)))
        .and_then(|v| u16::try_from(v).ok())
        .filter(|&v| v < UNKNOWN)
        .unwrap_or(UNKNOWN)
}

/// The body [`pack`] packed (not [`UNKNOWN`]).
#[inline(always)]
fn unpack(v: u16) -> BodyId {
    if v == GROUND_ID {
        GROUND
    } else {
        BodyId {
            joint: usize::from(v / 2),
            slot: u8::from(v % 2 == 1),
        }
    }
}

/// The ground, packed.
const GROUND_ID: u16 = u16::MAX;

/// Pairs of bodies whose shared joint is looked up once a sweep (further ones once a block).
const PAIRS: usize = 256;
/// A pair of bodies that shares no joint.
const NO_PIN: u16 = u16::MAX;
/// A pair whose joint is looked up once a block (an index that does not fit).
const UNKNOWN: u16 = u16::MAX - 1;

/// One body's motion over a block, borrowed: origin, velocity there, `ω`, tolerance.
struct Body<'a, T> {
    ox: &'a [T; BLOCK],
    oy: &'a [T; BLOCK],
    vx: &'a [T; BLOCK],
    vy: &'a [T; BLOCK],
    w: &'a [T; BLOCK],
    tol: &'a [T; BLOCK],
}

impl<'p, T: RealField + Copy, const N: usize> BlockCentres<'p, T, N> {
    /// An empty block for the bodies `bodies`, whose centres are asked for the pairs `pairs`.
    pub(crate) fn new(bodies: &Bodies<N>, pairs: Pairs<'p>) -> Self {
        let z = [[[T::zero(); BLOCK]; 2]; N];
        let (mut ids, mut pins) = ([[UNKNOWN; 2]; PAIRS], [NO_PIN; PAIRS]);
        pairs.each(bodies, |q, ka, kb| {
            if let (Some(id), Some(pin)) = (ids.get_mut(q), pins.get_mut(q)) {
                *id = [pack(ka), pack(kb)];
                *pin = match bodies.shared_joint(ka, kb) {
                    None => NO_PIN,
                    Some(j) => u16::try_from(j)
                        .ok()
                        .filter(|&j| j < UNKNOWN)
                        .unwrap_or(UNKNOWN),
                };
            }
        });
        BlockCentres {
            w: z,
            tol: z,
            zero: [T::zero(); BLOCK],
            scalar: [false; BLOCK],
            ids,
            pins,
            pairs,
        }
    }

    /// The joint bodies `ka` and `kb`, pair `q`, share.
    #[inline(always)]
    fn pin(&self, bodies: &Bodies<N>, q: usize, (ka, kb): (BodyId, BodyId)) -> Option<usize> {
        match self.pins.get(q) {
            Some(&NO_PIN) => None,
            Some(&j) if j != UNKNOWN => Some(usize::from(j)),
            _ => bodies.shared_joint(ka, kb),
        }
    }

    /// Angular velocities and tolerances of every body of the posed block `pos` from its
    /// unit-drive rates `unit` (a block holds no slider: every body but the ground is a link).
    /// Call [`Self::start`] first.
    #[inline(always)]
    pub(crate) fn bodies(
        &mut self,
        bodies: &Bodies<N>,
        pos: &BlockPoses<T, N>,
        unit: &BlockJointRates<T, N>,
    ) {
        let (one, e) = (T::one(), eps::<T>());
        let zr = lit::<T>(ZERO_RATE) * e;
        // conditioned(margin): the tolerance times 1/m², m = margin within [ε, 1], once a
        // sample for every body.
        let mut inv_m2 = [T::zero(); BLOCK];
        for (k, r) in inv_m2.iter_mut().enumerate() {
            let m = pos.margin[k].min(one).max(e);
            *r = one / (m * m);
        }
        for id in bodies.ids() {
            let BodyFrame::Link {
                origin: o,
                toward: t,
            } = bodies.frame(id)
            else {
                // The ground (a block frame would mean a slider, which blocks never hold).
                if id != GROUND {
                    self.scalar = [true; BLOCK];
                }
                continue;
            };
            // Marks in a fresh array, merged only when there is one (see `block_poses::merge`).
            let (mut w, mut tol) = ([T::zero(); BLOCK], [T::zero(); BLOCK]);
            let (mut scalar, mut any) = ([false; BLOCK], false);
            let (xo, yo, xt, yt) = (&pos.x[o], &pos.y[o], &pos.x[t], &pos.y[t]);
            let (vxo, vyo, vxt, vyt) = (&unit.vx[o], &unit.vy[o], &unit.vx[t], &unit.vy[t]);
            for k in 0..BLOCK {
                // direction_rates(d, d1, 0, 0) at unit scale: ω = (d × d1)/|d|².
                let (dx, dy) = (xt[k] - xo[k], yt[k] - yo[k]);
                let (d1x, d1y) = (vxt[k] - vxo[k], vyt[k] - vyo[k]);
                let l2 = dx * dx + dy * dy;
                let wk = (dx * d1y - dy * d1x) * (one / l2);
                // Sizes (max-abs), as `BodyMotion::of` takes them for the tolerance.
                let (lo, lt, ld) = (size(vxo[k], vyo[k]), size(vxt[k], vyt[k]), size(dx, dy));
                scalar[k] = !unit_scale(ld);
                any |= scalar[k];
                let scale = (lo + lt) / ld;
                tol[k] = zr * (wk.abs() + scale) * inv_m2[k];
                w[k] = wk;
            }
            let s = usize::from(id.slot);
            (self.w[id.joint][s], self.tol[id.joint][s]) = (w, tol);
            merge(&mut self.scalar, &scalar, any);
        }
    }

    /// Clears the marks of the block before.
    pub(crate) fn start(&mut self) {
        self.scalar = [false; BLOCK];
    }

    /// The motion of body `id` (after [`Self::bodies`]).
    #[inline(always)]
    fn body<'a>(
        &'a self,
        bodies: &Bodies<N>,
        id: BodyId,
        pos: &'a BlockPoses<T, N>,
        unit: &'a BlockJointRates<T, N>,
    ) -> Body<'a, T> {
        match bodies.frame(id) {
            BodyFrame::Link { origin, .. } if id != GROUND => Body {
                ox: &pos.x[origin],
                oy: &pos.y[origin],
                vx: &unit.vx[origin],
                vy: &unit.vy[origin],
                w: &self.w[id.joint][usize::from(id.slot)],
                tol: &self.tol[id.joint][usize::from(id.slot)],
            },
            _ => Body {
                ox: &self.zero,
                oy: &self.zero,
                vx: &self.zero,
                vy: &self.zero,
                w: &self.zero,
                tol: &self.zero,
            },
        }
    }

    /// Writes the instant centres of the pairs of bodies [`Self::new`] was given (`np` a
    /// sample, the order of [`Pairs::each`]) of the block's first `m` samples, from sample `k0`
    /// on: finite ones into `centres`, directions of those at infinity into `directions`, NaN
    /// otherwise.
    #[allow(
        clippy::too_many_arguments,
        reason = "the block, its bodies and where the centres go"
    )]
    #[inline(always)]
    pub(crate) fn centres(
        &mut self,
        bodies: &Bodies<N>,
        pos: &BlockPoses<T, N>,
        unit: &BlockJointRates<T, N>,
        (k0, m, np): (usize, usize, usize),
        mut centres: Option<&mut [Vec2<T>]>,
        mut directions: Option<&mut [Vec2<T>]>,
    ) {
        let nan_t = nan::<T>();
        let nan2 = Vec2::new(nan_t, nan_t);
        let tiny = tiny_square::<T>();
        let zr = lit::<T>(ZERO_RATE) * eps::<T>();
        for q in 0..np {
            let pair = match self.ids.get(q) {
                Some(&[a, b]) if a != UNKNOWN && b != UNKNOWN => Some((unpack(a), unpack(b))),
                _ => self.pairs.at(bodies, q),
            };
            let Some((ka, kb)) = pair else {
                continue;
            };
            let rows = (k0 * np + q, np);
            if let Some(jt) = self.pin(bodies, q, (ka, kb)) {
                // A pin: the centre is the joint.
                if let Some(c) = centres.as_deref_mut() {
                    scatter(c, rows, m, |b| Vec2::new(pos.x[jt][b], pos.y[jt][b]));
                }
                if let Some(d) = directions.as_deref_mut() {
                    scatter(d, rows, m, |_| nan2);
                }
                continue;
            }
            let (k, l) = (
                self.body(bodies, ka, pos, unit),
                self.body(bodies, kb, pos, unit),
            );
            let (mut cx, mut cy) = ([nan_t; BLOCK], [nan_t; BLOCK]);
            let (mut ex, mut ey) = ([nan_t; BLOCK], [nan_t; BLOCK]);
            let (mut dx, mut dy) = ([nan_t; BLOCK], [nan_t; BLOCK]);
            let (mut flat, mut any_flat) = ([false; BLOCK], false);
            for b in 0..BLOCK {
                // instant_centre(k, l) at p = k's origin.
                let (px, py) = (k.ox[b], k.oy[b]);
                let (rx, ry) = (px - k.ox[b], py - k.oy[b]);
                let (kvx, kvy) = (k.vx[b] + -ry * k.w[b], k.vy[b] + rx * k.w[b]);
                let (sx, sy) = (px - l.ox[b], py - l.oy[b]);
                let (lvx, lvy) = (l.vx[b] + -sy * l.w[b], l.vy[b] + sx * l.w[b]);
                let (dvx, dvy) = (kvx - lvx, kvy - lvy);
                let dw = k.w[b] - l.w[b];
                let finite = dvx.is_finite() & dvy.is_finite() & dw.is_finite();
                let parallel = dw.abs() <= k.tol[b] + l.tol[b];
                let at = finite & !parallel;
                let inv = T::one() / dw;
                (cx[b], cy[b]) = if at {
                    (px + -dvy * inv, py + dvx * inv)
                } else {
                    (nan_t, nan_t)
                };
                (dx[b], dy[b]) = (dvx, dvy);
                flat[b] = finite & parallel;
                any_flat |= flat[b];
            }
            // Centres at infinity (rare: a translating link, parallel cranks): their direction,
            // only in the blocks that have one.
            let (mut scalar, mut any) = ([false; BLOCK], false);
            if any_flat {
                for b in 0..BLOCK {
                    let (dvx, dvy) = (dx[b], dy[b]);
                    let (n, bn) = length(dvx, dvy, tiny);
                    let lk = size(k.vx[b], k.vy[b]);
                    let ll = size(l.vx[b], l.vy[b]);
                    scalar[b] = flat[b] & bn;
                    any |= scalar[b];
                    let still = n <= zr * (lk + ll) || n == T::zero();
                    let at_infinity = flat[b] & !still;
                    (ex[b], ey[b]) = if at_infinity {
                        (-dvy / n, dvx / n)
                    } else {
                        (nan_t, nan_t)
                    };
                }
            }
            if let Some(c) = centres.as_deref_mut() {
                scatter(c, rows, m, |b| Vec2::new(cx[b], cy[b]));
            }
            if let Some(d) = directions.as_deref_mut() {
                scatter(d, rows, m, |b| Vec2::new(ex[b], ey[b]));
            }
            merge(&mut self.scalar, &scalar, any);
        }
    }

    /// Writes the path curvature (into `kappa`) and centre of curvature (into `centres`) of
    /// the joints `columns` names, for the block's first `m` samples from sample `k0` on (`j`
    /// joints a sample for [`Columns::All`]).
    #[allow(
        clippy::too_many_arguments,
        reason = "the block, which joints, and where the curvatures go"
    )]
    #[inline(always)]
    pub(crate) fn curvature(
        &mut self,
        pos: &BlockPoses<T, N>,
        unit: &BlockJointRates<T, N>,
        columns: Columns,
        (k0, m, j): (usize, usize, usize),
        mut kappa: Option<&mut [T]>,
        mut centres: Option<&mut [Vec2<T>]>,
    ) {
        let nan_t = nan::<T>();
        let t = lit::<T>(16.0) * eps::<T>();
        let t2 = t * t;
        let (first, last, width) = match columns {
            Columns::All => (0, j, j),
            Columns::One(t) => (t, t + 1, 1),
        };
        for i in first..last {
            let (mut scalar, mut any) = ([false; BLOCK], false);
            let (px, py, vx, vy) = (&pos.x[i], &pos.y[i], &unit.vx[i], &unit.vy[i]);
            let (ax, ay) = (&unit.ax[i], &unit.ay[i]);
            let (mut kap, mut cx, mut cy) = ([nan_t; BLOCK], [nan_t; BLOCK], [nan_t; BLOCK]);
            for b in 0..BLOCK {
                let finite = px[b].is_finite()
                    & py[b].is_finite()
                    & vx[b].is_finite()
                    & vy[b].is_finite()
                    & ax[b].is_finite()
                    & ay[b].is_finite();
                let moving = finite & !(vx[b] == T::zero() && vy[b] == T::zero());
                let ordinary = unit_scale(vx[b].abs().max(vy[b].abs()))
                    & unit_scale(ax[b].abs().max(ay[b].abs()));
                scalar[b] = moving & !ordinary;
                any |= scalar[b];
                let v2 = vx[b] * vx[b] + vy[b] * vy[b];
                let c = vx[b] * ay[b] - vy[b] * ax[b];
                let speed = v2.sqrt();
                let k = c / (v2 * speed);
                let a2 = ax[b] * ax[b] + ay[b] * ay[b];
                let straight = c * c <= t2 * v2 * a2;
                let f = v2 / c;
                let (x, y) = (px[b] + -vy[b] * f, py[b] + vx[b] * f);
                let round = moving & !straight;
                kap[b] = if round {
                    k
                } else if moving {
                    T::zero()
                } else {
                    nan_t
                };
                let here = round & x.is_finite() & y.is_finite();
                (cx[b], cy[b]) = if here { (x, y) } else { (nan_t, nan_t) };
            }
            let (start, stride) = (k0 * width + (i - first), width);
            if let Some(out) = kappa.as_deref_mut() {
                scatter(out, (start, stride), m, |b| kap[b]);
            }
            if let Some(out) = centres.as_deref_mut() {
                scatter(out, (start, stride), m, |b| Vec2::new(cx[b], cy[b]));
            }
            merge(&mut self.scalar, &scalar, any);
        }
    }
}
