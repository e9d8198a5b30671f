//! A crank-speed schedule stored as a compact periodic table, interpolated without a heap.

use nalgebra::RealField;

use crate::error::{check_finite, check_length, Error};
use crate::numeric::scalar::lit;

/// A periodic crank schedule `θ(t)`: crank angle and speed at `n` uniform times `k·dt` over one
/// period `n·dt`, after which the crank has advanced by `advance` (2π for one turn per period).
///
/// Between samples it is a cubic Hermite interpolant of the angles with the stored speeds as
/// slopes: `θ` and `ω` are continuous, `α` is piecewise linear. The table borrows its data, so
/// firmware can keep it in flash as two `[f32; n]` arrays.
///
/// ```
/// use linkage_core::ScheduleTable;
/// // A constant 2 rad/s over a period of π s, sampled 4 times.
/// let dt = core::f32::consts::PI / 4.0;
/// let theta = [0.0, 2.0 * dt, 4.0 * dt, 6.0 * dt];
/// let omega = [2.0_f32; 4];
/// let table = ScheduleTable::new(dt, core::f32::consts::TAU, &theta, &omega).unwrap();
/// let (th, w, _) = table.at(1.0);
/// assert!((th - 2.0).abs() < 1e-6 && (w - 2.0).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScheduleTable<'a, T> {
    dt: T,
    advance: T,
    theta: &'a [T],
    omega: &'a [T],
}

impl<'a, T: RealField + Copy> ScheduleTable<'a, T> {
    /// A table of `theta.len()` samples `dt` apart.
    ///
    /// # Errors
    /// [`Error::InvalidLength`] for a non-positive `dt`, an empty table, a period `n·dt` that
    /// overflows, or mismatched lengths;
    /// [`Error::NotFinite`] for a non-finite entry.
    pub fn new(dt: T, advance: T, theta: &'a [T], omega: &'a [T]) -> Result<Self, Error> {
        check_length("schedule dt", dt)?;
        check_finite("schedule advance", advance)?;
        if theta.is_empty() {
            return Err(Error::InvalidLength {
                what: "schedule table (no samples)",
                value: 0.0,
            });
        }
        if omega.len() != theta.len() {
            return Err(Error::BufferLength {
                what: "schedule omega",
                expected: theta.len(),
                got: omega.len(),
            });
        }
        for &x in theta.iter().chain(omega) {
            check_finite("schedule entry", x)?;
        }
        // The period `n·dt` must be finite too, or every time falls in period 0.
        check_length(
            "schedule period (samples × dt)",
            dt * lit::<T>(theta.len() as f64),
        )?;
        Ok(ScheduleTable {
            dt,
            advance,
            theta,
            omega,
        })
    }

    /// Period of the schedule.
    pub fn period(&self) -> T {
        self.dt * lit::<T>(self.theta.len() as f64)
    }

    /// `(θ, ω, α)` at time `t` (any real `t`; the schedule repeats, advancing by `advance` per
    /// period).
    pub fn at(&self, t: T) -> (T, T, T) {
        let n = self.theta.len();
        let period = self.period();
        // `%` is exact (fmod), so the time within the period is right even when `t / period`
        // is huge; `cycles` only scales `advance` (and is ±∞ only when the angle overflows).
        let mut local = t % period;
        if local < T::zero() {
            local += period; // in (0, period]; `period` itself is handled below
        }
        let cycles = ((t - local) / period).round();
        let pos = local / self.dt;
        let k = pos.floor();
        // `as` saturates (NaN → 0), and `local ∈ [0, period]` keeps `k` in `0..=n` anyway.
        let mut i = k.to_subset().unwrap_or(0.0) as usize;
        let mut tau = pos - k;
        if i >= n {
            // Rounding put `local` on the period's end: it is the next period's start.
            i = n - 1;
            tau = T::one();
        }
        let (th0, w0) = (self.theta[i], self.omega[i]);
        let (th1, w1) = if i + 1 < n {
            (self.theta[i + 1], self.omega[i + 1])
        } else {
            (self.theta[0] + self.advance, self.omega[0])
        };
        let h = self.dt;
        let (m0, m1) = (w0 * h, w1 * h);
        let c = lit::<T>;
        let (t2, t3) = (tau * tau, tau * tau * tau);
        let theta = (c(2.0) * t3 - c(3.0) * t2 + T::one()) * th0
            + (t3 - c(2.0) * t2 + tau) * m0
            + (c(3.0) * t2 - c(2.0) * t3) * th1
            + (t3 - t2) * m1;
        let dtheta = (c(6.0) * t2 - c(6.0) * tau) * (th0 - th1)
            + (c(3.0) * t2 - c(4.0) * tau + T::one()) * m0
            + (c(3.0) * t2 - c(2.0) * tau) * m1;
        let ddtheta = (c(12.0) * tau - c(6.0)) * (th0 - th1)
            + (c(6.0) * tau - c(4.0)) * m0
            + (c(6.0) * tau - c(2.0)) * m1;
        (theta + cycles * self.advance, dtheta / h, ddtheta / (h * h))
    }
}

/// The crank schedule that holds a foot at constant speed `V` along its stance line, with one
/// crank turn per period and a duty factor `β`.
///
/// In stance the crank runs at `ω(θ) = V/u(θ)`, `u` the foot's speed along the stance line per
/// radian of crank, so stance time accumulates as `dt = u dθ / V` (trapezoid rule over the
/// given stance samples) and lasts `T_st`. The period is `T = T_st/β`; the swing covers the rest
/// of the turn, `Δθ_sw = 2π − (θ_end − θ_start)`, in `T_sw = T − T_st` with
///
/// `ω(τ) = ω₁ + (ω₀ − ω₁)·τ + 6·b·τ(1 − τ)`, `τ = (t − T_st)/T_sw ∈ [0, 1]`,
///
/// which starts at the stance's last speed `ω₁ = V/u_end` and ends at its first `ω₀ = V/u_start`
/// (ω continuous around the period), with the parabolic bump `b = Δθ_sw/T_sw − (ω₀ + ω₁)/2`
/// sized so the swing closes the turn: bounded acceleration. The swing's smallest speed is at
/// an end of the swing or, when `b < 0`, at the parabola's vertex; it must stay positive (the
/// crank never stops or reverses).
///
/// The schedule borrows the stance samples; [`StanceSchedule::at`] evaluates it and
/// [`StanceSchedule::fill`] writes the table a [`ScheduleTable`] (and firmware) interpolates.
///
/// ```
/// use core::f64::consts::{FRAC_PI_2, PI};
/// use linkage_core::{Error, StanceSchedule};
/// // A stance over half a turn in which the foot moves 1 per radian of crank, at foot speed 1
/// // and duty factor ½: the crank turns uniformly, 1 rad/s, stance and swing alike.
/// let theta = [0.0, FRAC_PI_2, PI];
/// let mut times = [0.0; 3];
/// let s = StanceSchedule::fit(&theta, &[1.0; 3], &mut times, 1.0, 0.5).unwrap();
/// assert_eq!((s.stance_time(), s.period()), (PI, 2.0 * PI));
/// let (th, w) = s.at(4.0); // in the swing
/// assert!((th - 4.0).abs() < 1e-12 && (w - 1.0).abs() < 1e-12);
/// // A foot that stops along the stance line cannot keep a constant speed.
/// let mut times = [0.0; 3];
/// assert!(matches!(
///     StanceSchedule::fit(&theta, &[1.0, 0.0, 1.0], &mut times, 1.0, 0.5),
///     Err(Error::ScheduleInfeasible { .. })
/// ));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StanceSchedule<'a, T> {
    theta: &'a [T],
    u: &'a [T],
    times: &'a [T],
    foot_speed: T,
    swing_time: T,
    w0: T,
    w1: T,
    bump: T,
}

impl<'a, T: RealField + Copy> StanceSchedule<'a, T> {
    /// Fits the schedule to stance samples: crank angles `theta` (strictly increasing, unwrapped
    /// across 2π), the foot's speed along the stance line per radian `u` at each, the foot speed
    /// `foot_speed` and the duty factor `duty_factor`. `times` (as long as `theta`) receives the
    /// time at which the crank reaches each stance angle.
    ///
    /// # Errors
    /// [`Error::BufferLength`] for slices of different lengths or fewer than 2 samples;
    /// [`Error::NotFinite`] for a non-finite sample; [`Error::InvalidLength`] for a non-positive
    /// foot speed or stance angles that do not increase; [`Error::NotFinite`] for a duty factor
    /// outside `(0, 1)`; [`Error::ScheduleInfeasible`] when the foot stops along the stance line
    /// (`u ≤ 0`), the stance time is zero or overflows, the stance covers a whole turn, or the
    /// swing would need the crank to stop.
    pub fn fit(
        theta: &'a [T],
        u: &'a [T],
        times: &'a mut [T],
        foot_speed: T,
        duty_factor: T,
    ) -> Result<Self, Error> {
        let n = theta.len();
        for (what, len) in [("stance speeds", u.len()), ("stance times", times.len())] {
            if len != n {
                return Err(Error::BufferLength {
                    what,
                    expected: n,
                    got: len,
                });
            }
        }
        if n < 2 {
            return Err(Error::BufferLength {
                what: "stance samples (at least 2)",
                expected: 2,
                got: n,
            });
        }
        check_length("foot speed", foot_speed)?;
        check_finite("duty factor", duty_factor)?;
        if duty_factor <= T::zero() || duty_factor >= T::one() {
            return Err(Error::NotFinite {
                what: "duty factor (between 0 and 1)",
                value: duty_factor.to_subset().unwrap_or(f64::NAN),
            });
        }
        for k in 0..n {
            check_finite("stance crank angle", theta[k])?;
            check_finite("stance foot speed per radian", u[k])?;
            if u[k] <= T::zero() {
                return Err(Error::ScheduleInfeasible {
                    why: "the foot stops along the stance line",
                    figure: "its speed per radian of crank",
                    value: u[k].to_subset().unwrap_or(f64::NAN),
                    unit: "length/rad",
                    hint: "no constant-speed schedule exists",
                });
            }
            if k > 0 && theta[k] <= theta[k - 1] {
                return Err(Error::InvalidLength {
                    what: "stance crank angle step (angles must increase)",
                    value: (theta[k] - theta[k - 1]).to_subset().unwrap_or(f64::NAN),
                });
            }
        }
        let half = lit::<T>(0.5);
        times[0] = T::zero();
        let mut acc = T::zero();
        for k in 1..n {
            acc += half * (u[k] + u[k - 1]) * (theta[k] - theta[k - 1]);
            times[k] = acc / foot_speed;
        }
        let stance_time = times[n - 1];
        let period = stance_time / duty_factor;
        let swing_time = period - stance_time;
        let f = |x: T| x.to_subset().unwrap_or(f64::NAN);
        if !(period.is_finite() && stance_time > T::zero() && swing_time > T::zero()) {
            return Err(Error::ScheduleInfeasible {
                why: "the stance takes no time or overflows at this foot speed",
                figure: "stance time",
                value: f(stance_time),
                unit: "s",
                hint: "",
            });
        }
        let swing_angle = T::two_pi() - (theta[n - 1] - theta[0]);
        if swing_angle <= T::zero() {
            return Err(Error::ScheduleInfeasible {
                why: "the stance covers a whole crank turn",
                figure: "swing angle",
                value: f(swing_angle),
                unit: "rad",
                hint: "",
            });
        }
        let (w0, w1) = (foot_speed / u[0], foot_speed / u[n - 1]);
        let bump = swing_angle / swing_time - half * (w0 + w1);
        let schedule = StanceSchedule {
            theta,
            u,
            times,
            foot_speed,
            swing_time,
            w0,
            w1,
            bump,
        };
        let slowest = schedule.slowest_swing_speed();
        if !slowest.is_finite() || slowest <= T::zero() {
            return Err(Error::ScheduleInfeasible {
                why: "the duty factor needs the crank to stop during the swing",
                figure: "minimum crank speed",
                value: f(slowest),
                unit: "rad/s",
                hint: "raise the duty factor or lower the foot speed",
            });
        }
        Ok(schedule)
    }

    /// Swing speed at `τ ∈ [0, 1]`.
    fn swing_speed(&self, tau: T) -> T {
        self.w1 + (self.w0 - self.w1) * tau + lit::<T>(6.0) * self.bump * tau * (T::one() - tau)
    }

    /// The smallest crank speed over the swing: at an end, or at the vertex of a convex
    /// parabola (`b < 0`) when it lies inside the swing.
    pub fn slowest_swing_speed(&self) -> T {
        let mut slowest = self.w0.min(self.w1);
        if self.bump < T::zero() {
            let vertex = lit::<T>(0.5) + (self.w0 - self.w1) / (lit::<T>(12.0) * self.bump);
            if vertex > T::zero() && vertex < T::one() {
                slowest = slowest.min(self.swing_speed(vertex));
            }
        }
        slowest
    }

    /// Time in stance (s).
    pub fn stance_time(&self) -> T {
        self.times[self.times.len() - 1]
    }

    /// One period, stance and swing (s).
    pub fn period(&self) -> T {
        self.stance_time() + self.swing_time
    }

    /// Crank angles where stance starts and ends.
    pub fn stance_angles(&self) -> (T, T) {
        (self.theta[0], self.theta[self.theta.len() - 1])
    }

    /// Crank angle and speed at time `t ∈ [0, period]` from the stance's start (times outside
    /// are clamped to it).
    pub fn at(&self, t: T) -> (T, T) {
        let t = t.max(T::zero()).min(self.period());
        let stance_time = self.stance_time();
        if t <= stance_time {
            let theta = interp(self.times, self.theta, t);
            (theta, self.foot_speed / interp(self.theta, self.u, theta))
        } else {
            let tau = (t - stance_time) / self.swing_time;
            let (t2, t3) = (tau * tau, tau * tau * tau);
            let c = lit::<T>;
            let advance = self.w1 * tau
                + c(0.5) * (self.w0 - self.w1) * t2
                + c(6.0) * self.bump * (t2 * c(0.5) - t3 / c(3.0));
            let end = self.theta[self.theta.len() - 1];
            (end + self.swing_time * advance, self.swing_speed(tau))
        }
    }

    /// Writes the table of `theta.len()` samples at times `k·dt`, `dt = period/len`, and
    /// returns `dt`.
    ///
    /// # Errors
    /// [`Error::BufferLength`] when `theta` and `omega` differ in length or are empty.
    pub fn fill(&self, theta: &mut [T], omega: &mut [T]) -> Result<T, Error> {
        if theta.is_empty() || omega.len() != theta.len() {
            return Err(Error::BufferLength {
                what: "schedule table (equal, non-empty theta and omega)",
                expected: theta.len().max(1),
                got: omega.len(),
            });
        }
        let dt = self.period() / lit::<T>(theta.len() as f64);
        for (k, (th, w)) in theta.iter_mut().zip(omega.iter_mut()).enumerate() {
            (*th, *w) = self.at(dt * lit::<T>(k as f64));
        }
        Ok(dt)
    }
}

/// Piecewise-linear interpolation of `(xs, ys)` at `x` (`xs` increasing; clamped at the ends).
fn interp<T: RealField + Copy>(xs: &[T], ys: &[T], x: T) -> T {
    let n = xs.len();
    if x <= xs[0] {
        return ys[0];
    }
    if x >= xs[n - 1] {
        return ys[n - 1];
    }
    // First index with xs[i] > x: in 1..n here.
    let i = xs.partition_point(|&v| v <= x);
    let (x0, x1, y0, y1) = (xs[i - 1], xs[i], ys[i - 1], ys[i]);
    if x1 > x0 {
        y0 + (y1 - y0) * ((x - x0) / (x1 - x0))
    } else {
        y0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cubic θ(t) is reproduced exactly by Hermite interpolation of its samples and slopes.
    #[test]
    fn reproduces_a_cubic_between_samples() {
        let f = |t: f64| 0.3 * t * t * t - 0.5 * t * t + 2.0 * t;
        let df = |t: f64| 0.9 * t * t - t + 2.0;
        let dt = 0.25;
        let theta: [f64; 8] = core::array::from_fn(|k| f(k as f64 * dt));
        let omega: [f64; 8] = core::array::from_fn(|k| df(k as f64 * dt));
        let table = ScheduleTable::new(dt, 100.0, &theta, &omega).unwrap();
        for k in 0..70 {
            let t = k as f64 * 0.0249;
            let (th, w, _) = table.at(t);
            assert!(
                (th - f(t)).abs() < 1e-12 && (w - df(t)).abs() < 1e-12,
                "{t}"
            );
        }
        // Periodic continuation: one period later the angle has advanced by `advance`.
        let (a, _, _) = table.at(0.1);
        let (b, _, _) = table.at(0.1 + table.period());
        assert!(
            (b - a - 100.0).abs() < 1e-12,
            "advance over one period {} (want 100)",
            b - a
        );
    }

    #[test]
    fn rejects_bad_tables() {
        assert!(
            ScheduleTable::new(0.0, 1.0, &[0.0], &[0.0]).is_err(),
            "a zero time step accepted"
        );
        assert!(
            ScheduleTable::<f64>::new(1.0, 1.0, &[], &[]).is_err(),
            "an empty table accepted"
        );
        assert!(
            ScheduleTable::new(1.0, 1.0, &[0.0, 1.0], &[0.0]).is_err(),
            "two angles with one speed accepted"
        );
        assert!(
            ScheduleTable::new(1.0, 1.0, &[f64::NAN], &[0.0]).is_err(),
            "a NaN angle accepted"
        );
    }

    /// Hand-computed case: a foot moving at a constant 3 mm per radian over a stance of π/2
    /// rad, at V = 6 mm/s: the stance takes 3·(π/2)/6 = π/4 s at ω = 2 rad/s; with β = 0.25
    /// the period is π s and the swing covers 3π/2 rad in 3π/4 s, a mean of 2 rad/s, so the
    /// bump is zero and the crank turns at 2 rad/s throughout.
    #[test]
    fn uniform_stance_gives_a_uniform_crank() {
        let theta: [f64; 5] =
            core::array::from_fn(|k| 1.0 + k as f64 * core::f64::consts::FRAC_PI_8);
        let u = [3.0; 5];
        let mut times = [0.0; 5];
        let s = StanceSchedule::fit(&theta, &u, &mut times, 6.0, 0.25).unwrap();
        let pi = core::f64::consts::PI;
        assert!(
            (s.stance_time() - pi / 4.0).abs() < 1e-15,
            "{}",
            s.stance_time()
        );
        assert!(
            (s.period() - pi).abs() < 1e-15,
            "period {} (want π)",
            s.period()
        );
        assert_eq!(s.slowest_swing_speed(), 2.0, "slowest swing speed");
        for k in 0..=40 {
            let t = k as f64 * pi / 40.0;
            let (th, w) = s.at(t);
            assert!((th - (1.0 + 2.0 * t)).abs() < 1e-13, "θ({t}) = {th}");
            assert!((w - 2.0).abs() < 1e-13, "ω({t}) = {w}");
        }
        let (mut th, mut w) = ([0.0; 8], [0.0; 8]);
        let dt = s.fill(&mut th, &mut w).unwrap();
        assert!(
            (dt - pi / 8.0).abs() < 1e-15,
            "fill's time step {dt} (want π/8)"
        );
        assert!((th[4] - (1.0 + pi)).abs() < 1e-13, "{}", th[4]); // t = π/2 s at 2 rad/s
    }

    /// A foot that slows along its stance: ω is continuous where stance meets swing, the turn
    /// closes (θ advances 2π per period), the swing stays above its reported slowest speed,
    /// and a duty factor too low for the swing is refused, naming the crank stopping.
    #[test]
    fn varying_stance_closes_the_turn_or_is_refused() {
        let theta: [f64; 33] = core::array::from_fn(|k| -0.8 + k as f64 * 0.05);
        let u: [f64; 33] = core::array::from_fn(|k| 2.0 + (k as f64 * 0.05).sin());
        let mut times = [0.0; 33];
        let s = StanceSchedule::fit(&theta, &u, &mut times, 5.0, 0.6).unwrap();
        let (start, end) = s.stance_angles();
        let ts = s.stance_time();
        let (th_a, w_a) = s.at(ts * (1.0 - 1e-12));
        let (th_b, w_b) = s.at(ts * (1.0 + 1e-12));
        assert!(
            (th_a - end).abs() < 1e-9 && (th_b - end).abs() < 1e-9,
            "θ just before / after the stance ends: {th_a}, {th_b} (want {end})"
        );
        assert!((w_a - w_b).abs() < 1e-9, "{w_a} vs {w_b}");
        let (th_end, w_end) = s.at(s.period());
        assert!(
            (th_end - (start + core::f64::consts::TAU)).abs() < 1e-12,
            "{th_end}"
        );
        assert!((w_end - s.at(0.0).1).abs() < 1e-12, "ω wraps continuously");
        let slowest = s.slowest_swing_speed();
        for k in 0..=1000 {
            let t = ts + (s.period() - ts) * k as f64 / 1000.0;
            assert!(s.at(t).1 >= slowest - 1e-12, "{t}");
        }
        let mut times = [0.0; 33];
        let err = StanceSchedule::fit(&theta, &u, &mut times, 5.0, 0.05).unwrap_err();
        assert!(matches!(err, Error::ScheduleInfeasible { .. }), "{err:?}");
        let mut times = [0.0; 33];
        let mut stop = u;
        stop[7] = 0.0;
        let err = StanceSchedule::fit(&theta, &stop, &mut times, 5.0, 0.6).unwrap_err();
        assert!(matches!(err, Error::ScheduleInfeasible { .. }), "{err:?}");
    }
}
