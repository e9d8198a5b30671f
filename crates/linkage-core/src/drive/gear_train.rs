//! Gear trains: speed ratio and sense of rotation.

use crate::error::Error;

/// A train of external spur gears, as the speed ratio `output/input` and its sign.
///
/// ```
/// use linkage_core::GearTrain;
/// // Thesis 1: an 18-tooth pinion drives a 15-tooth idler driving the 14-tooth crank gear.
/// let t = GearTrain::simple(&[18, 15, 14]).unwrap();
/// assert!((t.ratio() - 9.0 / 7.0).abs() < 1e-15);
/// assert!((t.output_speed(50.0) - 64.285_714_285_714_29).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GearTrain {
    /// `|output speed / input speed|`.
    magnitude: f64,
    /// `+1` when output and input turn the same way.
    sign: i8,
}

impl GearTrain {
    /// A simple train: each gear meshes with the next, one gear per shaft. The ratio is
    /// `z_first / z_last` (idlers cancel) and every external mesh reverses the sense.
    ///
    /// # Errors
    /// [`Error::TooFew`] for fewer than two gears or a gear of no teeth.
    pub fn simple(teeth: &[u32]) -> Result<Self, Error> {
        if teeth.len() < 2 {
            return Err(Error::TooFew {
                what: "gears in a simple gear train",
                needed: 2,
                got: teeth.len(),
            });
        }
        check_teeth(teeth.iter().copied())?;
        let meshes = teeth.len() - 1;
        Ok(GearTrain {
            magnitude: f64::from(teeth[0]) / f64::from(teeth[meshes]),
            sign: if meshes.is_multiple_of(2) { 1 } else { -1 },
        })
    }

    /// A compound train: `(driver, driven)` tooth counts of each external mesh, the driven gear
    /// of one stage sharing its shaft with the driver of the next. Ratio `Π driver/driven`.
    ///
    /// The product is formed with its power of two kept apart, so many stages cannot underflow
    /// or overflow on the way to a representable ratio.
    ///
    /// # Errors
    /// [`Error::TooFew`] for no stage or a gear of no teeth;
    /// [`Error::NotRepresentable`] when the ratio itself is below the smallest normal `f64` or
    /// above the largest (it would come out as 0, a subnormal without full precision, or ∞).
    pub fn compound(stages: &[(u32, u32)]) -> Result<Self, Error> {
        if stages.is_empty() {
            return Err(Error::TooFew {
                what: "stages in a compound gear train",
                needed: 1,
                got: 0,
            });
        }
        check_teeth(stages.iter().flat_map(|&(a, b)| [a, b]))?;
        // magnitude = m · 2^e with m kept in [2⁻³², 2³²]: every factor is in [2⁻³², 2³²], so
        // each product is a normal number and each rescaling by 2^±32 is exact.
        const STEP: f64 = 4_294_967_296.0; // 2³²
        let (mut m, mut e) = (1.0_f64, 0_i64);
        for &(a, b) in stages {
            m *= f64::from(a) / f64::from(b);
            while m > STEP {
                m /= STEP;
                e = e.saturating_add(32);
            }
            while m < 1.0 / STEP {
                m *= STEP;
                e = e.saturating_sub(32);
            }
        }
        // m·2^e is a normal f64 only for e within a little of [-1022, 1023].
        let not_representable = Error::NotRepresentable {
            what: "gear train ratio",
        };
        if !(-1200..=1200).contains(&e) {
            return Err(not_representable);
        }
        while e >= 32 {
            m *= STEP;
            e -= 32;
        }
        while e <= -32 {
            m /= STEP;
            e += 32;
        }
        // |e| < 32 now; the values only move one way, so a normal result had normal (exactly
        // scaled) intermediates.
        let two_e = (1u64 << e.unsigned_abs()) as f64; // exact: a power of two below 2³²
        let magnitude = if e >= 0 { m * two_e } else { m / two_e };
        if !(magnitude.is_finite() && magnitude >= f64::MIN_POSITIVE) {
            return Err(not_representable);
        }
        Ok(GearTrain {
            magnitude,
            sign: if stages.len().is_multiple_of(2) {
                1
            } else {
                -1
            },
        })
    }

    /// `|output/input|` speed ratio.
    pub fn ratio(&self) -> f64 {
        self.magnitude
    }

    /// `+1` if the output turns with the input, `-1` against it.
    pub fn sign(&self) -> i8 {
        self.sign
    }

    /// Output speed for an input speed (signed: the sense follows [`GearTrain::sign`]).
    pub fn output_speed(&self, input: f64) -> f64 {
        input * self.magnitude * f64::from(self.sign)
    }
}

fn check_teeth(teeth: impl Iterator<Item = u32>) -> Result<(), Error> {
    for z in teeth {
        if z == 0 {
            return Err(Error::TooFew {
                what: "teeth on each gear",
                needed: 1,
                got: 0,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compound_and_signs() {
        let t = GearTrain::compound(&[(12, 36), (10, 40)]).unwrap();
        assert!(
            (t.ratio() - 1.0 / 12.0).abs() < 1e-15,
            "ratio {} of 12:36, 10:40 (want 1/12)",
            t.ratio()
        );
        assert_eq!(t.sign(), 1, "sign of a compound train of two meshes");
        assert_eq!(
            GearTrain::simple(&[20, 40]).unwrap().sign(),
            -1,
            "sign of one external mesh"
        );
        let one = GearTrain::simple(&[20]);
        assert!(one.is_err(), "a single gear: {one:?}");
        let zero = GearTrain::simple(&[20, 0]);
        assert!(zero.is_err(), "a gear of no teeth: {zero:?}");
    }

    #[test]
    fn compound_ratio_is_exact_or_an_error() {
        // 40 stages of 1:2 is 2⁻⁴⁰, exactly; 1100 stages of 1:2 is below the smallest normal.
        let t = GearTrain::compound(&[(1, 2); 40]).unwrap();
        assert_eq!(t.ratio(), 1.0 / (1u64 << 40) as f64, "40 stages of 1:2");
        // Far below the float range on the way (4e9⁻⁶⁰ ≈ 1e-577) but exactly 1 in the end: a
        // plain product gives 0; this one is 1 to the rounding of 120 factors.
        let mut stages = [(1, 4_000_000_000); 60].to_vec();
        stages.extend([(4_000_000_000, 1); 60]);
        let r = GearTrain::compound(&stages).unwrap().ratio();
        assert!((r - 1.0).abs() < 1e-13, "{r}");
        let tiny = GearTrain::compound(&[(1, 2); 1100]);
        assert!(
            matches!(tiny, Err(Error::NotRepresentable { .. })),
            "1100 stages of 1:2: {tiny:?}"
        );
        let huge = GearTrain::compound(&[(u32::MAX, 1); 40]);
        assert!(
            matches!(huge, Err(Error::NotRepresentable { .. })),
            "40 stages of u32::MAX:1: {huge:?}"
        );
    }
}
