//! The instruction set the binding's fast sweeps run (the four-bar's uniform sweep and the
//! mechanism sweep): one CPU check, shared by `linkages` and `mechanism`.

use pyo3::prelude::*;

/// Which build of the fast sweep runs on this CPU (only `simd_level` makes one).
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Simd {
    Portable,
    #[cfg_attr(
        not(target_arch = "x86_64"),
        allow(dead_code, reason = "made only by the x86_64 CPU check")
    )]
    Avx2,
    #[cfg_attr(
        not(target_arch = "x86_64"),
        allow(dead_code, reason = "made only by the x86_64 CPU check")
    )]
    Avx512,
}

pub(crate) fn simd_level() -> Simd {
    // LINKAGE_PORTABLE=1 keeps the portable build's code (for comparisons and tests).
    if std::env::var_os("LINKAGE_PORTABLE").is_some_and(|v| !v.is_empty() && v != "0") {
        return Simd::Portable;
    }
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::is_x86_feature_detected as has;
        if has!("avx512f") && has!("avx512dq") && has!("avx512vl") {
            return Simd::Avx512;
        }
        if has!("avx2") && has!("fma") {
            return Simd::Avx2;
        }
    }
    Simd::Portable
}

/// The instruction set the fast uniform sweep uses here: `"avx512"`, `"avx2"` or `"portable"`.
#[pyfunction]
#[pyo3(name = "instruction_set")]
pub fn sweep_simd() -> &'static str {
    match simd_level() {
        Simd::Avx512 => "avx512",
        Simd::Avx2 => "avx2",
        Simd::Portable => "portable",
    }
}
