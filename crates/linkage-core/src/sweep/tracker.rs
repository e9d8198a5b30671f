//! Sweeping a mechanism over driver angles on a continuously tracked assembly branch.

use nalgebra::RealField;

use crate::error::{check_finite, Error};
use crate::mechanism::program::{Candidates, CrankRates, FlatParity, Mechanism};
use crate::numeric::scalar::{lit, Vec2};

/// Assembly margin (`sin γ`, see [`crate::DyadPose::margin`]) below which a dyad is "near a
/// toggle" and its branch is chosen by continuation rather than kept.
pub const DEFAULT_TOGGLE_MARGIN: f64 = 0.2;

/// Largest driver step (radians) taken while a dyad is near a toggle, by default: the fine grid
/// has the least power of two of points per turn that makes its step at most this (1024).
const DEFAULT_MAX_STEP: f64 = 1.0 / 128.0;

/// Fine grid steps per coarse step: away from toggles the canonical path steps 16 fine steps at
/// a time (2π/64 ≈ 0.098 rad with the default grid).
const COARSE: i64 = 16;

/// Bounds on the fine grid points per turn (powers of two, multiples of [`COARSE`]).
const MIN_FINE: i64 = 64;
const MAX_FINE: i64 = 1 << 20;

/// Where a sweep sample writes the rates it is asked for; absent buffers are not computed.
/// Higher rates need the lower ones (a jerk needs an acceleration and a velocity buffer).
///
/// ```
/// use linkage_core::{catalog, CrankRates, Error, Rates, Tracker, Vec2};
/// let m = catalog::hoecken::<f64>().mechanism();
/// let mut t = Tracker::new(&m).unwrap();
/// let (mut p, mut v, mut a) = ([Vec2::zeros(); 5], [Vec2::zeros(); 5], [Vec2::zeros(); 5]);
/// // At 2 rad/s the crank pin (10 from O) accelerates centripetally, 2²·10 toward O.
/// let drive = Some(CrankRates::new(2.0, 0.0));
/// t.step(0.0, drive, &mut p, Rates::acceleration(&mut v, &mut a)).unwrap();
/// assert!((a[2] - Vec2::new(-40.0, 0.0)).norm() < 1e-12);
/// // Rates need a drive to be rates of.
/// let r = t.step(0.0, None, &mut p, Rates::velocity(&mut v));
/// assert!(matches!(r, Err(Error::BufferLength { .. })));
/// ```
#[derive(Debug, Default)]
pub struct Rates<'a, T> {
    /// Joint velocities.
    pub velocity: Option<&'a mut [Vec2<T>]>,
    /// Joint accelerations.
    pub acceleration: Option<&'a mut [Vec2<T>]>,
    /// Joint jerks.
    pub jerk: Option<&'a mut [Vec2<T>]>,
}

impl<'a, T> Rates<'a, T> {
    /// Positions only.
    pub fn none() -> Self {
        Rates {
            velocity: None,
            acceleration: None,
            jerk: None,
        }
    }

    /// Velocities only.
    pub fn velocity(v: &'a mut [Vec2<T>]) -> Self {
        Rates {
            velocity: Some(v),
            acceleration: None,
            jerk: None,
        }
    }

    /// Velocities and accelerations.
    pub fn acceleration(v: &'a mut [Vec2<T>], a: &'a mut [Vec2<T>]) -> Self {
        Rates {
            velocity: Some(v),
            acceleration: Some(a),
            jerk: None,
        }
    }
}

/// Result of one sweep sample that assembled.
///
/// ```
/// use linkage_core::{catalog, InputRange, Rates, Tracker, Vec2};
/// // Evans C from θ = 0 to its input limit, where coupler and rocker are stretched flat.
/// let fb = catalog::evans_c::<f64>();
/// let InputRange::Between { hi, .. } = fb.input_range() else { unreachable!() };
/// let m = fb.mechanism();
/// let mut t = Tracker::new(&m).unwrap();
/// let mut p = [Vec2::zeros(); 5];
/// let s = t.step(0.0, None, &mut p, Rates::none()).unwrap();
/// assert!(s.regular && (s.margin - 0.75_f64.sqrt()).abs() < 1e-12); // a 60° triangle at B
/// let s = t.step(hi, None, &mut p, Rates::none()).unwrap();
/// assert!(!s.regular && s.margin < 1e-6); // at the toggle: rates would be NaN
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<T> {
    /// Smallest assembly margin of the mechanism's dyads at this sample (1 when it has none).
    pub margin: T,
    /// False when some joint is within the rate threshold of a toggle
    /// ([`crate::rate_margin`]), so its rates (and those of every joint built on it) are NaN.
    pub regular: bool,
}

/// A point of the driver's line in fine-grid units, `(idx + frac)·h` with `frac ∈ [0, 1)`;
/// grid points have `frac = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct At<T> {
    idx: i64,
    frac: T,
}

impl<T: RealField + Copy> At<T> {
    fn grid(idx: i64) -> Self {
        At {
            idx,
            frac: T::zero(),
        }
    }

    /// `self − other` in grid units.
    fn minus(&self, other: &Self) -> T {
        lit::<T>(self.idx.saturating_sub(other.idx) as f64) + (self.frac - other.frac)
    }

    /// Whether `self` lies strictly past `other` going in direction `dir` (±1).
    fn past(&self, other: &Self, dir: i64) -> bool {
        let ahead = self.idx > other.idx || (self.idx == other.idx && self.frac > other.frac);
        let behind = self.idx < other.idx || (self.idx == other.idx && self.frac < other.frac);
        if dir > 0 {
            ahead
        } else {
            behind
        }
    }

    fn on_coarse_grid(&self) -> bool {
        self.frac == T::zero() && self.idx.rem_euclid(COARSE) == 0
    }
}

/// How [`Tracker::place`] chooses each dyad's candidate.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Choice {
    /// Keep every orientation.
    Keep,
    /// Continuation: a dyad near a toggle takes the candidate nearest the extrapolated position.
    Continue,
    /// Keep every orientation, and report whether continuation would have flipped one.
    Probe,
}

/// Pairs of turns (`4π` each) beyond which a sample's turn count is kept modulo
/// `FAR_TURNS / 2` (`2³⁹` pairs, about `1.4·10¹³` rad): grid indices stay within `i64`.
const FAR_TURNS: u64 = 1 << 40;

/// Turns a jump walks looking for the period of the tracked state; a longer jump whose state has
/// not repeated by then is refused ([`Error::OutOfRange`]) rather than walked turn by turn.
const PERIOD_SEARCH: i64 = 1024;

/// The tracked state at a turn boundary, compared to find the period of a full-turn crank.
#[derive(Clone, Copy)]
struct Snapshot<T: RealField + Copy, const N: usize> {
    sign: [i8; N],
    older: [Vec2<T>; N],
    newest: [Vec2<T>; N],
    spacing: T,
    hist_margin: [T; N],
    nhist: u8,
    fine_here: bool,
}

impl<T: RealField + Copy, const N: usize> Snapshot<T, N> {
    /// Whether two states are the same, value for value, a NaN matching a NaN (a state holding
    /// one must still be seen to repeat).
    fn same(&self, other: &Self) -> bool {
        #[allow(clippy::eq_op, reason = "x != x is the NaN test for a generic float")]
        let eq = |a: T, b: T| a == b || (a != a && b != b);
        let pts = |a: &[Vec2<T>; N], b: &[Vec2<T>; N]| {
            a.iter().zip(b).all(|(p, q)| eq(p.x, q.x) && eq(p.y, q.y))
        };
        self.sign == other.sign
            && self.nhist == other.nhist
            && self.fine_here == other.fine_here
            && eq(self.spacing, other.spacing)
            && pts(&self.older, &other.older)
            && pts(&self.newest, &other.newest)
            && self
                .hist_margin
                .iter()
                .zip(&other.hist_margin)
                .all(|(&a, &b)| eq(a, b))
    }
}

/// Sweeps a [`Mechanism`] over driver angles, keeping each dyad on its assembly branch.
///
/// # Branch tracking
/// A dyad's branch is its orientation (the side of its base line its joint is on). The tracker
/// keeps each dyad's orientation, except near a toggle, where it continues the motion: the
/// candidate nearest the position extrapolated linearly from the two previous points of the
/// path is taken. At a bifurcation (a change-point linkage's flat position, a kite's crank pin
/// passing over the rocker pivot, a deltoid folding) this is the branch that continues
/// smoothly through it. A dyad built on a crank pin and a fixed joint (every four-bar's) knows
/// its flat positions in closed form ([`crate::FourBar::check_fixed_assembly_path`]): its
/// joint's signed height over the base has a simple zero there, so both branches through a
/// flat position change side exactly there and nowhere else, and the tracker flips its
/// orientation exactly at each one crossed — also for a sample a hair's breadth from it,
/// where the two candidates are too close for any extrapolation to tell apart (their rates are
/// not).
///
/// # The canonical path
/// Those decisions are made on a path fixed by the linkage alone, never by the caller's
/// sampling: the grid of `M` points per turn at absolute angles `2πk/M` (`M = 1024` by
/// default). From a sample, the tracker walks the grid toward the next sample, a coarse step
/// (16 grid steps, 0.098 rad) at a time where both ends of the step are clear of toggles (every
/// margin at least `toggle_margin`) and continuation would keep every orientation, and one grid
/// step at a time (6.1 mrad) elsewhere. A sample is then placed from the last grid point before
/// it, and it does not move the walk. So a sample's pose depends only on the linkage, the first
/// sample and the angles the path has run through: inserting or removing samples between two
/// samples never changes the branch at either. The first sample takes the branches the
/// constructions declare.
///
/// # Cost
/// The work is counted in placements (solves of every joint at one angle, [`Tracker::work`]):
/// at most 17 per coarse step and 1 per grid step, so a step of `Δθ` costs at most
/// `M·|Δθ|/2π + 2` placements. Grid angles are reduced to one turn exactly, so the walk of a
/// full-turn crank is periodic in the turn; a step of many turns walks turns only until the
/// state at a turn boundary repeats (Brent's cycle finding; one or two turns for a four-bar),
/// then skips whole periods: a jump of any size costs a bounded number of turns. A caller that
/// must stay responsive (Ctrl-C) steps a bounded number of samples at a time.
///
/// # Orientations in closed form
/// A mechanism whose every dyad is on a crank pin and a fixed joint and assembles over the
/// whole turn, with no slider (every four-bar whose crank turns fully: crank-rockers,
/// double-cranks, parallelograms, kites, deltoids and other change points;
/// `Mechanism::branches_in_closed_form`), has no choice left to the walk: an orientation turns
/// exactly at each flat position crossed — counted at every placement, near a toggle or not —
/// and at no other point. The count is a function of the angle (`Mechanism::flat_positions`),
/// so it telescopes along any path, and the tracker places each sample straight from the
/// first one (or from the start angle), one placement a sample, in any order: the walk's bits,
/// checked by a property test against the walk itself.
///
/// # Large angles
/// Every angle is reduced exactly to two turns before it is used ([`crate::reduce_angle`]: crank pins,
/// flat-position parities, the grid point before a sample), so a sample at `θ = 10³⁰⁰` gets the
/// pose of `θ mod 2π` to rounding. Up to `2⁴⁰` pairs of turns (`|θ| ≲ 1.4·10¹³` rad) the grid
/// index is exact. Beyond, a sample's turn count is replaced by a representative congruent to
/// it modulo `2⁴⁰` turns and at least `2⁴¹` turns from the origin, on the same side: exact
/// when the tracked state's period in turns divides `2⁴⁰` (every period that is a power of
/// two, one turn for every catalogue linkage); a jump there whose state has another period is
/// refused ([`Error::OutOfRange`]). Two such samples are walked between by their
/// representatives, which differ by the true difference modulo `2⁴⁰` turns.
///
/// A grid point where a construction is undetermined (a kite's crank pin exactly on the rocker
/// pivot) is stepped over. A sample that cannot assemble writes NaN joints, returns its error
/// and changes nothing else. A path that cannot be walked (a locked zone lies between two
/// samples) restarts at the new sample on the orientations of the last sample that assembled.
///
/// ```
/// use linkage_core::{Assembly, FourBar, Rates, Tracker, Vec2};
/// let fb = FourBar::new(20.0_f64, 10.0, 25.0, 25.0, (50.0, 0.0), Assembly::Open).unwrap();
/// let m = fb.mechanism();
/// let mut t = Tracker::new(&m).unwrap();
/// let mut joints = [Vec2::zeros(); 5];
/// for k in 0..4 {
///     // 100° steps: far from any toggle, the orientation is simply kept.
///     let s = t.step(1.745 * k as f64, None, &mut joints, Rates::none()).unwrap();
///     assert!(s.margin > 0.1);
/// }
/// // A jump of a billion radians costs one placement: a crank-rocker's orientation is known
/// // in closed form. (Where the walk is needed it costs a few turns, not 10⁸ of them.)
/// let before = t.work();
/// t.step(1e9, None, &mut joints, Rates::none()).unwrap();
/// assert_eq!(t.work() - before, 1, "one placement");
/// ```
#[derive(Clone, Debug)]
pub struct Tracker<'m, T: RealField + Copy, const N: usize> {
    mech: &'m Mechanism<T, N>,
    /// Orientation of each branch joint, `+1` or `-1` (compact, as it is saved per step).
    sign: [i8; N],
    /// `hist[newest]`: the walk's last point (the cursor), `hist[1 - newest]`: the one before
    /// (a two-slot ring, so committing a point copies only the mechanism's joints).
    hist: [[Vec2<T>; N]; 2],
    newest: usize,
    hist_at: [At<T>; 2],
    /// Driver angles of the history points (not reduced: flat positions are counted on them).
    hist_theta: [T; 2],
    hist_margin: [T; N],
    /// Margins of the joints as last placed (committed into `hist_margin` with the point).
    placed_margin: [T; N],
    nhist: u8,
    /// Orientations of the last sample that assembled: a path that cannot be walked restarts
    /// on them.
    held: [i8; N],
    /// Whether the cursor is inside a coarse step walked one grid step at a time.
    fine_here: bool,
    /// A coarse grid point the cursor is known to reach by one clear coarse step.
    clear_to: Option<i64>,
    toggle_margin: T,
    /// Grid points per turn.
    fine: i64,
    work: u64,
    /// The flat positions of each dyad on a crank pin and a fixed joint
    /// ([`Mechanism::flat_positions`], formed once): its orientation turns at those crossed,
    /// counted in closed form at every placement, near a toggle or not; it has none to turn at
    /// where both are absent.
    parity: [Option<FlatParity<T>>; N],
    /// Whether every orientation is a function of the angle ([`Mechanism::branches_in_closed_form`]):
    /// samples are then placed from the first one with no walk between.
    closed_form: bool,
    /// Whether the sample being placed is beyond `FAR_TURNS` pairs of turns, its turn count
    /// known modulo a power of two only (`at_of`).
    far: bool,
}

impl<'m, T: RealField + Copy, const N: usize> Tracker<'m, T, N> {
    /// A tracker starting on the branches the constructions declare.
    ///
    /// # Errors
    /// [`Error::NoDriver`] if the mechanism has no crank.
    pub fn new(mech: &'m Mechanism<T, N>) -> Result<Self, Error> {
        Self::with_settings(mech, lit(DEFAULT_TOGGLE_MARGIN), lit(DEFAULT_MAX_STEP))
    }

    /// A tracker with explicit continuation settings: `toggle_margin` in `[0, 1)`, `max_step`
    /// (radians, > 0) the longest grid step: the grid has the least power of two of points per
    /// turn (from 64 to 2²⁰) that makes its step at most `max_step`.
    ///
    /// # Errors
    /// [`Error::NoDriver`]; [`Error::NotFinite`] / [`Error::InvalidLength`] for bad settings.
    pub fn with_settings(
        mech: &'m Mechanism<T, N>,
        toggle_margin: T,
        max_step: T,
    ) -> Result<Self, Error> {
        if mech.driver().is_none() {
            return Err(Error::NoDriver);
        }
        check_finite("toggle_margin", toggle_margin)?;
        crate::error::check_length("max_step", max_step)?;
        let want = crate::numeric::scalar::to_f64(T::two_pi() / max_step);
        let mut fine = MIN_FINE;
        while (fine as f64) < want && fine < MAX_FINE {
            fine *= 2;
        }
        let mut sign = [1i8; N];
        for (s, c) in sign.iter_mut().zip(mech.constructions()) {
            *s = if c.initial_sign() < T::zero() { -1 } else { 1 };
        }
        let mut parity = [None; N];
        for (i, p) in parity.iter_mut().enumerate().take(mech.len()) {
            *p = mech.flat_positions(i);
        }
        Ok(Tracker {
            mech,
            sign,
            hist: [[Vec2::zeros(); N]; 2],
            newest: 0,
            hist_at: [At::grid(0); 2],
            hist_theta: [T::zero(); 2],
            hist_margin: [T::one(); N],
            placed_margin: [T::one(); N],
            nhist: 0,
            held: sign,
            fine_here: false,
            clear_to: None,
            toggle_margin,
            fine,
            work: 0,
            parity,
            closed_form: mech.branches_in_closed_form(),
            far: false,
        })
    }

    /// Current orientation of joint `i`: `+1` for [`crate::Side::Left`] / [`crate::Reach::Ahead`],
    /// `-1` for the other, `+1` for joints without a branch (and for an index beyond `N`).
    pub fn branch(&self, i: usize) -> T {
        if self.sign.get(i).is_some_and(|&s| s < 0) {
            -T::one()
        } else {
            T::one()
        }
    }

    /// Forces the orientation of joint `i` (`+1` / `-1`) and forgets the motion history, so the
    /// next sample starts afresh there. Used to pass to the other branch at a toggle, as a
    /// circuit sweep does.
    /// An index beyond `N` changes nothing.
    pub fn set_branch(&mut self, i: usize, sign: T) {
        if let Some(s) = self.sign.get_mut(i) {
            *s = if sign < T::zero() { -1 } else { 1 };
            self.held = self.sign;
            self.nhist = 0;
        }
    }

    /// Placements done so far: solves of every joint at one angle, the unit of the tracker's
    /// work (samples and the grid points walked between them). A deterministic count, for
    /// bounding cost in tests where a clock would not be.
    pub fn work(&self) -> u64 {
        self.work
    }

    /// Grid points per turn of the canonical path.
    pub fn grid_points_per_turn(&self) -> usize {
        self.fine as usize
    }

    /// Whether the orientations held now (those the constructions declare, on a new tracker)
    /// are what every sample gets, whatever the samples: every grid point of the turn places
    /// on them, with the margin of every dyad that may flip ([`Mechanism::may_flip`], marked
    /// in `watched`) at least the toggle margin.
    ///
    /// Why that suffices, for samples whose own watched margins clear the toggle margin too: a
    /// placement changes an orientation only for a dyad that may flip and is near a toggle (its
    /// margin, or its margin at the previous point of the walk, below the toggle margin). The
    /// walk places only grid points and the samples; by induction on the placements, every one
    /// is made on the held orientations, so its margins are the ones checked here — no watched
    /// dyad is near, none flips (a coarse probe that would flip only makes the walk take grid
    /// steps, which keep). So each sample's pose is [`Mechanism::pose`] at its angle, bit for
    /// bit. Costs one pose per grid point (`M`, 1024 by default).
    pub(crate) fn holds_everywhere(&self, scratch: &mut [Vec2<T>], watched: &mut [bool]) -> bool {
        let held = self
            .sign
            .iter()
            .zip(self.mech.constructions())
            .all(|(&s, c)| (s < 0) == (c.initial_sign() < T::zero()));
        for (i, w) in watched.iter_mut().enumerate() {
            *w = self.mech.may_flip(i);
        }
        // A dyad with flat positions turns there, whatever the margins on the grid.
        let no_flats = !self.parity.iter().flatten().any(FlatParity::any);
        held && no_flats
            && (0..self.fine).all(|idx| {
                matches!(
                    self.mech.pose_watched(self.grid_angle(idx), scratch, watched),
                    Ok((_, m)) if m >= self.toggle_margin
                )
            })
    }

    /// Whether every orientation is a function of the driver angle, known in closed form
    /// (see the type's docs): samples are placed from the reference angle with no walk.
    pub(crate) fn closed_form(&self) -> bool {
        self.closed_form
    }

    /// The assembly margin below which a dyad is near a toggle.
    pub(crate) fn toggle_margin(&self) -> T {
        self.toggle_margin
    }

    /// The grid step `h = 2π/M`.
    fn h(&self) -> T {
        T::two_pi() / lit::<T>(self.fine as f64)
    }

    /// Driver angle of grid point `idx`, reduced to one turn exactly (so the walk of a
    /// full-turn crank repeats bit for bit from turn to turn).
    fn grid_angle(&self, idx: i64) -> T {
        lit::<T>(idx.rem_euclid(self.fine) as f64) * self.h()
    }

    /// Driver angle of grid point `idx` along the path, for the parity of the flat positions
    /// passed: `idx·h` near the origin, else reduced to two turns exactly (the parity's
    /// period), as [`crate::numeric::turns::reduce`] reduces a sample's angle.
    fn grid_path_angle(&self, idx: i64) -> T {
        let two_turns = self.fine.saturating_mul(2);
        let angle = lit::<T>(idx as f64) * self.h();
        if angle.abs() < lit::<T>(crate::numeric::turns::REDUCE_FROM) {
            angle
        } else {
            lit::<T>(idx.rem_euclid(two_turns) as f64) * self.h()
        }
    }

    /// Where `theta` lies on the grid: from its exact reduction `θ = 4π·k + θ'`
    /// ([`crate::numeric::turns::split`]) at large angles, so the grid point before a sample is the one
    /// its pose is computed at. Beyond [`FAR_TURNS`] pairs of turns, `k` is replaced by a
    /// representative congruent to it modulo `FAR_TURNS / 2` and at least `FAR_TURNS` in size,
    /// with its sign (see [`Tracker`]'s docs); the second value says so.
    fn at_of(&self, theta: T) -> (At<T>, bool) {
        let (k, reduced) = crate::numeric::turns::split(theta);
        let h = self.h();
        let u = reduced / h;
        let fl = u.floor();
        let j = fl.to_subset().unwrap_or(0.0);
        if reduced == theta || !theta.is_finite() {
            // Small (or not finite: refused by the callers).
            let bound = 4.0e18;
            let idx = j.max(-bound).min(bound) as i64;
            return (At { idx, frac: u - fl }, false);
        }
        let negative = theta < T::zero();
        let magnitude = if negative { k.wrapping_neg() } else { k };
        let far = magnitude >= FAR_TURNS;
        let pairs = if far {
            FAR_TURNS + (magnitude & (FAR_TURNS / 2 - 1))
        } else {
            magnitude
        } as i64;
        let pairs = if negative { -pairs } else { pairs };
        let idx = pairs
            .saturating_mul(self.fine.saturating_mul(2))
            .saturating_add(j as i64);
        (At { idx, frac: u - fl }, far)
    }

    /// Solves every joint at `theta` (the point `at` of the path, at driver angle `path` before
    /// reduction to one turn) into `joints`, choosing
    /// branches as `choice` says. Returns the smallest margin and, for [`Choice::Probe`],
    /// whether continuation would flip a dyad.
    fn place(
        &mut self,
        theta: T,
        path: T,
        at: At<T>,
        choice: Choice,
        joints: &mut [Vec2<T>],
    ) -> Result<(T, bool), Error> {
        self.work = self.work.saturating_add(1);
        // Reduced once here rather than by every construction ([`crate::numeric::turns`]).
        let theta = crate::numeric::turns::reduce(theta);
        let mech = self.mech;
        let mut margin = T::one();
        let mut would_flip = false;
        let (new, old) = (self.newest, 1 - self.newest);
        let ratio = {
            let den = self.hist_at[new].minus(&self.hist_at[old]);
            if den != T::zero() {
                at.minus(&self.hist_at[new]) / den
            } else {
                T::zero()
            }
        };
        for i in 0..mech.len() {
            joints[i] = match mech.candidates(i, theta, joints, T::zero())? {
                Candidates::One(p) => p,
                Candidates::Two {
                    foot,
                    offset,
                    margin: m,
                } => {
                    margin = margin.min(m);
                    self.placed_margin[i] = m;
                    let mut s = if self.sign[i] < 0 {
                        -T::one()
                    } else {
                        T::one()
                    };
                    let near = m < self.toggle_margin || self.hist_margin[i] < self.toggle_margin;
                    let test = match choice {
                        Choice::Keep => false,
                        Choice::Continue => near,
                        Choice::Probe => true,
                    };
                    // A dyad on a crank pin and a fixed joint knows its flat positions exactly:
                    // both branches through one change side there, and only there.
                    // Counted at every placement, near a toggle or not: a grid step can cross
                    // one with both ends clear of the toggle margin (a fast-turning dyad).
                    // Whether an odd number of flat positions lies between the last point
                    // and here (None for a dyad not on a crank pin and a fixed joint).
                    let flats = match self.parity[i] {
                        Some(p) if (test || p.any()) && self.nhist >= 1 => {
                            Some(p.any() && p.at(self.hist_theta[new]) != p.at(path))
                        }
                        _ => None,
                    };
                    if let Some(odd) = flats {
                        if odd {
                            if choice == Choice::Probe {
                                would_flip = true;
                            } else {
                                s = -s;
                                self.sign[i] = -self.sign[i];
                            }
                        }
                    } else if test && self.nhist >= 2 {
                        let prev = self.hist[new][i];
                        let predicted = prev + (prev - self.hist[old][i]) * ratio;
                        let kept = foot + offset * s - predicted;
                        let flipped = foot - offset * s - predicted;
                        // Squared distances of a linkage at 1e±300 would underflow to 0 or
                        // overflow to ∞ and tie: compare them in units of a power of two near
                        // the larger (exact, and no change for ordinary sizes).
                        let unit =
                            crate::numeric::pow2::pow2_scale(kept.amax().max(flipped.amax()));
                        let (kept, flipped) = if unit == T::one() {
                            (kept, flipped)
                        } else {
                            (kept / unit, flipped / unit)
                        };
                        if flipped.norm_squared() < kept.norm_squared() {
                            if choice == Choice::Continue {
                                s = -s;
                                self.sign[i] = -self.sign[i];
                            } else {
                                would_flip = true;
                            }
                        }
                    }
                    foot + offset * s
                }
            };
        }
        Ok((margin, would_flip))
    }

    /// Records a placed point of the path as the newest history entry (the cursor).
    fn commit(&mut self, at: At<T>, theta: T, joints: &[Vec2<T>]) {
        let n = self.mech.len();
        self.newest = 1 - self.newest;
        self.hist[self.newest][..n].copy_from_slice(joints);
        self.hist_at[self.newest] = at;
        self.hist_theta[self.newest] = theta;
        self.nhist = (self.nhist + 1).min(2);
        self.hist_margin[..n].copy_from_slice(&self.placed_margin[..n]);
        self.clear_to = None;
    }

    /// Smallest margin of the dyads at the cursor.
    fn cursor_margin(&self) -> T {
        self.hist_margin[..self.mech.len()]
            .iter()
            .fold(T::one(), |a, &b| a.min(b))
    }

    /// Walks the canonical path from the cursor to the last path point not past `target`.
    /// Returns whether the stretch holding `target` is walked in grid steps (so a sample there
    /// is placed by continuation) rather than a clear coarse step (orientations kept).
    fn walk_to(&mut self, target: At<T>) -> Result<bool, Error> {
        let mut scratch = [Vec2::zeros(); N];
        let n = self.mech.len();
        loop {
            let c = self.hist_at[self.newest];
            if c == target {
                return Ok(false);
            }
            let dir: i64 = if target.past(&c, 1) { 1 } else { -1 };
            if self.fine_here {
                let mut next = At::grid(if dir > 0 {
                    c.idx.saturating_add(1)
                } else if c.frac > T::zero() {
                    c.idx
                } else {
                    c.idx.saturating_sub(1)
                });
                if next.past(&target, dir) {
                    return Ok(true);
                }
                let th = self.grid_angle(next.idx);
                let path = self.grid_path_angle(next.idx);
                if let Err(e) = self.place(th, path, next, Choice::Continue, &mut scratch[..n]) {
                    // A grid point where a construction is undetermined (a kite's crank pin
                    // exactly on the rocker pivot) is stepped over: the motion is continuous
                    // through it, only that instant's dyad is not.
                    if !matches!(e, Error::Coincident { .. }) {
                        return Err(e);
                    }
                    next = At::grid(next.idx.saturating_add(dir));
                    if next.past(&target, dir) {
                        return Ok(true);
                    }
                    let th = self.grid_angle(next.idx);
                    let path = self.grid_path_angle(next.idx);
                    self.place(th, path, next, Choice::Continue, &mut scratch[..n])?;
                }
                self.commit(next, self.grid_path_angle(next.idx), &scratch[..n]);
                if next.on_coarse_grid() {
                    self.fine_here = false;
                }
                continue;
            }
            let turns = target.idx.saturating_sub(c.idx).saturating_abs() / self.fine;
            if turns > 2 && c.on_coarse_grid() && self.nhist > 0 {
                self.jump(dir, turns - 1)?;
                continue;
            }
            // The coarse grid point ahead, strictly.
            let e = {
                let base = c.idx.div_euclid(COARSE).saturating_mul(COARSE);
                if dir > 0 {
                    At::grid(base.saturating_add(COARSE))
                } else if c.on_coarse_grid() {
                    At::grid(base.saturating_sub(COARSE))
                } else {
                    At::grid(base)
                }
            };
            let th = self.grid_angle(e.idx);
            let known = self.clear_to == Some(e.idx);
            if known && e.past(&target, dir) {
                return Ok(false);
            }
            let path = self.grid_path_angle(e.idx);
            let probe = self.place(th, path, e, Choice::Probe, &mut scratch[..n]);
            let (m, flip) = match probe {
                Ok(r) => r,
                // Undetermined there: walk the stretch in grid steps, which step over it.
                Err(Error::Coincident { .. }) => (T::zero(), true),
                Err(e) => return Err(e),
            };
            let clear = known
                || (!flip && m >= self.toggle_margin && self.cursor_margin() >= self.toggle_margin);
            if clear {
                if e.past(&target, dir) {
                    self.clear_to = Some(e.idx);
                    return Ok(false);
                }
                self.commit(e, path, &scratch[..n]);
                continue;
            }
            self.fine_here = true;
        }
    }

    /// The state at a turn boundary, relative to the turn.
    fn snapshot(&self) -> Snapshot<T, N> {
        let (new, old) = (self.newest, 1 - self.newest);
        Snapshot {
            sign: self.sign,
            older: self.hist[old],
            newest: self.hist[new],
            spacing: self.hist_at[new].minus(&self.hist_at[old]),
            hist_margin: self.hist_margin,
            nhist: self.nhist,
            fine_here: self.fine_here,
        }
    }

    /// Walks `turns` whole turns in direction `dir` from a coarse grid point, walking only
    /// until the state at a turn boundary repeats and skipping whole periods after that.
    fn jump(&mut self, dir: i64, turns: i64) -> Result<(), Error> {
        let turn = dir.saturating_mul(self.fine);
        let walk_turn = |t: &mut Self| -> Result<(), Error> {
            let to = At::grid(t.hist_at[t.newest].idx.saturating_add(turn));
            t.walk_to(to).map(|_| ())
        };
        let mut left = turns;
        let mut tortoise = self.snapshot();
        walk_turn(self)?;
        left -= 1;
        // Brent's cycle finding on the states at turn boundaries.
        let (mut power, mut lam) = (1i64, 1i64);
        let mut period = None;
        let mut walked = 1i64;
        while left > 0 {
            if self.snapshot().same(&tortoise) {
                period = Some(lam);
                break;
            }
            if walked >= PERIOD_SEARCH {
                break;
            }
            if power == lam {
                tortoise = self.snapshot();
                power = power.saturating_mul(2);
                lam = 0;
            }
            walk_turn(self)?;
            left -= 1;
            lam += 1;
            walked += 1;
        }
        if let Some(p) = period {
            if self.far && !p.unsigned_abs().is_power_of_two() {
                // The target's turn count is known modulo a power of two only (`at_of`): a
                // period that does not divide it cannot be skipped exactly.
                return Err(Error::OutOfRange {
                    what: "turns in the period of a tracked state that is not a power of two, \
                           jumping beyond 2^40 turns",
                    value: usize::try_from(p).unwrap_or(usize::MAX),
                    max: 1,
                });
            }
            let skip = left / p * p;
            let shift = skip.saturating_mul(turn);
            for at in self.hist_at.iter_mut() {
                at.idx = at.idx.saturating_add(shift);
            }
            left -= skip;
        } else if left > PERIOD_SEARCH {
            // A state that does not repeat (rounding that drifts from turn to turn): walking
            // the rest would take time in proportion to the jump.
            return Err(Error::OutOfRange {
                what: "turns of a jump whose tracked state does not repeat",
                value: usize::try_from(turns).unwrap_or(usize::MAX),
                max: usize::try_from(2 * PERIOD_SEARCH).unwrap_or(usize::MAX),
            });
        }
        for _ in 0..left {
            walk_turn(self)?;
        }
        Ok(())
    }

    /// Solves the sample at driver angle `theta`, writing joint positions into `joints` and,
    /// for each buffer `rates` holds, velocities, accelerations and jerks for the driver
    /// `motion` (each slice [`Mechanism::len`] long). Rates not asked for are not computed.
    ///
    /// # Errors
    /// [`Error::CannotAssemble`] / [`Error::Coincident`] when the sample cannot be assembled
    /// (the slices are filled with NaN); [`Error::NotFinite`] for a non-finite angle or motion;
    /// [`Error::BufferLength`] for wrong slices, or rates requested without a motion;
    /// [`Error::OutOfRange`] for a jump of more than 2048 turns whose tracked state does not
    /// repeat within 1024 of them (rounding that drifts from turn to turn), rather than a walk
    /// as long as the jump.
    pub fn step(
        &mut self,
        theta: T,
        motion: Option<CrankRates<T>>,
        joints: &mut [Vec2<T>],
        rates: Rates<'_, T>,
    ) -> Result<Sample<T>, Error> {
        let n = self.mech.len();
        if joints.len() != n {
            return Err(Error::BufferLength {
                what: "joints",
                expected: n,
                got: joints.len(),
            });
        }
        let nan = Vec2::new(
            crate::numeric::scalar::nan::<T>(),
            crate::numeric::scalar::nan::<T>(),
        );
        let Rates {
            velocity,
            acceleration,
            jerk,
        } = rates;
        let result = check_finite("crank angle", theta).and_then(|_| self.advance(theta, joints));
        let margin = match result {
            Ok(m) => m,
            Err(e) => {
                // The walk is left as it was: a sample that cannot assemble changes nothing.
                joints.fill(nan);
                for buf in [velocity, acceleration, jerk].into_iter().flatten() {
                    buf.fill(nan);
                }
                return Err(e);
            }
        };
        let regular;
        if let Some(vel) = velocity {
            let drive = motion.ok_or(Error::BufferLength {
                what: "motion (omega, alpha)",
                expected: 1,
                got: 0,
            })?;
            check_finite("omega", drive.omega)?;
            check_finite("alpha", drive.alpha)?;
            check_finite("jerk", drive.jerk)?;
            regular = self.mech.rates(joints, drive, vel, acceleration, jerk)?;
        } else if acceleration.is_some() || jerk.is_some() {
            return Err(Error::BufferLength {
                what: "velocities (needed for higher rates)",
                expected: n,
                got: 0,
            });
        } else {
            regular = margin >= crate::mechanism::joint_rates::rate_margin::<T>();
        }
        Ok(Sample { margin, regular })
    }

    /// Walks the canonical path toward `theta` and places the sample there. A sample that
    /// cannot be placed leaves the walk as it was.
    fn advance(&mut self, theta: T, joints: &mut [Vec2<T>]) -> Result<T, Error> {
        let (at, far) = self.at_of(theta);
        self.far = far;
        if self.nhist == 0 {
            // With a start angle (Mechanism::set_start_angle) the declared sides hold there,
            // and the first sample is reached by the walk below; else they hold at `theta`.
            let started = self.mech.start_angle().is_some_and(|a0| {
                let (at0, _) = self.at_of(a0);
                self.restart(a0, at0, joints).is_ok()
            });
            if !started {
                return self.restart(theta, at, joints);
            }
        }
        if self.closed_form {
            // Orientations are a function of the angle: counted from the cursor (the first
            // sample, or the start angle) in closed form, with no walk (see the type's docs).
            let walked = self.sign;
            let placed = self.place(theta, theta, at, Choice::Keep, joints);
            self.sign = walked;
            return placed.map(|(m, _)| m);
        }
        match self.walk_to(at) {
            Ok(near) => {
                // The sample does not move the walk: its own choice is not kept.
                let walked = self.sign;
                let choice = if near { Choice::Continue } else { Choice::Keep };
                let placed = self.place(theta, theta, at, choice, joints);
                if placed.is_ok() {
                    self.held = self.sign;
                }
                self.sign = walked;
                placed.map(|(m, _)| m)
            }
            Err(_) => {
                // The motion cannot pass continuously from the last sample to `theta` (a locked
                // zone lies between): restart at `theta` on the orientation held there.
                self.sign = self.held;
                self.restart(theta, at, joints)
            }
        }
    }

    /// Starts the path afresh at `theta` on the orientations held; on failure the state is
    /// left as it was (the next sample restarts too).
    fn restart(&mut self, theta: T, at: At<T>, joints: &mut [Vec2<T>]) -> Result<T, Error> {
        let nhist = self.nhist;
        self.nhist = 0;
        match self.place(theta, theta, at, Choice::Keep, joints) {
            Ok((margin, _)) => {
                self.fine_here = false;
                self.commit(at, theta, joints);
                self.held = self.sign;
                Ok(margin)
            }
            Err(e) => {
                self.nhist = nhist;
                Err(e)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constructions::dyad::Side;

    /// Parallelogram O(0,0), C(g,0), crank r, coupler g, rocker r.
    fn parallelogram() -> Mechanism<f64, 4> {
        let mut m = Mechanism::new();
        let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
        let c = m.fixed(Vec2::new(3.0, 0.0)).unwrap();
        let a = m.crank(o, 1.0, 0.0).unwrap();
        // At θ = 90° the parallelogram's B = A + (3, 0) is left of A → C.
        m.dyad(a, c, 3.0, 1.0, Side::Left).unwrap();
        m
    }

    #[test]
    fn a_snapshot_holding_nan_repeats_and_one_differing_value_does_not() {
        let m = parallelogram();
        let mut t = Tracker::new(&m).unwrap();
        let mut j = [Vec2::zeros(); 4];
        t.step(1.0, None, &mut j, Rates::none()).unwrap();
        t.step(1.1, None, &mut j, Rates::none()).unwrap();
        let mut a = t.snapshot();
        a.hist_margin[3] = f64::NAN;
        a.newest[2].x = f64::NAN;
        let b = a;
        assert!(a.same(&b), "a NaN in the state must match the same NaN");
        let mut c = a;
        c.newest[2].y += 1e-15;
        assert!(
            !a.same(&c),
            "a state differing in one value must not repeat"
        );
        let mut d = a;
        d.hist_margin[3] = 0.0;
        assert!(!a.same(&d), "a NaN must not match a number");
    }

    fn sweep_parallelogram(steps: usize) -> f64 {
        let m = parallelogram();
        let mut t = Tracker::new(&m).unwrap();
        let mut j = [Vec2::zeros(); 4];
        let mut worst: f64 = 0.0;
        for k in 0..=steps {
            // Start at 90°, go one full turn and a bit: passes both flat positions.
            let th = core::f64::consts::FRAC_PI_2 + 7.0 * k as f64 / steps as f64;
            t.step(th, None, &mut j, Rates::none()).unwrap();
            let expected = j[2] + Vec2::new(3.0, 0.0);
            worst = worst.max((j[3] - expected).norm());
        }
        worst
    }

    #[test]
    fn parallelogram_stays_parallelogram_through_flat_positions() {
        // Fine sampling, and sampling far too coarse to see the flat positions.
        for n in [3600, 5] {
            let worst = sweep_parallelogram(n);
            assert!(
                worst < 1e-12,
                "{n} samples a turn: off the parallelogram by {worst:e}"
            );
        }
    }

    /// Change-point four-bars (any link shortest), parallelograms, kites and deltoids, any
    /// pivots, coupler point and assembly: every one has its orientation in closed form.
    fn change_point() -> impl proptest::strategy::Strategy<Value = crate::FourBar<f64>> {
        use proptest::prelude::*;
        (
            0usize..4,
            (0.2f64..3.0, 0.2f64..3.0, 0.2f64..3.0),
            (0usize..4, 0.0f64..core::f64::consts::TAU),
            (-3.0f64..3.0, -3.0f64..3.0, -2.0f64..2.0, -2.0f64..2.0),
            any::<bool>(),
        )
            .prop_filter_map(
                "a four-bar",
                |(kind, (a, b, c), (perm, rot), (ox, oy, pa, pl), open)| {
                    let (g, r, cp, rk) = match kind {
                        0 => {
                            let (s, p, q) = (a.min(b).min(c) * 0.5, a, b);
                            let mut v = [s, p + q - s, p, q];
                            v.rotate_left(perm);
                            (v[0], v[1], v[2], v[3])
                        }
                        1 => (a, b, a, b),
                        // A kite turns fully when its crank is not longer than its coupler.
                        2 => (a.min(b), a.min(b), a.max(b), a.max(b)),
                        _ => (a, b, b, a),
                    };
                    let o = Vec2::new(ox, oy);
                    let cpos = o + Vec2::new(rot.cos(), rot.sin()) * g;
                    let asm = if open {
                        crate::Assembly::Open
                    } else {
                        crate::Assembly::Crossed
                    };
                    crate::FourBar::with_pivots(o, cpos, r, cp, rk, (pa * cp, pl * cp), asm).ok()
                },
            )
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig {
            cases: 256,
            max_global_rejects: 100_000,
            ..proptest::prelude::ProptestConfig::default()
        })]
        /// Where orientations are in closed form, placing each sample from the first one with no
        /// walk gives the walk's bits (or its error), at random angles over ±3 turns in random
        /// order and at points 1e-12 … 1e-3 rad from the flat positions; and a sample's pose does
        /// not depend on the order of the samples before it.
        #[test]
        fn closed_form_is_the_walk(
            fb in change_point(),
            random in proptest::collection::vec(-3.0f64..3.0, 1..40),
            near in proptest::collection::vec((0usize..2, -12i32..-3, proptest::prelude::any::<bool>()), 0..8),
        ) {
            let m = fb.mechanism();
            let d = fb.c - fb.o;
            let base = d.y.atan2(d.x);
            let mut th: Vec<f64> = random.iter().map(|u| u * core::f64::consts::TAU).collect();
            for &(which, e, after) in &near {
                let flat = base + core::f64::consts::PI * which as f64;
                let off = 10f64.powi(e);
                th.push(if after { flat + off } else { flat - off });
            }
            let mut closed = Tracker::new(&m).unwrap();
            // Parallelograms and deltoids turn fully; other change points (kites with the
            // crank longer than the coupler, a crank not the shortest link) may lock.
            let same = |x: f64, y: f64| (x - y).abs() < 1e-12;
            let g = fb.ground();
            let shapes = (same(g, fb.coupler) && same(fb.crank, fb.rocker))
                || (same(g, fb.rocker) && same(fb.crank, fb.coupler));
            proptest::prop_assert!(closed.closed_form || !shapes, "closed form for {:?}", fb);
            // Change points with the crank not the shortest link lock: walked, not compared.
            proptest::prop_assume!(closed.closed_form);
            let mut walk = Tracker::new(&m).unwrap();
            walk.closed_form = false;
            let (mut a, mut b) = ([Vec2::zeros(); 5], [Vec2::zeros(); 5]);
            let mut first = Vec::new();
            for &t in &th {
                let ra = closed.step(t, None, &mut a, Rates::none());
                let rb = walk.step(t, None, &mut b, Rates::none());
                proptest::prop_assert_eq!(ra.is_ok(), rb.is_ok(), "outcome at {}", t);
                if ra.is_ok() {
                    proptest::prop_assert_eq!(a, b, "joints at {}", t);
                }
                first.push(a);
            }
            // The same samples, reversed after the first: the same poses.
            let mut again = Tracker::new(&m).unwrap();
            again.step(th[0], None, &mut a, Rates::none()).ok();
            for (k, &t) in th.iter().enumerate().skip(1).rev() {
                again.step(t, None, &mut a, Rates::none()).ok();
                let same = a.iter().zip(&first[k]).all(|(p, q)| p == q || (p.x.is_nan() && q.x.is_nan()));
                proptest::prop_assert!(same, "order changed the pose at {}", t);
            }
            // One placement a sample, whatever the jump.
            proptest::prop_assert!(closed.work() <= th.len() as u64 + 1, "work {}", closed.work());
        }
    }

    #[test]
    fn unassemblable_sample_is_nan_and_error() {
        let mut m = Mechanism::<f64, 4>::new();
        let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
        let c = m.fixed(Vec2::new(10.0, 0.0)).unwrap();
        let a = m.crank(o, 1.0, 0.0).unwrap();
        m.dyad(a, c, 4.0, 4.0, Side::Left).unwrap();
        let mut t = Tracker::new(&m).unwrap();
        let mut j = [Vec2::zeros(); 4];
        let e = t.step(0.0, None, &mut j, Rates::none()).unwrap_err();
        match e {
            Error::CannotAssemble { joint: 3, gap } => {
                assert!((gap - 1.0).abs() < 1e-12, "gap {gap} for a gap of 1");
            }
            other => panic!("unexpected {other:?}"),
        }
        assert!(
            j.iter().all(|p| p.x.is_nan() && p.y.is_nan()),
            "joints of a failed step: {j:?}"
        );
    }
}
