//! The layout of a sweep's outputs: which joints its per-joint columns hold ([`Columns`]) and
//! which pairs of bodies it writes instant centres for ([`Pairs`]). Its own module so that the
//! engine and the block kernel of centres ([`super::block_centres`]) both use it without using
//! each other.
use crate::error::Error;
use crate::mechanism::bodies::{Bodies, BodyId};

/// Which joints a sweep's per-joint outputs (positions, rates, curvature) hold.
///
/// ```
/// use linkage_core::{catalog, sweep, Columns, Error, Rate, SweepOutputs, Vec2};
/// assert_eq!((Columns::All.width(5), Columns::One(4).width(5)), (5, 1));
/// // A column must name a joint of the mechanism (Hoecken's has 5).
/// let m = catalog::hoecken::<f64>().mechanism();
/// let (mut joints, mut valid) = ([Vec2::zeros(); 1], [false; 1]);
/// let mut out = SweepOutputs::positions(&mut joints, &mut valid);
/// out.columns = Columns::One(5);
/// let r = sweep(&m, &[0.0], Rate::Scalar(0.0), Rate::Scalar(0.0), out, &mut || true);
/// assert!(matches!(r, Err(Error::BufferLength { .. })));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Columns {
    /// Every joint: rows of `j` entries per sample.
    #[default]
    All,
    /// One joint (the trace point): one entry per sample. Nothing of the others is written.
    One(usize),
}

impl Columns {
    /// Entries per sample for a mechanism of `j` joints.
    pub fn width(self, j: usize) -> usize {
        match self {
            Columns::All => j,
            Columns::One(_) => 1,
        }
    }
}

/// Which pairs of bodies a sweep writes instant centres for: by default every pair, or the
/// few a user needs (a four-bar's two secondary centres, the coupler's pole), so that a sweep
/// computes and writes only those.
///
/// Bodies are numbered in [`Bodies::ids`] order, the ground `0` (a four-bar's are ground,
/// crank, coupler, rocker).
///
/// ```
/// use linkage_core::{catalog, sweep, Pairs, Rate, SweepOutputs, Vec2};
/// let m = catalog::hoecken::<f64>().mechanism();
/// let theta = [0.3, 1.1];
/// let (mut joints, mut valid) = ([Vec2::zeros(); 10], [false; 2]);
/// // Every pair: 6 a sample. Hoecken's crank-rocker: ground 0, crank 1, coupler 2, rocker 3.
/// let (mut all, mut all_dirs) = ([Vec2::zeros(); 12], [Vec2::zeros(); 12]);
/// let mut out = SweepOutputs::positions(&mut joints, &mut valid);
/// (out.centres, out.centre_directions) = (Some(&mut all[..]), Some(&mut all_dirs[..]));
/// sweep(&m, &theta, Rate::Scalar(0.0), Rate::Scalar(0.0), out, &mut || true).unwrap();
/// // Only ground–coupler (pair 1 of all) and crank–rocker (pair 4): 2 a sample, same bits.
/// let (mut two, mut two_dirs) = ([Vec2::zeros(); 4], [Vec2::zeros(); 4]);
/// let mut out = SweepOutputs::positions(&mut joints, &mut valid);
/// (out.centres, out.centre_directions) = (Some(&mut two[..]), Some(&mut two_dirs[..]));
/// out.pairs = Pairs::Only(&[[0, 2], [1, 3]]);
/// sweep(&m, &theta, Rate::Scalar(0.0), Rate::Scalar(0.0), out, &mut || true).unwrap();
/// assert_eq!([two[0], two[1], two[2], two[3]], [all[1], all[4], all[6 + 1], all[6 + 4]]);
/// assert_eq!(Pairs::All.count(4), 6);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Pairs<'a> {
    /// Every pair `(k, l)`, `k < l`: `B(B − 1)/2` a sample for `B` bodies ([`sweep_pairs`](crate::sweep_pairs)).
    #[default]
    All,
    /// These pairs of body indices, in this order (either order within a pair: a centre is
    /// the same for both, computed as for the lower index first, so the bits are those of
    /// [`Pairs::All`]). Each index must name a body, and the two must differ.
    Only(&'a [[usize; 2]]),
}

impl Pairs<'_> {
    /// Pairs a sample for a mechanism of `bodies` bodies, the ground included.
    pub fn count(self, bodies: usize) -> usize {
        match self {
            Pairs::All => bodies * bodies.saturating_sub(1) / 2,
            Pairs::Only(p) => p.len(),
        }
    }

    /// Checks that every pair names two different bodies of `bodies`.
    pub(crate) fn check(self, bodies: usize) -> Result<(), Error> {
        if let Pairs::Only(p) = self {
            for &[a, b] in p {
                if a.max(b) >= bodies {
                    return Err(Error::OutOfRange {
                        what: "body of an instant-centre pair",
                        value: a.max(b),
                        max: bodies.saturating_sub(1),
                    });
                }
                if a == b {
                    return Err(Error::InvalidChoice {
                        what: "instant-centre pair",
                        choices: "two different bodies",
                    });
                }
            }
        }
        Ok(())
    }

    /// Pair `q`'s bodies, the lower index first (after [`Self::check`]; None past the end).
    #[cold]
    #[inline(never)]
    pub(crate) fn at<const N: usize>(
        self,
        bodies: &Bodies<N>,
        q: usize,
    ) -> Option<(BodyId, BodyId)> {
        let (a, b) = match self {
            Pairs::All => {
                // Pairs (a, b), a < b, in order: a's run of `nb − 1 − a` pairs.
                let nb = bodies.count();
                let (mut a, mut r) = (0, q);
                while a + 1 < nb && r >= nb - 1 - a {
                    r -= nb - 1 - a;
                    a += 1;
                }
                (a, a + 1 + r)
            }
            Pairs::Only(p) => {
                let [a, b] = *p.get(q)?;
                (a.min(b), a.max(b))
            }
        };
        Some((bodies.ids().nth(a)?, bodies.ids().nth(b)?))
    }

    /// Calls `f(q, k, l)` for each pair `q` in output order (after [`Self::check`]).
    #[inline(always)]
    pub(crate) fn each<const N: usize>(
        self,
        bodies: &Bodies<N>,
        mut f: impl FnMut(usize, BodyId, BodyId),
    ) {
        match self {
            Pairs::All => {
                let mut q = 0;
                for (a, ka) in bodies.ids().enumerate() {
                    for kb in bodies.ids().skip(a + 1) {
                        f(q, ka, kb);
                        q += 1;
                    }
                }
            }
            Pairs::Only(p) => {
                for (q, &[a, b]) in p.iter().enumerate() {
                    // The lower index first, as in `All`: the same bits for either order.
                    let (a, b) = (a.min(b), a.max(b));
                    if let (Some(ka), Some(kb)) = (bodies.ids().nth(a), bodies.ids().nth(b)) {
                        f(q, ka, kb);
                    }
                }
            }
        }
    }
}
