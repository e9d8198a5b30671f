//! Kinetostatics: joint reactions and driver torque by Newton–Euler, and the driver torque by
//! the power method. Needs the `alloc` feature (a dense linear solve sized by the linkage).

use alloc::vec;
use alloc::vec::Vec;

use nalgebra::{DMatrix, DVector, RealField};

use crate::error::{check_finite, Error};
use crate::mechanism::bodies::{Bodies, BodyFrame, BodyId, GROUND};
use crate::mechanism::program::{Construction, Mechanism};
use crate::motion::centres::BodyMotion;
use crate::numeric::scalar::{cross, perp, Vec2};

/// Mass properties of one body, its centre of mass in the body's frame: `along` its frame's
/// axis (from the frame's origin joint toward its second joint, or along a slider's line) and
/// `left` of it.
///
/// ```
/// use linkage_core::{catalog, Dynamics, Inertia, Vec2};
/// // Hoecken's linkage held still at θ = 0, its crank of mass 2 with the centre of mass halfway
/// // along it (5 from O) under gravity 9.81, the other links massless: the driver holds the
/// // crank's weight at its lever, 2·9.81·5.
/// let m = catalog::hoecken::<f64>().mechanism();
/// let none = Inertia { mass: 0.0, along: 0.0, left: 0.0, inertia: 0.0 };
/// let crank = Inertia { mass: 2.0, along: 5.0, ..none };
/// // One entry per body, the ground first: ground, crank, coupler, rocker.
/// let dynamics = Dynamics::new(&m, &[none, crank, none, none], Vec2::new(0.0, -9.81)).unwrap();
/// let mut p = [Vec2::zeros(); 5];
/// m.pose(0.0, &mut p).unwrap();
/// let still = [Vec2::zeros(); 5];
/// let sol = dynamics.solve(&p, &still, &still, &[]).unwrap();
/// assert!((sol.torque - 98.1).abs() < 1e-9);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inertia<T> {
    /// Mass.
    pub mass: T,
    /// Centre of mass: distance along the frame's axis.
    pub along: T,
    /// Centre of mass: distance to the left of the axis.
    pub left: T,
    /// Moment of inertia about the centre of mass.
    pub inertia: T,
}

/// An external load on a body: a force applied at a joint of it, and a torque.
///
/// ```
/// use linkage_core::{Assembly, Bodies, Dynamics, FourBar, Inertia, Load, Vec2};
/// // A parallelogram's coupler translates, so a weight W anywhere on it needs the crank torque
/// // W·r·cos θ (virtual work).
/// let fb = FourBar::new(3.0_f64, 1.0, 3.0, 1.0, (1.5, 0.0), Assembly::Open).unwrap();
/// let m = fb.mechanism();
/// let none = Inertia { mass: 0.0, along: 0.0, left: 0.0, inertia: 0.0 };
/// let dynamics = Dynamics::new(&m, &[none; 4], Vec2::zeros()).unwrap();
/// let coupler = Bodies::of(&m).ids().nth(2).unwrap();
/// let load = Load { body: coupler, joint: 4, force: Vec2::new(0.0, -7.0), torque: 0.0 };
/// let (mut p, still) = ([Vec2::zeros(); 5], [Vec2::zeros(); 5]);
/// m.pose(1.0, &mut p).unwrap();
/// let sol = dynamics.solve(&p, &still, &still, &[load]).unwrap();
/// assert!((sol.torque - 7.0 * 1.0_f64.cos()).abs() < 1e-12);
/// // A load at a joint the mechanism does not have is refused.
/// assert!(dynamics.solve(&p, &still, &still, &[Load { joint: 9, ..load }]).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Load<T> {
    /// The body loaded.
    pub body: BodyId,
    /// The joint the force acts at.
    pub joint: usize,
    /// The force.
    pub force: Vec2<T>,
    /// A torque (counter-clockwise positive).
    pub torque: T,
}

/// The force a joint transmits between two bodies.
///
/// ```
/// use linkage_core::{Assembly, Bodies, Dynamics, FourBar, Inertia, Load, Vec2};
/// // A weight of 7 on a massless parallelogram's coupler: the ground pins O and C carry it.
/// let fb = FourBar::new(3.0_f64, 1.0, 3.0, 1.0, (1.5, 0.0), Assembly::Open).unwrap();
/// let m = fb.mechanism();
/// let none = Inertia { mass: 0.0, along: 0.0, left: 0.0, inertia: 0.0 };
/// let dynamics = Dynamics::new(&m, &[none; 4], Vec2::zeros()).unwrap();
/// let coupler = Bodies::of(&m).ids().nth(2).unwrap();
/// let load = Load { body: coupler, joint: 4, force: Vec2::new(0.0, -7.0), torque: 0.0 };
/// let (mut p, still) = ([Vec2::zeros(); 5], [Vec2::zeros(); 5]);
/// m.pose(1.0, &mut p).unwrap();
/// let sol = dynamics.solve(&p, &still, &still, &[load]).unwrap();
/// let ground: f64 = sol.reactions.iter().filter(|r| r.joint <= 1).map(|r| r.force.y).sum();
/// assert!((ground - 7.0).abs() < 1e-12);
/// assert!(sol.reactions.iter().all(|r| r.couple == 0.0)); // pins only
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reaction<T> {
    /// The joint.
    pub joint: usize,
    /// The body exerting the force.
    pub from: BodyId,
    /// The body receiving it.
    pub to: BodyId,
    /// The force on `to` (the force on `from` is its negative).
    pub force: Vec2<T>,
    /// For a slider block on its line, the couple on `to`; zero at pins.
    pub couple: T,
}

/// Result of a kinetostatic solve at one instant.
///
/// ```
/// use linkage_core::{catalog, Dynamics, Inertia, Vec2};
/// let m = catalog::hoecken::<f64>().mechanism();
/// let none = Inertia { mass: 0.0, along: 0.0, left: 0.0, inertia: 0.0 };
/// let dynamics = Dynamics::new(&m, &[none; 4], Vec2::zeros()).unwrap();
/// let (mut p, still) = ([Vec2::zeros(); 5], [Vec2::zeros(); 5]);
/// m.pose(0.5, &mut p).unwrap();
/// let sol = dynamics.solve(&p, &still, &still, &[]).unwrap();
/// // Massless and unloaded: no torque, and the reactions come in the layout's order.
/// assert!(sol.torque.abs() < 1e-12);
/// let layout: Vec<_> = dynamics.reaction_layout().collect();
/// assert_eq!(sol.reactions.len(), layout.len());
/// assert!(sol.reactions.iter().zip(&layout).all(|(r, &l)| (r.joint, r.from, r.to) == l));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ForceSolution<T> {
    /// Driver torque on the crank (from the body carrying the crank's centre).
    pub torque: T,
    /// Every joint and slider reaction.
    pub reactions: Vec<Reaction<T>>,
}

/// Unknown-force bookkeeping for one mechanism.
#[derive(Clone, Debug)]
struct Unknown {
    joint: usize,
    from: BodyId,
    to: BodyId,
    /// For a prismatic pair: the line's unit normal is the force direction, plus a couple.
    prismatic: bool,
}

/// The dynamic problem of a mechanism: bodies, their mass properties, gravity.
///
/// ```
/// use linkage_core::{catalog, Dynamics, Error, Inertia, Mechanism, Vec2};
/// let m = catalog::hoecken::<f64>().mechanism();
/// let none = Inertia { mass: 0.0, along: 0.0, left: 0.0, inertia: 0.0 };
/// // One inertia per body (4 here), and a crank to drive.
/// assert!(matches!(
///     Dynamics::new(&m, &[none; 3], Vec2::zeros()),
///     Err(Error::BufferLength { expected: 4, got: 3, .. })
/// ));
/// let mut frame = Mechanism::<f64, 1>::new();
/// frame.fixed(Vec2::zeros()).unwrap();
/// assert!(matches!(Dynamics::new(&frame, &[none], Vec2::zeros()), Err(Error::NoDriver)));
/// // The power method needs the crank to move: at rest it has no torque to give.
/// let crank = Inertia { mass: 2.0, along: 5.0, ..none };
/// let dynamics = Dynamics::new(&m, &[none, crank, none, none], Vec2::new(0.0, -9.81)).unwrap();
/// let (mut p, still) = ([Vec2::zeros(); 5], [Vec2::zeros(); 5]);
/// m.pose(0.0, &mut p).unwrap();
/// assert!(dynamics.power_torque(&p, &still, &still, &[]).is_nan());
/// ```
#[derive(Clone, Debug)]
pub struct Dynamics<'m, T: RealField + Copy, const N: usize> {
    mech: &'m Mechanism<T, N>,
    bodies: Bodies<N>,
    ids: Vec<BodyId>,
    inertia: Vec<Inertia<T>>,
    gravity: Vec2<T>,
    unknowns: Vec<Unknown>,
    /// Index (into `ids`) of the crank's body.
    driver: usize,
    /// The body the crank turns on (usually the ground).
    driver_base: BodyId,
}

impl<'m, T: RealField + Copy, const N: usize> Dynamics<'m, T, N> {
    /// Sets up the Newton–Euler system: `inertia` gives one entry per body of
    /// [`Bodies::ids`] (the ground's is ignored); `gravity` is the acceleration of gravity.
    ///
    /// Unknowns: at a pin shared by bodies `b0, b1, …` the forces on `b1, …` from `b0` (the pin
    /// is massless, so `b0` gets minus their sum); at a slider block, the normal force and couple
    /// from its line's carrier; the driver torque. With one degree of freedom there are exactly
    /// `3 × (moving bodies)` of them — the thesis-2 9×9 system for a four-bar.
    ///
    /// # Errors
    /// [`Error::NoDriver`]; [`Error::BufferLength`] for a wrong number of inertia entries or a
    /// linkage whose mobility is not one (then the system is not square).
    pub fn new(
        mech: &'m Mechanism<T, N>,
        inertia: &[Inertia<T>],
        gravity: Vec2<T>,
    ) -> Result<Self, Error> {
        let driver = mech.driver().ok_or(Error::NoDriver)?;
        let bodies = Bodies::of(mech);
        let ids: Vec<BodyId> = bodies.ids().collect();
        if inertia.len() != ids.len() {
            return Err(Error::BufferLength {
                what: "inertia (one per body, ground first)",
                expected: ids.len(),
                got: inertia.len(),
            });
        }
        for i in inertia {
            for (what, v) in [
                ("mass", i.mass),
                ("centre of mass along", i.along),
                ("centre of mass left", i.left),
                ("moment of inertia", i.inertia),
            ] {
                check_finite(what, v)?;
            }
        }
        check_finite("gravity x", gravity.x)?;
        check_finite("gravity y", gravity.y)?;
        let mut unknowns = Vec::new();
        for j in 0..mech.len() {
            let incident: Vec<BodyId> = ids
                .iter()
                .copied()
                .filter(|&b| bodies.contains(b, j))
                .collect();
            for &to in incident.iter().skip(1) {
                unknowns.push(Unknown {
                    joint: j,
                    from: incident[0],
                    to,
                    prismatic: false,
                });
            }
        }
        for &b in &ids {
            if let BodyFrame::Block { joint, .. } = bodies.frame(b) {
                let carrier = bodies.carrier_of(bodies.frame(b)).unwrap_or(GROUND);
                unknowns.push(Unknown {
                    joint,
                    from: carrier,
                    to: b,
                    prismatic: true,
                });
            }
        }
        let pins = unknowns.iter().filter(|u| !u.prismatic).count();
        let size = 2 * pins + 2 * (unknowns.len() - pins) + 1;
        if size != 3 * (ids.len() - 1) {
            return Err(Error::BufferLength {
                what: "kinetostatic unknowns (the linkage's mobility must be one)",
                expected: 3 * (ids.len() - 1),
                got: size,
            });
        }
        // `driver()` names the crank's joint (set only when a crank is pushed), so this always
        // matches; a typed error rather than a panic keeps that an invariant, not a promise.
        let Some(&Construction::Crank { centre, .. }) = mech.constructions().get(driver) else {
            return Err(Error::NoDriver);
        };
        let driver_base = ids
            .iter()
            .copied()
            .find(|&b| bodies.contains(b, centre))
            .unwrap_or(GROUND);
        let driver_body = BodyId {
            joint: driver,
            slot: 0,
        };
        let driver = ids.iter().position(|&b| b == driver_body).unwrap_or(0);
        Ok(Dynamics {
            mech,
            bodies,
            ids,
            inertia: inertia.to_vec(),
            gravity,
            unknowns,
            driver,
            driver_base,
        })
    }

    /// The bodies, ground first (the order of the inertia entries).
    pub fn body_ids(&self) -> &[BodyId] {
        &self.ids
    }

    /// `(joint, from, to)` of every reaction [`Dynamics::solve`] returns, in its order: the
    /// layout is fixed by the mechanism, so callers can size their outputs before solving.
    pub fn reaction_layout(&self) -> impl ExactSizeIterator<Item = (usize, BodyId, BodyId)> + '_ {
        self.unknowns.iter().map(|u| (u.joint, u.from, u.to))
    }

    /// Checks the pose slices and the loads' joints against the mechanism.
    fn check_inputs(
        &self,
        pos: &[Vec2<T>],
        vel: &[Vec2<T>],
        acc: &[Vec2<T>],
        loads: &[Load<T>],
    ) -> Result<(), Error> {
        let n = self.mech.len();
        for (what, got) in [
            ("joints", pos.len()),
            ("velocities", vel.len()),
            ("accelerations", acc.len()),
        ] {
            if got != n {
                return Err(Error::BufferLength {
                    what,
                    expected: n,
                    got,
                });
            }
        }
        if let Some(l) = loads.iter().find(|l| l.joint >= n) {
            return Err(Error::UnknownJoint {
                joint: n,
                refers_to: l.joint,
            });
        }
        Ok(())
    }

    /// Centre of mass of body `k` (index into [`Dynamics::body_ids`]) at a pose.
    fn centre_of_mass(&self, k: usize, pos: &[Vec2<T>]) -> Vec2<T> {
        let inert = self.inertia[k];
        let (origin, axis) = match self.bodies.frame(self.ids[k]) {
            BodyFrame::Ground => (Vec2::zeros(), Vec2::new(T::one(), T::zero())),
            BodyFrame::Link { origin, toward } => (pos[origin], pos[toward] - pos[origin]),
            BodyFrame::Block { joint, carrier } => (
                pos[joint],
                carrier.map_or(Vec2::new(T::one(), T::zero()), |(p, q)| pos[q] - pos[p]),
            ),
        };
        let n = axis.norm();
        let u = if n > T::zero() {
            axis / n
        } else {
            Vec2::new(T::one(), T::zero())
        };
        origin + u * inert.along + perp(u) * inert.left
    }

    /// Unit normal of a slider block's line.
    fn line_normal(&self, b: BodyId, pos: &[Vec2<T>]) -> Vec2<T> {
        let i = b.joint;
        match self.mech.constructions()[i] {
            Construction::Slider { direction, .. } => {
                let u = direction.at(pos).unwrap_or(Vec2::new(T::one(), T::zero()));
                perp(u)
            }
            _ => Vec2::new(T::zero(), T::one()),
        }
    }

    /// Newton–Euler solve at one instant from joint positions, velocities and accelerations
    /// (for the actual drive, in time).
    ///
    /// For each moving body: `Σ F = m a_G − m g − F_ext` and
    /// `Σ (r − G) × F + couples = I α − Σ (r_ext − G) × F_ext − τ_ext`.
    ///
    /// # Panics
    /// Never for a mechanism's own sizes: the dense system is `3(b − 1)` square for `b ≤ 2N + 1`
    /// bodies (at most 384 × 384 for the Python binding's `N = 64`). Only a capacity `N` in the
    /// tens of thousands, chosen at compile time, could make its allocation fail (an abort).
    ///
    /// # Errors
    /// [`Error::Coincident`] (joint = the driver) when the system is singular: a toggle, where
    /// statics cannot decide the reactions; [`Error::BufferLength`] when a slice is not
    /// [`Mechanism::len`] long; [`Error::UnknownJoint`] for a load at a joint beyond it.
    pub fn solve(
        &self,
        pos: &[Vec2<T>],
        vel: &[Vec2<T>],
        acc: &[Vec2<T>],
        loads: &[Load<T>],
    ) -> Result<ForceSolution<T>, Error> {
        self.check_inputs(pos, vel, acc, loads)?;
        let nb = self.ids.len();
        let size = 3 * (nb - 1);
        let mut a = DMatrix::<T>::zeros(size, size);
        let mut rhs = DVector::<T>::zeros(size);
        let zero = vec![Vec2::zeros(); pos.len()];
        let row_of = |b: BodyId| {
            self.ids
                .iter()
                .position(|&x| x == b)
                .filter(|&k| k > 0)
                .map(|k| 3 * (k - 1))
        };
        let centres: Vec<Vec2<T>> = (0..nb).map(|k| self.centre_of_mass(k, pos)).collect();
        // Inertial and gravity terms.
        for (k, (&id, &g)) in self.ids.iter().zip(&centres).enumerate().skip(1) {
            let m = BodyMotion::of(&self.bodies, id, pos, vel, acc, &zero);
            let inert = self.inertia[k];
            let a_g = m.acceleration_at(g);
            let r = 3 * (k - 1);
            let f = a_g * inert.mass - self.gravity * inert.mass;
            rhs[r] = f.x;
            rhs[r + 1] = f.y;
            rhs[r + 2] = inert.inertia * m.alpha;
        }
        for l in loads {
            if let Some(r) = row_of(l.body) {
                let k = r / 3 + 1;
                rhs[r] -= l.force.x;
                rhs[r + 1] -= l.force.y;
                rhs[r + 2] -= cross(pos[l.joint] - centres[k], l.force) + l.torque;
            }
        }
        // Unknown reactions: columns 2q, 2q + 1; the torque last.
        for (q, u) in self.unknowns.iter().enumerate() {
            let p = pos[u.joint];
            let (c0, c1) = (2 * q, 2 * q + 1);
            for (body, sign) in [(u.to, T::one()), (u.from, -T::one())] {
                let Some(r) = row_of(body) else { continue };
                let g = centres[r / 3 + 1];
                if u.prismatic {
                    let n = self.line_normal(u.to, pos);
                    a[(r, c0)] += n.x * sign;
                    a[(r + 1, c0)] += n.y * sign;
                    a[(r + 2, c0)] += cross(p - g, n) * sign;
                    a[(r + 2, c1)] += sign;
                } else {
                    a[(r, c0)] += sign;
                    a[(r + 1, c1)] += sign;
                    let d = p - g;
                    // (d × F)_z = d.x F.y − d.y F.x
                    a[(r + 2, c0)] += -d.y * sign;
                    a[(r + 2, c1)] += d.x * sign;
                }
            }
        }
        let t = size - 1;
        if let Some(r) = row_of(self.ids[self.driver]) {
            a[(r + 2, t)] += T::one();
        }
        if let Some(r) = row_of(self.driver_base) {
            a[(r + 2, t)] -= T::one();
        }
        let x = a.lu().solve(&rhs).ok_or(Error::Coincident {
            joint: self.mech.driver().unwrap_or(0),
        })?;
        if !x.iter().all(|v| v.is_finite()) {
            return Err(Error::Coincident {
                joint: self.mech.driver().unwrap_or(0),
            });
        }
        let reactions = self
            .unknowns
            .iter()
            .enumerate()
            .map(|(q, u)| {
                let (f, couple) = if u.prismatic {
                    (self.line_normal(u.to, pos) * x[2 * q], x[2 * q + 1])
                } else {
                    (Vec2::new(x[2 * q], x[2 * q + 1]), T::zero())
                };
                Reaction {
                    joint: u.joint,
                    from: u.from,
                    to: u.to,
                    force: f,
                    couple,
                }
            })
            .collect();
        Ok(ForceSolution {
            torque: x[t],
            reactions,
        })
    }

    /// Driver torque by the power method: the driver's power equals the rate of change of
    /// kinetic energy plus the power against gravity and the external loads,
    /// `T (ω_crank − ω_base) = Σ (m a_G·v_G + I α ω) − Σ m g·v_G − Σ F_ext·v_P − Σ τ_ext ω`.
    /// No joint force enters. NaN when the crank is at rest relative to its base, and for
    /// inputs [`Dynamics::solve`] would reject (slices of the wrong length, a load's joint
    /// beyond the mechanism).
    pub fn power_torque(
        &self,
        pos: &[Vec2<T>],
        vel: &[Vec2<T>],
        acc: &[Vec2<T>],
        loads: &[Load<T>],
    ) -> T {
        if self.check_inputs(pos, vel, acc, loads).is_err() {
            return crate::numeric::scalar::nan::<T>();
        }
        let zero = vec![Vec2::zeros(); pos.len()];
        let motions: Vec<BodyMotion<T>> = self
            .ids
            .iter()
            .map(|&b| BodyMotion::of(&self.bodies, b, pos, vel, acc, &zero))
            .collect();
        let mut power = T::zero();
        for (k, &m) in motions.iter().enumerate().skip(1) {
            let inert = self.inertia[k];
            let g = self.centre_of_mass(k, pos);
            let (v_g, a_g) = (m.velocity_at(g), m.acceleration_at(g));
            power +=
                inert.mass * (a_g - self.gravity).dot(&v_g) + inert.inertia * m.alpha * m.omega;
        }
        for l in loads {
            if let Some(k) = self.ids.iter().position(|&b| b == l.body) {
                let m = motions[k];
                power -= l.force.dot(&m.velocity_at(pos[l.joint])) + l.torque * m.omega;
            }
        }
        let base = self
            .ids
            .iter()
            .position(|&b| b == self.driver_base)
            .unwrap_or(0);
        let rel = motions[self.driver].omega - motions[base].omega;
        power / rel
    }
}

/// A load along a sweep: one force and torque per sample, on `body` at `joint`.
///
/// ```
/// use linkage_core::{Assembly, Bodies, Dynamics, ForceSweep, FourBar, Inertia, LoadSeries, Vec2};
/// // A weight growing along a sweep of a massless parallelogram: W_k·r·cos θ_k at each sample,
/// // by Newton–Euler and by the power method.
/// let fb = FourBar::new(3.0_f64, 1.0, 3.0, 1.0, (1.5, 0.0), Assembly::Open).unwrap();
/// let m = fb.mechanism();
/// let none = Inertia { mass: 0.0, along: 0.0, left: 0.0, inertia: 0.0 };
/// let dynamics = Dynamics::new(&m, &[none; 4], Vec2::zeros()).unwrap();
/// let theta = [0.5, 1.0, 1.5];
/// let force = [Vec2::new(0.0, -1.0), Vec2::new(0.0, -2.0), Vec2::new(0.0, -3.0)];
/// let coupler = Bodies::of(&m).ids().nth(2).unwrap();
/// let loads = [LoadSeries { body: coupler, joint: 4, force: &force, torque: &[0.0; 3] }];
/// let nr = dynamics.reaction_layout().count();
/// let (mut torque, mut power, mut valid) = ([0.0; 3], [0.0; 3], [false; 3]);
/// let (mut reactions, mut couples) = (vec![Vec2::zeros(); 3 * nr], vec![0.0; 3 * nr]);
/// let out = ForceSweep {
///     torque: &mut torque,
///     power_torque: &mut power,
///     valid: &mut valid,
///     reactions: &mut reactions,
///     couples: &mut couples,
/// };
/// dynamics.sweep(&theta, &[1.0; 3], &[0.0; 3], &loads, out).unwrap();
/// for k in 0..3 {
///     let want = (k + 1) as f64 * theta[k].cos();
///     assert!((torque[k] - want).abs() < 1e-12 && (power[k] - want).abs() < 1e-12);
/// }
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadSeries<'a, T> {
    /// The body loaded.
    pub body: BodyId,
    /// The joint the force acts at.
    pub joint: usize,
    /// The force at each sample.
    pub force: &'a [Vec2<T>],
    /// The torque at each sample (counter-clockwise positive).
    pub torque: &'a [T],
}

/// Where [`Dynamics::sweep`] writes, one entry per sample (`reactions`/`couples`: one row of
/// [`Dynamics::reaction_layout`]'s length per sample). Samples that do not assemble, or sit at a
/// toggle where statics cannot decide the reactions, are NaN with `valid` false.
///
/// ```
/// use linkage_core::{catalog, Dynamics, ForceSweep, Inertia, Vec2};
/// // Evans C swept to θ = 2, past its input limit (±75.5°): that sample is NaN and not valid.
/// let m = catalog::evans_c::<f64>().mechanism();
/// let none = Inertia { mass: 0.0, along: 0.0, left: 0.0, inertia: 0.0 };
/// let dynamics = Dynamics::new(&m, &[none; 4], Vec2::zeros()).unwrap();
/// let nr = dynamics.reaction_layout().count();
/// let (mut torque, mut power, mut valid) = ([0.0; 3], [0.0; 3], [true; 3]);
/// let (mut reactions, mut couples) = (vec![Vec2::zeros(); 3 * nr], vec![0.0; 3 * nr]);
/// let out = ForceSweep {
///     torque: &mut torque,
///     power_torque: &mut power,
///     valid: &mut valid,
///     reactions: &mut reactions,
///     couples: &mut couples,
/// };
/// dynamics.sweep(&[0.0, 2.0, 0.5], &[1.0; 3], &[0.0; 3], &[], out).unwrap();
/// assert_eq!(valid, [true, false, true]);
/// assert!(torque[1].is_nan() && power[1].is_nan() && reactions[nr].x.is_nan());
/// assert!(torque[0].abs() < 1e-12); // massless and unloaded
/// ```
#[derive(Debug)]
pub struct ForceSweep<'a, T> {
    /// Driver torque by Newton–Euler.
    pub torque: &'a mut [T],
    /// Driver torque by the power method (an independent check of `torque`).
    pub power_torque: &'a mut [T],
    /// Whether the sample was solved.
    pub valid: &'a mut [bool],
    /// Joint reactions, row-major `(sample, reaction)`.
    pub reactions: &'a mut [Vec2<T>],
    /// Slider couples, row-major `(sample, reaction)`; zero at pins.
    pub couples: &'a mut [T],
}

impl<T: RealField + Copy, const N: usize> Dynamics<'_, T, N> {
    /// Kinetostatics along a sweep: the mechanism tracked through crank angles `theta` at
    /// crank rates `omega`, `alpha` (one per sample), each sample solved by [`Dynamics::solve`]
    /// and [`Dynamics::power_torque`] under `loads`.
    ///
    /// # Errors
    /// [`Error::BufferLength`] when an input or output slice does not hold one entry (one row
    /// for reactions and couples) per sample; [`Error::UnknownJoint`] for a load at a joint
    /// beyond the mechanism; what [`crate::Tracker::new`] returns for a mechanism it cannot
    /// track. A sample that cannot be solved is not an error (it is NaN and not `valid`).
    pub fn sweep(
        &self,
        theta: &[T],
        omega: &[T],
        alpha: &[T],
        loads: &[LoadSeries<'_, T>],
        out: ForceSweep<'_, T>,
    ) -> Result<(), Error> {
        let n = theta.len();
        let nr = self.reaction_layout().count();
        let len = |what: &'static str, expected: usize, got: usize| {
            if expected == got {
                Ok(())
            } else {
                Err(Error::BufferLength {
                    what,
                    expected,
                    got,
                })
            }
        };
        len("omega (one per angle)", n, omega.len())?;
        len("alpha (one per angle)", n, alpha.len())?;
        for l in loads {
            len("load force (one per angle)", n, l.force.len())?;
            len("load torque (one per angle)", n, l.torque.len())?;
            if l.joint >= self.mech.len() {
                return Err(Error::UnknownJoint {
                    joint: self.mech.len(),
                    refers_to: l.joint,
                });
            }
        }
        len("torque", n, out.torque.len())?;
        len("power torque", n, out.power_torque.len())?;
        len("valid", n, out.valid.len())?;
        let rows = n.checked_mul(nr).ok_or(Error::BufferLength {
            what: "reactions (samples × reactions)",
            expected: usize::MAX,
            got: out.reactions.len(),
        })?;
        len("reactions (samples × reactions)", rows, out.reactions.len())?;
        len("couples (samples × reactions)", rows, out.couples.len())?;
        let nan = crate::numeric::scalar::nan::<T>();
        let j = self.mech.len();
        let mut tracker = crate::sweep::tracker::Tracker::new(self.mech)?;
        let (mut p, mut v, mut a) = ([Vec2::zeros(); N], [Vec2::zeros(); N], [Vec2::zeros(); N]);
        let mut sample_loads = Vec::with_capacity(loads.len());
        for k in 0..n {
            out.valid[k] = false;
            out.torque[k] = nan;
            out.power_torque[k] = nan;
            let row = k * nr..(k + 1) * nr;
            out.reactions[row.clone()].fill(Vec2::new(nan, nan));
            out.couples[row.clone()].fill(nan);
            let rates = crate::sweep::tracker::Rates::acceleration(&mut v[..j], &mut a[..j]);
            let motion = crate::mechanism::program::CrankRates::new(omega[k], alpha[k]);
            if tracker
                .step(theta[k], Some(motion), &mut p[..j], rates)
                .is_err()
            {
                continue;
            }
            sample_loads.clear();
            sample_loads.extend(loads.iter().map(|l| Load {
                body: l.body,
                joint: l.joint,
                force: l.force[k],
                torque: l.torque[k],
            }));
            let Ok(sol) = self.solve(&p[..j], &v[..j], &a[..j], &sample_loads) else {
                continue;
            };
            out.valid[k] = true;
            out.torque[k] = sol.torque;
            out.power_torque[k] = self.power_torque(&p[..j], &v[..j], &a[..j], &sample_loads);
            // `solve` returns one reaction per layout entry, in its order.
            for (q, r) in sol.reactions.iter().take(nr).enumerate() {
                out.reactions[k * nr + q] = r.force;
                out.couples[k * nr + q] = r.couple;
            }
        }
        Ok(())
    }
}
