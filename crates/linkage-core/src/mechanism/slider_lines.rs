//! The slider joints' lines over a sweep's rows: [`Mechanism::line_directions`]. Here rather
//! than beside [`LineDirection`](crate::LineDirection) (one layer down, in `constructions`), because every
//! `impl Mechanism` lives in the mechanism folder.
use nalgebra::RealField;

use crate::error::Error;
use crate::mechanism::program::{Construction, Mechanism};
use crate::numeric::scalar::{nan, Vec2};

impl<T: RealField + Copy, const N: usize> Mechanism<T, N> {
    /// The unit direction of the line the slider `joint` slides on, in each sample of `joints`
    /// (rows of [`Mechanism::len`] joint positions, as a sweep writes them), into `out` (one per
    /// row): [`LineDirection::at`](crate::LineDirection::at) of the slider's line, NaN where it is undetermined (the
    /// carrying link's joints coincide or are NaN: a sample that did not assemble).
    ///
    /// ```
    /// use linkage_core::{Error, LineDirection, Mechanism, Reach, Vec2};
    /// // A slider through O on a line carried by the crank O → A, turned by 0.3 rad.
    /// let mut m = Mechanism::<f64, 4>::new();
    /// let o = m.fixed(Vec2::zeros()).unwrap();
    /// let c = m.fixed(Vec2::new(3.0, 0.0)).unwrap();
    /// let a = m.crank(o, 1.0, 0.0).unwrap();
    /// let line = LineDirection::Link { from: o, to: a, angle: 0.3 };
    /// let s = m.slider(c, 4.0, o, line, Reach::Ahead).unwrap();
    /// // Two samples: the crank along +x, then a sample that did not assemble (NaN).
    /// let mut joints = [Vec2::new(f64::NAN, f64::NAN); 8];
    /// m.pose(0.0, &mut joints[..4]).unwrap();
    /// let mut u = [Vec2::zeros(); 2];
    /// m.line_directions(s, &joints, &mut u).unwrap();
    /// assert!((u[0] - Vec2::new(0.3_f64.cos(), 0.3_f64.sin())).norm() < 1e-15);
    /// assert!(u[1].x.is_nan() && u[1].y.is_nan());
    /// // The crank pin is not a slider.
    /// assert_eq!(m.line_directions(a, &joints, &mut u), Err(Error::NotASlider { joint: a }));
    /// ```
    ///
    /// # Errors
    /// [`Error::NotASlider`] when `joint` is not a slider joint of this mechanism;
    /// [`Error::BufferLength`] when `joints` does not hold `out.len()` rows of
    /// [`Mechanism::len`] joints.
    pub fn line_directions(
        &self,
        joint: usize,
        joints: &[Vec2<T>],
        out: &mut [Vec2<T>],
    ) -> Result<(), Error> {
        let Some(&Construction::Slider { direction, .. }) = self.constructions().get(joint) else {
            return Err(Error::NotASlider { joint });
        };
        let j = self.len();
        if joints.len() / j != out.len() || !joints.len().is_multiple_of(j) {
            return Err(Error::BufferLength {
                what: "joints",
                expected: out.len().saturating_mul(j),
                got: joints.len(),
            });
        }
        let undetermined = Vec2::new(nan::<T>(), nan::<T>());
        for (u, row) in out.iter_mut().zip(joints.chunks_exact(j)) {
            *u = direction.at(row).unwrap_or(undetermined);
        }
        Ok(())
    }
}
