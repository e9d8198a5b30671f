//! An atlas of the open arcs of four-bar coupler curves, for matching a target that is only a
//! part of a curve.
//!
//! # Entries
//! The circuits are the [`Atlas`]'s candidates ([`crate::candidate`]), each sampled at
//! [`ArcSpec::samples`] points evenly spaced in the circuit parameter (the closed atlas's
//! sampling: a full turn evenly in the crank angle from 0, a limited crank limit to limit and
//! back at [`FourBar::circuit_sample`]'s angles). Every circuit gives an arc for each of
//! [`ArcSpec::phases`] evenly spaced starting samples and each fraction of [`ARC_FRACTIONS`]
//! of the circuit (`round(fraction · samples)` segments from the start, wrapping round). An
//! arc's descriptor is that of an open target ([`Efd::open`], normalised), so a target arc
//! finds arcs of the same shape whatever its placement, scale and direction of travel; the
//! entry's parameters name the linkage and the arc ([`ARC_ENTRY_PARAMS`]), and [`arc_points`]
//! rebuilds the arc, so its normalisation frame ([`arc_frame`]) places the linkage on the
//! target.
//!
//! A target's arc rarely starts at a stored phase or spans a stored fraction: the nearest
//! entries are starting guesses for a least-squares fit of the true point-to-curve distance.
//!
//! # Determinism
//! As [`Atlas::build`]: built in chunks of candidates on threads, put back in index order.

use alloc::vec::Vec;

use crate::error::Error;
use crate::linkages::fourbar::{Assembly, FourBar};
use crate::numeric::scalar::Vec2;
use crate::synthesis::atlas::{each_circuit, entry_head, shape, Atlas, AtlasSpec, CircuitSamples};
use crate::synthesis::efd::{Efd, Normalisation};

/// Fractions of a circuit that atlas arcs span, shortest first.
pub const ARC_FRACTIONS: [f64; 7] = [0.125, 0.1875, 0.25, 0.375, 0.5, 0.625, 0.75];

/// Parameters per arc entry: `crank, coupler, rocker, along, left, assembly` as an
/// [`Atlas`] entry (ground `(0, 0)`–`(1, 0)`; assembly `0` open, `1` crossed), then the arc's
/// `phase` (its first sample is `phase · samples / phases`) and the index of its fraction in
/// [`ARC_FRACTIONS`].
pub const ARC_ENTRY_PARAMS: usize = 8;

/// How an arc atlas is made.
///
/// ```
/// use linkage_core::ArcSpec;
/// let spec = ArcSpec::default();
/// assert_eq!((spec.harmonics, spec.samples, spec.phases), (8, 128, 8));
/// assert_eq!(spec.arcs_per_circuit(), 56);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ArcSpec {
    /// Harmonics of the descriptors.
    pub harmonics: usize,
    /// Samples of each circuit.
    pub samples: usize,
    /// Starting samples per circuit, evenly spaced.
    pub phases: usize,
}

impl Default for ArcSpec {
    /// 8 harmonics, 128 samples a circuit (16 on the shortest arc), 8 starts.
    fn default() -> Self {
        ArcSpec {
            harmonics: 8,
            samples: 128,
            phases: 8,
        }
    }
}

impl ArcSpec {
    /// Entries a circuit gives: `phases · ARC_FRACTIONS.len()`.
    pub fn arcs_per_circuit(&self) -> usize {
        self.phases.saturating_mul(ARC_FRACTIONS.len())
    }

    pub(crate) fn check(&self) -> Result<(), Error> {
        if self.phases == 0 || self.phases > self.samples {
            return Err(Error::BufferLength {
                what: "arc phases",
                expected: self.samples.clamp(1, usize::MAX),
                got: self.phases,
            });
        }
        // The shortest arc needs a few segments to have a shape.
        if self.samples < 32 {
            return Err(Error::BufferLength {
                what: "arc circuit samples",
                expected: 32,
                got: self.samples,
            });
        }
        Ok(())
    }

    pub(crate) fn closed(&self) -> AtlasSpec {
        AtlasSpec {
            harmonics: self.harmonics,
            samples: self.samples,
        }
    }
}

impl Atlas {
    /// Builds an atlas of `entries` arcs (see the module; parameters [`ARC_ENTRY_PARAMS`] an
    /// entry) on `threads` threads. The result does not depend on `threads`.
    ///
    /// ```
    /// use linkage_core::{arc_frame, nearest, Atlas, ArcSpec, ARC_ENTRY_PARAMS};
    /// let spec = ArcSpec::default();
    /// let atlas = Atlas::build_arcs(200, spec, 2).unwrap();
    /// assert_eq!(atlas, Atlas::build_arcs(200, spec, 1).unwrap());
    /// assert_eq!(atlas.params.len(), 200 * ARC_ENTRY_PARAMS);
    /// // An arc's shape is nearest itself, and its frame can be rebuilt from its parameters.
    /// let query = &atlas.descriptors[9 * atlas.dim..10 * atlas.dim];
    /// assert_eq!(nearest(&atlas.descriptors, atlas.dim, query, 1, 1).unwrap(), [(9, 0.0, 0)]);
    /// let entry: [f64; ARC_ENTRY_PARAMS] = atlas.params[9 * 8..10 * 8].try_into().unwrap();
    /// assert!(arc_frame(&entry, spec).unwrap().scale > 0.0);
    /// ```
    ///
    /// # Errors
    /// As [`Atlas::build`]; [`Error::BufferLength`] for fewer than 32 samples (`"arc circuit
    /// samples"`) or no phases or more phases than samples (`"arc phases"`).
    pub fn build_arcs(entries: usize, spec: ArcSpec, threads: usize) -> Result<Atlas, Error> {
        Self::build_arcs_with(entries, spec, threads, ARC_ENTRY_PARAMS, build_arc_chunk)
    }

    /// [`Atlas::build_with`] of arcs: `chunk` gives the arcs of a range of candidates,
    /// `params` numbers an entry.
    pub(crate) fn build_arcs_with(
        entries: usize,
        spec: ArcSpec,
        threads: usize,
        params: usize,
        chunk: impl Fn(core::ops::Range<u64>, ArcSpec) -> Atlas + Sync,
    ) -> Result<Atlas, Error> {
        spec.check()?;
        let per = spec.arcs_per_circuit() as u64;
        Self::build_with(entries, spec.closed(), threads, params, per, |r| {
            chunk(r, spec)
        })
    }
}

/// The arcs of a range of candidates.
fn build_arc_chunk(range: core::ops::Range<u64>, spec: ArcSpec) -> Atlas {
    let mut arc = Vec::with_capacity(spec.samples);
    each_circuit(range, spec.closed(), |part, desc, i, fb, pts| {
        let mut params = [0.0; ARC_ENTRY_PARAMS];
        params[..6].copy_from_slice(&entry_head(fb));
        push_arcs(part, desc, i, pts, spec, &mut params, &mut arc);
    })
}

/// Pushes every arc of candidate `i`'s sampled `circuit` that has a shape: `params` holds the
/// entry's linkage, and its last two numbers are set to each arc's phase and fraction index.
pub(crate) fn push_arcs(
    part: &mut Atlas,
    desc: &mut [f32],
    i: u64,
    circuit: &[Vec2<f64>],
    spec: ArcSpec,
    params: &mut [f64],
    arc: &mut Vec<Vec2<f64>>,
) {
    let at = params.len() - 2;
    for phase in 0..spec.phases {
        for fraction in 0..ARC_FRACTIONS.len() {
            slice_arc(circuit, spec, phase, fraction, arc);
            if shape(Efd::open(arc, spec.harmonics), desc) {
                params[at..].copy_from_slice(&[phase as f64, fraction as f64]);
                part.push(desc, params, i);
            }
        }
    }
}

/// The arc `(phase, fraction)` of the sampled `circuit` into `out`: `round(fraction · n) + 1`
/// samples from sample `phase · n / phases`, wrapping round.
pub(crate) fn slice_arc(
    circuit: &[Vec2<f64>],
    spec: ArcSpec,
    phase: usize,
    fraction: usize,
    out: &mut Vec<Vec2<f64>>,
) {
    let n = circuit.len();
    let start = phase * n / spec.phases;
    let segments = (ARC_FRACTIONS[fraction] * n as f64).round() as usize;
    out.clear();
    out.extend((0..=segments).map(|k| circuit[(start + k) % n]));
}

/// An arc entry's index `v` (its phase or fraction) as a `usize` below `len`, or
/// [`Error::NotRepresentable`] naming `what`.
pub(crate) fn arc_index(v: f64, len: usize, what: &'static str) -> Result<usize, Error> {
    if v >= 0.0 && v < len as f64 && v.fract() == 0.0 {
        Ok(v as usize)
    } else {
        Err(Error::NotRepresentable { what })
    }
}

/// The linkage of an arc entry (ground `(0, 0)`–`(1, 0)`) and its arc's `phase` and fraction
/// index, checked.
fn arc_entry(
    entry: &[f64; ARC_ENTRY_PARAMS],
    spec: ArcSpec,
) -> Result<(FourBar<f64>, usize, usize), Error> {
    spec.check()?;
    let [crank, coupler, rocker, along, left, assembly, phase, fraction] = *entry;
    let phase = arc_index(phase, spec.phases, "arc phase")?;
    let fraction = arc_index(fraction, ARC_FRACTIONS.len(), "arc fraction")?;
    let assembly = if assembly == 0.0 {
        Assembly::Open
    } else {
        Assembly::Crossed
    };
    let fb = FourBar::new(1.0, crank, coupler, rocker, (along, left), assembly)?;
    Ok((fb, phase, fraction))
}

/// The points of an arc entry's arc, as [`Atlas::build_arcs`] described it (ground
/// `(0, 0)`–`(1, 0)`).
///
/// ```
/// use linkage_core::{arc_points, Atlas, ArcSpec, ARC_ENTRY_PARAMS};
/// let spec = ArcSpec::default();
/// let atlas = Atlas::build_arcs(7, spec, 1).unwrap();
/// // The first circuit's arcs from phase 0, shortest first: 16 + 1 points for an eighth.
/// let entry: [f64; ARC_ENTRY_PARAMS] = atlas.params[..8].try_into().unwrap();
/// assert_eq!(arc_points(&entry, spec).unwrap().len(), 17);
/// ```
///
/// # Errors
/// As [`Atlas::build_arcs`] for `spec`; [`Error::NotRepresentable`] (`"arc phase"`, `"arc
/// fraction"`) for an index out of range, the errors of [`FourBar::new`] for its lengths, and
/// [`Error::NotRepresentable`] (`"arc"`) when its circuit does not assemble at every sample.
pub fn arc_points(entry: &[f64; ARC_ENTRY_PARAMS], spec: ArcSpec) -> Result<Vec<Vec2<f64>>, Error> {
    let (fb, phase, fraction) = arc_entry(entry, spec)?;
    let mut circuit = CircuitSamples::new(spec.samples);
    let pts = circuit
        .of(&fb)
        .ok_or(Error::NotRepresentable { what: "arc" })?;
    let mut arc = Vec::with_capacity(spec.samples);
    slice_arc(pts, spec, phase, fraction, &mut arc);
    Ok(arc)
}

/// The normalisation frame of an arc entry's arc ([`Efd::open`] of [`arc_points`],
/// normalised): with the target's frame, [`crate::place_entry`] places the entry's linkage on
/// the target.
///
/// # Errors
/// As [`arc_points`], [`Efd::open`] and [`Efd::normalised`].
#[doc(hidden)]
pub fn arc_frame(
    entry: &[f64; ARC_ENTRY_PARAMS],
    spec: ArcSpec,
) -> Result<Normalisation<f64>, Error> {
    open_frame(&arc_points(entry, spec)?, spec.harmonics)
}

/// The normalisation frame of an open curve ([`Efd::open`] with `harmonics`, normalised).
pub(crate) fn open_frame(arc: &[Vec2<f64>], harmonics: usize) -> Result<Normalisation<f64>, Error> {
    Ok(Efd::open(arc, harmonics)?.normalised()?.1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthesis::atlas::nearest;
    use crate::synthesis::efd::query_descriptors;

    #[test]
    fn bad_specs_and_entries_are_errors() {
        let spec = ArcSpec::default();
        for bad in [
            ArcSpec { phases: 0, ..spec },
            ArcSpec {
                phases: 200,
                ..spec
            },
            ArcSpec {
                samples: 16,
                ..spec
            },
        ] {
            let got = Atlas::build_arcs(10, bad, 1);
            assert!(
                matches!(got, Err(Error::BufferLength { .. })),
                "{bad:?}: want a BufferLength error, got {:?}",
                got.map(|a| a.len())
            );
        }
        let good = [1.0, 2.0, 1.5, 0.5, 0.5, 0.0, 3.0, 2.0];
        let got = arc_points(&good, spec);
        assert!(got.is_ok(), "entry {good:?} rejected: {:?}", got.err());
        for (k, v, what) in [
            (6, 8.0, "arc phase"),
            (7, 1.5, "arc fraction"),
            (6, -1.0, "arc phase"),
        ] {
            let mut e = good;
            e[k] = v;
            assert_eq!(
                arc_points(&e, spec),
                Err(Error::NotRepresentable { what }),
                "entry {e:?} ({what} {v} at index {k})"
            );
        }
    }

    /// An arc cut from a circuit at a stored phase and fraction, moved, scaled and reversed,
    /// finds its own entry, and the entry's frame places the linkage back onto it.
    #[test]
    fn a_stored_arc_is_found_and_placed_back() {
        let spec = ArcSpec::default();
        let atlas = Atlas::build_arcs(2000, spec, 2).unwrap();
        let d = atlas.dim;
        for e in [5usize, 300, 1234] {
            let entry: [f64; ARC_ENTRY_PARAMS] =
                atlas.params[e * 8..(e + 1) * 8].try_into().unwrap();
            let arc = arc_points(&entry, spec).unwrap();
            let (s, c) = 0.7f64.sin_cos();
            let moved: Vec<Vec2<f64>> = arc
                .iter()
                .rev()
                .map(|p| {
                    Vec2::new(
                        3.0 * (c * p.x - s * p.y) + 10.0,
                        3.0 * (s * p.x + c * p.y) - 4.0,
                    )
                })
                .collect();
            let mut q = alloc::vec![0.0f32; 4 * d];
            let frame_t = query_descriptors(&moved, spec.harmonics, false, &mut q).unwrap();
            let hits = nearest(&atlas.descriptors, d, &q, 1, 1).unwrap();
            assert_eq!(hits[0].0, e, "{hits:?}");
            assert!(hits[0].1 < 1e-8, "{hits:?}");
            let frame_c = arc_frame(&entry, spec).unwrap();
            // One of the two ends of the major axis takes the entry's ground (0, 0)-(1, 0) to
            // the moved ground.
            let want = [
                Vec2::new(10.0, -4.0),
                Vec2::new(10.0 + 3.0 * c, -4.0 + 3.0 * s),
            ];
            let head: [f64; 5] = entry[..5].try_into().unwrap();
            let ok = [false, true].iter().any(|&flip| {
                let p = crate::synthesis::circuit::place_entry(&head, &frame_c, &frame_t, flip);
                (Vec2::new(p[0], p[1]) - want[0]).norm() < 1e-9
                    && (Vec2::new(p[2], p[3]) - want[1]).norm() < 1e-9
                    && (p[4] - 3.0 * entry[0]).abs() < 1e-9
            });
            assert!(ok, "entry {e} not placed back");
        }
    }
}
