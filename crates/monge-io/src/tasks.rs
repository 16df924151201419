//! Independent pieces of work side by side, one thread per core (one thread
//! where there are none, as in WebAssembly), their results in order: the same
//! whatever the number of threads.

use std::sync::atomic::{AtomicUsize, Ordering};

/// `f(0), f(1), …, f(n − 1)`, computed side by side by up to one thread per
/// core (this one included), each taking the next index left, returned in
/// order. A panic in `f` is passed on.
pub(crate) fn map<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get());
    let next = AtomicUsize::new(0);
    let work = || {
        let mut done = Vec::new();
        loop {
            let k = next.fetch_add(1, Ordering::Relaxed);
            if k >= n {
                return done;
            }
            done.push((k, f(k)));
        }
    };
    let mut all = std::thread::scope(|scope| {
        let helpers: Vec<_> = (1..threads.min(n)).map(|_| scope.spawn(work)).collect();
        let mut all = work();
        for helper in helpers {
            all.extend(
                helper
                    .join()
                    .unwrap_or_else(|p| std::panic::resume_unwind(p)),
            );
        }
        all
    });
    all.sort_by_key(|(k, _)| *k);
    all.into_iter().map(|(_, t)| t).collect()
}

#[cfg(test)]
mod tests {
    #[test]
    fn results_come_in_order() {
        assert_eq!(
            super::map(1000, |k| k * k),
            (0..1000).map(|k| k * k).collect::<Vec<_>>()
        );
        assert!(super::map(0, |k| k).is_empty());
    }
}
