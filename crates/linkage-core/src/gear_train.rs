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
    /// [`Error::InvalidLength`] for fewer than two gears or a zero tooth count.
    pub fn simple(teeth: &[u32]) -> Result<Self, Error> {
        if teeth.len() < 2 {
            return Err(Error::InvalidLength {
                what: "gear train (at least two gears)",
                value: teeth.len() as f64,
            });
        }
        check_teeth(teeth.iter().copied())?;
        let meshes = teeth.len() - 1;
        Ok(GearTrain {
            magnitude: f64::from(teeth[0]) / f64::from(teeth[meshes]),
            sign: if meshes % 2 == 0 { 1 } else { -1 },
        })
    }

    /// A compound train: `(driver, driven)` tooth counts of each external mesh, the driven gear
    /// of one stage sharing its shaft with the driver of the next. Ratio `Π driver/driven`.
    ///
    /// # Errors
    /// [`Error::InvalidLength`] for no stage or a zero tooth count.
    pub fn compound(stages: &[(u32, u32)]) -> Result<Self, Error> {
        if stages.is_empty() {
            return Err(Error::InvalidLength {
                what: "gear train (at least one stage)",
                value: 0.0,
            });
        }
        check_teeth(stages.iter().flat_map(|&(a, b)| [a, b]))?;
        let magnitude = stages
            .iter()
            .map(|&(a, b)| f64::from(a) / f64::from(b))
            .product();
        Ok(GearTrain {
            magnitude,
            sign: if stages.len() % 2 == 0 { 1 } else { -1 },
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
            return Err(Error::InvalidLength {
                what: "gear tooth count",
                value: 0.0,
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
        assert!((t.ratio() - 1.0 / 12.0).abs() < 1e-15);
        assert_eq!(t.sign(), 1);
        assert_eq!(GearTrain::simple(&[20, 40]).unwrap().sign(), -1);
        assert!(GearTrain::simple(&[20]).is_err());
        assert!(GearTrain::simple(&[20, 0]).is_err());
    }
}
