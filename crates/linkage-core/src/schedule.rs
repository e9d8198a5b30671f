//! A crank-speed schedule stored as a compact periodic table, interpolated without a heap.

use nalgebra::RealField;

use crate::error::{check_finite, check_length, Error};
use crate::scalar::lit;

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
        assert!((b - a - 100.0).abs() < 1e-12);
    }

    #[test]
    fn rejects_bad_tables() {
        assert!(ScheduleTable::new(0.0, 1.0, &[0.0], &[0.0]).is_err());
        assert!(ScheduleTable::<f64>::new(1.0, 1.0, &[], &[]).is_err());
        assert!(ScheduleTable::new(1.0, 1.0, &[0.0, 1.0], &[0.0]).is_err());
        assert!(ScheduleTable::new(1.0, 1.0, &[f64::NAN], &[0.0]).is_err());
    }
}
