//! The rigid bodies (links) of a mechanism program, and its mobility by Kutzbach–Gruebler.

use nalgebra::RealField;

use crate::constructions::slider::LineDirection;
use crate::mechanism::program::{Construction, Mechanism};
use crate::numeric::scalar::Vec2;

/// Index of the frame (ground) body.
pub const GROUND: BodyId = BodyId {
    joint: usize::MAX,
    slot: 0,
};

/// A body of a mechanism, named by the construction that created it and a slot (0 or 1).
///
/// A crank creates one body (its crank link); an RRR dyad two (its links from `p1` and `p2`);
/// a slider two (the connecting link, slot 0, and the sliding block, slot 1); a point carried by
/// a link joins the body that holds both its frame joints, or creates one if none does.
///
/// ```
/// use linkage_core::{catalog, Bodies, BodyId, GROUND};
/// let bodies = Bodies::of(&catalog::hoecken::<f64>().mechanism()); // joints O, C, A, B, P
/// // The dyad at B (joint 3) creates the coupler (slot 0, from A) and the rocker (slot 1, from C).
/// let (coupler, rocker) = (BodyId { joint: 3, slot: 0 }, BodyId { joint: 3, slot: 1 });
/// assert!([2, 3, 4].iter().all(|&j| bodies.contains(coupler, j)));
/// assert_eq!(bodies.shared_joint(coupler, rocker), Some(3));
/// assert!(bodies.contains(GROUND, 0) && !bodies.contains(GROUND, 2));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BodyId {
    /// The construction that created the body (`usize::MAX` for the ground).
    pub joint: usize,
    /// 0 or 1.
    pub slot: u8,
}

/// How a body's motion is known.
///
/// ```
/// use linkage_core::{catalog, Bodies, BodyFrame, BodyId, GROUND};
/// let bodies = Bodies::of(&catalog::hoecken::<f64>().mechanism());
/// assert_eq!(bodies.frame(GROUND), BodyFrame::Ground);
/// // The crank (created by joint A = 2) turns about O = 0.
/// let crank = BodyId { joint: 2, slot: 0 };
/// assert_eq!(bodies.frame(crank), BodyFrame::Link { origin: 0, toward: 2 });
/// // An id that names no body reads as the ground.
/// assert_eq!(bodies.frame(BodyId { joint: 99, slot: 0 }), BodyFrame::Ground);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BodyFrame {
    /// The frame: does not move.
    Ground,
    /// A link whose motion is fixed by two of its joints, `origin` and `toward`.
    Link {
        /// Origin joint.
        origin: usize,
        /// Second joint, setting the link's angle.
        toward: usize,
    },
    /// A slider block at `joint`, turning with its line's carrier (`None` for a fixed line).
    Block {
        /// The sliding joint.
        joint: usize,
        /// The carrying link's two joints, if the line turns.
        carrier: Option<(usize, usize)>,
    },
}

/// The bodies of a mechanism with capacity `N`: at most `2N + 1`.
///
/// ```
/// use linkage_core::{catalog, Bodies, BodyId, GROUND};
/// let bodies = Bodies::of(&catalog::hoecken::<f64>().mechanism());
/// // Ground, crank, coupler (which carries the foot P) and rocker.
/// assert_eq!(bodies.count(), 4);
/// let ids: Vec<BodyId> = bodies.ids().collect();
/// assert_eq!(ids[0], GROUND);
/// assert_eq!(ids[1..], [(2, 0), (3, 0), (3, 1)].map(|(joint, slot)| BodyId { joint, slot }));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Bodies<const N: usize> {
    created: [[Option<BodyFrame>; 2]; N],
    /// The body each carried point joined (None for other constructions).
    joined: [Option<BodyId>; N],
    len: usize,
}

/// Kutzbach–Gruebler count of a planar linkage.
///
/// ```
/// use linkage_core::{catalog, Bodies, Mobility};
/// // Kutzbach–Gruebler for a four-bar: 3(4 − 1) − 2·4 = 1.
/// let mob = Bodies::of(&catalog::hoecken::<f64>().mechanism()).mobility();
/// assert_eq!(mob, Mobility { links: 4, lower_pairs: 4, higher_pairs: 0 });
/// assert_eq!(mob.degrees_of_freedom(), 1);
/// // Counts no mechanism has: out of the i64 range, saturated or None.
/// let absurd = Mobility { links: 0, lower_pairs: usize::MAX, higher_pairs: usize::MAX };
/// assert_eq!(absurd.checked_degrees_of_freedom(), None);
/// assert_eq!(absurd.degrees_of_freedom(), i64::MIN);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mobility {
    /// Number of links `n`, the ground included.
    pub links: usize,
    /// Lower pairs `j1` (revolute and prismatic, one degree of freedom each). A joint shared by
    /// `k` links counts `k − 1`.
    pub lower_pairs: usize,
    /// Higher pairs `j2` (two degrees of freedom, e.g. a cam contact that rolls and slides).
    pub higher_pairs: usize,
}

impl Mobility {
    /// `F = 3(n − 1) − 2·j1 − j2`, saturating at the `i64` range (counts of a real mechanism
    /// are far inside it; the fields are public, so any value may arrive here).
    pub fn degrees_of_freedom(&self) -> i64 {
        // Each count is below 2⁶⁴, so the sum stays well inside i128.
        let (n, j1, j2) = (
            self.links as i128,
            self.lower_pairs as i128,
            self.higher_pairs as i128,
        );
        let f = 3 * (n - 1) - 2 * j1 - j2;
        f.clamp(i64::MIN as i128, i64::MAX as i128) as i64
    }

    /// `F = 3(n − 1) − 2·j1 − j2`, or `None` when it falls outside the `i64` range (only for
    /// counts no real mechanism has).
    pub fn checked_degrees_of_freedom(&self) -> Option<i64> {
        let (n, j1, j2) = (
            self.links as i128,
            self.lower_pairs as i128,
            self.higher_pairs as i128,
        );
        i64::try_from(3 * (n - 1) - 2 * j1 - j2).ok()
    }
}

impl<const N: usize> Bodies<N> {
    /// Derives the bodies of `mech`.
    pub fn of<T: RealField + Copy>(mech: &Mechanism<T, N>) -> Self {
        let mut b = Bodies {
            created: [[None; 2]; N],
            joined: [None; N],
            len: mech.len(),
        };
        for (i, c) in mech.constructions().iter().enumerate() {
            match *c {
                Construction::Fixed { .. } => b.joined[i] = Some(GROUND),
                Construction::Crank { centre, .. } => {
                    b.created[i][0] = Some(BodyFrame::Link {
                        origin: centre,
                        toward: i,
                    });
                }
                Construction::Dyad { p1, p2, .. } => {
                    b.created[i] = [
                        Some(BodyFrame::Link {
                            origin: p1,
                            toward: i,
                        }),
                        Some(BodyFrame::Link {
                            origin: p2,
                            toward: i,
                        }),
                    ];
                }
                Construction::Slider {
                    pivot, direction, ..
                } => {
                    let carrier = match direction {
                        LineDirection::Fixed(_) => None,
                        LineDirection::Link { from, to, .. } => Some((from, to)),
                    };
                    b.created[i] = [
                        Some(BodyFrame::Link {
                            origin: pivot,
                            toward: i,
                        }),
                        Some(BodyFrame::Block { joint: i, carrier }),
                    ];
                }
                Construction::Point { from, to, .. } => match b.holding(from, to) {
                    Some(body) => b.joined[i] = Some(body),
                    None => {
                        b.created[i][0] = Some(BodyFrame::Link {
                            origin: from,
                            toward: to,
                        })
                    }
                },
            }
        }
        b
    }

    /// Every body id, the ground first, then in program order.
    pub fn ids(&self) -> impl Iterator<Item = BodyId> + '_ {
        core::iter::once(GROUND).chain((0..self.len).flat_map(move |i| {
            (0..2u8).filter_map(move |slot| {
                self.created[i][usize::from(slot)].map(|_| BodyId { joint: i, slot })
            })
        }))
    }

    /// Number of bodies, the ground included.
    pub fn count(&self) -> usize {
        self.ids().count()
    }

    /// How body `id`'s motion is known ([`BodyFrame::Ground`] for the ground and for an id that
    /// names no body of this mechanism).
    pub fn frame(&self, id: BodyId) -> BodyFrame {
        if id == GROUND {
            return BodyFrame::Ground;
        }
        self.created
            .get(id.joint)
            .filter(|_| id.joint < self.len)
            .and_then(|slots| slots.get(usize::from(id.slot)))
            .copied()
            .flatten()
            .unwrap_or(BodyFrame::Ground)
    }

    /// Whether joint `j` is a joint of body `id` (a pin of it, or carried by it); false for a
    /// joint beyond the mechanism.
    pub fn contains(&self, id: BodyId, j: usize) -> bool {
        if j >= self.len {
            return false;
        }
        if self.joined.get(j) == Some(&Some(id)) {
            return true;
        }
        match self.frame(id) {
            BodyFrame::Ground => false,
            BodyFrame::Link { origin, toward } => origin == j || toward == j,
            BodyFrame::Block { joint, .. } => joint == j,
        }
    }

    /// A joint pinning bodies `k` and `l` together, if they share one.
    pub fn shared_joint(&self, k: BodyId, l: BodyId) -> Option<usize> {
        (0..self.len).find(|&j| self.contains(k, j) && self.contains(l, j))
    }

    /// The first body holding both joints `p` and `q`.
    fn holding(&self, p: usize, q: usize) -> Option<BodyId> {
        self.ids()
            .find(|&id| self.contains(id, p) && self.contains(id, q))
    }

    /// The body carrying a slider block's line: the ground for a fixed line.
    pub fn carrier_of(&self, frame: BodyFrame) -> Option<BodyId> {
        match frame {
            BodyFrame::Block { carrier: None, .. } => Some(GROUND),
            BodyFrame::Block {
                carrier: Some((p, q)),
                ..
            } => self.holding(p, q),
            _ => None,
        }
    }

    /// Kutzbach–Gruebler count: every joint shared by `k` bodies is `k − 1` revolutes, every
    /// slider block one prismatic pair with its line's carrier.
    pub fn mobility(&self) -> Mobility {
        let mut lower = 0;
        for j in 0..self.len {
            let k = self.ids().filter(|&id| self.contains(id, j)).count();
            lower += k.saturating_sub(1);
        }
        lower += self
            .ids()
            .filter(|&id| matches!(self.frame(id), BodyFrame::Block { .. }))
            .count();
        Mobility {
            links: self.count(),
            lower_pairs: lower,
            higher_pairs: 0,
        }
    }
}

impl<const N: usize> Bodies<N> {
    /// Pairs of joints that share a moving link (the ground's are fixed anyway), each once.
    fn link_pairs(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.ids().filter(|&id| id != GROUND).flat_map(move |id| {
            (0..self.len).flat_map(move |a| {
                (a + 1..self.len)
                    .filter(move |&b| self.contains(id, a) && self.contains(id, b))
                    .map(move |b| (a, b))
            })
        })
    }

    /// The loop-closure residual of a sweep: the largest change, over the samples whose
    /// joints are all finite, of a distance between two joints of one moving link (zero for
    /// exact kinematics: links are rigid). `joints` holds rows of [`Bodies`]' joint count.
    ///
    /// ```
    /// use linkage_core::{catalog, Bodies, Vec2};
    /// let m = catalog::hoecken::<f64>().mechanism();
    /// let mut rows = Vec::new();
    /// for k in 0..8 {
    ///     let mut j = [Vec2::zeros(); 5];
    ///     m.pose(k as f64, &mut j).unwrap();
    ///     rows.extend_from_slice(&j);
    /// }
    /// let b = Bodies::of(&m);
    /// assert!(b.closure_residual(&rows) < 1e-13);
    /// // The coupler point of one sample moved 0.5 further along its link: a residual of 0.5.
    /// let (a, bb) = (rows[5 * 3 + 2], rows[5 * 3 + 3]);
    /// rows[5 * 3 + 4] += (bb - a).normalize() * 0.5;
    /// assert!((b.closure_residual(&rows) - 0.5).abs() < 1e-12);
    /// ```
    pub fn closure_residual<T: RealField + Copy>(&self, joints: &[Vec2<T>]) -> T {
        let j = self.len.max(1);
        let rows = || {
            joints
                .chunks_exact(j)
                .filter(|r| r.iter().all(|p| p.x.is_finite() && p.y.is_finite()))
        };
        let mut worst = T::zero();
        for (a, b) in self.link_pairs() {
            let big = T::max_value().unwrap_or(T::one());
            let (mut lo, mut hi) = (big, -big);
            for r in rows() {
                let d = crate::numeric::scalar::length(r[b] - r[a]);
                lo = lo.min(d);
                hi = hi.max(d);
            }
            if hi >= lo {
                worst = worst.max(hi - lo);
            }
        }
        worst
    }

    /// The longest distance between two joints of one moving link in the pose `joints` (one
    /// row): the size a drawing of the linkage is scaled to.
    ///
    /// ```
    /// use linkage_core::{catalog, Bodies, Vec2};
    /// let m = catalog::hoecken::<f64>().mechanism();
    /// let mut j = [Vec2::zeros(); 5];
    /// m.pose(0.0, &mut j).unwrap();
    /// // The coupler carries the foot 50 from A: its longest span.
    /// assert!((Bodies::of(&m).longest_link(&j) - 50.0).abs() < 1e-12);
    /// ```
    pub fn longest_link<T: RealField + Copy>(&self, joints: &[Vec2<T>]) -> T {
        self.link_pairs()
            .filter(|&(_, b)| b < joints.len())
            .map(|(a, b)| crate::numeric::scalar::length(joints[b] - joints[a]))
            .fold(T::zero(), |acc, d| acc.max(d))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalog;

    /// Thesis 2 (Gruebler for the four-bar): n = 4, j1 = 4, F = 3(4 − 1) − 2·4 = +1.
    #[test]
    fn four_bar_mobility_matches_thesis_2() {
        let m = catalog::hoecken::<f64>().mechanism();
        let b = Bodies::of(&m);
        let mob = b.mobility();
        assert_eq!((mob.links, mob.lower_pairs), (4, 4), "(links, lower pairs)");
        assert_eq!(mob.degrees_of_freedom(), 1, "four-bar mobility");
        // The coupler point P joins the coupler A–B.
        let coupler = BodyId { joint: 3, slot: 0 };
        assert!(
            b.contains(coupler, 4) && b.contains(coupler, 2) && b.contains(coupler, 3),
            "coupler body holds joints 2, 3, 4: {}, {}, {}",
            b.contains(coupler, 2),
            b.contains(coupler, 3),
            b.contains(coupler, 4)
        );
    }

    /// Peaucellier: 8 links, 10 revolutes (docs/domain.md); Hart: 6 links, 7 revolutes.
    #[test]
    fn inversors_have_one_degree_of_freedom() {
        let p = Bodies::of(&catalog::peaucellier::<f64>().mechanism).mobility();
        assert_eq!(
            (p.links, p.lower_pairs, p.degrees_of_freedom()),
            (8, 10, 1),
            "Peaucellier (links, lower pairs, mobility)"
        );
        let h = Bodies::of(&catalog::hart::<f64>().mechanism).mobility();
        assert_eq!(
            (h.links, h.lower_pairs, h.degrees_of_freedom()),
            (6, 7, 1),
            "Hart (links, lower pairs, mobility)"
        );
        let g = Bodies::of(&catalog::hoecken_pantograph::<f64>(2.0).unwrap().mechanism).mobility();
        assert_eq!(
            (g.links, g.lower_pairs, g.degrees_of_freedom()),
            (8, 10, 1),
            "Hoecken pantograph (links, lower pairs, mobility)"
        );
        // Jansen's leg: frame, crank and two links per dyad (the rigid triangles b-d-e and
        // g-h-i are here pairs of binary links pinned together, which Gruebler counts alike).
        let j = Bodies::of(&catalog::jansen::<f64>().mechanism).mobility();
        assert_eq!(j.degrees_of_freedom(), 1, "Jansen mobility ({j:?})");
    }

    #[test]
    fn slider_crank_and_non_rigid_point() {
        use crate::{Reach, Vec2};
        let mut m = Mechanism::<f64, 6>::new();
        let o = m.fixed(Vec2::new(0.0, 0.0)).unwrap();
        let a = m.crank(o, 1.0, 0.0).unwrap();
        let s = m
            .slider(
                a,
                3.0,
                o,
                LineDirection::Fixed(Vec2::new(1.0, 0.0)),
                Reach::Ahead,
            )
            .unwrap();
        let mob = Bodies::of(&m).mobility();
        assert_eq!(
            (mob.links, mob.lower_pairs, mob.degrees_of_freedom()),
            (4, 4, 1),
            "slider-crank (links, lower pairs, mobility)"
        );
        // A point framed by two joints of different bodies is a new body pinned at both:
        // over-constrained, which the count reports.
        m.point(o, s, 1.0, 0.0).unwrap();
        let mob = Bodies::of(&m).mobility();
        assert_eq!(
            mob.degrees_of_freedom(),
            0,
            "mobility with a point pinned to two bodies ({mob:?})"
        );
    }
}
