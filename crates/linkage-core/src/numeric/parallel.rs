//! Work split among threads with results in a fixed order, so a result's bits never depend on
//! the number of threads (feature `std`).

use alloc::vec::Vec;
use core::ops::Range;

/// `work(0), work(1), …, work(parts − 1)` on up to `threads` threads (at least one), in order.
///
/// Consecutive parts go to the same thread. A thread that cannot be started (a resource limit)
/// does its share on the calling thread instead, so the call never fails for lack of threads.
///
/// # Panics
/// Only if `work` panics; the panic is passed on (no part is ever silently left out).
pub(crate) fn map_parts<R, F>(parts: usize, threads: usize, work: F) -> Vec<R>
where
    R: Send,
    F: Fn(usize) -> R + Sync,
{
    let threads = threads.clamp(1, parts.max(1));
    if threads == 1 {
        return (0..parts).map(work).collect();
    }
    let per = parts.div_ceil(threads);
    let work = &work;
    std::thread::scope(|scope| {
        let mut pending: Vec<Result<std::thread::ScopedJoinHandle<'_, Vec<R>>, Range<usize>>> =
            Vec::with_capacity(threads);
        for t in 0..threads {
            let range = (t * per).min(parts)..((t + 1) * per).min(parts);
            let mine = range.clone();
            let job = move || mine.map(work).collect::<Vec<R>>();
            pending.push(
                std::thread::Builder::new()
                    .spawn_scoped(scope, job)
                    .map_err(|_| range),
            );
        }
        let mut out = Vec::with_capacity(parts);
        for p in pending {
            match p {
                Ok(handle) => match handle.join() {
                    Ok(v) => out.extend(v),
                    Err(panic) => std::panic::resume_unwind(panic),
                },
                Err(range) => out.extend(range.map(work)),
            }
        }
        out
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_come_back_in_order_for_any_thread_count() {
        for threads in [1, 2, 3, 7, 64] {
            for parts in [0, 1, 5, 100] {
                let v = map_parts(parts, threads, |i| i * i);
                assert_eq!(
                    v,
                    (0..parts).map(|i| i * i).collect::<Vec<_>>(),
                    "{threads} {parts}"
                );
            }
        }
    }
}
