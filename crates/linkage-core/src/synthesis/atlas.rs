//! An atlas of normalised four-bars and their coupler curves' shapes, for path synthesis: build
//! it in parallel, query it for the shapes nearest a target's.
//!
//! # Entries
//! Entry candidates are numbered `0, 1, 2, …`; candidate `i` is a four-bar with the ground
//! `O = (0, 0)`, `C = (1, 0)` whose crank, coupler and rocker are log-uniform in
//! [`LENGTH_RANGE`] of the ground, coupler point `(along, left) = coupler·(u, v)` with
//! `u ∈ [−1, 2]`, `v ∈ [−1.5, 1.5]`, and assembly open for even `i`, crossed for odd `i`
//! (so mirror images are both present: the mirror of an open linkage in the ground line is the
//! crossed one with `−left`). The five continuous numbers are the additive recurrence
//! `frac(½ + i·αⱼ)` with `αⱼ` the powers of the inverse of the plastic-number generalisation for
//! dimension 5 (Roberts' R-sequence), a low-discrepancy cover of the box that needs nothing but
//! `i`. Every Grashof class appears.
//!
//! A candidate becomes an entry when its whole circuit assembles (a limited crank's as
//! [`FourBar::circuit`] traces it with the tracker, by [`FourBarBatch`] (the tracker's branch and validity); a full
//! turn on the declared assembly by the [`FourBar::uniform_sweep`] fast path) at every sample, it is not a change point, and its curve
//! has a shape ([`Efd::normalised`]). An entry keeps its normalised descriptor
//! ([`Efd::descriptor`], `f32`) and its parameters ([`ENTRY_PARAMS`], `f64`).
//!
//! # Determinism
//! Entries are built in chunks of candidate indices, the chunks shared among threads and put
//! back in index order: the atlas's bits do not depend on the number of threads.

use alloc::vec::Vec;

use crate::constructions::slider::Reach;
use crate::error::Error;
use crate::linkages::batch::FourBarBatch;
use crate::linkages::fourbar::{Assembly, FourBar, GrashofClass, InputRange};
use crate::linkages::slider_crank::SliderCrank;
use crate::linkages::uniform_sweep::AngleMode;
use crate::numeric::scalar::Vec2;
use crate::synthesis::circuit::Circuit;
use crate::synthesis::efd::{descriptor_len, Efd};
use crate::synthesis::slider_circuit::SliderCircuit;

/// Link lengths of atlas four-bars relative to the ground: `(least, greatest)`.
pub const LENGTH_RANGE: (f64, f64) = (0.2, 5.0);

/// Parameters per entry: `crank, coupler, rocker, along, left, assembly` (ground 1; assembly
/// `0` open, `1` crossed).
pub const ENTRY_PARAMS: usize = 6;

/// Parameters per slider-crank entry ([`Atlas::build_slider_cranks`]): `coupler, offset,
/// along, left` (crank 1, crank pivot at the origin, line along `+x`, reach ahead).
pub const SLIDER_ENTRY_PARAMS: usize = 4;

/// Candidate indices per unit of parallel work.
const CHUNK: u64 = 2048;

/// Most threads [`Atlas::build`] starts (more would only add start-up time; the bits are the
/// same for any count).
const MAX_THREADS: usize = 256;

/// How an atlas is made.
///
/// ```
/// use linkage_core::{Atlas, AtlasSpec, Error};
/// let spec = AtlasSpec::default();
/// assert_eq!((spec.harmonics, spec.samples), (8, 64));
/// // Too few samples of a circuit to describe its shape.
/// let coarse = AtlasSpec { samples: 4, ..spec };
/// assert!(matches!(
///     Atlas::build(10, coarse, 1),
///     Err(Error::BufferLength { what: "circuit samples", .. })
/// ));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AtlasSpec {
    /// Harmonics of the descriptors.
    pub harmonics: usize,
    /// Samples of each circuit.
    pub samples: usize,
}

impl Default for AtlasSpec {
    /// 8 harmonics, 64 samples per circuit (ample for 8 harmonics; refinement works on the
    /// true curve).
    fn default() -> Self {
        AtlasSpec {
            harmonics: 8,
            samples: 64,
        }
    }
}

/// Atlas entries as flat arrays: `descriptors[i·D .. (i+1)·D]` and
/// `params[i·ENTRY_PARAMS ..]` of entry `i`, with `D = dim` (for a slider-crank atlas,
/// [`Atlas::build_slider_cranks`], rows of [`SLIDER_ENTRY_PARAMS`]).
///
/// ```
/// use linkage_core::{candidate, nearest, Atlas, AtlasSpec, ENTRY_PARAMS};
/// let atlas = Atlas::build(100, AtlasSpec::default(), 2).unwrap();
/// assert_eq!((atlas.len(), atlas.dim), (100, 29));
/// assert_eq!(Atlas::build(100, AtlasSpec::default(), 1).unwrap(), atlas); // any thread count
/// // An entry's parameters are its candidate's, and its shape is nearest itself.
/// let fb = candidate(atlas.candidate[7]).unwrap();
/// assert_eq!(atlas.params[7 * ENTRY_PARAMS], fb.crank);
/// let query = &atlas.descriptors[7 * atlas.dim..8 * atlas.dim];
/// assert_eq!(nearest(&atlas.descriptors, atlas.dim, query, 1, 1).unwrap(), [(7, 0.0, 0)]);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Atlas {
    /// Descriptor length `D` ([`descriptor_len`] of the harmonics).
    pub dim: usize,
    /// Normalised descriptors, row-major `(entries, D)`.
    pub descriptors: Vec<f32>,
    /// Parameters, row-major `(entries, ENTRY_PARAMS)`.
    pub params: Vec<f64>,
    /// Index of the candidate each entry came from.
    pub candidate: Vec<u64>,
}

impl Atlas {
    /// Appends an entry: its descriptor, parameters and candidate index.
    pub(crate) fn push(&mut self, desc: &[f32], params: &[f64], candidate: u64) {
        self.descriptors.extend_from_slice(desc);
        self.params.extend_from_slice(params);
        self.candidate.push(candidate);
    }

    /// Number of entries.
    pub fn len(&self) -> usize {
        self.candidate.len()
    }

    /// Whether the atlas is empty.
    pub fn is_empty(&self) -> bool {
        self.candidate.is_empty()
    }

    /// Builds an atlas of `entries` entries on `threads` threads (at least one, at most 256).
    /// The result does not depend on `threads`.
    ///
    /// # Errors
    /// [`Error::BufferLength`] for fewer than 1 harmonic or 8 samples; [`Error::CountOverflow`]
    /// for more entries, harmonics or samples than an address space holds.
    pub fn build(entries: usize, spec: AtlasSpec, threads: usize) -> Result<Atlas, Error> {
        Self::build_with(entries, spec, threads, ENTRY_PARAMS, 1, |r| {
            build_chunk(r, spec)
        })
    }

    /// Builds an atlas of `entries` slider-cranks ([`slider_candidate`]; parameters
    /// [`SLIDER_ENTRY_PARAMS`] an entry) on `threads` threads, as [`Atlas::build`] does
    /// four-bars. The result does not depend on `threads`.
    ///
    /// ```
    /// use linkage_core::{nearest, slider_candidate, Atlas, AtlasSpec, SLIDER_ENTRY_PARAMS};
    /// let atlas = Atlas::build_slider_cranks(50, AtlasSpec::default(), 2).unwrap();
    /// assert_eq!(atlas, Atlas::build_slider_cranks(50, AtlasSpec::default(), 1).unwrap());
    /// assert_eq!(atlas.params.len(), 50 * SLIDER_ENTRY_PARAMS);
    /// let sc = slider_candidate(atlas.candidate[3]).unwrap();
    /// assert_eq!(atlas.params[3 * SLIDER_ENTRY_PARAMS], sc.coupler);
    /// let query = &atlas.descriptors[3 * atlas.dim..4 * atlas.dim];
    /// assert_eq!(nearest(&atlas.descriptors, atlas.dim, query, 1, 1).unwrap(), [(3, 0.0, 0)]);
    /// ```
    ///
    /// # Errors
    /// As [`Atlas::build`].
    pub fn build_slider_cranks(
        entries: usize,
        spec: AtlasSpec,
        threads: usize,
    ) -> Result<Atlas, Error> {
        Self::build_with(entries, spec, threads, SLIDER_ENTRY_PARAMS, 1, |r| {
            build_slider_chunk(r, spec)
        })
    }

    /// [`Atlas::build`] with `chunk` making the entries of a range of candidates (at most
    /// `per_candidate` each), `params` numbers an entry.
    pub(crate) fn build_with(
        entries: usize,
        spec: AtlasSpec,
        threads: usize,
        params: usize,
        per_candidate: u64,
        chunk: impl Fn(core::ops::Range<u64>) -> Atlas + Sync,
    ) -> Result<Atlas, Error> {
        check_spec(spec)?;
        let dim = descriptor_len(spec.harmonics);
        // The descriptors (f32) and parameters (f64) of every entry must fit in memory: this
        // also keeps the counts below from overflowing.
        let row = dim.saturating_mul(4).max(params * 8);
        if entries
            .checked_mul(row)
            .is_none_or(|bytes| bytes > isize::MAX as usize)
        {
            return Err(Error::CountOverflow {
                what: "atlas entries",
            });
        }
        let threads = threads.clamp(1, MAX_THREADS);
        let mut atlas = Atlas {
            dim,
            ..Atlas::default()
        };
        // Candidates per chunk: about CHUNK entries a chunk.
        let span = (CHUNK / per_candidate.max(1)).max(1);
        let mut next_chunk = 0u64;
        while atlas.len() < entries {
            // A round of chunks, about enough for what is missing (half the candidates or
            // more give their entries), split among the threads and put back in order.
            let missing = (entries - atlas.len()) as u64;
            let round = (2 * missing)
                .div_ceil(span * per_candidate.max(1))
                .max(threads as u64);
            let chunks: Vec<u64> = (next_chunk..next_chunk + round).collect();
            next_chunk += round;
            let parts = crate::numeric::parallel::map_parts(chunks.len(), threads, |j| {
                let c = chunks[j];
                chunk(c * span..(c + 1) * span)
            });
            for p in parts {
                atlas.descriptors.extend_from_slice(&p.descriptors);
                atlas.params.extend_from_slice(&p.params);
                atlas.candidate.extend_from_slice(&p.candidate);
            }
        }
        atlas.descriptors.truncate(entries * dim);
        atlas.params.truncate(entries * params);
        atlas.candidate.truncate(entries);
        Ok(atlas)
    }
}

fn check_spec(spec: AtlasSpec) -> Result<(), Error> {
    if spec.harmonics == 0 {
        return Err(Error::BufferLength {
            what: "harmonics",
            expected: 1,
            got: 0,
        });
    }
    if spec.samples < 8 {
        return Err(Error::BufferLength {
            what: "circuit samples",
            expected: 8,
            got: spec.samples,
        });
    }
    // A circuit's points and its harmonics' coefficients are allocated whole: counts beyond the
    // address space are an error, not a capacity-overflow panic.
    let fits = |count: usize, size: usize| {
        count
            .checked_mul(size)
            .is_some_and(|bytes| bytes <= isize::MAX as usize)
    };
    if !fits(spec.samples, core::mem::size_of::<Vec2<f64>>()) {
        return Err(Error::CountOverflow {
            what: "circuit samples",
        });
    }
    if !fits(spec.harmonics, core::mem::size_of::<[f64; 4]>()) {
        return Err(Error::CountOverflow { what: "harmonics" });
    }
    Ok(())
}

fn build_chunk(range: core::ops::Range<u64>, spec: AtlasSpec) -> Atlas {
    each_circuit(range, spec, |part, desc, i, fb, pts| {
        if shape(Efd::closed(pts, spec.harmonics), desc) {
            part.push(desc, &entry_head(fb), i);
        }
    })
}

/// The part of an atlas that `add` makes from every candidate of `range` whose circuit
/// assembles at `spec.samples` samples: `add(part, descriptor buffer, index, linkage,
/// circuit)`.
pub(crate) fn each_circuit(
    range: core::ops::Range<u64>,
    spec: AtlasSpec,
    mut add: impl FnMut(&mut Atlas, &mut [f32], u64, &FourBar<f64>, &[Vec2<f64>]),
) -> Atlas {
    let dim = descriptor_len(spec.harmonics);
    let mut part = Atlas {
        dim,
        ..Atlas::default()
    };
    let mut desc = alloc::vec![0.0f32; dim];
    let mut circuit = CircuitSamples::new(spec.samples);
    for i in range {
        let Some(fb) = candidate(i) else { continue };
        let Some(pts) = circuit.of(&fb) else { continue };
        add(&mut part, &mut desc, i, &fb, pts);
    }
    part
}

/// An atlas entry's parameters of `fb` ([`ENTRY_PARAMS`]).
pub(crate) fn entry_head(fb: &FourBar<f64>) -> [f64; ENTRY_PARAMS] {
    let crossed = if fb.assembly == Assembly::Open {
        0.0
    } else {
        1.0
    };
    [fb.crank, fb.coupler, fb.rocker, fb.along, fb.left, crossed]
}

/// Writes the normalised descriptor of `efd` into `desc`; `false` when the curve has no shape
/// (no descriptors, a point-like first harmonic, a value that is not finite).
pub(crate) fn shape(efd: Result<Efd<f64>, Error>, desc: &mut [f32]) -> bool {
    let Ok((norm, _)) = efd.and_then(|e| e.normalised()) else {
        return false;
    };
    norm.descriptor(false, desc).is_ok() && desc.iter().all(|v| v.is_finite())
}

/// Buffers for sampling circuits at `samples` points, reused from one linkage to the next.
pub(crate) struct CircuitSamples {
    pts: Vec<Vec2<f64>>,
    theta: Vec<f64>,
    valid: Vec<bool>,
}

impl CircuitSamples {
    pub(crate) fn new(samples: usize) -> Self {
        CircuitSamples {
            pts: Vec::with_capacity(samples),
            theta: alloc::vec![0.0; samples],
            valid: alloc::vec![false; samples],
        }
    }

    /// `fb`'s circuit ([`circuit_points`]); `None` when a sample does not assemble.
    pub(crate) fn of(&mut self, fb: &FourBar<f64>) -> Option<&[Vec2<f64>]> {
        self.pts.clear();
        circuit_points(fb, &mut self.pts, &mut self.theta, &mut self.valid).then_some(&self.pts)
    }
}

/// [`build_chunk`] of slider-cranks: an entry for each candidate whose circuit assembles at
/// every sample (its closed form, [`SliderCircuit`]) and whose curve has a shape.
fn build_slider_chunk(range: core::ops::Range<u64>, spec: AtlasSpec) -> Atlas {
    each_slider_circuit(range, spec, |part, desc, i, sc, pts| {
        if shape(Efd::closed(pts, spec.harmonics), desc) {
            part.push(desc, &[sc.coupler, sc.offset, sc.along, sc.left], i);
        }
    })
}

/// [`each_circuit`] of the slider-crank atlas's candidates ([`slider_candidate`]): `add` gets
/// each one whose circuit ([`SliderCircuit::polyline`] of `spec.samples` points) assembles at
/// every sample.
pub(crate) fn each_slider_circuit(
    range: core::ops::Range<u64>,
    spec: AtlasSpec,
    mut add: impl FnMut(&mut Atlas, &mut [f32], u64, &SliderCrank<f64>, &[Vec2<f64>]),
) -> Atlas {
    let dim = descriptor_len(spec.harmonics);
    let mut part = Atlas {
        dim,
        ..Atlas::default()
    };
    let mut desc = alloc::vec![0.0f32; dim];
    for i in range {
        let Some(sc) = slider_candidate(i) else {
            continue;
        };
        let Some(pts) = slider_circuit_points(sc, spec.samples) else {
            continue;
        };
        add(&mut part, &mut desc, i, &sc, &pts);
    }
    part
}

/// The circuit of `sc` at `samples` points, or `None` when a sample does not assemble.
pub(crate) fn slider_circuit_points(
    sc: SliderCrank<f64>,
    samples: usize,
) -> Option<Vec<Vec2<f64>>> {
    let pts = SliderCircuit::new(sc).ok()?.polyline(samples);
    pts.iter()
        .all(|p| p.x.is_finite() && p.y.is_finite())
        .then_some(pts)
}

/// The coupler curve of `fb`'s circuit into `pts` (`theta.len()` samples); `false` when a
/// sample does not assemble.
///
/// A full turn is the [`FourBar::uniform_sweep`] fast path on the declared assembly. A limited
/// crank's circuit is [`FourBar::circuit`]'s (limit to limit on the declared assembly, back on
/// the other, at [`FourBar::circuit_sample`]'s angles), each half swept by [`FourBarBatch`],
/// whose rows are by its rule exactly the [`crate::Tracker`]'s at the same angles and ~30×
/// faster.
fn circuit_points(
    fb: &FourBar<f64>,
    pts: &mut Vec<Vec2<f64>>,
    theta: &mut [f64],
    valid: &mut [bool],
) -> bool {
    let n = theta.len();
    pts.resize(n, Vec2::zeros());
    match fb.input_range() {
        InputRange::Never => false,
        InputRange::Full => {
            let dt = core::f64::consts::TAU / n as f64;
            fb.uniform_sweep(0.0, dt, 0, AngleMode::Trig, pts).is_ok()
                && pts.iter().all(|p| p.x.is_finite() && p.y.is_finite())
        }
        _ => {
            let mut split = n;
            for (k, t) in theta.iter_mut().enumerate() {
                let Some((angle, second)) = fb.circuit_sample(k, n) else {
                    return false;
                };
                *t = angle;
                if second && split == n {
                    split = k;
                }
            }
            let mut other = *fb;
            other.assembly = match fb.assembly {
                Assembly::Open => Assembly::Crossed,
                Assembly::Crossed => Assembly::Open,
            };
            for (f, range) in [(fb, 0..split), (&other, split..n)] {
                let batch = FourBarBatch {
                    o: core::slice::from_ref(&f.o),
                    c: core::slice::from_ref(&f.c),
                    crank: core::slice::from_ref(&f.crank),
                    coupler: core::slice::from_ref(&f.coupler),
                    rocker: core::slice::from_ref(&f.rocker),
                    along: core::slice::from_ref(&f.along),
                    left: core::slice::from_ref(&f.left),
                    assembly: core::slice::from_ref(&f.assembly),
                };
                let r = range.clone();
                if batch
                    .sweep(&theta[r.clone()], &mut pts[r.clone()], &mut valid[r])
                    .is_err()
                {
                    return false;
                }
            }
            valid.iter().all(|&v| v)
        }
    }
}

/// φ₅ = 1.134724138401519492605446…, the root of x⁶ = x + 1 (Roberts' generalised golden ratio
/// in five dimensions). The root of x⁵ = x + 1 (1.1673…, φ₄), used before atlas format 3, makes
/// α₄ + α₅ = 1: the last two coordinates of every point summed to an integer, and the atlas
/// covered only a slice of its box (every coupler point on `u + v = ½`).
const ROBERTS_PHI: f64 = 1.134_724_138_401_519_5;

/// Point `i` of Roberts' five-dimensional low-discrepancy sequence in `[0, 1)⁵`:
/// `frac(½ + i·αⱼ)`, `αⱼ = φ^−j` with `φ` the root of `x⁶ = x + 1`.
fn sequence(i: u64) -> [f64; 5] {
    let mut u = [0.0f64; 5];
    let mut a = 1.0;
    for v in u.iter_mut() {
        a /= ROBERTS_PHI;
        let x = 0.5 + (i as f64) * a;
        *v = x - x.floor();
    }
    u
}

/// Candidate `i` of the atlas's sequence (see the module); `None` for a change point or a
/// linkage that never assembles.
#[doc(hidden)]
pub fn candidate(i: u64) -> Option<FourBar<f64>> {
    let u = sequence(i);
    let (lo, hi) = (LENGTH_RANGE.0.ln(), LENGTH_RANGE.1.ln());
    let len = |t: f64| (lo + (hi - lo) * t).exp();
    let (crank, coupler, rocker) = (len(u[0]), len(u[1]), len(u[2]));
    let along = coupler * (-1.0 + 3.0 * u[3]);
    let left = coupler * (-1.5 + 3.0 * u[4]);
    let assembly = if i.is_multiple_of(2) {
        Assembly::Open
    } else {
        Assembly::Crossed
    };
    let fb = FourBar::new(1.0, crank, coupler, rocker, (along, left), assembly).ok()?;
    if fb.grashof() == GrashofClass::ChangePoint || fb.input_range() == InputRange::Never {
        return None;
    }
    Some(fb)
}

/// φ₄ = 1.167303978261418684256045…, the root of x⁵ = x + 1: Roberts' generalised golden
/// ratio in four dimensions, for the slider-crank atlas's four shape numbers.
const ROBERTS_PHI4: f64 = 1.167_303_978_261_418_7;

/// Point `i` of Roberts' four-dimensional low-discrepancy sequence in `[0, 1)⁴`:
/// `frac(½ + i·αⱼ)`, `αⱼ = φ₄^−j`.
fn sequence4(i: u64) -> [f64; 4] {
    let mut u = [0.0f64; 4];
    let mut a = 1.0;
    for v in u.iter_mut() {
        a /= ROBERTS_PHI4;
        let x = 0.5 + (i as f64) * a;
        *v = x - x.floor();
    }
    u
}

/// Candidate `i` of the slider-crank atlas: crank pivot `(0, 0)`, crank 1, the line along
/// `+x`, [`Reach::Ahead`] (the other reach is the same linkage with the line reversed and the
/// offset negated, see [`SliderCrank`], so it adds no shape), and from point `i` of Roberts'
/// four-dimensional sequence the coupler log-uniform in [`LENGTH_RANGE`], the offset uniform
/// in `(−(1 + coupler), 1 + coupler)` (every offset at which the linkage moves; both signs, so
/// mirror images are both present), and the coupler point `coupler·(u, v)` with
/// `u ∈ [−1, 2]`, `v ∈ [−1.5, 1.5]` as for four-bars. `None` for a change point
/// (`|offset| + 1 = coupler`) or a linkage that does not move.
#[doc(hidden)]
pub fn slider_candidate(i: u64) -> Option<SliderCrank<f64>> {
    let u = sequence4(i);
    let (lo, hi) = (LENGTH_RANGE.0.ln(), LENGTH_RANGE.1.ln());
    let coupler = (lo + (hi - lo) * u[0]).exp();
    let offset = (1.0 + coupler) * (2.0 * u[1] - 1.0);
    let point = (coupler * (-1.0 + 3.0 * u[2]), coupler * (-1.5 + 3.0 * u[3]));
    let sc = slider_entry_linkage(coupler, offset, point).ok()?;
    (!sc.is_change_point() && sc.input_range() != InputRange::Never).then_some(sc)
}

/// The slider-crank of a slider-crank atlas entry: crank pivot at the origin, crank 1, the line
/// along `+x`, reach ahead.
pub(crate) fn slider_entry_linkage(
    coupler: f64,
    offset: f64,
    point: (f64, f64),
) -> Result<SliderCrank<f64>, Error> {
    SliderCrank::new(
        Vec2::zeros(),
        0.0,
        offset,
        1.0,
        coupler,
        point,
        Reach::Ahead,
    )
}

/// The `k` entries nearest (squared Euclidean distance of descriptors) any of `targets`
/// (`K` rows of `dim`), by brute force over `descriptors` (`N` rows of `dim`) on `threads`
/// threads: `(entry, squared distance, which target)`, nearest first, ties by entry index.
///
/// # Errors
/// [`Error::BufferLength`] when `dim` is zero or does not divide the arrays' lengths.
#[doc(hidden)]
pub fn nearest(
    descriptors: &[f32],
    dim: usize,
    targets: &[f32],
    k: usize,
    threads: usize,
) -> Result<Vec<(usize, f32, usize)>, Error> {
    if dim == 0 || !descriptors.len().is_multiple_of(dim) || !targets.len().is_multiple_of(dim) {
        return Err(Error::BufferLength {
            what: "descriptor rows",
            expected: dim,
            got: descriptors.len() % dim.max(1) + targets.len() % dim.max(1),
        });
    }
    let n = descriptors.len() / dim;
    if k == 0 || n == 0 || targets.is_empty() {
        return Ok(Vec::new());
    }
    // No more results than pairs of an entry and a target (which also bounds the lists'
    // allocation whatever `k` is asked).
    let k = k.min(n.saturating_mul(targets.len() / dim));
    let threads = threads.clamp(1, n.div_ceil(4096).max(1));
    let per = n.div_ceil(threads);
    let mut best: Vec<(usize, f32, usize)> =
        crate::numeric::parallel::map_parts(threads, threads, |t| {
            let rows = (t * per).min(n)..((t + 1) * per).min(n);
            scan(
                &descriptors[rows.start * dim..rows.end * dim],
                dim,
                targets,
                k,
                rows.start,
            )
        })
        .into_iter()
        .flatten()
        .collect();
    best.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
    best.truncate(k);
    Ok(best)
}

/// One thread's share of [`nearest`]: a sorted short list of the best `k`.
fn scan(
    part: &[f32],
    dim: usize,
    targets: &[f32],
    k: usize,
    offset: usize,
) -> Vec<(usize, f32, usize)> {
    let mut best: Vec<(usize, f32, usize)> = Vec::with_capacity(k + 1);
    let mut worst = f32::INFINITY;
    for (r, row) in part.chunks_exact(dim).enumerate() {
        for (t, target) in targets.chunks_exact(dim).enumerate() {
            let d = squared_distance(row, target);
            if best.len() < k || d < worst {
                let at = best.partition_point(|x| x.1 <= d);
                best.insert(at, (offset + r, d, t));
                best.truncate(k);
                if best.len() == k {
                    worst = best[k - 1].1;
                }
            }
        }
    }
    best
}

/// `Σ (a − b)²` in eight independent lanes (so the compiler can vectorise the sum; the
/// lanes are added in a fixed order, so the result does not depend on the machine).
#[inline(always)]
fn squared_distance(a: &[f32], b: &[f32]) -> f32 {
    let mut lanes = [0.0f32; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            let e = x[k] - y[k];
            lanes[k] += e * e;
        }
    }
    let mut tail = 0.0f32;
    for (x, y) in ra.iter().zip(rb) {
        let e = x - y;
        tail += e * e;
    }
    ((lanes[0] + lanes[4]) + (lanes[1] + lanes[5]))
        + ((lanes[2] + lanes[6]) + (lanes[3] + lanes[7]))
        + tail
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sequence's φ solves x⁶ = x + 1, and its points fill the five-dimensional box: each
    /// coordinate has the mean of uniform points and every pair is uncorrelated to sampling
    /// accuracy (with φ₄ instead, the last two coordinates were anti-correlated, `u + v = ½`).
    #[test]
    fn the_sequence_fills_its_box() {
        let phi = ROBERTS_PHI;
        let residual = phi.powi(6) - phi - 1.0;
        assert!(residual.abs() < 1e-15, "φ⁶ − φ − 1 = {residual:e}");
        let n = 20_000u64;
        let pts: Vec<[f64; 5]> = (0..n).map(sequence).collect();
        let mean = |a: usize| pts.iter().map(|p| p[a]).sum::<f64>() / n as f64;
        for a in 0..5 {
            assert!(
                (mean(a) - 0.5).abs() < 0.01,
                "coordinate {a}: mean {}",
                mean(a)
            );
            for b in a + 1..5 {
                let cov = pts.iter().map(|p| (p[a] - 0.5) * (p[b] - 0.5)).sum::<f64>() / n as f64;
                // Correlation = covariance over the uniform variance 1/12.
                let corr = 12.0 * cov;
                assert!(corr.abs() < 0.1, "coordinates {a}, {b}: correlation {corr}");
            }
        }
    }

    #[test]
    fn build_is_the_same_on_any_number_of_threads() {
        let spec = AtlasSpec {
            harmonics: 5,
            samples: 64,
        };
        let one = Atlas::build(3000, spec, 1).unwrap();
        let three = Atlas::build(3000, spec, 3).unwrap();
        assert_eq!(one.len(), 3000, "entries built on one thread");
        assert_eq!(
            one, three,
            "atlas built on one thread differs from three threads'"
        );
        // Every Grashof class but the change point is present.
        let mut seen = std::collections::HashSet::new();
        for &i in &one.candidate {
            seen.insert(candidate(i).unwrap().grashof());
        }
        assert_eq!(seen.len(), 5, "{seen:?}");
    }

    #[test]
    fn an_entry_is_its_own_nearest() {
        let spec = AtlasSpec::default();
        let atlas = Atlas::build(2000, spec, 2).unwrap();
        let d = atlas.dim;
        for e in [0, 17, 1999] {
            let q = &atlas.descriptors[e * d..(e + 1) * d];
            let hits = nearest(&atlas.descriptors, d, q, 3, 2).unwrap();
            assert_eq!(hits[0].0, e, "nearest to entry {e}: {hits:?}");
            assert_eq!(hits[0].1, 0.0, "distance of entry {e} to itself: {hits:?}");
            assert!(
                hits[1].1 >= hits[0].1,
                "hits for entry {e} not by distance: {hits:?}"
            );
        }
    }
}
