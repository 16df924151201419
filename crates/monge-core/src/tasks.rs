//! Independent pieces of work, run in parallel with the `parallel` feature
//! (rayon), their results in order: the same whatever the number of threads.
//! The geometry's rows and beams go through it, and so do `monge-io`'s
//! chunked writers and its side-by-side files.

/// `f(0), f(1), …, f(n − 1)`, computed side by side where the `parallel`
/// feature is on (on this thread where there are no threads, as in
/// WebAssembly), returned in order. A panic in `f` is passed on.
///
/// ```
/// let squares = monge_core::tasks::map(1000, |k| k * k);
/// assert_eq!(squares, (0..1000).map(|k| k * k).collect::<Vec<_>>());
/// ```
pub fn map<T: Send>(n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        (0..n).into_par_iter().map(f).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        (0..n).map(f).collect()
    }
}

/// Elements per range of a plain pass over many ([`ranges`]): enough to
/// outweigh handing a task to the pool.
pub const BLOCK: usize = 1 << 16;

/// `f` of the consecutive ranges of `0..len`, `block` long but the last,
/// side by side with [`map`], in order: for one pass over many elements.
///
/// ```
/// let sums = monge_core::tasks::ranges(10, 4, |r| r.sum::<usize>());
/// assert_eq!(sums, [0 + 1 + 2 + 3, 4 + 5 + 6 + 7, 8 + 9]);
/// ```
pub fn ranges<T: Send>(
    len: usize,
    block: usize,
    f: impl Fn(std::ops::Range<usize>) -> T + Sync + Send,
) -> Vec<T> {
    let block = block.max(1);
    map(len.div_ceil(block), |b| {
        f(b * block..len.min((b + 1) * block))
    })
}

/// `(a(), b())`, with `b` run by the pool while `a` runs on this thread
/// (one after the other without the `parallel` feature): for work that has to
/// stay on this thread, such as writing to a file that is not `Send`, beside
/// work that can move. A panic in either is passed on, once both are done.
///
/// ```
/// let mut written = Vec::new();
/// let (len, squares) = monge_core::tasks::beside(
///     || {
///         written.extend_from_slice(b"first batch");
///         written.len()
///     },
///     || monge_core::tasks::map(4, |k| k * k),
/// );
/// assert_eq!((len, squares), (11, vec![0, 1, 4, 9]));
/// ```
pub fn beside<A, B: Send>(a: impl FnOnce() -> A, b: impl FnOnce() -> B + Send) -> (A, B) {
    #[cfg(feature = "parallel")]
    {
        let mut moved = None;
        let here = rayon::in_place_scope(|s| {
            s.spawn(|_| moved = Some(b()));
            a()
        });
        // The scope returns once the spawned `b` has run (or passes its panic on).
        (here, moved.expect("the scope ran b"))
    }
    #[cfg(not(feature = "parallel"))]
    {
        (a(), b())
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn results_come_in_order() {
        assert_eq!(
            super::map(1000, |k| k * k),
            (0..1000).map(|k| k * k).collect::<Vec<_>>()
        );
    }

    #[test]
    fn beside_runs_both_and_keeps_the_first_here() {
        let here = std::thread::current().id();
        let (a, b) = super::beside(
            || std::thread::current().id(),
            || super::map(100, |k| k + 1).into_iter().sum::<usize>(),
        );
        assert_eq!((a, b), (here, 5050));
    }

    #[test]
    #[should_panic(expected = "b failed")]
    fn a_panic_beside_is_passed_on() {
        super::beside(|| 1, || panic!("b failed"));
    }
}
