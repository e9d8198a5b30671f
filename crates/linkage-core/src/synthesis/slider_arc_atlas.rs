//! An atlas of the open arcs of slider-crank coupler curves: the slider-crank twin of the
//! four-bar arc atlas ([`Atlas::build_arcs`]), for matching a target that is only a part of a
//! slider-crank's curve.
//!
//! # Entries
//! The circuits are the slider-crank atlas's candidates ([`slider_candidate`]: crank pivot at
//! the origin, crank 1, the line along `+x`, reach ahead), each sampled at
//! [`ArcSpec::samples`] points evenly spaced in the circuit parameter ([`SliderCircuit`]'s
//! closed form: a full turn evenly in the crank angle, a limited crank limit to limit and back
//! on the other reach). Every circuit gives an arc for each of [`ArcSpec::phases`] starting
//! samples and each fraction of [`ARC_FRACTIONS`], exactly as for four-bars; an entry's
//! parameters are the slider-crank atlas entry's and the arc's phase and fraction index
//! ([`SLIDER_ARC_ENTRY_PARAMS`]), and [`slider_arc_frame`] rebuilds the arc's normalisation
//! frame, so [`crate::place_slider_entry`] places the linkage on a target arc.
//!
//! # Determinism
//! As [`Atlas::build`]: built in chunks of candidates on threads, put back in index order.

use alloc::vec::Vec;

use crate::error::Error;
use crate::numeric::scalar::Vec2;
use crate::synthesis::arc_atlas::{
    arc_index, open_frame, push_arcs, slice_arc, ArcSpec, ARC_FRACTIONS,
};
use crate::synthesis::atlas::{
    each_slider_circuit, slider_circuit_points, slider_entry_linkage, Atlas, SLIDER_ENTRY_PARAMS,
};
use crate::synthesis::efd::Normalisation;

/// Parameters per slider-crank arc entry: `coupler, offset, along, left` as a slider-crank
/// atlas entry ([`SLIDER_ENTRY_PARAMS`]: crank 1, crank pivot at the origin, the line along
/// `+x`, reach ahead), then the arc's `phase` and the index of its fraction in
/// [`ARC_FRACTIONS`].
pub const SLIDER_ARC_ENTRY_PARAMS: usize = SLIDER_ENTRY_PARAMS + 2;

impl Atlas {
    /// Builds an atlas of `entries` open arcs of slider-crank circuits (see the module;
    /// parameters [`SLIDER_ARC_ENTRY_PARAMS`] an entry) on `threads` threads. The result does
    /// not depend on `threads`.
    ///
    /// ```
    /// use linkage_core::{nearest, slider_arc_frame, Atlas, ArcSpec, SLIDER_ARC_ENTRY_PARAMS};
    /// let spec = ArcSpec::default();
    /// let atlas = Atlas::build_slider_arcs(200, spec, 2).unwrap();
    /// assert_eq!(atlas, Atlas::build_slider_arcs(200, spec, 1).unwrap());
    /// assert_eq!(atlas.params.len(), 200 * SLIDER_ARC_ENTRY_PARAMS);
    /// // An arc's shape is nearest itself, and its frame can be rebuilt from its parameters.
    /// let query = &atlas.descriptors[9 * atlas.dim..10 * atlas.dim];
    /// assert_eq!(nearest(&atlas.descriptors, atlas.dim, query, 1, 1).unwrap(), [(9, 0.0, 0)]);
    /// let entry: [f64; SLIDER_ARC_ENTRY_PARAMS] = atlas.params[9 * 6..10 * 6].try_into().unwrap();
    /// assert!(slider_arc_frame(&entry, spec).unwrap().scale > 0.0);
    /// ```
    ///
    /// # Errors
    /// As [`Atlas::build_arcs`].
    pub fn build_slider_arcs(
        entries: usize,
        spec: ArcSpec,
        threads: usize,
    ) -> Result<Atlas, Error> {
        Self::build_arcs_with(entries, spec, threads, SLIDER_ARC_ENTRY_PARAMS, build_chunk)
    }
}

/// The arcs of a range of slider-crank candidates whose circuit assembles at every sample.
fn build_chunk(range: core::ops::Range<u64>, spec: ArcSpec) -> Atlas {
    let mut arc = Vec::with_capacity(spec.samples);
    each_slider_circuit(range, spec.closed(), |part, desc, i, sc, pts| {
        let mut params = [0.0; SLIDER_ARC_ENTRY_PARAMS];
        params[..SLIDER_ENTRY_PARAMS].copy_from_slice(&[sc.coupler, sc.offset, sc.along, sc.left]);
        push_arcs(part, desc, i, pts, spec, &mut params, &mut arc);
    })
}

/// The points of a slider-crank arc entry's arc, as [`Atlas::build_slider_arcs`] described it
/// (crank pivot at the origin, the line along `+x`).
///
/// ```
/// use linkage_core::{slider_arc_points, Atlas, ArcSpec, SLIDER_ARC_ENTRY_PARAMS};
/// let spec = ArcSpec::default();
/// let atlas = Atlas::build_slider_arcs(7, spec, 1).unwrap();
/// // The first circuit's arcs from phase 0, shortest first: 16 + 1 points for an eighth.
/// let entry: [f64; SLIDER_ARC_ENTRY_PARAMS] = atlas.params[..6].try_into().unwrap();
/// assert_eq!(slider_arc_points(&entry, spec).unwrap().len(), 17);
/// ```
///
/// # Errors
/// As [`Atlas::build_arcs`] for `spec`; [`Error::NotRepresentable`] (`"arc phase"`, `"arc
/// fraction"`) for an index out of range, the errors of [`SliderCrank::new`](crate::SliderCrank::new) for its numbers,
/// and [`Error::NotRepresentable`] (`"arc"`) when its circuit does not assemble at every
/// sample.
pub fn slider_arc_points(
    entry: &[f64; SLIDER_ARC_ENTRY_PARAMS],
    spec: ArcSpec,
) -> Result<Vec<Vec2<f64>>, Error> {
    spec.check()?;
    let [coupler, offset, along, left, phase, fraction] = *entry;
    let phase = arc_index(phase, spec.phases, "arc phase")?;
    let fraction = arc_index(fraction, ARC_FRACTIONS.len(), "arc fraction")?;
    let sc = slider_entry_linkage(coupler, offset, (along, left))?;
    let pts =
        slider_circuit_points(sc, spec.samples).ok_or(Error::NotRepresentable { what: "arc" })?;
    let mut arc = Vec::with_capacity(spec.samples);
    slice_arc(&pts, spec, phase, fraction, &mut arc);
    Ok(arc)
}

/// The normalisation frame of a slider-crank arc entry's arc ([`Efd::open`](crate::Efd::open) of
/// [`slider_arc_points`], normalised): with the target's frame,
/// [`crate::place_slider_entry`] places the entry's slider-crank on the target.
///
/// # Errors
/// As [`slider_arc_points`], [`Efd::open`](crate::Efd::open) and [`Efd::normalised`](crate::Efd::normalised).
#[doc(hidden)]
pub fn slider_arc_frame(
    entry: &[f64; SLIDER_ARC_ENTRY_PARAMS],
    spec: ArcSpec,
) -> Result<Normalisation<f64>, Error> {
    open_frame(&slider_arc_points(entry, spec)?, spec.harmonics)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthesis::atlas::nearest;
    use crate::synthesis::efd::query_descriptors;
    use crate::synthesis::slider_circuit::place_slider_entry;

    #[test]
    fn bad_entries_are_errors() {
        let spec = ArcSpec::default();
        let good = [2.0, 0.5, 1.0, 0.5, 3.0, 2.0];
        assert!(slider_arc_points(&good, spec).is_ok(), "a valid entry");
        for (k, v, what) in [
            (4, 8.0, "arc phase"),
            (4, 1.5, "arc phase"),
            (5, 7.0, "arc fraction"),
            (5, -1.0, "arc fraction"),
        ] {
            let mut e = good;
            e[k] = v;
            assert_eq!(
                slider_arc_points(&e, spec),
                Err(Error::NotRepresentable { what }),
                "entry {e:?}"
            );
        }
        let mut e = good;
        e[0] = -1.0;
        assert!(slider_arc_points(&e, spec).is_err(), "a negative rod");
        let bad_spec = ArcSpec { phases: 0, ..spec };
        assert!(slider_arc_points(&good, bad_spec).is_err(), "no phases");
    }

    /// An arc of the atlas, run backwards, moved, turned and scaled, finds its own entry as
    /// nearest, and the entry's frame places the slider-crank back onto it.
    #[test]
    fn a_stored_arc_is_found_and_placed_back() {
        let spec = ArcSpec::default();
        let atlas = Atlas::build_slider_arcs(3000, spec, 2).unwrap();
        let (d, w) = (atlas.dim, SLIDER_ARC_ENTRY_PARAMS);
        for e in [5usize, 777, 2999] {
            let entry: [f64; SLIDER_ARC_ENTRY_PARAMS] =
                atlas.params[e * w..(e + 1) * w].try_into().unwrap();
            let arc = slider_arc_points(&entry, spec).unwrap();
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
            let frame_c = slider_arc_frame(&entry, spec).unwrap();
            // One of the two ends of the major axis takes the entry's crank pivot (0, 0) to
            // (10, -4), its line (+x) to the direction 0.7, and the crank 1 to 3.
            let head: [f64; SLIDER_ENTRY_PARAMS] = entry[..SLIDER_ENTRY_PARAMS].try_into().unwrap();
            let ok = [false, true].iter().any(|&flip| {
                let p = place_slider_entry(&head, &frame_c, &frame_t, flip);
                let turn = (p[2] - 0.7).rem_euclid(core::f64::consts::TAU);
                (Vec2::new(p[0], p[1]) - Vec2::new(10.0, -4.0)).norm() < 1e-9
                    && turn.min(core::f64::consts::TAU - turn) < 1e-9
                    && (p[4] - 3.0).abs() < 1e-9
                    && (p[5] - 3.0 * entry[0]).abs() < 1e-9
            });
            assert!(ok, "entry {e} not placed back");
        }
    }
}
