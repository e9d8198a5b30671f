//! Shared property-test configuration.

use proptest::test_runner::{Config as ProptestConfig, FileFailurePersistence};

/// Cases per property: `LINKAGE_PROPTEST_CASES` (default 2000; `make fuzz` runs 1e5).
pub fn cases() -> u32 {
    std::env::var("LINKAGE_PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2000)
}

/// `cases()` cases, filters allowed to reject up to four times as many, and minimal failing
/// cases kept in `regressions` (a path under the crate, replayed first on every run).
pub fn config(regressions: &'static str) -> ProptestConfig {
    let cases = cases();
    ProptestConfig {
        cases,
        max_local_rejects: 4 * cases.max(1024),
        max_global_rejects: 4 * cases.max(1024),
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(regressions))),
        ..ProptestConfig::default()
    }
}
